"""The ST names every row of a campaign whose first sample had a monitored reading out of range
(st108d, issue 34 "deployed as scored").

dep108 / dep108f (bench_dep108, bench_dep108f) made the C start such a sensor from the monitor's
``first_c`` and reference it late on its return; the ST block (st_watch.py) does neither: on
bench_dep108f's seen ``back`` case (T_amb +30 on rows 0-39) it flags RANGE and refuses rows 0-39,
then says nothing on rows 40-119 while 4.3-8.0 um off the C.

RULE (st_watch.py, no key, no constant): the block's own range test at a campaign's first sample
(any monitored reading measured and beyond ``MON_LO_LIM`` / ``MON_HI_LIM``, whatever rule the row
names first) sets ``mon_rfirst``, kept to the campaign's end; ``mon_unsure`` is TRUE on every row
while it is set.  The numbers (c) and (mon_flag, mon_rule, mon_sensor) are not touched.

BAR (committed before the rule is scored; not moved after).  Tree = this branch's block, BASE =
ab96d05d's (``git archive`` src).  A row is *flagged* where ``mon_flag``, ``mon_unsure`` or
``refused`` is TRUE; *differs* where max |ST - C| > 1e-9 um (C = the JSON mirror ``Simulator``,
equal to the C to 1e-9 um on these cases per dep108 / dep108f).
* S1 on bench_dep108's root (/tmp/dep108/droot, its data), T_amb ``back`` +30 (dep108f's seen
  case) and ``all`` +30 (dep108's): every differing row flagged (BASE: 320 unflagged on ``back``).
* S2 bench_st108b's 8 healthy streams (lr/dl 9964-9967, st108b's root): 0 rows whose
  ``mon_unsure`` differs from BASE (none has a reading out of range at its first sample).
* S3 c and (mon_flag, mon_rule, mon_sensor) identical to BASE on every S1 / S2 row.
* S4 PARSED_DIGEST updated (blark parses), test_export_st97d / test_export.py / the ST modules
  pass; a test (<= ~2 s CPU, test_export_lean107b's room fixture) failing on BASE; one docs line.
* KEPT where S1-S4 hold; else REFUSED.  Porting MON_FIRST_C (numbers agree) only if time is left.

SCORED (2026-12-07, the bar 3b1d5b3a unchanged; BASE /tmp/st108d/basesrc = ``git archive ab96d05d
src``; CPU user + sys by /usr/bin/time).  No seeds drawn.
* S1 met.  ``back`` +30: 480 rows, all differing (max 7.97 um); unflagged BASE 320 (rows 40-119 of
  each campaign) -> RULE 0; mon_unsure rows 160 -> 480.  ``all`` +30: 480 differing (21.5 um),
  unflagged 0 -> 0 (already refused / mon_lost on every row).  ``score`` 6.5 + 0.9 s CPU.
* S2 met.  bench_st108b ``stream`` on /tmp/st108b_root's lr/dl 9964-9967 (46084 rows), tree and
  BASE (69.4 + 0.9 / 67.9 + 0.9 s): 0 rows whose ``mon_unsure`` differs, printed lines identical.
* S3 met.  ``back`` / ``all``: c, refused, flag, rule, sensor identical (``score``'s S3 line); the
  8 streams: 0 rows whose c or (flag, rule, sensor) differ.
* S4: see the report (/work/notes/sec108/st108d.md).
* Found on the way: the block's ``first`` holds through refused rows to the first taken sample, so
  the rule resets on ``reset`` (the campaign's start), not on ``first``; on ``back`` the block takes
  T_amb afresh at row 40 (its reference there), hence 4.3-8.0 um off the C.  MON_FIRST_C not ported.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st108d.py score ROOT DATA BASESRC
"""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
from _cli import project_root, run_commands  # noqa: E402

TOL = 1e-9     # um
CASES = [("T_amb", 30.0, "back"), ("T_amb", 30.0, "all")]


def _block(deployed, basesrc: str | None) -> str:
    """The ST block of ``deployed`` as the tree exports it (``basesrc``: as that src does, in a child)."""
    from thermocomp.apps.deploy.export import exported_files

    if basesrc is None:
        return exported_files(deployed, "st")["compensator.st"]
    with tempfile.NamedTemporaryFile(suffix=".pkl") as f:
        pickle.dump(deployed, f)
        f.flush()
        code = ("import pickle, sys; from thermocomp.apps.deploy.export import exported_files; "
                "d = pickle.load(open(sys.argv[1], 'rb')); "
                "sys.stdout.write(exported_files(d, 'st')['compensator.st'])")
        env = {**os.environ, "PYTHONPATH": str(Path(basesrc).resolve() / "src")}
        return subprocess.run([sys.executable, "-c", code, f.name], env=env, check=True,
                              capture_output=True, text=True).stdout


def _run(block: str, ss, df) -> dict:
    """Per row: the block's c, refused, flag, rule, sensor, mon_unsure; the mirror's c."""
    from test_export import StructuredText
    from thermocomp.apps.deploy.export import Simulator

    st, sim = StructuredText(block), Simulator(ss)
    sim.reset()
    U, t = df[ss.inputs].to_numpy(float), df["time"].to_numpy(float)
    got = {k: [] for k in ("st", "c", "refused", "flag", "rule", "sensor", "unsure")}
    for i in range(len(df)):
        a, c = st(U[i], t[i], i == 0), sim.step(U[i], t[i])
        v = st.vars
        for key, x in (("st", np.array(a, float)), ("c", np.array(c, float)), ("refused", bool(v["refused"])),
                       ("flag", bool(v["mon_flag"])), ("rule", int(v["mon_rule"])),
                       ("sensor", int(v["mon_sensor"])), ("unsure", bool(v.get("mon_unsure", False)))):
            got[key].append(x)
    return {k: np.array(x) for k, x in got.items()}


def score(root: str, data: str, basesrc: str) -> None:
    """S1 and S3 on bench_dep108's root (module doc): per case and block, rows, differing, unflagged."""
    from bench_dep108 import _changed
    from hydra import compose, initialize_config_dir

    from thermocomp.apps.deploy.export import state_space
    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    base, data = project_root(root), str(Path(data).resolve())
    os.chdir(base)
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"data.path={data}", "track=false"])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    deployed = deployable_model(cfg, ds, train_ids, str(base / "run" / "model.pkl"), "export.model")[0]
    ss = state_space(deployed, monitor=True)
    blocks = {"BASE": _block(deployed, basesrc), "RULE": _block(deployed, None)}
    for column, push, mode in CASES:
        tests = [_changed(ds.campaigns[c], column, push, mode) for c in test_ids]
        runs = {who: [_run(b, ss, df) for df in tests] for who, b in blocks.items()}
        for who, per in runs.items():
            got = {k: np.concatenate([r[k] for r in per]) for k in per[0]}
            gap = np.max(np.abs(got["c"] - got["st"]), axis=1)
            differ, flagged = gap > TOL, got["flag"] | got["unsure"] | got["refused"]
            print(f"{column} {mode} {push:+g} {who}: {len(gap)} rows; differing {int(differ.sum())} (max "
                  f"{gap.max():.3g} um), unflagged {int((differ & ~flagged).sum())}; unsure rows "
                  f"{int(got['unsure'].sum())}", flush=True)
        same = [np.array_equal(np.vstack([r[k] for r in runs["BASE"]]) if k == "st" else
                               np.concatenate([r[k] for r in runs["BASE"]]),
                               np.vstack([r[k] for r in runs["RULE"]]) if k == "st" else
                               np.concatenate([r[k] for r in runs["RULE"]]))
                for k in ("st", "refused", "flag", "rule", "sensor")]
        print(f"  S3 c, refused, flag, rule, sensor identical to BASE: {same}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": score}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
