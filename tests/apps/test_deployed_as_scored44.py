"""What is deployed equals what was scored: `run` writes model.pkl and its test RMSE, `replay`
loads that model.pkl and streams the same test rows; the exported C streams them too.

For every family x wrapper, on (a) separate test campaigns (the year-round scenario, short: its
ambient levels span 6-31 °C, so ATI has intervals) and (b) one record cut in two with
``data.test_fraction`` (a small ``long_record``, the test part continuing the train part,
``data.reference=none``).  On (a) the deployed compensator is the default one (adaptive, the
envelope clamps): nothing leaves the envelope or trips the monitor there, so its RMSE is run's.
On (b) the test part is colder than any training sample and the clamp acts (a deployment
choice, reported as ``clamped_samples``): the stream compared is the plain one, envelope off.
ATI on one record has one ambient level, one interval: (b) runs without the wrapper.

Then faults on the cut record, where a test part of one file is streamed as recorded.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from conftest import FAST, UNTRACKED, refused, thermocomp
from covering import covering

REL = 1e-9
SMALL = {  # the point is the plumbing, not the accuracy
    "lstm": ("model.estimator.max_epochs=2", "model.estimator.hidden_size=4", "model.estimator.chunk=16"),
    "arx_rf": ("model.estimator.forest.n_estimators=5", "model.estimator.state_column=S_spindle_rpm"),
    "auto": ("model.candidates=[mlr,arx,lagbank]", "model.estimator.n_folds=2"),
}
# model=auto takes ATI as a candidate of its own (ati=cmeans with it is refused)
AUTO_ATI = ("model.candidates=[mlr,ati]", "model.estimator.n_folds=2")
FAMILIES = ("mlr", "pcr", "arx", "arx_rf", "lagbank", "hammerstein", "lstm", "auto")
DEPLOYMENTS = (("none", "campaigns"), ("cmeans", "campaigns"), ("none", "record"))
# family x deployment: `make test` replays its covering set (tests/covering.py), so every family,
# both wrappers and both data layouts (checked below), and auto with ATI (its own candidate,
# AUTO_ATI); the rest is `full`.  The exported C below still runs every exportable family's record.
CELLS = covering("a family x deployment cell past the covering set", keep=[("auto", "cmeans-campaigns")],
                 model=FAMILIES, deployment={"-".join(d): d for d in DEPLOYMENTS})
KEPT = {(m, *d) for p in CELLS if not p.marks for m, d in [p.values]}
# checked at collection (a failed check fails the module)
assert {m for m, _, _ in KEPT} == set(FAMILIES) and {(w, where) for _, w, where in KEPT} == set(DEPLOYMENTS)
PLAIN = ("monitor.adaptive=false", "promote.envelope.policy=off")
# ATI's elbow refits the base model on every campaign left out for each number of intervals
# (~7 s of CPU over the cells, the forest's and the LSTM's most; tests/shell/test_ati.py tests
# it): two intervals, fixed, as in test_replay, so every cell deploys a model of two intervals
ATI_INTERVALS = ("ati.estimator.n_intervals=2",)


@pytest.fixture(scope="module")
def record(tmp_path_factory) -> Path:
    """A 3-day long_record at 5 min (865 samples) as one file: its train and test files joined
    on the record's clock."""
    root = tmp_path_factory.mktemp("record")
    thermocomp("simulate", "sim=long_record", f"data.path={root / 'sim'}", *UNTRACKED,
               "sim.generator.duration_days=3", "sim.generator.sample_period_s=300")
    manifest = pd.read_csv(root / "sim" / "campaigns.csv").set_index("campaign")
    parts = [pd.read_csv(root / "sim" / f"{c}.csv").assign(
        time=lambda d, c=c: d["time"] + manifest.loc[c, "record_offset_s"]) for c in ("R1a", "R1b")]
    path = root / "rec.csv"
    pd.concat(parts).to_csv(path, index=False)
    return path


@pytest.fixture(scope="module")
def data(short_dataset, record) -> dict:
    return {"campaigns": (f"data.path={short_dataset}",),
            "record": (f"data.path={record}", "data.test_fraction=0.1")}


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """``run`` once per cell, shared by the tests of this module: cell -> its out folder."""
    return {"root": tmp_path_factory.mktemp("runs")}


def _run(runs, data, model, ati, where) -> Path:
    key = (model, ati, where)
    if key not in runs:
        out = runs["root"] / "-".join(key)
        extra = AUTO_ATI if (model, ati) == ("auto", "cmeans") else SMALL.get(model, ())
        if ati == "cmeans" and model != "auto":
            extra += ATI_INTERVALS
        wrapper = () if (model, ati) == ("auto", "cmeans") else (f"ati={ati}",)
        thermocomp("run", *data[where], f"model={model}", *wrapper, *extra, f"out={out}", *FAST)
        runs[key] = out
    return runs[key]


def _test_rmse(out: Path) -> dict[str, float]:
    metrics = json.loads((out / "metrics.json").read_text())
    return {t: m["test"]["rmse"] for t, m in metrics["targets"].items()}


@pytest.mark.parametrize("model, deployment", CELLS)
def test_replay_of_runs_model_pkl_streams_runs_test_rmse(runs, data, tmp_path, model, deployment):
    ati, where = deployment
    out = _run(runs, data, model, ati, where)
    plain = PLAIN if where == "record" else ()
    thermocomp("replay", *data[where], f"replay.model={out / 'model.pkl'}", f"out={tmp_path}",
               *plain, *UNTRACKED)
    replay = json.loads((tmp_path / "replay.json").read_text())
    assert replay["adaptive"] is (where == "campaigns")
    assert replay["events"] == [] and replay["excluded_inputs"] == []
    for target, rmse in _test_rmse(out).items():
        r = replay["targets"][target]
        assert r["clamped_samples"] == 0, r
        assert r["rmse"] == pytest.approx(rmse, rel=REL), (target, r)
        assert r["rmse_batch"] == pytest.approx(rmse, rel=REL), (target, r)
        assert r["max_abs_stream_minus_batch"] < 1e-9, (target, r)


# -- the exported code of the cut record ------------------------------------------------------

EXPORTABLE = ("mlr", "pcr", "arx", "lagbank", "hammerstein")


@pytest.mark.skipif(shutil.which("gcc") is None, reason="no C compiler")
@pytest.mark.parametrize("model", EXPORTABLE)
def test_the_exported_c_streams_the_record_as_run_scores_its_test_part(runs, data, record, tmp_path,
                                                                         model):
    """The compiled C reads the whole record (the train rows warm it, as replay warms the stream
    of a continuing part) and its corrections on the test rows leave run's test RMSE."""
    out = _run(runs, data, model, "none", "record")
    code = tmp_path / "code"
    thermocomp("export", f"export.model={out / 'model.pkl'}", *data["record"], "export.format=c",
               *PLAIN, f"out={code}", *UNTRACKED)
    compiled(code)
    with record.open() as rows:
        streamed = subprocess.run([str(code / "stream")], stdin=rows, capture_output=True, text=True,
                                  check=True).stdout
    corrections = pd.read_csv(__import__("io").StringIO(streamed))
    measured = pd.read_csv(record)
    test_rows = json.loads((out / "ingest_report.json").read_text())["campaigns"]["rec_test"]["record_rows"]
    for target, rmse in _test_rmse(out).items():
        left = (measured[target] + corrections["C_" + target[2:]]).to_numpy()[slice(*test_rows)]
        assert np.sqrt(np.mean(left ** 2)) == pytest.approx(rmse, rel=REL), target


# -- faults in the test part of one record ------------------------------------------------------

SENSOR = "T_bed_left"


def _faulty_record(record: Path, folder: Path, test_first: int) -> Path:
    """The record with ``SENSOR`` missing for 5 samples 10 samples into its test part, and
    ``T_motor`` for 2 samples in its train part (rows 101-102 of the file)."""
    df = pd.read_csv(record)
    df.loc[test_first + 10:test_first + 14, SENSOR] = np.nan
    df.loc[100:101, "T_motor"] = np.nan
    folder.mkdir()
    df.to_csv(folder / "faulty.csv", index=False)
    return folder / "faulty.csv"


@pytest.mark.parametrize("stage", ["replay", "monitor"])
def test_a_dropout_in_the_test_part_of_a_record_streams_and_is_named_with_its_time(
        runs, data, record, tmp_path, capsys, stage):
    """The test part of one record is streamed as recorded, its dropout held or reconstructed
    and named (sensor, campaign, seconds from the part's start); the train part, repaired as
    run repairs it.  Before: the record's missing cells were counted in every part, so the
    train part was re-read as a campaign file of its own (`<record>/<record>: campaign file not
    found`, exit 2), and replay.json's `missing` gave the test part the train part's cells."""
    model = _run(runs, data, "mlr", "none", "record") / "model.pkl"
    test_first = json.loads((model.parent / "ingest_report.json").read_text()
                            )["campaigns"]["rec_test"]["record_rows"][0]
    path = _faulty_record(record, tmp_path / "data", test_first)
    args = [f"data.path={path}", "data.test_fraction=0.1", f"{stage}.model={model}", *FAST]
    refused = thermocomp(stage, *args, f"out={tmp_path / 'refused'}", check=False)
    # the train part's gap is refused as run refuses it, naming the record's row
    assert refused.returncode == 2, refused.stderr
    assert ("faulty.csv, column 'T_motor', data row 101: train campaign faulty_train: gap of 2"
            in refused.stderr)

    out = tmp_path / "out"
    printed = thermocomp(stage, *args, "data.max_gap_samples=2", f"out={out}").stdout
    report = json.loads((out / f"{stage}.json").read_text())
    first = [e for e in report["events"] if e["sensor"] == SENSOR][0]
    assert first["campaign"] == "faulty_test" and first["to"] == "excluded"
    assert "dropout" in first["reason"] and first["time"] == 10 * 300.0
    assert report["missing"] == {"faulty_test": {SENSOR: 5}}
    # the printed summary says which sensor and when, as monitor's does
    assert f"first: {SENSOR} (faulty_test, 0.83 h)" in printed.splitlines()[-1]


def test_replay_says_when_the_envelope_clamp_makes_its_rmse(runs, data, record, tmp_path):
    """The record's test part is colder than its train part: the deployed stream clamps, and
    its RMSE leaves run's.  The printed table said nothing of why (only replay.json's
    clamped_samples did).  Colder along its training pattern, the default passes it as scored
    (tests/shell/test_envelope_pattern.py): every excursion is clamped here."""
    out = _run(runs, data, "mlr", "none", "record")
    printed = thermocomp("replay", *data["record"], f"replay.model={out / 'model.pkl'}",
                         "promote.envelope.pattern=false", f"out={tmp_path}", *UNTRACKED).stdout
    r = json.loads((tmp_path / "replay.json").read_text())["targets"]["E_Z"]
    assert r["clamped_samples"] > 0 and r["rmse"] != pytest.approx(r["rmse_batch"], rel=0.01)
    assert (f"clamped: {r['clamped_samples']} of {r['n_samples']} samples had an input outside the "
            "training envelope (promote.envelope.policy=clamp)") in printed


def test_a_record_with_a_trimmed_first_row_is_cut_for_the_stream_where_run_cut_it(record, tmp_path):
    """`run` trims an incomplete first row (data.max_edge_samples=1) and cuts the rest; the
    stream reads the record as recorded and cut it before the trim, one row earlier: replay
    scored 87 rows, run 86, and their RMSEs differed (1.547 vs 1.556 µm on this record)."""
    df = pd.read_csv(record)
    df.loc[0, "T_motor"] = np.nan
    (tmp_path / "data").mkdir()
    df.to_csv(tmp_path / "data" / "edge.csv", index=False)
    args = (f"data.path={tmp_path / 'data' / 'edge.csv'}", "data.test_fraction=0.1",
            "data.max_edge_samples=1")
    thermocomp("run", *args, "model=lagbank", f"out={tmp_path / 'run'}", *FAST)
    thermocomp("replay", *args, f"replay.model={tmp_path / 'run' / 'model.pkl'}", *PLAIN,
               f"out={tmp_path / 'replay'}", *UNTRACKED)
    metrics = json.loads((tmp_path / "run" / "metrics.json").read_text())["targets"]["E_Z"]["test"]
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())["targets"]["E_Z"]
    scored = json.loads((tmp_path / "run" / "ingest_report.json").read_text())["campaigns"]
    assert replay["n_samples"] == scored["edge_test"]["rows"] == round(0.1 * (len(df) - 1))
    assert replay["rmse"] == pytest.approx(metrics["rmse"], rel=REL)



def drifted(record: Path, run_out: Path, sensor: str, folder: Path) -> Path:
    """``folder/drift.csv``: ``record`` with 1 K/h of drift on ``sensor`` from 10 samples into
    the test part that the run in ``run_out`` cut (its ingest report's row)."""
    test_first = json.loads((run_out / "ingest_report.json").read_text()
                            )["campaigns"]["rec_test"]["record_rows"][0]
    df = pd.read_csv(record)
    onset = df["time"][test_first + 10]
    df[sensor] += np.clip(df["time"] - onset, 0, None) / 3600 * 1.0
    folder.mkdir()
    df.round(2).to_csv(folder / "drift.csv", index=False)
    return folder / "drift.csv"


def test_monitor_is_silent_on_the_healthy_test_part_and_names_a_planted_drift(runs, data, record,
                                                                              tmp_path):
    """The same machine's test part: no event; with 1 K/h of drift on one sensor from 10 samples
    in, that sensor is excluded, for drift, once its drift is past the warning band (0.4 °C: 24
    min) and within 10 samples of it."""
    model = _run(runs, data, "mlr", "none", "record") / "model.pkl"
    args = ("data.test_fraction=0.1", f"monitor.model={model}", *FAST)
    thermocomp("monitor", f"data.path={record}", *args, f"out={tmp_path / 'healthy'}")
    healthy = json.loads((tmp_path / "healthy" / "monitor.json").read_text())
    assert healthy["events"] == []
    assert all(s["state_counts"]["alarm"] == s["state_counts"]["excluded"] == 0
               for s in healthy["sensors"].values())
    drifting = drifted(record, model.parent, SENSOR, tmp_path / "data")
    thermocomp("monitor", f"data.path={drifting}", *args, f"out={tmp_path / 'drift'}")
    drift = json.loads((tmp_path / "drift" / "monitor.json").read_text())
    first = [e for e in drift["events"] if e["to"] == "excluded"][0]
    assert first["sensor"] == SENSOR and first["reason"].startswith("drift"), first
    observable = 10 * 300.0 + 0.4 * 3600          # from the test part's start
    assert observable <= first["time"] <= observable + 10 * 300.0, first



def test_replay_refuses_a_test_campaign_that_dropped_a_column_naming_file_and_column(
        runs, data, short_dataset, tmp_path, capsys):
    model = _run(runs, data, "mlr", "none", "campaigns") / "model.pkl"
    copy = tmp_path / "data"
    shutil.copytree(short_dataset, copy)
    manifest = pd.read_csv(copy / "campaigns.csv")
    test_file = manifest.loc[manifest["split"] == "test", "file"].iloc[0]
    pd.read_csv(copy / test_file).drop(columns="T_motor2").to_csv(copy / test_file, index=False)
    refused(["replay", f"data.path={copy}", f"replay.model={model}", f"out={tmp_path / 'out'}",
             *UNTRACKED], capsys, f"{test_file}, column 'T_motor2'",
            "lacks a column the deployed model reads")
    assert not (tmp_path / "out" / "replay.json").exists()


# -- faults sent to the served model ------------------------------------------------------------

@pytest.fixture(scope="module")
def served(short_dataset, tmp_path_factory):
    """``(MLflow's scoring app behind thermocomp's limits, the adaptive compensator, a healthy
    test campaign)``: MLR on the short year-round data, deployed as promote deploys it."""
    import mlflow
    from hydra import compose, initialize_config_dir
    from mlflow.pyfunc import scoring_server

    from thermocomp.apps.deploy import StreamingCompensator
    from thermocomp.apps.deploy.pyfunc import save_compensator
    from thermocomp.apps.deploy.server import RequestLimits
    from thermocomp.base.paths import conf_dir
    from thermocomp.core import io
    from thermocomp.shell.builders import build_compensator, deployable

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=["model=mlr", f"data.path={short_dataset}"])
    ds, _ = io.read_dataset(short_dataset, {}, missing="keep")
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    streaming = StreamingCompensator.from_training(build_compensator(cfg).fit(train), train)
    adaptive = deployable(cfg, streaming, train)
    folder = save_compensator(adaptive, tmp_path_factory.mktemp("served") / "model")
    app = RequestLimits(scoring_server.init(mlflow.pyfunc.load_model(str(folder))), 1 << 24, 10_000)
    healthy = ds.campaigns[ds.ids("test")[0]][adaptive.columns_ + ["time"]].reset_index(drop=True)
    return app, adaptive, healthy


FAULTS = {   # what the machine sends from row k on, and the detector that must name it
    "stuck": (lambda v, k: v.where(v.index < k, v[k]), ("freeze", "drift")),
    "NaN burst": (lambda v, k: v.mask((v.index >= k) & (v.index < k + 5)), ("dropout",)),
    "spike": (lambda v, k: v + 20.0 * (v.index == k), ("jump", "out of range")),
    "unit step °C -> K": (lambda v, k: v + 273.15 * (v.index >= k), ("out of range",)),
}


@pytest.mark.parametrize("fault", FAULTS)
def test_the_served_model_names_the_faulty_sensor_and_when_and_stays_in_bounds(served, fault):
    from test_hostile_stream import _asgi, _split

    app, adaptive, healthy = served
    sensor, k = "T_motor2", len(healthy) // 2
    change, detectors = FAULTS[fault]
    frame = healthy.assign(**{sensor: change(healthy[sensor], k)})
    status, answer, _ = _asgi(app, _split(frame, reset=True, session=fault))
    assert status == 200, answer
    out = pd.DataFrame(answer["predictions"])
    y = -out[["C_" + t[2:] for t in adaptive.targets_]].to_numpy(float)
    assert np.isfinite(y).all()
    assert (y >= adaptive.guard.lo - 1e-9).all() and (y <= adaptive.guard.hi + 1e-9).all()
    events = [dict(e, row=i) for i, cell in enumerate(out["events"]) for e in json.loads(cell)]
    first = [e for e in events if e["sensor"] == sensor][0]
    assert first["to"] == "excluded" and first["reason"].startswith(detectors), first
    assert k <= first["row"] <= k + 10 and first["time"] == healthy["time"][first["row"]]
    assert not [e for e in events if e["row"] < k]          # nothing before the fault


def test_the_served_model_refuses_a_dropped_column_in_one_line_naming_it(served):
    """MLflow's app quotes the whole block before the reason of a refusal (here 3 KB on 37
    lines, the column named last): thermocomp's server answers the reason alone."""
    from test_hostile_stream import _asgi, _split

    app, _, healthy = served
    status, answer, _ = _asgi(app, _split(healthy.drop(columns="T_motor2"), reset=True))
    assert status == 400
    assert answer["message"] == "Model is missing inputs ['T_motor2']."
    assert answer["error_code"] == "INVALID_PARAMETER_VALUE"
