"""diag103's forward-within bound (``search.START_FORWARD_WITHIN_PCT`` = 28) scored where it bites --
fresh start lags reading 28-40 forward within -- and train-only reads that might tell lag 9443 E_Y's
harm (+13.3 %, its T_bearing_f3 3600 s start lag reads 33.3) from the real start lags of its kind
(stop 105, diag105; issue 34: "diagnose ... never leaves a record's test error more than 2 % worse").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag105.py band ROOT BOUND SET     # SET diagnosed with the bound at BOUND
    python benchmarks/bench_diag105.py fresh ROOT BOUND        # FRESH in order until the stop rule
    python benchmarks/bench_diag105.py fresh ROOT BOUND LIKE   # the fresh cases bound LIKE's run drew
    python benchmarks/bench_diag105.py score ROOT SET           # the band table: bound 28 vs 40 vs 0

``band`` / ``fresh`` write ``ROOT/SET-bBOUND.jsonl`` (bench_diag91's rows) and
``ROOT/decisions-SET-bBOUND.jsonl`` (bench_diag103b's decisions: per target the rounds in which a
start lag reached the forward clause, each with its forward-within read, CV gain, cleared,
accepted), the src's ``START_FORWARD_WITHIN_PCT`` set to BOUND for the run (main's src otherwise;
BOUND 0 = no forward clause, 40 = the band refused).

Part (1): the bound in its band (procedure fixed BEFORE any fresh seed is drawn)
------------------------------------------------------------------------------
Draws: bench_diag103b's kinds and scenario (bench_diag86's ``draw``, 12 campaigns, every 3rd test,
8 train; MLR on every target, ``max_effects=2``), kinds in the order lag, lag, planted repeated:
:data:`FRESH` = 10025-10029, then (only if needed) 9476-9480.  A BAND READ is a start lag that
reached the clause (bound 28's run) reading 28 <= forward within < 40.  Stop rule: draw all of
10025-10029; if they hold fewer than :data:`ENOUGH` (3) band reads, go on through 9476-9480 one
draw at a time until 3 (at most those 5); 9481-9485 are never drawn here: they are kept for
scoring any rule part (2) builds.  Each drawn case is diagnosed three times: bound 28 (main),
40 (the band refused) and 0 (no forward clause).  Score per row (draw, target) whose bound-28
decisions hold a band read: the row's test change (100 (after / before - 1) %) at 28 vs at 40; a
band read ACCEPTED at 28 is HELPFUL if the row at 28 is better than at 40 by more than 0.5 points,
HARMFUL if worse by more than 0.5 (a row > 2 % worse at 28 counts as the bound's harm), NEUTRAL
otherwise.  The same for reads < 28 refused (28 vs 0): the bound's other side.  This is a trace
(TRACED table): the bound is not moved on these numbers.
"""

from __future__ import annotations

import json
import sys
from contextlib import contextmanager
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402
from bench_diag103 import SETS as SETS_103  # noqa: E402

_KINDS = ["lag", "lag", "planted"] * 4
FRESH = list(zip(_KINDS, range(10025, 10030))) + list(zip(_KINDS[5:], range(9476, 9481)))
FIRST = 5                      # 10025-10029: always drawn
ENOUGH = 3                     # band reads that stop the draws after FIRST
BAND = (28.0, 40.0)
SETS = {"harms": SETS_103["harms"], "start": SETS_103["start"], "spent": SETS_103["spent"], "fresh": FRESH}


@contextmanager
def _bound(value: float):
    from thermocomp.apps.diagnose import search as search_module

    was = search_module.START_FORWARD_WITHIN_PCT
    search_module.START_FORWARD_WITHIN_PCT = float(value)
    try:
        yield
    finally:
        search_module.START_FORWARD_WITHIN_PCT = was


def _band_reads(dec: dict) -> int:
    return sum(BAND[0] <= lag["forward_within"] < BAND[1] for rounds in dec.values() for r in rounds
               for lag in r["lags"])


def band(root: str, bound: str, name: str, cases=None) -> None:
    """:data:`SETS` ``name`` (or ``cases``) diagnosed with the bound at ``bound``."""
    from bench_diag103b import _diagnosed

    with _bound(float(bound)):
        _diagnosed(root, f"b{bound}", name, SETS[name] if cases is None else cases)


def fresh(root: str, bound: str, like: str = "") -> None:
    """:data:`FRESH` by the stop rule (module doc), or the cases bound ``like``'s run drew."""
    from bench_diag103b import decisions

    if like:
        rows = open(Path(root) / f"fresh-b{like}.jsonl")
        cases = [json.loads(line)["case"].split(":") for line in rows]
        band(root, bound, "fresh", [(k, int(s)) for k, s in cases])
        return
    found = [0]

    def until_enough():
        for i, case in enumerate(FRESH):
            if i >= FIRST and found[0] >= ENOUGH:
                return
            yield case

    import bench_diag91

    keep_cases = bench_diag91.diagnose_cases

    def counting(root_, label, name, cases, dataset, reference="first_sample", keep=None):
        def keep2(case, ds, d):
            found[0] += _band_reads(decisions(d))
            if keep is not None:
                keep(case, ds, d)
        return keep_cases(root_, label, name, cases, dataset, reference, keep2)

    bench_diag91.diagnose_cases = counting
    try:
        band(root, bound, "fresh", until_enough())
    finally:
        bench_diag91.diagnose_cases = keep_cases
    print(f"  band reads ({BAND[0]:.0f}-{BAND[1]:.0f}): {found[0]} (enough {ENOUGH})")


def _verdict(delta: float) -> str:
    return "HELPFUL" if delta < -0.5 else "HARMFUL" if delta > 0.5 else "neutral"


def score(root: str, name: str) -> None:
    """The band table (module doc) of ``ROOT/{NAME,decisions-NAME}-b{28,40,0}.jsonl``."""
    from bench_diag98 import _changes

    ch = {b: _changes(root, name, f"b{b}") for b in ("28", "40", "0")}
    dec = [json.loads(line) for line in open(Path(root) / f"decisions-{name}-b28.jsonl")]
    tally: dict = {}
    for row in dec:
        for t, rounds in row["decisions"].items():
            key = (row["case"], t)
            c28, c40, c0 = (ch[b][key] for b in ("28", "40", "0"))
            for r in rounds:
                for lag in r["lags"]:
                    fw = lag["forward_within"]
                    side = "band" if BAND[0] <= fw < BAND[1] else "below" if fw < BAND[0] else "above"
                    other = c40 if side == "band" else c0 if side == "below" else c28
                    v = _verdict(c28 - other) if lag["accepted"] or side == "below" else "-"
                    tally.setdefault((side, v), []).append(key)
                    print(f"  {key[0]:14s} {t} r{r['round']} {lag['effect'][:40]:40s} fwd {fw:6.1f} gain "
                          f"{lag['gain']:5.1f}{' clears' if lag['clears'] else ''}"
                          f"{' *' if lag['accepted'] else ''}"
                          f" | test % b28 {c28:+6.1f} b40 {c40:+6.1f} b0 {c0:+6.1f} | {side} {v}")
    every = {b: sorted(k for k, v in ch[b].items() if v > 2.0) for b in ch}
    print(f"  rows {len(ch['28'])}; rows > 2 % worse: " + "; ".join(f"b{b} {every[b]}" for b in ch))
    for (side, v), keys in sorted(tally.items()):
        print(f"  {side:5s} {v:8s} {len(keys)} {sorted(set(keys))}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"band": band, "fresh": fresh, "score": score}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
