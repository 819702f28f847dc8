"""The diagnosed ambient law around an ATI model's ambient interaction exports (exportati60).

``diagnose ati=cmeans`` fits each ATI interval on the features ``Z`` and, with the ambient
interaction, on ``Z (A0 - 20)``: where ``Z`` holds the diagnosed ambient law's block ``x (A0 -
20)``, the interaction's half of it is ``x (A0 - 20)^2``.  The code's laws counted 1 or ``A0 -
20`` and ``export`` refused it by name; each law now counts ``(A0 - 20)`` to the power 0, 1 or 2
(``law_ambient``), and the compiled C, the Structured Text, the numpy reference and the JSON read
back equal ``replay`` to 1e-9 µm, the clamp acting."""

from __future__ import annotations

import pytest

from covering import covering
from test_export import needs_cc
from test_export_effects59 import _door
from test_export_rest60 import AMBIENT_LAW, INITIAL, STEP, _exported
from thermocomp.core.models import MLR, Hammerstein, LagBank
from thermocomp.core.models.ati import ATIRegressor


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _door(tmp_path_factory.mktemp("ati60") / "data")


@needs_cc
@pytest.mark.parametrize("base, effects", covering(
    "the four kinds of law per interval are the base's laws on the same columns, whichever base",
    base={"mlr": MLR(), "lagbank": LagBank(n_taus=2)},
    effects={"alone": [AMBIENT_LAW], "with-a-transient-and-a-step": [AMBIENT_LAW, INITIAL, STEP]}))
def test_the_ambient_law_around_an_ati_models_interaction_exports(data, tmp_path, effects, base):
    """Per interval four kinds of law: on ``x`` (power 0), the ambient law's block and the
    interaction's half on ``x`` (power 1), the interaction's half on the ambient law's block
    (power 2); ``replay`` = the code."""
    ati = ATIRegressor(base, n_intervals=2, ambient_interaction=True)
    ss = _exported(data, tmp_path, effects, base=ati)                  # refused before
    assert set(ss.law_ambient) == {0, 1, 2}
    # every interval has its (A0 - 20)^2 law
    squared = {(lo, hi) for lo, hi, p in zip(ss.law_lo, ss.law_hi, ss.law_ambient) if p == 2}
    assert len(squared) == 2


@needs_cc
@pytest.mark.parametrize("effects", [[AMBIENT_LAW], [INITIAL]], ids=["ambient-law", "transient"])
def test_a_hammerstein_base_under_the_interaction_exports(data, tmp_path, effects):
    """A Hammerstein interval's powers of its states follow the interaction (read from the
    context, not times ``A0 - 20``): its first half's law carries them; refused before."""
    ati = ATIRegressor(Hammerstein(lagbank=LagBank(n_taus=2)), n_intervals=2,
                       ambient_interaction=True)
    ss = _exported(data, tmp_path, effects, base=ati)                  # refused before
    assert ss.powers and max(ss.law_ambient) == 1 + (AMBIENT_LAW in effects)
