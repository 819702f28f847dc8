"""Issue 34, item 4: diagnose's one-SE choice when the round's best candidate did not clear and a
cleared candidate reads the same column with another kind of effect (benchmarks/bench_diag89d.py).

On the planted position draw 9265 (12 campaigns, 8 train) the position products (``interaction``
on S_pos_Y) gain most in CV but do not clear by ranks over many short blocks; S_pos_Y itself
(``signal``) clears every check, lies outside one standard error of the products, and was kept
out because it is another kind: nothing was accepted.  A leaner read of the same sensor is the
same effect; another column, or an ambient law (no column), is not.
"""

from __future__ import annotations

from functools import lru_cache

from test_diagnose_choice89 import BASE, SE, _evaluation
from test_diagnose_few import few
from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.apps.diagnose.features import Effect
from thermocomp.apps.diagnose.search import choose
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR


def _signal(column: str, mse) -> object:
    return _evaluation(Effect("signal", "raw", column), mse, 1, True)


def test_a_cleared_signal_is_the_same_effect_as_an_uncleared_product_of_its_column():
    product = _evaluation(Effect("interaction", "inputs_product", "S_pos_Y"), BASE, 10, False)
    lean = _signal("S_pos_Y", BASE + 3 * SE)                        # outside the product's band
    other = _signal("S_pos_X", BASE + 3 * SE)
    ambient = _evaluation(Effect("ambient_interval", "ambient_linear"), BASE, 10, False)
    assert choose([lean, other], rivals=[lean, other, product]) == [lean]
    assert choose([other], rivals=[other, product]) == []
    assert choose([lean], rivals=[lean, ambient]) == []


@lru_cache(maxsize=None)
def _planted_9265() -> dict:
    ds, _ = few("axis_position", 9265)
    assert len(ds.ids("train")) == 8
    d = diagnose(ds, Compensator(MLR()), targets=["E_Y"], options=SearchOptions(max_effects=2))
    return d.to_json("E_Y")


def test_the_position_sensor_is_taken_past_its_uncleared_products():
    j = _planted_9265()
    first = j["rounds"][0]
    best = max((e for e in first["evaluated"] if not e.get("control")),
               key=lambda e: e["evidence"]["cv_rmse_gain"])
    assert best["kind"] == "interaction" and not best["evidence"]["clears_bar"]
    taken = first["accepted"]
    assert taken is not None and taken["evidence"]["clears_bar"]
    assert taken["column"] == best["column"] == "S_pos_Y" and taken["kind"] != best["kind"]
    assert j["after"]["test_rmse"] < j["before"]["test_rmse"]
