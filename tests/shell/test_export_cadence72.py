"""A lag bank trained on 120 s rows and streamed 30 s rows answers for the time that passed, not
for the rows (cadence72): it steps on the training grid in every
form (the batch ``run`` predicts, the Python streams, the exported Simulator, the compiled C, the
Structured Text).  It answered for the rows: its lags' discretisation and its feedback count
samples, and the 30 s stream was far off its own 120 s answer at the same instants (rate71: a
lathe's lag bank 10.2 µm off at 60 s against 300 s).  Between grid rows it answers with its own
step from the last grid row's state, not kept (between73; it held the grid row's answer)."""

from __future__ import annotations

import copy

import numpy as np
import pandas as pd
import pytest

import test_export_first_time as first_time
from test_export import StructuredText, _compiled, _make_dataset, _streamed, needs_cc
from test_export_guard import _rows, _simulated, _st
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.apps.deploy.streaming import batch_prediction, replay
from thermocomp.core.context import keeps_memory
from thermocomp.core.models import MLR

FASTER = 4              # the stream's rows per training row
AGREE_UM = 1e-9


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("cadence") / "data")


def _deployed(dataset, adaptive: bool):
    """``(lag bank deployed as replay deploys it, its compensator, its first test campaign)``."""
    deployed, test = first_time._deployed(dataset, adaptive)
    return deployed, getattr(deployed, "streaming", deployed).compensator, test


def _faster(df: pd.DataFrame) -> pd.DataFrame:
    """The campaign sampled FASTER times as often (every column linear between its rows): the
    training rows are every FASTER-th row of it."""
    t = df["time"].to_numpy(float)
    fine = np.linspace(t[0], t[-1], (len(t) - 1) * FASTER + 1)
    return pd.DataFrame({c: np.interp(fine, t, df[c].to_numpy(float)) for c in df.columns})


def _every_row(comp):
    """``comp`` stepping on every row (no training grid): the model's own step."""
    stepped = copy.deepcopy(comp)
    stepped.grid_period_s_ = None
    return stepped


def _corrections(deployed, df) -> np.ndarray:
    return -replay(deployed, df)[deployed.targets_].to_numpy(float)


@needs_cc
@pytest.mark.parametrize("adaptive", (True, False), ids=("adaptive", "plain"))
def test_a_faster_stream_answers_as_the_training_cadence_in_every_form(dataset, tmp_path, adaptive):
    deployed, comp, test = _deployed(dataset, adaptive)
    fast = _faster(test)
    at_training = _corrections(deployed, test)
    streamed = _corrections(deployed, fast)
    # at the training instants the faster stream gives the training cadence's answer (it gave
    # another: the lags held each input over a quarter of the step they were fitted on) ...
    assert np.max(np.abs(streamed[::FASTER] - at_training)) <= AGREE_UM
    # ... and between them the model's own step from the state the last grid row committed
    # (between73): the answer of that row's stream with this row next, every row stepped
    # (it held the grid row's answer)
    between = np.flatnonzero(np.arange(len(fast)) % FASTER)
    stepped = _every_row(comp)
    for i in between[[0, 1, 2, len(between) // 2, -1]]:
        grid = i - i % FASTER
        alone = pd.concat([fast.iloc[:grid + 1:FASTER], fast.iloc[[i]]], ignore_index=True)
        own = -batch_prediction(stepped, alone)[deployed.targets_].to_numpy(float)[-1]
        assert np.max(np.abs(streamed[i] - own)) <= AGREE_UM, i
    assert np.min(np.abs(streamed[between] - at_training[between // FASTER])) > 0
    # run's batch prediction of the faster record is the stream's (replay = run)
    batch = -batch_prediction(comp, fast)[deployed.targets_].to_numpy(float)
    assert np.max(np.abs(batch - streamed)) <= AGREE_UM
    cols, ss = deployed.columns_, state_space(deployed)
    assert ss.grid_period == 120.0
    forms = {"simulator": _simulated(ss, [fast], cols),
             "c": _streamed(_compiled(deployed, tmp_path), _rows([fast], cols)).to_numpy(float),
             "st": _st(StructuredText(exported_files(deployed, "st")["compensator.st"]), [fast], cols)}
    for form, got in forms.items():
        assert np.max(np.abs(got - streamed)) <= AGREE_UM, form


def test_only_a_model_with_a_memory_is_held_between_grid_rows(dataset):
    """A static law (MLR) answers every row as it comes: nothing in it counts samples."""
    _, comp, _ = _deployed(dataset, False)
    assert comp.grid_period_s_ == 120.0
    assert all(keeps_memory(e, len(comp.selected_[t])) for t, e in comp.estimators_.items())
    static = MLR().fit(np.arange(8.0).reshape(4, 2), np.arange(4.0))
    assert not keeps_memory(static, 2)
