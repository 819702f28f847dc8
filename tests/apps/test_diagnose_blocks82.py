"""Issue 34 (diag82): each target tested on its own blocks, re-cut each round on that round's
residual (diag82f), the control held to every check a candidate must pass, the deployed penalty's
standard error on the shared design (benchmarks/bench_diag82.py, bench_diag82f.py).
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache
from types import SimpleNamespace

import numpy as np

from test_diagnose_few import few
from test_diagnose_positions61 import train_problem
from test_diagnose_within67 import _evaluation, _result, _search
from test_diagnose_withinrest69 import _residuals
from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.apps.diagnose.candidates import CONTROL
from thermocomp.apps.diagnose.cv import CrossValidator, smallest_p
from thermocomp.apps.diagnose.features import Effect
from thermocomp.core.compensator import Compensator
from thermocomp.core.model_selection.blocks import cut_blocks, decorrelation_length
from thermocomp.core.models import MLR


def test_the_control_is_refused_by_the_within_campaign_checks_a_candidate_is():
    # a random walk gaining within one campaign only: every other check passes (CV gain, p,
    # margin, in range); a candidate is refused that way (clean69), so must the control be
    current, one, _ = (_result(r) for r in _residuals())
    control = replace(_evaluation(Effect("signal", "raw", CONTROL), current, one), control=True)
    lag = _evaluation(Effect("dynamics", "lowpass_inputs", tau_s=3600.0), current, one)
    s = _search("campaigns")
    s._family_bar([control, lag], current)
    assert control.gain_pct >= s.options.min_gain_pct and control.gain_pct_within >= 5.0
    assert control.gain_pct_within_rest < s.options.min_gain_pct
    assert not control.clears_bar and not lag.clears_bar
    assert control.p_family is None                  # its own p: not a member of the family


def test_the_deployed_penalty_reads_the_penalty_blocks_not_the_test_blocks():
    # test blocks of one sample each, penalty blocks of one unit each: the one-SE rule's
    # standard error is over the latter (the gantry's E_Z_error, bench_diag82)
    units = np.repeat(np.arange(4), 5)
    cv = object.__new__(CrossValidator)
    cv.problem = SimpleNamespace(validated=np.ones(20, bool), block_index=np.arange(20),
                                 penalty_index=units, n_blocks_tested=20)
    err = np.arange(40, dtype=float).reshape(20, 2)
    np.testing.assert_allclose(cv._block_mse(err), err.reshape(4, 5, 2).mean(axis=1))


@lru_cache(maxsize=None)
def _every_target(seed: int):
    ds, _ = few("axis_position", seed)
    return diagnose(ds, Compensator(MLR()), options=SearchOptions(max_effects=2))


def test_a_planted_position_effect_is_found_on_its_targets_own_blocks():
    # planted 8061 (bench_diag81b): every target diagnosed, E_Y's residual decorrelates faster
    # than E_X's and E_Z's; on their 8 blocks (one per campaign) the effect was missed, on its own
    # it is taken, and the reach reported is the target of fewest blocks'
    d = _every_target(8061)
    j = d.to_json("E_Y")
    accepted = [e for e in j["effects"] if e["accepted"]]
    assert accepted and accepted[0]["kind"] == "interaction" and accepted[0]["column"] == "S_pos_Y"
    assert j["after"]["test_rmse"] < j["before"]["test_rmse"]
    designs = j["cv"]["designs"]
    assert designs["E_Y"]["test_blocks"] > designs["E_X"]["test_blocks"]
    assert j["cv"]["test_blocks"] == min(v["test_blocks"] for v in designs.values())
    assert j["cv"]["min_p"] == smallest_p(j["cv"]["test_blocks"])
    for t, v in designs.items():
        assert d.targets[t].search.start.block_mse.size == v["test_blocks"]
    assert not any(d.to_json(t)["control_ever_clears_bar"] for t in d.targets)


def test_a_round_recuts_the_test_blocks_on_its_own_residual_not_the_penalty_blocks():
    # blocks cut on a white residual are too fine for a slow one (a random walk left after an
    # effect is taken): re-cut on it, as long as it takes to decorrelate (planted 8282, diag82e)
    p = train_problem()
    rng = np.random.default_rng(8351)
    white, slow = rng.normal(size=len(p.y)), rng.normal(size=len(p.y)).cumsum()
    # the shared design one block per campaign (8282's): never finer than the re-cut
    p.set_test_blocks(decorrelation_length(white, p.campaigns, p.validated, p.held_out), len(p.y))
    fine, length, penalty = p.n_blocks_tested, p.block_samples, p.penalty_index.copy()
    assert p.recut_test_blocks(slow)
    assert p.block_samples == decorrelation_length(slow, p.campaigns, p.validated, p.held_out) > length
    assert p.n_blocks_tested < fine
    np.testing.assert_array_equal(p.block_index, cut_blocks(p.unit_index, p.campaigns, p.block_samples,
                                                            scored=p.measured))
    np.testing.assert_array_equal(p.penalty_index, penalty)      # the deployed penalty's: kept
    assert not p.recut_test_blocks(slow)


def test_a_round_recut_is_never_coarser_than_the_shared_design():
    # the shared (shipped) design's blocks bound a re-cut: vtl78's dX re-cut to 9 blocks of the
    # shared 15 lost the ram's effect (bench_verify82, bench_diag82g)
    p = train_problem()
    rng = np.random.default_rng(8452)
    white, slow = rng.normal(size=len(p.y)), rng.normal(size=len(p.y)).cumsum()
    short = decorrelation_length(white, p.campaigns, p.validated, p.held_out)
    long_ = decorrelation_length(slow, p.campaigns, p.validated, p.held_out)
    shared = (short + long_) // 2
    assert short < shared < long_
    p.set_test_blocks(short, shared)
    assert p.recut_test_blocks(slow)
    assert p.block_samples == shared
    np.testing.assert_array_equal(p.block_index, p.penalty_index)
    assert p.n_blocks_tested == int(p.penalty_index[p.validated].max()) + 1


def test_each_round_reports_its_blocks_the_first_on_the_starting_design():
    d = _every_target(8061)
    j = d.to_json("E_Y")
    searched = [r for r in j["rounds"] if r["step"] >= 1]
    assert searched and all(r["test_blocks"] >= 1 and r["block_samples"] >= 1 for r in searched)
    assert searched[0]["test_blocks"] == j["cv"]["designs"]["E_Y"]["test_blocks"]
