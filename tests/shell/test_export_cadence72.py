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
    stepped._grid_period_s = None      # the grid as known (deploy73: a property asked once)
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


def test_a_fit_asks_no_memory_and_the_grid_is_asked_once_when_read(dataset, monkeypatch):
    """(deploy73) A fit, CV folds included, asked every model whether it keeps a memory (a ramp
    streamed twice per target: 3.4 % of MLR's fit CPU on make run's record); the grid is now
    asked once, when first read (by a stream, the export, a prediction between grid rows), and
    is what it was; a compensator pickled by cadence72's code keeps the grid it found."""
    import pickle

    from sklearn.base import clone

    from thermocomp.core import compensator as module

    _, comp, test = _deployed(dataset, False)
    asked = []
    monkeypatch.setattr(module, "keeps_memory", lambda *a: asked.append(a) or keeps_memory(*a))
    fresh = pickle.loads(pickle.dumps(clone(comp).fit({"A": test, "B": test.assign(E_X=test["E_Z"])})))
    assert not asked                               # the fit asked none
    assert fresh.grid_period_s_ == 120.0 and asked
    n = len(asked)
    assert fresh.grid_period_s_ == 120.0 and len(asked) == n          # asked once
    state = {k: v for k, v in fresh.__dict__.items() if k not in ("_grid_period_s", "_sample_period_s")}
    older = comp.__class__.__new__(comp.__class__)
    older.__setstate__({**state, "grid_period_s_": 120.0})     # as cadence72's code pickled it
    assert older.grid_period_s_ == 120.0 and len(asked) == n


def test_a_state_saved_before_the_grid_steps_its_next_row_and_says_so(dataset, caplog):
    """(deploy73) A stream state saved before cadence72 holds no grid (its stream stepped every
    row): restored into a model with a training grid, the next row is stepped and kept, not
    answered from a committed grid state it does not know, the grid counting from it; said once
    (before: restored without a word)."""
    deployed, _, test = _deployed(dataset, False)
    fast, k = _faster(test), 2 * FASTER + 2            # row k lies between two grid rows
    deployed.reset()
    deployed.predict(fast.iloc[:k])
    saved = deployed._snapshot()
    rest = fast.iloc[k:].reset_index(drop=True)
    times = rest["time"].to_numpy(float)
    deployed.predict(rest.iloc[:1])
    assert deployed._on_grid[0] < times[0]              # uninterrupted: row k between, not stepped
    with caplog.at_level("WARNING"):
        deployed._restore(saved[:9])                    # as saved before cadence72
        deployed._restore(saved[:9])
    said = [r.getMessage() for r in caplog.records if "saved before cadence72" in r.getMessage()]
    assert len(said) == 1 and "120 s grid" in said[0] and "next sample is stepped" in said[0]
    deployed.predict(rest.iloc[:1])
    assert deployed._on_grid[0] == times[0]             # stepped, the grid from it ...
    deployed.predict(rest.iloc[1:FASTER])
    assert deployed._on_grid[0] == times[0]             # ... its rows between not stepped ...
    deployed.predict(rest.iloc[FASTER:FASTER + 1])
    assert deployed._on_grid[0] == times[FASTER]        # ... the next a period on


def test_a_record_with_one_faster_train_campaign_is_fitted_on_every_row_and_held(dataset):
    """(deploy73, benchmarks/bench_deploy73.py) A record whose one train campaign (its first 20
    min) was logged 4 times faster is fitted on every row, its grid the median step (most rows
    at 120 s), and a fast campaign is predicted on that grid, answered between from the committed
    grid state (between73; the grid kept, for stepping every row was better for one lag model
    and worse for the other there, held between: the bench's figures in its docstring)."""
    from sklearn.base import clone

    from test_export import CAMPAIGNS

    _, comp, test = _deployed(dataset, False)
    frames = {c: pd.read_csv(dataset / f"{c}.csv") for c, s in CAMPAIGNS if s == "train"}
    first = next(iter(frames))
    frames[first] = _faster(frames[first].iloc[:10])
    mixed = clone(comp).fit(frames)
    assert mixed.grid_period_s_ == 120.0
    fast = _faster(test)
    y = mixed.predict({"t": fast})["t"][mixed.targets_].to_numpy(float)
    grid = fast.iloc[::FASTER].reset_index(drop=True)
    on_grid = mixed.predict({"t": grid})["t"][mixed.targets_].to_numpy(float)
    assert np.array_equal(y[::FASTER], on_grid)         # stepped on the median step's grid
    assert not np.array_equal(y, np.repeat(on_grid, FASTER, axis=0)[:len(fast)])   # not held


def test_a_state_saved_with_the_grid_rows_output_restores_to_the_same_next_outputs(dataset):
    """(deploy74) The grid state keeps the times alone: the last stepped row's output it held,
    unread since between73, is gone; a state saved with it (``tests/data/deploy74/old_state.pkl``,
    this module's lag bank streamed 30 s rows up to row 2 * FASTER + 2 by the code of 4812ce97,
    its next 12 outputs with it) restores, and its stream goes on to the outputs that code gave;
    pickled, a stream that holds one loads alike.  To 1e-12 relative, not to the bit: the model
    is fitted here afresh, and another CPU's BLAS kernels give its coefficients other last bits
    (a machine of stop 79: 1.07e-14 µm off the pickle written on stop 74's)."""
    import pickle
    from pathlib import Path

    saved = (Path(__file__).parents[1] / "data" / "deploy74" / "old_state.pkl").read_bytes()
    old = pickle.loads(saved)
    deployed, _, test = _deployed(dataset, False)
    assert len(deployed._snapshot()[9]) == 2                # the times alone
    rest = _faster(test).iloc[old["k"]:old["k"] + old["rows"]].reset_index(drop=True)
    assert len(old["state"][9]) == 3                        # the old state holds the output
    deployed._restore(old["state"])
    np.testing.assert_allclose(deployed.predict(rest)[deployed.targets_].to_numpy(float), old["next"],
                               rtol=1e-12, atol=0)
    old = pickle.loads(saved)                               # (the stream stepped its states)
    deployed._restore(old["state"])
    deployed.__dict__["_on_grid"] = old["state"][9]         # a stream pickled with it
    again = pickle.loads(pickle.dumps(deployed))
    np.testing.assert_allclose(again.predict(rest)[again.targets_].to_numpy(float), old["next"],
                               rtol=1e-12, atol=0)
