"""Learning from reference measurements (issue 36 item 6): ``adapt`` against the frozen model."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import refused
from test_hostile import FAST, make_dataset
from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.deploy.adapt import Adaptation, ReferenceAdapter, ReferenceSchedule
from thermocomp.apps.deploy.report import replay_report
from thermocomp.apps.deploy.streaming import replay
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR

PERIOD_S, HOURS = 300.0, 8.0
TRAIN_GAIN = 3.0              # µm/K on T_0 of the training machine


def campaign(rng, gain: float, ambient: float) -> pd.DataFrame:
    """An 8 h campaign, heating then cooling, whose error is ``gain`` µm/K on T_0's rise."""
    t = np.arange(int(HOURS * 3600 / PERIOD_S)) * PERIOD_S
    peak = 1 - np.exp(-5 / 1.5)          # heated 5 h (tau 1.5 h), then cooling
    heat = np.where(t < 5 * 3600, 1 - np.exp(-t / 5400), peak * np.exp(-(t - 5 * 3600) / 5400))
    t0 = ambient + 6 * heat + rng.normal(0, 0.03, len(t))
    t1 = ambient + 0.5 * np.sin(t / 9000) + rng.normal(0, 0.03, len(t))
    e = gain * (t0 - t0[0]) - 1.0 * (t1 - t1[0]) + rng.normal(0, 0.3, len(t))
    return pd.DataFrame({"time": t, "T_0": t0, "T_amb": t1, "E_X": e})


@pytest.fixture(scope="module")
def streams():
    """The frozen stream of MLR fitted on four campaigns, and test campaigns of the same machine
    and of the machine aged (gain +30 % .. +60 % over the series)."""
    rng = np.random.default_rng(0)
    train = {f"K{i}": campaign(rng, TRAIN_GAIN, 18 + i) for i in range(4)}
    stream = StreamingCompensator.from_training(Compensator(MLR()).fit(train), train)
    same = {f"T{i}": campaign(rng, TRAIN_GAIN, 19 + 0.5 * i) for i in range(6)}
    aged = {f"T{i}": campaign(rng, TRAIN_GAIN * (1.3 + 0.06 * i), 19 + 0.5 * i) for i in range(6)}
    return stream, same, aged


def rmse(stream, test, method: str) -> tuple[float, dict]:
    adapt = Adaptation(ReferenceAdapter(1, method), ReferenceSchedule(7200.0))
    report = replay_report(stream, test, adapt=adapt)["targets"]["E_X"]
    return report["rmse"], report["adapt"]


def test_adapt_recovers_a_change_of_law_and_costs_nothing_where_nothing_changed(streams):
    stream, same, aged = streams
    frozen_aged, _ = rmse(stream, aged, "none")
    adapted_aged, info = rmse(stream, aged, "bias")
    assert info["n_references"] == 6 * 3           # at 2, 4 and 6 h of each 8 h campaign
    assert info["rmse_frozen"] == pytest.approx(frozen_aged)
    assert adapted_aged <= 0.7 * frozen_aged        # >= 30 % lower after the change of law
    frozen_same, _ = rmse(stream, same, "none")
    adapted_same, _ = rmse(stream, same, "bias")
    assert adapted_same <= 1.05 * frozen_same       # <= 5 % cost where nothing changed


def test_the_frozen_model_is_what_adapt_none_streams(streams):
    stream, _, aged = streams
    plain = replay_report(stream, aged)["targets"]["E_X"]["rmse"]
    assert rmse(stream, aged, "none")[0] == pytest.approx(plain)


@pytest.mark.parametrize("method", ["bias", "rls"])
def test_a_wild_reference_moves_the_correction_within_the_bounds(method):
    adapter = ReferenceAdapter(2, method, forgetting=0.5, max_gain_change=0.2, max_bias_um=5.0)
    for _ in range(20):
        adapter.update(np.array([10.0, -3.0]), np.array([1e6, -1e6]))
    assert np.all(np.abs(adapter.bias_) <= 5.0) and np.all(np.abs(adapter.gain_ - 1) <= 0.2)
    y = np.array([40.0, -40.0])
    assert np.all(np.abs(adapter.apply(y) - y) <= 0.2 * 40.0 + 5.0)
    adapter.update(np.array([np.nan, 1.0]), np.array([1.0, np.nan]))   # nothing to learn from
    assert np.all(np.isfinite(adapter.apply(y)))


def test_what_is_learned_survives_a_new_campaign_until_forgotten():
    adapter = ReferenceAdapter(1, "bias")
    adaptation = Adaptation(adapter, ReferenceSchedule(600.0))
    adaptation.correct(np.zeros((12, 1)), np.arange(12) * 60.0, np.full((12, 1), 4.0))
    learned = adapter.bias_.copy()
    adaptation.start()
    assert adapter.bias_ == pytest.approx(learned) and learned[0] > 0
    assert adapter.n_references_ == 1          # at 600 s only
    adapter.forget()
    assert adapter.bias_[0] == 0.0


def test_the_schedule_takes_none_at_the_start_and_one_per_period():
    schedule = ReferenceSchedule(600.0)
    due = [schedule.due(t) for t in np.arange(0, 3001, 60.0)]
    assert not due[0]
    assert [60.0 * i for i, d in enumerate(due) if d] == [600.0, 1200.0, 1800.0, 2400.0, 3000.0]


def test_replay_reports_adapt_figures(tmp_path):
    from thermocomp.shell.cli import main

    data = make_dataset(tmp_path / "ds", rows=200)
    out = tmp_path / "out"
    assert main(["replay", *FAST, f"data.path={data}", f"out={out}", "adapt.method=bias",
                 "adapt.every_s=1800"]) == 0
    figures = json.loads(Path(out / "replay.json").read_text())["targets"]["E_X"]["adapt"]
    assert figures["method"] == "bias" and figures["n_references"] == 6
    assert set(figures) == {"method", "rmse_frozen", "gain", "bias_um", "n_references"}


@pytest.mark.parametrize("key, value, says", [
    ("adapt.method", "kalman", "adapt.method='kalman': must be one of"),
    ("adapt.forgetting", "0", "adapt.forgetting=0: must be a number in (0, 1]"),
    ("adapt.every_s", "-5", "adapt.every_s=-5: must be"),
    ("adapt.max_gain_change", "1", "adapt.max_gain_change=1: must be a number in [0, 1)")])
def test_bad_adapt_settings_are_refused_in_one_line(tmp_path, capsys, key, value, says):
    data = make_dataset(tmp_path / "ds")
    refused(["replay", *FAST, f"data.path={data}", f"out={tmp_path / 'out'}", f"{key}={value}"],
            capsys, says)
    assert not (tmp_path / "out" / "replay.json").exists()


def test_the_ageing_machine_changes_its_law_only_after_training():
    from thermocomp.apps.sim import YearRoundSpindle

    kw = dict(n_campaigns=6, duration_h=(3.0, 4.0), seed=0)
    new, _ = YearRoundSpindle(**kw).generate()
    aged, truth = YearRoundSpindle(effects=["ageing"], effect_params={"ageing": {"gain": 0.5}},
                                   **kw).generate()
    record = truth["undeclared_effects"][0]
    assert record["name"] == "ageing" and record["targets"] == ["E_X", "E_Y", "E_Z"]
    errors = new.columns_of("E_")
    for cid in new.ids():
        before, after = new.campaigns[cid][errors], aged.campaigns[cid][errors]
        if cid in new.ids("train"):
            pd.testing.assert_frame_equal(before, after)
        else:    # the thermal error grows (the probe noise is the same draw in both)
            grown = (after - after.iloc[0]).abs().max() - (before - before.iloc[0]).abs().max()
            assert (grown > 0).all(), cid


def test_the_served_model_learns_from_the_references_a_session_sends(streams, tmp_path):
    import mlflow

    from thermocomp.apps.deploy.pyfunc import save_compensator

    stream, _, aged = streams
    deployed = copy.deepcopy(stream)
    deployed.adapt_ = Adaptation(ReferenceAdapter(1, "bias"))      # served: no schedule
    model = mlflow.pyfunc.load_model(str(save_compensator(deployed, tmp_path / "model")))
    first, second = (aged[c][["time", "T_0", "T_amb"]] for c in ("T4", "T5"))
    refs = [aged[c]["E_X"].where(aged[c]["time"] % 7200 == 0).where(aged[c]["time"] > 0)
            for c in ("T4", "T5")]

    def served(frame, session, reset=True, measured=None):
        block = frame if measured is None else frame.assign(E_X=measured)
        return model.predict(block, params={"session": session, "reset": reset})["C_X"].to_numpy()

    # what the adaptation gives on the stream's own corrections, references where the rows carry them
    expected = Adaptation(ReferenceAdapter(1, "bias"))
    want = [-expected.correct(replay(stream, f)[["E_X"]].to_numpy(), f["time"].to_numpy(),
                              r.to_numpy()[:, None])[:, 0] for f, r in zip((first, second), refs)]
    np.testing.assert_allclose(served(first, "m1", measured=refs[0]), want[0], atol=1e-9)
    np.testing.assert_allclose(served(second, "m1", measured=refs[1]), want[1], atol=1e-9)
    # a new session (another machine) starts from the model as promoted: the frozen stream
    frozen = -replay(stream, first)["E_X"].to_numpy()
    np.testing.assert_allclose(served(first, "m2"), frozen, atol=1e-9)
    assert np.abs(want[1] - (-replay(stream, second)["E_X"].to_numpy())).max() > 1.0


def test_monitor_streams_the_adapted_correction(tmp_path):
    from thermocomp.shell.cli import main

    rng = np.random.default_rng(1)
    root = tmp_path / "ds"
    root.mkdir()
    rows = []
    for i in range(6):
        cid, split = f"K{i}", "train" if i < 3 else "test"
        df = campaign(rng, TRAIN_GAIN * (1.0 if split == "train" else 1.5), 18 + i)
        df.insert(2, "T_1", df["T_0"].rolling(6, min_periods=1).mean() + rng.normal(0, 0.03, len(df)))
        df.to_csv(root / f"{cid}.csv", index=False)
        rows.append((cid, f"{cid}.csv", split))
    pd.DataFrame(rows, columns=["campaign", "file", "split"]).to_csv(root / "campaigns.csv", index=False)
    out = tmp_path / "out"
    assert main(["monitor", *FAST, f"data.path={root}", f"out={out}", "adapt.method=bias"]) == 0
    target = json.loads((out / "monitor.json").read_text())["targets"]["E_X"]
    assert target["adapt"]["n_references"] == 3 * 3
    assert target["rmse_adaptive"] < 0.7 * target["adapt"]["rmse_frozen"]


def test_rls_with_a_short_memory_is_warned_and_bias_is_not():
    """rls below forgetting 0.9 swings its gain to the bound between references (measured:
    E_X 1.30 -> 15.3 µm at 0.5): the user is told; bias, or rls with a long memory, is quiet."""
    import logging

    from omegaconf import OmegaConf

    from thermocomp.apps.deploy.adapt import from_config
    from thermocomp.base.log import logger
    from thermocomp.base.paths import conf_dir

    defaults = OmegaConf.load(conf_dir() / "adapt" / "default.yaml")
    records: list = []
    handler = logging.Handler()
    handler.emit = records.append
    logger.addHandler(handler)
    try:
        for method, forgetting in (("rls", 0.5), ("rls", 0.95), ("bias", 0.5)):
            given = OmegaConf.merge(defaults, {"method": method, "forgetting": forgetting})
            assert from_config(given, 2) is not None
    finally:
        logger.removeHandler(handler)
    warned = [r.getMessage() for r in records if r.levelno == logging.WARNING]
    assert len(warned) == 1 and "adapt.forgetting=0.5" in warned[0], warned
