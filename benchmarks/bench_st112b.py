"""The C's hold after a lone jump rebuilt in the block, not flagged (st112b, issue 34 "deployed as
scored").

Left by st111 / st112: after a lone JUMP of a sensor the others predict (``MON_STEP_HELD``) the C
holds it out and feeds the model its rebuild from the others (watch_c.py ``mon_rebuilt``:
``pred[k]``, the set-without-it operator row) from the jump's row to its BACK (or a spike's
return); the block read the measured value there, flagged (``mon_unsure``), 0.01-6.7 um off.

RULE (st_watch.py ``mon_rb`` / ``mon_rbx``, st.py): where st112's ``mon_sj`` stands (a lone jump
from a whole set ended the judgement, nothing flagged, named or in the warning band since), on the
jump's row and each row after while the C's BACK cannot come yet (its calm, 0 at the jump, under a
window: ``mon_sj_age <= MON_WINDOW``), no ``mon_rjump`` / ``mon_rsettle``: the model reads
``mon_base + MON_SPIKE_FIELD[k] . (u - mon_base - mon_shift)`` (the C's sum, in its order) and its
fallback set as the C serves it; ``mon_unsure`` FALSE there.  Anything else: flagged as before.

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
