"""The banner names every diagnosed effect the code holds, the ambient law too (diagexport59).

On ``yearround_spindle`` (seed 5972) ``diagnose`` accepted the inputs' ambient law for E_Y and
E_Z; the exported code holds it (a second law per target, times ``A0 - 20``), but the banner
and ``provenance.laws`` said nothing of it: ``model: mlr+diagnosed`` and no line per target,
while a lag or a product is named ("with the derived inputs of ...").  A reader of the code could
not tell which target carries the law.  Every effect the code holds is now named.
"""

from __future__ import annotations

import pytest

from test_export_effects59 import AMBIENT_LAW, LAG, LOWPASS, _diagnosed, data  # noqa: F401
from thermocomp.apps.deploy.export import exported_files, state_space


@pytest.mark.parametrize("effects", [[AMBIENT_LAW], [LAG, AMBIENT_LAW], [LOWPASS]],
                         ids=["ambient", "lag+ambient", "lowpass"])
def test_the_banner_names_each_diagnosed_effect_the_code_holds(data, effects):  # noqa: F811
    stream, _ = _diagnosed(data, effects)
    said = state_space(stream).provenance["laws"]["E_X"]
    banner = exported_files(stream, "c")["compensator.c"].split("*/")[0]
    for e in effects:
        name = {"ambient_linear": "ambient_interval:", "lowpass_inputs": "of the model inputs",
                "first_order_lag": "signal:S_door"}[e["transform"]]
        assert name in said and name in banner
    if AMBIENT_LAW in effects:        # the unit as the banner writes units, not escaped
        assert "20 degC" in banner and "\\x" not in banner
    if LAG in effects:
        assert "with the derived inputs of signal:S_door first_order_lag(tau=600s)" in said
