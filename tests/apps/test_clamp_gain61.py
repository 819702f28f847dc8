"""A diagnosed low-pass copy of the inputs over an ARX or ATI base has an exact clamp gain (gain61).

The envelope clamp bounds what an input's excess moves a correction by ``|gain @ e|``, the
model's response to a unit step held for the clamp's horizon.  A diagnosed model's low-pass copy
``L_tau[x]`` over an ARX model had none (its lag through the delays and the feedback is no
product of two gains): the clamp took the clamped stream's value whatever the excess.  The ARX
model's difference equation on the lag has a closed form, exact at the stream's samples
(:meth:`~thermocomp.core.models.ARX.lagged_step_gain`), and an ATI model's intervals pass the
lag to theirs (:mod:`thermocomp.core.gains`).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from test_envelope_dynamics import _step_response
from thermocomp.apps.diagnose import AugmentedRegressor
from thermocomp.core.context import step_gain
from thermocomp.core.gains import gain_at
from thermocomp.core.models import ARX, LagBank
from thermocomp.core.models.ati import ATIRegressor

TAU_S = 3600.0
LOWPASS = {"kind": "dynamics", "transform": "lowpass_inputs", "tau_s": TAU_S}
AMBIENT_LAW = {"kind": "ambient_interval", "transform": "ambient_linear"}


def _lagged_problem(seed: int = 3, n_campaigns: int = 8, n: int = 240):
    """An error that follows a one-hour lag of its first input, the second at once, with a
    slope in the campaign's initial ambient; inputs wander, one sample a minute."""
    rng = np.random.default_rng(seed)
    groups = np.repeat([f"C{i}" for i in range(n_campaigns)], n)
    ambient = np.repeat(rng.uniform(5, 30, n_campaigns), n)
    X = np.cumsum(rng.normal(0, 0.1, (len(groups), 3)), axis=0)
    context = pd.DataFrame({"campaign": groups, "time": np.tile(np.arange(n) * 60.0, n_campaigns),
                            "ambient_c0": ambient, "S_door": 0.0})
    y = ((1.5 * _lag(X[:, 0], context) - X[:, 1]) * (1 + 0.02 * (ambient - 15))
         + rng.normal(0, 0.02, len(groups)))
    return X, y, context


BASES = {
    "arx": (lambda: ARX(ar=True, delays=(0, 2)), [LOWPASS, AMBIENT_LAW]),
    "ati(arx) interaction": (lambda: ATIRegressor(ARX(ar=True), n_intervals=2,
                                                  ambient_interaction=True), [LOWPASS]),
    "ati(lagbank) interaction": (lambda: ATIRegressor(LagBank(n_taus=2), n_intervals=2,
                                                      ambient_interaction=True), [LOWPASS]),
}


def _arx_models(est) -> list:
    base = est.estimator_
    return list(base.estimators_) if isinstance(base, ATIRegressor) else [base]


@pytest.mark.parametrize("name", sorted(BASES))
@pytest.mark.parametrize("a0", [10.0, 26.0])
def test_a_lowpass_copys_gain_is_its_held_step_response(name, a0):
    """Two hours held (the copy's lag at 86 %): the gain is the streamed response of a unit step
    to 1e-6, in each ATI interval; ``None`` before (clamped outright)."""
    X, y, context = _lagged_problem()
    base, effects = BASES[name]
    est = AugmentedRegressor(base(), effects=effects).fit(X, y, context=context)
    for arx in (m for m in _arx_models(est) if isinstance(m, ARX)):
        # the ARX model reads the copy (a column after the inputs), through its feedback
        assert arx.ar_coef_ != 0.0 and any(j >= 3 for j, _ in arx.terms_)
    rows = 120
    state = est.stream_init({"campaign": "S", "time": 0.0, "ambient_c0": a0, "S_door": 0.0})
    gain = step_gain(est, state, rows * 60.0)
    held = [_step_response(est, j, X.shape[1], rows, a0) for j in range(X.shape[1])]
    np.testing.assert_allclose(gain, held, rtol=1e-6, atol=1e-9)


def test_the_arx_models_lagged_gain_is_no_product_of_the_two_gains():
    """A lag's ramp through the feedback and a delay: the closed form is the simulated cascade,
    and the lag's held factor times the steady state (a static base's copy) is off by more than
    the tolerance of the test above."""
    X, y, context = _lagged_problem()
    lagged = np.column_stack([_lag(X[:, j], context) for j in range(3)])
    arx = ARX(ar=True, delays=(0, 2)).fit(np.column_stack([X, lagged]), y, context=context)
    # a law that reads the lags, one delayed, through a feedback of a few samples
    arx.terms_, arx.coef_, arx.ar_coef_ = [(3, 2), (4, 0), (1, 0)], np.array([1.5, -0.7, -1.0]), 0.6
    lead, h = np.r_[[np.nan] * 3, [TAU_S] * 3], 7200.0
    exact = arx.lagged_step_gain(lead, h, 60.0)
    p = np.exp(-60.0 / TAU_S)
    for j in range(3, 6):      # the lag of a unit step in column j, streamed (less the intercept's)
        rows = np.zeros((int(h / 60.0) + 1, 6))
        rows[:, j] = 1.0 - p ** np.arange(len(rows))
        moved = (arx.stream_steps(rows, arx.stream_init())[0]
                 - arx.stream_steps(0 * rows, arx.stream_init())[0])
        np.testing.assert_allclose(exact[j], moved[-1], rtol=1e-6, atol=1e-9)
    product = arx.step_gain() * (1.0 - np.exp(-h / TAU_S))
    assert np.abs(product - exact)[3:].max() > 1e-3 * np.abs(exact[3:]).max()


def _lag(x: np.ndarray, context: pd.DataFrame) -> np.ndarray:
    """The diagnosed low-pass copy's lag of ``x`` (tau ``TAU_S``), per campaign."""
    out, a, first = np.empty_like(x), np.exp(-60.0 / TAU_S), context["time"].to_numpy() == 0.0
    for i, v in enumerate(x):
        out[i] = v if first[i] else a * out[i - 1] + (1 - a) * v
    return out


def test_the_terms_are_the_gain_of_each_campaigns_interval():
    """The gain the stream takes in a campaign is the terms' sum at its initial ambient: the
    interval's model, its interaction times ``A0 - 20``."""
    X, y, context = _lagged_problem()
    est = AugmentedRegressor(ATIRegressor(ARX(ar=True), n_intervals=2, ambient_interaction=True),
                             effects=[LOWPASS]).fit(X, y, context=context)
    terms = est.gain_terms(7200.0)
    assert {t.power for t in terms} == {0, 1} and len({(t.lo, t.hi) for t in terms}) == 2
    for a0 in (8.0, 28.0):
        state = est.stream_init({"campaign": "S", "time": 0.0, "ambient_c0": a0, "S_door": 0.0})
        np.testing.assert_array_equal(step_gain(est, state, 7200.0), gain_at(terms, a0))
    assert gain_at(terms, np.nan) is None
