"""Two loggers' records and Keysight exports written with a stranger's variations (pair70).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_pair70.py write ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_pair70.py init ROOT lathe_mm [override ...]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_pair70.py matrix ROOT lathe_mm base_mm
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_pair70.py table ROOT lathe_mm

Each variation is written beside the same seed's record as bench_twolog70 / bench_keysight70
write it (``base_*``), so that a variation read right scores what its base scores.  Seeds
7141-7144, fixed before anything ran:

* ``lathe_mm`` (7141, bench_twolog70's lathe): the probe software writes millimetres,
  ``dX [mm]`` ``0,0123`` (four decimals: the base's 0.1 µm);
* ``lathe_k`` (7142): the DAQ writes kelvin, ``Headstock [K]`` ``293.45``;
* ``lathe_first`` (7143): the probe software started FIRST, 20 min before the DAQ, in every run
  (both files timestamped, the probe PC 7 s ahead as in the base): the probes' first 4 rows have
  no temperature; ``lathe_first_s``: the same files with each logger's time in seconds from its
  own start (``t [s]``), no timestamps;
* ``dmu_kmm`` (7144, bench_keysight70's machining centre, BenchLink's English export): the
  thermocouple channels in kelvin, ``101 <Air> (K)``, the probes' Mx+B in millimetres,
  ``201 <DISP_X> (mm)`` (six decimals: the base's 0.001 µm).

What is measured (written before anything ran)
----------------------------------------------
* ``init`` of each folder as a stranger types it: tries (each refusal's advice followed), what
  it says of the units and the pairs.
* ``matrix`` (lab_matrix: ``run`` -> ``replay`` -> ``promote`` -> C ``export``, mlr and lagbank,
  ``data.join.offset_s=7`` on the lathes' two loggers): expected ``lathe_mm``, ``lathe_k`` and
  ``dmu_kmm`` = their base's test RMSE (relative difference <= 1e-6: the same numbers in another
  unit); ``lathe_first`` = its base's with the probes' first 20 min cut (said);
  ``lathe_first_s`` at ``data.join.offset_s=1200`` (the error logger's start that much before
  the DAQ's) = ``lathe_first``; at 0 (what "taken as started together" reads) worse; replay = run.

Measured (2026-12-02, every step once, 2 shared cores; docs/own-data.md, "Two loggers, other
units, the probes first")
-----------------------------------------------------------------------------------------
``init``: one try on every folder (1.8-2.2 s CPU in process).  ``matrix`` (18 cells, 81.4 + 6.0 s
CPU): mm, K and the Keysight K/mm export = their base (relative difference <= 9.7e-14), MET;
``lathe_first_s`` at offset 1200 = ``lathe_first`` (0.0 difference), MET; at offset 0 (a ``run``
each): dX 4.55 (mlr) / 2.32 (lagbank) µm against 1.84 / 1.52.  replay = run (<= 1.3e-15) in 14
of 18 cells; MISSED on seed 7141 (base and mm alike): the sensor monitor excluded
``T_NC_X1_drive`` twice (drift over its last 2 samples, the joined rows every 300 s), replay dX
2.175 against run 1.827 (mlr), 2.131 against 2.105 (lagbank), the C pack cut at its first event
(13 rows); the simulated run at 60 s (errors now and then) has none (replay = run, 1.807).
(mon71 traced it: not the 300 s period but the training's first joined row, 5 min into a
warm-up, the monitor's reference; at 60 s started 5 min late the same exclusion:
bench_mon71.)
Every C pack passed, promote = the run's mean where replay = run.
"""

from __future__ import annotations

import sys
from datetime import datetime
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]

import bench_keysight70 as keysight  # noqa: E402
import bench_twolog70 as twolog  # noqa: E402
import lab_matrix  # noqa: E402

LATHES = {"lathe_mm": 7141, "lathe_k": 7142, "lathe_first": 7143}
DMU = {"dmu_kmm": 7144}
SEEDS = {**LATHES, **DMU}
FIRST_S = 1200.0          # lathe_first: the probe software started this long before the DAQ
KELVIN = 273.15


def _varied_lathe(name: str, temp: pd.DataFrame, disp: pd.DataFrame) -> tuple:
    """The lathe's two files of one run as the variation ``name`` writes them."""
    if name == "lathe_mm":
        for axis in ("X", "Y"):
            um = disp.pop(f"d{axis} [µm]").str.replace(",", ".").astype(float)
            disp[f"d{axis} [mm]"] = [f"{v / 1000:.4f}".replace(".", ",") for v in um]
    elif name == "lathe_k":
        for c in [c for c in temp.columns if c.endswith("[°C]")]:
            temp[c.replace("[°C]", "[K]")] = [f"{float(v) + KELVIN:.2f}" for v in temp.pop(c)]
        temp = temp[["Time", *[c for c in temp.columns if c != "Time"]]]
    elif name == "lathe_first":
        at = pd.to_datetime(temp["Time"])
        temp = temp[(at >= at.iloc[0] + pd.Timedelta(seconds=FIRST_S)).to_numpy()]
    return temp, disp


def _in_seconds(folder: Path, out: Path) -> None:
    """``lathe_first``'s files with each logger's time in seconds from its own start."""
    out.mkdir(parents=True, exist_ok=True)
    for path in sorted(folder.glob("*_temp.csv")):
        temp = pd.read_csv(path, dtype=str)
        at = pd.to_datetime(temp.pop("Time"))
        temp.insert(0, "t [s]", ((at - at.iloc[0]).dt.total_seconds()).map(lambda s: f"{s:g}"))
        temp.to_csv(out / path.name, index=False)
        disp_path = path.with_name(path.name.replace("_temp", "_disp"))
        disp = pd.read_csv(disp_path, sep=";", dtype=str)
        at = pd.to_datetime(disp.pop("Zeitstempel"), format="%d.%m.%Y %H:%M:%S")
        disp.insert(0, "t [s]", ((at - at.iloc[0]).dt.total_seconds()).map(lambda s: f"{s:g}"))
        disp.to_csv(out / disp_path.name, index=False, sep=";")


def write_lathes(root: Path) -> None:
    for name, sim_dir, folder in lab_matrix.simulated(root, LATHES, twolog.simulate):
        base = root / name.replace("lathe", "base")
        base.mkdir(parents=True, exist_ok=True)
        for row in pd.read_csv(sim_dir / "campaigns.csv").itertuples(index=False):
            sim = pd.read_csv(sim_dir / row.file)
            # (lathe_first's base: both loggers from the run's start to its end, every run)
            run = "first" if name == "lathe_first" else row.campaign
            temp, disp = twolog.lab_files(sim, pd.Timestamp(row.start), run)
            temp.to_csv(base / f"{row.campaign}_temp.csv", index=False)
            disp.to_csv(base / f"{row.campaign}_disp.csv", index=False, sep=";")
            temp, disp = _varied_lathe(name, temp.copy(), disp.copy())
            temp.to_csv(folder / f"{row.campaign}_temp.csv", index=False)
            disp.to_csv(folder / f"{row.campaign}_disp.csv", index=False, sep=";")
        if name == "lathe_first":
            _in_seconds(folder, root / "lathe_first_s")


def write_dmu(root: Path) -> None:
    settings = keysight.SETTINGS["dmu_a"]
    units = {c: ("K" if c.startswith("T_") else "mm" if c.startswith("E_") else None)
             for c in keysight.CHANNELS}
    for name, sim_dir, folder in lab_matrix.simulated(root, DMU, keysight.simulate):
        base = root / name.replace("dmu", "base")
        base.mkdir(parents=True, exist_ok=True)
        for k, row in enumerate(pd.read_csv(sim_dir / "campaigns.csv").itertuples(index=False)):
            frame = pd.read_csv(sim_dir / row.file)
            start = pd.Timestamp(row.start).to_pydatetime()
            keysight.write_run(base, k, frame, start, settings)
            _write_kmm(folder, k, frame, start, settings, units)


def _write_kmm(folder: Path, k: int, frame: pd.DataFrame, start: datetime, settings: dict,
               units: dict) -> None:
    """A run as the base writes it, the temperatures' channels in kelvin and the probes' in mm
    (the same digits: a value's text in its unit, six decimals for mm)."""
    text = keysight.export_text(frame, start, k + 1, settings, np.random.default_rng([7070, k]))
    lines = text.split("\r\n")
    at = next(i for i, line in enumerate(lines) if line.startswith("Scan"))
    header = lines[at].split(",")
    for j, cell in enumerate(header):
        for column, (channel, labels, unit_labels) in keysight.CHANNELS.items():
            if cell == f"{channel} <{labels[0]}> ({unit_labels[0]})" and units[column]:
                header[j] = f"{channel} <{labels[0]}> ({units[column]})"
    scaled = {j: units[c] for j, h in enumerate(header) for c in keysight.CHANNELS
              if units[c] and h.startswith(f"{keysight.CHANNELS[c][0]} <")}
    lines[at] = ",".join(header)
    for i in range(at + 1, len(lines)):
        if not lines[i]:
            continue
        cells = lines[i].split(",")
        for j, unit in scaled.items():
            v = float(cells[j])
            cells[j] = f"{v + KELVIN:.3f}" if unit == "K" else f"{v / 1000:.6f}"
        lines[i] = ",".join(cells)
    path = folder / settings["file"].format(k=k + 1)
    path.write_bytes("\r\n".join(lines).encode("utf-8"))


def write(root: Path) -> None:
    write_lathes(root)
    write_dmu(root)


FAMILIES = {k: v for k, v in lab_matrix.matrix_families().items() if k in ("mlr", "lagbank")}


def main(argv: list[str]) -> int:
    np.seterr(all="ignore")
    names = {**SEEDS, "lathe_first_s": 7143, **{n.replace("lathe", "base").replace("dmu", "base"): s
                                                for n, s in SEEDS.items()}}
    return lab_matrix.main(__doc__, argv, names, FAMILIES, ("plain",),
                           {"write": lambda root, rest: write(root),
                            "init": lambda root, rest: lab_matrix.initialised(root, rest[0], rest[1:])})


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
