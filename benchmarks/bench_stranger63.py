"""A stranger's pass on a machine nobody tuned on, to the machine (session 63, stranger63).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger63.py write ROOT

The machine is ``benchmarks/trunnion63.py`` (a 5-axis trunnion mill, a chiller on the spindle's
coolant, a weekend shutdown, a hall door), simulated by ``thermocomp simulate`` with
``benchmarks/conf63/sim/trunnion63.yaml``; its physics and the lab's export below were committed
before any model ran on them (seeds 6301 and 6302 fixed beforehand).

The lab's files (``write``)
---------------------------
``trunnion`` (seed 6301): the machine's edge PC writes one CSV per calendar week
(``DMU65_KW47.csv``...), Excel's German style: ``;`` separated, decimal comma, a date-time
column ``Datum/Zeit`` as ``16.11.26 06:01`` (two-digit year, no seconds), headers with units
(``T Spindel vorn [°C]``, ``Drehzahl [1/min]``, ``dX [mm]``); the probe's master-ball results
in MILLIMETRES (4 decimals), empty between cycles and whenever the machine is off (the probe
cycle needs the machine powered: weekdays 6-22 h), zeroed at the week's start (Monday 0:00,
the machine cold after the weekend).  The last week is the test (``data.test_fraction=0.34``).

``trunnion_b`` (seed 6302, a second draw): the lab's own logger, one file per week
(``woche1.csv``...), ``;`` and decimal comma, NO time column (a row every 60 s, said to init
as ``data.sample_period_s=60``), the errors in µm (``dX [µm]``).
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
SEEDS = {"trunnion": 6301, "trunnion_b": 6302}
HEADERS = {"T_spindle_front": "T Spindel vorn [°C]", "T_spindle_motor": "T Spindelmotor [°C]",
           "T_coolant_return": "T Kühlmittel Rücklauf [°C]", "T_ram": "T Pinole [°C]",
           "T_column": "T Ständer [°C]", "T_bed": "T Bett [°C]",
           "T_trunnion": "T Schwenkbrücke [°C]", "T_table": "T Rundtisch [°C]",
           "T_amb": "T Halle [°C]", "S_spindle_rpm": "Drehzahl [1/min]"}


def simulate(seed: int, path: Path) -> None:
    """``thermocomp simulate`` of the trunnion mill (the documented own-machine route)."""
    env = dict(os.environ, THERMOCOMP_TARGETS="trunnion63.",
               PYTHONPATH=f"{REPO / 'src'}:{REPO / 'benchmarks'}")
    subprocess.run([sys.executable, "-m", "thermocomp", "simulate",
                    f"hydra.searchpath=[file://{REPO / 'benchmarks' / 'conf63'}]", "sim=trunnion63",
                    f"seed={seed}", f"data.path={path}", "track=false"], env=env, check=True)


def powered(time_s: np.ndarray) -> np.ndarray:
    hours = time_s / 3600.0
    return ((hours // 24) % 7 < 5) & (hours % 24 >= 6) & (hours % 24 < 22)


def lab_frame(frame: pd.DataFrame, start: pd.Timestamp, in_mm: bool, with_time: bool
              ) -> pd.DataFrame:
    out = {}
    if with_time:
        out["Datum/Zeit"] = (start + pd.to_timedelta(frame["time"], unit="s")).dt.strftime(
            "%d.%m.%y %H:%M")
    for column, header in HEADERS.items():
        out[header] = frame[column]
    on = powered(frame["time"].to_numpy(float))
    for axis in "XYZ":
        values = frame[f"E_{axis}"].where(on)
        out[f"d{axis} [{'mm' if in_mm else 'µm'}]"] = (values / 1000).round(4) if in_mm else values
    return pd.DataFrame(out)


def write(root: Path) -> None:
    for name, seed in SEEDS.items():
        sim = root / "sim" / name
        if not (sim / "campaigns.csv").exists():
            simulate(seed, sim)
        listed = pd.read_csv(sim / "campaigns.csv")
        folder = root / name
        folder.mkdir(parents=True, exist_ok=True)
        for k, row in enumerate(listed.itertuples()):
            start = pd.Timestamp(row.start)
            frame = pd.read_csv(sim / row.file)
            if name == "trunnion":
                lab = lab_frame(frame, start, in_mm=True, with_time=True)
                target = folder / f"DMU65_KW{start.isocalendar().week}.csv"
            else:
                lab = lab_frame(frame, start, in_mm=False, with_time=False)
                target = folder / f"woche{k + 1}.csv"
            lab.to_csv(target, sep=";", decimal=",", index=False, float_format="%.6g")


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    what, root = argv[0], Path(argv[1]).resolve()
    if what == "write":
        write(root)
        print(json.dumps({p.name: sorted(x.name for x in p.iterdir())
                          for p in (root / n for n in SEEDS)}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
