"""A stranger's pass on a gear profile grinder and a lab's LabVIEW Measurement Files nobody tuned on
(stranger69).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger69.py write ROOT

The machine is ``benchmarks/gpg69.py`` (a gear profile grinding machine: a heavy rotary table on
a polymer-concrete bed, a column with the wheelhead, the grinding oil held at a logged set point
by a chiller; planted: the table's radial growth at the head's logged radius, ``S_X_mm`` x the
table's rise, on E_X), simulated by ``thermocomp simulate`` with
``benchmarks/conf69/sim/gpg69.yaml``; its physics and the lab's export below were committed before
any model ran on them (seeds 6901 and 6902 fixed beforehand).

The lab's files (``write``)
---------------------------
The lab logs with a LabVIEW VI whose "Write To Measurement File" Express VI writes ONE ``.lvm``
PER RUN (``ZP1200_Lauf_01.lvm`` ...), the text form NI calls a LabVIEW Measurement File: a
file header (``LabVIEW Measurement``, ``Writer_Version 2``, ``Reader_Version 2``, ``Separator
Tab``, ``Decimal_Separator``, ``Multi_Headings``, ``X_Columns``, ``Time_Pref``, ``Operator``,
``Description``, ``Date`` ``yyyy/mm/dd``, ``Time`` ``hh:mm:ss`` with a 10-digit fraction after
the decimal separator) ending in ``***End_of_Header***``, an empty line, then segments: each a
segment header (``Channels``, ``Samples``, ``Date``, ``Time``, ``Y_Unit_Label``,
``X_Dimension``, ``X0``, ``Delta_X``, one cell per channel, a trailing TAB) ending in
``***End_of_Header***``, the names line (``X_Value`` where there is an X column, the channel
names, ``Comment``), then the rows (no cell under ``Comment``).  A German Windows LabVIEW:
the file in Windows-1252 (``Ständer``, ``Schleiföl``, ``Sollwert Ölkühler``), the lab's own
channel names: ``Luft``, ``Bett``, ``Ständer``, ``Schleifkopf``, ``Schleifspindel``,
``Rundtisch``, ``Schleiföl`` (``Deg C``), ``dX``, ``dY``, ``dZ`` (``um``), ``Drehzahl
Scheibe`` (``1/min``), ``X-Achse`` (``mm``), ``Sollwert Ölkühler`` (``Deg C``).

``gpg_a`` (seed 6901, eight 24 h runs): ``Decimal_Separator ,`` (decimal commas everywhere: the
values, ``X0``, ``Delta_X``, the ``Time`` fraction ``06:00:00,0000000000``), ``X_Columns One``
(an ``X_Value`` column, seconds from the run's start: ``Time_Pref Relative``),
``Multi_Headings No``, ONE segment holding the run's 1440 rows.

``gpg_b`` (seed 6902, the same machine three weeks later): ``Decimal_Separator .``,
``X_Columns No`` (no X column: the time only in the segment headers, ``Delta_X 60``),
``Time_Pref Absolute`` (``X0`` seconds since 1904-01-01 UTC), ``Multi_Headings Yes``, the VI
writing a SEGMENT PER HOUR (60 rows, each under its own segment header with its ``Date``,
``Time``, ``X0`` and names line).

What is measured (written before anything ran)
----------------------------------------------
* ``init`` of each record's folder as a stranger types it (the folder, then
  ``data.test_fraction`` to hold the last run out, then what each message says): tries counted,
  how many runs are read, each header's role, the start and the period read.
* ``matrix`` (lab_matrix): every family + auto, ``run`` -> ``replay`` -> ``promote`` -> C
  ``export`` with its check pack: test RMSE per target; replay = run (<= 1e-9).
* ``diagnose`` (mlr): FOUND when an accepted effect on E_X names the X axis' column.
* ``monitor`` (mlr): the healthy test run quiet (0 sensor events), then +3 K on ``Schleifkopf``
  from row 600 of the held-out run (10 h in, the shift's afternoon).
* CPU (user + sys) of every command (in process, ``RUSAGE_SELF`` + children).

No rule is adopted from these records: they are a check, not a tuning set.

Measured (2026-12-01, every step once, 2 shared cores, other sessions' load; docs/own-data.md)
----------------------------------------------------------------------------------------------
``init gpg_a`` at 51165c81: the folder "manifest not found (a dataset folder needs
campaigns.csv)"; one file "a record's file is .csv, ... .mat, not .lvm"; renamed ``.txt``, "no
column reads as a measured error ... the numeric columns: none".  Mended (68bca30b, 15c2029e,
c290fdf6): ``.lvm`` read as its channels (core/io/lvm.py), ``cp1252`` detected, the set point a
state, ``X-Achse [mm]`` (350 mm) a state by its span; one try each (5.0 / 4.9 s CPU).
``matrix`` (test RMSE dX / dY / dZ µm; before 11.94 / 3.16 / 12.18 and 12.16 / 3.24 / 11.89):
6901 mlr 4.04 / 0.31 / 0.31, hammerstein 1.98 / 0.40 / 0.26, auto 1.98 / 0.34 / 0.28; 6902 mlr
4.38 / 0.23 / 0.31, hammerstein 2.68 / 0.21 / 0.57, auto 2.68 / 0.22 / 0.30.  Every cell: replay =
run (<= 1.3e-15), |stream - batch| <= 2.8e-14, promote = run, C pack passed.  ``diagnose`` mlr:
NOT FOUND at the defaults (the planted S_X-Achse x T_Rundtisch rise ranked first, CV gain 89 %,
but 5 / 3 forward test blocks: min p 0.031 / 0.12); FOUND with ``diagnose.cv=campaigns`` (dX
4.04 -> 0.38, 4.38 -> 0.68; 9.5 / 9.9 s CPU).  ``monitor`` mlr: healthy 0 events; +3 K on
``Schleifkopf`` at 10 h excluded at once.

    ... bench_stranger69.py init ROOT gpg_a [override ...]   # init as a stranger, one try
    ... bench_stranger69.py matrix ROOT gpg_a                # run -> replay -> promote -> C
    ... bench_stranger69.py table ROOT gpg_a
    ... bench_stranger69.py monitor ROOT gpg_a mlr Schleifkopf
    ... bench_stranger69.py diagnose ROOT gpg_a mlr
"""

from __future__ import annotations

import json
import sys
from datetime import datetime, timedelta, timezone
from pathlib import Path

import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]
SEEDS = {"gpg_a": 6901, "gpg_b": 6902}
ENCODING = "cp1252"                         # a German Windows LabVIEW's
# contract name -> (the lab's channel name, LabVIEW's unit label)
CHANNELS = {
    "T_amb": ("Luft", "Deg C"), "T_bed": ("Bett", "Deg C"), "T_column": ("Ständer", "Deg C"),
    "T_wheelhead": ("Schleifkopf", "Deg C"), "T_spindle": ("Schleifspindel", "Deg C"),
    "T_table": ("Rundtisch", "Deg C"), "T_oil": ("Schleiföl", "Deg C"),
    "E_X": ("dX", "um"), "E_Y": ("dY", "um"), "E_Z": ("dZ", "um"),
    "S_n_wheel_rpm": ("Drehzahl Scheibe", "1/min"), "S_X_mm": ("X-Achse", "mm"),
    "S_oil_set_C": ("Sollwert Ölkühler", "Deg C"),
}
# how each record's VI is set
SETTINGS = {
    "gpg_a": {"decimal": ",", "x_column": True, "time_pref": "Relative", "segment_rows": None},
    "gpg_b": {"decimal": ".", "x_column": False, "time_pref": "Absolute", "segment_rows": 60},
}
EPOCH_1904 = datetime(1904, 1, 1, tzinfo=timezone.utc)
UTC_OFFSET_H = 2.0                          # the lab's clock in September: CEST


def simulate(seed: int, path: Path) -> None:
    """``thermocomp simulate`` of the grinder (the documented own-machine route)."""
    lab_matrix.simulate_scenario("gpg69", "conf69", seed, path,
                                 *(["sim.generator.weeks_later=3"] if seed == 6902 else []))


def number(value: float, decimal: str, digits: int = 6) -> str:
    return f"{value:.{digits}f}".replace(".", decimal)


def clock(stamp: datetime, decimal: str) -> tuple[str, str]:
    """LabVIEW's ``Date`` and ``Time`` cells: ``2027/09/06``, ``06:00:00,0000000000``."""
    fraction = f"{stamp.microsecond:06d}0000"
    return stamp.strftime("%Y/%m/%d"), f"{stamp:%H:%M:%S}{decimal}{fraction}"


def lvm_text(frame: pd.DataFrame, start: datetime, run: int, settings: dict) -> str:
    """One run as the Express VI writes it (lines joined by CRLF, as on Windows)."""
    dec, with_x = settings["decimal"], settings["x_column"]
    date, time = clock(start, dec)
    lines = ["LabVIEW Measurement\t", "Writer_Version\t2", "Reader_Version\t2", "Separator\tTab",
             f"Decimal_Separator\t{dec}",
             f"Multi_Headings\t{'Yes' if settings['segment_rows'] else 'No'}",
             f"X_Columns\t{'One' if with_x else 'No'}", f"Time_Pref\t{settings['time_pref']}",
             "Operator\tM. Brandt", f"Description\tZP 1200 Wärmegang, Lauf {run}",
             f"Date\t{date}", f"Time\t{time}", "***End_of_Header***\t", ""]
    names = [name for name, _ in CHANNELS.values()]
    units = [unit for _, unit in CHANNELS.values()]
    n = len(frame)
    step = float(frame["time"].iloc[1] - frame["time"].iloc[0])
    rows = settings["segment_rows"] or n
    for first in range(0, n, rows):
        part = frame.iloc[first:first + rows]
        seconds = float(part["time"].iloc[0])
        at = start + timedelta(seconds=seconds)
        d, t = clock(at, dec)
        x0 = seconds if settings["time_pref"] == "Relative" else (
            at - timedelta(hours=UTC_OFFSET_H)).replace(tzinfo=timezone.utc).timestamp() - \
            EPOCH_1904.timestamp()
        k = len(names)

        def per_channel(cell: str) -> str:
            return "\t".join([cell] * k) + "\t"
        lines += [f"Channels\t{k}\t", f"Samples\t{per_channel(str(len(part)))}",
                  f"Date\t{per_channel(d)}", f"Time\t{per_channel(t)}",
                  "Y_Unit_Label\t" + "\t".join(units) + "\t",
                  f"X_Dimension\t{per_channel('Time')}",
                  f"X0\t{per_channel(f'{x0:.16E}'.replace('.', dec))}",
                  f"Delta_X\t{per_channel(number(step, dec))}", "***End_of_Header***\t",
                  "\t".join((["X_Value"] if with_x else []) + names + ["Comment"])]
        for row in part.itertuples(index=False):
            cells = [number(getattr(row, c), dec) for c in CHANNELS]
            if with_x:
                cells.insert(0, number(row.time, dec))
            lines.append("\t".join(cells))
        if settings["segment_rows"] and first + rows < n:
            lines.append("")
    return "\r\n".join(lines) + "\r\n"


def write_run(folder: Path, k: int, frame: pd.DataFrame, start: datetime, settings: dict) -> Path:
    path = folder / f"ZP1200_Lauf_{k + 1:02d}.lvm"
    path.write_bytes(lvm_text(frame, start, k + 1, settings).encode(ENCODING))
    return path


def write(root: Path) -> None:
    for name, sim, folder in lab_matrix.simulated(root, SEEDS, simulate):
        manifest = pd.read_csv(sim / "campaigns.csv")
        for k, row in enumerate(manifest.itertuples(index=False)):
            write_run(folder, k, pd.read_csv(sim / row.file),
                      pd.Timestamp(row.start).to_pydatetime(), SETTINGS[name])


import lab_matrix  # noqa: E402  (the benches' shared matrix and steps)
from lab_matrix import project, stage  # noqa: E402

FAMILIES = lab_matrix.matrix_families()
WRAPPERS = ("plain",)


def initialised(root: Path, name: str, extra: list[str]) -> None:
    """``thermocomp init`` of the record ``name``'s folder with ``extra`` (one try, as a stranger
    types it)."""
    project(root)
    rc, said, cpu = stage("init", str(root / name), *extra, f"out={root / f'init-{name}'}")
    print(json.dumps({"init": name, "extra": extra, "rc": rc, "said": said[:600],
                      "cpu": round(cpu, 2)}), flush=True)


def planted(src: Path, dst: Path, header: str, kind: str) -> float:
    """``dst``: the record ``src`` with the lab's channel ``header`` of its held-out (last) run
    jumped by +3 K from data row 600 on, written as the VI writes it; the onset (s)."""
    import shutil

    name = src.name
    shutil.copytree(src, dst, dirs_exist_ok=True)
    sim = src.parent / "sim" / name
    manifest = pd.read_csv(sim / "campaigns.csv")
    k, row = len(manifest) - 1, manifest.iloc[-1]
    frame = pd.read_csv(sim / row["file"])
    column = next(c for c, (h, _) in CHANNELS.items() if h == header)
    frame.loc[600:, column] += 3.0
    write_run(dst, k, frame, pd.Timestamp(row["start"]).to_pydatetime(), SETTINGS[name])
    return float(frame["time"].iloc[600])


def main(argv: list[str]) -> int:
    return lab_matrix.main(__doc__, argv, SEEDS, FAMILIES, WRAPPERS, {
        "write": lambda root, rest: write(root),
        # init ROOT name [override ...]
        "init": lambda root, rest: initialised(root, rest[0], rest[1:]),
        # monitor ROOT name family channel...
        "monitor": lambda root, rest: lab_matrix.monitoring(root, rest[0], rest[1], rest[2:],
                                                            planted),
    })


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
