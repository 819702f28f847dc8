"""A stranger's pass on a 5-axis trunnion machining centre logged by a Keysight DAQ (keysight70).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_keysight70.py write ROOT

The machine is ``benchmarks/keysight70.py`` (a motor spindle on a moving column, a trunnion
cradle tilting the C table about A; planted: the table's growth along its normal turned by the
logged tilt, ``2.3 sin(A) rise(table)`` on E_Y, ``cos(A)`` on E_Z), simulated by ``thermocomp
simulate`` with ``benchmarks/conf70/sim/keysight70.yaml``; its physics and the lab's export below
were committed before any model ran on them (seeds 7041 and 7042 fixed beforehand).

The lab's files (``write``)
---------------------------
The lab logs with a Keysight 34970A (7041) or DAQ970A (7042) data acquisition unit: a 20-channel
multiplexer in slot 1 with eight type-T thermocouples (channels 101-108, ``(C)``), and in slot 2
the capacitive probes' amplifiers on DC-volt channels 201-203, the CNC's analogue outputs of the
spindle speed (204) and the A axis' position (205), each scaled by the logger's ``Mx+B`` to µm,
rpm and degrees.  One scan a minute, one file per run, exported as CSV by the logger's software.
The shape below is written from memory of BenchLink Data Logger 3's and the DAQ970A's
(BenchVue DAQ) CSV exports, NOT checked against a file from a real unit:

* a header block of ``key,value`` lines before the table: ``Name``, ``Owner``, ``Comments``,
  ``Acquisition Date`` (``03/01/2027 06:00:00``), ``Instrument`` (model, serial number,
  address), ``Total Sweeps``, ``Total Channels``, then an empty line;
* the table's header: ``Scan`` (the sweep number from 1), ``Time``, then per channel
  ``<channel> <label> (<unit>)`` followed by ``Alarm <channel>`` (``101 <Luft> (C)``,
  ``Alarm 101``, ...); a TRAILING separator on every line of the table (an empty last column);
* ``Time`` as ``MM/DD/YYYY HH:MM:SS:mmm``, US month first, the milliseconds after a COLON
  (``03/01/2027 06:01:00:013``: the scan's start jitters by a few ms);
* an ``Alarm`` cell is 0 (no alarm), 1 (below the channel's LO limit) or 2 (above HI): limits
  set on the spindle's thermocouple (HI 30 °C) and on the table's (HI 26 °C), 0 on every other
  channel;
* the Mx+B scaled channels carry the label the lab typed: ``(um)``, ``(RPM)``, ``(DEG)``.

``dmu_a`` (seed 7041, eight 24 h runs from Monday 2027-03-01, every date at most the 17th):
BenchLink Data Logger 3 on an English PC, 34970A; ``,`` between cells, ``.`` decimals; channel
labels ``Air``, ``Bed``, ``Column``, ``Headstock``, ``Spindle``, ``Trunnion``, ``Table``,
``Coolant``, ``DISP_X``, ``DISP_Y``, ``DISP_Z``, ``Spindle speed``, ``A axis``; files
``dmu_run01.csv`` ...

``dmu_b`` (seed 7042, the same machine three weeks later): a DAQ970A exported on a German PC:
``;`` between cells and decimal COMMAS (``21,345``), the same header block and ``Time`` format
(``03/22/2027 06:00:00:000``); the probes' channels left at the default Mx+B label, so
``201 <DISP_X> (VDC)`` holds µm; German labels ``Luft``, ``Bett``, ``Ständer``,
``Spindelkasten``, ``Spindel``, ``Schwenkbrücke``, ``Rundtisch``, ``KSS``, ``Drehzahl``,
``A-Achse``; the file in UTF-8 with a BOM; files ``Lauf_01.csv`` ...

What is measured (written before anything ran)
----------------------------------------------
* ``init`` of each record's folder as a stranger types it: tries counted (each refusal's message
  followed, as a new user would), how many runs are read, each header's role, the start and
  the period read; CPU of a successful ``init``.
* ``matrix`` (lab_matrix) of mlr, lagbank, auto: ``run`` -> ``replay`` -> ``promote`` -> C
  ``export`` with its check pack: test RMSE per target; replay = run.
* ``diagnose`` (mlr): FOUND when an accepted effect on E_Y names the A axis' column.
* ``monitor`` (mlr) on the healthy test run: its events (0 expected).
* CPU (user + sys) of every command (in process, ``RUSAGE_SELF`` + children).

No rule is adopted from these records: they are a check, not a tuning set.

Measured (2026-12-02, every step once, 2 shared cores, other sessions' load; docs/own-data.md)
----------------------------------------------------------------------------------------------
``init dmu_a`` at b20c26c1: "value '03/01/2027 06:00:00:011' is a date with slashes, day or month
first?"; with ``data.time='%m/%d/%Y %H:%M:%S'`` (its hint) and with ``...:%f``: "not a time in
data.time's format": stuck after 3 tries (both records; the colon before the ms read by no
format).  Mended (e5ca9645, then the C): the Keysight Time month first, its ms read; Scan and
the 13 Alarm columns left out (Scan was refused as 201 °C, the alarms read as temperatures);
a role pattern's own unit for the VDC-labelled probes.  After: dmu_a 1 try (2.8-3.6 s CPU), dmu_b
2 (the first names ``data.roles.error=['201 <DISP_X> (um)', ...]``; 2.6-3.7 s).  ``matrix`` (test RMSE
X / Y / Z µm; before 8.28 / 22.84 / 88.77 and 8.09 / 24.21 / 73.62): dmu_a mlr 0.34 / 5.68 /
4.84, lagbank 0.29 / 5.29 / 4.28, auto 0.33 / 1.98 / 1.82; dmu_b mlr 0.23 / 6.43 / 5.27,
lagbank 0.31 / 5.97 / 4.90, auto 0.27 / 2.01 / 1.58; replay = run (<= 8.9e-16), promote = run,
C pack passed (refused at export before: data.time %m/%d/%Y).  ``monitor`` mlr healthy: 0
events on both (file and stdin).  ``diagnose`` mlr: FOUND on both (dmu_a A x T_Table rise, Y
5.68 -> 0.84; dmu_b A x T_KSS rise, Y 6.43 -> 0.87; 16.9 / 18.9 s CPU).
lead71 (2026-12-02, at f37527c1, once): ``init dmu_a`` now names ``101 <Air> (C)`` ambient
(the angle brackets split as word marks); ``matrix dmu_a --families auto``: 0.327 / 1.975 /
1.818, as before; replay = run (5.6e-17), promote = run, C pack passed, 0 events (16.5 s CPU).

    ... bench_keysight70.py init ROOT dmu_a [override ...]   # init as a stranger, one try
    ... bench_keysight70.py matrix ROOT dmu_a                # run -> replay -> promote -> C
    ... bench_keysight70.py table ROOT dmu_a
    ... bench_keysight70.py monitor ROOT dmu_a mlr
    ... bench_keysight70.py diagnose ROOT dmu_a mlr
"""

from __future__ import annotations

import sys
from datetime import datetime, timedelta
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]
SEEDS = {"dmu_a": 7041, "dmu_b": 7042}
# contract name -> (channel, the label per record, the unit label per record)
CHANNELS = {
    "T_amb": (101, ("Air", "Luft"), ("C", "C")),
    "T_bed": (102, ("Bed", "Bett"), ("C", "C")),
    "T_column": (103, ("Column", "Ständer"), ("C", "C")),
    "T_headstock": (104, ("Headstock", "Spindelkasten"), ("C", "C")),
    "T_spindle": (105, ("Spindle", "Spindel"), ("C", "C")),
    "T_trunnion": (106, ("Trunnion", "Schwenkbrücke"), ("C", "C")),
    "T_table": (107, ("Table", "Rundtisch"), ("C", "C")),
    "T_coolant": (108, ("Coolant", "KSS"), ("C", "C")),
    "E_X": (201, ("DISP_X", "DISP_X"), ("um", "VDC")),
    "E_Y": (202, ("DISP_Y", "DISP_Y"), ("um", "VDC")),
    "E_Z": (203, ("DISP_Z", "DISP_Z"), ("um", "VDC")),
    "S_n_spindle_rpm": (204, ("Spindle speed", "Drehzahl"), ("RPM", "RPM")),
    "S_pos_A": (205, ("A axis", "A-Achse"), ("DEG", "DEG")),
}
HI_LIMITS = {"T_spindle": 30.0, "T_table": 26.0}      # the alarms the lab set
SETTINGS = {
    "dmu_a": {"which": 0, "sep": ",", "decimal": ".", "model": "34970A", "bom": False,
              "instrument": "34970A (Serial Number MY41012345) at GPIB0::9::INSTR",
              "file": "dmu_run{k:02d}.csv", "software": "BenchLink Data Logger 3"},
    "dmu_b": {"which": 1, "sep": ";", "decimal": ",", "model": "DAQ970A", "bom": True,
              "instrument": "DAQ970A (Serial Number MY58001234) at USB0::0x2A8D::0x5101::INSTR",
              "file": "Lauf_{k:02d}.csv", "software": "DAQ970A"},
}


def simulate(seed: int, path: Path) -> None:
    """``thermocomp simulate`` of the machining centre (the documented own-machine route)."""
    lab_matrix.simulate_scenario("keysight70", "conf70", seed, path,
                                 *(["sim.generator.weeks_later=3"] if seed == 7042 else []))


def stamp(at: datetime) -> str:
    """Keysight's ``Time``: ``MM/DD/YYYY HH:MM:SS:mmm``."""
    return f"{at:%m/%d/%Y %H:%M:%S}:{at.microsecond // 1000:03d}"


def export_text(frame: pd.DataFrame, start: datetime, run: int, settings: dict, rng) -> str:
    """One run as the logger's software exports it (CRLF, as on Windows)."""
    sep, dec, which = settings["sep"], settings["decimal"], settings["which"]

    def num(v: float, digits: int) -> str:
        return f"{v:.{digits}f}".replace(".", dec)

    head = [f"Name{sep}DMU thermal run {run:02d}", f"Owner{sep}Thermal lab",
            f"Comments{sep}{settings['software']} export, 5-axis trunnion thermal test",
            f"Acquisition Date{sep}{start:%m/%d/%Y %H:%M:%S}",
            f"Instrument{sep}{settings['instrument']}", f"Total Sweeps{sep}{len(frame)}",
            f"Total Channels{sep}{len(CHANNELS)}", ""]
    names = ["Scan", "Time"]
    for channel, labels, units in CHANNELS.values():
        names += [f"{channel} <{labels[which]}> ({units[which]})", f"Alarm {channel}"]
    lines = head + [sep.join(names) + sep]
    jitter_ms = rng.integers(0, 40, len(frame))
    for i, row in enumerate(frame.itertuples(index=False)):
        at = start + timedelta(seconds=float(row.time), milliseconds=int(jitter_ms[i]))
        cells = [str(i + 1), stamp(at)]
        for column in CHANNELS:
            value = float(getattr(row, column))
            digits = 3 if column.startswith(("T_", "E_")) else 1
            alarm = 2 if value > HI_LIMITS.get(column, np.inf) else 0
            cells += [num(value, digits), str(alarm)]
        lines.append(sep.join(cells) + sep)
    return "\r\n".join(lines) + "\r\n"


def write_run(folder: Path, k: int, frame: pd.DataFrame, start: datetime, settings: dict) -> Path:
    path = folder / settings["file"].format(k=k + 1)
    text = export_text(frame, start, k + 1, settings, np.random.default_rng([7070, k]))
    path.write_bytes(("\ufeff" if settings["bom"] else "").encode() + text.encode("utf-8"))
    return path


def write(root: Path) -> None:
    for name, sim, folder in lab_matrix.simulated(root, SEEDS, simulate):
        manifest = pd.read_csv(sim / "campaigns.csv")
        for k, row in enumerate(manifest.itertuples(index=False)):
            write_run(folder, k, pd.read_csv(sim / row.file),
                      pd.Timestamp(row.start).to_pydatetime(), SETTINGS[name])


import lab_matrix  # noqa: E402  (the benches' shared matrix and steps)

FAMILIES = {k: v for k, v in lab_matrix.matrix_families().items()
            if k in ("mlr", "lagbank", "auto")}
WRAPPERS = ("plain",)


def main(argv: list[str]) -> int:
    return lab_matrix.main(__doc__, argv, SEEDS, FAMILIES, WRAPPERS, {
        "write": lambda root, rest: write(root),
        # init ROOT name [override ...]
        "init": lambda root, rest: lab_matrix.initialised(root, rest[0], rest[1:]),
        # monitor ROOT name family: the healthy test run only
        "monitor": lambda root, rest: lab_matrix.monitoring(root, rest[0], rest[1], [], None),
    })


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
