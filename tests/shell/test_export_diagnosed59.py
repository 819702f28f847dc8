"""A diagnosed model exports where its effects are laws the code holds (deploy59).

``thermocomp diagnose`` writes a model config (MLR and the effects it accepted, around
:class:`~thermocomp.apps.diagnose.AugmentedRegressor`) that reruns, promotes and is served like
any model; ``export`` refused every one of them, "model AugmentedRegressor is not one of the
linear families", with no way on: a diagnosis that only removed a broken sensor, or that only
added the inputs' ambient law ``x (A0 - 20)`` (the default scenario's planted ambient law), could
not reach a PLC, though the first is its base model on fewer inputs and the second what an ATI
interval with its interaction is, which the code already runs.  Now both export (the C, the ST
and the numpy reference equal ``replay``, the clamp acting); any other effect is refused naming
it and the route that runs it (the served model).
"""

from __future__ import annotations

import functools

import pytest
from sklearn.base import clone

from conftest import refused
from test_export import _compose, needs_cc
from test_export_ati57 import _levels
from test_export_auto57 import TOLERANCE_UM, _proved, deployed
from test_export_refusal59 import OwnMLR
from thermocomp.apps.deploy.export import NotExportable, state_space
from thermocomp.apps.diagnose import AugmentedRegressor
from thermocomp.core.models import MLR
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.model_store import save_model
from thermocomp.shell.source import read_streamed

AMBIENT_LAW = {"kind": "ambient_interval", "transform": "ambient_linear"}
# exportdiag59 exports the plain lag, exportrest60 its initial-state transient, around an ATI
# model too; exportati60 the ambient law around an ATI model's ambient interaction
LAG = {"kind": "dynamics", "transform": "first_order_lag", "column": "T_a", "tau_s": 3600.0,
       "initial_state": ["T_a", "T_amb"]}


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _levels(tmp_path_factory.mktemp("diagnosed") / "data")


@functools.cache
def _plain_made(data) -> tuple:
    """:func:`_plain`'s objects of ``data``, made once per dataset (read-only)."""
    _, tests, mlr = deployed(data, "model=mlr", pushed="T_a")
    cfg = _compose(f"data.path={data}", "track=false", "monitor.adaptive=false",
                   "promote.envelope.pattern=false")
    ds, train_ids, _, _ = read_streamed(cfg)
    return tests, mlr, cfg, {c: ds.campaigns[c] for c in train_ids}


def _plain(data) -> tuple:
    """``(test campaigns with T_a pushed out half-way, plain MLR's compensator, the config, the
    train campaigns)`` of ``data``, made once per dataset (ci102b: every diagnosed model of a
    module fitted this same MLR and read the same record again); callers get copies."""
    tests, mlr, cfg, train = _plain_made(data)
    return ([df.copy() for df in tests], clone(mlr), cfg,
            {c: df.copy() for c, df in train.items()})


def _diagnosed(data, effects: list, alpha=None, base=None):
    """``(stream as replay deploys it, test campaigns with T_a pushed out half-way, compensator)``
    of ``base`` (MLR) with ``effects`` for E_X, the way diagnose's written config builds it."""
    tests, mlr, cfg, train = _plain(data)
    comp = mlr.set_params(estimator=AugmentedRegressor(
        base if base is not None else MLR(), effects={"E_X": effects},
        alpha=None if alpha is None else {"E_X": alpha}))
    comp.fit(train)
    return deploy_stream(cfg, comp, train), tests, comp


@needs_cc
@pytest.mark.parametrize("effects, alpha", [([], None), ([AMBIENT_LAW], None), ([AMBIENT_LAW], 0.01)],
                         ids=["none-or-removal", "ambient-law", "ambient-law-shrunk"])
def test_a_diagnosed_model_of_laws_the_code_holds_exports_as_replay(data, tmp_path, effects, alpha):
    stream, tests, comp = _diagnosed(data, effects, alpha)
    law = state_space(stream).law_ambient                     # refused before
    assert law == ([0, 1] if effects else [0])
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


def test_another_diagnosed_effect_is_refused_naming_it_and_the_route_that_runs_it(data, tmp_path,
                                                                                  capsys):
    # exportati60 exports the ambient law around an ATI model's interaction, the last effect
    # refused: a base of no family the code holds is what a diagnosed model still refuses
    # (exportati63: arx_rf exports, its forest beside the effects' laws; exportlstm64: lstm, its
    # network reading the features the code computes: test_export_diaglstm64)
    stream, _, comp = _diagnosed(data, [AMBIENT_LAW, LAG], base=OwnMLR())
    with pytest.raises(NotExportable, match=r"model OwnMLR is not one of the linear families"):
        state_space(stream)
    pkl = save_model(comp, tmp_path / "model.pkl")
    refused(["export", f"data.path={data}", f"export.model={pkl}", f"out={tmp_path / 'code'}",
             "track=false"], capsys, "OwnMLR is not one of the linear families", "thermocomp serve")
    assert not (tmp_path / "code").exists()
