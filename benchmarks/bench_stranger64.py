"""A stranger's pass on a machine and an export nobody tuned on (session 64, stranger64).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger64.py write ROOT

The machine is ``benchmarks/portal64.py`` (a double-column portal mill in an unclimatised hall:
skylight sun on the right column, a long Z ram whose logged extension levers the Y and Z
errors, a cross-rail heated by its drives, the hall heating on at 05:00 on weekdays),
simulated by ``thermocomp simulate`` with ``benchmarks/conf64/sim/portal64.yaml``; its physics
and the lab's exports below were committed before any model ran on them (seeds 6401 and 6402
fixed beforehand).

The lab's files (``write``)
---------------------------
``pm12`` (seed 6401, three weekly campaigns): one TAB-separated ``.txt`` per week
(``PM12_week1.txt`` ...) with a metadata preamble (``Machine;PM-12``, ``Operator: ...``, four
lines) before the header, headers with units in brackets (``T ram [°C]``, ``Z ram [mm]``,
``dZ [mm]``), decimal commas, the time as elapsed hours ``t [h]`` since the campaign's start
(week 2 starts at 168; four decimals, as the lab's sheet shows them), the probe's errors in mm
(four decimals), empty between the 5-min probe cycles.  The last week is the test.

``pm12_long`` (seed 6402, ``one_record=true``: the three weeks as one record): one CSV (``,``,
decimal points) with Excel serial dates (days since 1899-12-30) as the time column ``Date``,
errors in µm, and the cross-rail's sensor dropped out (empty cells) for half a day (the second
Wednesday 08:00-20:00, in the train part).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]
SEEDS = {"pm12": 6401, "pm12_long": 6402}
HEADERS = {"T_col_L": "T column L [°C]", "T_col_R": "T column R [°C]",
           "T_rail": "T cross-rail [°C]", "T_rail_drive": "T Y drive [°C]",
           "T_saddle": "T saddle [°C]", "T_ram": "T ram [°C]", "T_spindle": "T spindle [°C]",
           "T_motor": "T spindle motor [°C]", "T_bed": "T bed [°C]", "T_hall": "T hall [°C]",
           "S_spindle_rpm": "Spindle [rpm]", "S_pos_Z": "Z ram [mm]"}
PREAMBLE = ("Machine;PM-12\nOperator: K. Brandt\nProject: thermal drift, hall 3 (no HVAC)\n"
            "Probe: touch probe on the table, cycle 5 min\n")
DROPOUT = ("T_rail", 9 * 24 + 8.0, 9 * 24 + 20.0)    # column, from / to hour of the record
EXCEL_EPOCH = pd.Timestamp("1899-12-30")


def simulate(seed: int, path: Path, *extra: str) -> None:
    """``thermocomp simulate`` of the portal mill (the documented own-machine route)."""
    env = dict(os.environ, THERMOCOMP_TARGETS="portal64.",
               PYTHONPATH=f"{REPO / 'src'}:{REPO / 'benchmarks'}")
    subprocess.run([sys.executable, "-m", "thermocomp", "simulate",
                    f"hydra.searchpath=[file://{REPO / 'benchmarks' / 'conf64'}]", "sim=portal64",
                    f"seed={seed}", f"data.path={path}", "track=false", *extra], env=env, check=True)


def weekly_file(frame: pd.DataFrame, week: int) -> str:
    """One week as the PM-12's logger PC exports it (TAB, decimal commas, a preamble)."""
    out = {"t [h]": (frame["time"] / 3600.0 + 168.0 * week).map(lambda h: f"{h:.4f}")}
    for column, header in HEADERS.items():
        out[header] = frame[column].map(lambda v: f"{v:g}")
    for axis in "XYZ":
        out[f"d{axis} [mm]"] = (frame[f"E_{axis}"] / 1000.0).map(
            lambda v: "" if np.isnan(v) else f"{v:.4f}")
    table = pd.DataFrame(out).to_csv(sep="\t", index=False, lineterminator="\n")
    return PREAMBLE + table.replace(".", ",")


def long_file(frame: pd.DataFrame, start: pd.Timestamp) -> pd.DataFrame:
    """The long record as the second lab saves it from Excel: serial dates, a dropout."""
    days = (start - EXCEL_EPOCH) / pd.Timedelta(days=1) + frame["time"] / 86400.0
    out = {"Date": days.map(lambda d: f"{d:.10f}")}
    for column, header in HEADERS.items():
        out[header] = frame[column]
    for axis in "XYZ":
        out[f"d{axis} [µm]"] = frame[f"E_{axis}"]
    lab = pd.DataFrame(out)
    column, lo, hi = DROPOUT
    hours = frame["time"] / 3600.0
    lab.loc[(hours >= lo) & (hours < hi), HEADERS[column]] = np.nan
    return lab


def write(root: Path) -> None:
    for name, seed in SEEDS.items():
        sim = root / "sim" / name
        if not (sim / "campaigns.csv").exists():
            simulate(seed, sim, *(["sim.generator.one_record=true"] if name == "pm12_long" else []))
        listed = pd.read_csv(sim / "campaigns.csv")
        folder = root / name
        folder.mkdir(parents=True, exist_ok=True)
        for k, row in enumerate(listed.itertuples()):
            frame = pd.read_csv(sim / row.file)
            if name == "pm12":
                (folder / f"PM12_week{k + 1}.txt").write_text(weekly_file(frame, k),
                                                              encoding="utf-8")
            else:
                long_file(frame, pd.Timestamp(row.start)).to_csv(
                    folder / "PM12_march.csv", index=False, float_format="%.6g")


def main(argv: list[str]) -> None:
    step, root = argv[0], Path(argv[1]).resolve()
    if step == "write":
        write(root)
    else:
        raise SystemExit(f"unknown step {step!r}")


if __name__ == "__main__":
    main(sys.argv[1:])
