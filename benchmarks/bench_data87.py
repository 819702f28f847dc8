"""Data in (stop 87, data87): a unit changed under an unchanged header on stdin; a folder whose
files differ in encoding and thousands separator.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_data87.py units ROOT     # (a) seed 9145
    python benchmarks/bench_data87.py folder ROOT    # (b) seeds 9141-9144
    python benchmarks/bench_data87.py sessions ROOT  # (c) test_stranger69's LabVIEW runs

``units`` (a): ``ROOT/ds``, the default scenario at the tests' short size (9 campaigns of 2-3 h,
6 train, 3 test; seed 9145); its first test campaign with, from data row 15 on, its warmest
temperature column in °F or in kelvin (``x + 273.15``) or its largest error column in mm
(``x / 1000``), the header unchanged (and once unchanged: ``none``).  Each piped into
``monitor monitor.input=-`` and, written over the record's file, ``monitor`` of the file: the
exit code and what each says.  What "flagged on a file" means there: exit 2, naming file,
column and row (``data.kelvin_threshold_c``, ``data.max_step_ratio``).

``folder`` (b): ``ROOT/semicolons`` and ``ROOT/commas``, four runs of test_audit86's German
export (seeds 9141 for the fourth, 9142-9144 for the first three): three a logger's PC wrote
as UTF-8 (``;`` and decimal commas, or a script's ``,`` and decimal points), the fourth
re-saved by a German Excel, cp1252, ``;``, decimal commas, its speeds grouped by a point
(``6.000``).  ``init`` (no key), then ``run`` by its config (``data.test_fraction`` 0.25 where
init wrote none); and ``run`` by hand with each ``data.encoding`` a user can give.

``sessions`` (c): test_data86b's en-GB LabVIEW folder (three ``.lvm`` runs, test_stranger69's
values), ``init``, ``run model=lagbank`` by its config; the held-out run's ``.lvm`` piped into
``monitor`` of the run's model.pkl once, and twice appended (two sessions, a 'LabVIEW
Measurement' header each).

No bar (gaps closed, not a rule scored): each outcome before (main 25b18da6) and after
(fix/data87).

Scored (2026-12-04, 25b18da6 (this branch's base) -> fix/data87, ``units`` / ``folder
/tmp/data87/bench/<tree>_<command>``)
------------------------------------------------------------------------------------------
``units``: the test campaign K03, its warmest temperature T_motor1 and its largest error E_Z.
On the file every change was exit 2 on both trees (°F: "column 'T_motor1', line 16 (data row
15): steps from 19.04 to 66.51 in one sample and the rows from here on read as °F of the °C
before: the unit changes inside the file, convert it (data.max_step_ratio=5)"; mm: "column
'E_Z', ... steps from 11.9 to 0.0123 ... read as mm of the µm before ..."); piped in:

* °F and K: exit 0, "events: 1, exclusions: 1 (32.4 per 100 h), first: T_motor1", RMSE fixed
  E_X / E_Y / E_Z 2.932 / 1.909 / 25.680 µm (the unchanged stream's 0.908 / 0.691 / 1.803) ->
  exit 2, "file <stdin>, column 'T_motor1', data row 15: " and the file's words after it.
* mm: exit 0, 0 events, E_Z scored 8.973 µm (the probe's rows in mm taken as µm) -> exit 2,
  "file <stdin>, column 'E_Z', data row 15: steps from 11.9 to 0.0123 ... mm of the µm before".
* none: exit 0, 0 events, 0.908 / 0.691 / 1.803 on both trees (the monitor quiet on the
  healthy stream, as before).
* the kelvin step's words, on the file (both trees) and now on stdin: "292.32 °C is above
  data.kelvin_threshold_c=200: no temperature, in °C or kelvin (the column's median is 291):
  another quantity? give its column a role, data.roles.state=[<header>] ..." -> "...: the
  rows from here on read as kelvin of the °C before: the unit changes inside the file, convert
  it" (the rows above in °C, from it on at least 0.9 in kelvin's range).

``folder`` (main -> here), ``semicolons`` / ``commas``:

* ``init``: exit 2 on both, "file .../run4.csv, column 'T Luft [\ufffdC]', line 1: byte 0xb0
  is not UTF-8 text (a Windows export? set data.encoding=cp1252, ...)" -> exit 0, "run1.csv:
  encoding each file's own (UTF-8 and cp1252 files)", written ``encoding: auto`` and, for
  ``semicolons``, ``thousands: .``; for ``commas``, ``delimiter / decimal / thousands: auto``
  ("the thousands separator '.' of some files: each file's own read, data.thousands=auto").
  ``run`` by the config: exit 0, E_dX / E_dZ test RMSE 0.03 / 0.03 µm (run4, the held-out
  Excel file, its speeds read 6000 / 12000 / 1500 as run1's: test_data87).
* ``run`` by hand, ``data.encoding=utf-8``: exit 2 at run4's 0xb0 (``semicolons``), or at
  run1's '20.39' with the folder-wide ``data.thousands='.'`` (``commas``), both trees;
  ``cp1252``: exit 2, "file .../run1.csv: file is UTF-8 text ('[°C];T'), not
  data.encoding=cp1252: save it as the others", both trees; ``auto`` (with
  ``data.thousands=auto``): exit 2, "data.encoding must be a character set ... got 'auto'" ->
  exit 0, the config's figures.
* a file ambiguous on its own (run4 with one speed '6.5' beside '6.000' and '20,41'; test_data87)
  was refused naming the file alone, "the decimal mark is ambiguous (cells with ',' and with
  '.')" -> "column 'Spindel [1/min]', data row 4: the decimal mark is ambiguous ('6.5' here,
  '20,41' in column 'T Luft [°C]', data row 1: each mark as a decimal mark)".

``init`` now looks at every file's bytes of a folder (before: its first file and the manifest):
0.030 s CPU to decode a 69 MB UTF-8 file (measured once, 2026-12-04), ``ascii_only`` stopping
at the first byte beyond ASCII.

``sessions`` (c), main -> here: one session piped in, exit 0, campaigns ['stdin'], E_dX RMSE
fixed 0.0210 µm over 120 samples (both trees); the same twice appended: exit 2, "file <stdin>:
the LabVIEW Measurement File streamed holds 2 sessions (a 'LabVIEW Measurement' header each), a
run each: stream one run" -> exit 0, campaigns ['stdin_1', 'stdin_2'], 0.0210 µm over 240
samples (each session from a reset, as the file's runs: told by its own header, not by a gap).
``connect.warm``'s log, one campaign, still refuses it.

Verdict (no bar): KEPT -- stdin says what the file says; a folder of files two programs saved
is read file by file where each is unambiguous; a LabVIEW stream's sessions are its runs.
"""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
from _cli import made_folder, run_commands

HERE = Path(__file__).resolve().parent
CHANGES = {"°F": ("T_", lambda c: (c * 1.8 + 32).round(2)),
           "K": ("T_", lambda c: (c + 273.15).round(2)),
           "mm": ("E_", lambda um: (um / 1000).round(5)), "none": ("T_", lambda c: c)}
LIGHT = ["track=false", "plots=none"]


def _cli(*args: str, stdin: bytes | None = None) -> subprocess.CompletedProcess:
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run([sys.executable, "-m", "thermocomp", *args], input=stdin,
                          capture_output=True, env=env)
    return subprocess.CompletedProcess(done.args, done.returncode,
                                       *(b.decode("utf-8", "replace") for b in (done.stdout,
                                                                               done.stderr)))


def _said(done: subprocess.CompletedProcess) -> str:
    if done.returncode == 0:
        lines = [ln for ln in done.stdout.splitlines() if ln.startswith(("E_", "events"))]
        return " | ".join(" ".join(ln.split()) for ln in lines)
    return next((ln for ln in done.stderr.splitlines() if ln.startswith("thermocomp: error")),
                done.stderr.strip()[-300:])


def units(root: str) -> None:
    """(a): each change piped in and on the file, ``monitor``'s exit and words."""
    base = made_folder(root)
    ds = base / "ds"
    done = _cli("simulate", "seed=9145", f"data.path={ds}", "sim.generator.n_campaigns=9",
                "sim.generator.duration_h=[2.0,3.0]", *LIGHT)
    assert done.returncode == 0, done.stderr[-2000:]
    index = pd.read_csv(ds / "campaigns.csv")
    name = index.loc[index["split"] == "test", "file"].iloc[0]
    clean = (ds / name).read_text()
    for change, (prefix, convert) in CHANGES.items():
        rows = pd.read_csv(io.StringIO(clean))
        column = max((c for c in rows.columns if c.startswith(prefix)),
                     key=lambda c: rows[c].abs().median())
        rows[column] = rows[column].where(rows.index < 14, convert(rows[column]))
        args = ["monitor", f"data.path={ds}", *LIGHT]
        piped = _cli(*args, "monitor.input=-", f"out={base / 'stdin'}",
                     stdin=rows.to_csv(index=False).encode())
        rows.to_csv(ds / name, index=False)
        on_file = _cli(*args, f"out={base / 'file'}")
        (ds / name).write_text(clean)
        print(f"{change} ({name} {column} from data row 15): stdin exit {piped.returncode}, "
              f"{_said(piped)}\n    file exit {on_file.returncode}, {_said(on_file)}")


def folder(root: str) -> None:
    """(b): the two folders, ``init`` and ``run`` by its config, and ``run`` by hand."""
    sys.path[:0] = [str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
    from test_data87 import _lab_folder

    base = made_folder(root)
    for kind, script_like in (("semicolons", False), ("commas", True)):
        runs = _lab_folder(base / kind, script_like)
        init = base / f"init-{kind}"
        done = _cli("init", str(runs), f"out={init}")
        said = [ln for ln in done.stdout.splitlines() if "encoding" in ln or "thousands" in ln
                or "separators" in ln]
        print(f"{kind}: init exit {done.returncode}, "
              + (" | ".join(said) if done.returncode == 0 else _said(done)))
        if done.returncode == 0:
            conf = (init / "conf" / "data" / f"{kind}.yaml").read_text(encoding="utf-8")
            print("    wrote: " + ", ".join(ln for ln in conf.splitlines()
                                            if ln.split(":")[0] in ("encoding", "thousands",
                                                                    "delimiter", "decimal")))
            done = _cli("run", f"hydra.searchpath=[file://{init / 'conf'}]", f"data={kind}",
                        *LIGHT, f"out={base / f'run-{kind}'}")
            print(f"    run by its config: exit {done.returncode}, {_said_run(done)}")
        for code in ("utf-8", "cp1252", "auto"):
            done = _cli("run", f"data.path={runs}", f"data.encoding={code}",
                        "data.thousands=auto" if code == "auto" else "data.thousands=.",
                        "data.roles.error=[d*]", "data.test_fraction=0.25", *LIGHT,
                        f"out={base / f'run-{kind}-{code}'}")
            print(f"    run, data.encoding={code}: exit {done.returncode}, {_said_run(done)}")


def _said_run(done: subprocess.CompletedProcess) -> str:
    if done.returncode != 0:
        return _said(done)
    return " | ".join(" ".join(ln.split()[:7]) for ln in done.stdout.splitlines()
                      if ln.startswith("E_"))


def sessions(root: str) -> None:
    """(c): one session and the same twice piped into ``monitor``."""
    import json

    sys.path[:0] = [str(HERE.parent / "tests" / d) for d in ("", "shell", "apps")]
    from test_data86b import _gb_folder

    base = made_folder(root)
    runs = _gb_folder(base / "runs")
    done = _cli("init", str(runs), f"out={base / 'init'}")
    assert done.returncode == 0, done.stderr[-2000:]
    common = [f"hydra.searchpath=[file://{base / 'init' / 'conf'}]", "data=runs",
              "model=lagbank", *LIGHT]
    done = _cli("run", *common, f"out={base / 'run'}")
    assert done.returncode == 0, done.stderr[-2000:]
    one = (runs / "ZP1200_Lauf_03.lvm").read_bytes()
    for label, piped in (("one session", one), ("two sessions", one + b"\r\n" + one)):
        out = base / f"monitor-{label[:3]}"
        done = _cli("monitor", *common, f"monitor.model={base / 'run' / 'model.pkl'}",
                    "monitor.input=-", f"out={out}", stdin=piped)
        if done.returncode:
            print(f"{label}: exit {done.returncode}, {_said(done)}")
            continue
        report = json.loads((out / "monitor.json").read_text())
        said = report["targets"]["E_dX"]
        print(f"{label}: exit 0, campaigns {list(report['campaigns'])}, E_dX RMSE fixed "
              f"{said['rmse_fixed']:.4f} µm over {said['n_samples']} samples")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"units": units, "folder": folder, "sessions": sessions}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
