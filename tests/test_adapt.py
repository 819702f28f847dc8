"""Learning from reference measurements (issue 36 item 6): ``adapt`` against the frozen model."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import refused
from test_hostile import FAST, make_dataset
from thermocomp.compensator import Compensator
from thermocomp.deploy import StreamingCompensator
from thermocomp.deploy.adapt import ReferenceAdapter, ReferenceSchedule
from thermocomp.deploy.report import replay_report
from thermocomp.models import MLR

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
    adapt = (ReferenceAdapter(1, "bias" if method == "none" else method), ReferenceSchedule(7200.0))
    if method == "none":
        adapt[0].method = "none"
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
    adapter.update(np.array([0.0]), np.array([4.0]))
    learned = adapter.bias_.copy()
    adapter.reset()
    assert adapter.bias_ == pytest.approx(learned) and learned[0] > 0
    adapter.forget()
    assert adapter.bias_[0] == 0.0


def test_the_schedule_takes_none_at_the_start_and_one_per_period():
    schedule = ReferenceSchedule(600.0)
    due = [schedule.due(t) for t in np.arange(0, 3001, 60.0)]
    assert not due[0]
    assert [60.0 * i for i, d in enumerate(due) if d] == [600.0, 1200.0, 1800.0, 2400.0, 3000.0]


def test_replay_reports_adapt_figures(tmp_path):
    from thermocomp.cli import main

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
    from thermocomp.sim import YearRoundSpindle

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
