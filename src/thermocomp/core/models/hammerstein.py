r"""Hammerstein lag bank: machine states through a static power law, then the lag bank's dynamics.

.. math:: \hat y(t) = \mathrm{LagBank}\big[x(t),\; u_1(t)^{e},\, \dots,\, u_m(t)^{e}
          \;\; (e \in E)\big], \qquad u_j = s_j / \max_{\text{train}} |s_j|

A Hammerstein model is a static nonlinearity followed by linear dynamics.  The
heat a spindle, a drive or a pump puts into the structure is not linear in its
state: bearing friction power grows roughly as the speed to a power between 1
and 2.  Temperatures are already the machine's response to that heat and enter
linearly; the machine-state columns (``S_*`` of the context, not declared
inputs) enter through powers of themselves, and every term then runs through
the first-order lags of :class:`~thermocomp.core.models.lagbank.LagBank`, which
turn heat input into its slow thermal response.  Which powers enter (none, each
exponent alone, all of them) is chosen with the lag bank's own time-series
cross-validation on the training rows only.
"""

from __future__ import annotations

from collections.abc import Mapping
from itertools import combinations

import numpy as np
import pandas as pd
from sklearn.base import BaseEstimator, RegressorMixin, clone
from sklearn.utils.validation import check_is_fitted, validate_data

from ...base.errors import ContractError
from ...base.params import BOOLEAN, check_estimator, choice, numbers, optional, texts
from ..context import SideInputs, groups_of, merge_columns, require, step_gain
from ..io.contract import match_columns
from ._dynamics import segment_bounds
from .base import measured_rows
from .lagbank import LagBank


def _unmeasured(values: np.ndarray, groups) -> list[tuple[int, int]]:
    """``(column, first row)`` of each campaign in which a state column has no value at all."""
    return [(j, start) for start, stop in segment_bounds(groups, len(values))
            for j in np.flatnonzero(np.isnan(values[start:stop]).all(axis=0))]


def _held(values: np.ndarray, groups) -> np.ndarray:
    """State columns with a missing sample holding the previous one (0 before a campaign's first)."""
    out = np.empty_like(values)
    for start, stop in segment_bounds(groups, len(values)):
        out[start:stop] = pd.DataFrame(values[start:stop]).ffill().fillna(0.0).to_numpy()
    return out


def _candidates(exponents) -> list[tuple[float, ...]]:
    """Every subset of ``exponents``, the empty one (no state) first."""
    exps = sorted({float(e) for e in exponents})
    return [c for k in range(len(exps) + 1) for c in combinations(exps, k)]


class Hammerstein(SideInputs, RegressorMixin, BaseEstimator):
    r"""Lag bank on the inputs and on powers of the machine states, powers chosen by time-series CV.

    .. math:: \hat y(t) = c + \sum_{i} \Big( b_{i,0}\, v_i(t) + \sum_{k=1}^{K} b_{i,k}\,
              \big(L_{\tau_k}[v_i](t) - v_i(t)\big) \Big), \qquad
              v = \big(x_1, \dots, x_p,\; u_j^{e}\ (j = 1..m,\ e \in E)\big)

    where :math:`x` are the declared inputs, :math:`u_j = s_j / \max_{\mathrm{train}}|s_j|`
    the machine-state columns of the context matching ``states`` (scaled on
    the training rows; a state constant there is left out), :math:`u^e` the
    sign-preserving power :math:`\mathrm{sign}(u)\,|u|^e` (a speed is
    :math:`\ge 0`; a signed state keeps its sign), :math:`L_\tau` the
    first-order lags and :math:`b, c` the ridge fit of
    :class:`~thermocomp.core.models.lagbank.LagBank` (see there).  The set
    :math:`E` is the subset of ``exponents`` (the empty set -- the plain lag
    bank -- included) with the lowest free-run CV error of the lag bank on the
    training rows: leave-campaigns-out, or forward chaining on one long record.
    No output feedback: simulation and one-step prediction coincide.

    A missing state sample holds the previous one (0 before a campaign's first).
    A state that some training campaign never measures is left out; a campaign
    to predict that never measures a state the model uses is refused
    (:class:`~thermocomp.base.errors.ContractError`), as is one without its column.
    Without a context (or without state columns) this is the plain lag bank.

    Parameters
    ----------
    lagbank : LagBank, optional
        The dynamics and its CV (default ``LagBank()``; ``ar`` must stay
        ``False``), cloned in ``fit``.
    states : list of str or None, default ``['S_*']``
        Glob patterns of the context's machine-state columns; None: none.
    exponents : list of float, default ``[1.0, 2.0]``
        Candidate powers of the scaled states.
    choose_exponents : bool, default True
        False: every power of ``exponents`` enters, no CV between subsets (a
        copy fixed to a fit's choice, see :meth:`chosen_params`).
    state_start : {'rest', 'steady'}, default 'rest'
        The lags of a state at a campaign's first sample.  ``'steady'``: at the state's first
        value, as the temperatures' (as if it had run so forever).  ``'rest'``: a state that is
        never negative and 0 on some training row (a speed, a power, an on/off flag: 0 is its
        rest) starts at 0, its heat beginning with the record; any other state (a temperature,
        a position, a pallet number) steady.  Steady, a run started at full speed holds that
        speed in its longest lags all run: a constant offset (``benchmarks/bench_auto_hmc59.py``).

    Attributes
    ----------
    lagbank_ : LagBank
        Fitted on ``[x | u^e ...]``.
    state_columns_ : list of str
        The state columns used (those matching ``states``, not constant on
        the training rows, the chosen set not empty).
    state_scale_ : ndarray
        :math:`\max_{\mathrm{train}}|s_j|` of each.
    rest_states_ : list of str
        The state columns whose lags start at rest (``state_start='rest'``).
    exponents_ : tuple of float
        The chosen :math:`E` (empty: no state enters).
    cv_results_ : DataFrame
        One row per candidate ``exponents``: its lag bank's chosen free-run
        CV MSE and penalty; ``chosen`` marks the winner.
    context_columns_ : list of str
        ``time`` (when fitted with it) and ``state_columns_``.
    """

    param_rules = {"states": optional(texts("glob patterns")),
                   "exponents": numbers(0.0, open_lo=True), "choose_exponents": BOOLEAN,
                   "state_start": choice("rest", "steady")}

    def __init__(self, lagbank=None, states=("S_*",), exponents=(1.0, 2.0), choose_exponents=True,
                 state_start="rest"):
        self.lagbank = lagbank
        self.states = states
        self.exponents = exponents
        self.choose_exponents = choose_exponents
        self.state_start = state_start

    def param_relations(self) -> list[tuple[str, str]]:
        if self.lagbank is not None and getattr(self.lagbank, "ar", False) is not False:
            return [("lagbank", "must have ar=false (the Hammerstein model has no output feedback)")]
        return []

    def _basis(self, S: np.ndarray, exponents) -> np.ndarray:
        U = S / self.state_scale_
        return np.hstack([np.abs(U) ** e * np.sign(U) for e in exponents]) if exponents else U[:, :0]

    @staticmethod
    def _raw_states(context, n: int, columns) -> np.ndarray:
        if not columns:
            return np.zeros((n, 0))
        S = np.column_stack([np.asarray(require(context, c, "the Hammerstein model (machine state)"),
                                        dtype=float) for c in columns])
        if len(S) != n:
            raise ValueError(f"context has {len(S)} rows, X has {n}")
        return S

    def _states(self, context, n: int) -> np.ndarray:
        """The fitted state columns, held over missing samples; a campaign that never measures one
        is refused (holding 0 through it would read as a machine at rest)."""
        S = self._raw_states(context, n, self.state_columns_)
        groups = groups_of(context)
        for j, row in _unmeasured(S, groups):
            where = f"campaign {groups[row]!r}" if groups is not None else "the rows"
            raise ContractError(f"{where} has no value of {self.state_columns_[j]!r}, a machine state "
                                f"the Hammerstein model reads", column=self.state_columns_[j])
        return _held(S, groups)

    def _usable_states(self, context, n: int) -> tuple[list[str], np.ndarray]:
        """The context's state columns this model can fit on (matching ``states``, measured in
        every campaign, not constant: a state some train campaign never measures, or constant,
        carries nothing to fit) and their values, held over missing samples."""
        found = [] if context is None or self.states is None else match_columns(
            [str(c) for c in context.columns], list(self.states))
        S = self._raw_states(context, n, found)
        unmeasured = {j for j, _ in _unmeasured(S, groups_of(context))}
        S = _held(S, groups_of(context))
        keep = (np.ptp(S, axis=0) > 0) & ~np.isin(np.arange(S.shape[1]), list(unmeasured))
        return [c for c, k in zip(found, keep) if k], S[:, keep]

    def why_no_state(self, context) -> str:
        """Why no machine state enters (:meth:`_usable_states` found none)."""
        if self.states is None:
            return "states=None"
        found = [] if context is None else match_columns([str(c) for c in context.columns],
                                                          list(self.states))
        if not found:
            return f"no machine-state column of the record matches states={list(self.states)}"
        return f"its machine states {found} are constant or unmeasured in a train campaign"

    def plain_lagbank(self, context, n: int) -> LagBank | None:
        """The lag bank (unfitted) this model is on ``context``'s ``n`` rows when no machine
        state can enter (:meth:`_usable_states` finds none): it fits and predicts exactly as that
        lag bank (``model=auto`` validates it once); None where a state may enter."""
        if self._usable_states(context, n)[0]:
            return None
        return clone(self.lagbank) if self.lagbank is not None else LagBank()

    def fit(self, X, y, context=None):
        check_estimator(self)
        base = clone(self.lagbank) if self.lagbank is not None else LagBank()
        # (a target measured now and then: NaN between measurements, the states and the lag
        # bank's features on every row, the fit on the measured ones: LagBank._fit_measured)
        X, y, _ = measured_rows(self, X, y)
        X = np.asarray(X, dtype=float)
        found, S = self._usable_states(context, len(y))
        self.without_states_ = None if found else self.why_no_state(context)
        scale = np.max(np.abs(S), axis=0) if S.size else np.zeros(0)
        self.state_scale_ = scale
        # 0 its least training value: the state's rest (a speed, a flag), where its lags start
        rest = (S.min(axis=0) == 0) if self.state_start == "rest" and S.size else np.zeros(len(found), bool)
        p = X.shape[1]
        records, fitted = [], {}
        fixed = [tuple(sorted({float(e) for e in self.exponents}))]
        for exps in ([()] if not found else _candidates(self.exponents) if self.choose_exponents
                     else fixed):
            model = clone(base)
            model._refit_later = True   # only the chosen powers' lag bank is refitted (below)
            if rest.any():      # the rest states' columns in each power's block of the basis
                model.set_params(rest_columns=[p + b * len(found) + j for b in range(len(exps))
                                               for j in np.flatnonzero(rest)])
            model.fit(np.hstack([X, self._basis(S, exps)]), y, context=context)
            row = model.cv_results_[model.cv_results_["chosen"]].iloc[0]
            records.append({"exponents": list(exps), "cv_mse_free_run": float(row["cv_mse_free_run"]),
                            "alpha": float(row["alpha"])})
            fitted[exps] = model
        table = pd.DataFrame(records)
        best = int(table["cv_mse_free_run"].to_numpy().argmin())   # ties: fewer terms (listed first)
        table["chosen"] = table.index == best
        self.cv_results_ = table
        self.exponents_ = tuple(table.loc[best, "exponents"])
        self.lagbank_ = fitted[self.exponents_]._refit_chosen(
            np.hstack([X, self._basis(S, self.exponents_)]), y, context=context)
        if not self.exponents_:
            found, self.state_scale_, rest = [], scale[:0], rest[:0]
        self.state_columns_ = found
        self.rest_states_ = [c for c, r in zip(found, rest) if r]
        self.context_columns_ = merge_columns(self.lagbank_.context_columns_, found)
        return self

    def chosen_params(self) -> dict:
        """The parameters that fix what the CV chose (the powers, the lag bank's penalty): a copy
        fitted with them runs one lag bank, with no choice of its own (see
        :func:`thermocomp.core.compensator.with_chosen_hyperparameters`)."""
        check_is_fitted(self)
        lagbank = clone(self.lagbank if self.lagbank is not None else LagBank())
        lagbank.set_params(**self.lagbank_.chosen_params())
        if not self.exponents_:         # no state entered: the plain lag bank
            return {"states": None, "lagbank": lagbank}
        return {"exponents": list(self.exponents_), "choose_exponents": False, "lagbank": lagbank}

    def predict(self, X, context=None):
        """Predicted error (free run; ``y_measured`` in ``context`` changes nothing)."""
        check_is_fitted(self)
        X = np.asarray(validate_data(self, X, reset=False), dtype=float)
        S = self._states(context, X.shape[0])
        return self.lagbank_.predict(np.hstack([X, self._basis(S, self.exponents_)]), context=context)

    # -- streaming (deployment) ---------------------------------------------------------
    def stream_init(self, context: Mapping | None = None) -> dict:
        check_is_fitted(self)
        return {"lagbank": self.lagbank_.stream_init(context), "held": np.zeros(len(self.state_columns_))}

    def stream_step(self, x_row, state: dict, context: Mapping | None = None) -> tuple[float, dict]:
        """One sample of ``predict``: ``context`` maps ``time`` and each of ``state_columns_``
        to this sample's values (a NaN state holds the previous sample's)."""
        now = np.array([float(require(context, c, "Hammerstein stream_step")) for c in self.state_columns_])
        held = np.where(np.isnan(now), state["held"], now)
        row = np.concatenate([np.asarray(x_row, dtype=float).reshape(-1),
                              self._basis(held[None, :], self.exponents_)[0]])
        y_hat, lagbank = self.lagbank_.stream_step(row, state["lagbank"], context)
        return y_hat, {"lagbank": lagbank, "held": held}

    def stream_steps(self, X, state: dict, context: Mapping | None = None) -> tuple[np.ndarray, dict]:
        """A block of rows at once (:func:`thermocomp.core.context.stream_steps`): each state
        held over its missing values from the state's, the lag bank's block on the powers."""
        X = np.asarray(X, dtype=float)
        if not len(X):
            return np.empty(0), state
        now = self._raw_states(context, len(X), self.state_columns_)
        held = pd.DataFrame(np.vstack([state["held"], now])).ffill().to_numpy()[1:]
        rows = np.hstack([X, self._basis(held, self.exponents_)])
        y, lagbank = self.lagbank_.stream_steps(rows, state["lagbank"], context)
        return y, {"lagbank": lagbank, "held": held[-1].copy()}

    def step_gain(self, state=None, horizon_s: float = np.inf) -> np.ndarray | None:
        """Gain per input (:func:`thermocomp.core.context.step_gain`): the lag bank's on the
        temperatures (the powers of the states are no inputs)."""
        check_is_fitted(self)
        gain = step_gain(self.lagbank_, None if state is None else state["lagbank"], horizon_s)
        return None if gain is None else gain[:self.n_features_in_]

    def lagged_step_gain(self, lead_taus, horizon_s: float = np.inf,
                         period_s: float | None = None) -> np.ndarray | None:
        """:meth:`step_gain` where input ``j`` is a first-order lag of tau ``lead_taus[j]`` of
        the held step (:meth:`LagBank.lagged_step_gain`; the states' powers do not move)."""
        check_is_fitted(self)
        width = self.lagbank_.coef_.size // (self.lagbank_.taus_.size + 1)
        lead = np.full(width, np.nan)
        lead[:self.n_features_in_] = lead_taus
        gain = self.lagbank_.lagged_step_gain(lead, horizon_s, period_s)
        return None if gain is None else gain[:self.n_features_in_]


def without_states_note(comp) -> str | None:
    """One line where a fitted compensator ``comp`` holds a Hammerstein model into which no
    machine state entered (none in the record, or each constant): it is the plain lag bank,
    ``model=lagbank``'s very fit, which a run says rather than report it as another family."""
    for est in getattr(comp, "estimators_", {}).values():
        why = getattr(est, "without_states_", None) if isinstance(est, Hammerstein) else None
        if why:
            return (f"model=hammerstein: {why}: the plain lag bank was fitted, the same model as "
                    "model=lagbank (its states are what it adds)")
    return None
