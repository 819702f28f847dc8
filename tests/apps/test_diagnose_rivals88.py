"""Issue 34, item 4: a candidate the saturation check refuses is no rival in diagnose's one-SE
choice (benchmarks/bench_diag88c.py).

On the lag_node draw 8980 (12 campaigns, 8 train) with each campaign's first error reading at its
noise-free zero and every target diagnosed, the lag of every input from the initial state gains
most in CV but can take one value per campaign a fold trains on, so it is refused; as the one-SE
choice's best rival it kept T_box1's start lag, which clears every check, out: nothing accepted.
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

from test_diagnose_few import few

from thermocomp.apps.diagnose import SearchOptions, diagnose
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
    assert taken["evidence"]["clears_bar"] and taken["evidence"]["n_features"] < best["evidence"]["n_features"]
    assert j["after"]["test_rmse"] < 0.5 * j["before"]["test_rmse"]
