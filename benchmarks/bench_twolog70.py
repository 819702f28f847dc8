"""A stranger's record logged by TWO loggers per run: the temperatures in one file, the
displacements in another, each with its own clock and rate (twolog70).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_twolog70.py write ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_twolog70.py init ROOT lathe_a [override ...]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_twolog70.py matrix ROOT lathe_a joined_a
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_twolog70.py table ROOT lathe_a

The machine is the Swiss-type lathe of ``conf/sim/swiss_lathe_door.yaml`` (paper 004: 12
temperatures, the door, the spindle and tool speeds; E_X / E_Y measured by probes every 5 min),
simulated by ``thermocomp simulate`` with ``sim.generator.error_gaps=nan`` (the errors only where
the probes measured), seeds 7043 (``lathe_a``) and 7044 (``lathe_b``), fixed before anything ran.
Each record has two runs: ``calibration`` (80 h, train) and ``production`` (24 h, held out).

The lab's files (``write``), written before any model ran on them
----------------------------------------------------------------
Per run two files in one folder, no manifest:

* ``<run>_temp.csv``: the thermocouple DAQ's, every 60 s, ``,``-separated, decimal point,
  ``Time`` as ``2023-03-07 07:02:00`` (the DAQ's clock is the lab's reference), the lab's names
  with units: ``Ambient [°C]``, ``Headstock [°C]`` ..., ``Spindle [rpm]``, ``Tool [rpm]``,
  ``Door [-]`` (the machine's signals go to the DAQ).  In ``calibration`` the DAQ was STARTED
  2 MIN LATE (its first two rows missing: the probes' sample at 07:00 has no temperature).
* ``<run>_disp.csv``: the probe software's, every 300 s (the probe cycle), ``;``-separated,
  decimal commas, ``Zeitstempel`` as ``07.03.2023 07:00:07``, ``dX [µm]``, ``dY [µm]``; its PC's
  clock runs 7 S AHEAD of the DAQ's (every stamp +7 s).  In ``production`` the probe software was
  stopped 30 min before the DAQ (its last 6 probe rows are not in the file).

``joined_a`` / ``joined_b``: the same runs as a lab that joined them by hand would give them, ONE
file per run (``<run>.csv``, the contract's names, ``time`` in seconds from the run's start): the
probe rows only, each with the simulated temperatures and states AT the probe's true instant
(what a perfect join gives; the calibration run keeps its 07:00 row, which the DAQ missed).

What is expected (written before anything ran)
----------------------------------------------
* ``init lathe_a`` (the folder as a stranger types it, tries counted): one try; it says each run's
  pair (``calibration_temp.csv`` + ``calibration_disp.csv``), the two clocks' rates, that the
  errors' times are the rows (temperatures interpolated onto them), and the row the late DAQ cuts.
* ``run`` (mlr, lagbank, auto) -> ``replay`` (lab_matrix's cell, with promote and the C export
  as they come): the test RMSE of ``lathe_a`` within 3 % of ``joined_a``'s for each target and
  family with the 7 s left as it is (``data.join.offset_s`` 0: a 7 s shift of temperatures that
  change over minutes), within 1 % with ``data.join.offset_s=7``; replay = run (<= 1e-9).
* The C export's check pack streams a test file through ``stream.c``: a run of two files is no
  one CSV it reads; said as it comes.

Measured (2026-12-02, every step once, 2 shared cores; docs/own-data.md)
------------------------------------------------------------------------
``init lathe_a`` at 48af5bfc (before the join): stuck after three tries ("looks ','-separated",
then the probe file "looks ';'-separated", no setting reading both).  Now one try per record
(2.1 / 2.5 s CPU), each pair said, ``delimiter: auto`` written.  Test RMSE dX / dY (µm):

    record    two loggers, offset 0   two loggers, offset 7   one file, every probe row
    7043 mlr      2.070 / 1.402           2.159 / 1.450            2.209 / 1.538
    7043 lagbank  1.816 / 1.386           1.926 / 1.432            1.676 / 1.110
    7043 auto     1.429 / 1.255           1.316 / 1.046            1.233 / 0.745
    7044 mlr      1.783 / 1.189           1.835 / 1.219            1.830 / 1.197
    7044 lagbank  1.967 / 1.259           1.997 / 1.282            1.489 / 0.963
    7044 auto     1.461 / 0.863           1.466 / 0.863            1.109 / 0.640

Both expectations MISSED: against the whole hand-joined record the two loggers' record lacks
the calibration's first probe row (the late DAQ: its reference) and the test's last 30 min.
Added after that matrix (``same`` step): the hand-joined runs cut to the rows both loggers
hold score exactly what the join at ``offset_s=7`` scores (difference 0.0 in all 12 cells).
Every cell: replay = run (<= 1.3e-15), promote = run's mean, C pack passed.  CPU of the two
matrices (24 cells: run, replay, promote, export, cc): 51.0 s and 82.0 s user + sys.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]
SEEDS = {"lathe_a": 7043, "lathe_b": 7044}
PERIOD_T, PERIOD_E = 60.0, 300.0        # the DAQ's and the probes' periods (s)
AHEAD_S = 7.0                           # the probe PC's clock minus the DAQ's
LATE_DAQ_S = 120.0                      # calibration: the DAQ started this late
EARLY_STOP_S = 1800.0                   # production: the probe software stopped this early
NAMES = {"T_amb": "Ambient", "T_headstock": "Headstock", "T_guidebush": "Guide bush",
         "T_toolholder1": "Tool holder 1", "T_toolholder2": "Tool holder 2",
         "T_frame1": "Frame 1", "T_frame2": "Frame 2", "T_nc_spindle_motor": "NC spindle motor",
         "T_nc_tool_motor": "NC tool motor", "T_nc_x1_drive": "NC X1 drive",
         "T_nc_z1_drive": "NC Z1 drive", "T_nc_cabinet": "NC cabinet"}
STATES = {"S_spindle_rpm": "Spindle [rpm]", "S_tool_rpm": "Tool [rpm]", "S_door": "Door [-]"}


def simulate(seed: int, path: Path) -> None:
    """``thermocomp simulate`` of the shipped lathe, the probes' rows only."""
    subprocess.run([sys.executable, "-m", "thermocomp", "simulate", "sim=swiss_lathe_door",
                    f"seed={seed}", f"data.path={path}", "track=false",
                    "sim.generator.error_gaps='nan'"], check=True,
                   env=dict(os.environ, PYTHONPATH=str(REPO / "src")))


def lab_files(sim: pd.DataFrame, start: pd.Timestamp, run: str) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The DAQ's frame and the probe software's of one simulated run (``sim``: the contract's)."""
    at = start + pd.to_timedelta(sim["time"], unit="s")
    temp = pd.DataFrame({"Time": at.dt.strftime("%Y-%m-%d %H:%M:%S")})
    for name, lab in NAMES.items():
        temp[f"{lab} [°C]"] = sim[name].map(lambda v: f"{v:.2f}")
    for name, lab in STATES.items():
        temp[lab] = sim[name].map(lambda v: f"{v:g}")
    keep = sim["time"] % PERIOD_T == 0
    if run == "calibration":
        keep &= sim["time"] >= LATE_DAQ_S
    temp = temp[keep.to_numpy()]
    probed = sim["E_X"].notna().to_numpy().copy()
    if run == "production":
        probed &= (sim["time"] <= sim["time"].iloc[-1] - EARLY_STOP_S).to_numpy()
    stamps = (at + pd.Timedelta(seconds=AHEAD_S))[probed]
    disp = pd.DataFrame({"Zeitstempel": stamps.dt.strftime("%d.%m.%Y %H:%M:%S").to_numpy()})
    for axis in ("X", "Y"):
        disp[f"d{axis} [µm]"] = [f"{v:.1f}".replace(".", ",") for v in sim[f"E_{axis}"][probed]]
    return temp, disp


def joined(sim: pd.DataFrame) -> pd.DataFrame:
    """The run as one hand-joined file: the probe rows, the true temperatures at them."""
    rows = sim[sim["E_X"].notna()].copy()
    rows["time"] = rows["time"] - rows["time"].iloc[0]
    return rows


def write(root: Path) -> None:
    for name, sim_dir, folder in lab_matrix.simulated(root, SEEDS, simulate):
        one = root / name.replace("lathe", "joined")
        one.mkdir(parents=True, exist_ok=True)
        manifest = pd.read_csv(sim_dir / "campaigns.csv")
        for row in manifest.itertuples(index=False):
            sim = pd.read_csv(sim_dir / row.file)
            temp, disp = lab_files(sim, pd.Timestamp(row.start), row.campaign)
            temp.to_csv(folder / f"{row.campaign}_temp.csv", index=False)
            disp.to_csv(folder / f"{row.campaign}_disp.csv", index=False, sep=";")
            joined(sim).to_csv(one / f"{row.campaign}.csv", index=False)
        print(json.dumps({"wrote": name, "runs": list(manifest["campaign"])}), flush=True)


def same_rows(root: Path) -> None:
    """``same_a`` / ``same_b`` (added after the first matrix, see Measured): the hand-joined runs
    cut to the rows the two loggers share (calibration without its 07:00 row, production
    without its last 30 min), so that the join alone differs."""
    for name in SEEDS:
        sim_dir, one = root / "sim" / name, root / name.replace("lathe", "same")
        one.mkdir(parents=True, exist_ok=True)
        for row in pd.read_csv(sim_dir / "campaigns.csv").itertuples(index=False):
            sim = pd.read_csv(sim_dir / row.file)
            if row.campaign == "calibration":
                sim = sim[sim["time"] >= LATE_DAQ_S]
            else:
                sim = sim[sim["time"] <= sim["time"].iloc[-1] - EARLY_STOP_S]
            joined(sim.reset_index(drop=True)).to_csv(one / f"{row.campaign}.csv", index=False)


def initialised(root: Path, rest: list) -> None:
    """``thermocomp init`` of a record's folder with the overrides given (one try)."""
    name, extra = rest[0], rest[1:]
    lab_matrix.project(root)
    out = root / f"init-{name}"
    if out.exists():
        shutil.rmtree(out)
    rc, said, cpu = lab_matrix.stage("init", str(root / name), *extra, f"out={out}")
    print(json.dumps({"init": name, "extra": extra, "rc": rc, "said": said[:600],
                      "cpu": round(cpu, 2)}), flush=True)


import lab_matrix  # noqa: E402  (the benches' shared matrix and steps)

FAMILIES = {k: v for k, v in lab_matrix.matrix_families().items() if k in ("mlr", "lagbank", "auto")}


def main(argv: list[str]) -> int:
    np.seterr(all="ignore")
    return lab_matrix.main(__doc__, argv, SEEDS, FAMILIES, ("plain",),
                           {"write": lambda root, rest: write(root), "init": initialised,
                            "same": lambda root, rest: same_rows(root)})


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
