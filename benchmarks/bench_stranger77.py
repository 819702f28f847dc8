"""A stranger's pass on a surface grinder and its logger's HDF5 file (stranger77).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger77.py write ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger77.py faults ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger77.py matrix ROOT SEED CONF

The machine is ``benchmarks/grinder77.py`` (a horizontal-spindle surface grinder, its own
lumped network and kinematics: a bed, a table on oil-fed ways, a column, a wheelhead riding it,
a motor spindle, a hydraulic unit, a 400 l coolant tank with an on/off chiller; the hall heated
on working days only; 15 sensors at 60 s, capacitive probes dZ / dY; twelve days from Monday
2027-03-01, weekend included; seeds 7746-7755 only).

``write``: the record as the lab's Python logger (h5py) writes it, one HDF5 file
``ROOT/grinder<SEED>/SG630_2027-03.h5``: a group per day (``20270301``, midnight to
midnight, local time), in each a dataset ``time`` (epoch seconds, its ``units`` attribute
``seconds since 1970-01-01 00:00:00`` as CF says) and a dataset per channel (float32, its
``units`` attribute CF's: ``degC``, ``um``, ``rpm``, ``mm``, ``1``; ``long_name``), an
``operator`` dataset of text. Quirks: 6 samples of ``table`` NaN on day 3 (a loose plug), the
logger down 5 min on day 5 (its rows missing), the sensor ``column front top`` replaced on day
9 (0.25 K off), its channel ``column front top (new)``.

``faults``: ``ROOT/fault_<kind>_<SEED>/SG630_2027-03.h5``, the file with one fault in its last
day: ``frozen`` (spindle front bearing held from row 600), ``jump`` (+2 K on column rear top
from row 700), ``drift`` (coolant tank +1 K/h from row 500), ``dropout`` (30 NaN of wheelhead
from row 800).

``matrix``: bench_stranger75's (run -> replay per family on the data config init wrote).

Measured 2026-12-03, seed 7746 (``write`` 0.5 s CPU). Before stranger77 ``thermocomp init
ROOT/grinder7746/SG630_2027-03.h5`` refused the file ("a record's file is .csv, ... .lvm, not
.h5"); with core/io/hdf5.py, "run '20270309' holds other channels than run '20270301'" (the
replaced sensor); with the runs written as one table, ``init`` alone (no key) proposed the
``data.columns`` entry joining the two channels (and, before its gap look read the shared
channels, ``data.max_edge_samples=11515``). ``matrix`` on its config (236 + 16 s CPU): test
RMSE dY / dZ (µm; 32.06 / 13.67 before) mlr 1.882 / 1.063, pcr 2.844 / 2.591, arx 1.979 /
0.980, lagbank 1.971 / 0.951, hammerstein 0.515 / 0.951, lstm 1.850 / 1.063, auto 1.184 / 0.959
(hammerstein / arx chosen), mlr ``ati=cmeans`` as mlr (one campaign of continued days, one
ambient level: one model); replay = run in every cell. Fresh draws 7747 / 7748 (``init`` with
no key; MLR 2.048 / 0.824, 0.889 / 0.810 µm): ``monitor`` no event. Faults, C, promote,
diagnose: docs/own-data.md, "A surface grinder's HDF5 logger file".
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402
from _faults import four_faults  # noqa: E402
from bench_stranger75 import matrix  # noqa: E402

FILE = "SG630_2027-03.h5"
STATES = (("wheel speed", "rpm", "rpm"), ("wheelhead Z", "z", "mm"), ("coolant pump", "grind", "1"))
PROBES = (("probe dZ", "E_dZ"), ("probe dY", "E_dY"))
REPLACED, REPLACED_DAY, OFFSET = "column front top", 9, 0.25
GAP_DAY, GAP_ROW, GAP_ROWS = 5, 610, 5
NAN_DAY, NAN_CHANNEL, NAN_ROW = 3, "table", 400
ROWS_A_DAY = 1440


def channels(seed: int) -> tuple[np.ndarray, dict[str, tuple[np.ndarray, str]]]:
    """The record's epoch seconds and channels ``name -> (values, units)`` (no quirk yet)."""
    import grinder77 as g
    r = g.simulate(seed)
    epoch = g.FIRST_DAY.timestamp() + r["t"]
    out = {name: (r["sensors"][:, j], "degC") for j, (name, _, _) in enumerate(g.SENSORS)}
    out.update({name: (r[key], unit) for name, key, unit in STATES})
    out.update({name: (np.round(r[key], 3), "um") for name, key in PROBES})
    return epoch, out


def write_file(path: Path, epoch: np.ndarray, chans: dict, fault=None) -> None:
    """The logger's HDF5 file; ``fault(name, day, values)`` alters a day's channel."""
    import grinder77 as g
    import h5py
    path.parent.mkdir(parents=True, exist_ok=True)
    with h5py.File(path, "w") as f:
        f.attrs["machine"], f.attrs["logger"] = "SG 630 surface grinder", "h5logger 2.3 (python)"
        for day, start in enumerate(g.day_starts(), start=1):
            rows = np.arange((day - 1) * ROWS_A_DAY, day * ROWS_A_DAY)
            if day == GAP_DAY:
                rows = np.delete(rows, np.arange(GAP_ROW, GAP_ROW + GAP_ROWS))
            grp = f.create_group(f"{start:%Y%m%d}")
            grp.attrs["start"] = start.isoformat()
            tds = grp.create_dataset("time", data=epoch[rows])
            tds.attrs["units"] = "seconds since 1970-01-01 00:00:00"
            for name, (values, unit) in chans.items():
                v = values[rows].astype(float)
                label = name
                if name == REPLACED and day >= REPLACED_DAY:
                    label, v = f"{name} (new)", v + OFFSET
                if name == NAN_CHANNEL and day == NAN_DAY:
                    v[NAN_ROW:NAN_ROW + 6] = np.nan
                if fault is not None:
                    v = fault(name, day, v)
                ds = grp.create_dataset(label, data=v.astype(np.float32))
                ds.attrs["units"], ds.attrs["long_name"] = unit, label
            grp.create_dataset("operator", data=np.array([b"shift A", b"shift B"]))


def write(root: str, seed: str) -> None:
    """The logger's file of seed ``seed``: ``ROOT/grinder<SEED>/SG630_2027-03.h5``."""
    epoch, chans = channels(int(seed))
    path = Path(root) / f"grinder{seed}" / FILE
    write_file(path, epoch, chans)
    print(f"wrote {path} ({epoch.size} samples)")


def faults(root: str, seed: str) -> None:
    """``ROOT/fault_<kind>_<SEED>/``: the file, its last day with one fault (docstring)."""
    import grinder77 as g
    epoch, chans = channels(int(seed))
    cases = four_faults(ROWS_A_DAY, 60.0, frozen=("spindle front bearing", 600),
                        jump=("column rear top", 700), drift=("coolant tank", 500),
                        dropout=("wheelhead", 800, 830))
    for kind, (label, change) in cases.items():
        def fault(name, day, v, label=label, change=change):
            return change(v) if name == label and day == g.DAYS else v
        path = Path(root) / f"fault_{kind}_{seed}" / FILE
        write_file(path, epoch, chans, fault)
        print(f"wrote {path}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "faults": faults, "matrix": matrix}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
