"""Diagnose's test blocks as long as the candidates' gains take to decorrelate, in the ``campaigns``
scheme, with a between-campaign guard (diag91b; ``benchmarks/bench_diag91b.py``).

8 train campaigns of the year-round machine: the residual that still holds the effect being tested
forgets slowly (about one block per campaign, a family-wise floor above alpha), while the
per-sample gains forget faster.  Forward chaining keeps the residual's blocks
(test_diagnose_record.py), and a gain mostly one number per campaign keeps them too
(test_diagnose_few.py's clean seed 4004).
"""

from __future__ import annotations

import numpy as np
import pytest

from test_diagnose_few import few
from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR


def _diagnosis(effect: str, seed: int, target: str, alone: bool = True) -> dict:
    ds, _ = few(effect, seed)
    assert len(ds.ids("train")) == 8
    d = diagnose(ds, Compensator(MLR()), targets=[target] if alone else None,
                 options=SearchOptions(max_effects=2))
    return d.to_json(target)


def _first_round(j: dict) -> dict:
    return next(r for r in j["rounds"] if r["step"] == 1)


def test_a_planted_position_effect_is_found_on_blocks_its_gains_decorrelate_over():
    # planted 8966: the residual's blocks are 9 over 8 campaigns (smallest p 1/512, family-wise
    # short of alpha); the position's gains forget within ~10 samples, so round 1 tests on far
    # more blocks and the position effect is taken with the test error more than halved
    j = _diagnosis("axis_position", 8966, "E_Y")
    assert j["cv"]["scheme"] == "campaigns" and j["cv"]["units"] == 8
    first = _first_round(j)
    assert first["test_blocks"] > 2 * j["cv"]["units"]
    top = [e for e in j["effects"] if e["accepted"]][0]
    assert (top["kind"], top["column"]) == ("interaction", "S_pos_Y")
    assert top["evidence"]["p_value_family"] <= j["bar"]["alpha"]
    assert j["after"]["test_rmse"] < 0.5 * j["before"]["test_rmse"]
    assert not j["control_ever_clears_bar"]


def test_a_slow_start_lag_is_taken_on_its_gains_blocks_and_the_control_never_clears():
    # lag:9289 (a slow thermal node planted): main tests E_X's round 1 on the residual's 10 blocks
    # and takes nothing; on the gains' blocks a 14400 s lag from the initial thermal state is taken
    # (every target diagnosed: the shared design's blocks bound E_X's, as `diagnose` runs)
    j = _diagnosis("lag_node", 9289, "E_X", alone=False)
    assert j["cv"]["scheme"] == "campaigns"
    assert _first_round(j)["test_blocks"] > 2 * j["cv"]["units"]
    taken = [e for e in j["effects"] if e["accepted"]]
    assert taken and taken[0]["kind"] == "dynamics" and not taken[0].get("control")
    assert j["after"]["test_rmse"] < 0.7 * j["before"]["test_rmse"]
    assert not j["control_ever_clears_bar"]


def test_the_between_campaign_share_of_a_gain():
    # one number per campaign: share 1; the same mean in every campaign: share 0; in between for
    # a per-campaign offset under per-sample noise, as the one-way decomposition says
    from thermocomp.core.model_selection.blocks import between_campaign_share

    campaigns = np.repeat(["C1", "C2", "C3", "C4"], 50)
    offsets = np.repeat([1.0, -1.0, 2.0, -2.0], 50)
    scored = np.ones(campaigns.size, bool)
    assert between_campaign_share(offsets, campaigns, scored) == pytest.approx(1.0)
    alternating = np.tile([1.0, -1.0], 100)
    assert between_campaign_share(alternating, campaigns, scored) == 0.0
    noise = np.random.default_rng(0).normal(0.0, 1.0, campaigns.size)
    share = between_campaign_share(offsets + noise, campaigns, scored)
    assert 0.6 < share < 0.85        # 2.5 / (2.5 + 1) = 0.71 in expectation
    scored[:50] = False              # rows not scored are left out
    assert between_campaign_share(offsets, campaigns, scored) == pytest.approx(1.0)
