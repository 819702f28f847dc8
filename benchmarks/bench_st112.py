"""Which ``mon_unsure`` causes fire on healthy streams, on rows where the ST equals the C (st112,
issue 34 "deployed as scored")?

st111b's ``mon_rjump`` took bench_st108b's healthy lr/dl 9964-9967 from 291 to 1527 ``mon_unsure``
rows of 46,084, none on a row off the C.  ``causes`` counts, per stream, the ``mon_unsure`` rows,
those off the C (max |ST - C| > 1e-9 um, C = the JSON mirror ``Simulator``) and, per cause
(st108b's band after the stop or ``mon_lost``, a held STEP_OUT, ``mon_rjump``, ``mon_rsettle``,
``mon_junsure``, ``mon_rfirst``, ``mon_rlater``), the rows it is TRUE on and of them those equal to
the C.  The block is the tree's (``PYTHONPATH``); bench_st108b's records (its ``make`` ROOT).

RULE (st_watch.py, st112): no ``mon_rjump`` at the return of a sensor whose lone jump, the set
whole before it, ended the judgement (``mon_lost``) within a window, nothing else since, where the
C's spike test passes (its prediction by the others with every other in, the set-without-it
operator's row ``MON_SPIKE_FIELD``, within ``MON_READMIT x MON_WARN``): the C puts its reference
back as the block does, its set whole again.  The 4 healthy streams' rjumps were each such a
3-row spike (lr9964 T_bed_right at 4163-4166, dl9964 6940, lr9966 3982, dl9966 6637).

SCORED (2026-12-08, bar f77be8f2 unchanged, rule b6307c0b; BASE = 277c06b1's src, a worktree run
beside; CPU user + sys, 2 cores shared, load 18-21).
* BASE ``causes``: 1527 rows, 1308 of them ``mon_rjump`` (lr9964 155, dl9964 257, lr9966 336,
  dl9966 560), none off the C; the rest st108b's band and held STEP_OUTs, as before st111b.
* S1 bench_st108b ``stream`` lr/dl 9964-9967: ``mon_unsure`` 1527 -> 291 of 46,084 rows (lr9964
  170 -> 33, dl9964 272 -> 33, lr9966 360 -> 42, dl9966 583 -> 41, the other 4 equal); ``same`` 0 / 0
  on all 8 (c, flag, rule, sensor), stop equal; 0 rows off the C unflagged on both.  BASE 83.2 s,
  RULE 75.6 s.
* S2 0 unflagged rows off the C, BASE and RULE alike: bench_st111 ``seen`` (4 campaigns, unsure 21
  each on both); bench_st111c ``score`` seed 3 (8 cases, unsure equal per case) and ``stream``
  lr9964 (8 cases; unsure from r2 equal but jump-then-none / jump-then-jump 170 -> 33);
  bench_st109b ``fresh`` 10207 (unsure equal per campaign).  ``score`` 3 here: 0 over whole
  campaigns, unsure 1072 on both.
* S3 ``score`` fresh 10263, 10264, 10265 (drawn and scored once, after b6307c0b): 0 unflagged rows
  off the C on all 48 case runs, unsure equal per case (1275 / 852 / 1052 on both).  41.2 s.
* The C's spike decision scanned on lr9132 (T_head_left, T_col_back, T_bed_right out 3 rows by 6
  largest steps, back -0.3 .. +0.3 K by 0.01): the block's matched the C's on all 183 returns.

``score``: bench_st111c's cases (bench_st111b's faults on ``_room(7, seed)``, BASE's block and the
tree's), counting also the unflagged rows off the C over the whole campaign (``all``, not only
from r2) and the ``mon_unsure`` rows over it.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st112.py causes ROOT RECORD [RECORD ...]
    python benchmarks/bench_st112.py score BASESRC SEED [SEED ...]
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
from _cli import run_commands  # noqa: E402

TOL = 1e-9      # um
LATCHED = ("mon_rjump", "mon_rsettle", "mon_junsure", "mon_rfirst", "mon_rlater")


def _row(v, window: int) -> dict:
    """The causes TRUE on the row just stepped (read off the block's memory)."""
    band = (v["mon_stop_row"] > 0 or v["mon_lost"]) and v["mon_usince"] - 1 <= 2 * window
    held = v["mon_held"] >= 0 and v["mon_held_set"] < 0 and not v["mon_lost"]
    return {"band": bool(band), "held STEP_OUT": bool(held), **{k: bool(v.get(k, False)) for k in LATCHED}}


def causes(root: str, *records: str) -> None:
    """The module doc's counts, per record."""
    import bench_st108b

    from test_export import StructuredText
    from thermocomp.apps.deploy.export import Simulator

    for record in records:
        _, ss, frame, _, _, tree, _ = bench_st108b._cell(root, record)
        st, sim = StructuredText(tree), Simulator(ss)
        sim.reset()
        U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
        window = int(ss.monitor["window"])
        off, unsure, why = [], [], []
        for i in range(len(frame)):
            a, c = st(U[i], t[i], i == 0), sim.step(U[i], t[i])
            off.append(np.max(np.abs(np.asarray(a, float) - np.asarray(c, float))) > TOL)
            unsure.append(bool(st.vars["mon_unsure"]))
            why.append(_row(st.vars, window))
        off, unsure = np.array(off), np.array(unsure)
        print(f"  {record}: {len(off)} rows; mon_unsure {int(unsure.sum())} (equal to the C "
              f"{int((unsure & ~off).sum())}); off the C {int(off.sum())}, unflagged by mon_unsure "
              f"{int((off & ~unsure).sum())}", flush=True)
        for name in why[0]:
            on = np.array([w[name] for w in why])
            if on.any():
                print(f"    {name}: {int(on.sum())} rows from row {int(np.argmax(on))}, equal to the C "
                      f"{int((on & unsure & ~off).sum())}", flush=True)


def score(basesrc: str, *seeds: str) -> None:
    """``score`` (module doc), per seed, case and block."""
    import tempfile

    from bench_st108d import _block
    from bench_st111b import FIRST, SECOND, _deployed, faulted, loose
    from bench_st111c import run

    from thermocomp.apps.deploy.export import state_space

    for seed in map(int, seeds):
        with tempfile.TemporaryDirectory() as tmp:
            deployed, campaigns = _deployed(seed, tmp)
            ss = state_space(deployed, monitor=True)
            blocks = {"BASE": _block(deployed, basesrc), "RULE": _block(deployed, None)}
        names = [ss.inputs[i] for i in ss.monitor["inputs"]]
        a, b = [c for c in names if c != "T_amb"][:2]
        for who, block in blocks.items():
            for first in FIRST:
                for second in SECOND:
                    late = every = unsure = 0
                    for df in campaigns:
                        r = run(block, ss, faulted(df, a, b, first, second))
                        bad = loose(r)
                        every += int(bad.sum())
                        late += int(bad[len(df) // 2:].sum())
                        unsure += int(r["unsure"].sum())
                    print(f"seed {seed} {who} {a} {first} then {b} {second}: unflagged off the C {every} "
                          f"(from r2 {late}); unsure {unsure}", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"causes": causes, "score": score}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
