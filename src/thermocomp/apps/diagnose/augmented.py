r"""The diagnosed model: any estimator plus the features of the accepted effects."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from sklearn.base import BaseEstimator, RegressorMixin, clone
from sklearn.utils.validation import check_is_fitted, validate_data

from ...base.errors import ContractError, ParameterError
from ...core.context import (
    AMBIENT_C0,
    TIME,
    SideInputs,
    context_columns,
    groups_of,
    merge_columns,
    scalar,
)
from ...core.gains import GainTerm, gain_at, gain_terms, within
from ...core.models._campaign_ls import LSTSQ_TOL
from ...core.models.base import measured_rows
from ...core.models.linear import MLR
from ...core.timerule import CLOCK_START, median_step, step_time
from .features import (
    AMBIENT_CENTRE_C,
    Effect,
    as_effect,
    design,
    frames,
    in_frame,
    initial_weights,
    level_weights,
)
from .shrink import PartialRidgePath

MODEL_NAME = "diagnosed"   # the model diagnose writes (conf/model/diagnosed.yaml, "<family>+diagnosed")


def _spread(Z: np.ndarray, fit_intercept: bool) -> np.ndarray:
    """Each column's spread on the rows: its standard deviation (root mean square without an
    intercept); 1 for a column that varies by less than the cut-off of the columns' median
    spread: rounding, left where the cut-off drops it (stranger66: a lag's initial-state
    direction along offsets that sum to 0 varies by ~1e-16; scaled up, it took -1.4e15)."""
    spread = Z.std(axis=0) if fit_intercept else np.sqrt(np.mean(Z ** 2, axis=0))
    return np.where(spread > LSTSQ_TOL * np.median(spread), spread, 1.0)


class AugmentedRegressor(SideInputs, RegressorMixin, BaseEstimator):
    r"""A model family with extra regressors from diagnosed effects.

    .. math:: \hat y(t) = f\big(x(t),\ \phi_1(t), \dots, \phi_m(t)\big)

    where :math:`f` is ``estimator`` (any family: MLR, PCR, ARX, ARX+RF, an ATI
    model ...) and :math:`\phi_j` are the features of the accepted effects
    (:func:`thermocomp.apps.diagnose.features.effect_features`: lags of an undeclared
    signal, low-pass copies of the inputs, ambient interactions, products,
    squares), built per row from the inputs and the ``context`` (:mod:`thermocomp.core.context`).
    The estimator sees them as extra inputs, so it fits them its own way (OLS,
    principal components, greedy ARX selection ...).  With ``alpha`` and an
    :class:`~thermocomp.core.models.MLR` base the effect coefficients are shrunk
    instead (ridge on the standardised :math:`\phi_j`, the inputs unpenalised,
    :mod:`thermocomp.apps.diagnose.shrink`): many correlated extra regressors fitted
    on one long record otherwise extrapolate badly.  ``sensor_fault`` effects
    build nothing: the faulty sensor is left out of ``data.inputs`` instead.

    Parameters
    ----------
    estimator : regressor, default MLR()
        The base model, cloned in ``fit``.
    effects : list of effect dicts, or dict target -> list
        :class:`~thermocomp.apps.diagnose.features.Effect` fields (``kind``,
        ``transform``, ``column``, ``other``, ``tau_s``, ``threshold_c``).  A
        dict gives each target its own effects: :meth:`for_target` picks them
        (the Compensator calls it per target); a target missing from it gets none.
    reference : {'first_sample', 'none'}
        Frame of the context columns (``data.reference``).
    alpha : float >= 0, dict target -> float, or None
        Ridge penalty on the standardised effect features when the base is an
        MLR (chosen by ``diagnose``'s cross-validation); ``None`` or 0: the
        base estimator fits them as plain inputs (an MLR on the columns scaled
        to unit spread, so its cut-off is fair to every unit).  Other bases
        ignore it (they fit their own way: PCR truncates, ARX selects, lagbank
        has its ridge).

    Attributes
    ----------
    estimator_ : fitted base estimator
    effects_ : list of Effect used for this target
    required_context_ : list of str
        Raw context columns (``S_``/``T_``) the effects need at prediction time.
    context_columns_ : list of str
        Everything read from the context at prediction time (the effects' and
        the base estimator's).
    initial_weights_ : list of (ndarray or None)
        Per effect, the initial-state directions learned from the training
        campaigns (effects with ``initial_directions``).
    n_features_in_ : int
    """

    def __init__(self, estimator=None, effects=(), reference: str = "first_sample", alpha=None):
        self.estimator = estimator
        self.effects = effects
        self.reference = reference
        self.alpha = alpha

    def for_target(self, target: str) -> "AugmentedRegressor":
        """An unfitted copy with the effects of ``target`` (per-target dict) as a list."""
        effects = self.effects if self.effects is not None else ()
        if isinstance(effects, Mapping):
            effects = effects.get(target, ())
        alpha = self.alpha.get(target) if isinstance(self.alpha, Mapping) else self.alpha
        return clone(self).set_params(effects=[dict(e) if isinstance(e, Mapping) else e
                                               for e in effects], alpha=alpha)

    def _effects(self) -> list[Effect]:
        effects = self.effects if self.effects is not None else ()
        if isinstance(effects, Mapping):
            raise ParameterError("AugmentedRegressor effects are given per target: fit the copy "
                                 "for_target(target) returns (the Compensator does)")
        return [e for e in (as_effect(e) for e in effects) if e.transform != "remove"]

    def _design(self, X, context) -> np.ndarray:
        if context is not None and len(context) != X.shape[0]:
            raise ValueError(f"context has {len(context)} rows, X has {X.shape[0]}")
        return design(X, self.effects_, context, groups_of(context), self.reference,
                      self.initial_weights_)

    def fit(self, X, y, context=None):
        if self.reference not in ("first_sample", "none"):
            raise ParameterError(f"AugmentedRegressor reference={self.reference!r} is not "
                                 "first_sample or none")
        alpha = self._alpha()
        X, y, measured = measured_rows(self, X, y)   # (NaN between a probe cycle's measurements)
        self.effects_ = self._effects()
        self.required_context_ = list(dict.fromkeys(c for e in self.effects_ for c in e.context_columns))
        g = groups_of(context)
        # the stream's step for a sample without a time (the time rule); rows without a time
        # column are 1 apart, as the design counts them
        time = context[TIME].to_numpy(float) if context is not None and TIME in context else None
        self.sample_period_s_ = (median_step(time, g) if time is not None else None) or 1.0
        self.initial_weights_ = [
            level_weights(X[measured], y[measured]) if e.transform == "ambient_scaled"
            else initial_weights(context, e.initial_state, g, e.initial_directions) if e.learns else None
            for e in self.effects_]
        Z = self._design(X, context)
        base = self.estimator if self.estimator is not None else MLR()
        widened = isinstance(base, MLR) and Z.shape[1] > X.shape[1]    # an MLR with effect features
        # at penalty 0 it fits them scale-fair: LinearRegression's relative cut-off (1e-6) on
        # the raw design dropped every temperature beside a state in a large unit (a power in
        # mW, a speed's square in rpm^2: coefficients ~1e-14); on columns of unit spread it
        # drops only a direction collinear there (pen0b69; an exact fit gave a lag's collinear
        # initial-state offsets -1.4e15, the stream 1e-3 off the batch); with a penalty the
        # ridge path below gives both coef_ and intercept_
        scale = _spread(Z[measured], base.fit_intercept) if widened and not alpha else None
        self.estimator_ = clone(base).fit(Z if scale is None else Z / scale, y, context=context)
        if scale is not None:
            self.estimator_.coef_ = self.estimator_.coef_ / scale   # the intercept is the same
        if alpha and widened:
            # the same law, its effect coefficients shrunk (streams as any MLR does)
            # the effects' features run on every row, the law is the measured rows' least squares
            path = PartialRidgePath(Z[measured], y[measured], X.shape[1], self.estimator_.fit_intercept)
            self.estimator_.coef_, self.estimator_.intercept_ = path.coefficients(alpha)
        # the campaign's initial ambient: an ambient law needs it; a lag's initial state reads
        # it where it is known, else the mean of its sensors' first values (features.initial_state),
        # as every deployed form does (stranger66: a record without an air sensor and without a
        # manifest ambient_c was diagnosed, and the stream refused every diagnosed model of it)
        laws = any(e.transform in ("ambient_linear", "ambient_step", "ambient_mean", "ambient_scaled")
                   for e in self.effects_)
        base = AMBIENT_C0 in context_columns(self.estimator_)
        self.ambient_optional_ = not (laws or base)
        ambient = laws or base or any(e.initial_state for e in self.effects_)
        self.context_columns_ = merge_columns([TIME] if self.effects_ else [],
                                              [AMBIENT_C0] if ambient else [],
                                              self.required_context_,
                                              context_columns(self.estimator_))
        return self

    def _alpha(self) -> float:
        if isinstance(self.alpha, Mapping):
            raise ParameterError("AugmentedRegressor alpha is given per target: fit the copy "
                                 "for_target(target) returns (the Compensator does)")
        alpha = 0.0 if self.alpha is None else float(self.alpha)
        if not alpha >= 0:
            raise ParameterError(f"AugmentedRegressor alpha={self.alpha!r} must be >= 0")
        return alpha

    def predict(self, X, context=None):
        check_is_fitted(self)
        X = validate_data(self, X, reset=False)
        return self.estimator_.predict(self._design(X, context), context=context)

    # -- streaming (deployment) -------------------------------------------------------------
    def stream_init(self, context: Mapping | None = None) -> dict:
        """State before a campaign's first sample; ``context`` may hold ``ambient_c0``."""
        check_is_fitted(self)
        return {"first": {}, "last": {}, "lag": {}, "t": None, "clock": CLOCK_START,
                "ambient_c0": scalar(context, AMBIENT_C0),
                "base": self.estimator_.stream_init(context)}

    def _raw(self, column, context, state, reference: str | None = None) -> float:
        if context is None or column not in context:
            raise ContractError("the diagnosed model's stream_step needs this column in its context "
                                "(raw value of the sample)", column=column)
        value = float(context[column])
        if np.isnan(value):   # hold the last valid value, as the batch frame does
            value = state["last"].get(column, np.nan)
        if not np.isnan(value):
            state["last"][column] = value
            state["first"].setdefault(column, value)
        if np.isnan(value):
            return 0.0
        reference = self.reference if reference is None else reference
        return value - state["first"][column] if reference == "first_sample" else value

    def _lag(self, key, u: np.ndarray, tau: float, dt: float | None, state) -> np.ndarray:
        prev = state["lag"].get(key)
        z = u if prev is None or dt is None else np.exp(-dt / tau) * prev + (1 - np.exp(-dt / tau)) * u
        state["lag"][key] = z
        return z

    def _initial_state(self, i: int, e: Effect, context, a0: float, t: float, state) -> np.ndarray:
        key = ("initial", i)
        if key not in state["first"]:   # absolute values at the first sample that has them
            raw = np.array([float((context or {}).get(c, np.nan)) for c in e.initial_state])
            if np.isnan(raw).all():
                w = self.initial_weights_[i]
                return np.zeros(len(w) if w is not None else len(raw))
            ref = a0 if np.isfinite(a0) else float(np.nanmean(raw))
            offsets = np.nan_to_num(raw - ref)
            if self.initial_weights_[i] is not None:
                offsets = self.initial_weights_[i] @ offsets
            state["first"][key] = offsets
        return state["first"][key] * (1.0 - np.exp(-(t - state["t0"]) / e.tau_s))

    # -- the envelope clamp's bound (clampdiag60, gain61) ------------------------------------
    def _lead_taus(self) -> np.ndarray | None:
        """Per column of the base, the tau of the low-pass copy it is (``nan``: none), in the
        columns' order (:meth:`gain_terms`); ``None`` without a low-pass copy."""
        k = int(self.n_features_in_)
        lead = [np.nan] * k
        for i, e in enumerate(self.effects_):
            tr = e.transform
            if tr in ("lowpass_inputs", "ambient_linear", "ambient_step", "inputs_product"):
                lead += [float(e.tau_s) if tr == "lowpass_inputs" else np.nan] * k
            else:
                lead.append(np.nan)
            if tr in ("first_order_lag", "lowpass_inputs") and e.initial_state:
                w = self.initial_weights_[i]
                lead += [np.nan] * (len(w) if w is not None else len(e.initial_state))
        return np.asarray(lead) if any(e.transform == "lowpass_inputs" for e in self.effects_) else None

    def gain_terms(self, horizon_s: float = np.inf, lead=None, period_s: float = 1.0) -> list:
        """The gain per input of a step held for ``horizon_s`` (:meth:`step_gain`), split by the
        campaign's initial ambient (:mod:`thermocomp.core.gains`): the base's terms over the
        features, each on ``x``, and on an ambient law's block times ``A0 - 20`` more, on an
        ambient step's where ``A0 > A_thr`` too.

        The stream's clamp changes the inputs ``x`` alone: a raw signal, its lag, a product or a
        square (of the context's columns as read) and a lag's initial-state transient do not move
        with it (gain 0, exact).  A low-pass copy ``L_tau[x]`` is a lag of the held step: the
        base's gain with those columns lagged (``lagged_step_gain``: over a static base ``1 -
        exp(-h / tau)`` of the copy's coefficients, over a lag bank cascades, over an ARX model
        the difference equation's response to the lag; exact, gain61) on ``x``.  ``c (x - x(0))``
        (diagpos61) scales it by the state ``c`` of the stream's last sample, held over the
        horizon: a gain of the stream's state, not of ``A0`` (no gain without ``state``; the
        exported code holds the state's value, :meth:`held_gain_terms`, export62)."""
        return self._terms(horizon_s, lead)

    def held_gain_terms(self, horizon_s: float = np.inf) -> tuple[list, dict]:
        """``(terms, {effect index: terms})``: :meth:`gain_terms` with every ``inputs_product``'s
        state at 0, and per such effect the terms its state's held value multiplies (its block
        alone): the stream's gain at a held value ``c_i`` is the first plus ``c_i`` times each
        (export62: the exported code holds the state's value at the campaign's first excess)."""
        products = [i for i, e in enumerate(self.effects_) if e.transform == "inputs_product"]
        zero = self._terms(horizon_s, state={"state_of": dict.fromkeys(products, 0.0)})
        return zero, {i: self._terms(horizon_s, unit=i) for i in products}

    def _terms(self, horizon_s: float, lead=None, state=None, unit: int | None = None) -> list:
        """:meth:`gain_terms`, a state's product with the inputs' rises (``inputs_product``) at
        the stream ``state``'s last value of it (``None``: no gain); ``unit``: that effect's
        block alone, at a state's value of 1 (:meth:`held_gain_terms`)."""
        check_is_fitted(self)
        if lead is not None:
            return [GainTerm(-np.inf, np.inf, 0, None)]     # a diagnosed model in a lag: none
        base = gain_terms(self.estimator_, horizon_s, self._lead_taus(),
                          getattr(self, "sample_period_s_", None) or 1.0)
        return [part for t in base for part in self._blocks(t, state, unit)]

    def _blocks(self, term: GainTerm, state=None, unit: int | None = None) -> list:
        """One base term over the features as terms over ``x`` (:meth:`gain_terms`); ``unit``:
        the ``inputs_product`` effect whose block alone is kept, at a state's value of 1."""
        if term.gain is None:
            return [term]
        gain, k = term.gain, int(self.n_features_in_)
        x, at, out = gain[:k].copy() if unit is None else np.zeros(k), k, []
        for i, e in enumerate(self.effects_):
            tr = e.transform
            if tr in ("lowpass_inputs", "ambient_linear", "ambient_step", "inputs_product"):
                block = gain[at:at + k]
                at += k
                if unit is not None:            # the one effect's block alone
                    x += block if i == unit else 0.0
                elif tr == "lowpass_inputs":      # its lag of the held step: in the base's gain
                    x += block
                elif tr == "inputs_product":    # x's rise times the state's value held
                    held = (state or {}).get("state_of", {}).get(i)
                    if held is None:
                        return [term._replace(gain=None)]
                    x += held * block
                elif tr == "ambient_linear":
                    out += within([term._replace(gain=block)], -np.inf, np.inf, power=1)
                else:
                    out += within([term._replace(gain=block)], float(e.threshold_c), np.inf)
            elif tr in ("ambient_mean", "ambient_scaled"):    # one column: a direction of x x (A0 - 20)
                w = np.full(k, 1.0 / k) if tr == "ambient_mean" else self.initial_weights_[i]
                out += within([term._replace(gain=gain[at] * w)], -np.inf, np.inf, power=1)
                at += 1
            else:     # one column of the context, not of x
                at += 1
            if tr in ("first_order_lag", "lowpass_inputs") and e.initial_state:
                w = self.initial_weights_[i]
                at += len(w) if w is not None else len(e.initial_state)
        if at != gain.size:      # the features' columns as stream_step builds them
            raise ContractError(f"the diagnosed model's features are {at} columns, its base's "
                                f"gain {gain.size}")
        return [term._replace(gain=x), *out]

    def held_ranges(self, context) -> dict:
        """``{effect index: (lowest, highest)}``: each ``inputs_product``'s state over the stacked
        training ``context``, in the frame the stream reads it (the guard's gain at the ends of the
        range, :func:`thermocomp.apps.deploy.held_gains.held_factor_gain`)."""
        check_is_fitted(self)
        out = {}
        for i, e in enumerate(self.effects_):
            if e.transform == "inputs_product" and e.column in context:
                own = frames(e, self.reference)[0]
                c = in_frame(context[e.column].to_numpy(float), groups_of(context), own)
                out[i] = (float(np.nanmin(c)), float(np.nanmax(c)))
        return out

    def step_gain(self, state=None, horizon_s: float = np.inf) -> np.ndarray | None:
        """Gain per input (:func:`thermocomp.core.context.step_gain`) of a step held for
        ``horizon_s``: :meth:`gain_terms` at the campaign's ``A0`` (``state['ambient_c0']``);
        ``None`` when the base has no gain, or an ambient law has no ``A0``."""
        check_is_fitted(self)
        return gain_at(self._terms(horizon_s, state=state),
                       scalar(state, AMBIENT_C0) if state is not None else np.nan)

    def stream_step(self, x_row, state: dict, context: Mapping | None = None) -> tuple[float, dict]:
        """One sample of simulation-mode ``predict``.

        ``context`` maps ``time`` (s), ``ambient_c0`` (°C, if the effects use it)
        and every column of ``required_context_`` to this sample's raw value.
        """
        x = np.asarray(x_row, dtype=float).ravel()
        t = scalar(context, TIME)
        period = getattr(self, "sample_period_s_", None)
        if period is not None and "clock" in state:      # the stream's time rule (core.timerule)
            state["clock"], t, dt, _ = step_time(state["clock"], t, period)
            dt = None if np.isnan(dt) else dt
        else:   # fitted or started before the rule: a missing time restarts the lags, as it did
            dt = None if state["t"] is None or np.isnan(t) else t - state["t"]
        state.setdefault("t0", t)
        state["t"] = t if not np.isnan(t) else state["t"]
        a0 = scalar(context, AMBIENT_C0, state["ambient_c0"])
        parts = [x]
        for i, e in enumerate(self.effects_):
            tr = e.transform
            own, other = frames(e, self.reference)
            if tr in ("raw", "first_order_lag", "square"):
                c = np.array([self._raw(e.column, context, state, own)])
                if tr == "first_order_lag":
                    c = self._lag(i, c, e.tau_s, dt, state)
                parts.append(c**2 if tr == "square" else c)
                if tr == "first_order_lag" and e.initial_state:
                    parts.append(self._initial_state(i, e, context, a0, t, state))
            elif tr == "product":
                o = self._raw(e.other, context, state, other)
                if e.over is not None:      # the temperature over the air (features.effect_features)
                    o -= self._raw(e.over, context, state, other)
                parts.append(np.array([self._raw(e.column, context, state, own) * o]))
            elif tr == "inputs_product":
                value = self._raw(e.column, context, state, own)
                state.setdefault("state_of", {})[i] = value
                x0 = state["first"].setdefault(("inputs", i), x.copy())
                parts.append(value * (x - x0))
            elif tr == "lowpass_inputs":
                parts.append(self._lag(i, x, e.tau_s, dt, state))
                if e.initial_state:
                    parts.append(self._initial_state(i, e, context, a0, t, state))
            elif tr == "ambient_linear":
                parts.append(x * (a0 - AMBIENT_CENTRE_C))
            elif tr == "ambient_mean":
                parts.append(np.array([x.mean() * (a0 - AMBIENT_CENTRE_C)]))
            elif tr == "ambient_scaled":
                parts.append(np.array([x @ self.initial_weights_[i] * (a0 - AMBIENT_CENTRE_C)]))
            elif tr == "ambient_step":
                parts.append(x * float(a0 > e.threshold_c))
        z = np.concatenate(parts)
        y, state["base"] = self.estimator_.stream_step(z, state["base"], context)
        return float(y), state
