"""Issue 34, item 4 (margin67): the margin on blocks finer than the campaigns is tested by the
same sign flips as the gain, not by Student's t (benchmarks/bench_margin67.py).

The blocks' MSE spans orders of magnitude and a real effect's gain grows with it, so the
margin's ``e_i = (1 - m)^2 MSE_i - MSE+_i`` are right-skewed; Student's t took the hot blocks'
spread for the null's scale and refused a planted effect better than the margin in every block.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import t as student_t

from test_diagnose_few import diagnosis
from thermocomp.apps.diagnose.cv import sign_flip_pvalue
from thermocomp.apps.diagnose.search import margin_pvalue


def _student_t_margin(before, after, margin_pct):
    """The margin's p as it was (one-sided Student t of the e_i)."""
    e = (1.0 - margin_pct / 100.0) ** 2 * before - after
    return student_t.sf(e.mean() / (e.std(ddof=1) / np.sqrt(e.size)), e.size - 1)


def test_a_gain_beyond_the_margin_in_every_block_clears_whatever_the_blocks_spread():
    # 11 blocks whose error spans 1-250 µm², each 70 % better: e_i is proportional to MSE_i, so
    # Student's t of it depends on the blocks' spread only, not on the gain
    before = np.geomspace(1.0, 250.0, 11)
    t_p = [_student_t_margin(before, (1.0 - g) * before, 5.0) for g in (0.3, 0.7, 0.95)]
    assert min(t_p) > 0.01 and np.ptp(t_p) < 1e-9
    # every block beyond the margin: only the all-positive pattern reaches the observed mean
    assert margin_pvalue(before, 0.3 * before, 5.0) == pytest.approx(2.0 ** -11)
    # a gain under the margin in every block, or the hot blocks made worse, stays refused
    assert margin_pvalue(before, 0.95 * before, 5.0) == 1.0
    worse = np.where(before > np.median(before), 1.1 * before, 0.3 * before)
    assert margin_pvalue(before, worse, 5.0) > 0.5
    # fewer than 2 blocks: nothing to test
    assert margin_pvalue(before[:1], 0.3 * before[:1], 5.0) == 1.0


@pytest.mark.parametrize("n", [7, 40])    # exact and Monte Carlo patterns
def test_p_values_over_one_draw_of_the_sign_patterns_are_each_rows_own(n):
    from thermocomp.apps.diagnose.cv import sign_flip_pvalues
    rng = np.random.default_rng(n)
    D = rng.standard_t(2, size=(3, n)) + [[0.0], [0.5], [-0.5]]
    D[1, 2] = np.nan                  # a column non-finite in one row is dropped from all
    kept = D[:, np.isfinite(D).all(axis=0)]
    together = sign_flip_pvalues(D, seed=4)
    assert together.tolist() == [sign_flip_pvalue(d, seed=4) for d in kept]


def test_a_planted_position_effect_lost_to_students_t_on_11_blocks_is_accepted():
    # fresh seed 6702 of the few-campaign scenario (8 train campaigns, 11 ranked test blocks):
    # the position times the inputs' rises gains beyond the margin in every block; t's p was
    # 0.039 > alpha and nothing was accepted
    j = diagnosis("axis_position", 6702)
    assert j["cv"]["test_blocks"] > j["cv"]["units"]
    first = next(e for e in j["effects"] if e["accepted"])
    assert (first["kind"], first["column"]) == ("interaction", "S_pos_Y")
    evidence = first["evidence"]
    assert evidence["p_value_margin"] <= 0.01 and evidence["p_value_family"] <= 0.01
    assert j["after"]["test_rmse"] < 0.5 * j["before"]["test_rmse"]
    assert not j["control_ever_clears_bar"]
