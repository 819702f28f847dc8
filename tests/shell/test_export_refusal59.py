"""A model that does not export is refused with the way it does reach the machine (deploy59).

``export`` of an ``arx_rf`` or ``lstm`` model said only that it is not one of the linear
families (listing five), with no way on: the served model (``thermocomp serve``, ``connect``,
every route of docs/to-the-machine.md but the code) runs it, and the ATI models and ``auto``'s
blends of those families export too, which the list left out.
"""

from __future__ import annotations

import pytest

from conftest import refused
from test_export import _compose, _make_dataset
from thermocomp.core.models import MLR
from thermocomp.shell.builders import build_compensator
from thermocomp.shell.model_store import save_model
from thermocomp.shell.source import read_streamed


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("refusal") / "data")


class OwnMLR(MLR):
    """A lab's own estimator (``model.estimator._target_``): the export knows the families by
    their exact type (a subclass may stream otherwise), so this MLR is a family it does not know."""


def test_a_family_the_export_does_not_know_is_refused_naming_what_exports_and_the_route(
        dataset, tmp_path, capsys):
    """(exportrest62: arx_rf exports, its forest as arrays; exportati63: within an ATI model
    too, which this refused: a family the export does not know is what is left.)"""
    cfg = _compose("model=mlr", f"data.path={dataset}", "track=false")
    ds, train_ids, _, _ = read_streamed(cfg)
    comp = build_compensator(cfg, ds=ds).set_params(estimator=OwnMLR())
    pkl = save_model(comp.fit({c: ds.campaigns[c] for c in train_ids}), tmp_path / "model.pkl")
    refused(["export", f"data.path={dataset}", f"export.model={pkl}", f"out={tmp_path / 'code'}",
             "track=false"], capsys, "OwnMLR is not one of the linear families",
            "their ATI models and model=auto's blends of them", "thermocomp serve, connect")
    assert not (tmp_path / "code").exists()
