"""A stream on a logger's clock (150000 s, ...) whose first time is missing, in every deployed form:
the Python stream (plain and adaptive), the exported Simulator, the compiled C and the Structured
Text step as the complete record does (:mod:`thermocomp.core.timerule`).  The first time
taken as 0.0 put 150120 s between the first two samples and threw the lag states a day ahead (the
exported C of a lag bank on large_mill_week: up to 1.06 µm off, decaying)."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import copied_once
from test_export import StructuredText, _compiled, _compose, _make_dataset, _streamed, needs_cc
from test_export_guard import _rows, _simulated, _st
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.apps.deploy.report import stream_rows
from thermocomp.apps.deploy.streaming import replay
from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
from thermocomp.shell.source import read_streamed

CLOCK_S = 150000.0      # the logger's clock at the record's start
AGREE_UM = 1e-9


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("first_time") / "data")


@copied_once
def _deployed(dataset, adaptive: bool):
    """``(lag bank deployed as replay deploys it, its first test campaign on the logger's clock)``:
    a copy, fitted once per dataset and ``adaptive`` (six tests read two fits; a test steps,
    resets and restores its copy)."""
    cfg = _compose(f"data.path={dataset}", "track=false", f"monitor.adaptive={str(adaptive).lower()}",
                   "model=lagbank", "model.estimator.n_taus=3")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    stream = deploy_stream(cfg, build_compensator(cfg, ds=ds).fit(train), train)
    deployed = deployable(cfg, stream, train, ds) if adaptive else stream
    test = ds.campaigns[test_ids[0]].reset_index(drop=True)
    return deployed, test.assign(time=test["time"] + CLOCK_S)


@pytest.fixture(scope="module")
def code(dataset, tmp_path_factory):
    """``code(adaptive)``: ``(the compiled C, the Structured Text)`` of that fit, built once for
    the module's two tests of it (the same fit, so the same code; gcc's -O2 build is the
    costliest step of a test)."""
    made = {}

    def built(adaptive: bool) -> tuple:
        if adaptive not in made:
            deployed, _ = _deployed(dataset, adaptive)
            folder = tmp_path_factory.mktemp("first_time_code")
            made[adaptive] = (_compiled(deployed, folder), exported_files(deployed, "st")["compensator.st"])
        return made[adaptive]
    return built


def _corrections(deployed, df) -> np.ndarray:
    return -replay(deployed, df)[deployed.targets_].to_numpy(float)


@needs_cc
@pytest.mark.parametrize("adaptive", (True, False), ids=("adaptive", "plain"))
def test_a_stream_without_its_first_time_steps_as_the_complete_record_in_every_form(
        dataset, code, adaptive):
    deployed, complete = _deployed(dataset, adaptive)
    gap = complete.copy()
    gap.loc[0, "time"] = np.nan
    expected = _corrections(deployed, complete)
    # the lags matter: the first time as 0.0 (what the forms took it as) is far off
    assert np.max(np.abs(_corrections(deployed, gap.fillna({"time": 0.0})) - expected)) > 1e-3
    cols, ss = deployed.columns_, state_space(deployed)
    assert ss.uses_time and ss.substitute_time
    forms = {"python stream": _corrections(deployed, gap),
             "simulator": _simulated(ss, [gap], cols),
             "c": _streamed(code(adaptive)[0], _rows([gap], cols)).to_numpy(float),
             "st": _st(StructuredText(code(adaptive)[1]), [gap], cols)}
    for form, got in forms.items():
        assert np.max(np.abs(got[1:] - expected[1:])) <= AGREE_UM, form


@needs_cc
@pytest.mark.parametrize("adaptive", (True, False), ids=("adaptive", "plain"))
def test_a_time_set_back_is_a_missing_time_in_every_form(dataset, code, adaptive):
    """A logger's clock set back an hour mid-campaign: every form takes that time as missing, one
    period after the previous sample, as a stream without it.  The plain stream took it as read:
    the lag bank's ``exp(-dt/tau)`` of dt = -3600 s gave ~1e12 µm of correction."""
    deployed, complete = _deployed(dataset, adaptive)
    back, missing = complete.copy(), complete.copy()
    k = len(complete) // 2
    back.loc[k, "time"] = complete.loc[k - 1, "time"] - 3600.0
    missing.loc[k, "time"] = np.nan
    expected = _corrections(deployed, missing)
    assert np.abs(expected).max() < 1e3
    cols, ss = deployed.columns_, state_space(deployed)
    forms = {"python stream": _corrections(deployed, back),
             "simulator": _simulated(ss, [back], cols),
             "c": _streamed(code(adaptive)[0], _rows([back], cols)).to_numpy(float),
             "st": _st(StructuredText(code(adaptive)[1]), [back], cols)}
    for form, got in forms.items():
        assert np.max(np.abs(got - expected)) <= AGREE_UM, form


def test_the_events_of_such_a_stream_count_from_its_first_row(dataset):
    """Its missing first time is an event at 0 s from the campaign's start, as the complete
    record's first row is (it was at -150120 s: the first time read was taken as the start)."""
    deployed, complete = _deployed(dataset, True)
    gap = complete.copy()
    gap.loc[0, "time"] = np.nan
    events = stream_rows(deployed, gap).events
    substituted = [e for e in events if e["sensor"] == "time" and e["to"] == "substituted"]
    assert [e["time"] for e in substituted] == [0.0], events
    back = [e for e in events if e["sensor"] == "time" and e["to"] == "ok"]
    assert [e["time"] for e in back] == [complete["time"][1] - complete["time"][0]], events


def test_a_stream_saved_before_the_time_rule_resumes_as_it_ran(dataset):
    """End states of an older model (promote's snapshots kept the last time used and read, no
    clock) and an adaptive compensator pickled then restore onto the stream's clock."""
    deployed, df = _deployed(dataset, True)
    X, t = df[deployed.columns_].to_numpy(float), df["time"].to_numpy(float)
    deployed.reset()
    ran = [deployed.step(x, s) for x, s in zip(X, t)][11:]
    deployed.reset()
    for x, s in zip(X[:11], t[:11]):
        deployed.step(x, s)
    snap = list(deployed._snapshot())
    _, last, read, *_ = snap[5]           # (restart66: and the time set back, none)
    stream = snap[0][:7]               # the plain stream's, without its clock
    old = (stream, *snap[1:5], last, read, *snap[6:])
    deployed.reset()
    deployed._restore(old)
    assert np.array_equal(ran, [deployed.step(x, s) for x, s in zip(X[11:], t[11:])])
    state = {k: v for k, v in deployed.__dict__.items() if k != "_clock"}
    pickled = object.__new__(type(deployed))
    pickled.__setstate__({**state, "_last_time": last, "_last_read": read})
    assert pickled._clock.snapshot()[:4] == (False, last, read, 0.0)   # (restart66: no time set back)
    assert np.isnan(pickled._clock.snapshot()[4])
