"""A stranger's pass on a double-column (bridge) milling machine logged by a Keysight 34970A /
DAQ970A (BenchLink Data Logger CSV) and its NC's probe log (stranger83).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger83.py write ROOT SEED [LOCALE]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger83.py faults ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger83.py matrix ROOT SEED CONF

The machine is ``benchmarks/bridge83.py`` (a double-column machining centre, its own lumped
network and kinematics: the table on the bed in X, a crossrail on two columns heated unequally
(the hydraulic unit against the right one, the left one by the hall's gate in the afternoon
sun), the saddle in Y, the ram in Z with a motor spindle; a hall without air conditioning; 12
day runs of 10 h from 06:00 on 12 of 19 days from Monday 2027-09-13, the shop using the machine
unlogged on other weekdays; 13 thermocouples; the TCP's dX / dY / dZ measured by the NC's
probing cycle on one of three spheres (Y = -1200, 0, +1200 mm in turn) every 15 min, nothing in
between; planted position effects Y x (right - left column) rise (dZ: the crossrail's tilt) and
Y x the crossrail's rise (dY); seeds 8556-8570 only).

``write``: a run is two files of ``ROOT/bridge<SEED>/`` (a pair: one stem, a word each):

* ``MCR_L<NN>_daq.csv``, the temperatures as BenchLink Data Logger 3 exports a 34970A's scan
  (``LOCALE`` ``us``, the default) or a DAQ970A's on a German PC (``de``): a header block of
  ``key,value`` lines (``Name``, ``Owner``, ``Comments``, ``Acquisition Date``, ``Instrument``,
  ``Total Sweeps``, ``Total Channels``), an empty line, then ``Scan,Time,101 <AIR> (C),Alarm
  101,...`` (channels 101-113 type-T thermocouples, 201 the spindle's speed from the NC's
  analogue output scaled by Mx+B, ``(RPM)``), every line ending in the separator; one scan a
  minute; ``Time`` in the PC's short date, then the time, the ms after a colon
  (``us``: ``9/13/2027 6:00:00:013``, no leading zeros; ``de``: ``13.09.2027 06:00:00:013``);
  the readings as the instrument returns them, ``+2.13450000E+01`` (``de``: ``;`` between cells,
  ``+2,13450000E+01``); an open thermocouple reads ``+9.90000000E+37`` (the 34970A's overload);
  an alarm cell 0, 1 (below LO) or 2 (above HI): HI set on ``SPINDLE`` (40 °C) and ``MOTOR``
  (60 °C).
* ``MCR_L<NN>_probe.csv``, the NC's probing macro's log (written by the control, whatever the
  PC's locale): a title line, then ``DATE,TIME,SPHERE,Y [mm],dX [mm],dY [mm],dZ [mm]``, a row a
  cycle (``09/13/2027,06:00:41,1,-1200.000,-0.0077,0.0021,-0.0153``: month first, the cycle's
  touch 41 s after the DAQ's scan).

Quirks: ``SADDLE``'s thermocouple open for 3 scans in run 5 (``+9.90000000E+37``).  The layout
is written from memory of BenchLink Data Logger 3's CSV export and the 34970A's reading format,
NOT checked against a file a real unit wrote.

``faults``: ``ROOT/fault_<kind>_<SEED>/``, the files (``us``), the last run with one fault:
``frozen`` (``RAM`` held from row 300, 5 h in), ``jump`` (+2 K on ``COL_R`` from row 330),
``drift`` (``HYD_OIL`` +1 K/h from row 240), ``dropout`` (90 scans of ``SADDLE`` open,
``+9.90000000E+37``, from row 400).

``matrix``: bench_stranger75's (run -> replay per family on the data config init wrote).
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

OPEN_RUN, OPEN_SIGNAL, OPEN_ROW = 5, "SADDLE", 250
HI_LIMITS = {"SPINDLE": 40.0, "MOTOR": 60.0}
OVERLOAD = 9.9e37
PROBE_LAG_S = 41
LOCALES = {
    "us": {"sep": ",", "decimal": ".", "instrument": "34970A (Serial Number: MY44054321) at "
           "GPIB0::9::INSTR", "stamp": lambda at: f"{at.month}/{at.day}/{at.year} "
           f"{at.hour}:{at:%M:%S}"},
    "de": {"sep": ";", "decimal": ",", "instrument": "DAQ970A (Serial Number: MY58012345) at "
           "USB0::0x2A8D::0x5101::MY58012345::0::INSTR", "stamp": lambda at: f"{at:%d.%m.%Y %H:%M:%S}"},
}


def runs(seed: int):
    """The record: ``(bridge83 result, [(run label, local start, rows)])``."""
    import bridge83 as m
    r = m.simulate(int(seed))
    return r, [(f"{n:02d}", start, np.arange(rows.start, rows.stop))
               for n, (start, rows) in enumerate(m.run_windows(), start=1)]


def _temperatures(r, label: str, idx: np.ndarray, fault=None) -> dict[str, np.ndarray]:
    import bridge83 as m
    out = {}
    for j, (name, _, _) in enumerate(m.SENSORS):
        v = r["sensors"][idx, j].copy()
        if label == f"{OPEN_RUN:02d}" and name == OPEN_SIGNAL:
            v[OPEN_ROW:OPEN_ROW + 3] = np.nan
        out[name] = fault(name, v) if fault is not None else v
    return out


def daq_text(r, label: str, start, idx: np.ndarray, locale: str, fault=None) -> str:
    """One run's BenchLink Data Logger CSV export (module docstring), CRLF as on Windows."""
    import bridge83 as m
    cfg = LOCALES[locale]
    sep, stamp = cfg["sep"], cfg["stamp"]
    temps = _temperatures(r, label, idx, fault)
    channels = [(101 + j, name, "C", temps[name]) for j, name in enumerate(temps)]
    channels.append((201, "SPINDLE_RPM", "RPM", r["speed"][idx]))

    def reading(v: float) -> str:
        return f"{OVERLOAD if np.isnan(v) else v:+.8E}".replace(".", cfg["decimal"])

    head = [f"Name{sep}MCR thermal run {label}", f"Owner{sep}Metrology lab",
            f"Comments{sep}Double column mill MCR-B2 - probe cycle every 15 min",
            f"Acquisition Date{sep}{stamp(start)}", f"Instrument{sep}{cfg['instrument']}",
            f"Total Sweeps{sep}{idx.size}", f"Total Channels{sep}{len(channels)}", ""]
    names = ["Scan", "Time"]
    for ch, name, unit, _ in channels:
        names += [f"{ch} <{name}> ({unit})", f"Alarm {ch}"]
    lines = head + [sep.join(names) + sep]
    jitter = np.random.default_rng([8556, int(label)]).integers(0, 30, idx.size)
    for k in range(idx.size):
        at = start + timedelta(seconds=k * m.STEP_S, milliseconds=int(jitter[k]))
        cells = [str(k + 1), f"{stamp(at)}:{at.microsecond // 1000:03d}"]
        for _, name, _, v in channels:
            alarm = 2 if np.isfinite(v[k]) and v[k] > HI_LIMITS.get(name, np.inf) else 0
            cells += [reading(float(v[k])), str(alarm)]
        lines.append(sep.join(cells) + sep)
    return "\r\n".join(lines) + "\r\n"


def probe_text(r, start, idx: np.ndarray) -> str:
    """One run's probe log (module docstring): a row a probing cycle."""
    import bridge83 as m
    lines = ["BRIDGE MILL MCR-B2 PROBE LOG - SPHERE CYCLE",
             "DATE,TIME,SPHERE,Y [mm],dX [mm],dY [mm],dZ [mm]"]
    for k in range(0, idx.size, m.PROBE_EVERY):
        at = start + timedelta(seconds=k * m.STEP_S + PROBE_LAG_S)
        y = float(r["y"][idx[k]])
        lines.append(",".join([f"{at:%m/%d/%Y}", f"{at:%H:%M:%S}",
                               str(m.SPHERES_Y.index(y) + 1), f"{y:.3f}",
                               *(f"{r[e][idx[k]] / 1e3:.4f}" for e in ("E_dX", "E_dY", "E_dZ"))]))
    return "\r\n".join(lines) + "\r\n"


def _write_all(folder: Path, r, runs_, locale: str = "us", fault=None) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    for n, (label, start, idx) in enumerate(runs_):
        last = fault if n == len(runs_) - 1 else None
        (folder / f"MCR_L{label}_daq.csv").write_bytes(
            daq_text(r, label, start, idx, locale, last).encode("ascii"))
        (folder / f"MCR_L{label}_probe.csv").write_bytes(probe_text(r, start, idx).encode("ascii"))


def write(root: str, seed: str, locale: str = "us") -> None:
    """The lab's files of seed ``seed``: ``ROOT/bridge<SEED>/``."""
    r, runs_ = runs(int(seed))
    folder = Path(root) / f"bridge{seed}"
    _write_all(folder, r, runs_, locale)
    print(f"wrote {folder} ({2 * len(runs_)} files, {sum(i.size for _, _, i in runs_)} scans)")


def faults(root: str, seed: str) -> None:
    """``ROOT/fault_<kind>_<SEED>/``: the files, the last run with one fault (docstring)."""
    import bridge83 as m
    r, runs_ = runs(int(seed))
    cases = four_faults(runs_[-1][2].size, m.STEP_S, frozen=("RAM", 300), jump=("COL_R", 330),
                        drift=("HYD_OIL", 240), dropout=("SADDLE", 400, 490))
    fault_folders(root, seed, cases,
                  lambda folder, fault: _write_all(folder, r, runs_, "us", fault))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "faults": faults, "matrix": matrix}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
