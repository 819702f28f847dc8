"""Hostile streams: a total sensor dropout, a step on every sensor, and the served model's requests.

The adaptive compensator must take its sensors back once they read again (an ``excluded`` →
``ok`` event for each), report transitions only, and give a held correction for a row without
any temperature; the served model must refuse a request too big or too deep before it parses it.
"""

from __future__ import annotations

import io as text_io
import json
import sys

import numpy as np
import pandas as pd
import pytest
from hydra.utils import instantiate
from omegaconf import OmegaConf

from conftest import ROOT
from thermocomp import io
from thermocomp.cli import main
from thermocomp.compensator import Compensator
from thermocomp.deploy import StreamingCompensator
from thermocomp.deploy.pyfunc import CompensatorModel
from thermocomp.monitor import STATES, AdaptiveCompensator
from thermocomp.stages.monitor import _stream

FAST = ["track=false", "plots=none"]


@pytest.fixture(scope="session")
def deployed(default_dataset):
    """``(adaptive compensator, test campaigns)``: the default scenario's MLR behind the monitor."""
    ds, _ = io.read_dataset(default_dataset, {})
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    est = instantiate(OmegaConf.load(ROOT / "conf/model/mlr.yaml").estimator)
    comp = Compensator(est).fit(train)
    adaptive = AdaptiveCompensator.from_training(StreamingCompensator.from_training(comp, train), train)
    return adaptive, {c: ds.campaigns[c] for c in ds.ids("test")}


def _temperatures(df: pd.DataFrame) -> list[str]:
    return [c for c in df.columns if c.startswith("T_")]


def _dropout(df: pd.DataFrame, first: int, rows: int = 3) -> pd.DataFrame:
    """``df`` with every temperature missing in ``rows`` consecutive rows from ``first``."""
    df = df.copy()
    df.loc[df.index[first:first + rows], _temperatures(df)] = np.nan
    return df


def _rmse(adaptive, df: pd.DataFrame, y: np.ndarray) -> np.ndarray:
    measured = adaptive.compensator.measured({"c": df})["c"][adaptive.targets_].to_numpy(float)
    return np.sqrt(np.nanmean((measured - y) ** 2, axis=0))


def _per_row(adaptive, df: pd.DataFrame) -> tuple[list[list[dict]], np.ndarray]:
    """Each row's events and the sensor states after it, streamed from a reset."""
    adaptive.reset()
    X, t = df[adaptive.columns_].to_numpy(float), df["time"].to_numpy(float)
    events, states = [], []
    for i in range(len(X)):
        adaptive._step(X[i], t[i])
        events.append(adaptive.last_events_)
        states.append(adaptive.monitor.states)
    adaptive.reset()
    return events, np.array(states)


# -- a total dropout: every sensor comes back (item 3) --------------------------------------------

def test_every_sensor_comes_back_after_a_total_dropout_and_the_error_stays_near_fixed(deployed):
    adaptive, test = deployed
    fixed = adaptive.streaming
    cid, healthy = next(iter(test.items()))
    first = len(healthy) // 3
    df = _dropout(healthy, first)
    y_ad, events, _ = _stream(adaptive, df)
    y_fix, _, _ = _stream(fixed, df)          # holds its last correction on the missing rows
    y_ok, _, _ = _stream(adaptive, healthy)
    back = {e["sensor"] for e in events if e["from"] == "excluded" and e["to"] == "ok"}
    assert back == set(adaptive.monitor.names), events
    last = {e["sensor"]: e["to"] for e in events if e["sensor"] in adaptive.monitor.names}
    assert set(last.values()) == {"ok"}, last
    assert np.isfinite(y_ad).all()
    got, fix, ok = _rmse(adaptive, df, y_ad), _rmse(adaptive, df, y_fix), _rmse(adaptive, healthy, y_ok)
    assert (got <= 1.2 * np.minimum(fix, ok)).all(), (got, fix, ok)


def test_monitor_on_stdin_takes_the_sensors_back_after_a_total_dropout(default_dataset, tmp_path,
                                                                       monkeypatch):
    manifest = pd.read_csv(default_dataset / "campaigns.csv")
    df = pd.read_csv(default_dataset / manifest.query("split == 'test'")["file"].iloc[0])
    monkeypatch.setattr(sys, "stdin", text_io.StringIO(_dropout(df, len(df) // 3).to_csv(index=False)))
    assert main(["monitor", "monitor.input=-", f"data.path={default_dataset}", f"out={tmp_path}",
                 *FAST]) == 0
    report = json.loads((tmp_path / "monitor.json").read_text())
    back = {e["sensor"] for e in report["events"] if (e["from"], e["to"]) == ("excluded", "ok")}
    assert back == set(report["sensors"])
    for target, r in report["targets"].items():
        assert r["all_finite"] and r["rmse_adaptive"] <= 1.2 * r["rmse_fixed"], (target, r)


def test_rows_without_any_temperature_get_the_held_correction_from_the_pyfunc(deployed):
    adaptive, test = deployed
    model = CompensatorModel(adaptive)
    model.load_context(None)
    frame = next(iter(test.values()))[adaptive.columns_ + ["time"]].reset_index(drop=True)
    corrections = [c for c in model.predict(None, frame.head(1), {"reset": True}).columns
                   if c.startswith("C_")]
    before = model.predict(None, frame.iloc[1:20], {})
    blank = frame.iloc[20:23].copy()
    blank[_temperatures(blank)] = np.nan
    answers = [model.predict(None, blank.iloc[[i]], {}) for i in range(len(blank))]  # one a request
    for out in answers:
        np.testing.assert_array_equal(out[corrections].to_numpy(), before[corrections].tail(1))
    dropped = {e["sensor"] for e in json.loads(answers[0]["events"][0]) if "dropout" in e["reason"]}
    assert dropped == set(adaptive.monitor.names)
    after = model.predict(None, frame.iloc[23:], {})
    assert np.isfinite(after[corrections].to_numpy()).all()
    assert after["excluded_inputs"].iloc[-1] == ""           # every sensor back by the end


# -- the event log: transitions only, every return logged (item 4) -------------------------------

def test_a_step_on_every_sensor_logs_each_change_of_state_once_and_every_return(deployed):
    adaptive, test = deployed
    returns = 0
    for cid, healthy in list(test.items())[:3]:
        df = healthy.copy()
        df.loc[df.index[len(df) // 2:], _temperatures(df)] += 5.0
        events, states = _per_row(adaptive, df)
        flat = [json.dumps(e, sort_keys=True) for row in events for e in row]
        assert len(flat) == len(set(flat)), cid              # no event twice
        before = np.zeros(len(adaptive.monitor.names), dtype=int)
        for row, now in zip(events, states):
            for j, name in enumerate(adaptive.monitor.names):
                chain = [(e["from"], e["to"]) for e in row if e["sensor"] == name and e["to"] in STATES]
                if before[j] == now[j]:
                    assert chain == [], (cid, name, chain)
                else:   # the row's events lead from the state before it to the state after it
                    assert chain and chain[0][0] == STATES[before[j]] and chain[-1][1] == STATES[now[j]]
                    assert all(a[1] == b[0] for a, b in zip(chain, chain[1:])), chain
            returns += sum(e["to"] == "ok" and e["from"] == "excluded" for e in row)
            before = now
    assert returns > 0


def test_a_failing_adaptive_step_is_raised_not_logged_again_with_the_last_rows_events(deployed,
                                                                                      monkeypatch):
    """`monitor` held the correction of an adaptive step that raised, and logged the previous
    row's events once more for every such row (1,130 duplicates of 1,210 events)."""
    adaptive, test = deployed
    df = _dropout(next(iter(test.values())), 9, rows=1)     # row 9 has events, row 10 fails
    update = adaptive.monitor.update

    def failing(x, t):
        if t >= df["time"].iloc[10]:
            raise ValueError("a defect in the monitor")
        return update(x, t)

    monkeypatch.setattr(adaptive.monitor, "update", failing)
    with pytest.raises(ValueError, match="a defect in the monitor"):
        _stream(adaptive, df)
    assert adaptive.last_events_ == []
    monkeypatch.undo()
    adaptive.reset()
