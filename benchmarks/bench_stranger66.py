"""A stranger's pass on a machine and an export nobody tuned on (session 66, stranger66).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger66.py write ROOT

The machine is ``benchmarks/tsc66.py`` (a twin-spindle turning centre: a shared slant bed, a
main and a counter spindle with a turret each, the counter spindle only in back-working jobs;
planted: the bed's growth levered by the counter headstock's logged position, ``S_Z2_mm`` x the
bed's rise, on E_Z2), simulated by ``thermocomp simulate`` with ``benchmarks/conf66/sim/tsc66.yaml``;
its physics and the lab's export below were committed before any model ran on them (seeds 6601
and 6602 fixed beforehand).

The lab's files (``write``)
---------------------------
``tsc_a`` (seed 6601, six 40 h runs): one file per run (``TC2_run01.txt`` ...) as the lab's
DAQ script writes them (numpy-``savetxt`` style): a block of ``#`` comment lines above the
table (``# instrument: ...``, ``# operator: ...``, ``# run: 01``, ``# start: 2027-03-08
06:00:00``, ``# sample period: 60 s``, an empty ``#`` line), the column header itself a comment
line (``# t [s]<TAB>Air [degC]<TAB>...``), TAB-separated with a TRAILING TAB on every line,
decimal points, the time in seconds since the run's start (each file its own clock from 0: the
start only in the comment block), units ``[degC]``, ``[um]``, ``[rpm]``, ``[mm]``; defects:
``nan`` where the probe lost dZ1 (4 rows of run 3), and run 5's last line cut off mid-row
without its newline (the DAQ was stopped while writing).

    ... bench_stranger66.py init ROOT tsc_a [override ...]   # init as a stranger, one try
    ... bench_stranger66.py matrix ROOT tsc_a                # run -> replay -> promote -> C
    ... bench_stranger66.py table ROOT tsc_a
    ... bench_stranger66.py monitor ROOT tsc_a mlr "Bed" "Turret 2"
    ... bench_stranger66.py diagnose ROOT tsc_a mlr
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]
SEEDS = {"tsc_a": 6601, "tsc_b": 6602}
NAMES = {"T_amb": "Air [degC]", "T_bed": "Bed [degC]", "T_main_head": "Headstock 1 [degC]",
         "T_counter_head": "Headstock 2 [degC]", "T_turret1": "Turret 1 [degC]",
         "T_turret2": "Turret 2 [degC]", "T_coolant": "Coolant [degC]",
         "S_n1_rpm": "n1 [rpm]", "S_n2_rpm": "n2 [rpm]", "S_Z2_mm": "Z2 pos [mm]",
         "E_X1": "dX1 [um]", "E_Z1": "dZ1 [um]", "E_X2": "dX2 [um]", "E_Z2": "dZ2 [um]"}
LOST = ("E_Z1", 2, 1500, 1504)           # column, run index, first and last+1 row: nan
CUT = 4                                  # run index whose last line is cut off mid-row


def simulate(seed: int, path: Path) -> None:
    """``thermocomp simulate`` of the turning centre (the documented own-machine route)."""
    env = dict(os.environ, THERMOCOMP_TARGETS="tsc66.",
               PYTHONPATH=f"{REPO / 'src'}:{REPO / 'benchmarks'}")
    subprocess.run([sys.executable, "-m", "thermocomp", "simulate",
                    f"hydra.searchpath=[file://{REPO / 'benchmarks' / 'conf66'}]", "sim=tsc66",
                    f"seed={seed}", f"data.path={path}", "track=false"], env=env, check=True)


def run_file(frame: pd.DataFrame, k: int, start: str) -> str:
    """One run as the lab's DAQ script writes it (``#`` block, TAB, a trailing TAB)."""
    head = ["# TC-2 twin-spindle turning centre, thermal test",
            "# instrument: Keysight DAQ970A, 4 capacitive probes (test bars in both spindles)",
            "# operator: J. Moreau", f"# run: {k + 1:02d}", f"# start: {start}",
            "# sample period: 60 s", "#",
            "# " + "\t".join(["t [s]", *NAMES.values()]) + "\t"]
    rows = []
    for i, r in enumerate(frame.itertuples(index=False)):
        r = r._asdict()
        cells = [f"{r['time']:.0f}"]
        for column in NAMES:
            v = r[column]
            if column == LOST[0] and k == LOST[1] and LOST[2] <= i < LOST[3]:
                cells.append("nan")
            elif column.startswith("T_"):
                cells.append(f"{v:.3f}")
            elif column.startswith("S_"):
                cells.append(f"{v:.0f}")
            else:
                cells.append(f"{v:.2f}")
        rows.append("\t".join(cells) + "\t")
    text = "\n".join(head + rows) + "\n"
    if k == CUT:                         # the DAQ stopped while writing its last line
        text = text[:-1]
        text = text[:text.rindex("\n") + 1 + len(rows[-1]) // 2]
    return text


def write(root: Path) -> None:
    for name, seed in SEEDS.items():
        sim = root / "sim" / name
        if not (sim / "campaigns.csv").exists():
            simulate(seed, sim)
        manifest = pd.read_csv(sim / "campaigns.csv")
        folder = root / name
        folder.mkdir(parents=True, exist_ok=True)
        for k, row in enumerate(manifest.itertuples(index=False)):
            frame = pd.read_csv(sim / row.file)
            start = pd.Timestamp(row.start).strftime("%Y-%m-%d %H:%M:%S")
            (folder / f"TC2_run{k + 1:02d}.txt").write_text(run_file(frame, k, start),
                                                            encoding="utf-8")


def main(argv: list[str]) -> None:
    step, root = argv[0], Path(argv[1]).resolve()
    if step == "write":
        write(root)
    else:
        raise SystemExit(f"unknown step {step!r}")


if __name__ == "__main__":
    main(sys.argv[1:])
