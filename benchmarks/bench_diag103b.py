"""diag103's forward bound (``search.START_FORWARD_WITHIN_PCT`` = 28: a start lag the campaigns'
means cannot resolve must also gain 28 % forward within the later train campaigns) scored on FRESH
draws that reach it, against its parent 4a21da2b's src, and what the forward read costs (stop 103,
diag103b; issue 34: "diagnose ... never leaves a record's test error more than 2 % worse").
diag103's own fresh draws 9968-9972 never reached the bound (its one start lag read 44.1).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag103b.py draws ROOT LABEL SET      # SET's draws -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag103b.py fresh ROOT LABEL          # fresh draws until 6 decisions reached
    python benchmarks/bench_diag103b.py fresh ROOT LABEL LIKE     # the fresh cases LIKE's run drew
    python benchmarks/bench_diag103b.py cpu ROOT LABEL            # diagnose CPU / wall on CPU_CASES
    python benchmarks/bench_diag103b.py bar ROOT MAIN PARENT      # V1-V3 below on two labels' rows

:data:`SETS`: ``harms`` bench_diag103's two seen harms (planted 9342, lag 9443), ``start``
bench_diag103's 20 seen draws whose diagnosis took a start lag; ``fresh`` the seeds 9986-9995 in
the order :data:`FRESH` (kinds chosen before drawing: lag, lag, planted, repeated; bench_diag86's
``draw``, 12 campaigns, every 3rd test, 8 train; MLR on every target, ``max_effects=2``).
``draws`` are bench_diag91's rows (``diagnose_cases``) with, per target, the DECISIONS: the rounds
in which at least one start lag reached the clause (``forward_gain_pct_within`` in its evidence,
asked only by main's src), each with the reads of those start lags (forward within gain, CV gain,
cleared or not, accepted or not).  ``fresh ROOT LABEL`` draws :data:`FRESH` in order and stops
after the draw that brings the decisions to :data:`ENOUGH` (6); ``fresh ROOT LABEL LIKE`` draws
the cases ``ROOT/fresh-LIKE.jsonl`` holds (the parent's src cannot tell a decision).  ``cpu``:
:data:`CPU_CASES` each diagnosed :data:`REPEATS` times in one process (CPU user + sys and wall per
run; with main's src also the CPU inside ``CrossValidator.forward_within``).

The trace on seen draws (2026-12-07, main 6b25ee8e's src; before the bar)
--------------------------------------------------------------------------
``draws ROOT main start`` (21.7 s CPU, 0.6-0.8 s a draw): 20 decisions on 20 rows of the 20 draws
(each round 1 on 8 train campaigns): every lag draw's E_X (16), 9443 E_Y, 9195 E_Z, planted 9342
E_X and 8885 E_Z; the other 3 planted draws none.  The start lags weighed read 2.9-77.3 forward
within, the accepted ones 33.3-76.2 (9443 E_Y's harm 33.3).  The clause refused 8 start lags: 9342
E_X's 4 (24.1-25.9: its +13.9 % gone, diag103's aim), 8885 E_Z's T_nose 1440 s (2.9; not taken on
4a21da2b either: diag103's seen rows moved on 9342 E_X only), 9193 E_X's two T_nose (20.2 / 21.9)
and 9444 E_X's T_nose (25.4), each behind an accepted rival.  So a lag draw reaches the clause
about once, a planted one now and then: 6 decisions take ~6 fresh draws of these kinds.

The bar (committed BEFORE the fresh seeds 9986-9995 are simulated; scored once, never tuned)
----------------------------------------------------------------------------------------------
MAIN = 6b25ee8e's src (the rule), PARENT = 4a21da2b's src (``git archive 4a21da2b src conf``).
A row is (draw, target), its change diagnose's own, 100 (after / before - 1) % of the test RMSE as
run; a decision is (draw, target, round) with at least one start lag reaching the clause; a
REACHED row has at least one decision.  Fresh draws stop at 6 decisions (at most 10 draws).
V1 fresh rows > 2 % worse (all rows of the drawn records): MAIN's count <= PARENT's.
V2 mean change over the REACHED rows: MAIN's <= PARENT's + 1 point.
V3 diagnose CPU on :data:`CPU_CASES` (the sum over the 3 records of each one's median CPU over 3
runs; one process per label, PARENT then MAIN, back to back): MAIN <= 1.15 x PARENT.
KEPT (no src change) if V1-V3 hold; REFUSED if V1 or V2 fails (``benchmarks/diag103b_revert.patch``
takes the rule and its tests out, NOT applied: the lead decides); V3 alone failing: the cost is
reported.  VOID if fewer than 6 decisions are reached in 10 draws.

Measured (2026-12-07; MAIN = 6b25ee8e's src, PARENT = 4a21da2b's; nice, 2 cores shared, load 4-7)
--------------------------------------------------------------------------------------------
The bar at 4ada1479 (00:40 UTC); then ``fresh ROOT main`` (9.5 s CPU; 00:41): 7 decisions after 8
draws (9986-9993; 9994-9995 not drawn), ``fresh ROOT parent main`` (10.8 s), ``cpu`` parent then
main (8.9 / 8.5 s), scored once; bar and src unchanged.  ``bar /tmp/diag103b/rows main parent``::

  fresh planted:9988 E_Y: -17.2 -> -41.0 %
  wall 3.35 -> 3.56 s; main's CPU inside forward_within 0.056 s
  start lags the clause refused: 7 [13.6, 16.2, 17.4, 18.3, 19.4, 19.7, 25.3]
  decisions 7 (enough 6) on 7 rows [('lag:9986', 'E_X'), ('lag:9987', 'E_X'), ('lag:9990', 'E_X'),
    ('lag:9992', 'E_X'), ('lag:9993', 'E_X'), ('lag:9993', 'E_Y'), ('planted:9988', 'E_Y')];
    every row's mean change -11.81 -> -12.80 %
  V1 fresh rows > 2 % worse (24 rows) 0 [] -> 0 []: met
  V2 reached rows' mean change (7 rows) -32.78 -> -36.17 %: met
  V3 diagnose CPU on 3 records 1.96 -> 1.91 s (0.974 x): met
  verdict: KEPT

The decisions (``decisions-fresh-main.jsonl``; explains only): the 5 lag draws' E_X start lags
(T_box1 / T_box2 / T_nose 1440 s, T_bearing_f1) read 40.2-80.3 forward within, all above 28, and were taken as
on the parent.  Two decisions refused every start lag weighed: planted 9988 E_Y round 2, after the
position effect, T_box2 / T_box1 / T_amb 1800 s at 17.4-25.3 (the parent took T_box2 1800 s there:
test 3.169 -> 2.623 µm, the position effect alone 1.870: the rule's one moved row, 24 points
better), and lag 9993 E_Y round 1, T_box2 3600 s / T_motor1 at 13.6 / 16.2 (the parent took
nothing there either).  No fresh decision read between 28 and 40: the bound's own value was not
tested closely, only that real E_X start lags clear it and a round-2 start lag after the position
effect (diag100: 0.27-0.60 within / pooled on seen 8885 / 9103, helpful there) does not.
CPU: the forward read costs 0.011 / 0.030 / 0.015 s per diagnosis on 9342 / 9443 / 9972 (a base
read and one per start lag weighed): ~3 % of diagnose's 0.58-0.76 s; main's total
0.974 x the parent's, within the runs' noise (the parent's 9342 runs 0.64-0.81 s).
"""

from __future__ import annotations

import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import made_folder, run_commands  # noqa: E402
from bench_diag103 import SETS as SETS_103  # noqa: E402

FRESH = [(k, s) for s, k in zip(range(9986, 9996), ["lag", "lag", "planted"] * 3 + ["lag"])]
ENOUGH = 6                     # decisions that stop the fresh draws
CPU_CASES = [("planted", 9342), ("lag", 9443), ("lag", 9972)]   # seen / spent, start lags weighed
REPEATS = 3
SETS = {"harms": SETS_103["harms"], "start": SETS_103["start"], "fresh": FRESH}


def decisions(d) -> dict:
    """Per target, the rounds in which a start lag reached the forward clause, with those reads."""
    out = {}
    for t, x in d.targets.items():
        for r in x.search.rounds:
            reached = [ev for ev in r.evaluated if getattr(ev, "gain_pct_forward_within", None) is not None]
            if reached:
                out.setdefault(t, []).append({"round": r.step, "lags": [
                    {"effect": ev.effect.title, "forward_within": ev.gain_pct_forward_within,
                     "gain": ev.gain_pct, "clears": bool(ev.clears_bar), "accepted": bool(ev.accepted)}
                    for ev in reached]})
    return out


def _diagnosed(root: str, label: str, name: str, cases) -> None:
    """``cases`` diagnosed (bench_diag91's rows) with their decisions -> ``ROOT/NAME-LABEL.jsonl``
    and ``ROOT/decisions-NAME-LABEL.jsonl``; ``cases`` may stop early (read lazily)."""
    from bench_diag91 import diagnose_cases
    from bench_diag92c import _dataset as draw_12

    with open(made_folder(root) / f"decisions-{name}-{label}.jsonl", "w") as out:
        def keep(case, ds, d):
            dec = decisions(d)
            print(json.dumps({"case": case, "decisions": dec}, default=float), file=out, flush=True)
            for t, rounds in dec.items():
                for r in rounds:
                    print(f"    decision {t} round {r['round']}: " + "; ".join(
                        f"{lag['effect'][:40]} fwd {lag['forward_within']:.1f} gain {lag['gain']:.1f}"
                        f"{' clears' if lag['clears'] else ''}{' *' if lag['accepted'] else ''}"
                        for lag in r["lags"]), flush=True)
            _diagnosed.count += sum(len(v) for v in dec.values())

        _diagnosed.count = 0
        diagnose_cases(root, label, name, cases, draw_12, keep=keep)


def draws(root: str, label: str, name: str) -> None:
    """:data:`SETS` ``name`` diagnosed -> ``ROOT/NAME-LABEL.jsonl`` and its decisions."""
    _diagnosed(root, label, name, SETS[name])


def fresh(root: str, label: str, like: str = "") -> None:
    """:data:`FRESH` in order until :data:`ENOUGH` decisions (or ``like``'s cases) diagnosed."""
    if like:
        rows = open(Path(root) / f"fresh-{like}.jsonl")
        cases = [json.loads(line)["case"].split(":") for line in rows]
        _diagnosed(root, label, "fresh", [(k, int(s)) for k, s in cases])
        return

    def until_enough():
        for case in FRESH:
            if _diagnosed.count >= ENOUGH:
                return
            yield case

    _diagnosed(root, label, "fresh", until_enough())
    print(f"  decisions reached: {_diagnosed.count} (enough: {ENOUGH})")


def cpu(root: str, label: str) -> None:
    """:data:`CPU_CASES` diagnosed :data:`REPEATS` times each: CPU, wall, CPU in forward_within."""
    from bench_diag98 import _dataset
    from cpu import cpu_seconds

    from thermocomp.apps.diagnose import diagnose
    from thermocomp.apps.diagnose.cv import CrossValidator
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    spent = [0.0]
    original = getattr(CrossValidator, "forward_within", None)
    if original is not None:
        def timed(self, *args, **kwargs):
            t0 = cpu_seconds()
            try:
                return original(self, *args, **kwargs)
            finally:
                spent[0] += cpu_seconds() - t0
        CrossValidator.forward_within = timed
    with open(made_folder(root) / f"cpu-{label}.jsonl", "w") as out:
        for kind, seed in CPU_CASES:
            ds, options = _dataset(kind, seed)
            for run in range(REPEATS):
                spent[0] = 0.0
                t0, w0 = cpu_seconds(), time.perf_counter()
                diagnose(ds, Compensator(MLR()), options=options)
                row = {"case": f"{kind}:{seed}", "run": run, "cpu_s": cpu_seconds() - t0,
                       "wall_s": time.perf_counter() - w0,
                       "forward_cpu_s": spent[0] if original is not None else None}
                print(json.dumps(row), file=out, flush=True)
                print(f"  {row['case']} {label} run {run}: CPU {row['cpu_s']:.2f} s, wall "
                      f"{row['wall_s']:.2f} s, forward_within {row['forward_cpu_s']}", flush=True)


def _cpu_sum(root: str, label: str, key: str = "cpu_s") -> float | None:
    """The sum over the records of each one's median ``key`` (None where the src has no such read)."""
    rows = [json.loads(line) for line in open(Path(root) / f"cpu-{label}.jsonl")]
    if any(r[key] is None for r in rows):
        return None
    return sum(statistics.median(r[key] for r in rows if r["case"] == c)
               for c in dict.fromkeys(r["case"] for r in rows))


def bar(root: str, main: str, parent: str) -> None:
    """V1-V3 (module doc) on ``ROOT/{fresh,decisions-fresh,cpu}-{MAIN,PARENT}.jsonl``."""
    from bench_diag98 import _changes, print_moved

    ch = {n: _changes(root, "fresh", n) for n in (main, parent)}
    assert ch[main].keys() == ch[parent].keys(), "the fresh rows differ"
    dec = [json.loads(line) for line in open(Path(root) / f"decisions-fresh-{main}.jsonl")]
    reached = sorted((r["case"], t) for r in dec for t in r["decisions"])
    n_dec = sum(len(v) for r in dec for v in r["decisions"].values())
    print_moved("fresh", ch[parent], ch[main])
    worse = {n: sorted(k for k, v in ch[n].items() if v > 2.0) for n in ch}
    mean = {n: float(np.mean([ch[n][k] for k in reached])) if reached else float("nan") for n in ch}
    every = {n: float(np.mean(list(ch[n].values()))) for n in ch}
    c = {n: _cpu_sum(root, n) for n in (main, parent)}
    items = [(f"V1 fresh rows > 2 % worse ({len(ch[main])} rows) {len(worse[parent])} {worse[parent]} -> "
              f"{len(worse[main])} {worse[main]}", len(worse[main]) <= len(worse[parent])),
             (f"V2 reached rows' mean change ({len(reached)} rows) {mean[parent]:+.2f} -> "
              f"{mean[main]:+.2f} %",
              mean[main] <= mean[parent] + 1.0),
             (f"V3 diagnose CPU on {len(CPU_CASES)} records {c[parent]:.2f} -> {c[main]:.2f} s "
              f"({c[main] / c[parent]:.3f} x)", c[main] <= 1.15 * c[parent])]
    print(f"  wall {_cpu_sum(root, parent, 'wall_s'):.2f} -> {_cpu_sum(root, main, 'wall_s'):.2f} s; main's "
          f"CPU inside forward_within {_cpu_sum(root, main, 'forward_cpu_s'):.3f} s")
    refused = [lag["forward_within"] for r in dec for v in r["decisions"].values() for d in v
               for lag in d["lags"] if lag["forward_within"] < 28.0]
    print(f"  start lags the clause refused: {len(refused)} {sorted(round(x, 1) for x in refused)}")
    print(f"  decisions {n_dec} (enough {ENOUGH}) on {len(reached)} rows {reached}; every row's mean change "
          f"{every[parent]:+.2f} -> {every[main]:+.2f} %")
    for text, ok in items:
        print(f"  {text}: {'met' if ok else 'FAILS'}")
    verdict = ("VOID" if n_dec < ENOUGH else "KEPT" if all(ok for _, ok in items)
               else "REFUSED" if not (items[0][1] and items[1][1]) else "KEPT (V3 fails: cost reported)")
    print(f"  verdict: {verdict}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"draws": draws, "fresh": fresh, "cpu": cpu, "bar": bar}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
