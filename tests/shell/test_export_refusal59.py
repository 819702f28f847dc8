"""A model that does not export is refused with the way it does reach the machine (deploy59).

``export`` of an ``arx_rf`` or ``lstm`` model said only that it is not one of the linear
families (listing five), with no way on: the served model (``thermocomp serve``, ``connect``,
every route of docs/to-the-machine.md but the code) runs it, and the ATI models and ``auto``'s
blends of those families export too, which the list left out.
"""

from __future__ import annotations

import pytest

from conftest import refused
from test_export import _fitted, _make_dataset


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("refusal") / "data")


def test_a_forest_is_refused_naming_what_exports_and_the_route_that_runs_it(dataset, tmp_path,
                                                                          capsys):
    """(exportrest62: arx_rf exports, its forest as arrays; within an ATI model it does not.)"""
    pkl = _fitted(dataset, tmp_path, "arx_rf", "model.estimator.forest.n_estimators=3",
                  "ati=cmeans", "ati.estimator.n_intervals=2")
    refused(["export", f"data.path={dataset}", f"export.model={pkl}", f"out={tmp_path / 'code'}",
             "track=false"], capsys, "ARXRF is not one of the linear families",
            "their ATI models and model=auto's blends of them", "thermocomp serve, connect")
    assert not (tmp_path / "code").exists()
