"""A stranger's pass on a machine and an export nobody tuned on (session 65, stranger65).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger65.py write ROOT

The machine is ``benchmarks/edm65.py`` (a wire EDM with an on/off dielectric chiller in a
day-night hall; planted: a clamping frame that follows the water while the tank is flooded,
``S_flooded`` x the water's rise), simulated by ``thermocomp simulate`` with
``benchmarks/conf65/sim/edm65.yaml``; its physics and the lab's exports below were committed
before any model ran on them (seeds 6501 and 6502 fixed beforehand).

The lab's files (``write``)
---------------------------
``edm_a`` (seed 6501, eight days as one record): one file per day (``EDM_20270607.csv`` ...)
as the machine's logger writes them: ``;``-separated, decimal commas, a TWO-ROW header (German
names, then a row of units: ``°C``, ``W``, ``-``, ``µm``), the date and the time of day in two
columns (``Datum;Uhrzeit``, ``07.06.2027;00:00:00``), the generator's power with THOUSANDS
separators (``1.200,0``), a sensor that drops out written ``---`` (the table's sensor, 5 rows
on day 2), the water's sensor RENAMED from day 5 on (``T Dielektrikum`` -> ``T Wasser``, its
new name in the logger's new configuration), and on day 3 the logger restarted at 14:00 and
wrote its two header rows AGAIN in the middle of the file.

``edm_b`` (seed 6502): one file from the lab's spreadsheet (``,``, decimal points, the
thousands grouped ``"1,200.0"`` in quotes), ``#N/A`` where the gauge lost E_X (3 rows) and
``Err:502`` in one cell of ``T cabinet`` (a LibreOffice formula error), the time an ISO stamp.

    ... bench_stranger65.py init ROOT                 # thermocomp init of both exports
    ... bench_stranger65.py matrix ROOT edm_a         # run -> replay -> promote -> C
    ... bench_stranger65.py table ROOT edm_a
    ... bench_stranger65.py monitor ROOT edm_a mlr "T Tisch"
    ... bench_stranger65.py diagnose ROOT edm_a mlr
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]
SEEDS = {"edm_a": 6501, "edm_b": 6502}
NAMES_A = {"T_hall": ("T Halle", "°C"), "T_water": ("T Dielektrikum", "°C"),
           "T_table": ("T Tisch", "°C"), "T_bed": ("T Bett", "°C"),
           "T_col_front": ("T Ständer vorn", "°C"), "T_col_back": ("T Ständer hinten", "°C"),
           "T_upper_arm": ("T Oberarm", "°C"), "T_lower_arm": ("T Unterarm", "°C"),
           "T_cabinet": ("T Generatorschrank", "°C"), "S_gen_W": ("Generatorleistung", "W"),
           "S_flooded": ("Becken geflutet", "-"), "E_X": ("dX", "µm"), "E_Y": ("dY", "µm")}
RENAMED_FROM_DAY = 5                       # day index (0-based: the sixth file is day 5)
RENAMED = ("T_water", "T Wasser")
DROPOUT = ("T_table", 1, 600, 605)         # column, day, first and last+1 row
RESTART = (2, 14 * 60)                     # day, row before which the header is written again
NAMES_B = {"T_hall": "T hall", "T_water": "T dielectric", "T_table": "T table", "T_bed": "T bed",
           "T_col_front": "T column front", "T_col_back": "T column back",
           "T_upper_arm": "T upper arm", "T_lower_arm": "T lower arm", "T_cabinet": "T cabinet",
           "S_gen_W": "Generator power [W]", "S_flooded": "Tank flooded [-]",
           "E_X": "dX [um]", "E_Y": "dY [um]"}
START = pd.Timestamp("2027-06-07")


def simulate(seed: int, path: Path) -> None:
    """``thermocomp simulate`` of the wire EDM (the documented own-machine route)."""
    env = dict(os.environ, THERMOCOMP_TARGETS="edm65.",
               PYTHONPATH=f"{REPO / 'src'}:{REPO / 'benchmarks'}")
    subprocess.run([sys.executable, "-m", "thermocomp", "simulate",
                    f"hydra.searchpath=[file://{REPO / 'benchmarks' / 'conf65'}]", "sim=edm65",
                    f"seed={seed}", f"data.path={path}", "track=false"], env=env, check=True)


def german(v: float, decimals: int, thousands: bool = False) -> str:
    text = f"{v:,.{decimals}f}" if thousands else f"{v:.{decimals}f}"
    return text.replace(",", "_").replace(".", ",").replace("_", ".")


def day_file(frame: pd.DataFrame, day: int) -> str:
    """One day as the EDM's logger writes it (``;``, decimal commas, names then units)."""
    stamps = START + pd.to_timedelta(frame["time"], unit="s")
    names = dict(NAMES_A)
    if day >= RENAMED_FROM_DAY:
        names[RENAMED[0]] = (RENAMED[1], "°C")
    head = ["Datum", "Uhrzeit"] + [n for n, _ in names.values()]
    units = ["", ""] + [u for _, u in names.values()]
    rows = []
    for i, (k, r) in enumerate(frame.iterrows()):
        cells = [stamps[k].strftime("%d.%m.%Y"), stamps[k].strftime("%H:%M:%S")]
        for column in names:
            v = r[column]
            if column == DROPOUT[0] and day == DROPOUT[1] and DROPOUT[2] <= i < DROPOUT[3]:
                cells.append("---")
            elif column == "S_gen_W":
                cells.append(german(v, 1, thousands=True))
            elif column == "S_flooded":
                cells.append(f"{int(v)}")
            else:
                cells.append(german(v, 2 if column.startswith("T_") else 1))
        if day == RESTART[0] and i == RESTART[1]:
            rows += [";".join(head), ";".join(units)]
        rows.append(";".join(cells))
    return "\r\n".join([";".join(head), ";".join(units), *rows]) + "\r\n"


def lab_b(frame: pd.DataFrame) -> str:
    stamps = START + pd.to_timedelta(frame["time"], unit="s")
    out = {"Timestamp": stamps.dt.strftime("%Y-%m-%d %H:%M:%S")}
    for column, header in NAMES_B.items():
        if column == "S_gen_W":
            out[header] = frame[column].map(lambda v: f'"{v:,.1f}"')
        elif column.startswith("T_"):
            out[header] = frame[column].map(lambda v: f"{v:.2f}")
        else:
            out[header] = frame[column].map(lambda v: f"{v:g}")
    lab = pd.DataFrame(out)
    lab.loc[3001:3003, NAMES_B["E_X"]] = "#N/A"
    lab.loc[7000, NAMES_B["T_cabinet"]] = "Err:502"
    lines = [",".join(lab.columns)] + [",".join(row) for row in lab.astype(str).to_numpy()]
    return "\n".join(lines) + "\n"


def write(root: Path) -> None:
    for name, seed in SEEDS.items():
        sim = root / "sim" / name
        if not (sim / "campaigns.csv").exists():
            simulate(seed, sim)
        frame = pd.read_csv(sim / "record.csv")
        folder = root / name
        folder.mkdir(parents=True, exist_ok=True)
        if name == "edm_b":
            (folder / "edm_b_export.csv").write_text(lab_b(frame), encoding="utf-8")
            continue
        day = (frame["time"] // 86400).astype(int)
        for k, part in frame.groupby(day):
            stamp = (START + pd.Timedelta(days=int(k))).strftime("%Y%m%d")
            (folder / f"EDM_{stamp}.csv").write_bytes(day_file(part, int(k)).encode("cp1252"))


def main(argv: list[str]) -> None:
    step, root = argv[0], Path(argv[1]).resolve()
    if step == "write":
        write(root)
    else:
        raise SystemExit(f"unknown step {step!r}")


if __name__ == "__main__":
    main(sys.argv[1:])
