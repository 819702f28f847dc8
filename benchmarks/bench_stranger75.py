"""A stranger's pass on a horizontal boring mill and its lab's run files (stranger75).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger75.py write ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger75.py faults ROOT SEED
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_stranger75.py matrix ROOT SEED CONF

The machine is ``benchmarks/hbm75.py`` (a table-type horizontal boring mill: the headstock's
height heating the column where it stands, a gearbox, an NC rotary table indexed by a torque
motor, a lube unit; 22 sensors, six runs of 22 h at 60 s; seeds 7601-7640 only).

``write``: the runs as the lab's logger PC writes them, ``ROOT/hbm<SEED>/HBM160_<yyyymmdd>.csv``
(one file a run, no ``campaigns.csv``): ``,``-separated, decimal points, UTF-8, units in
parentheses (``Quill front (°C)``, ``dZ (µm)``, ``Spindle (rpm)``, ``Y head (mm)``); quirks:
the time ``Date/Time`` on the PC's LOCAL clock without an offset (``2027-10-31 02:59:00``
written twice: Saturday's run crosses the end of daylight saving time); an ISO WEEKDAY column
``Weekday`` (1 = Monday ... 7 = Sunday, the logger's own), and under every run's rows a ``#``
BLOCK of the logger's run summary (seven lines: ``# --- run summary ---``, start, stop,
samples, the largest speed, operator, a note).

``matrix``: per family (mlr, pcr, arx, lagbank, hammerstein, lstm, auto; ``ati=cmeans`` on mlr)
``run`` on the data config ``init`` wrote (``ROOT/init/<...>.yaml``, given as CONF) and ``replay``
of its model.pkl: per target run's test RMSE, replay's RMSE, its RMSE
batch (``promote``: a tracked sweep, then ``thermocomp promote``, by hand).

Measured 2026-12-02, seed 7601 (``write``: 1.5 s CPU): ``thermocomp init ROOT/hbm7601
data.timezone=Europe/Berlin`` (the key its refusal names), no other key, then ``matrix`` on the
config it wrote: test RMSE dX / dY / dZ (µm; 4.88 / 42.29 / 122.17 before) mlr 0.315 / 0.403 /
0.746, pcr 1.007 / 1.601 / 5.433, arx 0.398 / 0.392 / 1.104, lagbank 0.536 / 0.827 / 0.460,
hammerstein 0.489 / 0.797 / 0.312, lstm 0.316 / 0.398 / 0.756, auto 0.327 / 0.388 / 0.616, mlr
``ati=cmeans`` 0.259 / 0.373 / 0.704; replay = run in every cell (<= 1.1e-13 µm, no event). Before
stranger75's mends init refused the files (the ``#`` block), then ``Y head (mm)`` (beyond
data.max_abs_error), and read ``Weekday`` as the temperature T_Weekday (mlr 0.315 / 0.404 /
0.746, auto 0.419 / 0.388 / 0.690 with it). The rest (faults, monitor, C, promote, diagnose):
docs/own-data.md, "A horizontal boring mill's run files".
"""
from __future__ import annotations

import json
import subprocess
import sys
from io import StringIO
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402

# the logger's labels of hbm75's 22 temperatures, in the machine's sensor order
LABELS = ("Air floor", "Air 3m", "Foundation", "X bed front", "X bed rear", "Saddle", "Table top",
          "Table rim", "B motor", "Column foot", "Column mid", "Column head", "Headstock L",
          "Headstock R", "Quill front", "Quill rear", "Quill sleeve", "Gearbox", "Lube tank",
          "Lube return", "Cabinet", "Coolant")
OTHERS = {"S_n_rpm": "Spindle (rpm)", "S_Y_mm": "Y head (mm)", "S_B_turn": "B indexing (-)",
          "E_X": "dX (µm)", "E_Y": "dY (µm)", "E_Z": "dZ (µm)"}


def lab_names() -> dict:
    """Contract name -> the header the lab's logger writes."""
    from hbm75 import sensors
    return {**{s.column: f"{label} (°C)" for s, label in zip(sensors(), LABELS, strict=True)},
            **OTHERS}
FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "lstm", "auto")


def _summary(k: int, stamps: list[str], frame) -> str:
    return (f"# --- run summary ---\n# start: {stamps[0]}\n# stop: {stamps[-1]}\n"
            f"# samples: {len(frame)}\n# max spindle speed: {frame.S_n_rpm.max():.0f} rpm\n"
            f"# operator: M. Keller\n# note: run {k + 1}, test mandrel 300 mm, probe checked\n")


def write(root: str, seed: str) -> None:
    """The lab's run files of seed ``seed`` in ``ROOT/hbm<SEED>/``."""
    import pandas as pd
    from hbm75 import Hbm75, local_clock, run_starts

    from thermocomp.apps.sim.scenario import write_scenario

    raw, folder = Path(root) / f"raw{seed}", Path(root) / f"hbm{seed}"
    folder.mkdir(parents=True, exist_ok=True)
    write_scenario(Hbm75(seed=int(seed)), raw)
    for k, start in enumerate(run_starts()):
        f = pd.read_csv(raw / f"run{k + 1}.csv")
        stamps = local_clock(start, f.time)
        lab = pd.DataFrame({"Date/Time": stamps,
                            "Weekday": [pd.Timestamp(s).isoweekday() for s in stamps]})
        for column, header in lab_names().items():
            lab[header] = f[column].round(3 if column.startswith("E_") else 2)
        path = folder / f"HBM160_{start:%Y%m%d}.csv"
        with open(path, "w", encoding="utf-8", newline="") as fh:
            lab.to_csv(fh, index=False, lineterminator="\r\n")
            fh.write(_summary(k, stamps, f).replace("\n", "\r\n"))
        print(f"wrote {path} ({len(lab)} rows)")


def faults(root: str, seed: str) -> None:
    """``ROOT/fault_<kind>_<SEED>.csv``: the test run's file (the last) as written, one fault in
    each: ``stuck`` (Quill front frozen from row 300), ``jump`` (+2 K on Column head from row
    600), ``drift`` (Gearbox +1 K/h from row 400), ``nan`` (20 empty cells of Headstock L)."""
    import pandas as pd

    folder = Path(root) / f"hbm{seed}"
    path = sorted(folder.glob("HBM160_*.csv"))[-1]
    text = path.read_text(encoding="utf-8")
    body, block = text[:text.index("#")], text[text.index("#"):]
    f = pd.read_csv(StringIO(body), dtype=str, keep_default_na=False)

    def shifted(column, start, by):
        out = f.copy()
        out.loc[start:, column] = (out.loc[start:, column].astype(float) + by).round(2).astype(str)
        return out
    stuck = f.copy()
    stuck.loc[300:, "Quill front (°C)"] = stuck.at[300, "Quill front (°C)"]
    nan = f.copy()
    nan.loc[700:719, "Headstock L (°C)"] = ""
    ramp = (pd.Series(range(len(f))) - 400).clip(lower=0) / 60.0
    cases = {"stuck": stuck, "jump": shifted("Column head (°C)", 600, 2.0),
             "drift": shifted("Gearbox (°C)", 0, ramp.to_numpy()), "nan": nan}
    for kind, frame in cases.items():
        out = Path(root) / f"fault_{kind}_{seed}.csv"
        out.write_text(frame.to_csv(index=False, lineterminator="\r\n") + block, encoding="utf-8")
        print(f"wrote {out}")


def matrix(root: str, seed: str, conf: str) -> None:
    """``run`` -> ``replay`` -> ``promote`` per family on the data config ``conf`` (init's)."""
    root_p, conf_p = Path(root).resolve(), Path(conf).resolve()
    common = [f"hydra.searchpath=[file://{conf_p.parent.parent}]", f"data={conf_p.stem}", "track=false"]
    cli = [sys.executable, "-m", "thermocomp"]
    cells = [(f, []) for f in FAMILIES] + [("mlr", ["ati=cmeans"])]
    for family, keys in cells:
        out = root_p / "mx" / (family + ("-ati" if keys else ""))
        ran = subprocess.run([*cli, "run", *common, f"model={family}", *keys, "plots=none",
                              f"out={out}"], capture_output=True, text=True)
        if ran.returncode:
            print(f"{out.name}: run exit {ran.returncode}: {ran.stderr[-400:]}")
            continue
        rep = subprocess.run([*cli, "replay", *common, f"replay.model={out / 'model.pkl'}",
                              f"out={out / 'replay'}"], capture_output=True, text=True)
        if rep.returncode:
            print(f"{out.name}: replay exit {rep.returncode}: {rep.stderr[-400:]}")
            continue
        scored = json.loads((out / "metrics.json").read_text())["targets"]
        streamed = json.loads((out / "replay" / "replay.json").read_text())["targets"]
        line = "; ".join(f"{t} {scored[t]['test']['rmse']:.3f} / {r['rmse']:.3f} / {r['rmse_batch']:.3f}"
                         for t, r in streamed.items())
        print(f"{out.name}: (run / replay / batch) {line}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "faults": faults, "matrix": matrix}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
