"""Issue 34, item 4 (within67): in the ``campaigns`` scheme every candidate kind must gain within the
held-out campaigns, not only in their means (benchmarks/bench_within67.py).

A regressor near a constant within a campaign -- the hall air's square, a regime of it -- fits the
campaigns' offsets (the first sample's probe noise in the first-sample frame) as a lag's
initial-state transient does; on a null draw of the grinder records ``T_amb``'s square was
accepted that way and raised the test error.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from thermocomp.apps.diagnose.cv import CVResult
from thermocomp.apps.diagnose.features import Effect
from thermocomp.apps.diagnose.search import Evaluation, Search, SearchOptions

N_UNITS, ROWS = 9, 40


def _search(scheme: str) -> Search:
    units = np.repeat(np.arange(N_UNITS), ROWS)
    s = object.__new__(Search)
    s.problem = SimpleNamespace(validated=np.ones(units.size, bool), unit_index=units,
                                n_units=N_UNITS, n_blocks_tested=N_UNITS, scheme=scheme,
                                units_trained=N_UNITS - 1, shared_ranked=False)
    s.options = SearchOptions()
    s.cv = SimpleNamespace(closed_form=False)   # no refits here: diag103's forward read not asked
    return s


def _result(residual: np.ndarray, n_units: int = N_UNITS) -> CVResult:
    """A CV result of ``residual`` over ``n_units`` equal units (its blocks)."""
    unit = np.array([np.mean(r ** 2) for r in residual.reshape(n_units, -1)])
    return CVResult(residual, residual, float(np.sqrt(np.mean(residual ** 2))), unit,
                    block_mse=unit)


def _evaluation(effect: Effect, current: CVResult, result: CVResult) -> Evaluation:
    pct = 100.0 * (current.rmse - result.rmse) / current.rmse
    return Evaluation(effect, result.rmse, current.rmse - result.rmse, pct, 0.0, 0.5, True,
                      n_features=1, result=result, gain_pct_in_range=pct, p_margin=0.0)


def _family(scheme: str):
    rng = np.random.default_rng(3)
    offsets = rng.choice([-1.0, 1.0], N_UNITS) * rng.uniform(0.6, 1.2, N_UNITS)
    noise = rng.normal(0.0, 0.4, N_UNITS * ROWS)
    units = np.repeat(np.arange(N_UNITS), ROWS)
    current = _result(offsets[units] + noise)
    # T_amb's square fits the campaigns' offsets and nothing within them; a real effect's
    # regressor takes a third of the error within every campaign and leaves the offsets
    square = _evaluation(Effect("nonlinear", "square", "T_amb"), current, _result(noise))
    real = _evaluation(Effect("signal", "raw", "S_pos_Y"), current,
                       _result(offsets[units] + noise * (2.0 / 3.0)))
    s = _search(scheme)
    s._family_bar([square, real], current)
    return s, square, real


def test_a_candidate_of_any_kind_that_only_fits_the_campaigns_offsets_is_refused():
    s, square, real = _family("campaigns")
    margin = s.options.min_gain_pct
    # both pass every other condition of the bar: 9 of 9 campaigns gain, family-wise p 2/512
    assert square.gain_pct >= margin and real.gain_pct >= margin
    assert square.p_family <= s.options.alpha and real.p_family <= s.options.alpha
    assert not square.clears_bar and real.clears_bar
    assert abs(square.gain_pct_within) < 1e-9 and real.gain_pct_within >= margin
    assert square.entry()["evidence"]["cv_rmse_gain_pct_within"] == square.gain_pct_within


def test_forward_chaining_is_not_asked_the_within_gain():
    _, square, real = _family("forward")
    assert square.clears_bar and real.clears_bar
    assert square.gain_pct_within is None and "cv_rmse_gain_pct_within" not in square.entry()["evidence"]
