"""Each round's test blocks as long as the gains of the family members that COULD clear take to
decorrelate (diag92d; ``benchmarks/bench_diag92d.py``).

Planted 8969 (8 train campaigns): on E_Y, S_pos_Y raw (p 0.09 on one block per campaign: it
cannot clear) took 51 samples to decorrelate and kept the round on 8 blocks, where the
family-wise floor 3/256 exceeds alpha, though the position members (p 0.008) decorrelate in 33.
"""

from __future__ import annotations

from test_diagnose_few import few
from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR


def test_a_member_that_cannot_clear_does_not_coarsen_the_rounds_blocks():
    ds, _ = few("axis_position", 8969)
    assert len(ds.ids("train")) == 8
    j = diagnose(ds, Compensator(MLR()), targets=["E_Y"],
                 options=SearchOptions(max_effects=2)).to_json("E_Y")
    assert j["cv"]["scheme"] == "campaigns" and j["cv"]["units"] == 8
    first = next(r for r in j["rounds"] if r["step"] == 1)
    assert first["test_blocks"] > j["cv"]["units"]          # not one block per campaign
    top = [e for e in j["effects"] if e["accepted"]][0]
    assert (top["kind"], top["column"]) == ("interaction", "S_pos_Y")
    assert top["evidence"]["p_value_family"] <= j["bar"]["alpha"]
    assert j["after"]["test_rmse"] < 0.6 * j["before"]["test_rmse"]
    assert not j["control_ever_clears_bar"]
