r"""Lag bank: every input through causal first-order lags on a log grid, ridge chosen by time-series CV.

.. math:: \hat y(t) = c + \sum_{i=1}^{p} \Big( b_{i,0}\, x_i(t)
          + \sum_{k=1}^{K} b_{i,k}\, \big(L_{\tau_k}[x_i](t) - x_i(t)\big) \Big)
          \;[+\; a\, y(t-1)]

:math:`L_\tau` is the first-order lag :math:`\tau \dot z + z = x` (a thermal
mass between a sensor and the structure that moves), discretised exactly for
any sampling and started in steady state at each campaign's first sample
(:func:`~thermocomp.core.models._dynamics.first_order_lags`).  A sum of first-order
lags on a log grid of time constants approximates any stable, non-oscillating
thermal transfer function from a sensor to the error, so one linear model
covers what would otherwise be a search over delays and time constants; the
ridge penalty keeps the many strongly correlated features in check.  The lags
enter as their lead over the input, :math:`L_\tau[x] - x` (the same linear
span as :math:`L_\tau[x]`): zero in steady state, so the penalty on them
shrinks towards the static model :math:`c + b_0^\top x`, whose gain is the
steady gain, and the dynamic terms only have to earn their transients.  The
levels :math:`b_0` carry ``level_penalty`` times the penalty: by default (1)
the same, so the strongest penalty leaves a constant; with 0 they are free
and it leaves the static least-squares model (MLR).

Its strength is chosen by time-series cross-validation on the training rows
only: campaigns -> leave-campaigns-out, one long record -> forward chaining
(expanding window, a gap of the longest lag between train and validation).
See :func:`default_splitter`.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd
from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.model_selection import GroupKFold
from sklearn.preprocessing import StandardScaler
from sklearn.preprocessing._data import _handle_zeros_in_scale, _is_constant_feature
from sklearn.utils.validation import check_is_fitted, validate_data
from threadpoolctl import threadpool_limits

from ...base.errors import ParameterError, TooFewSamples
from ...base.params import (
    NON_NEGATIVE,
    POSITIVE,
    check_estimator,
    choice,
    either,
    integer,
    integers,
    numbers,
    optional,
)
from ..context import TIME, Y_MEASURED, SideInputs, feedback_gain, groups_of, scalar, values
from ..model_selection.splitters import ForwardChaining, forward_block
from ..model_selection.splitters import forward_gap as shared_forward_gap
from ..timerule import CLOCK_START, median_step, step_time
from ._dynamics import (
    free_run,
    lag_index,
    previous,
    segment_bounds,
    segment_starts,
)
from ._memo import ArrayMemo
from ._pooled import (
    CampaignMoments,
    lag_features,
    pooled_path_cv,
    pooled_refit,
    spectra_of_grams,
    standardisation,
    weights_of_moments,
)
from .base import measured_rows

DEFAULT_ALPHAS = np.logspace(-4, 6, 21)   # ridge penalties on standardised features, half-decade steps
MIN_SPLITS = 2


# -- time-series splitters: the shared ones (thermocomp.core.model_selection.splitters) ------------------
MIN_TRAIN_FRACTION = 0.5


def default_splitter(groups, n: int, gap: int, n_splits: int = 5):
    """The CV splitter of ``n`` training rows: leave-campaigns-out or forward chaining.

    Two or more campaigns in ``groups``: :class:`~sklearn.model_selection.GroupKFold`
    over campaigns (``min(n_splits, n_campaigns)`` folds), campaigns being the
    units that are independent of each other.  One campaign (or none given):
    :class:`ForwardChaining` with ``gap`` rows between train and validation.
    Its ``split(X, y, groups)`` yields ``(train, validation)`` row indices.
    """
    if groups is not None:
        n_campaigns = len(pd.unique(np.asarray(groups, dtype=object)))
        if n_campaigns >= 2:
            return GroupKFold(n_splits=min(int(n_splits), n_campaigns))
    return ForwardChaining(n_splits=int(n_splits), gap=int(gap), min_train_fraction=MIN_TRAIN_FRACTION)


def forward_gap(longest_lag_samples: float, n: int, n_splits: int,
                min_train_fraction: float = MIN_TRAIN_FRACTION) -> int:
    """Gap of forward chaining over ``n`` rows: the longest lag in samples, at most half a
    validation block (:func:`thermocomp.core.model_selection.splitters.forward_gap`)."""
    return shared_forward_gap(longest_lag_samples, forward_block(n, n_splits, min_train_fraction))


# -- the ridge path over the folds ---------------------------------------------------------------
def ridge_path_cv(Z, y, splits, alphas, groups=None, ar_column: int | None = None,
                  ar_scaling: tuple[float, float] = (0.0, 1.0), z_key: bytes | None = None,
                  free_columns: int = 0) -> dict:
    r"""Validation MSE of ridge fits of ``y`` on ``Z`` for every fold and penalty.

    Each fold centres ``Z`` and ``y`` on its training rows and solves
    :math:`(Z_c^\top Z_c + \alpha D)\,w = Z_c^\top y_c` for every ``alpha`` from
    one eigendecomposition of the fold's Gram matrix, :math:`D` the identity
    but for the first ``free_columns`` columns, which are not penalised (:func:`fold_weights`).
    With ``free_columns=0`` these are the numbers of scikit-learn's ``RidgeCV(alphas, cv=splits,
    scoring='neg_mean_squared_error')`` (one ``Ridge`` per fold and penalty, i.e. one
    Gram product each) at the cost of one Gram product per fold.

    With ``ar_column`` (the column of ``Z`` holding :math:`(y(t-1) - \mu)/\sigma`,
    ``ar_scaling = (mu, sigma)``) the fitted equation is also run free -- its
    own previous prediction fed back, from 0 at each segment start of
    ``groups`` through every row, as on a machine -- and scored on the
    validation rows (``inf`` when unstable).

    The folds' factorisations depend on ``Z`` alone and are remembered (every target of a
    compensator shares its features): by ``z_key``, a digest standing for ``Z``, else by
    ``Z``'s bytes.

    Returns
    -------
    dict
        ``one_step`` and ``free_run``: arrays (n_folds, n_alphas) of validation MSE.
    """
    alphas = np.asarray(alphas, dtype=float)
    n_folds = len(splits)
    one_step = np.empty((n_folds, alphas.size))
    free = np.empty_like(one_step)
    others = [j for j in range(Z.shape[1]) if j != ar_column]
    # the folds' Gram matrices depend on Z alone: every target of a compensator shares them
    spectra = fold_spectra(Z, splits, alphas, free_columns, z_key)
    for f, (tr, va) in enumerate(splits):
        W, c = fold_weights(spectra[f], Z, y, tr, alphas)
        one_step[f] = np.mean((Z[va] @ W + c - y[va, None]) ** 2, axis=0)
        if ar_column is None:
            free[f] = one_step[f]
            continue
        # y(t) = w (y(t-1) - mu) / sigma + u(t) = a y(t-1) + u(t) - a mu: back to the raw y(t-1)
        mu, sigma = ar_scaling
        a = W[ar_column] / sigma
        u = Z[:, others] @ W[others] + c - a * mu
        for i in range(alphas.size):
            if not abs(a[i]) < 1.0:
                free[f, i] = np.inf
                continue
            y_hat = free_run(float(a[i]), u[:, i], groups)
            free[f, i] = np.mean((y_hat[va] - y[va]) ** 2)
    return {"one_step": one_step, "free_run": free}


def _training_grams(Z, splits):
    """``(mean, centred Gram)`` of each fold's training rows.  Folds that split the rows in
    two (leave-campaigns-out) take the whole Gram less the validation rows' (one product of
    all rows and one of each validation block, instead of one of each training set)."""
    n = len(Z)
    trains, valids = splits[::2], splits[1::2]
    if all(np.array_equal(np.bincount(np.r_[tr, va], minlength=n), np.ones(n, dtype=int))
           for tr, va in zip(trains, valids)):
        total, sums = Z.T @ Z, Z.sum(axis=0)
        for tr, va in zip(trains, valids):
            Zva = Z[va]
            mean = (sums - Zva.sum(axis=0)) / len(tr)
            yield mean, total - Zva.T @ Zva - len(tr) * np.outer(mean, mean)
        return
    lengths = [len(tr) for tr in trains]
    if all(m and tr[0] == 0 and tr[-1] == m - 1 and np.all(np.diff(tr) == 1)
           for tr, m in zip(trains, lengths)):
        yield from _prefix_grams(Z, lengths)   # forward chaining: nested prefixes, one pass
        return
    for tr in trains:
        Ztr = Z[tr]
        mean = Ztr.mean(axis=0)
        Ztr -= mean
        gram = Ztr.T @ Ztr
        del Ztr                        # not held while the next fold's copy is made
        yield mean, gram


# rows of Z centred at a time by _prefix_grams: a copy of this many bytes, not of a fold's rows;
# below glibc's largest mmap threshold (32 MB), so each block reuses the last one's pages
# instead of faulting in fresh (huge) pages (64 MB blocks: 0.4-0.6 s of sys time a pass on
# 300,000 x 306, 16 MB none)
PREFIX_BLOCK_BYTES = 16e6


def _prefix_grams(Z, lengths):
    r"""``(mean, centred Gram)`` of each prefix ``Z[:m]``, ``m`` in ``lengths``, in one pass.

    Forward chaining's training sets are nested prefixes: each fold's product over its own rows
    (a copy of up to 0.9 of a year's 1.2 GB features each, and their sum 3.5 times the rows of
    one) is the running one of blocks of rows, each block's moments pooled into it as they come
    (Chan, Golub & LeVeque's update: no cancellation of :math:`\sum z z^\top - m \bar z \bar z^\top`).
    """
    p = Z.shape[1]
    block = max(1, int(PREFIX_BLOCK_BYTES // (8 * max(p, 1))))
    count, mean, gram = 0, np.zeros(p), np.zeros((p, p))
    done, start = {}, 0
    for stop in sorted(set(lengths)):
        for lo in range(start, stop, block):
            rows = Z[lo:min(lo + block, stop)]
            b_mean = rows.mean(axis=0)
            rows = rows - b_mean
            b_count, shift = len(rows), b_mean - mean
            total = count + b_count
            gram = gram + rows.T @ rows + np.outer(shift, shift) * (count * b_count / total)
            mean = mean + shift * (b_count / total)
            count = total
        done[stop], start = (mean, gram), stop
    for m in lengths:
        yield done[m][0].copy(), done[m][1].copy()   # spectra_of_grams overwrites the Gram


def _compute_fold_spectra(Z, alpha, free, *splits) -> tuple:
    """Per fold ``(mean, eigenvalues, eigenvectors, B, S)`` of the centred training rows' Gram
    matrix, or with one penalty ``alpha`` ``(mean, None, Cholesky factor of G + alpha I, B, S)``.

    With ``free`` unpenalised leading columns ``s`` the spectrum is that of the penalised
    columns' Gram with ``s`` projected out, :math:`G_{pp} - G_{ps} G_{ss}^{+} G_{sp}`
    (Frisch-Waugh-Lovell), ``S`` :math:`G_{ss}^{+}` and ``B`` :math:`G_{ss}^{+} G_{sp}`
    (both None without free columns).
    """
    return spectra_of_grams(_training_grams(Z, splits), alpha, free)


_fold_spectra = ArrayMemo(_compute_fold_spectra, size=4)


def fold_spectra(Z, splits, alphas, free: int = 0, z_key: bytes | None = None) -> tuple:
    """The factorisations of each fold's training Gram matrix (:func:`_compute_fold_spectra`),
    remembered by ``z_key`` (a digest standing for ``Z``), else by ``Z``'s bytes."""
    alphas = np.atleast_1d(np.asarray(alphas, dtype=float))
    args = (alphas[0] if alphas.size == 1 else None, int(free),
            *(rows for split in splits for rows in split))
    key = _fold_spectra.key(z_key, *args) if z_key is not None else _fold_spectra.key(Z, *args)
    return _fold_spectra.lookup(key, Z, *args)


def fold_weights(spectrum, Z, y, tr, alphas) -> tuple[np.ndarray, np.ndarray]:
    r"""``(W, c)``: ridge coefficients (one column per penalty) and intercepts on the rows ``tr``.

    Solves :math:`(G + \alpha D) w = Z_c^\top y_c` from the fold's ``spectrum``
    (:func:`fold_spectra`); the free columns' part follows the penalised one,
    :math:`w_s = G_{ss}^{+} r_s - B\, w_p`.
    """
    y_mean = y[tr].mean()
    weights = np.zeros(len(y))
    weights[tr] = y[tr] - y_mean
    rhs = Z.T @ weights                  # (Z_tr - mean)^T (y_tr - y_mean): the centred y sums to 0
    return weights_of_moments(spectrum, rhs, y_mean, alphas)


def _summary(name: str, folds: np.ndarray) -> dict:
    """Mean and s.d. over folds (``inf`` for an unstable model)."""
    if not np.all(np.isfinite(folds)):
        return {name: float("inf"), f"{name}_sd": float("inf")}
    return {name: float(np.mean(folds)), f"{name}_sd": float(np.std(folds))}


# one stack of rows is featurised for every target, every fold and every single-campaign model;
# bounded in bytes too: a year at 1 min of 34 sensors makes 1.2 GB of features per stack, and four
# stacks held at once took a run to 7 GB (scale58); past the bound only the newest is kept
LAG_FEATURES_MAX_BYTES = 512e6
_lag_bank_features = ArrayMemo(lag_features, max_bytes=LAG_FEATURES_MAX_BYTES)


def _clock_of(t: float | None) -> tuple:
    """The time rule's clock of a stream state saved before it (its last time ``t``, None at a
    start): a time read goes on being taken as it is, as that state's rule took it."""
    return CLOCK_START if t is None else (False, float(t), float("nan"), 0.0)


def _block_times(context, n: int) -> np.ndarray:
    """The ``time`` of each of a block's ``n`` rows (NaN where the context has none)."""
    time = None if context is None else context.get(TIME)
    if time is None:
        return np.full(n, np.nan)
    return np.broadcast_to(np.asarray(time, dtype=float), (n,))


def _block_clock(clock: tuple, time: np.ndarray, period_s: float) -> tuple[tuple, np.ndarray]:
    """``(clock after, dt of each row)`` of :func:`step_time` over a block's ``time``: in one go
    where every time is read (after the first, the clock's offset is fixed), else row by row."""
    n = len(time)
    dt = np.empty(n)
    if np.isfinite(time).all():
        clock, now, dt[0], _ = step_time(clock, float(time[0]), period_s)
        shift = clock[3]
        if n > 1:
            now_all = time - shift                # step_time's own subtraction
            dt[1:] = np.diff(now_all)
            now_all[0] = now
            clock = (False, float(now_all[-1]), float(time[-1]), shift, float("nan"))
        return clock, dt
    for i in range(n):
        clock, _, dt[i], _ = step_time(clock, float(time[i]), period_s)
    return clock, dt


def _increments(F, groups) -> np.ndarray:
    """``F(t) - F(t-1)`` per segment, 0 at a segment's first row (steady before it)."""
    return F - F[lag_index(groups, len(F), 1)]


def _level_scale(n_columns: int, p: int, ratio: float) -> np.ndarray:
    """Column factors that turn a penalty ``ratio * alpha`` on the ``p`` leading columns into
    ``alpha``: ridge on ``Z / sqrt(ratio)`` is ridge on ``Z`` with that penalty (1 for ``ratio=0``,
    whose columns are left free instead)."""
    scale = np.ones(n_columns)
    if ratio > 0:
        scale[:p] = 1.0 / np.sqrt(ratio)
    return scale


def _records(design: str, ratio: float, alphas, scores: dict) -> list[dict]:
    """The CV table's rows of one design and level penalty, one per ridge penalty
    (``scores``: :func:`ridge_path_cv`'s; the increments design has no free-run error)."""
    out = []
    for i, alpha in enumerate(alphas):
        free = scores["free_run"][:, i] if design != "increments" else np.array([np.inf])
        out.append({"design": design, "ar": design == "lags+ar", "alpha": float(alpha),
                    "level_penalty": ratio, **_summary("cv_mse_free_run", free),
                    **_summary("cv_mse_one_step", scores["one_step"][:, i])})
    return out


def _levels_weighted(Z, p: int, ratio: float) -> tuple[np.ndarray, int]:
    """``(Z with its p levels scaled, number of free columns)`` of the level penalty ``ratio``."""
    if ratio == 0:
        return Z, p
    return (Z * _level_scale(Z.shape[1], p, ratio) if ratio != 1 else Z), 0


# -- the standardisation of a design, in blocks --------------------------------------------------
def _blocks(D):
    """Row blocks of ``D`` of at most :data:`PREFIX_BLOCK_BYTES` (views)."""
    rows = max(1, int(PREFIX_BLOCK_BYTES // (8 * max(D.shape[1], 1))))
    return [D[start:start + rows] for start in range(0, len(D), rows)] or [D]


def _column_sums(blocks) -> np.ndarray:
    """``np.sum(D, axis=0)`` of the stacked ``blocks``, bit for bit: numpy adds a C-ordered
    array's rows one after the other, so each block continues from the sum so far."""
    total = None
    for block in blocks:
        total = block.sum(axis=0) if total is None else np.add.reduce(np.vstack([total[None], block]),
                                                                      axis=0)
    return total


def standard_scaler(D) -> StandardScaler:
    """``StandardScaler().fit(D)`` of a finite design, bit for bit, in blocks of rows.

    scikit-learn's fit makes ``D - mean`` (a copy of the design: a year's 1.2 GB) and its NaN mask,
    and checks and converts ``D`` first; this runs its numbers (Chan, Golub & LeVeque's two-pass
    variance, ``_incremental_mean_and_var`` from nothing) over blocks of rows instead
    (tests/core/test_scale60.py holds the two equal, so an upgrade that moves them fails there).
    """
    D = np.asarray(D, dtype=float)
    total = _column_sums(_blocks(D))
    if not np.isfinite(total).all():   # a NaN or inf: scikit-learn's own rules
        return StandardScaler().fit(D)
    count = np.full(D.shape[1], float(len(D)))
    mean = total / count
    correction = _column_sums(block - mean for block in _blocks(D))
    squares = _column_sums((block - mean) ** 2 for block in _blocks(D))
    var = (squares - correction ** 2 / count) / count
    scaler = StandardScaler()
    scaler.n_features_in_, scaler.n_samples_seen_ = D.shape[1], np.int64(len(D))
    scaler.mean_, scaler.var_ = mean, var
    scaler.scale_ = _handle_zeros_in_scale(np.sqrt(var), copy=False,
                                           constant_mask=_is_constant_feature(var, mean, len(D)))
    return scaler


def standardised(D, scaler: StandardScaler) -> np.ndarray:
    """``scaler.transform(D)`` (a new array), bit for bit, without scikit-learn's checks and its
    copy of ``D`` before the one it standardises in place."""
    out = np.empty(D.shape)
    for block, rows in zip(_blocks(np.asarray(D, dtype=float)), _blocks(out)):
        np.subtract(block, scaler.mean_, out=rows)
        rows /= scaler.scale_
    return out


# -- the estimator ---------------------------------------------------------------------------------
class LagBank(SideInputs, RegressorMixin, BaseEstimator):
    r"""Linear model of the inputs and their first-order lags on a log grid, ridge by time-series CV.

    .. math:: \hat y(t) = c + \sum_i \Big( b_{i,0}\, x_i(t) + \sum_{k=1}^{K} b_{i,k}\,
              \big(L_{\tau_k}[x_i](t) - x_i(t)\big) \Big) \;[+\; a\, y(t-1)]

    :math:`L_\tau[x](t)` is the first-order lag of input :math:`x` with time
    constant :math:`\tau` (exact discretisation, steady start at each
    campaign's first sample; its lead over :math:`x` vanishes in steady state,
    see the module docstring); :math:`\tau_1 < \dots < \tau_K` are
    log-spaced from ``tau_min_s`` (default: the sample period) to
    ``tau_max_s``.  The features are standardised on the training rows and
    fitted by ridge regression; its penalty ``alpha`` is the one of
    ``alphas`` with the lowest mean validation MSE over the folds of
    :func:`default_splitter` on the *training rows* (leave-campaigns-out for
    campaign data; for one long record forward chaining over its second half
    with a gap of the longest lag, see :class:`ForwardChaining` and
    :func:`forward_gap`).

    The optional autoregressive term ``a y(t-1)`` is fitted on the measured
    previous error (equation error; 0 before a campaign's first sample, the
    reference frame's value).  Prediction runs in simulation mode (free run:
    the model's own previous prediction fed back, from 0 at each campaign
    start) unless the context holds ``y_measured`` (one-step mode: the measured
    previous error).  For an AR model ``alpha`` is chosen on the free-run
    validation error, as the model runs on a machine (the one-step error
    instead only if no penalty gives a stable model); ``ar='auto'`` keeps the
    term only if its best free-run CV error beats the model without it.
    With ``ar=True`` or ``'auto'`` one-step prediction has its own model, the
    lowest *one-step* CV error among two designs and all penalties: the AR
    model above (a free-run penalty would shrink the measured :math:`y(t-1)`
    along with the lags), and the increments model

    .. math:: \hat y(t) = y(t-1) + c + \sum_j b_j \big(f_j(t) - f_j(t-1)\big)

    over the same features :math:`f_j` -- persistence plus the effect of what
    changed since the last sample, which the penalty shrinks towards
    persistence (on a drifting record a fitted :math:`a < 1` pulls every
    prediction back towards the training mean).  With ``ar=False`` both modes
    coincide.

    Lags never cross a campaign start (the context's ``campaign``); the time
    steps come from the context's ``time`` (s), else from the row index times
    ``sample_period_s``.  The output at ``t`` depends on earlier rows, so
    scikit-learn's ``check_methods_sample_order_invariance`` and
    ``check_methods_subset_invariance`` do not apply.

    Parameters
    ----------
    n_taus : int, default 8
        Number :math:`K` of time constants.
    tau_min_s : float or None, default None
        Shortest time constant (s); None: the sample period.
    tau_max_s : float, default 172800.0
        Longest time constant (s), 2 days.
    alphas : array-like or None, default None
        Ridge penalties tried (on standardised features); None:
        ``np.logspace(-4, 6, 21)``.
    n_splits : int, default 5
        Folds of the CV (fewer with fewer campaigns or samples).
    ar : {False, True, 'auto'}, default False
        Autoregressive term; ``'auto'`` decides by the free-run CV error (one-step
        prediction uses the AR model with either ``True`` or ``'auto'``).
    sample_period_s : float, default 60.0
        Time step (s) assumed when the context has no ``time``.
    level_penalty : float >= 0 or list of them, default 1.0
        The levels' penalty as a share of ``alpha`` (the lags carry ``alpha``): 1 shrinks
        all coefficients alike, 0 leaves the levels free (least squares given the lags);
        several values: the CV chooses among them and ``alphas``.  On ``large_mill_week``
        (one training week, every forward fold extrapolating) the CV picks the strongest
        penalty and E_X gets 7.5 µm against MLR's 2.0; 0 gives 1.6-2.5 but doubles the
        error on records where MLR extrapolates badly (``benchmarks/bench_lagbank_records.py``).
    rest_columns : list of int or None, default None
        Input columns whose lags start at rest (0) at a campaign's first sample instead of
        in steady state at their first value: an input that was 0 before the record (a machine
        state, see :class:`~thermocomp.core.models.hammerstein.Hammerstein`).

    Attributes
    ----------
    taus_ : ndarray (K,)
        Time constants (s).
    sample_period_s_ : float
        Median training time step (s).
    features_ : list of str
        Feature names, ``x`` then ``L[<tau>s](x)-x`` for each input.
    coef_ : ndarray (p (K + 1),)
        Coefficients of the (unstandardised) features.
    ar_coef_ : float
        ``a`` (0.0 without the AR term).
    intercept_ : float
    alpha_ : float
        Chosen ridge penalty.
    level_penalty_ : float
        Chosen share of it on the levels.
    one_step_design_ : {'lags+ar', 'increments'} or None
        Design of the one-step model (None with ``ar=False``).
    coef_one_step_, ar_coef_one_step_, intercept_one_step_, alpha_one_step_ : ndarray, float or None
        Its coefficients (``ar_coef_one_step_`` is 1 for ``increments``) and penalty.
    splitter_ : cross-validator
        The splitter used; ``gap_`` its gap (rows, forward chaining only).
    cv_results_ : DataFrame
        One row per (``design``, ``level_penalty``, ``alpha``), designs ``lags``, ``lags+ar``
        (``ar`` True) and ``increments``: mean and s.d. over folds of the
        validation MSE in ``free_run`` (inf for ``increments``) and
        ``one_step`` mode; ``chosen`` marks the free-run model.
    context_columns_ : list of str
        ``['time']`` when fitted with a ``time`` context, else ``[]``.
    """

    def __init__(self, n_taus: int = 8, tau_min_s: float | None = None,
                 tau_max_s: float = 172800.0, alphas=None, n_splits: int = 5, ar=False,
                 sample_period_s: float = 60.0, level_penalty=1.0, rest_columns=None):
        self.n_taus = n_taus
        self.tau_min_s = tau_min_s
        self.tau_max_s = tau_max_s
        self.alphas = alphas
        self.n_splits = n_splits
        self.ar = ar
        self.sample_period_s = sample_period_s
        self.level_penalty = level_penalty
        self.rest_columns = rest_columns

    # -- parameters ---------------------------------------------------------------------
    # n_taus: a feature per input and time constant
    param_rules = {"n_taus": integer(1, at_most=1000), "tau_min_s": optional(POSITIVE), "tau_max_s": POSITIVE,
                   "alphas": optional(either(POSITIVE, numbers(0.0, open_lo=True))),
                   "n_splits": integer(MIN_SPLITS), "ar": choice(False, True, "auto"),
                   "sample_period_s": POSITIVE, "level_penalty": either(numbers(0.0), NON_NEGATIVE),
                   "rest_columns": optional(integers(0, empty=True))}

    def _rest(self, p: int) -> np.ndarray | None:
        """The columns of :attr:`rest_columns` as a mask over ``p`` inputs (None: none)."""
        if not self.rest_columns:
            return None
        mask = np.zeros(p, bool)
        mask[np.asarray(list(self.rest_columns), dtype=int)] = True
        return mask

    def param_relations(self) -> list[tuple[str, str]]:
        if self.tau_min_s is not None and not self.tau_min_s <= self.tau_max_s:
            return [("tau_min_s", f"must not exceed tau_max_s={self.tau_max_s}")]
        return []

    def _check_params(self) -> tuple[np.ndarray, list[float]]:
        """``(alphas, level penalty ratios)``, sorted (the ratios from 1 down)."""
        check_estimator(self)
        alphas = DEFAULT_ALPHAS if self.alphas is None else np.atleast_1d(
            np.asarray(self.alphas, dtype=float))
        ratios = sorted({float(r) for r in np.atleast_1d(self.level_penalty)}, reverse=True)
        return np.sort(alphas), ratios

    # -- features -----------------------------------------------------------------------
    def _time(self, context, groups, n: int) -> np.ndarray:
        """Context time, or the row index in each campaign times the sample period."""
        time = values(context, TIME, n)
        if time is not None:
            return time
        out = np.empty(n)
        period = getattr(self, "sample_period_s_", self.sample_period_s)
        for start, stop in segment_bounds(groups, n):
            out[start:stop] = np.arange(stop - start) * period
        return out

    def _features(self, X, context) -> np.ndarray:
        """``[x | L_tau1[x] - x | ... | L_tauK[x] - x]``, one block of ``p`` columns per time
        constant (read-only: remembered for the next model on the same rows)."""
        return self._keyed_features(X, context)[1]

    def _keyed_features(self, X, context) -> tuple[bytes, np.ndarray]:
        """(digest of what the features derive from, :meth:`_features`)."""
        groups, n = groups_of(context), X.shape[0]
        starts = segment_starts(groups, n)    # campaigns as run numbers: a numeric memo key
        runs = None if groups is None else np.repeat(np.arange(starts.size), np.diff(np.r_[starts, n]))
        args = (np.asarray(X, dtype=float), self._time(context, groups, n), runs, self.taus_,
                self._rest(X.shape[1]))
        key = _lag_bank_features.key(*args)
        return key, _lag_bank_features.lookup(key, *args)

    # -- fit ----------------------------------------------------------------------------
    # The ridge path's matrices are a few hundred columns wide: BLAS threads only add contention
    # (an eigendecomposition 15x slower with 2 threads on a busy 2-core machine), as in diagnose.
    @threadpool_limits.wrap(limits=1, user_api="blas")
    def fit(self, X, y, context=None):
        alphas, ratios = self._check_params()
        X, y, measured = measured_rows(self, X, y)
        X = np.asarray(X, dtype=float)
        n, p = X.shape
        if n < MIN_SPLITS + 1:
            raise TooFewSamples(f"LagBank needs at least {MIN_SPLITS + 1} samples for its time-series "
                             f"CV, got n_samples={n}")
        groups = groups_of(context)
        time = values(context, TIME, n)
        period = median_step(time, groups) if time is not None else None
        self.sample_period_s_ = period if period is not None else float(self.sample_period_s)
        tau_min = self.sample_period_s_ if self.tau_min_s is None else float(self.tau_min_s)
        tau_min = min(tau_min, float(self.tau_max_s))
        self.taus_ = np.geomspace(tau_min, float(self.tau_max_s), int(self.n_taus))
        names = [str(c) for c in getattr(self, "feature_names_in_", [f"x{j}" for j in range(p)])]
        self.features_ = names + [f"L[{tau:.6g}s]({c})-{c}" for tau in self.taus_ for c in names]
        if not measured.all():      # a target measured now and then: see _fit_measured
            return self._fit_measured(X, y, measured, context, groups, alphas, ratios, p, time)

        splits = self._splits(X, y, groups, self.taus_[-1] / self.sample_period_s_)
        folds = self._campaign_folds(groups, n, splits) if self.ar is False else None
        if folds is not None:
            return self._fit_pooled(X, y, context, groups, folds, alphas, ratios, p, time)

        f_key, F = self._keyed_features(X, context)

        designs = {False: ["lags"], True: ["lags+ar"], "auto": ["lags", "lags+ar"]}[self.ar]
        if self.ar is not False:
            designs.append("increments")   # one-step only: persistence plus the feature changes
        y_prev = previous(y, groups)
        records, scalers = [], {}
        for design in designs:
            D, target = self._design(design, F, y, y_prev, groups)
            scalers[design] = scaler = standard_scaler(D)
            Z = standardised(D, scaler)
            for ratio in ratios:
                # D is F, F with y(t-1) or F's increments, standardised: F's digest stands for it
                z_key = ArrayMemo.key(f_key, design, scaler.mean_, scaler.scale_, ratio,
                                      y_prev if design == "lags+ar" else None)
                Zw, n_free = _levels_weighted(Z, p, ratio)
                scores = ridge_path_cv(Zw, target, splits, alphas, groups,
                                       ar_column=D.shape[1] - 1 if design == "lags+ar" else None,
                                       ar_scaling=(scaler.mean_[-1], scaler.scale_[-1]), z_key=z_key,
                                       free_columns=n_free)
                records += _records(design, ratio, alphas, scores)
        # the refit standardises its design again: the last design's copies (a year's 1.2 GB
        # each) are not held with it
        del D, Z, Zw
        table = pd.DataFrame(records)
        design = self._keep_choice(table, self._choose(table[table["design"] != "increments"]))
        self.context_columns_ = [TIME] if time is not None else []
        if self.ar is False and getattr(self, "_refit_later", False):
            self._pending_design = design      # a caller choosing among lag banks refits its choice
            return self
        self.coef_, self.ar_coef_, self.intercept_ = self._refit(
            design, F, y, y_prev, groups, scalers[design], self.alpha_, p, self.level_penalty_)
        if self.ar is not False:   # the one-step model: the best one-step CV error of the AR designs
            rows = table[table["design"] != "lags"]
            pick = rows["cv_mse_one_step"].idxmin()
            self.one_step_design_ = str(table.loc[pick, "design"])
            self.alpha_one_step_ = float(table.loc[pick, "alpha"])
            self.coef_one_step_, self.ar_coef_one_step_, self.intercept_one_step_ = self._refit(
                self.one_step_design_, F, y, y_prev, groups, scalers[self.one_step_design_],
                self.alpha_one_step_, p, float(table.loc[pick, "level_penalty"]))
        return self

    def _splits(self, X, y, groups, longest_lag_rows: float) -> list:
        """The CV's ``(train, validation)`` folds of the rows ``X, y`` (``groups``: their
        campaigns), a forward gap of ``longest_lag_rows`` rows; sets ``splitter_`` and ``gap_``."""
        n = len(y)
        k = min(int(self.n_splits), n - 1)   # tiny samples: fewer folds, blocks of >= 1 row
        self.splitter_ = default_splitter(groups, n, forward_gap(longest_lag_rows, n, k), n_splits=k)
        self.gap_ = int(getattr(self.splitter_, "gap", 0))
        labels = groups
        if isinstance(self.splitter_, GroupKFold):   # its folds by sorted labels: the same from their
            labels = pd.factorize(np.asarray(groups, dtype=object), sort=True)[0]   # codes, sorted
        return list(self.splitter_.split(X, y, labels))   # faster than strings (a tenth of an ATI)

    def _fit_measured(self, X, y, measured, context, groups, alphas, ratios, p: int, time):
        """:meth:`fit` of a target measured now and then (a probe cycle on a dense log,
        ``data.sparse_targets``): the lag-bank features computed on every row (the inputs'
        dynamics on the dense stream), the ridge path and its CV on the measured rows only.
        Without output feedback: ``y(t-1)`` is not measured where ``y(t)`` is."""
        if self.ar is True:
            raise ParameterError("LagBank.ar=true needs the error measured at every sample (its AR "
                                 "term is fitted on y(t-1)); this target is measured now and then "
                                 "(data.sparse_targets): ar=auto or false")
        rows = np.flatnonzero(measured)
        m = rows.size
        if m < MIN_SPLITS + 1:
            raise TooFewSamples(f"LagBank: the target is measured on {m} rows, its time-series CV "
                                f"needs at least {MIN_SPLITS + 1}")
        F = self._features(X, context)[rows]
        g = None if groups is None else np.asarray(groups, dtype=object)[rows]
        spacing = X.shape[0] / m              # rows per measurement: the gap in measured rows
        splits = self._splits(F, y[rows], g, self.taus_[-1] / self.sample_period_s_ / spacing)
        scaler = standard_scaler(F)
        Z = standardised(F, scaler)
        records = []
        for ratio in ratios:
            Zw, n_free = _levels_weighted(Z, p, ratio)
            scores = ridge_path_cv(Zw, y[rows], splits, alphas, g, free_columns=n_free)
            records += _records("lags", ratio, alphas, scores)
        table = pd.DataFrame(records)
        self._keep_choice(table, self._choose(table))
        self.coef_, self.ar_coef_, self.intercept_ = self._refit(
            "lags", F, y[rows], None, g, scaler, self.alpha_, p, self.level_penalty_)
        self.context_columns_ = [TIME] if time is not None else []
        self.measured_rows_ = int(m)
        return self

    @threadpool_limits.wrap(limits=1, user_api="blas")   # as fit: the same sums in the same order
    def _refit_chosen(self, X, y, context=None) -> LagBank:
        """The refit of the chosen penalty that :meth:`fit` left out when its ``_refit_later`` was
        set (without output feedback), on the same ``X, y, context``: the numbers :meth:`fit`
        would have (its features, remembered or made again, and their standardisation are the
        same).  A caller that fits several lag banks to keep one (Hammerstein's powers: four on a
        year, each refit a product over every row) refits only that one."""
        self.__dict__.pop("_refit_later", None)
        design = self.__dict__.pop("_pending_design", None)
        if design is None:                      # fitted whole (or pooled: its refit costs nothing)
            return self
        X, y = np.asarray(X, dtype=float), np.asarray(y, dtype=float)
        groups = groups_of(context)
        F = self._features(X, context)
        y_prev = previous(y, groups)
        D, _ = self._design(design, F, y, y_prev, groups)
        self.coef_, self.ar_coef_, self.intercept_ = self._refit(
            design, F, y, y_prev, groups, standard_scaler(D), self.alpha_, X.shape[1],
            self.level_penalty_)
        return self

    @staticmethod
    def _campaign_folds(groups, n: int, splits):
        """Each fold's ``(train, validation)`` segment indices when every fold holds whole
        segments out (leave-campaigns-out) and the segments are those of the rows' campaigns,
        else None (forward chaining cuts a record)."""
        if groups is None or not isinstance(splits[0][0], np.ndarray):
            return None
        starts = segment_starts(groups, n)
        if starts.size < MIN_SPLITS or pd.unique(np.asarray(groups, dtype=object)).size != starts.size:
            return None
        seg = np.repeat(np.arange(starts.size), np.diff(np.r_[starts, n]))
        sizes = np.bincount(seg, minlength=starts.size)
        folds = []
        for tr, va in splits:
            parts = []
            for rows in (tr, va):
                counts = np.bincount(seg[rows], minlength=starts.size)
                if not np.all((counts == 0) | (counts == sizes)):
                    return None
                parts.append(np.flatnonzero(counts))
            folds.append(tuple(parts))
        return folds

    def _fit_pooled(self, X, y, context, groups, folds, alphas, ratios, p: int, time):
        """:meth:`fit` without output feedback when the CV holds whole campaigns out: its sums
        from each campaign's moments (:mod:`thermocomp.core.models._pooled`), the same numbers
        up to rounding, and a campaign's moments are computed once for all the fits that hold it."""
        n = X.shape[0]
        moments = CampaignMoments(X, self._time(context, groups, n), segment_bounds(groups, n),
                                  self.taus_, y, self._rest(X.shape[1]))
        centre, scale = standardisation(moments.pool(np.arange(len(moments.counts))))
        records = []
        for ratio in ratios:
            d = _level_scale(centre.size, p, ratio) / scale
            scores = pooled_path_cv(moments, folds, centre, d, alphas, p if ratio == 0 else 0)
            # without output feedback one step is the free run
            records += _records("lags", ratio, alphas, {"free_run": scores, "one_step": scores})
        table = pd.DataFrame(records)
        self._keep_choice(table, self._choose(table))
        ratio = self.level_penalty_
        d = _level_scale(centre.size, p, ratio) / scale
        W, c = pooled_refit(moments, centre, d, self.alpha_, p if ratio == 0 else 0)
        coef = W[:, 0] * d
        self.coef_, self.ar_coef_, self.intercept_ = coef, 0.0, float(c[0] - centre @ coef)
        self.context_columns_ = [TIME] if time is not None else []
        return self

    def _keep_choice(self, table: pd.DataFrame, best: int) -> str:
        """Keep the CV table with its ``best`` row marked chosen, that row's penalty and share of
        it on the levels, no one-step model (:meth:`fit` adds one where an AR design may enter);
        the chosen design's name."""
        table["chosen"] = table.index == best
        self.cv_results_ = table
        self.alpha_ = float(table.loc[best, "alpha"])
        self.level_penalty_ = float(table.loc[best, "level_penalty"])
        self.one_step_design_ = self.alpha_one_step_ = self.coef_one_step_ = None
        self.ar_coef_one_step_ = self.intercept_one_step_ = None
        return str(table.loc[best, "design"])

    def chosen_params(self) -> dict:
        """The parameters that fix what the CV chose (one penalty, the AR term kept or not):
        a copy fitted with them runs no choice of its own (see
        :func:`thermocomp.core.compensator.with_chosen_hyperparameters`)."""
        check_is_fitted(self)
        if self.ar is not False:   # a one-step model chosen apart (its own design and penalty):
            return {}              # fixing the free-run choice alone would lose it
        chosen = self.cv_results_.loc[self.cv_results_["chosen"]].iloc[0]
        return {"alphas": [self.alpha_], "ar": bool(chosen["ar"]), "level_penalty": [self.level_penalty_]}

    @staticmethod
    def _design(design: str, F, y, y_prev, groups):
        """Regressors and target of a design: ``lags`` ``(F, y)``, ``lags+ar`` ``([F | y(t-1)], y)``,
        ``increments`` ``(F(t) - F(t-1), y(t) - y(t-1))``."""
        if design == "lags":
            return F, y
        if design == "lags+ar":
            return np.column_stack([F, y_prev]), y
        return _increments(F, groups), y - y_prev

    def _refit(self, design: str, F, y, y_prev, groups, scaler, alpha: float, p: int,
               ratio: float):
        """``(coef, a, c)`` of the ridge fit on all training rows, back in unstandardised units,
        the ``p`` levels penalised by ``ratio * alpha``.

        ``increments`` predicts ``y(t) = y(t-1) + (F(t) - F(t-1)) b + c``: ``a = 1``.
        """
        D, target = self._design(design, F, y, y_prev, groups)
        Z, n_free = _levels_weighted(standardised(D, scaler), p, ratio)
        rows = np.arange(len(D))
        # one fit, not remembered: its factor is of no use to another target's penalty
        spectrum = _compute_fold_spectra(Z, float(alpha), n_free, rows, rows[:0])[0]
        W, c = fold_weights(spectrum, Z, target, rows, np.array([float(alpha)]))
        coef = W[:, 0] * _level_scale(D.shape[1], p, ratio) / scaler.scale_
        a = {"lags": 0.0, "lags+ar": float(coef[-1]), "increments": 1.0}[design]
        return coef[:F.shape[1]].copy(), a, float(c[0] - scaler.mean_ @ coef)

    @staticmethod
    def _choose(table: pd.DataFrame) -> int:
        """Row of the lowest free-run CV MSE (ties: no AR, then the larger share of the penalty on
        the levels, then the larger penalty).

        An AR model unstable for every penalty has no finite free-run score:
        forced (``ar=True``) it is then chosen on its one-step score.
        """
        score = table["cv_mse_free_run"].to_numpy()
        if not np.isfinite(score).any():
            score = table["cv_mse_one_step"].to_numpy()
        order = np.lexsort((-table["alpha"].to_numpy(), -table["level_penalty"].to_numpy(),
                            table["ar"].to_numpy(), score))
        return int(table.index[order[0]])

    # -- prediction ---------------------------------------------------------------------
    @threadpool_limits.wrap(limits=1, user_api="blas")
    def predict(self, X, context=None):
        """Predicted error: free run (simulation), or one-step with ``y_measured`` in ``context``."""
        check_is_fitted(self)
        X = validate_data(self, X, reset=False)
        X = np.asarray(X, dtype=float)
        groups, y_measured = groups_of(context), values(context, Y_MEASURED, X.shape[0])
        F = self._features(X, context)
        if y_measured is not None and self.coef_one_step_ is not None:
            coef, a, c = self.coef_one_step_, self.ar_coef_one_step_, self.intercept_one_step_
            if self.one_step_design_ == "increments":
                F = _increments(F, groups)
        else:
            coef, a, c = self.coef_, self.ar_coef_, self.intercept_
        u = F @ coef + c
        if a == 0.0:
            return u
        if y_measured is None:
            return free_run(a, u, groups)
        y_prev = previous(y_measured, groups)
        missing = np.isnan(y_prev)
        if not missing.any():
            return a * y_prev + u
        starts = set(segment_starts(groups, len(u)).tolist())   # a gap: carry the model's estimate
        out = np.empty_like(u)
        for t in range(len(u)):
            prev = 0.0 if t in starts else (out[t - 1] if missing[t] else y_prev[t])
            out[t] = a * prev + u[t]
        return out

    # -- streaming (deployment) ---------------------------------------------------------
    def stream_init(self, context: Mapping | None = None) -> dict:
        """State at a campaign start: no lag state yet (steady start on the first sample)."""
        check_is_fitted(self)
        return {"z": None, "clock": CLOCK_START, "y_prev": 0.0}

    def stream_step(self, x_row, state: dict, context: Mapping | None = None) -> tuple[float, dict]:
        """One sample of simulation-mode ``predict``: ``(y_hat, new_state)``.

        ``context`` maps ``'time'`` (s) to this sample's time; a sample without it is
        ``sample_period_s_`` after the previous one, by the stream's time rule
        (:mod:`thermocomp.core.timerule`: a first one is at 0 and the first time read counts on
        from it).
        """
        x = np.asarray(x_row, dtype=float).reshape(-1)
        clock = state.get("clock") or _clock_of(state["t"])
        clock, _, dt, _ = step_time(clock, scalar(context, TIME), self.sample_period_s_)
        if state["z"] is None:
            rest = self._rest(x.size)
            z = np.tile(x if rest is None else np.where(rest, 0.0, x), self.taus_.size)
        else:
            a = np.repeat(np.exp(-dt / self.taus_), x.size)
            z = a * state["z"] + (1.0 - a) * np.tile(x, self.taus_.size)
        y_hat = float(np.concatenate([x, z - np.tile(x, self.taus_.size)]) @ self.coef_ + self.intercept_
                      + self.ar_coef_ * state["y_prev"])
        return y_hat, {"z": z, "clock": clock, "y_prev": y_hat}

    def stream_steps(self, X, state: dict, context: Mapping | None = None) -> tuple[np.ndarray, dict]:
        """A block of rows at once (:func:`thermocomp.core.context.stream_steps`): the rows'
        times by the time rule, each lag by ``lfilter`` from the state's (one call per run of
        equal steps), the feedback by ``lfilter`` from the state's previous output."""
        from scipy.signal import lfilter

        X = np.asarray(X, dtype=float)
        n, p = X.shape
        if not n:
            return np.empty(0), state
        clock = state.get("clock") or _clock_of(state["t"])
        clock, dt = _block_clock(clock, _block_times(context, n), self.sample_period_s_)
        coef, taus = self.coef_, self.taus_
        y = X @ coef[:p] + self.intercept_
        # a start is steady on its first row; otherwise stream_step's first update
        z_prev = None if state["z"] is None else state["z"].reshape(taus.size, p)
        runs = np.flatnonzero(np.r_[True, dt[2:] != dt[1:-1]]) + 1 if n > 1 else np.zeros(0, int)
        stepwise = len(runs) > max(64, n // 64)   # irregular steps: the recursion row by row
        z_last = np.empty((taus.size, p))
        for k in range(taus.size):
            Z = np.empty((n, p))
            if z_prev is None:
                Z[0] = X[0]
            else:
                a = np.exp(-dt[0] / taus)[k]
                Z[0] = a * z_prev[k] + (1.0 - a) * X[0]
            if stepwise:
                a = np.exp(-dt[1:] / taus[k])
                for i in range(1, n):
                    Z[i] = a[i - 1] * Z[i - 1] + (1.0 - a[i - 1]) * X[i]
            else:
                for start, stop in zip(runs, np.r_[runs[1:], n]):
                    a = np.exp(-dt[start] / taus)[k]    # stream_step's factor, to the bit
                    Z[start:stop] = lfilter([1.0 - a], [1.0, -a], X[start:stop], axis=0,
                                            zi=a * Z[start - 1:start])[0]
            z_last[k] = Z[-1]
            y += (Z - X) @ coef[p * (k + 1):p * (k + 2)]
        a = float(self.ar_coef_)
        if a != 0.0:
            y = lfilter([1.0], [1.0, -a], y, zi=[a * state["y_prev"]])[0]
        return y, {"z": z_last.reshape(-1), "clock": clock, "y_prev": float(y[-1])}

    def step_gain(self, state=None, horizon_s: float = np.inf) -> np.ndarray | None:
        """Gain per input (:func:`thermocomp.core.context.step_gain`) of a step held for
        ``horizon_s``: the level coefficient plus each lag's, times ``L_tau[x] - x = -exp(-h/tau)``
        (through the AR term at its steady state).  At ``inf`` the level coefficients alone: no
        record shows them when the longest lag outlasts it, the ridge splits a slow input
        between ``x`` and ``L_tau[x] - x`` as it likes (a synthetic band-pass response, nothing
        at steady state, got -58 µm/K)."""
        check_is_fitted(self)
        n = self.coef_.size // (self.taus_.size + 1)
        lags = self.coef_[n:].reshape(self.taus_.size, n)
        held = np.exp(-horizon_s / self.taus_) if np.isfinite(horizon_s) else np.zeros(self.taus_.size)
        return feedback_gain(self.coef_[:n] - held @ lags, self.ar_coef_)

    def lagged_step_gain(self, lead_taus, horizon_s: float = np.inf,
                         period_s: float | None = None) -> np.ndarray | None:
        """:meth:`step_gain` where column ``j`` is a first-order lag of tau ``lead_taus[j]`` of
        the held step (``nan``: the step itself), as a diagnosed low-pass copy ``L_tau[x]`` of
        the inputs is (exportati60).

        That column's response after ``m = h / dt`` samples is ``s1 = 1 - a^m``, and the bank's
        channel ``L_tau_k[c] - c`` on it the cascade's less ``s1``: two discrete first-order lags,
        each updated on its input's new value (``a = exp(-dt/tau)``, ``b = exp(-dt/tau_k)``, ``dt``
        the bank's sample period), ``s2 = 1 - (a (1 - b) a^m - b (1 - a) b^m) / (a - b)``, and ``1
        - (1 + m (1 - a)) a^m`` where ``a = b`` (exact at the samples of a regular stream; the
        continuous cascade's ``1 - (tau e^{-h/tau} - tau_k e^{-h/tau_k}) / (tau - tau_k)`` as
        ``dt -> 0``).  ``period_s`` is not read: the lead's lag steps on the bank's clock."""
        check_is_fitted(self)
        n = self.coef_.size // (self.taus_.size + 1)
        lags = self.coef_[n:].reshape(self.taus_.size, n)
        lead = np.asarray(lead_taus, float)
        gain = self.coef_[:n].copy()
        dt = float(self.sample_period_s_)
        m = horizon_s / dt if np.isfinite(horizon_s) else np.inf
        for j in range(n):
            if np.isnan(lead[j]):
                s1, s2 = 1.0, np.array([_decayed(np.exp(-dt / tau), m) for tau in self.taus_])
                s2 = 1.0 - s2
            else:
                s1 = 1.0 - _decayed(np.exp(-dt / lead[j]), m)
                s2 = np.array([_cascade(np.exp(-dt / lead[j]), np.exp(-dt / tau), m)
                               for tau in self.taus_])
            gain[j] = gain[j] * s1 + lags[:, j] @ (s2 - s1)
        return feedback_gain(gain, self.ar_coef_)


def _decayed(a: float, m: float) -> float:
    """``a^m`` (0 at an infinite horizon)."""
    return a ** m if np.isfinite(m) else 0.0


def _cascade(a: float, b: float, m: float) -> float:
    """A unit step's response after ``m`` samples of a lag of pole ``b`` on a lag of pole ``a``
    (both at rest, each updated on its input's new value): :meth:`LagBank.lagged_step_gain`."""
    if not np.isfinite(m):
        return 1.0
    if np.isclose(a, b, rtol=1e-9, atol=0.0):
        return 1.0 - (1.0 + m * (1.0 - a)) * a ** m
    return 1.0 - (a * (1.0 - b) * a ** m - b * (1.0 - a) * b ** m) / (a - b)
