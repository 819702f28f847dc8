"""A diagnosed lstm whose only effect is the ambient law exports (diaglstm63).

``diagnose`` around an ``lstm`` base fits its network on ``[x, features]``; ``export`` refused
every such model ("a diagnosed model on lstm"), also the one whose only accepted effect is the
inputs' ambient law ``x (A0 - 20 °C)``: its network then reads ``[x, x (A0 - 20)]``, what an ATI
interval's network with the ambient interaction reads, which the code already steps
(``lstm_ambient``, exportati63).  Now that model (a sensor's removal beside it too: the base on
the inputs kept) is the lstm emitter's network reading ``[x, x (A0 - 20)]`` and its skip law's
ambient law: on test_export_effects59's door record (T_a pushed out half-way, the door missing
at a start and mid-run) the compiled C, the Structured Text and the numpy reading equal
``replay``.  (Any other effect set on an lstm base, refused here naming the effect that blocked
it, exports since exportlstm64: test_export_diaglstm64, the network's inputs each a feature of
the code, ``lstm_in`` and ``lstm_in_law``.)
"""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.base import clone

from conftest import copied_once
from test_export import _compose, checked_pack, needs_cc
from test_export_auto57 import TOLERANCE_UM, _proved, deployed
from test_export_effects59 import AMBIENT_LAW, _diagnosed, _door
from thermocomp.apps.deploy.export import state_space
from thermocomp.apps.diagnose import AugmentedRegressor
from thermocomp.apps.diagnose.diagnosis import augment
from thermocomp.core.models.lstm import LSTM
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import save_model
from thermocomp.shell.source import read_streamed


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    """test_export_effects59's door record."""
    return _door(tmp_path_factory.mktemp("diaglstm63") / "data")


def _net() -> LSTM:
    """test_export_lstm62's tiny network, kept whatever its held-out score."""
    return LSTM(max_epochs=2, hidden_size=4, chunk=16, validation_fraction=0.0)


def _with_removal(data, removed: str, with_model: bool = False):
    """``(stream, test campaigns)`` of the lstm with the ambient law and ``removed`` left out of
    the inputs, as diagnose's ``augment`` writes an accepted sensor_fault: a deep copy, fitted
    once per record and sensor (two tests read it)."""
    stream, tests, comp = _fitted_without(data, removed)
    return (stream, tests) + ((comp,) if with_model else ())


@copied_once
def _fitted_without(data, removed: str) -> tuple:
    _, tests, mlr = deployed(data, "model=mlr", pushed="T_a")
    cfg = _compose(f"data.path={data}", "track=false", "monitor.adaptive=false",
                   "promote.envelope.pattern=false")
    ds, train_ids, _, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = augment(clone(mlr).set_params(estimator=_net()), {"E_X": [AMBIENT_LAW]},
                   excluded=[removed], inputs=list(mlr.inputs_))
    comp.fit(train)
    tests = [df.copy() for df in tests]
    tests[0].loc[[0, 1], "S_door"] = np.nan
    tests[1].loc[[20, 21, 22], "S_door"] = np.nan
    return deploy_stream(cfg, comp, train), tests, comp


def _the_net_reads_x_and_its_ambient_law(ss, n_read: int) -> None:
    """One network over ``[x, x (A0 - 20)]`` (``n_read`` inputs, each twice), taking the factor
    of its skip law's own law (no ambient power), the second half the ambient law's."""
    [sources], [laws] = ss.lstm_in, ss.lstm_in_law
    assert ss.lstm_target == [0] and len(sources) == 2 * n_read
    assert sources[:n_read] == sources[n_read:] and all(0 <= s < len(ss.inputs) for s in sources)
    assert [ss.law_ambient[r] for r in laws] == [0] * n_read + [1] * n_read
    assert laws[0] == ss.lstm_law[0] and ss.lstm_width == max(2 * n_read, 4)
    assert ss.clamp_outright == [1]          # no step gain: clamped outright, as streamed


@needs_cc
def test_a_diagnosed_lstm_with_the_ambient_law_alone_streams_as_replay(data, tmp_path):
    stream, tests = _diagnosed(data, [AMBIENT_LAW], base=_net())
    [(_, est, _)] = stream._plan
    assert isinstance(est, AugmentedRegressor) and type(est.estimator_) is LSTM
    ss = state_space(stream)                                  # refused before
    _the_net_reads_x_and_its_ambient_law(ss, len(stream.columns_))
    assert "ambient_interval" in ss.provenance["laws"]["E_X"]
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


@needs_cc
def test_and_with_a_sensors_removal_beside_it(data, tmp_path):
    stream, tests = _with_removal(data, "T_b")
    assert "T_b" not in stream.columns_
    ss = state_space(stream)                                  # refused before
    _the_net_reads_x_and_its_ambient_law(ss, len(stream.columns_))
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


@needs_cc
def test_the_export_commands_check_pack_passes(data, tmp_path):
    """``thermocomp export`` of the saved model (the removal and the ambient law): its pack,
    run on the compiled ``stream``, passes."""
    _, _, comp = _with_removal(data, "T_b", with_model=True)
    pkl = save_model(comp, tmp_path / "model.pkl")
    out = tmp_path / "code"
    assert main(["export", f"data.path={data}", f"export.model={pkl}", "export.format=c",
                 f"out={out}", "track=false"]) == 0               # refused before
    assert "stream: check passed" in checked_pack(out)


# (every other effect set on an lstm base, refused here naming the effect that blocked it, and
# the ambient law around an ATI lstm's interaction, export since exportlstm64:
# test_export_diaglstm64.py)
