"""An ARX deployed gets its sensor fallbacks, as the same ARX under one ATI interval does (deploy87).

On audit86b's lr9032 (one record, its test part continuing its train part) ``arx`` and ``arx`` with
``ati=cmeans`` (one training campaign: one interval, the same model) predicted alike to the digit
and raised the same two events, yet replay's deployed RMSE read 2.070 against 2.096 µm: the
wrapped model had a fallback for T_table (:mod:`thermocomp.apps.deploy.fallback`) and ARX none,
since :func:`~thermocomp.core.compensator.refit_as_chosen` took an ARX's ``chosen_`` (its own
order and inputs) for model=auto's choice and refused to refit it.  Here sub71's spindle record
(``test_sensor_fallback71``): the spindle reads nothing from the test campaign's middle on.
"""

from __future__ import annotations

import numpy as np
import pytest

from test_sensor_fallback71 import N, _campaign
from thermocomp.apps.deploy import AdaptiveCompensator, StreamingCompensator
from thermocomp.apps.deploy.report import stream_rows
from thermocomp.core.compensator import Compensator, refit_as_chosen
from thermocomp.core.models import ARX
from thermocomp.core.models.ati import ATIRegressor


def _record(seed: int):
    """sub71's campaign, its first structure sensor the air's (ATI reads the initial ambient)."""
    return _campaign(seed).rename(columns={"T_0": "T_amb"})


@pytest.fixture(scope="module")
def train():
    return {f"K{i}": _record(i) for i in range(4)}


def _deployed(estimator, train):
    comp = Compensator(estimator).fit(train)
    return AdaptiveCompensator.from_training(StreamingCompensator.from_training(comp, train), train)


def test_an_arx_is_refitted_as_configured_not_refused_as_an_auto_choice(train):
    fitted = Compensator(ARX()).fit(train)
    assert hasattr(fitted.estimators_["E_Z"], "chosen_")     # its own choice, not auto's
    template = refit_as_chosen(fitted)
    assert template is not None and type(template.estimator) is ARX


def test_two_deployments_with_equal_corrections_score_equal_with_a_sensor_out(train):
    plain, wrapped = _deployed(ARX(), train), _deployed(ATIRegressor(ARX(), candidates=(1,)), train)
    assert sorted(plain.fallbacks_) == sorted(wrapped.fallbacks_) != []
    test = _record(9171)
    healthy = stream_rows(plain, test, "T").y
    np.testing.assert_array_equal(stream_rows(wrapped, test, "T").y, healthy)
    out = test.copy()
    out.loc[N // 2:, "T_spindle"] = np.nan
    a, b = stream_rows(plain, out, "T"), stream_rows(wrapped, out, "T")
    assert [e["sensor"] for e in a.events] == [e["sensor"] for e in b.events]
    assert "T_spindle" in [e["sensor"] for e in a.events if e.get("to") == "excluded"]
    np.testing.assert_allclose(a.y, b.y, atol=1e-9)
    assert np.abs(a.y[N // 2 + 1:] - healthy[N // 2 + 1:]).max() > 0     # the fallback served
