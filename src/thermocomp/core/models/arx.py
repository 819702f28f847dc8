"""ARX with greedy input selection and information-criterion model choice (paper 000, Sect. 2.2)."""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy.linalg import lstsq, solve
from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.utils.validation import check_is_fitted, validate_data

from ...base.errors import ParameterError, TooFewSamples
from ...base.params import BOOLEAN, check_estimator, choice, either, integer, integers
from ..context import Y_MEASURED, SideInputs, feedback_gain, groups_of, values
from ..model_selection.criteria import CRITERIA, LABELS, information_criteria
from ..model_selection.greedy import SEARCHES, greedy_path, scaled_gram
from ._dynamics import free_run, lag_index, previous, segment_bounds, segment_starts
from .base import measured_rows

SELECTION_ERRORS = ("equation", "simulation")


def _exogenous(X, groups, terms, coef, intercept) -> np.ndarray:
    """``sum_n b_n x_n(t - k_n) + c`` with lags held at each campaign's first sample."""
    n = X.shape[0]
    u = np.full(n, intercept, dtype=float)
    for d in sorted({d for _, d in terms}):
        picked = [(j, b) for (j, dd), b in zip(terms, coef) if dd == d]
        cols, b = [j for j, _ in picked], np.array([b for _, b in picked])
        u += (X[:, cols] if d == 0 else X[lag_index(groups, n, d)][:, cols]) @ b
    return u


class ARX(SideInputs, RegressorMixin, BaseEstimator):
    r"""First-order ARX per error parameter with greedy input and model selection.

    .. math:: \hat y(t) = a\, y(t-1) + \sum_{n \in S} b_n\, x_n(t - k_n) + c

    For every model size ``1..max_inputs`` and with and without the
    autoregressive term ``a``, the inputs ``S`` (with their delays ``k_n``) are
    chosen greedily among the columns of ``X`` (the split greedy search of
    paper 000, Sect. 2.2, or forward selection), and the model with the lowest
    information criterion wins (BICc by default, as in the paper).
    Coefficients are least squares on the equation error: in training the AR
    regressor is the *measured* previous error.

    Prediction runs in two modes.  Simulation (default): the AR term is fed
    the model's own previous prediction (free run, starting from 0 at each
    campaign start, the reference frame's initial error), as on a machine with
    no measured error.  One-step (``y_measured`` in the context): the AR term
    uses the measured previous error.  Lags never cross campaigns (the
    context's ``campaign``): before a campaign's first sample inputs are held
    at their first value and the previous error is 0.

    scikit-learn's ``check_estimator`` passes with the default ``delays=(0,)``
    whenever the AR term loses; a model with an AR term or delays depends on
    row order by design, so ``check_methods_sample_order_invariance`` and
    ``check_methods_subset_invariance`` do not apply to it.

    Parameters
    ----------
    criterion : {'bicc', 'bic', 'aicc', 'aic'}, default 'bicc'
        Information criterion of the model choice
        (see :func:`~thermocomp.core.model_selection.information_criteria`).
    max_inputs : int, default 10
        Largest number of inputs tried.
    ar : {'auto', True, False}, default 'auto'
        ``'auto'`` lets the criterion decide; ``True``/``False`` force the AR term in or out.
    delays : sequence of int, default (0,)
        Input delays (samples) tried for every input; one delay per input is kept.
    search : {'residual', 'forward'}, default 'residual'
        Greedy search (see :func:`~thermocomp.core.model_selection.greedy_path`); ``residual``
        is the paper's.
    selection_error : {'simulation', 'equation'}, default 'simulation'
        RSS the criterion scores.  ``simulation``: AR models are scored on
        their free-run error (an unstable ``|a| >= 1`` model scores +inf), which
        is how the model runs on a machine.  ``equation``: the one-step equation
        error, as MATLAB's System Identification Toolbox in the paper; with any
        unmodelled slow effect the measured ``y(t-1)`` then wins almost always
        and the free run can drift (on the default year-round data it picks the
        AR term for all three axes and the test RMS of E_Z rises from 5.6 to 7.1 µm).
    fit_intercept : bool, default True

    Attributes
    ----------
    terms_ : list of (int, int)
        ``(column of X, delay)`` of the chosen inputs, in selection order.
    inputs_ : list of str
        Their names (``feature_names_in_`` or ``x<j>``, ``[t-k]`` for delays).
    coef_ : ndarray (n_terms,)
        ``b_n`` of the chosen inputs.
    ar_coef_ : float
        ``a`` (0.0 when the AR term lost).
    intercept_ : float
    selection_ : DataFrame
        One row per model tried: ``ar``, ``n_inputs``, ``inputs``, ``n_params``,
        ``n_obs``, ``rss``, ``aic``, ``aicc``, ``bic``, ``bicc``, ``chosen``.
    chosen_ : dict
        The winner (``ar``, ``n_inputs``, ``inputs``, ``criterion``, ``value``)
        and ``reason``: why it won against the best model of the other AR option.
    """

    def __init__(self, criterion: str = "bicc", max_inputs: int = 10, ar="auto", delays=(0,),
                 search: str = "residual", selection_error: str = "simulation",
                 fit_intercept: bool = True):
        self.criterion = criterion
        self.max_inputs = max_inputs
        self.ar = ar
        self.delays = delays
        self.search = search
        self.selection_error = selection_error
        self.fit_intercept = fit_intercept

    # -- parameters ---------------------------------------------------------------------
    param_rules = {"criterion": choice(*CRITERIA), "max_inputs": integer(1),
                   "ar": choice("auto", True, False), "delays": either(integer(0), integers(0)),
                   "search": choice(*SEARCHES), "selection_error": choice(*SELECTION_ERRORS),
                   "fit_intercept": BOOLEAN}

    def _check_params(self) -> tuple[int, ...]:
        check_estimator(self)
        return tuple(sorted({int(d) for d in np.atleast_1d(self.delays)}))

    def _check_delays(self, delays, groups, n: int) -> None:
        """A delay as long as a campaign holds its input at the campaign's first value throughout
        (``delays=[100000]`` ended in 'ARX found no usable input', a traceback): refused, naming
        the shortest campaign."""
        bounds = segment_bounds(groups, n)
        lo, hi = min(bounds, key=lambda b: b[1] - b[0])
        if max(delays) >= hi - lo:
            name = f" ({np.asarray(groups)[lo]})" if groups is not None else ""
            raise ParameterError(f"ARX.delays={[int(d) for d in delays]}: each delay must be shorter "
                                 f"than the shortest campaign{name}, {hi - lo} samples")

    # -- design -------------------------------------------------------------------------
    def _design(self, X, y, groups, delays, rows) -> tuple[np.ndarray, np.ndarray]:
        """Centred ``[x_j(t-d) for every (d, j) | y(t-1) | y(t)]`` on ``rows``, and the means.

        One allocation, filled in place: the search then needs only ``A.T @ A``.
        """
        n, p = X.shape
        A = np.empty((int(rows.sum()), p * len(delays) + 2))
        for i, d in enumerate(delays):
            A[:, i * p:(i + 1) * p] = X[lag_index(groups, n, d)[rows]]
        # (0 where unmeasured: an AR term is then never fitted, see fit; a constant column)
        A[:, -2] = np.nan_to_num(previous(y, groups)[rows], nan=0.0)
        A[:, -1] = y[rows]
        means = A.mean(axis=0) if self.fit_intercept else np.zeros(A.shape[1])
        A -= means
        return A, means

    def _term_name(self, term) -> str:
        j, d = term
        names = getattr(self, "feature_names_in_", None)
        name = str(names[j]) if names is not None else f"x{j}"
        return name if d == 0 else f"{name}[t-{d}]"

    def fit(self, X, y, context=None):
        delays = self._check_params()
        groups = groups_of(context)
        X, y, measured = measured_rows(self, X, y)
        X = np.asarray(X, dtype=float)
        n, p = X.shape
        if n < 2:
            raise TooFewSamples(f"ARX needs at least 2 samples, got n_samples={n}")
        self._check_delays(delays, groups, n)
        terms = [(j, d) for d in delays for j in range(p)]
        options = [False, True] if self.ar == "auto" else [bool(self.ar)]
        rows = measured.copy()
        if not measured.all():
            # a target measured now and then: the equation error's y(t-1) is not measured at
            # the measured rows, so the AR term cannot be fitted (its delays can: the inputs
            # are dense)
            if self.ar is True:
                raise ParameterError("ARX.ar=true needs the error measured at every sample (the "
                                     "AR term is fitted on y(t-1)); this target is measured now "
                                     "and then (data.sparse_targets): ar=auto or false")
            options = [False]
        if True in options:
            rows[segment_starts(groups, n)] = False   # y(t-1) is unknown at a campaign's first sample
            if not rows.any():
                if self.ar is True:
                    raise ValueError("ARX with ar=True needs campaigns of at least 2 samples")
                options, rows = [False], np.ones(n, dtype=bool)

        A, means = self._design(X, y, groups, delays, rows)
        M, scale = scaled_gram(A)                    # constant columns stay 0: never selected
        i_ar, i_y = len(terms), len(terms) + 1
        sensor_of = [j for j, _ in terms] + [-1, -2]
        n_obs = int(rows.sum())
        tss = float(M[i_y, i_y]) * scale[i_y] ** 2   # the target's sum of squares: the RSS floor's scale
        max_k = min(int(self.max_inputs), p)

        records, paths = [], {}
        for with_ar in options:
            try:
                order, rss, _ = greedy_path(M, i_y, range(len(terms)), sensor_of,
                                            forced=(i_ar,) if with_ar else (), max_inputs=max_k,
                                            search=self.search)
            except np.linalg.LinAlgError:        # constant previous error: no AR model
                continue
            paths[with_ar] = order
            for k in range(1, len(order) + 1):
                value = rss[k - 1] * scale[i_y] ** 2
                if with_ar and self.selection_error == "simulation":
                    value = self._free_run_rss(X, y, groups, rows, M, scale, means,
                                               [terms[j] for j in order[:k]], order[:k])
                n_params = k + int(with_ar) + int(self.fit_intercept)
                records.append({"ar": with_ar, "n_inputs": k,
                                "inputs": ", ".join(self._term_name(terms[j]) for j in order[:k]),
                                "n_params": n_params, "n_obs": n_obs, "rss": value,
                                **information_criteria(value, n_obs, n_params, tss=tss)})
        if not records:
            raise ValueError("ARX found no usable input: every column is constant")
        table = pd.DataFrame(records)
        # Ties go to the smaller model: stable sort by size, then the first minimum.
        ranked = table.sort_values(["n_params", "ar"], kind="stable")
        best = int(ranked[self.criterion].idxmin()) if np.isfinite(ranked[self.criterion]).any() \
            else int(ranked.index[0])
        table["chosen"] = table.index == best
        self.selection_ = table
        win = table.loc[best]
        with_ar, k = bool(win["ar"]), int(win["n_inputs"])
        chosen = paths[with_ar][:k]

        self.terms_ = [terms[j] for j in chosen]
        self.inputs_ = [self._term_name(t) for t in self.terms_]
        self.coef_, self.ar_coef_, self.intercept_ = self._least_squares(A, M, scale, means, chosen,
                                                                          with_ar)
        self.chosen_ = {"ar": with_ar, "n_inputs": k, "inputs": list(self.inputs_),
                        "criterion": self.criterion, "value": float(win[self.criterion]),
                        "reason": self._reason(table, best)}
        self.context_columns_ = []
        return self

    @staticmethod
    def _least_squares(A, M, scale, means, chosen, with_ar) -> tuple[np.ndarray, float, float]:
        """``(b, a, c)`` of the equation-error fit.

        From the scaled Gram matrix when it is well conditioned (a tiny solve),
        else by QR on the centred design (LAPACK gelsy) to keep the accuracy.
        """
        cols = list(chosen) + ([A.shape[1] - 2] if with_ar else [])
        sub = M[np.ix_(cols, cols)]
        if np.linalg.cond(sub) < 1e6:
            theta = solve(sub, M[cols, -1], assume_a="pos", check_finite=False) * scale[-1] / scale[cols]
        else:
            theta = lstsq(A[:, cols], A[:, -1], lapack_driver="gelsy", check_finite=False)[0]
        k = len(chosen)
        a = float(theta[k]) if with_ar else 0.0
        return theta[:k].copy(), a, float(means[-1] - means[cols] @ theta)

    @staticmethod
    def _free_run_rss(X, y, groups, rows, M, scale, means, terms, chosen) -> float:
        """RSS of an equation-error-fitted AR model run free (``inf`` if unstable).

        Its coefficients come from the scaled Gram matrix ``M`` (a (k+1)-square
        solve, not a regression on the data): this runs for every model size.
        """
        cols = list(chosen) + [M.shape[0] - 2]
        try:
            theta = solve(M[np.ix_(cols, cols)], M[cols, -1], assume_a="pos", check_finite=False)
        except np.linalg.LinAlgError:
            return float("inf")
        theta = theta * scale[-1] / scale[cols]
        coef, a = theta[:-1], float(theta[-1])
        c = float(means[-1] - means[cols] @ theta)
        if not abs(a) < 1:
            return float("inf")
        y_hat = free_run(a, _exogenous(X, groups, terms, coef, c), groups)
        return float(np.sum((y - y_hat)[rows] ** 2))

    def _reason(self, table: pd.DataFrame, best: int) -> str:
        crit, win = self.criterion, table.loc[best]
        text = (f"lowest {LABELS[crit]} = {win[crit]:.2f} of {len(table)} models tried "
                f"({int(win['n_inputs'])} inputs, {'with' if win['ar'] else 'without'} AR term)")
        other = table[table["ar"] != win["ar"]]
        if len(other):
            alt = other.loc[other[crit].idxmin()]
            text += (f"; best {'without' if win['ar'] else 'with'} AR term: {alt[crit]:.2f} "
                     f"({int(alt['n_inputs'])} inputs), {alt[crit] - win[crit]:.2f} worse")
        return text

    # -- prediction ---------------------------------------------------------------------
    def _exogenous(self, X, groups) -> np.ndarray:
        return _exogenous(X, groups, self.terms_, self.coef_, self.intercept_)

    def predict(self, X, context=None):
        """Predicted error: free run (simulation), or one-step with ``y_measured`` in ``context``."""
        check_is_fitted(self)
        X = validate_data(self, X, reset=False)
        groups, y_measured = groups_of(context), values(context, Y_MEASURED, X.shape[0])
        u = self._exogenous(X, groups)
        if self.ar_coef_ == 0.0:
            return u
        if y_measured is None:
            return free_run(self.ar_coef_, u, groups)
        y_prev = previous(np.asarray(y_measured, dtype=float), groups)
        missing = np.isnan(y_prev)
        if missing.any():   # a gap in the measurement: carry the model's own estimate
            starts = set(segment_starts(groups, len(u)).tolist())
            out = np.empty_like(u)
            for t in range(len(u)):
                prev = 0.0 if t in starts else (out[t - 1] if missing[t] else y_prev[t])
                out[t] = self.ar_coef_ * prev + u[t]
            return out
        return self.ar_coef_ * y_prev + u

    # -- streaming (deployment) ---------------------------------------------------------
    def stream_init(self, context=None) -> dict:
        """State at a campaign start: previous output 0, no input history yet."""
        check_is_fitted(self)
        return {"y_prev": 0.0, "history": None}

    def stream_step(self, x_row, state: dict, context=None) -> tuple[float, dict]:
        """One sample of simulation-mode ``predict``: ``(y_hat, new_state)``."""
        x_row = np.asarray(x_row, dtype=float).reshape(-1)
        depth = max((d for _, d in self.terms_), default=0) + 1
        history = state["history"]
        history = np.tile(x_row, (depth, 1)) if history is None \
            else np.vstack([history[1:], x_row[None, :]])
        u = self.intercept_
        for (j, d), b in zip(self.terms_, self.coef_):
            u += b * history[depth - 1 - d, j]
        y_hat = float(self.ar_coef_ * state["y_prev"] + u)
        return y_hat, {"y_prev": y_hat, "history": history}

    def stream_steps(self, X, state: dict, context=None) -> tuple[np.ndarray, dict]:
        """A block of rows at once (:func:`thermocomp.core.context.stream_steps`): the delayed
        inputs from the history joined to the block, the feedback by ``lfilter`` from the
        state's previous output."""
        from scipy.signal import lfilter

        X = np.asarray(X, dtype=float)
        if not len(X):
            return np.empty(0), state
        depth = max((d for _, d in self.terms_), default=0) + 1
        history = state["history"]
        # the rows before the block's first as stream_step keeps them (a start: its first row)
        past = np.tile(X[0], (depth - 1, 1)) if history is None else history[1:]
        joined = np.vstack([past, X])
        n = len(X)
        u = np.full(n, float(self.intercept_))
        for (j, d), b in zip(self.terms_, self.coef_):      # stream_step's order of the sum
            u += b * joined[depth - 1 - d:depth - 1 - d + n, j]
        a = float(self.ar_coef_)
        y = u if a == 0.0 else lfilter([1.0], [1.0, -a], u, zi=[a * state["y_prev"]])[0]
        return y, {"y_prev": float(y[-1]), "history": joined[-depth:].copy()}

    def step_gain(self, state=None, horizon_s: float = np.inf) -> np.ndarray | None:
        """Gain per input (:func:`thermocomp.core.context.step_gain`): each input's
        coefficients summed over its delays, through the AR term at its steady state (ARX
        counts samples, not seconds: ``horizon_s`` is not read)."""
        check_is_fitted(self)
        gain = np.zeros(self.n_features_in_)
        for (j, _), b in zip(self.terms_, self.coef_):
            gain[j] += b
        return feedback_gain(gain, self.ar_coef_)

    def lagged_step_gain(self, lead_taus, horizon_s: float = np.inf,
                         period_s: float = 1.0) -> np.ndarray | None:
        """:meth:`step_gain` where column ``j`` is a first-order lag of tau ``lead_taus[j]`` of
        the held step (``nan``: the step itself), as a diagnosed low-pass copy ``L_tau[x]`` of the
        inputs is: the difference equation's response to it ``m = horizon_s / period_s`` samples
        into the step, exact at the stream's samples (gain61).

        The lag (pole ``p = exp(-period_s / tau)``, updated on its input's new value; ``p = 0``:
        the step) is ``1 - p^k`` ``k`` samples in; a term ``b x_j(t - d)`` on it, through the
        feedback ``a``, is ``b sum_{k=1..M} a^(M-k) (1 - p^k)``, ``M = m - d``
        (:func:`_lagged_response`).  At an infinite horizon :meth:`step_gain`'s steady state,
        which the model alone gives at any (it counts samples, not seconds: no period); with a
        period the response at the horizon, as a lag bank's lags and a static base's copy are
        (tests/shell/test_clamp_diagnosed60's ARX, ``a = 0.986`` over a horizon of 49 samples:
        2.14 µm/K on ``T_a``; the steady state on ``x`` and the horizon on the copy gave 21.4).
        ``None`` without a steady state (``|a| >= 1``)."""
        check_is_fitted(self)
        a = float(self.ar_coef_)
        if abs(a) >= 1.0:
            return None
        lead = np.asarray(lead_taus, float)
        m = horizon_s / float(period_s)
        gain = np.zeros(self.n_features_in_)
        for (j, d), b in zip(self.terms_, self.coef_):
            p = 0.0 if np.isnan(lead[j]) else float(np.exp(-period_s / lead[j]))
            gain[j] += b * _lagged_response(a, p, m - d)
        return gain


def _lagged_response(a: float, p: float, M: float) -> float:
    """``sum_{k=1..M} a^(M-k) (1 - p^k)``: the output of ``y(t) = a y(t-1) + u(t)``, at rest, ``M``
    samples after its input ``u`` began the response ``1 - p^k`` of a lag of pole ``p`` to a unit
    step (``p = 0``: the step): ``(1 - a^M) / (1 - a) - p (a^M - p^M) / (a - p)`` (``- M p^M``
    where ``a = p``)."""
    if not np.isfinite(M):
        return 1.0 / (1.0 - a)
    if M <= 0:
        return 0.0
    aM = np.sign(a) ** round(M) * abs(a) ** M      # a negative feedback: the nearest sample's sign
    if np.isclose(a, p, rtol=1e-9, atol=0.0):
        return (1.0 - aM) / (1.0 - a) - M * p ** M
    return (1.0 - aM) / (1.0 - a) - p * (aM - p ** M) / (a - p)
