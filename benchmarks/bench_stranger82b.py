"""A stranger's pass on a 5-axis trunnion machining centre and its Yokogawa GX20 ASCII export
(stranger82b).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger82b.py write ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger82b.py faults ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger82b.py matrix ROOT SEED CONF

The machine is ``benchmarks/trunnion82b.py`` (a vertical 5-axis machining centre, its own lumped
network and kinematics: an A trunnion and a C rotary table on torque motors, a motor spindle
cooled by a chiller, X / Y / Z ball screws heated by their nuts, a hall without air conditioning;
12 day runs of 10 h from 06:00 on 12 of 19 days from Monday 2027-09-06, the shop using the
machine unlogged on other weekdays; 16 thermocouples; the TCP's dX / dY / dZ measured by the
NC's probing cycle on a sphere every 15 min (45 samples), nothing in between; planted position
effects X x the X screw's rise (dX), sin A / cos A x the trunnion's rise (dY / dZ), cos C /
sin C x the table's rise (dX / dY); seeds 8341-8345 only).

``write``: the runs as the lab's Yokogawa SMARTDAC+ GX20 records them and its Universal Viewer
converts a display-data file to ASCII (``.csv``): a file a run ``ROOT/trunnion<SEED>/
GX20_<yyMMdd>_<HHmmss>.csv``: a header block of ``"key","value"`` rows (``"Universal Viewer"``,
``"Model","GX20"``, ``"Serial No."``, ``"File Name"``, ``"Batch Name"``, ``"Start Time"``,
``"Sampling Interval","20s"``), then the channel table: ``"Channel"`` (``0001`` .. the
measurement channels, ``C001`` .. the communication channels the NC writes by Modbus),
``"Tag"`` (the lab's names: written here only), ``"Tag Comment"``, ``"Unit"`` (``C``, ``mm``,
``deg``, ``um``), then the data's column row ``"Date Time","0001",...`` and a row a sample
(``2027/09/06 06:00:20.0``, values ``21.3``, a broken thermocouple ``Burnout``, an input out of
range ``+Over`` / ``-Over``).  Channels: 0001 - 0016 the thermocouples, C001 - C004 the NC's
X / Y (mm) and A / C (deg), C005 - C007 the probing cycle's dX / dY / dZ (µm), written by the NC
at each cycle and left blank in the export between cycles (the lab's setting: an unrefreshed
communication channel blank, an assumption of this bench).  Quirks: ``MOTOR``'s plug loose for 4
samples in run 5 (``Burnout``), the recorder stopped and restarted in run 9 (two files, 10 min
apart).  The structure is the GX/GP ASCII conversion as Yokogawa's Universal Viewer manual and
users' posts describe it; no file a GX20 or the viewer wrote was at hand to check it.

``faults``: ``ROOT/fault_<kind>_<SEED>/``, the files, the last run with one fault: ``frozen``
(``PINOLE`` held from row 900), ``jump`` (+2 K on ``STAENDER_H`` from row 1000), ``drift``
(``KUEHLUNG`` +1 K/h from row 700), ``dropout`` (90 ``Burnout`` of ``MUTTER_X`` from row 1200).

``matrix``: bench_stranger75's (run -> replay per family on the data config init wrote).

Measured 2026-12-04, seed 8341 (``write`` 1.7 s CPU, 13 files, 21,570 rows; ``init`` 4.9 + 0.6
s CPU).  Before stranger82b ``thermocomp init ROOT/trunnion8341`` refused the folder: "no column
reads as a measured error (no length unit in a header ...); the numeric columns: 'C', 'C#2' ..."
(the channel table's ``Unit`` row taken for the header).  Now (``core/io/yokogawa.py``, the
standard library's ``csv``: no extra dependency) ``init`` alone (no key) wrote ``DX_TCP`` /
``DY_TCP`` / ``DZ_TCP`` as errors, read as a probe cycle ("measured on 1 row in 45": fitted and
scored on the measured rows only), ``X_POS`` / ``Y_POS`` / ``A_POS`` / ``C_POS`` states,
``HALLE`` the ambient (its name), ``max_gap_samples: 4`` (the loose plug's ``Burnout``), the last
run held out (13 campaigns: run 9's two files two).  The fresh draw 8342 read by ``init`` with
no key (5.3 + 0.4 s CPU): the same config but its path.

``matrix`` on its config: test RMSE dX / dY / dZ (µm, 40 probed rows of the last run, Thu 23
Sept; uncompensated 11.864 / 3.249 / 23.504) mlr 13.479 / 6.699 / 1.449, pcr 8.816 / 5.564 /
1.394, arx 10.376 / 6.593 / 1.282, lagbank 11.070 / 5.274 / 1.723, hammerstein 5.049 / 4.719 /
1.490, lstm 12.059 / 7.169 / 1.557, auto 5.049 / 4.719 / 1.449 (its validation: hammerstein on
dX / dY, mlr on dZ), mlr ``ati=cmeans`` 12.731 / 7.531 / 2.008; replay = run = batch in every cell to the
printed digit.  Every family WORSE than none on dY and all but pcr and hammerstein on dX: the
TCP's dX / dY carry the table's growth times cos C / sin C and the pivot's times sin A, and X
times the X screw's rise, that no law of the temperatures alone holds; dZ (mostly the ram and
spindle) compensated 23.5 -> 1.3-1.7.  Issue 34's acceptance on this record: auto better than
mlr on dX / dY, EQUAL to it on dZ (its validation chose mlr: 1.639 against arx's 1.716); within
10 % of the best family on 2 of 3 (dX, dY: hammerstein's; dZ +13.0 % of arx's).
Fresh draw 8342 (its own init config, ``run`` only; uncompensated 18.843 / 2.940 / 14.674): mlr
5.116 / 1.903 / 2.662, arx 4.969 / 1.952 / 2.664, pcr 6.794 / 1.939 / 2.382, hammerstein 2.867 /
1.543 / 1.835, auto 2.918 / 1.632 / 1.921: auto better than mlr on all three and within 10 % of
the best family (hammerstein) on all three (+1.8 %, +5.8 %, +4.7 %).

``diagnose`` (MLR, defaults, ``plots=none``; 11.7 + 1.4 s CPU): dX's planted X x the X screw's
rise found (``S_X_POS`` x ``T_MUTTER_X`` rise, absolute): test 13.48 -> 4.44 µm (CV 7.52 ->
3.23); dY, dZ nothing accepted (6.70, 1.45: never worse); the pivot's sin A / cos A x the
trunnion's rise (about 2 µm a K) and the table's cos C / sin C not found (12 CV units of ~35
probed samples each).

``monitor`` (``monitor.model`` the matrix's mlr, ``plots=none``; 6.3-7.0 s CPU each) on the
healthy last run: no event (fixed = adaptive = replay's 13.479 / 6.699 / 1.449).  Faults in the
last run (fixed / adaptive RMSE dX, dY, dZ): ``PINOLE`` (the ram) frozen at 5.0 h: excluded at
6.43 h (11.761 / 12.512, 6.344 / 6.484, 2.433 / 1.781); ``STAENDER_H`` +2 K at 5.56 h: excluded
at once (15.302 / 12.343, 7.913 / 6.408, 3.548 / 1.566); 90 ``Burnout`` of ``MUTTER_X`` at 6.67
h: excluded at once (13.620 / 13.361, 6.687 / 6.701, 1.438 / 1.441); ``KUEHLUNG`` (the spindle's
coolant, chiller-held) drifting 1 K/h from 3.89 h: NO event (dZ 1.449 -> 2.284 both): "no other
sensor predicts T_KUEHLUNG", monitor said of the healthy run: no band bounds its drift, and its
28.3 °C at the end is 4.3 K above the training runs' 24.0 °C, inside ``monitor.range_margin_c``
(10 °C).
The fresh draw 8342 (healthy, ``data.path`` only, 8341's mlr; 5.2 + 0.4 s CPU): NOT quiet: at
9.04 h of its last run ``RUNDTISCH`` (the C table) excluded ("drift: self-prediction error
-0.59 °C over the last 2 samples") and with it ``WIEGE`` (the trunnion: "no other sensor
predicts it once T_RUNDTISCH is out"), 2 exclusions, a rate-limited dX correction (fixed /
adaptive 5.860 / 5.763, 4.843 / 4.888, 1.213 / 1.209: no harm); 8342 with its own mlr (``run``
on its config): the same two exclusions at 9.04 h and 23 rate-limit events on dZ, dY 1.903 ->
2.299 adaptive (+20.8 %), dX 5.116 -> 5.222, dZ 2.662 -> 2.568: stranger82's coupled pair (the
table and the trunnion, each the other's only predictor) on a healthy record: in the 5 min
before it no temperature of the two moved by more than the logger's 0.1 K step (``WIEGE``
flickering 21.6 / 21.7 °C, ``RUNDTISCH`` 22.2), A and C still (50 / 270 deg).

``promote``: a tracked sweep ``run -m model=mlr,hammerstein,auto`` (49.7 + 3.4 s CPU), then
``thermocomp promote`` (10.9 + 0.7 s): auto @champion by its validation (2.85 against
hammerstein's 2.94 and mlr's 4.41, means over the three; its test 5.049 / 4.719 / 1.449).
``export export.model=models:/thermocomp-compensator@champion export.format=c
export.check=true`` (19.4 + 0.4 s CPU): compiled with ``gcc -std=c99 -O2 -Wall -Wextra
-Werror`` (hammerstein on dX / dY, mlr on dZ), its pack (6 campaigns, 10,800 rows) passed
(largest difference 2.8e-14 µm); ``thermocomp rows`` of the GX20 export (the test run,
``rows.errors=true``) streamed through ``./stream``: test RMSE (error referenced at its first
probe, plus the correction, over the 40 probed rows) 5.0486724 / 4.7187424 / 1.4489677 µm =
replay's = run's batch 5.049 / 4.719 / 1.449.

Mended (each with a test in tests/shell/test_stranger82b.py that fails on main), before -> now: a
folder of GX20 ASCII exports refused ("the numeric columns: 'C', 'C#2' ...") -> read
(yokogawa.py), piped into ``monitor monitor.input=-`` too; a GX20 export fed to the exported
``./stream`` exit 2 on "line 13: input T_amb has no finite value ..." after writing a header line
(its ``Tag`` row taken for the header, ``Tag Comment`` for a sample) -> refused at line 1 as a
Yokogawa export, nothing written, ``thermocomp rows`` named; its rows streamed = replay (mlr
13.479 / 6.699 / 1.449 µm, RMSE over the 40 probed rows, the error referenced at its first
probe); the export a European PC's viewer writes (``;``, decimal commas; 8341's first three
files rewritten so) refused as the comma one was before ("'C', 'C#2' ...") -> read as the comma
export (the separator the first line's; init's roles the same as of those files written
``°C`` in cp1252, but its ``encoding``).  Not defects: a cut file (its last row short) read
with that row's missing cells as an edge, ``init`` proposing ``data.max_edge_samples=1`` that
drops it; a cp1252 export's ``°C`` (init wrote ``encoding: cp1252``); channels without a tag
named by their number (``T_0001`` ...).
Left: on 8341 no family compensates dX / dY below none but hammerstein / pcr (dX) (the pivot's
and table's terms depend on A / C); auto equal to mlr on dZ; the coolant's drift unseen (a sensor
no other predicts); the healthy table / trunnion pair excluded on 8342 (dY +20.8 % adaptive with
its own mlr); the pivot's planted A effects under diagnose's bar.
"""
from __future__ import annotations

import sys
from datetime import timedelta
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402
from _faults import fault_folders, four_faults  # noqa: E402
from bench_stranger75 import matrix  # noqa: E402

LOOSE_RUN, LOOSE_SIGNAL, LOOSE_ROW = 5, "MOTOR", 700
SPLIT_RUN, SPLIT_ROW, SPLIT_GAP = 9, 1000, 30
PROBED = ("DX_TCP", "DY_TCP", "DZ_TCP")


def channels() -> list[tuple[str, str, str, str]]:
    """``(channel, tag, unit, the simulation's key or sensor)`` in channel order."""
    import trunnion82b as m
    out = [(f"{i:04d}", name, "C", name) for i, (name, _, _) in enumerate(m.SENSORS, start=1)]
    out += [("C001", "X_POS", "mm", "x"), ("C002", "Y_POS", "mm", "y"),
            ("C003", "A_POS", "deg", "a"), ("C004", "C_POS", "deg", "c")]
    return out + [(f"C{5 + i:03d}", tag, "um", f"E_d{ax}")
                  for i, (tag, ax) in enumerate(zip(PROBED, "XYZ"))]


def runs(seed: int):
    """The record: ``(trunnion82b result, [(run label, local start, rows)])``."""
    import trunnion82b as m
    r = m.simulate(int(seed))
    out = []
    for n, (start, rows) in enumerate(m.run_windows(), start=1):
        idx = np.arange(rows.start, rows.stop)
        if n == SPLIT_RUN:
            out.append((f"{n:02d}a", start, idx[:SPLIT_ROW]))
            out.append((f"{n:02d}b", start + timedelta(seconds=(SPLIT_ROW + SPLIT_GAP) * m.STEP_S),
                        idx[SPLIT_ROW + SPLIT_GAP:]))
        else:
            out.append((f"{n:02d}", start, idx))
    return r, out


def _column(r, key, idx):
    import trunnion82b as m
    names = [s[0] for s in m.SENSORS]
    v = r["sensors"][idx, names.index(key)] if key in names else r[key][idx].copy()
    if key.startswith("E_"):           # measured at the probing cycles only (every 15 min of the day)
        v = np.where(idx % m.PROBE_EVERY == 0, v, np.nan)
    return v


def _value(v: float, unit: str) -> str:
    if np.isnan(v):
        return "Burnout" if unit == "C" else ""
    return f"{v:.1f}" if unit in ("C", "mm", "deg") else f"{v:.2f}"


def write_file(path: Path, r, label: str, start, idx, fault=None) -> None:
    """One run's ASCII export (module docstring); ``fault(name, values)`` alters a temperature."""
    import trunnion82b as m
    chans = channels()
    cols = []
    for _, tag, _, key in chans:
        v = np.asarray(_column(r, key, idx), dtype=float)
        if label == f"{LOOSE_RUN:02d}" and tag == LOOSE_SIGNAL:
            v = v.copy()
            v[LOOSE_ROW:LOOSE_ROW + 4] = np.nan
        cols.append(fault(key, v) if fault is not None else v)
    q = '"{}"'.format
    row = lambda key, cells: ",".join([q(key), *(q(c) for c in cells)])  # noqa: E731
    lines = [row("Universal Viewer", ["R4.04.01"]), row("Model", ["GX20"]),
             row("Serial No.", ["S5T800123"]), row("File Name", [f"{path.stem}.GDS"]),
             row("Data Type", ["Display Data"]), row("File Message", [""]),
             row("Batch Name", [f"WAERMEGANG DMU LAUF {label}"]),
             row("Start Time", [f"{start:%Y/%m/%d %H:%M:%S}"]),
             row("Sampling Interval", [f"{m.STEP_S:.0f}s"]), "",
             row("Channel", [c for c, _, _, _ in chans]), row("Tag", [t for _, t, _, _ in chans]),
             row("Tag Comment", ["" for _ in chans]), row("Unit", [u for _, _, u, _ in chans]), "",
             row("Date Time", [c for c, _, _, _ in chans])]
    for k in range(idx.size):
        when = start + timedelta(seconds=k * m.STEP_S)
        cells = [f"{when:%Y/%m/%d %H:%M:%S}.0"]
        cells += [_value(c[k], u) for c, (_, _, u, _) in zip(cols, chans)]
        lines.append(",".join(cells))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\r\n".join(lines) + "\r\n", encoding="ascii")


def _write_all(folder: Path, r, runs_, fault=None) -> None:
    for n, (label, start, idx) in enumerate(runs_):
        write_file(folder / f"GX20_{start:%y%m%d_%H%M%S}.csv", r, label, start, idx,
                   fault if n == len(runs_) - 1 else None)


def write(root: str, seed: str) -> None:
    """The lab's files of seed ``seed``: ``ROOT/trunnion<SEED>/``."""
    r, runs_ = runs(int(seed))
    folder = Path(root) / f"trunnion{seed}"
    _write_all(folder, r, runs_)
    print(f"wrote {folder} ({len(runs_)} files, {sum(i.size for _, _, i in runs_)} rows)")


def faults(root: str, seed: str) -> None:
    """``ROOT/fault_<kind>_<SEED>/``: the files, the last run with one fault (docstring)."""
    import trunnion82b as m
    r, runs_ = runs(int(seed))
    cases = four_faults(runs_[-1][2].size, m.STEP_S, frozen=("PINOLE", 900),
                        jump=("STAENDER_H", 1000), drift=("KUEHLUNG", 700),
                        dropout=("MUTTER_X", 1200, 1290))
    fault_folders(root, seed, cases, lambda folder, fault: _write_all(folder, r, runs_, fault))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "faults": faults, "matrix": matrix}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
