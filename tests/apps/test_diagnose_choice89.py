"""Issue 34, item 4: diagnose's one-SE choice when the round's best candidate did not clear and is
a richer read of the same effect as the cleared ones (benchmarks/bench_diag89.py).

That best rival still sets the band (how well the effect can be read); a cleared read within it
is chosen as any other.  Only where no cleared read is within it does it stop keeping the effect
out: then the cleared reads of its own effect are admitted (pde66's same column; diag88c: the lag
of every model input against the lag of one of them).  With every read of the effect admitted
whatever its CV error (diag88c's rule 2 alone), the fewest regressors took T_box1's start lag
with 2 directions, outside the band, over the 3 inside it (lag:9270 E_X, test +7 %).

On the lag_node draw 8980 (12 campaigns, 8 train) with each campaign's first error reading at its
noise-free zero and every target diagnosed, the lag of every input from the initial state gains
most in CV but can take one value per campaign a fold trains on, so it is refused; no cleared
read is within its band, and T_box1's start lag, which clears every check, was kept out.
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import numpy as np

from test_diagnose_few import few
from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.apps.diagnose.cv import CVResult
from thermocomp.apps.diagnose.features import Effect
from thermocomp.apps.diagnose.search import Evaluation, choose
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR


def _first_reading_zeroed(ds):
    """``ds`` with each campaign's first error reading at its noise-free value, 0."""
    frames = {}
    for cid, frame in ds.campaigns.items():
        frame = frame.copy()
        frame.loc[frame.index[0], [c for c in frame.columns if c.startswith("E_")]] = 0.0
        frames[cid] = frame
    return replace(ds, campaigns=frames)


@lru_cache(maxsize=None)
def _lag_node_zeroed() -> dict:
    ds = _first_reading_zeroed(few("lag_node", 8980)[0])
    assert len(ds.ids("train")) == 8
    d = diagnose(ds, Compensator(MLR()), options=SearchOptions(max_effects=2))   # every target
    return d.to_json("E_X")


def test_a_saturated_read_of_every_input_does_not_keep_a_cleared_start_lag_out():
    j = _lag_node_zeroed()
    first = j["rounds"][0]
    best = max(first["evaluated"], key=lambda e: e["evidence"]["cv_rmse_gain"])
    # the round's largest CV gain: a lag of many inputs whose regressors saturate the campaigns
    assert not best["evidence"]["clears_bar"]
    assert best["evidence"]["n_features"] + 1 >= j["cv"]["units"] - 1
    taken = first["accepted"]
    assert taken is not None and taken["effect"].get("initial_state")
    assert taken["evidence"]["clears_bar"]
    assert taken["evidence"]["n_features"] < best["evidence"]["n_features"]
    assert j["after"]["test_rmse"] < 0.5 * j["before"]["test_rmse"]


def _evaluation(effect: Effect, unit_mse, n_features: int, clears: bool) -> Evaluation:
    mse = np.asarray(unit_mse, float)
    result = CVResult(np.zeros(1), np.zeros(1), float(np.sqrt(mse.mean())), mse)
    return Evaluation(effect, result.rmse, 10.0 - result.rmse, 0.0, 0.0, 0.0, clears,
                      result=result, n_features=n_features)


START = {"initial_state": ("T_box1", "T_motor1", "T_nose"), "initial_directions": 3}
BASE = np.random.default_rng(7).uniform(1.0, 2.0, 8)     # the best rival's MSE per campaign
SE = BASE.std(ddof=1) / np.sqrt(BASE.size)


def _lag(column, mse, directions: int, clears: bool = True) -> Evaluation:
    start = dict(START, initial_directions=directions)
    kind = "first_order_lag" if column else "lowpass_inputs"
    return _evaluation(Effect("dynamics", kind, column, tau_s=14400.0, **start), mse,
                       directions + (1 if column else 10), clears)


def test_a_lag_of_every_input_does_not_veto_the_lag_of_one_input_but_another_kind_does():
    lean = _lag("T_box1", BASE + 3 * SE, 3)                        # outside the rival's band
    every = _lag(None, BASE, 3, clears=False)
    ambient = _evaluation(Effect("ambient_interval", "ambient_linear"), BASE, 10, False)
    assert choose([lean], rivals=[lean, every]) == [lean]
    assert choose([lean], rivals=[lean, ambient]) == []


def test_a_cleared_read_within_the_band_is_chosen_over_a_leaner_read_outside_it():
    every = _lag(None, BASE, 3, clears=False)
    inside = _lag("T_box1", BASE + 0.5 * SE, 3)                    # 3 directions, in the band
    outside = _lag("T_box1", BASE + 3 * SE, 2)                     # 2 directions, fewer regressors
    assert choose([inside, outside], rivals=[inside, outside, every]) == [inside]
    # with no cleared read in the band both are the rival's effect: the fewest regressors first
    richer = _lag("T_box1", BASE + 2 * SE, 3)
    assert choose([richer, outside], rivals=[richer, outside, every]) == [outside, richer]
