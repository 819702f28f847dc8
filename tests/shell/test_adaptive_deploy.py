"""The adaptive compensator deployed: `replay` for every model family, plain and wrapped (each
family × wrapper: `make test-all`), on faulty test campaigns, the pyfunc fed hostile rows, and
the plain stream when `monitor.adaptive=false`.

The data: 9 short year-round campaigns (6 train, 3 test, an undeclared door); in the first test
campaign one sensor jumps by +50 °C at mid-campaign, in the second another one drops out (empty
cells) from mid-campaign to the end; the third is healthy.
"""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest
from hydra import compose, initialize_config_dir

from conftest import cli
from covering import covering
from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.deploy.report import plain, replay_report
from thermocomp.apps.monitor import AdaptiveCompensator
from thermocomp.base.paths import conf_dir
from thermocomp.core import io
from thermocomp.shell.builders import build_compensator, deployable
from thermocomp.shell.stages.replay import replay

MODELS = ("mlr", "pcr", "arx", "arx_rf", "lstm", "lagbank")
WRAPPERS = (("none", "none"), ("cmeans", "none"), ("none", "emd"))   # (ati, denoise)
SMALL = {  # keep every fit small: the point is the plumbing, not the accuracy
    "lstm": ["model.estimator.max_epochs=2", "model.estimator.hidden_size=4", "model.estimator.chunk=16"],
    "arx_rf": ["model.estimator.forest.n_estimators=5"],
}
TOLERANCE_UM = 1e-6
JUMP_C = 50.0


def _compose(*overrides):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=list(overrides))


@pytest.fixture(scope="session")
def faulty(short_door_dataset, tmp_path_factory):
    """``(path, {"jump": (campaign, sensor, first faulty row), "dropout": (...), "healthy": id})``."""
    clean, path = short_door_dataset, tmp_path_factory.mktemp("adaptive") / "faulty"
    shutil.copytree(clean, path)
    manifest = pd.read_csv(path / "campaigns.csv")
    test = manifest[manifest["split"] == "test"]
    (jump_id, jump_file), (drop_id, drop_file) = test[["campaign", "file"]].to_numpy()[:2]
    df = pd.read_csv(path / jump_file)
    sensors = [c for c in df.columns if c.startswith("T_") and not c.startswith("T_amb")]
    k = len(df) // 2
    df.loc[k:, sensors[0]] += JUMP_C
    df.to_csv(path / jump_file, index=False)
    faults = {"jump": (jump_id, sensors[0], k)}
    df = pd.read_csv(path / drop_file)
    k = len(df) // 2
    df.loc[k:, sensors[-1]] = np.nan                 # written as empty cells
    df.to_csv(path / drop_file, index=False)
    faults["dropout"] = (drop_id, sensors[-1], k)
    faults["healthy"] = str(test["campaign"].iloc[2])
    return path, clean, faults


def _check_faults_reported(report: dict, faults: dict) -> None:
    for kind in ("jump", "dropout"):
        cid, sensor, _ = faults[kind]
        mine = [e for e in report["events"] if e["campaign"] == cid and e["sensor"] == sensor]
        assert mine and mine[0]["to"] == "excluded", (kind, report["events"][:5])
        assert ("dropout" in mine[0]["reason"] if kind == "dropout"
                else mine[0]["reason"].startswith(("jump", "out of range"))), mine[0]
        assert sensor in report["excluded_inputs"]   # the fault lasts to the campaign's end
    assert report["excluded_inputs"] == sorted(report["excluded_inputs"])


def _check_bounded(report: dict) -> None:
    for target, r in report["targets"].items():
        lo, hi = r["bound"]
        assert r["all_finite"] and r["rmse"] is not None and np.isfinite(r["rmse"]), (target, r)
        assert lo - 1e-9 <= r["streamed_range"][0] <= r["streamed_range"][1] <= hi + 1e-9, (target, r)
        assert r["max_abs_correction"] == pytest.approx(max(map(abs, r["streamed_range"])))
        # the plain stream still equals the batch prediction (up to a campaign's first gap)
        assert r["max_abs_stream_minus_batch"] <= TOLERANCE_UM, (target, r)


def _cases() -> list:
    """Every family and every wrapper (plain, ATI, EMD) in `make test` by a Latin pairing
    (covering.py); the other pairs are marked ``full``: the adaptive layer is the same for every
    wrapper (apps/deploy/adaptive.py talks to the plain stream only), and each family streams
    with each wrapper exactly as it predicts in test_replay's
    test_every_configuration_streams_exactly_as_it_predicts (its pairwise cases)."""
    return covering("the adaptive layer talks to the plain stream only, whatever wraps it",
                    model=MODELS,
                    wrapper=dict(zip(("plain", "ati_cmeans", "denoise_emd"), WRAPPERS)))


@pytest.mark.parametrize("model, wrapper", _cases())
def test_every_family_replays_faults_through_the_adaptive_compensator(faulty, tmp_path, model, wrapper):
    path, _, faults = faulty
    ati, denoise = wrapper
    cfg = _compose(f"model={model}", f"ati={ati}", f"denoise={denoise}", f"data.path={path}",
                   f"out={tmp_path}", "track=false", *SMALL.get(model, []))
    report = replay(cfg)
    assert report["adaptive"] and report["pod"]["n_modes"] >= 1
    written = json.loads((tmp_path / "replay.json").read_text())
    assert written["events"] == report["events"] and written["excluded_inputs"] == report["excluded_inputs"]
    n = sum(len(pd.read_csv(path / f"{c}.csv")) for c in report["test_campaigns"])
    assert all(r["n_samples"] == n for r in report["targets"].values())
    _check_faults_reported(report, faults)
    _check_bounded(report)


def test_the_adaptive_guard_bounds_what_the_plain_stream_lets_through(faulty):
    """On the +50 °C jump the plain stream's envelope clamp does not keep the output inside the
    training error range; the deployed (adaptive) stream does, and names the sensor."""
    path, _, faults = faulty
    cfg = _compose("model=arx", f"data.path={path}")
    ds, _ = io.read_dataset(path, {}, missing="keep")
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    streaming = StreamingCompensator.from_training(build_compensator(cfg).fit(train), train)
    adaptive = deployable(cfg, streaming, train)
    assert isinstance(adaptive, AdaptiveCompensator) and plain(adaptive) is streaming
    cid = faults["jump"][0]
    fixed = replay_report(streaming, {cid: ds.campaigns[cid]})
    guarded = replay_report(adaptive, {cid: ds.campaigns[cid]})
    assert not fixed["adaptive"] and fixed["events"] == [] and fixed["targets"]["E_X"]["bound"] is None
    assert {e["sensor"] for e in guarded["events"]} >= {faults["jump"][1]}
    _check_bounded(guarded)
    # the same plain stream is compared with batch in both reports
    for t, r in guarded["targets"].items():
        assert r["max_abs_stream_minus_batch"] == fixed["targets"][t]["max_abs_stream_minus_batch"]
    # clamping each input to its training range does not bound the output (issue 14): the plain
    # stream leaves the training error range on some target, the guarded one never does
    outside = [t for t, r in guarded["targets"].items()
               if not r["bound"][0] <= fixed["targets"][t]["streamed_range"][0]
               <= fixed["targets"][t]["streamed_range"][1] <= r["bound"][1]]
    assert outside, fixed["targets"]
    for t in outside:
        assert guarded["targets"][t]["rmse"] < fixed["targets"][t]["rmse"]


@pytest.mark.slow
def test_replay_cli_plain_stream_refuses_a_dropout_and_an_incomplete_train_split(faulty, tmp_path):
    path, clean, faults = faulty
    common = ["track=false", "model=mlr"]
    # monitor.adaptive=false: the plain stream, as today; a clean dataset replays without events
    cli("replay", *common, f"data.path={clean}", f"out={tmp_path / 'clean'}", "monitor.adaptive=false")
    report = json.loads((tmp_path / "clean" / "replay.json").read_text())
    assert report["adaptive"] is False and report["pod"] is None and report["events"] == []
    # ... and refuses the dropout (exit 2, one line naming campaign and sensor, nothing written)
    bad = cli("replay", *common, f"data.path={path}", f"out={tmp_path / 'plain'}",
              "monitor.adaptive=false", check=False)
    cid, sensor, k = faults["dropout"]
    line = bad.stderr.strip().splitlines()[-1]
    assert bad.returncode == 2 and f"{cid}.csv" in line and f"'{sensor}'" in line, bad.stderr
    assert f"row {k + 1}:" in line                # the first empty cell, 1-based data row
    assert not (tmp_path / "plain").exists()
    # a train campaign with a gap is refused, naming its file, column and row
    broken = tmp_path / "broken"
    shutil.copytree(path, broken)
    manifest = pd.read_csv(broken / "campaigns.csv")
    train_file = manifest.loc[manifest["split"] == "train", "file"].iloc[0]
    df = pd.read_csv(broken / train_file)
    df.loc[4, "T_nose"] = np.nan
    df.to_csv(broken / train_file, index=False)
    df = pd.read_csv(broken / manifest.set_index("campaign").loc[cid, "file"])   # the dropout
    bad = cli("replay", *common, f"data.path={broken}", f"out={tmp_path / 'b'}", check=False)
    assert bad.returncode == 2 and train_file in bad.stderr and "'T_nose'" in bad.stderr
    assert "row 5" in bad.stderr and not (tmp_path / "b").exists()
    # ... unless the data config repairs it, as `run` would; the test dropout still streams as NaN
    cli("replay", *common, f"data.path={broken}", f"out={tmp_path / 'r'}", "data.max_gap_samples=1")
    report = json.loads((tmp_path / "r" / "replay.json").read_text())
    n_gap = len(df) - k
    assert report["missing"] == {cid: {sensor: n_gap}}
    _check_faults_reported(report, faults)


# -- the pyfunc -------------------------------------------------------------------------------

@pytest.fixture(scope="session")
def served(faulty, tmp_path_factory):
    """An adaptive ARX compensator saved as a pyfunc folder and loaded back through MLflow."""
    import mlflow

    from thermocomp.apps.deploy.pyfunc import save_compensator

    path, _, faults = faulty
    ds, _ = io.read_dataset(path, {}, missing="keep")
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    cfg = _compose("model=arx")
    streaming = StreamingCompensator.from_training(build_compensator(cfg).fit(train), train)
    adaptive = deployable(cfg, streaming, train)
    healthy = ds.campaigns[faults["healthy"]]
    folder = save_compensator(adaptive, tmp_path_factory.mktemp("pyfunc") / "model",
                              input_example=healthy[adaptive.columns_ + ["time"]].head(3))
    return mlflow.pyfunc.load_model(str(folder)), adaptive, healthy, folder


def _within(out: pd.DataFrame, adaptive) -> bool:
    g = adaptive.guard
    y = -out[[f"C_{t[2:]}" for t in adaptive.targets_]].to_numpy(float)   # C = -Ê
    return bool(np.isfinite(y).all() and (y >= g.lo - 1e-9).all() and (y <= g.hi + 1e-9).all())


def test_pyfunc_holds_the_adaptive_compensator_and_reports_exclusions_and_events(served):
    model, adaptive, healthy, _ = served
    held = model.unwrap_python_model().streaming
    assert isinstance(held, AdaptiveCompensator) and held.monitor.names == adaptive.monitor.names
    outputs = model.metadata.get_output_schema().input_names()
    assert outputs == ["C_X", "C_Y", "C_Z", "n_clamped", "excluded_inputs", "events"]
    frame = healthy[adaptive.columns_ + ["time"]]
    got = model.predict(frame, params={"reset": True})
    adaptive.reset()
    direct = adaptive.predict(frame)
    adaptive.reset()
    np.testing.assert_allclose(got[["C_X", "C_Y", "C_Z"]].to_numpy(),
                               -direct[adaptive.targets_].to_numpy(), rtol=0, atol=1e-12)
    assert got["events"].tolist() == direct["events"].tolist()


def test_served_model_turns_hostile_rows_into_bounded_corrections_and_events(served):
    model, adaptive, healthy, _ = served
    frame = healthy[adaptive.columns_ + ["time"]].reset_index(drop=True).copy()
    sensor = adaptive.monitor.names[1]
    frame.loc[8:, sensor] = np.nan                      # a dropout to the end of the block
    frame.loc[12, "time"] = np.nan                      # a NaN time
    frame.loc[15, "time"] = frame.loc[14, "time"] - 600.0   # time going backwards
    out = model.predict(frame, params={"reset": True, "session": "hostile"})
    assert len(out) == len(frame) and _within(out, adaptive)
    events = [dict(e, row=i) for i, cell in enumerate(out["events"]) for e in json.loads(cell)]
    mine = [e for e in events if e["sensor"] == sensor]
    assert mine[0]["row"] == 8 and mine[0]["to"] == "excluded" and "dropout" in mine[0]["reason"]
    assert all(sensor in out["excluded_inputs"].iloc[i].split(",") for i in range(8, len(out)))
    assert out["excluded_inputs"].iloc[0] == ""
    times = [e for e in events if e["sensor"] == "time"]
    assert times[0]["row"] == 12 and "no finite value" in times[0]["reason"]
    assert any(e["row"] == 15 and "does not increase" in e["reason"] for e in times)
    # the plain streaming compensator refuses such a row: the adaptive one is what makes it safe
    from mlflow.exceptions import MlflowException

    from thermocomp.apps.deploy.pyfunc import CompensatorModel

    fixed = CompensatorModel(plain(adaptive))
    fixed.load_context(None)
    with pytest.raises(MlflowException, match=f"{sensor} has no finite value"):
        fixed.predict(None, frame, {"reset": True})


def _invoke(model, frame: pd.DataFrame, **params) -> pd.DataFrame:
    """What the scoring server answers to a JSON request (its own handler, without the socket);
    missing values are sent as JSON ``null``."""
    from mlflow.pyfunc.scoring_server import invocations

    split = frame.astype(object).where(frame.notna(), None).to_dict(orient="split")
    split.pop("index")
    body = json.dumps({"dataframe_split": split, "params": params}, allow_nan=False)
    resp = invocations(body, "application/json", model, model.metadata.get_input_schema())
    assert resp.status == 200, resp.response
    return pd.DataFrame(json.loads(resp.response)["predictions"])


def test_json_nulls_reach_the_served_model_as_missing_values_and_sessions_stay_apart(served):
    """Through the scoring server's request handler: a sensor sent as ``null`` gives bounded
    corrections and its exclusion; two machines' blocks interleaved in two sessions, one with
    the dropout, one healthy, each get the answers of their stream alone."""
    model, adaptive, healthy, _ = served
    frame = healthy[adaptive.columns_ + ["time"]].reset_index(drop=True)
    sensor = adaptive.monitor.names[2]
    bad = frame.copy()
    bad.loc[10:, sensor] = np.nan
    alone = {"bad": model.predict(bad, params={"session": "bad", "reset": True}),
             "good": model.predict(frame, params={"session": "good", "reset": True})}
    assert _within(alone["bad"], adaptive)
    assert sensor in alone["bad"]["excluded_inputs"].iloc[-1].split(",")
    assert not any(alone["good"]["excluded_inputs"].str.len())
    got = {"bad": [], "good": []}
    for i, start in enumerate(range(0, len(frame), 7)):
        for s, df in (("bad", bad), ("good", frame)):
            got[s].append(_invoke(model, df.iloc[start:start + 7], session=s, reset=i == 0))
    for s in alone:
        both = pd.concat(got[s], ignore_index=True)
        np.testing.assert_allclose(both[["C_X", "C_Y", "C_Z"]].to_numpy(),
                                   alone[s][["C_X", "C_Y", "C_Z"]].to_numpy(), rtol=0, atol=1e-9)
        assert both["events"].tolist() == alone[s]["events"].tolist()
        assert both["excluded_inputs"].tolist() == alone[s]["excluded_inputs"].tolist()


@pytest.mark.slow
def test_replay_of_a_saved_pyfunc_replays_what_it_holds(served, faulty, tmp_path):
    """`replay.model=<pyfunc folder>` streams the adaptive compensator inside it, not a refit."""
    _, adaptive, _, folder = served
    path, _, faults = faulty
    cli("replay", f"data.path={path}", f"out={tmp_path}", "track=false", "model=mlr",
        f"replay.model={folder}")
    report = json.loads((tmp_path / "replay.json").read_text())
    assert report["source"] == str(folder) and report["model"] == "arx" and report["adaptive"]
    assert report["pod"]["n_modes"] == adaptive.monitor.pod.n_modes_
    _check_faults_reported(report, faults)
    _check_bounded(report)
