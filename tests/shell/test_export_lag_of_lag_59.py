"""A lag diagnose accepted on a lag-bank base is refused at export naming it and the ways out.

``thermocomp diagnose model=lagbank`` on a Swiss lathe with a door (seed 5971, diagexport59)
accepted the door's 900 s lag for E_X and E_Y; its rerun promoted, ``export`` refused with
"the law of E_Y lags a diagnosed effect's lag (a second-order lag): the code's lags are
first-order": no effect named, no next step.  The refusal now names the effect and says the
served model runs it, or that an MLR base's code holds that lag.
"""

from __future__ import annotations

import pytest

from test_export_effects59 import LAG, _diagnosed, data  # noqa: F401  (the module's record)
from thermocomp.apps.deploy.export import NotExportable, state_space
from thermocomp.core.models import LagBank


def test_a_lag_of_a_diagnosed_lag_is_refused_naming_the_effect_and_the_ways_out(data):  # noqa: F811
    stream, _ = _diagnosed(data, [LAG], base=LagBank(n_taus=2))
    with pytest.raises(NotExportable) as refused:
        state_space(stream)
    said = str(refused.value)
    assert "signal:S_door first_order_lag(tau=600s)" in said
    assert "thermocomp serve" in said and "model=mlr" in said
