"""The compiled stream prints its sensor monitor's flags (issue 34; stop 100, cflags100; audit99's
finding 3).

Before: ``stream.c`` printed the corrections ``C_<axis>`` only; the code's monitor state
(``tc_state.mon_flags``, its out set ``mon_out_set``) was checked only through its numpy mirror
(``CodeMonitor``), and a control engineer reading the rows could not see that a sensor went out
(stderr names events, not the state of each row).

RULE (cflags100; REFUSED: in benchmarks/cflags100_rule.patch, not in src; C ``printed_flags`` in
export/driver.py, the kinds ``watch.FLAG_KINDS`` in ``compensator.h``'s ``TC_FLAG_NAMES`` /
``TC_FLAG_BITS``): ``./stream --flags`` appends to each row, after the corrections, one 0/1
column per kind of ``mon_flags`` (``mon_excluded``, ``mon_readmitted``, ``mon_out``,
``mon_band``, ``mon_not_in_code``, ``mon_rereferenced``, ``mon_new_state``) and
``excluded_inputs``: the monitored sensors out, in the order they went out, ``;`` between them
(the served model's column of that name and its sensor names; served joins by ``,``, which would
need CSV quoting).  Numbers and names a CNC integrator splits at ``,`` without a CSV library.
Opt-in: without ``--flags`` the output is byte for byte as before (tests and benches read the
rows whole as numbers of TC_N_OUTPUTS columns: ``_streamed``, ``bench_swap99.compiled``).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_cflags100.py flags ROOT RECORD BASE_SRC   # the F1-F3 lines
    python benchmarks/bench_cflags100.py export ROOT RECORD FOLDER    # RECORD's C into FOLDER

``flags``: RECORD's mlr-none cell under ROOT (bench_swap99's ``_cell``: bench_mon98's healthy
frame, its drift and ambient cases), its C exported by this tree (``stream --flags``) and by BASE_SRC (a
``git archive`` of main's src; ``export`` run by BASE_SRC's python path), both compiled (gcc
-Werror), each case streamed through both; per case the rows whose printed flags differ from the
mirror's (``Simulator.watch``: each kind's bit, the out set's names in order), the rows flagged,
and whether the correction columns are BASE's bytes.

Records (SEEN only; no fresh seed simulated): dl9878 (bench_dep99b's traced record), dl9902
(bench_step99's traced record), ROOT a copy of those benches' ROOTs (/tmp/dep99b/root,
/tmp/step99/rule); measured after the bar, outside it: tr9876 (swap99's, its healthy frame
without an event) and ``fl`` (fl_thermal's served MLR, tests/conftest.py ``fl_thermal_served``).

BAR (written and committed before measuring; BASE = cd356319's src)
---
F1. dl9878 and dl9902, drift and ambient cases: the C's printed flags (7 kinds and
    excluded_inputs) equal the mirror's on every row: 0 rows differ.
F2. their healthy cases: no row flagged (every kind 0, excluded_inputs empty).
F3. every case: the correction columns of ``--flags`` byte-identical to BASE's stream output.
F4. the PARSED_DIGEST / ST untouched (no ST change; tests/shell/test_export.py passes).
F5. a test (tests/shell/test_export_cflags100.py, < 5 s) that fails on cd356319 and passes here.
KEPT if F1-F5 hold (src + test + docs); else REFUSED (benchmarks/cflags100_rule.patch).

Scored (bar b876db82; then, before any measurement, b3701907: without TC_MONITOR ``--flags``
prints 0 and none out, the monitor's state never being set there, and ``watch.flag_row`` shared
by the test and the bench; 2026-12-06 16:14-16:21 UTC under a load of 7-10 on 2 cores; BASE =
``git archive cd356319 src``; ROOT /tmp/cflags100/root).  Rows flagged: any kind 1 or a sensor
out.  CPU (user + sys) / wall of ``flags``: dl9878 44.2 / 145 s, dl9902 39.3 / 110 s, tr9876
57.9 / 132 s, fl 13.9 / 65 s (its fit)::

    record  case     rows   printed flags != mirror   rows flagged        corrections = BASE's bytes
    dl9878  healthy  7200   0 rows                    17 (from row 3249)  yes
    dl9878  drift    7200   0 rows                    1067                yes
    dl9878  ambient  7200   0 rows                    965                 yes
    dl9902  healthy  7200   0 rows                    57 (from row 989)   yes
    dl9902  drift    7200   0 rows                    1077                yes
    dl9902  ambient  7200   0 rows                    996                 yes
    outside the bar (measured after it):
    tr9876  healthy  10080  0 rows                    0                   yes
    tr9876  drift    10080  0 rows                    7420 (from 140)     yes
    tr9876  ambient  10080  0 rows                    6885 (from 670)     yes
    fl      healthy  1112   0 rows                    0                   yes

F1 MET (0 rows differ in 4 cases, 28800 rows).  F2 NOT MET as worded: dl9878's and dl9902's
healthy frames (bench_mon98's "healthy": no planted drift) carry their generator's faults
(bench_swap99 / bench_step99 logs: served 6 and 32 events, the mirror 6 and 8 flagged rows), and
the C prints them, as the mirror (0 rows differ): 17 and 57 rows flagged.  A clause aimed wrong
(it should have named frames without served events); the frames without any event, tr9876's
healthy and fl_thermal's test campaign, print no flag (outside the bar).  F3 MET (every case's
corrections byte-identical to BASE's).  F4 MET (no ST change; with the rule test_export.py
(PARSED_DIGEST), test_export_dep99b / cmon80 / cmon92b and test_lint: 37 passed).  F5 MET
(test_export_cflags100: 4.13 s call under a load of 7.5; fails on cd356319: ``--flags`` is a
usage error, exit 2).
VERDICT: REFUSED (F2 as worded).  The rule, its test and docs: benchmarks/cflags100_rule.patch
(``git apply`` on cd356319); ``flags`` / ``export`` need it applied (``watch.FLAG_KINDS``,
``flag_row``).  Next: a bar that names frames without served events for "no flag", and the
conformance pack's check.sh comparing these columns (not built).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_swap99  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_mon98b import _dl  # noqa: E402

bench_swap99.RECORDS.update({"dl9902": _dl(9902)})      # bench_step99's seen record


def _cell(root: str, record: str) -> tuple:
    """``(deployed, ss, names, start, {case: (sensor, frame)})``: bench_swap99's cell (its healthy
    frame, drift and ambient cases) or, for ``fl``, fl_thermal's served MLR (tests/conftest.py),
    its test campaign healthy only."""
    if record == "fl":
        sys.path[:0] = [str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
        from conftest import fl_thermal_served

        os.environ.pop("THERMOCOMP_TARGETS", None)
        deployed, ss, frame = fl_thermal_served()
        return deployed, ss, list(deployed.monitor.names), 0, {"healthy": ("-", frame)}
    deployed, ss, frame, start, names, drifts = bench_swap99._cell(root, record)
    return deployed, ss, names, start, {"healthy": ("-", frame), **drifts}


def export(root: str, record: str, folder: str) -> None:
    """RECORD's cell exported as C into FOLDER by this python path's src, and compiled."""
    from thermocomp.apps.deploy.export import exported_files

    deployed = _cell(root, record)[0]
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    for name, text in exported_files(deployed, "c").items():
        (out / name).write_text(text)
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "compensator.c",
                    "stream.c", "-lm", "-o", "stream"], cwd=out, check=True, capture_output=True)


def _mirror_flags(deployed, ss, full, names) -> list[tuple]:
    """Per row the mirror's ``watch.flag_row`` (the served model stepped beside it)."""
    from bench_cmon92 import Stepped

    from thermocomp.apps.deploy.export.watch import flag_row

    run = Stepped(deployed, ss)
    return [flag_row(run.sim.watch, names) for _ in run.rows(full)]


def flags(root: str, record: str, base_src: str) -> None:
    """The ``flags`` lines (module doc)."""
    from thermocomp.apps.deploy.export.watch import FLAG_KINDS

    deployed, ss, names, start, cases = _cell(root, record)
    folder = Path(root).resolve() / "cflags" / record
    export(root, record, str(folder / "rule"))
    env = {**os.environ, "PYTHONPATH": f"{Path(base_src).resolve()}{os.pathsep}{HERE}"}
    subprocess.run([sys.executable, __file__, "export", root, record, str(folder / "base")],
                   env=env, check=True)
    n_out, kinds = len(ss.targets), [f"mon_{k}" for k, _ in FLAG_KINDS]
    for case, (sensor, full) in cases.items():
        rows = full[["time", *ss.inputs]].to_csv(index=False, float_format="%.17g")
        got = subprocess.run([str(folder / "rule" / "stream"), "--flags"], input=rows,
                             capture_output=True, text=True, check=True).stdout
        base = subprocess.run([str(folder / "base" / "stream")], input=rows,
                              capture_output=True, text=True, check=True).stdout
        cut = "".join(",".join(line.split(",")[:n_out]) + "\n" for line in got.splitlines())
        printed = pd.read_csv(pd.io.common.StringIO(got), keep_default_na=False, dtype=str)
        said = [(*(int(v) for v in r[kinds]), r["excluded_inputs"]) for _, r in printed.iterrows()]
        mirror = _mirror_flags(deployed, ss, full, names)
        differ = [i for i, (a, b) in enumerate(zip(said, mirror)) if a != b]
        flagged = [i for i, r in enumerate(said) if any(r[:-1]) or r[-1]]
        print(f"{record} {case} ({sensor}): {len(said)} rows (mirror {len(mirror)}); flags != mirror "
              f"{len(differ)} rows{f' (first fed row {differ[0] - start} of the drift)' if differ else ''}; "
              f"rows flagged {len(flagged)} (first at drift row "
              f"{flagged[0] - start if flagged else '-'}); corrections = BASE's bytes: {cut == base}",
              flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"flags": flags, "export": export}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
