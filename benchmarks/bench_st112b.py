"""The C's hold after a lone jump rebuilt in the block, not flagged (st112b, issue 34 "deployed as
scored").

Left by st111 / st112: after a lone JUMP of a sensor the others predict (``MON_STEP_HELD``) the C
holds it out and feeds the model its rebuild from the others (watch_c.py ``mon_rebuilt``:
``pred[k]``, the set-without-it operator row) from the jump's row to its BACK (or a spike's
return); the block read the measured value there, flagged (``mon_unsure``), 0.01-6.7 um off.

RULE (st_watch.py ``mon_rb*``, st.py): where st112's ``mon_sj`` stands (a lone jump from a whole set
ended the judgement, nothing flagged, named or in the warning band since), from the jump's row to
the C's BACK as the block tells it (calm for its wait, a window of its error with every sensor in
within ``MON_BACK_BAND``, its reading moving: ``_pass_once_back``), no ``mon_rjump`` /
``mon_rsettle``: the model reads ``mon_base + MON_SPIKE_FIELD[k] . (u - mon_base - mon_shift)``
(the C's sum, in its order), its fallback set as the C serves; ``mon_unsure`` FALSE there.  Where
the hold is lost track of (anything named or at the band, a near tie, a run to its freeze run)
``mon_rbunsure``: ``mon_unsure`` to the campaign's end.

SCORED (2026-12-08; bar 8ad0c441 unchanged; BASE /tmp/base-st112b = fae9cdac; CPU user + sys).
* d9fad4e1 (the hold to a window after the jump): seen 10/10/11/10 -> 0/0/0/0 rows off the C;
  fresh 10275-10277 drawn and scored once here: 0 unflagged on 10276 / 10277, but 10275's T_1
  jump-first cases 57 / 9 / 32 / 69 unflagged, as BASE (the C holds T_1 past st108b's wait).
* 1f9594db (the BACK told, traced on 10275 campaign 0: 10275 no longer fresh): seen 0/0/0/0;
  seed 3 jump-first off the C 41/83/97/41 -> 0/42/56/0, drop-first equal; 10275 unflagged
  57/9/32/69 -> 0/0/0/0, off 121/288/163/121 -> 12/226/101/0; 10277 40/80/96/40 -> 0/40/56/0;
  10276 equal; unflagged 0 everywhere.  bench_st108b healthy 8: c moved on the 12 spike-hold rows
  only, now equal to the C; flag/rule/sensor identical; mon_unsure rows 291 -> 279.

Bar: benchmarks/st112b_bar.md (committed first).  A row is *off the C* where max |ST - C| > 1e-9 um
(C = the JSON mirror ``Simulator``), *unflagged* where off and none of ``mon_flag``, ``mon_unsure``,
``refused``.  ``score``: bench_st111b's cases (its ``_deployed(seed)`` room record, A's fault then
B's), per case and block, whole test campaigns: rows off the C, of them unflagged, ``mon_unsure``.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st112b.py score BASESRC SEED [SEED ...]
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
from _cli import run_commands  # noqa: E402

TOL = 1e-9      # um


def score(basesrc: str, *seeds: str) -> None:
    """Per seed, case and block (BASESRC's, the tree's): rows off the C, unflagged, unsure."""
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
        for first in FIRST:
            for second in SECOND:
                said = []
                for who, block in blocks.items():
                    off = bad = unsure = 0
                    for df in campaigns:
                        r = run(block, ss, faulted(df, a, b, first, second))
                        off += int((np.max(np.abs(r["c"] - r["st"]), axis=1) > TOL).sum())
                        bad += int(loose(r).sum())
                        unsure += int(r["unsure"].sum())
                    said.append(f"{who} off the C {off}, unflagged {bad}, unsure {unsure}")
                print(f"seed {seed} {a} {first} then {b} {second}: {'; '.join(said)}", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"score": score}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
