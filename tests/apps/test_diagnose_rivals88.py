"""Issue 34, item 4: in diagnose's one-SE choice a lag of every model input that did not clear is
the same effect as a lag of one of them that did, not another explanation that vetoes it
(benchmarks/bench_diag88c.py).

On the lag_node draw 8980 (12 campaigns, 8 train) with each campaign's first error reading at its
noise-free zero and every target diagnosed, the lag of every input from the initial state gains
most in CV but can take one value per campaign a fold trains on, so it is refused; as the one-SE
choice's best rival it kept T_box1's start lag, which clears every check, out: nothing accepted.
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


def test_a_saturated_candidate_does_not_keep_a_cleared_start_lag_out():
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


def test_a_lag_of_every_input_does_not_veto_the_lag_of_one_input_but_another_kind_does():
    base = np.random.default_rng(7).uniform(1.0, 2.0, 8)
    start = {"initial_state": ("T_box1", "T_motor1", "T_nose"), "initial_directions": 3}
    lean = _evaluation(Effect("dynamics", "first_order_lag", "T_box1", tau_s=14400.0, **start),
                       4 * base, 4, True)
    every = _evaluation(Effect("dynamics", "lowpass_inputs", tau_s=7200.0, **start), base, 12, False)
    ambient = _evaluation(Effect("ambient_interval", "ambient_linear"), base, 10, False)
    assert choose([lean], rivals=[lean, every]) == [lean]
    assert choose([lean], rivals=[lean, ambient]) == []
