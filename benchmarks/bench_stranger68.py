"""A stranger's pass on a turn-mill centre and a lab's Excel workbook nobody tuned on (stranger68).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger68.py write ROOT

The machine is ``benchmarks/mtc68.py`` (a turn-mill centre: a main spindle in a fixed headstock,
a travelling column with a B-axis milling head whose tool spindle mills; planted: the tool
spindle's axial growth turned by the logged B angle onto E_X (cos B) and E_Z (sin B)),
simulated by ``thermocomp simulate`` with ``benchmarks/conf68/sim/mtc68.yaml``; its physics and
the lab's export below were committed before any model ran on them (seeds 6851 and 6852 fixed
beforehand).

The lab's files (``write``)
---------------------------
As the lab's Excel macro writes its test runs (openpyxl here; the values written, no formulas):

``mtc_a`` (seed 6851, eight 24 h runs): ONE workbook, ``MTC800_thermal_2027-06.xlsx``, its
first sheet ``Info`` (a cover: machine, lab, operator, the test bar, a table of the sensors and
where they sit), then ONE SHEET PER RUN, ``Run 1`` ... ``Run 8``.  A run's sheet: row 1 a title
merged over the table's width (``MTC 800 - thermal test, run 3 - Fri 18.06.2027 06:00``), row 2
empty, row 3 the GROUP HEADER in MERGED CELLS (``Date / time`` merged down over rows 3-4,
``Temperatures`` over the seven sensors, ``Displacement at the test bar`` over dX / dY / dZ,
``NC`` over the two speeds and B), row 4 the channel names (``Air``, ``Bed``, ``Headstock``,
``Spindle front``, ``Column``, ``B head``, ``Coolant``, ``dX``, ``dY``, ``dZ``, ``Main
spindle``, ``Tool spindle``, ``B axis``), row 5 a UNITS ROW (``°C``, ``µm``, ``1/min``, ``°``),
then the rows: the time a date-time cell (format ``dd.mm.yyyy hh:mm``), the values numbers
shown with two decimals; under the table an empty row and a ``Maximum`` row (each column's
largest value, the macro's summary).

``mtc_b`` (seed 6852, the same machine three weeks later): ONE WORKBOOK PER RUN in a folder
(``Run_01.xlsx`` ... ``Run_08.xlsx``, the macro's other mode), each its ``Info`` sheet first and
the run's sheet ``Data`` second, laid out as above (no ``Maximum`` row).

What is measured (written before anything ran)
----------------------------------------------
* ``init`` of each record as a stranger types it (the workbook or the folder, then
  ``data.test_fraction`` to hold the last run out, then what each message says): tries counted,
  how many runs are read, what each header's role is (B in ``°``: a state).
* ``matrix`` (lab_matrix): every family + auto, ``run`` -> ``replay`` -> ``promote`` -> C
  ``export`` with its check pack: test RMSE per target; replay = run (<= 1e-9).
* ``diagnose`` (mlr): FOUND when an accepted effect on E_X or E_Z names the B axis' column.
* ``monitor`` (mlr): the healthy test run quiet (0 sensor events), then +3 K on ``B head`` from
  row 600 of the held-out run (10 h in, the shift's afternoon).
* CPU (user + sys) of every command (in process, ``RUSAGE_SELF`` + children).

No rule is adopted from these records: they are a check, not a tuning set.

Measured (2026-12-01, every step once, 2 shared cores, other sessions' load; docs/own-data.md)
----------------------------------------------------------------------------------------------
``init mtc_a`` at 25cac747: "no column reads as a measured error ... the numeric columns: none"
(the cover read); with ``data.sheet='Run 1'`` the same (the unit row's ``°`` unknown: the row
read as data); with ``data.roles.error=[dX,dY,dZ]`` too, "no 'time' column" (its name in the
merged cell above).  Mended (c3501319): each run sheet a campaign, the cover left out, the
merged name, ``°`` a unit, the ``Maximum`` row under an empty row a footer; one try each
(3.7 / 4.2 s CPU).  ``matrix`` (test RMSE dX / dY / dZ µm; before 16.06 / 2.20 / 38.26 and
14.58 / 2.71 / 29.18): 6851 mlr 9.73 / 0.64 / 11.02, hammerstein 6.71 / 0.51 / 7.25, auto 5.75 /
0.52 / 7.02; 6852 mlr 14.11 / 0.50 / 14.34, auto (Hammerstein's validation 5.43 on dX) 15.82 /
0.37 / 16.19 (its test run at B = 90° 53 % of the time, the train runs 8-24 %).  Every cell:
replay = run (<= 3.6e-15), |stream - batch| <= 7.1e-14, promote = run, C pack passed; the
matrix 125.7 s CPU (6851, 7 cells).  ``diagnose`` mlr FOUND on both seeds (``S_B_axis`` x the
rises, on dZ and dX): 6851 -> 1.87 / 0.43 / 1.66, 6852 -> 3.46 / 0.48 / 3.59 (16 / 13 s CPU).
``monitor`` mlr: healthy 0 events; +3 K on ``B head`` at 10 h excluded at once.

    ... bench_stranger68.py init ROOT mtc_a [override ...]   # init as a stranger, one try
    ... bench_stranger68.py matrix ROOT mtc_a                # run -> replay -> promote -> C
    ... bench_stranger68.py table ROOT mtc_a
    ... bench_stranger68.py monitor ROOT mtc_a mlr "B head"
    ... bench_stranger68.py diagnose ROOT mtc_a mlr
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]
SEEDS = {"mtc_a": 6851, "mtc_b": 6852}
WORKBOOK_A = "MTC800_thermal_2027-06.xlsx"
# contract name -> (group, channel, unit) as the macro writes them
CHANNELS = {
    "T_amb": ("Temperatures", "Air", "°C"), "T_bed": ("Temperatures", "Bed", "°C"),
    "T_headstock": ("Temperatures", "Headstock", "°C"),
    "T_spindle_front": ("Temperatures", "Spindle front", "°C"),
    "T_column": ("Temperatures", "Column", "°C"), "T_bhead": ("Temperatures", "B head", "°C"),
    "T_coolant": ("Temperatures", "Coolant", "°C"),
    "E_X": ("Displacement at the test bar", "dX", "µm"),
    "E_Y": ("Displacement at the test bar", "dY", "µm"),
    "E_Z": ("Displacement at the test bar", "dZ", "µm"),
    "S_n_main_rpm": ("NC", "Main spindle", "1/min"), "S_n_tool_rpm": ("NC", "Tool spindle", "1/min"),
    "S_B_deg": ("NC", "B axis", "°"),
}
WHERE = {"Air": "1.5 m beside the machine, shaded", "Bed": "bed, below the headstock",
         "Headstock": "main headstock housing, top", "Spindle front": "main spindle, front flange",
         "Column": "column, X slide side", "B head": "B-axis head housing, near the motor",
         "Coolant": "coolant tank outlet"}


def simulate(seed: int, path: Path) -> None:
    """``thermocomp simulate`` of the turn-mill centre (the documented own-machine route)."""
    lab_matrix.simulate_scenario("mtc68", "conf68", seed, path,
                                 *(["sim.generator.weeks_later=3"] if seed == 6852 else []))


def cover(book, runs: int) -> None:
    """The workbook's first sheet, ``Info``: what the macro writes above the runs."""
    info = book.active
    info.title = "Info"
    for row in (("Thermal test", "MTC 800 turn-mill centre, S/N 5517"),
                ("Lab", "Machine tool lab, hall 2"), ("Operator", "R. Okafor"),
                ("Test bar", "d 40 mm x 300 mm in the main spindle; capacitive probes X, Y, Z"),
                ("Runs", runs), ("Sample period", "60 s"), (), ("Sensor", "Position", "Type")):
        info.append(list(row))
    for name, where in WHERE.items():
        info.append([name, where, "Pt100 class A"])


def run_sheet(sheet, frame: pd.DataFrame, title: str, start: pd.Timestamp, maximum: bool) -> None:
    """One run as the macro writes it: a title, the merged group header, names, units, rows."""
    from openpyxl.utils import get_column_letter

    width = 1 + len(CHANNELS)
    sheet.append([title])
    sheet.merge_cells(start_row=1, start_column=1, end_row=1, end_column=width)
    sheet.append([])
    groups, names, units = ["Date / time"], [None], [None]
    for group, name, unit in CHANNELS.values():
        groups.append(group if group not in groups else None)
        names.append(name)
        units.append(unit)
    sheet.append(groups)
    sheet.append(names)
    sheet.append(units)
    sheet.merge_cells(start_row=3, start_column=1, end_row=4, end_column=1)
    column = 2
    for group in dict.fromkeys(g for g, _, _ in CHANNELS.values()):
        span = sum(1 for g, _, _ in CHANNELS.values() if g == group)
        sheet.merge_cells(start_row=3, start_column=column, end_row=3,
                          end_column=column + span - 1)
        column += span
    stamps = start + pd.to_timedelta(frame["time"], unit="s")
    for stamp, row in zip(stamps, frame[list(CHANNELS)].itertuples(index=False)):
        sheet.append([stamp.to_pydatetime(), *(round(float(v), 3) for v in row)])
    first = 6
    for cells in sheet.iter_rows(min_row=first, max_row=sheet.max_row):
        cells[0].number_format = "dd.mm.yyyy hh:mm"
        for c in cells[1:]:
            c.number_format = "0.00"
    if maximum:
        sheet.append([])
        sheet.append(["Maximum", *(round(float(frame[c].max()), 3) for c in CHANNELS)])
    sheet.column_dimensions["A"].width = 17
    for k in range(2, width + 1):
        sheet.column_dimensions[get_column_letter(k)].width = 12


def title(k: int, start: pd.Timestamp) -> str:
    return f"MTC 800 - thermal test, run {k + 1} - {start:%a %d.%m.%Y %H:%M}"


def write(root: Path) -> None:
    from openpyxl import Workbook

    for name, sim, folder in lab_matrix.simulated(root, SEEDS, simulate):
        manifest = pd.read_csv(sim / "campaigns.csv")
        runs = list(manifest.itertuples(index=False))
        if name == "mtc_a":
            book = Workbook()
            cover(book, len(runs))
            for k, row in enumerate(runs):
                start = pd.Timestamp(row.start)
                run_sheet(book.create_sheet(f"Run {k + 1}"), pd.read_csv(sim / row.file),
                          title(k, start), start, maximum=True)
            book.save(folder / WORKBOOK_A)
            continue
        for k, row in enumerate(runs):
            book = Workbook()
            cover(book, 1)
            start = pd.Timestamp(row.start)
            run_sheet(book.create_sheet("Data"), pd.read_csv(sim / row.file), title(k, start),
                      start, maximum=False)
            book.save(folder / f"Run_{k + 1:02d}.xlsx")


import lab_matrix  # noqa: E402  (the benches' shared matrix and steps)
from lab_matrix import project, stage  # noqa: E402

FAMILIES = lab_matrix.matrix_families()
WRAPPERS = ("plain",)


def record_path(root: Path, name: str) -> Path:
    """What a stranger gives ``init``: the workbook where the folder holds one, else the folder."""
    books = sorted((root / name).glob("*.xlsx"))
    return books[0] if len(books) == 1 else root / name


def initialised(root: Path, name: str, extra: list[str]) -> None:
    """``thermocomp init`` of the record ``name`` with ``extra`` (one try, as a stranger types it)."""
    project(root)
    rc, said, cpu = stage("init", str(record_path(root, name)), *extra,
                          f"out={root / f'init-{name}'}")
    conf = root / f"init-{name}" / "conf" / "data"
    if not rc and not (conf / f"{name}.yaml").exists():     # (named after the workbook)
        next(conf.glob("*.yaml")).rename(conf / f"{name}.yaml")
    print(json.dumps({"init": name, "extra": extra, "rc": rc, "said": said[:600],
                      "cpu": round(cpu, 2)}), flush=True)


def planted(src: Path, dst: Path, header: str, onset_row: int, jump_k: float = 3.0) -> Path:
    """``dst``: a copy of the record ``src`` with ``header`` of its held-out (last) run jumped by
    ``jump_k`` K from data row ``onset_row`` on, saved as the macro saves it; the path to read."""
    import shutil

    from openpyxl import load_workbook

    shutil.copytree(src, dst, dirs_exist_ok=True)
    book_path = sorted(dst.glob("*.xlsx"))[-1]
    book = load_workbook(book_path)
    sheet = book.worksheets[-1]
    k = [c.value for c in sheet[4]].index(header) + 1
    for r in range(6 + onset_row, sheet.max_row + 1):
        cell = sheet.cell(row=r, column=k)
        if isinstance(cell.value, (int, float)) and sheet.cell(row=r, column=1).value != "Maximum":
            cell.value = round(cell.value + jump_k, 3)
    book.save(book_path)
    return book_path if len(list(dst.glob("*.xlsx"))) == 1 else dst


def monitoring(root: Path, name: str, family: str, sensors, onset_row: int = 600) -> None:
    """``monitor`` of the saved model on the healthy test run, then with each sensor of
    ``sensors`` (a channel name) jumped by +3 K from ``onset_row`` (10 h at 60 s) on."""
    import os

    os.environ["THERMOCOMP_ROOT"] = str(root / "tc")
    rows = [{"case": "healthy", **lab_matrix.monitored(root, name, family,
                                                       root / "mon" / f"{name}-healthy")}]
    print(json.dumps(rows[-1]), flush=True)
    for header in sensors:
        folder = root / "faulted" / f"{name}-jump-{header.replace(' ', '_')}"
        path = planted(root / name, folder, header, onset_row)
        row = lab_matrix.monitored(root, name, family, root / "mon" / folder.name,
                                   f"data.path={path}")
        rows.append({"case": f"jump {header}", "onset_h": onset_row / 60, **row})
        print(json.dumps(rows[-1]), flush=True)
    (root / f"monitor-{name}.json").write_text(json.dumps(rows, indent=1))


def main(argv: list[str]) -> int:
    return lab_matrix.main(__doc__, argv, SEEDS, FAMILIES, WRAPPERS, {
        "write": lambda root, rest: write(root),
        # init ROOT name [override ...]
        "init": lambda root, rest: initialised(root, rest[0], rest[1:]),
        # monitor ROOT name family channel...
        "monitor": lambda root, rest: monitoring(root, rest[0], rest[1], rest[2:]),
    })


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
