"""A stranger's pass on a wire EDM and its SINUMERIK trace XML files (stranger81).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger81.py write ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger81.py faults ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger81.py matrix ROOT SEED CONF

The machine is ``benchmarks/edm81.py`` (a wire EDM, its own lumped network and kinematics: a
base on a foundation, a Y saddle and an X table on ball screws heated by their nuts, the work
tank's de-ionised water exchanged with a reservoir held at 20.0 °C by an on/off chiller
(+-0.3 K), the lower arm in the water, the upper arm and Z head on a C-frame column, the
generator cabinet; a shop without air conditioning (18-23 °C over the day, the weather's
drift); unattended cutting: 12 runs of 22 h from 07:00 on 12 of 19 days from Monday 2027-05-10,
the shop using the machine unlogged on other weekdays; 17 sensors, the wire's dX / dY against a
reference pin; planted position effects X x the X screw's rise (dX), Y x the Y screw's rise and
Z x the arms' tilt (dY); seeds 8111-8130 only).

``write``: the runs as the lab's NC saves a SINUMERIK Operate trace, one XML file a run
``ROOT/edm<SEED>/KT_<yyyymmdd>_<HHMM>_Lauf<NN>.xml``: ``traceCaptureFile`` / ``traceData`` /
``dataFrame`` (``startTime``: the NC's local clock, no zone; ``samplingTime`` 10 s), its
``frameHeader``'s ``dataSignal`` s (``id``, ``name``, ``type``, ``unit``) and a ``rec`` row a
sample (``time`` s since the start, ``f<id>`` each value): the temperatures, the wire's errors
(``um``), the generator's power (``kW``) and the flushing pressure (``bar``) the lab's user data
``/NC/_N_NC_GD9_ACX/<NAME>`` (the PLC writes them), the axes ``/Channel/MachineAxis/aaIm[u1,1..3]``
(``mm``), the chiller's contactor a PLC input ``/Plc/I7.3`` (BOOL 0/1).  Quirks: 6 values of
``T_MUTTER_X`` not delivered in run 4 (no ``f17`` attribute in 6 rows), the trace restarted in
run 8 (``Lauf08a`` / ``Lauf08b``, 10 min apart).  The structure is the trace files' as described
in Siemens' documentation and users' posts; no file SINUMERIK wrote was at hand to check it.

``faults``: ``ROOT/fault_<kind>_<SEED>/``, the files, the last run with one fault: ``frozen``
(``T_OBERARM`` held from row 3600, 10 h in), ``jump`` (+2 K on ``T_STAENDER_H`` from row 4000),
``drift`` (``T_VORRAT``, the chiller's reservoir, +1 K/h from row 3000), ``dropout`` (90 NaN of
``T_MUTTER_X`` from row 4500).

``matrix``: bench_stranger75's (run -> replay per family on the data config init wrote).

Measured 2026-12-04, seed 8111 (``write`` 5.1 s CPU, 13 files of 2.85 MB; ``init`` 30.0 + 0.7 s
CPU).  Before stranger81 ``thermocomp init ROOT/edm8111`` refused the folder: "manifest not
found ...; its files, .xml (13), are no kind read as a run".  Now (``core/io/sinumerik.py``, the
standard library's ``xml.etree.iterparse``: no extra dependency, 0.10 s CPU a file) ``init``
alone (no key) wrote the wire's ``DX_DRAHT`` / ``DY_DRAHT`` as errors, the three axes
(``aaIm_u1_1..3``: the index in brackets no unit), ``GEN_LEISTUNG``, ``SPUELDRUCK`` and ``I7.3``
(an on/off flag) as states, ``max_gap_samples: 6`` (the values not delivered), the last run held
out (13 campaigns, run 8's two files two), and, after the second mend below, ``T_HALLE`` as the
ambient (it was ``ambient: []``: the hall's air kept a machine temperature, ``T_HALLE``, by its
contract-like ``T_`` prefix).  ``T_BODEN`` (the floor) stays a temperature, as ``NOT_THE_HALLS``
says.  The fresh draw 8112 read by ``init`` with no key: the same roles and keys.

``matrix`` on its config (388 + 26 s CPU, 8.6 min wall on 2 cores shared by four jobs): test
RMSE dX / dY (µm; uncompensated 4.45 / 2.87 on the last run, Thu 27 May) mlr 2.065 / 2.404, pcr
1.999 / 3.930, arx 1.887 / 2.915, lagbank 2.128 / 3.675, hammerstein 2.128 / 4.510, lstm 2.104
/ 2.428, auto 2.065 / 2.580 (its validation chose mlr on dX, mlr 0.60 + arx 0.40 on dY), mlr
``ati=cmeans`` 2.352 / 2.000; replay = run = batch in every cell (to the printed digit).
Issue 34's acceptance on this record: auto within 10 % of the best single family on both
(dX +9.4 % of arx's, dY +7.3 % of mlr's) but worse than mlr on dY (2.580 > 2.404): the
validation's choice, not scored here as a defect.

``diagnose`` (MLR, defaults, ``plots=none``; 43.6 + 8.5 s CPU, 77 s wall): the Z x arms' tilt
position effect found on dY (``S_aaIm_u1_3`` x ``T_OBERARM``); the X / Y screws' effects not
accepted (dX's ``S_aaIm_u1_1`` x rises the top candidate, CV gain 19.2 %, p 0.036, family p
0.045 > alpha 0.01 with 12 CV units).  Two healthy sensors excluded as faults:
``T_VORRAT`` (the chiller's reservoir: its on/off cycle no neighbour predicts, self-prediction
jump 3.81, removal's CV gain 3.8 %, p 0.096) and then ``T_UNTERARM`` (the lower arm in the
water: its jump 1.90 with ``T_VORRAT`` in, 3.58 once it was out, a cascade; CV gain 0.2 %, p 0.39): test
RMSE dX / dY 2.07 / 2.40 -> 2.24 / 1.74 µm (dX 8 % WORSE: issue 34's "never more than 2 %
worse" broken by the fault bar, stranger74 / stranger80's known case, diag75 / diag76 refused
rules).  Without the sensor_fault family (``diagnose.families=[signal,dynamics,ambient_interval,
interaction,nonlinear]``; 48.6 + 8.6 s CPU): dX none accepted (2.07 -> 2.07), dY the same
interaction (2.40 -> 1.85; CV 2.34 -> 1.74).  Which removal costs dX (``run model=mlr`` with
``data.roles.ignore``, 17 s CPU each; test dX / dY µm): ``[T_VORRAT]`` 2.05 / 2.37 (no harm),
``[T_UNTERARM]`` 2.23 / 2.16, both 2.24 / 2.17: the cascade's second removal is the harm (a rule
to weigh: a sensor's jump judged with every declared sensor in).  Mended by that rule
(``bench_cascade81``, KEPT): ``T_VORRAT`` alone excluded, test dX / dY 2.065 / 2.404 -> 2.045 /
1.831 µm (the Z x tilt effect on dY as before).

``monitor`` (``monitor.model`` the matrix's mlr, ``plots=none``; 14-17 s CPU each) on the healthy
last run: no event (fixed = adaptive = run's 2.065 / 2.404); on fresh draws 8112 / 8113 (``data.path``
only): no event (1.709 / 2.285 and 5.330 / 2.495 µm, fixed = adaptive).  Faults in the last run
(fixed / adaptive RMSE dX, dY): ``T_STAENDER_H`` +2 K at 11.11 h: excluded at once ("jump: +2 °C
in one sample"), re-admitted re-referenced 100 s on (4.944 / 2.068, 2.711 / 2.407: the adaptive
as healthy); 90 NaN of ``T_MUTTER_X`` at 12.50 h: excluded at once, re-admitted as readings came
back (2.060 / 2.051, 2.410 / 2.407); ``T_OBERARM`` frozen at 10.0 h: excluded at 21.05 h, by its
self-prediction drift (+0.41 °C), not as a freeze (the field moved less than the warning band
for 11 h: the frozen reading stayed near the truth, 2.313 / 2.208, 2.313 / 2.370);
``T_VORRAT`` drifting 1 K/h from 8.33 h: excluded at 18.39 h only, "out of range: 30.33 °C
outside the training range [18.2, 20.3] ± 10 °C" (no other sensor predicts it: only the range
detector judges it, its 10 K margin 10 h of this drift), re-admitted 5.5 min later while still
out of range ("no detector fired for 10 samples"), excluded again (2.171 / 2.071, 2.106 / 2.343).

``promote``: a tracked sweep ``run -m model=mlr,hammerstein,lagbank`` (50.6 + 4.0 s CPU;
validation RMSE 2.38 / 2.95 / 3.38, test 2.23 / 3.32 / 2.90, means over dX / dY), then
``thermocomp promote`` (17.2 + 1.0 s): mlr @champion by its validation.  ``export
export.model=models:/thermocomp-compensator@champion export.format=c export.check=true`` (32.4
+ 0.6 s): compiled with ``gcc -std=c99 -O2 -Wall -Wextra -Werror``, its pack (the test run and
its jump / freeze / dropout / range variants of ``T_FUNDAMENT`` and a common step, 47,520 rows)
passed (largest difference 3.7e-14 µm); ``thermocomp rows`` of the trace folder (the test run,
``rows.errors=true``; 16.5 + 0.6 s CPU) streamed through ``./stream``: the pack's corrections to
6.2e-15 µm, and its test RMSE (error referenced at the run's first sample, plus the
correction) equal to replay's (2.065 / 2.404; difference 0.0).  The champion replayed on the
next draw's files (8112, ``data.path`` only): 1.709 / 2.285 µm, no event, stream - batch <=
7.1e-15 µm (14.1 + 0.6 s CPU).

Mended (each with a test in tests/shell/test_stranger81.py that fails on main), before -> now:
a folder of traces "no kind read as a run" -> read (sinumerik.py); ``T_HALLE`` proposed a
temperature, ``ambient: []`` -> the ambient (detect.py ``_may_be_air``: a ``T_`` name, not the
contract's ``T_amb``, whose words say the air); the trace's settings ``Thermik_setup.xml``
beside the traces crashed ``init`` (pyarrow's "Parquet magic bytes not found" traceback) -> no
run in a folder, refused alone naming its root element; a trace piped into ``monitor
monitor.input=-`` "1 column(s) not read: '<?xml ...' is not numeric" -> "stdin holds a
SINUMERIK trace's XML (its signature) ...: give the file as data.path=<file>"; a session's
two traces in one file (slow temperatures, fast errors) "run 'Trace 2' holds other channels than
run 'Trace 1' ...: one file per run" -> one record's channels, ``data.resample_s`` proposed.
A ``startTime`` ``27-05-10T07:00`` (numpy read the year 27) refused as "column 'time', data row
1: value '0027-05-10...' is not an ISO 8601 timestamp", a column and value the file does not
hold -> "dataFrame 'Trace 1': startTime '27-05-10T07:00:00.000' is no ISO 8601 time"; a
``startTime`` with its offset (``+02:00``) -> that instant in UTC.
Diagnose's health step excluded ``T_UNTERARM`` once ``T_VORRAT`` was out (dX 8 % worse) -> a
fault's jump must clear in the first table too (bench_cascade81, KEPT; test in
tests/shell/test_diagnose.py).
Left: the reservoir's own exclusion (healthy, its jump 3.81: no harm, dX 2.065 -> 2.045); the
range detector's 10 K margin for a sensor no other predicts (a chiller's reservoir held within
0.3 K drifted 10 K before it was excluded; range73 refused, range77 measured) and its
re-admission while out of range (stranger78's open rule); auto worse than mlr on dY by its
validation's blend; the X / Y screws' planted effects under the bar with 12 CV units; a trace's
``startTime`` taken as written (UTC unless ``data.timezone``; this campaign crosses no clock
change).
"""
from __future__ import annotations

import sys
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402
from _faults import fault_folders, four_faults  # noqa: E402
from _runs import restarted_runs  # noqa: E402
from bench_stranger75 import matrix  # noqa: E402

GUD = "/NC/_N_NC_GD9_ACX/"                 # the lab's global user data the PLC writes
MISSING_RUN, MISSING_SIGNAL, MISSING_ROW = 4, "T_MUTTER_X", 2400
SPLIT_RUN, SPLIT_ROW, SPLIT_GAP = 8, 3000, 60     # the trace restarted 8.3 h in, 10 min later


def signals() -> list[tuple[str, str, str]]:
    """``(name in the trace, its unit or '', the simulation's key or sensor)`` in trace order."""
    import edm81 as e
    out = [(GUD + "DX_DRAHT", "um", "E_dX"), (GUD + "DY_DRAHT", "um", "E_dY")]
    out += [(f"/Channel/MachineAxis/aaIm[u1,{i}]", "mm", k) for i, k in ((1, "x"), (2, "y"),
                                                                       (3, "z"))]
    out += [(GUD + "GEN_LEISTUNG", "kW", "power"), (GUD + "SPUELDRUCK", "bar", "flush"),
            ("/Plc/I7.3", "", "chiller")]
    out += [(GUD + name, "°C", name) for name, _, _ in e.SENSORS]
    return out


def channels(seed: int):
    """The record: ``(edm81 result, [(run label, local start, rows)])``."""
    import edm81 as e
    r = e.simulate(int(seed))
    return r, restarted_runs(e.run_windows(), e.STEP_S, SPLIT_RUN, SPLIT_ROW, SPLIT_GAP)


def _column(r, key, idx):
    import edm81 as e
    names = [s[0] for s in e.SENSORS]
    return r["sensors"][idx, names.index(key)] if key in names else r[key][idx]


def write_file(path: Path, r, label: str, start, idx, fault=None) -> None:
    """One run's trace (its XML as SINUMERIK Operate saves a trace, module docstring);
    ``fault(name, values)`` alters a temperature signal."""
    import edm81 as e
    sig = signals()
    cols = []
    for name, _, key in sig:
        v = np.asarray(_column(r, key, idx), dtype=float)
        cols.append(fault(key, v) if fault is not None else v)
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<traceCaptureFile version="1.0">',
             ' <traceCaptureSetup name="Thermik_Drahterodieren" comment="KT Lauf '
             f'{label}">',
             ' </traceCaptureSetup>', ' <traceData>',
             f' <dataFrame name="Trace 1" startTime="{start:%Y-%m-%dT%H:%M:%S}.000" '
             f'samplingTime="{e.STEP_S:.3f}">', '  <frameHeader>']
    for i, (name, unit, _) in enumerate(sig, start=1):
        kind = "BOOL" if name.startswith("/Plc/I") else "DOUBLE"
        lines.append(f'   <dataSignal id="{i}" name={quoteattr(name)} type="{kind}" '
                     f'unit={quoteattr(unit)}/>')
    lines.append('  </frameHeader>')
    miss = MISSING_SIGNAL if label == f"{MISSING_RUN:02d}" else None
    for k in range(idx.size):
        cells = []
        for i, ((name, _, key), v) in enumerate(zip(sig, cols), start=1):
            if (key == miss and MISSING_ROW <= k < MISSING_ROW + 6) or np.isnan(v[k]):
                continue                       # (the PLC's value not delivered: no attribute)
            text = str(int(v[k])) if name.startswith("/Plc/I") else f"{v[k]:.4f}"
            cells.append(f'f{i}="{text}"')
        lines.append(f'  <rec time="{k * e.STEP_S:.3f}" ' + " ".join(cells) + "/>")
    lines += [' </dataFrame>', ' </traceData>', '</traceCaptureFile>', '']
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines), encoding="utf-8")


def _write_all(folder: Path, r, runs, fault=None) -> None:
    for n, (label, start, idx) in enumerate(runs):
        last = n == len(runs) - 1
        write_file(folder / f"KT_{start:%Y%m%d_%H%M}_Lauf{label}.xml", r, label, start, idx,
                   fault if last else None)


def write(root: str, seed: str) -> None:
    """The lab's files of seed ``seed``: ``ROOT/edm<SEED>/``."""
    r, runs = channels(int(seed))
    folder = Path(root) / f"edm{seed}"
    _write_all(folder, r, runs)
    print(f"wrote {folder} ({len(runs)} files, {sum(i.size for _, _, i in runs)} rows)")


def faults(root: str, seed: str) -> None:
    """``ROOT/fault_<kind>_<SEED>/``: the files, the last run with one fault (docstring)."""
    r, runs = channels(int(seed))
    cases = four_faults(runs[-1][2].size, 10.0, frozen=("T_OBERARM", 3600), jump=("T_STAENDER_H", 4000),
                        drift=("T_VORRAT", 3000), dropout=("T_MUTTER_X", 4500, 4590))
    fault_folders(root, seed, cases, lambda folder, fault: _write_all(folder, r, runs, fault))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "faults": faults, "matrix": matrix}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
