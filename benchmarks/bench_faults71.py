"""Faults in the RAW exports of stop 70's three lab records, sent through every deployed form (faults71).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_faults71.py write ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_faults71.py faults ROOT [family] [record]

``bench_deploy_faults.py`` faults the contract's columns of a simulated record; stop 70's lab
records were never faulted in their deployed forms.  Here a stranger's faults are written into the
held-out run's file AS THE LAB'S SOFTWARE WRITES IT (its separator, decimal mark, encoding, header
block), the train files untouched, and the faulted folder goes through each deployed form of the
model ``run`` fitted on the healthy record (``family``: mlr by default):

* ``replay`` (``monitor.adaptive=true``, the adaptive compensator, and ``false``, the plain
  stream) and ``monitor``, as the CLI runs them with ``data.path=<faulted folder>``;
* the served model (:class:`~thermocomp.apps.deploy.pyfunc.CompensatorModel` in process,
  adaptive as promote registers it and plain, ``served_plain``; the body a ``text/csv`` request
  as the server turns it into cells, :func:`server.csv_as_split`, then MLflow's schema step, a
  refusal worded as the server words it, :func:`server.unconverted_row`): the
  test file's table from its header row (the Keysight export as written; catman's unit and
  comment rows dropped, its TABs made commas and its decimal commas points by the client; the
  lathe's temperature file as written);
* the exported C (``export.format=c``, ``cc``, ``stream < <faulted test file>``; the lathe's
  temperature file, the inputs: the probe file holds only the errors).

The records (``write``: simulated with the benches' own code and seeds, ``init`` with no override,
``run``, C ``export`` with its check pack): ``dmu_a`` (``bench_keysight70``, seed 7041, test
``dmu_run08.csv``), ``rig_a`` (``bench_catman70``, seed 7131, test ``Spindeltest_08.TXT``),
``lathe_a`` (``bench_twolog70``, seed 7043, test ``production_temp.csv`` +
``production_disp.csv``).  ``h``: the test file's middle data row.

Faults and what is expected of each (written and committed before any of them ran)
-------------------------------------------------------------------------------------
Every form, per fault, one of: ``as healthy`` (the corrections within 1e-9 µm of the healthy
file's), ``refused`` (exit 2 / HTTP 400, the message naming the file (replay, monitor), the column
and the row or line; nothing written), ``flagged`` (the monitor's or the adaptive compensator's
event names the sensor, the corrections bounded), ``bounded`` (finite, within the clamp's or the
guard's bound: max|C| no more than 2x the healthy max|C| + 10 µm), or ``SILENTLY WRONG`` (exit 0,
no word, a correction non-finite or beyond the bounded bar, or a number read as another).

``dmu_a`` (Keysight, ``,``, ``.``):

* ``alarm``: ``Alarm 101`` = 1 and ``Alarm 105`` = 2 from ``h`` on (the DAQ's alarm set, the
  readings unchanged): every form as healthy, no event (the Alarm columns are left out).
* ``ovld_probe``: ``202 <DISP_Y> (um)`` reads ``OVLD`` for 10 rows from ``h`` (a probe's
  amplifier overloaded): no input changes, so the corrections as healthy wherever the form
  computes them; replay / monitor score E_Y without those rows or refuse naming file, column,
  row and ``OVLD``; the served model and the C (no adapt: no reference is learned) as healthy or
  refused naming the column and row.
* ``unplugged``: ``105 <Spindle> (C)`` reads ``+9.90000000E+37`` from ``h`` to the end (the DAQ's
  overload value, what an open thermocouple reads): adaptive forms flagged (the spindle sensor
  excluded), plain stream and C bounded (the envelope clamp), or refused naming the row; never
  SILENTLY WRONG (a reading of 1e37 °C taken as a temperature, a correction of 1e20 µm).
* ``unplugged_listed``: the same file, the refusal's hint followed where it gives one
  (``data.missing_values=['+9.90000000E+37']`` in every form that reads the data config;
  added after the first run, before it ran): adaptive forms flagged, bounded; the plain stream
  refuses the row (exit 2 naming file, column, row), as for an empty cell.
* ``dash``: ``105 <Spindle> (C)`` reads ``---`` for 5 rows from ``h`` (init listed no mark):
  refused (exit 2 naming file, column, row, the cell and ``data.missing_values``) in replay /
  monitor; the C exit 2 naming line and input; the served model 400 naming column and row.

``rig_a`` (catman Easy, TAB, ``,``, cp1252):

* ``description_row``: catman's channel-comment row (``<TAB>MCS kapazitiv, 0-500 µm<TAB>...``)
  again at ``h`` (an export appended): left out (and said) or refused naming file and line in
  every form; never a sample.
* ``point_decimal``: ``T Lager vorn`` at ``h`` written ``21.34567`` (a point in a decimal-comma
  file, a cell typed in by hand): read as 21.34567 or refused naming the row; never 2134567.
* ``comma_garbage``: ``T Lager vorn`` at ``h`` written ``21,34,567``: refused naming file, column,
  row (C: line and input; served: 400 naming column and row).
* ``unplugged``: ``T Lager vorn`` empty from ``h`` to the end (the channel unplugged): the plain
  stream and the C refuse naming the row (exit 2), as designed; adaptive forms flagged, bounded.

``lathe_a`` (two loggers: the DAQ's ``,`` / ``.`` temperatures, the probes' ``;`` / ``,``):

* ``clock_back``: the DAQ's ``Time`` set back 1 h from ``h`` on (its PC's clock corrected): each
  form refuses naming file, column and row, or says the clock went back and streams on by the
  time rule; never a correction from rows joined to the wrong probe samples without a word.
* ``clock_ahead``: the DAQ's ``Time`` 1 h ahead from ``h`` on: a 1 h pause in the temperatures;
  the join cuts the probe rows it cannot place (said); the corrections of a static model (mlr)
  as healthy, a lag model's bounded.
* ``comma_cell``: ``Headstock [°C]`` at ``h`` written ``"20,46"`` (quoted, a decimal comma in
  the point file): read as 20.46 or refused naming the row; never 2046.
* ``unplugged``: ``Headstock [°C]`` empty from ``h`` to the end: as rig_a's.

Healthy (each record's test file as written): every form as healthy (0 change), ``monitor`` and
the adaptive forms 0 events.  Nothing is tuned on these faults: a form found SILENTLY WRONG or
refusing unclearly is fixed in src (a test that fails on the old code); the monitor's detection
thresholds are not changed here (helper mon71 changes its exclusion rules this stop).

Measured (2026-12-02, once, 2 shared cores; ``write`` 20.6 s CPU, ``faults`` mlr 43.8 s, lagbank 57.0 s)
------------------------------------------------------------------------------------------------------
Healthy: every form as healthy, 0 monitor events on all three records, both families, but the
served lag bank on ``lathe_a``'s temperature file (the DAQ's 60 s rows; the model scored on the
probes' 300 s rows): 88 guard events (``rate_limited`` / ``free``), 51 of 1441 rows changed, by
3.02 µm at most (0.16 µm RMS) against the plain stream: NOT quiet (the guard's rate from the
5-min training rows; not changed here).  As expected, in every form that reads the file
(replay adaptive and plain, monitor: exit 2 naming file, column, line and data row; served: 400
naming column and row of the block; C: exit 2 naming line and input): ``dash``, ``comma_garbage``,
``comma_cell``, ``description_row`` (``'MCS kapazitiv, 0-500 µm' is not a number``), ``ovld_probe``
(replay / monitor; the served model and the C read no probe: as healthy), ``point_decimal``
(replay / monitor refuse ``25.19000``; the C reads it as 25.19: as healthy), ``clock_back``
(replay / monitor: ``time decreases ... (row 720)``; the C says its time rule and streams on, as
healthy for mlr, 3.26 µm for lagbank), ``alarm`` (as healthy).  ``clock_ahead``: replay / monitor
warn (``the clock jumps an hour forward ... line 722``), cut 12 probe rows, score 3.82 / 2.44 µm
(mlr; healthy 2.07 / 1.40): the rest of the run is joined to temperatures an hour off.
``unplugged`` (empty cells): plain stream and C refuse naming the row; adaptive forms flag the
sensor (``excluded``) and stay bounded: rig_a test RMSE Z 1.20 -> 7.91 µm (mlr; 12.30 without
the exclusion), lagbank 1.01 -> 6.48; lathe_a 2.07 / 1.40 -> 2.07 / 1.40.

Not as expected, before the fixes (at 108935ae):

* ``unplugged`` (+9.90000000E+37, dmu_a): replay and monitor refused it with a wrong reason (``no
  temperature, in °C or kelvin (the column's median is 4.95e+37): another quantity? give its
  column a role, data.roles.state=...``); the C took it as a temperature, clamped it without a
  word (mlr: 160 µm off the healthy corrections); the served PLAIN stream likewise (mlr 160 µm;
  lagbank 1.16e+39 µm, SILENTLY WRONG); following the hint one would need,
  ``data.missing_values=['+9.90000000E+37']``, was refused (``marks that are no number``).
  Now: the reader says ``9.9e+37 °C is beyond 10000 °C, which no sensor reads ... list it ... in
  data.missing_values``; that key takes it; ``stream.c`` exits 2 (``line 730: input
  T_105_Spindle: 9.9e+37 degC is beyond 10000 degC ...``); the plain stream refuses it as a
  missing value (served: 400).  The adaptive forms flag it (excluded) but stay far off on E_Z:
  ``unplugged_listed`` test RMSE E_Z 4.84 -> 66.06 µm (mlr), 4.28 -> 36.44 (lagbank); served
  129 / 69.6 µm off at the run's end: the spindle's thermocouple is reconstructed from sensors
  that do not follow the spindle (reported, the sensor monitor is not changed here).
* ``unplugged`` (lathe_a, plain replay): ``production_temp.csv, column 'T_Headstock', data row
  145`` for a cell on that file's line 722 (the rows counted were the probe file's).  Now
  ``production_temp.csv (its rows: production_disp.csv's samples, the temperatures interpolated
  onto them), ..., data row 145: ... no finite value at <t> s from its first row``.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]

import lab_matrix  # noqa: E402
from _cli import run_commands  # noqa: E402

# record -> (bench module, test file(s), encoding, separator, description rows under the header)
RECORDS = {
    "dmu_a": ("bench_keysight70", "dmu_run08.csv", "utf-8", ",", 0),
    "rig_a": ("bench_catman70", "Spindeltest_08.TXT", "cp1252", "\t", 2),
    "lathe_a": ("bench_twolog70", "production_temp.csv", "utf-8", ",", 0),
}
HEADERS = ("Scan", "Zeit  1", "Time")       # a table's header row starts with one of these


def write(root: Path) -> None:
    """Each record simulated and exported by its bench's own code (one record each), ``init``ed
    with no override, fitted (mlr, lagbank) and exported as C with its check pack."""
    import importlib

    lab_matrix.project(root)
    for name, (module, *_) in RECORDS.items():
        bench = importlib.import_module(module)
        bench.SEEDS = {name: bench.SEEDS[name]}
        if not (root / name).exists():
            bench.write(root)
        lab_matrix.initialised(root, name, [])
        for family in ("mlr", "lagbank"):
            out = root / "out" / f"{name}-{family}-plain"
            rc, said, cpu = lab_matrix.stage("run", *lab_matrix.data_args(root, name),
                                             f"model={family}", "plots=none", f"out={out}")
            row = lab_matrix.exported(lab_matrix.data_args(root, name), str(out / "model.pkl"),
                                      root / "code" / f"{name}-{family}")
            print(json.dumps({"record": name, "family": family, "run": rc, "cpu": round(cpu, 1),
                              **row}), flush=True)


def _table(lines: list[str], sep: str, rows: int) -> tuple[int, int, list[str]]:
    """``(header line, first data line, header cells)`` of a lab's file."""
    head = next(i for i, line in enumerate(lines) if line.startswith(HEADERS))
    return head, head + 1 + rows, lines[head].split(sep)


def _set(lines, sep, rows, column: str, at: range, value) -> list[str]:
    """``lines`` with the cell of ``column`` (a header's start) on the data rows ``at`` (0-based,
    negative: from the end) replaced by ``value(old)``."""
    head, first, names = _table(lines, sep, rows)
    k = next(i for i, n in enumerate(names) if n.startswith(column))
    out = list(lines)
    for r in at:
        cells = out[first + r].split(sep)
        cells[k] = value(cells[k])
        out[first + r] = sep.join(cells)
    return out


def faults(name: str, lines: list[str]) -> dict[str, list[str] | tuple]:
    """The fault name -> the faulted test file's lines, as the lab's software would write them."""
    _, _, enc, sep, rows = RECORDS[name]
    head, first, _ = _table(lines, sep, rows)
    n = sum(1 for x in lines[first:] if x.strip())
    h = n // 2
    rest = range(h, n)

    def put(column, at, value):
        return _set(lines, sep, rows, column, at, value)
    if name == "dmu_a":
        alarmed = _set(put("Alarm 101", rest, lambda v: "1"), sep, rows, "Alarm 105", rest,
                       lambda v: "2")
        return {"alarm": alarmed,
                "ovld_probe": put("202 <DISP_Y>", range(h, h + 10), lambda v: "OVLD"),
                "unplugged": put("105 <Spindle>", rest, lambda v: "+9.90000000E+37"),
                "dash": put("105 <Spindle>", range(h, h + 5), lambda v: "---")}
    if name == "rig_a":
        return {"description_row": lines[:first + h] + [lines[head + 2]] + lines[first + h:],
                "point_decimal": put("T Lager vorn", [h], lambda v: v.replace(",", ".")),
                "comma_garbage": put("T Lager vorn", [h], lambda v: "21,34,567"),
                "unplugged": put("T Lager vorn", rest, lambda v: "")}
    def shifted(by):
        return put("Time", rest, lambda v: str(pd.Timestamp(v) + pd.Timedelta(seconds=by)))
    return {"clock_back": shifted(-3600), "clock_ahead": shifted(3600),
            "comma_cell": put("Headstock", [h], lambda v: f'"{v.replace(".", ",")}"'),
            "unplugged": put("Headstock", rest, lambda v: "")}


def _lines(root: Path, name: str) -> list[str]:
    _, test, enc, *_ = RECORDS[name]
    return (root / name / test).read_bytes().decode(enc).splitlines()


def faulted_folder(root: Path, name: str, fault: str, lines: list[str]) -> Path:
    """The record's folder with its test file replaced by ``lines`` (CRLF, its encoding)."""
    _, test, enc, *_ = RECORDS[name]
    folder = root / "faulted" / f"{name}-{fault}"
    if folder.exists():
        shutil.rmtree(folder)
    shutil.copytree(root / name, folder)
    (folder / test).write_bytes(("\r\n".join(lines) + "\r\n").encode(enc))
    return folder


def _said(rc: int, said: str) -> str:
    return f"exit {rc}: {said[:240]}"


def client_body(name: str, lines: list[str]) -> bytes:
    """The ``text/csv`` body a lab's client sends: the table from its header (catman's unit and
    comment rows dropped, TABs made commas, decimal commas points)."""
    _, _, _, sep, rows = RECORDS[name]
    head, first, _ = _table(lines, sep, rows)
    table = [lines[head], *lines[first:]]
    if sep == "\t":
        units = lines[head + 1].split(sep)
        names = [f"{n} [{u}]" if u else n for n, u in zip(lines[head].split(sep), units)]
        table = [",".join(names)] + [",".join(c.replace(",", ".") for c in x.split(sep))
                                     for x in lines[first:]]
    return "\n".join(x for x in table if x.strip()).encode()


def served(deployed, body: bytes) -> tuple[np.ndarray | None, str, int]:
    """The served model's corrections for a ``text/csv`` body: (corrections, refusal, events)."""
    from mlflow.models.utils import _enforce_schema
    from mlflow.pyfunc.scoring_server import infer_and_parse_data

    from thermocomp.apps.deploy.pyfunc import CompensatorModel, signature
    from thermocomp.apps.deploy.server import csv_as_split, unconverted_row

    split = None
    try:
        split = csv_as_split(body)
        schema = signature(deployed).inputs        # MLflow's parse and schema step, as served
        frame = _enforce_schema(infer_and_parse_data(json.loads(split), schema), schema)
        out = CompensatorModel(deployed).predict(None, frame, {"session": "m", "reset": True})
    except Exception as exc:  # noqa: BLE001  (what the server answers 400 with)
        said = (unconverted_row(str(exc), split, from_csv=True) if split else None) or str(exc)
        return None, f"400: {said[:240]}", 0
    c = out[[k for k in out.columns if k.startswith("C_")]].to_numpy(float)
    events = out["events"] if "events" in out else []
    return c, "", sum(1 for e in events if e not in ("", "[]", None))


def streamed_c(code: Path, path: Path) -> tuple[np.ndarray | None, str]:
    run = subprocess.run([str(code / "stream")], stdin=open(path, "rb"), capture_output=True)
    said = run.stderr.decode(errors="replace").strip().splitlines()
    if run.returncode:
        return None, f"exit {run.returncode}: {said[-1][:240] if said else ''}"
    rows = run.stdout.decode().splitlines()[1:]
    return np.array([[float(v) for v in r.split(",")] for r in rows]), "; ".join(said)[:240]


def _change(c: np.ndarray | None, healthy: np.ndarray, said: str) -> str:
    if c is None:
        return said
    n = min(len(c), len(healthy))
    d = np.abs(c[:n] - healthy[:n])
    text = (f"max|C| {np.max(np.abs(c)):.3g} change {np.max(d):.3g} last {np.max(d[-1]):.3g}"
            f" rows {len(c)}/{len(healthy)}")
    return text + ("" if np.isfinite(c).all() else " NON-FINITE") + (f" [{said}]" if said else "")


def deployed_model(root: Path, name: str, family: str, adaptive: str = "true"):
    from hydra import compose, initialize_config_dir

    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    with initialize_config_dir(config_dir=str(root / "tc" / "conf"), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[
            *lab_matrix.data_args(root, name), "track=false", f"monitor.adaptive={adaptive}"])
    ds, train, _, _ = read_streamed(cfg)
    return deployable_model(cfg, ds, train, str(root / "out" / f"{name}-{family}-plain" /
                                                 "model.pkl"), "replay.model")[0]


HINTED = {"unplugged_listed": ("unplugged", ["data.missing_values=['+9.90000000E+37']"])}


def run_faults(root: Path, family: str = "mlr", record: str = "") -> None:
    """Every record (or ``record``) x fault x form; a row per fault into
    ``ROOT/faults-<family>.jsonl``."""
    lab_matrix.project(root)
    out_file = root / f"faults-{family}.jsonl"
    for name, (_, test, *_rest) in RECORDS.items():
        if record and name != record:
            continue
        model = str(root / "out" / f"{name}-{family}-plain" / "model.pkl")
        deployed = deployed_model(root, name, family)
        plain_served = deployed_model(root, name, family, "false")
        code = root / "code" / f"{name}-{family}"
        lines = _lines(root, name)
        healthy_served = served(deployed, client_body(name, lines))[0]
        healthy_plain = served(plain_served, client_body(name, lines))[0]
        healthy_c = streamed_c(code, root / name / test)[0]
        cases = {"healthy": lines, **faults(name, lines)}
        cases.update({k: cases[of] for k, (of, _) in HINTED.items() if of in cases
                      and name == "dmu_a"})
        for fault, faulted in cases.items():
            folder = faulted_folder(root, name, fault, faulted)
            hint = HINTED.get(fault, ("", []))[1]
            data = [*lab_matrix.data_args(root, name), f"data.path={folder}", *hint]
            row: dict = {"record": name, "family": family, "fault": fault}
            for adaptive in ("true", "false"):
                rep = lab_matrix.replayed(data, model, root / "rep" / f"{name}-{fault}-{adaptive}",
                                          list(deployed.targets_), f"monitor.adaptive={adaptive}")
                if isinstance(rep.get("replay"), str):
                    rep["replay"] = rep["replay"].replace(str(root), "ROOT")
                row[f"replay_{'adaptive' if adaptive == 'true' else 'plain'}"] = rep
            row["monitor"] = lab_matrix.monitored(root, name, family,
                                                  root / "mon" / f"{name}-{fault}-{family}",
                                                  f"data.path={folder}", "plots=none", *hint)
            c, said, events = served(deployed, client_body(name, faulted))
            row["served"] = _change(c, healthy_served, said) + f" events {events}"
            c, said, _ = served(plain_served, client_body(name, faulted))
            row["served_plain"] = _change(c, healthy_plain, said)
            c, said = streamed_c(code, folder / test)
            row["c"] = _change(c, healthy_c, said)
            print(json.dumps(row, default=str), flush=True)
            with open(out_file, "a") as f:
                f.write(json.dumps(row, default=str) + "\n")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "write": lambda root: write(Path(root).resolve()),
        "faults": lambda root, family="mlr", record="": run_faults(Path(root).resolve(), family,
                                                                   record),
    }, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
