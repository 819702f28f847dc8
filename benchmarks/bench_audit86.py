"""audit86: thermocomp run as a stranger would, off the happy path (a log; numbers below).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_audit86.py write CSV ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_audit86.py matrix DATA ROOT [CELLS]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_audit86.py faults DATA ROOT

``write``: ``ROOT/<kind>.<ext>``, the contract file ``CSV`` (a simulated campaign) as a lab's
raw export: headers with units (``Zeit [s]``, ``T headstock [°C]``, ``dX [µm]``, ``Spindel
[1/min]``, ``Tuer [-]``, the ambient ``Halle [°C]``), ``;`` and decimal commas, in ten forms:
``semi_bom.csv`` (a UTF-8 BOM, CRLF), ``notime.csv`` (no time column), ``tab.txt``, ``utf16.txt``
(tab-separated UTF-16 with its BOM, Excel's "Unicode text"), ``trail.csv`` (blank trailing
lines), ``unitchange.csv`` (a second export pasted under the first, its header again, ``dX`` in
mm from there), ``kelvinhalf.csv`` (one sensor in kelvin from the half on, its header unchanged),
``duphead.csv`` (``T frame1 [°C]`` twice, different values), ``nonmono.csv`` (rows 1001 / 1002
swapped), ``allnan.csv`` (``T frame2`` every cell empty).

``matrix``: every family (``CELLS``: ``family[+key=value...]`` comma-separated; default every
family, and each exportable one with ``ati=cmeans``) on the dataset ``DATA``: ``run`` ->
``replay`` (run's test RMSE against replay's streamed and batch one) -> ``export
export.format=c export.check=true`` -> the C compiled (gcc -std=c99 -Wall -Wextra -Werror)
and its conformance pack run (``./stream --check``), per cell one line.

``faults``: ``ROOT/fault_<kind>/``, the contract folder ``DATA`` (the climate room's) with its
last campaign (of 589 rows at 60 s) given one fault: ``frozen`` (``T_headstock`` held from row
240, 4 h in), ``jump`` (+2 K on ``T_frame1`` from row 300), ``drift`` (``T_nc_x1_drive`` +1
K/h from row 180), ``dropout`` (``T_guidebush`` empty in rows 350-370).

What was run (2026-12-04, on 14a3bd50 then this branch; 2 cores shared by six sessions, CPU
user + sys by ``/usr/bin/time``; seeds 9011 ``sim=swiss_lathe_door`` and 9012
``sim=climate_room``, drawn once, nothing tuned on them).  The bar of an audit, written before:
every command of the README and of a stranger's path ends in a result or in a refusal naming
file, column and row with a fix that works (exit 2, nothing written); replay = run to 1 %; the
exported C = the served model (its pack) and = what was scored; the monitor quiet on a healthy
record and catching each planted fault.

(1) A fresh clone (``git clone -q /work/main /tmp/audit86-clone``, main's venv linked as
``.venv``: ``make run``'s install step would have written into main's venv, so its two commands
were typed instead): ``thermocomp simulate`` + ``thermocomp run`` print the README's table to
the digit (E_Z 5.46 2.60 30.61 -> 5.80), 4.5 + 0.9 s CPU; ``run data=fl_thermal`` E_ch5 ->
3.05 (the README's expected "-> 3.0x"); ``export ... export.format=c``, ``cc``, ``./stream < K03.csv``:
``C_X,C_Y,C_Z`` and its rows; ``twin`` / ``connect`` (port 4911, not 4840: other sessions share
the machine): E_Z RMS 37.887 -> 3.066 µm compensated, 89 samples, 0 stale; ``serve`` (port
5911): the README's request answers ``C_Z``; a ``"5,83"`` cell refused "column 'T_bearing_f1',
data row 1 of the block: value '5,83' is not a number", a request lacking 9 inputs refused by
MLflow's schema naming them, a time going back substituted and said as an event.

(2) Lab exports (``write``) of the lathe's 80 h calibration run (4801 rows at 60 s): ``init``
(1.2-1.5 s CPU each) read ``semi_bom``, ``tab``, ``utf16``, ``trail``, ``duphead`` (said:
"column 8 read as 'T frame1#2 [°C]'") in one try, and ``notime`` in two (refused "no 'time'
column ...: set data.sample_period_s", then read); so too, hand-written: every cell quoted, a
German ``Datum/Uhrzeit`` (cp1252), one over the 2023-03-26 DST start (said: "the clock jumps an
hour forward ... data.timezone=Europe/Berlin"), an elapsed ``hh:mm:ss`` past 24 h, old Mac CR
line ends, UTF-16 BE, a trailing ``;`` on every line.  ``run`` of each (1.6-1.8 s CPU): E_dX /
E_dY 0.98 / 0.66 µm in every form; the exported C fed each raw file (``;``, TAB, UTF-16, no
time column) printed the same 4801 corrections byte for byte; ``replay`` = batch = run (0.982 /
0.661) and ``monitor`` (file: 0 events; ``monitor.input=-`` of each form: 0 events, the same
RMSE).  Refused, exit 2, file / column / line named: ``kelvinhalf`` ("line 2402: 306.49 °C is
above data.kelvin_threshold_c=200 ..."), ``allnan`` ("column has no valid value ...
data.roles.ignore=['T frame2']"), ``unitchange`` ("line 2402 ... the file's header written
again under its data"), ``nonmono``; a folder mixing cp1252 and UTF-8 files ("save it as the
others"); an empty file, a header alone, 2 rows (each a one-line refusal).

Mended (one commit each, a test failing on main in tests/shell/test_audit86.py or
test_time_order56.py):

* ``nonmono`` (rows 1001 / 1002 swapped, a sample written late) was told "the logger's clock
  set back ...; sorting the rows would mix its stretches before and after this row: cut the
  file at this row into two runs": now "the rows are not in time order; sort them by their
  time" (a set-back is interleaved only where, sorted, samples fall closer than 0.75 of the
  median step; the 88.5 min set-back of test_messy_folder58 still is one);
* a German Excel export's speed ``6.000`` beside ``21,18``: ``init`` refused "the decimal mark
  is ambiguous" before it looked for the thousands separator its docs say it finds; now read
  in one try, ``data.thousands='.'`` written and said (3960 cells);
* a folder of runs two PCs exported (``;`` + decimal commas, and a TAB UTF-16 file): ``init``
  refused "set data.delimiter='\\t'", which refuses the others, while ``run`` read the folder;
  now ``delimiter: auto`` / ``decimal: auto`` written and said, E_dX 2.28 µm as ``run`` alone;
* a manifest kept in Excel (BOM, ``;``, ``;;;;`` rows under the table) was refused "campaign id
  '' is empty" at its row 44; the empty rows under it are now left out and said (the climate
  room under "Messungen März 2023/": E_X / E_Z 1.56 / 2.41, the same as its own folder);
* a one-file record's train part too short was told "raise data.test_fraction" (which
  shortens it): now "lower data.val_fraction and data.test_fraction", and a record too short
  for any cut says so;
* ``unitchange``: before its refusal ``init`` said 17 lines "'dX [mm]' in 1 cell of number
  column 'dX [µm]': ... a mark for a value not measured, read as missing": a row of the
  header's names gives no marks now;
* a stream with decimal commas (``monitor.input=-``) named a bad cell ``2x,5`` at data row 999
  as "data row 1: non-numeric value" (its column read as text, commas unread), a line of text
  under the header as "'T headstock [°C]' is not numeric ('20,25')", no row: now "data row
  999: non-numeric value: '2x,5' is not a number", "data row 2401: ... 'Halle [°C]'";
* the exported ``stream.c`` refused ``duphead`` ("the header names input T_frame1 twice")
  that run / replay / monitor read as ``T frame1#2``: now read so, its 4801 corrections those
  of the file with the second header renamed, byte for byte;
* the C of ``hammerstein ati=cmeans`` failed a ``gcc -std=c99 -O2 -Wall -Wextra -Werror`` build
  (gcc 12.2: "array subscript -1 is below array bounds of 'MON_PREDICTABLE'" in
  ``mon_beyond``, inlined where ``far`` may be -1 to its eyes); ``mon_beyond`` now returns at a
  negative index: compiled, its pack passed.  No test: the warning follows gcc's inlining of
  that one model's code (every other cell of the matrix compiled), and the model takes minutes
  to fit; measured here only.

(3) ``matrix /tmp/a86/climate_room_9012`` (43 runs, C40-C43 held out; 722 + 41 s CPU, 49 min
wall for the 13 cells): run / replay / batch test RMSE E_X ; E_Z (µm), equal to the printed
digit in every cell; each cell's C (gcc warnings as errors) run through its pack (9 campaigns:
C40-C43 and C40's five planted faults), every one passed, largest difference 5.8e-13 µm:

=======================  ===============  ===============
cell                     E_X              E_Z
=======================  ===============  ===============
mlr                      1.5604           2.4137
pcr                      1.7519           2.9975
arx                      1.5861           2.4426
lagbank                  1.1614           1.5528
hammerstein              1.1614           1.5528
lstm                     1.5604           2.4137
auto                     0.4575           0.6659
mlr ati=cmeans           0.4575           0.6659
pcr ati=cmeans           1.1073           2.6698
arx ati=cmeans           0.6614           0.7075
lagbank ati=cmeans       0.3435           0.5943
hammerstein ati=cmeans   0.3373           0.5541  (its C: the gcc failure above, mended)
=======================  ===============  ===============

``arx_rf`` refused on it, exit 2, "model.estimator.state_column='S_door' is no column ...
name one, or null for none".  ``lstm`` = mlr and ``hammerstein`` = lagbank to the digit: the
LSTM's early stopping kept the linear law (models.md says so), the Hammerstein powers gave
nothing over the lags.  On the lathe 9011 (``matrix ... "arx_rf,mlr+denoise=emd,..."``):
arx_rf 1.4068 / 1.2504 (E_X / E_Y), mlr denoise=emd 2.3642 / 1.4934, lagbank denoise=emd
1.0884 / 0.7609, auto 0.8929 / 0.6848, run = replay = batch, packs passed (plain, ``run``
alone: mlr 2.1822 / 1.4045, lagbank 1.1121 / 0.7658, hammerstein 0.8929 / 0.6861: auto
better than mlr on both and within 10 % of the best, hammerstein's, on both);
``adapt.method`` is no key of ``run``
(refused naming the groups it composes): ``replay adapt.method=bias`` of the climate room's
mlr: 16 references, E_X 1.560 -> 1.314, E_Z 2.414 -> 2.246 (2.3 + 0.3 s).

Issue 34 on this record: auto better than mlr on both targets (0.458 / 0.666 against 1.560 /
2.414) and than every plain family; within 10 % of the best single family: NOT on either
where the ATI-wrapped ones count (it chose mlr + ATI; hammerstein ATI 0.337 / 0.554: auto
+35.6 % / +20.2 %; lagbank ATI +33.2 % / +12.0 %).  Reported, not changed (model=auto is
another session's).

``promote``: a tracked sweep ``run -m model=mlr,lagbank,auto`` in the clone (19.1 + 1.7 s
CPU), ``promote`` (5.6 + 0.9 s): auto, v1 @champion; ``export
export.model=models:/thermocomp-compensator@champion export.format=c export.check=true``: its
pack passed (9 campaigns, largest 1.4e-14 µm); the compiled champion fed C40-C43 as recorded:
pooled test RMSE 0.45746 / 0.66587 µm = run's 0.4575 / 0.6659 (deployed = scored).

(4) ``monitor`` (the matrix's mlr, 2.9-3.3 s CPU each) on the healthy fresh test campaigns: 0
events, fixed = adaptive = run's 1.560 / 2.414.  ``faults``: frozen ``T_headstock`` at 4.0 h:
excluded at 4.23 h (fixed / adaptive E_X 2.376 / 1.561, E_Z 2.775 / 2.414); +2 K on
``T_frame1`` at 5.0 h: excluded at 5.00 h, re-admitted at 5.17 h (4.435 / 1.560, 4.813 /
2.421); ``T_nc_x1_drive`` +1 K/h from 3.0 h: excluded at 4.00 h (9.074 / 1.626); ``T_guidebush``
empty for 21 samples at 5.83 h: excluded, re-admitted at 6.33 h (1.560 / 1.560).  Each caught,
the adaptive stream within 0.1 µm of the healthy one.

Left: a folder whose files need different ``data.encoding`` (cp1252 beside UTF-8) or
``data.thousands`` has no setting that reads it (refused with the fix: save them alike); a
unit changed inside a file under the same header (dX from µm to mm) is said by the file reader
("the unit changes inside the file") but not by a stream on stdin; issue 34's within-10 % on
this record (above); ``init`` still prints the first file's "delimiter ';'" beside the folder's
``auto``.
"""
from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import made_folder, run_commands  # noqa: E402
from _faults import fault_folders, four_faults  # noqa: E402

FAMILIES = ("mlr", "pcr", "arx", "arx_rf", "lagbank", "hammerstein", "lstm", "auto")
EXPORTABLE_ATI = ("mlr", "pcr", "arx", "lagbank", "hammerstein")
STATES = {"S_spindle_rpm": "Spindel [1/min]", "S_tool_rpm": "Werkzeug [1/min]",
          "S_door": "Tuer [-]"}


def lab_names(columns) -> dict:
    """A lab's header with its unit for each contract name."""
    names = {"time": "Zeit [s]", "T_amb": "Halle [°C]"}
    for c in columns:
        if c.startswith("T_") and c != "T_amb":
            names[c] = f"T {c[2:]} [°C]"
        elif c.startswith("E_"):
            names[c] = f"d{c[2:]} [µm]"
        elif c.startswith("S_"):
            names[c] = STATES.get(c, f"{c[2:]} [-]")
    return names


def semi(frame: pd.DataFrame, **kw) -> str:
    return frame.to_csv(sep=";", decimal=",", index=False, **kw)


def write(csv: str, root: str) -> None:
    """The ten exports of ``csv`` into ``root``."""
    out = made_folder(root)
    lab = pd.read_csv(csv)
    lab = lab.rename(columns=lab_names(lab.columns))
    half = len(lab) // 2
    (out / "semi_bom.csv").write_bytes(b"\xef\xbb\xbf" + semi(lab, lineterminator="\r\n").encode())
    (out / "notime.csv").write_text(semi(lab.drop(columns="Zeit [s]")), encoding="utf-8")
    (out / "tab.txt").write_text(lab.to_csv(sep="\t", index=False), encoding="utf-8")
    (out / "utf16.txt").write_text(lab.to_csv(sep="\t", index=False), encoding="utf-16")
    (out / "trail.csv").write_text(semi(lab) + "\n\n", encoding="utf-8")
    second = lab.iloc[half:].copy()
    second["dX [µm]"] /= 1000
    (out / "unitchange.csv").write_text(
        semi(lab.iloc[:half]) + semi(second.rename(columns={"dX [µm]": "dX [mm]"})), encoding="utf-8")
    kelvin = lab.copy()
    kelvin.loc[half:, "T headstock [°C]"] += 273.15
    (out / "kelvinhalf.csv").write_text(semi(kelvin), encoding="utf-8")
    twice = lab.copy()
    twice.columns = [("T frame1 [°C]" if c == "T frame2 [°C]" else c) for c in lab.columns]
    (out / "duphead.csv").write_text(semi(twice), encoding="utf-8")
    swapped = lab.copy()
    t = swapped["Zeit [s]"].to_numpy().copy()
    t[[1000, 1001]] = t[[1001, 1000]]
    swapped["Zeit [s]"] = t
    (out / "nonmono.csv").write_text(semi(swapped), encoding="utf-8")
    empty = lab.copy()
    empty["T frame2 [°C]"] = np.nan
    (out / "allnan.csv").write_text(semi(empty), encoding="utf-8")
    print(f"{len(lab)} rows, 10 files in {out}")


def _thermocomp(*words: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "thermocomp", "-q", *words],
                          capture_output=True, text=True)


def _pack(code: Path) -> str:
    """The conformance pack of ``code`` run through its compiled ``stream``: the largest
    difference per campaign, or the first refusal."""
    build = subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2",
                            "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=code,
                           capture_output=True, text=True)
    if build.returncode:
        return f"gcc: {build.stderr[-300:]}"
    said = []
    for rows in sorted((code / "check").glob("*/rows.csv")):
        with rows.open() as stdin:
            ran = subprocess.run(["./stream", "--check", str(rows.parent / "expected.csv")],
                                 cwd=code, stdin=stdin, capture_output=True, text=True)
        last = (ran.stderr.strip().splitlines() or [""])[-1]
        said.append(f"{rows.parent.name} rc {ran.returncode} {last[-90:]}")
    return "; ".join(said) or "no campaign in the pack"


def matrix(data: str, root: str, cells: str = "") -> None:
    """run -> replay -> export (C, its pack) per cell on ``data``."""
    out_root = made_folder(root)
    todo = ([c.split("+") for c in cells.split(",")] if cells else
            [[f] for f in FAMILIES] + [[f, "ati=cmeans"] for f in EXPORTABLE_ATI])
    common = [f"data.path={Path(data).resolve()}", "track=false"]
    for family, *keys in todo:
        out = out_root / "-".join([family, *(k.replace("=", "_") for k in keys)])
        ran = _thermocomp("run", *common, f"model={family}", *keys, "plots=none", f"out={out}")
        if ran.returncode:
            print(f"{out.name}: run exit {ran.returncode}: {ran.stderr[-300:]}", flush=True)
            continue
        rep = _thermocomp("replay", *common, *keys, f"replay.model={out / 'model.pkl'}",
                          f"out={out / 'replay'}")
        if rep.returncode:
            print(f"{out.name}: replay exit {rep.returncode}: {rep.stderr[-300:]}", flush=True)
            continue
        scored = json.loads((out / "metrics.json").read_text())["targets"]
        streamed = json.loads((out / "replay" / "replay.json").read_text())["targets"]
        line = "; ".join(f"{t} {scored[t]['test']['rmse']:.4f} / {r['rmse']:.4f} / "
                         f"{r['rmse_batch']:.4f}" for t, r in streamed.items())
        exp = _thermocomp("export", *common, *keys, f"export.model={out / 'model.pkl'}",
                          "export.format=c", "export.check=true", f"out={out / 'code'}")
        packed = (_pack(out / "code") if exp.returncode == 0 else
                  f"export exit {exp.returncode}: {exp.stderr.strip()[-200:]}")
        print(f"{out.name}: (run / replay / batch) {line} | C: {packed}", flush=True)


def faults(data: str, root: str) -> None:
    """The four faults of the last campaign of ``data`` (a contract folder), a folder each."""
    src = Path(data).resolve()
    last = pd.read_csv(src / "campaigns.csv")["file"].iloc[-1]
    n = len(pd.read_csv(src / last))
    cases = four_faults(n, 60.0, ("T_headstock", 240), ("T_frame1", 300), ("T_nc_x1_drive", 180),
                        ("T_guidebush", 350, 371))

    def write_all(folder: Path, fault) -> None:
        shutil.copytree(src, folder, dirs_exist_ok=True)
        frame = pd.read_csv(src / last)
        for name in frame.columns:
            frame[name] = fault(name, frame[name].to_numpy(float))
        frame.to_csv(folder / last, index=False)

    fault_folders(made_folder(root), "audit86", cases, write_all)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "matrix": matrix, "faults": faults}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
