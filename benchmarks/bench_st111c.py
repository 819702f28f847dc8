"""After the block's own ``mon_lost``, the C's level shift (``SETTLED``) of a sensor no other
predicts: does the ST flag every row it differs from the C (st111c, issue 34 "deployed as scored")?

Left by st111b as "a jump of a held sensor" (lr9964 drop then jump, 1521 rows at 0.061 um
unflagged): traced here, its +2.88 K step of T_spindle_rear is under that sensor's jump limit
(12.63 K) and bend limit (12.57 K): no jump in the C nor the block.  The C's ``SETTLED`` test
(its two windows parted past ``settle_lim``, steady) re-references it 9 rows later (row 2169, by
2.56 K); the block stopped its own test at ``mon_lost``, so it read the step on.

RULE (st_watch.py, ``mon_rsettle``): after ``mon_lost`` the block keeps its settle ring on its own
readings and reference age, and where one with ``MON_SETTLES`` has its windows parted past
``MON_SETTLE_LIM`` (the C's test less its steadiness test: never on fewer rows) sets
``mon_unsure`` to the campaign's end.  c, flag, rule and sensor unchanged.

CASES: bench_st111b's, the same rule and counts, plus per case and block the rows from r2 with
``mon_unsure`` (``unsure``), the cost the bar caps (benchmarks/st111c_bar.md).

SCORED (2026-12-07, bar dd2a8770 unchanged, rule 68c8569b; BASE = 1a5fcb13's src, a worktree, run
beside in the same process; CPU user + sys by /usr/bin/time, 2 cores shared, load 10-13).
* C1 ``stream`` lr9964 (bench_st108b's root): drop then jump unflagged rows off the C 1521 (0.061
  um) -> 0; its ``unsure`` rows from r2 631 -> 2152 (the C differs from row 2169 to the end, all
  flagged); the other 7 cases: 0 unflagged and ``unsure`` identical on both.  93.4 s.
* C2 ``score`` seed 3: added 0 on all 8 cases, BASE and RULE; ``unsure`` identical per case (368
  rows from r2 summed, both).  14.4 s.
* C3 fresh 10233, 10234, 10235 (each drawn and scored once, after 68c8569b): added 0 and late
  unflagged 0 on all 24 cases, BASE and RULE; ``unsure`` identical per case.  40.7 s.
* C4 bench_st108b ``stream`` lr/dl 9964-9967 (BASE 76.2 s, RULE 80.5 s): every saved array (st, c,
  flag, rule, sensor, mon_unsure, stop) byte-identical (``same``: 0 / 0 on all 8; mon_unsure 1527
  rows on both).
* fresh 10211's 1 + 2 rows (st111b's, traced with aa013efc = 1a0fc91a + st111b): campaign 1, rows
  118 (jump then jump) and 118-119 (jump then drift): the first fault's residual (T_1's lone jump
  re-referenced by its whole step, 0.351 / 0.095 um: st111's class), which in the first fault alone
  ends at row 118; not the second fault's.  On 1a5fcb13 (st111's port merged) 0 late unflagged rows
  on all 12 jump-first runs of 10211, BASE and RULE.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st111c.py score BASESRC SEED [SEED ...]
    python benchmarks/bench_st111c.py stream ROOT BASESRC RECORD [RECORD ...]
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests" / "apps"),
                str(HERE.parent / "tests")]
from _cli import run_commands  # noqa: E402


def run(block: str, ss, df) -> dict:
    """bench_st111b's ``run`` and, per row, ``mon_unsure``."""
    from test_export import StructuredText
    from thermocomp.apps.deploy.export import Simulator

    st, sim = StructuredText(block), Simulator(ss)
    sim.reset()
    U, t = df[ss.inputs].to_numpy(float), df["time"].to_numpy(float)
    got = {k: [] for k in ("st", "c", "flagged", "lost", "unsure")}
    for i in range(len(df)):
        a, c = st(U[i], t[i], i == 0), sim.step(U[i], t[i])
        v = st.vars
        got["st"].append(np.array(a, float))
        got["c"].append(np.array(c, float))
        got["unsure"].append(bool(v["mon_unsure"]))
        got["flagged"].append(bool(v["mon_flag"]) or got["unsure"][-1] or bool(v["refused"]))
        got["lost"].append(bool(v["mon_lost"]))
    return {k: np.array(x) for k, x in got.items()}


def _cases(label: str, ss, campaigns: list, blocks: dict) -> None:
    """Per case and block: bench_st111b's counts and the ``mon_unsure`` rows from r2."""
    from bench_st111b import FIRST, SECOND, faulted, loose

    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    a, b = [c for c in names if c != "T_amb"][:2]
    for who, block in blocks.items():
        for first in FIRST:
            alone = [run(block, ss, faulted(df, a, b, first, "none")) for df in campaigns]
            for second in SECOND:
                late = added = lost = unsure = 0
                worst = 0.0
                for df, r0 in zip(campaigns, alone):
                    r = r0 if second == "none" else run(block, ss, faulted(df, a, b, first, second))
                    r2 = len(df) // 2
                    bad = loose(r)
                    bad[:r2] = False
                    late += int(bad.sum())
                    added += int((bad & ~loose(r0)).sum())
                    lost += int(r["lost"][r2 - 1])
                    unsure += int(r["unsure"][r2:].sum())
                    if bad.any():
                        worst = max(worst, float(np.max(np.abs(r["c"] - r["st"])[bad])))
                print(f"{label} {who} {a} {first} then {b} {second}: late unflagged {late}, added {added} "
                      f"(max {worst:.3g} um); unsure {unsure}; mon_lost at r2-1 in {lost} of "
                      f"{len(campaigns)}", flush=True)


def score(basesrc: str, *seeds: str) -> None:
    """The room record's cases per seed, BASE's block and the tree's."""
    from bench_st108d import _block
    from bench_st111b import _deployed

    from thermocomp.apps.deploy.export import state_space

    for seed in map(int, seeds):
        with tempfile.TemporaryDirectory() as tmp:
            deployed, campaigns = _deployed(seed, tmp)
            blocks = {"BASE": _block(deployed, basesrc), "RULE": _block(deployed, None)}
            _cases(f"seed {seed}", state_space(deployed, monitor=True), campaigns, blocks)


def stream(root: str, basesrc: str, *records: str) -> None:
    """The same cases on bench_st108b's healthy streams (ROOT as its ``make`` makes them)."""
    import bench_st103b
    import bench_st108b
    from bench_st108d import _block

    for record in records:
        _, ss, frame, _, _, tree, base = bench_st103b._cell(root, record, bench_st108b.MADE_BY,
                                                            lambda d: _block(d, basesrc))
        _cases(record, ss, [frame], {"BASE": base, "RULE": tree})


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": score, "stream": stream}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
