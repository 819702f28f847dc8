"""Issue 34, item 4: diagnose's acceptance test on blocks as long as the candidates' gains take to
decorrelate, where that is shorter than the residual's (benchmarks/bench_diag91.py).

A residual that still holds the effect being tested forgets slowly: on the year-round machine with
8 train campaigns its blocks were one per campaign, the sign flips' floor 1/256 (1/512 with 9),
and family-wise no effect reached 0.01 (bench_diag89b's cause A).  The test needs its units'
GAINS near-independent, and the per-sample gain forgets faster than the residual: the round is
tested on finer blocks, every other check unchanged.
"""

from __future__ import annotations

from functools import lru_cache

from test_diagnose_few import few
from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR


@lru_cache(maxsize=None)
def _diagnosed(effect: str, seed: int, target: str, alone: bool = True) -> dict:
    """``target``'s diagnosis, alone or beside every target (the shared penalty's blocks)."""
    ds, _ = few(effect, seed)
    assert len(ds.ids("train")) == 8
    d = diagnose(ds, Compensator(MLR()), targets=[target] if alone else None,
                 options=SearchOptions(max_effects=2))
    return d.to_json(target)


def _accepted(j: dict) -> list:
    return [e for e in j["effects"] if e["accepted"]]


def test_a_position_effect_is_tested_on_its_gains_blocks_and_accepted_with_8_campaigns():
    j = _diagnosed("axis_position", 8966, "E_Y")
    first = j["rounds"][0]
    # the residual, holding the position, would give one block per campaign: the gains' are finer
    assert first["test_blocks"] > 2 * j["cv"]["units"]
    taken = first["accepted"]
    assert taken is not None and taken["kind"] == "interaction"
    assert "S_pos_Y" in str(taken["column"]) + str(taken["transform"])
    assert taken["evidence"]["p_value_family"] <= 0.01
    assert not j["control_ever_clears_bar"]
    assert j["after"]["test_rmse"] < 0.6 * j["before"]["test_rmse"]


def test_a_start_lag_of_one_input_is_accepted_on_its_gains_blocks():
    # every target: alone, E_X's round 2 (after the lag) lets the control clear on the residual's
    # blocks as on the gains' (bench_diag91); beside them it tests on the shared design's
    j = _diagnosed("lag_node", 9289, "E_X", alone=False)
    first = j["rounds"][0]
    assert first["test_blocks"] > 2 * j["cv"]["units"]
    taken = _accepted(j)
    assert taken and taken[0]["kind"] == "dynamics" and taken[0]["effect"].get("initial_state")
    assert not j["control_ever_clears_bar"]
    assert j["after"]["test_rmse"] < 0.6 * j["before"]["test_rmse"]
