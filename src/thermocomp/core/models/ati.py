r"""Ambient temperature interval (ATI) models: one model per season (paper 003, Sect. 4).

A machine's thermal error law drifts with the ambient level (paper 003: the
same spindle test gives a different error in winter and in summer).  The ATI
model splits the ambient range into contiguous intervals, fits one model per
interval and, on the machine, picks the model of the interval that holds the
campaign's initial ambient temperature.
"""

from __future__ import annotations

import warnings
from functools import lru_cache

import numpy as np
import pandas as pd
from sklearn.base import BaseEstimator, RegressorMixin, clone
from sklearn.cluster import KMeans
from sklearn.utils.validation import check_is_fitted, validate_data

from ...base.errors import ContractError, FallbackWarning, listed
from ...base.params import BOOLEAN, NON_NEGATIVE, check_estimator, choice, either, integer, integers, number
from ..context import (
    AMBIENT_C0,
    SideInputs,
    context_columns,
    groups_of,
    merge_columns,
    scalar,
    stream_branches,
    stream_steps,
    subset,
)
from ..gains import AMBIENT_CENTRE_C, gain_at, gain_terms, within
from ..metrics import rsd, sm_sd
from ._campaign_ls import CampaignLeastSquares
from .base import measured_rows
from .linear import MLR

CLUSTERINGS = ("fuzzy", "hard")
MIN_AMBIENTS = 3          # distinct ambient levels an interval needs to fit a slope in ambient
AMBIENT_RESOLUTION_C = 0.5  # °C: closer initial ambients are one level (ambient_levels)
MIN_CAMPAIGNS = 2         # training campaigns an interval's model is fitted on, at least


def cluster_ambient(ambient, n_clusters: int, clustering: str = "fuzzy", fuzziness: float = 2.0,
                    random_state: int = 0) -> np.ndarray:
    r"""Cluster label of each campaign's initial ambient temperature (1-D C-means).

    ``fuzzy``: fuzzy C-means (scikit-fuzzy; memberships :math:`u_{ck}`, fuzziness
    :math:`m`), each campaign in its cluster of largest membership;
    ``hard``: k-means (scikit-learn), the hard C-means of paper 003, Sect. 4.2.1.
    Both start from centres at the quantiles :math:`(c + 1/2)/M` of the data
    (deterministic, and a good start in one dimension).  Labels are renumbered
    so that cluster 0 is the coldest.
    """
    if clustering not in CLUSTERINGS:
        raise ValueError(f"clustering must be one of {CLUSTERINGS}, got {clustering!r}")
    key = (tuple(np.asarray(ambient, float).round(9)), int(n_clusters), clustering,
           float(fuzziness), int(random_state))
    return np.array(_cluster_cached(*key))


@lru_cache(maxsize=4096)
def _cluster_cached(ambient: tuple, n_clusters: int, clustering: str, fuzziness: float,
                    random_state: int) -> tuple:
    # Cached: the elbow's folds and every target re-cluster the same campaigns.
    a = np.array(ambient)
    centres = np.quantile(a, (np.arange(n_clusters) + 0.5) / n_clusters)
    if clustering == "hard":
        labels = KMeans(n_clusters=n_clusters, init=centres[:, None], n_init=1,
                        random_state=random_state).fit(a[:, None]).labels_
    else:
        import skfuzzy

        dist = np.abs(a[None, :] - centres[:, None]) + 1e-9
        u0 = dist ** (-2.0 / (fuzziness - 1.0))
        u0 /= u0.sum(axis=0)
        _, u, *_ = skfuzzy.cluster.cmeans(a[None, :], n_clusters, fuzziness, error=1e-7,
                                          maxiter=1000, init=u0, seed=random_state)
        labels = u.argmax(axis=0)
    order = sorted(set(labels.tolist()), key=lambda c: a[labels == c].mean())
    return tuple(order.index(c) for c in labels.tolist())


@lru_cache(maxsize=4096)
def _intervals_cached(ambient: tuple, n: int, clustering: str, fuzziness: float, random_state: int,
                      min_campaigns: int) -> tuple:
    # Cached: a diagnosis refits the ATI model on the same train campaigns for every candidate,
    # and each elbow asks once per held-out campaign and count (17,290 times, 4.5 s, on 14 runs)
    a = np.array(ambient)
    labels = cluster_ambient(a, n, clustering, fuzziness, random_state)
    return tuple(merge_thin_intervals(a, interval_boundaries(a, labels), min_campaigns).tolist())


def interval_boundaries(ambient, labels) -> np.ndarray:
    r"""Boundaries between contiguous ambient intervals from cluster labels (sorted).

    As in paper 003 (Table 5): the boundary between two neighbouring clusters is
    the midpoint of the warmest ambient of the colder one and the coldest of
    the warmer one, :math:`b = (\max A_c + \min A_{c+1}) / 2`; if the clusters
    overlap (possible with fuzzy memberships) the midpoint of their means.
    """
    a, labels = np.asarray(ambient, float), np.asarray(labels)
    clusters = sorted(set(labels), key=lambda c: a[labels == c].mean())
    bounds = []
    for lo, hi in zip(clusters[:-1], clusters[1:]):
        top, bottom = a[labels == lo].max(), a[labels == hi].min()
        b = (top + bottom) / 2 if top < bottom else (a[labels == lo].mean() + a[labels == hi].mean()) / 2
        bounds.append(b)
    return np.array(bounds, float)


def ambient_levels(ambient, resolution: float = AMBIENT_RESOLUTION_C) -> int:
    """Number of distinct ambient levels among initial ambients ``ambient`` (°C; NaN ignored).

    From the coldest up, a value at least ``resolution`` above the first value of the current
    level starts the next one.  Runs of a room held at one set point start within its control's
    swing (rig40: 19.97 .. 20.08 °C) and are one level: a slope in ambient fitted on that spread
    is noise, and extrapolated to the next run it cost rig40 E_X 0.37 -> 0.91 µm
    (``benchmarks/bench_ati_ramp.py``).  A continuous spread counts about one level per
    ``resolution``, and no rounding edge splits two close values.
    """
    a = np.asarray(ambient, float)
    a = np.sort(a[np.isfinite(a)])
    count, start = 0, -np.inf
    for value in a:
        if value - start >= resolution:
            count, start = count + 1, value
    return count


def merge_thin_intervals(ambient, boundaries, least: int = MIN_CAMPAIGNS) -> np.ndarray:
    """``boundaries`` less those that leave an interval with fewer than ``least`` of the
    campaigns ``ambient`` (one initial ambient per campaign, °C).

    Such an interval is merged into its neighbour across the smaller ambient gap (the colder
    one on a tie), until every interval holds ``least`` campaigns or one interval is left.
    An interval of one campaign fits its model on that run alone: one programme, its sensors
    rising together, gains no other run constrains.  With 3-4 train campaigns the elbow's
    folds were such intervals (``yearround_spindle`` with 6 campaigns, seed 5411: E_Y's fold
    predicting K02 by a model of K01 alone, 4.53 µm against MLR's 2.13; the refit on four kept
    two intervals of two for E_Z, 2.32 against one with the interaction, 0.56;
    ``benchmarks/bench_auto_losses56.py``).

    Returns
    -------
    ndarray
        The boundaries kept, sorted.
    """
    a = np.asarray(ambient, float)
    bounds = sorted(np.asarray(boundaries, float).tolist())
    while bounds:
        which = interval_of(a, bounds)
        counts = np.bincount(which, minlength=len(bounds) + 1)
        thin = np.flatnonzero(counts < least)
        if not thin.size:
            break
        m = int(thin[0])
        if m in (0, len(bounds)):             # an end interval has one neighbour
            drop = 0 if m == 0 else m - 1
        else:
            mine = a[which == m]
            below = mine.min() - a[which == m - 1].max() if counts[m - 1] else np.inf
            above = a[which == m + 1].min() - mine.max() if counts[m + 1] else np.inf
            drop = m - 1 if below <= above else m
        del bounds[drop]
    return np.array(bounds, float)


def interval_of(ambient, boundaries) -> np.ndarray:
    """Interval index of each ambient; a value on a boundary belongs to the colder interval."""
    return np.searchsorted(np.asarray(boundaries, float), np.asarray(ambient, float), side="left")


class ATIRegressor(SideInputs, RegressorMixin, BaseEstimator):
    r"""One model per ambient temperature interval (ATI), chosen by initial ambient (paper 003).

    Campaign :math:`k` with initial ambient :math:`A_k` is predicted by the
    model of its interval,

    .. math::

        \hat y(t) = f_{m(k)}(x(t)),\quad m(k) = \#\{\,i : b_i < A_k\,\},

    where :math:`b_1 < \dots < b_{M-1}` are the boundaries between C-means
    clusters of the training campaigns' :math:`A_k` (see
    :func:`interval_boundaries`) and :math:`f_m` is ``base_estimator`` fitted on
    the campaigns of interval :math:`m`.  With ``n_intervals='elbow'`` the number
    of intervals :math:`M` is chosen among ``candidates`` by the elbow of the
    leave-one-campaign-out :math:`SM` and :math:`SD` (mean and standard
    deviation of the held-out campaigns' :math:`R_{sd}`, paper 003 Eqs. 20-21):
    the smallest :math:`M` beyond which more intervals improve :math:`SM + SD`
    by less than ``elbow_tolerance`` (relative), i.e. where the curve flattens.
    In each fold the intervals are rebuilt from the remaining campaigns, so the
    held-out campaign never shapes its own interval.  Paper 003 uses one
    campaign per interval (the coldest of it); here every campaign of the
    interval trains its model.

    ``fit``/``predict`` read ``campaign`` and ``ambient_c0`` from ``context``
    (:mod:`thermocomp.core.context`) and hand each base model the context of its
    rows.  Without ``context`` the campaigns' ambient is unknown and the model
    is one ``base_estimator`` (one interval).

    Parameters
    ----------
    base_estimator : regressor, default MLR()
        Any model family; cloned per interval; gets the context of its rows.
    n_intervals : int or 'elbow', default 'elbow'
    candidates : sequence of int, default (2, 3, 4, 5, 6)
        Numbers of intervals tried by the elbow (paper 003's range; add 1 to
        let the elbow keep a single model).
    clustering : {'fuzzy', 'hard'}, default 'fuzzy'
        Fuzzy C-means (scikit-fuzzy) or hard C-means (k-means).
    fuzziness : float, default 2.0
        Exponent :math:`m` of fuzzy C-means.
    elbow_tolerance : float, default 0.10
        Relative tolerance of the elbow.
    random_state : int, default 0
    ambient_interaction : bool, default False
        Each interval's model also gets :math:`x\,(A_k - 20\,°C)`, so the law
        may change linearly with the ambient inside an interval
        (:math:`\hat y = f_m(x, x (A_k - 20))`); used only for an interval whose
        training campaigns have at least ``MIN_AMBIENTS`` (3) distinct ambient
        levels (:func:`ambient_levels`: 0.5 °C apart), where that slope is identifiable.
    min_campaigns : int, default 2
        Training campaigns an interval needs: a thinner one is merged into its nearer neighbour
        (:func:`merge_thin_intervals`), in the final fit and in the elbow's folds alike, so
        ``n_intervals_`` may be below the count asked or chosen; 1 keeps every interval
        (paper 003 fits each interval's model on one campaign).

    Attributes
    ----------
    n_intervals_ : int
        Intervals kept (thin ones merged: ``min_campaigns``).
    boundaries_ : ndarray of shape (n_intervals_ - 1,), °C
    intervals_ : list of dict
        Per interval: ``low``/``high`` (°C, None for the open ends),
        ``ambient_min``/``ambient_max`` of its training campaigns, ``campaigns``.
    estimators_ : list of fitted base estimators, coldest interval first
    interactions_ : list of bool
        Per interval, whether its model takes the ambient interaction.
    elbow_ : dict or None
        ``n_intervals``, ``sm``, ``sd`` (µm) per candidate, ``chosen``,
        ``single_model`` (the CV SM/SD of one interval: this wrapper's, with the ambient
        interaction when it is on, not the bare base model) and ``reason`` when no
        candidate could be cross-validated.
    campaign_ambient_ : dict campaign -> initial ambient (°C) of the training data
    """

    param_rules = {"n_intervals": either(choice("elbow"), integer(1)),
                   "candidates": integers(1), "clustering": choice(*CLUSTERINGS),
                   "fuzziness": number(1.0, open_lo=True), "elbow_tolerance": NON_NEGATIVE,
                   "ambient_interaction": BOOLEAN, "random_state": integer(0, 2 ** 32 - 1),
                   "min_campaigns": integer(1)}
    # the elbow's MLR folds from per-campaign QR factors (_HeldOutFits); False: every fold
    # fitted on its rows by ``_fit_base`` (the reference the fast path is tested against)
    _fast_elbow = True

    def __init__(self, base_estimator=None, n_intervals="elbow", candidates=(2, 3, 4, 5, 6),
                 clustering: str = "fuzzy", fuzziness: float = 2.0, elbow_tolerance: float = 0.10,
                 random_state: int = 0, ambient_interaction: bool = False,
                 min_campaigns: int = MIN_CAMPAIGNS):
        self.base_estimator = base_estimator
        self.n_intervals = n_intervals
        self.candidates = candidates
        self.clustering = clustering
        self.fuzziness = fuzziness
        self.elbow_tolerance = elbow_tolerance
        self.random_state = random_state
        self.ambient_interaction = ambient_interaction
        self.min_campaigns = min_campaigns

    # -- fitting ----------------------------------------------------------------------------
    def _base(self):
        return clone(self.base_estimator if self.base_estimator is not None else MLR())

    def _interacts(self, context) -> bool:
        """Whether a model fitted on these rows takes ``X·(A0 − 20 °C)`` too: only with
        ``ambient_interaction`` and rows from at least ``MIN_AMBIENTS`` distinct ambient levels
        (:func:`ambient_levels`; with fewer the slope in ambient is not identifiable and would
        only extrapolate)."""
        if not self.ambient_interaction or context is None or AMBIENT_C0 not in context:
            return False
        return self._interacts_at(np.asarray(context[AMBIENT_C0], float))

    def _interacts_at(self, a0_rows) -> bool:
        """:meth:`_interacts` for rows whose ``ambient_c0`` are ``a0_rows``."""
        return bool(self.ambient_interaction) and ambient_levels(np.unique(a0_rows)) >= MIN_AMBIENTS

    @staticmethod
    def _design(X, context, interacts: bool) -> np.ndarray:
        """``X``, or ``[X, X·(A0 − 20 °C)]``: within an interval the law may still change
        linearly with the ambient level."""
        if not interacts:
            return X
        a0 = np.asarray(context[AMBIENT_C0], float)
        return np.hstack([X, X * (a0 - AMBIENT_CENTRE_C)[:, None]])

    def _fit_base(self, X, y, rows, context) -> tuple:
        """``(fitted base model, whether it takes the interaction)`` on the rows ``rows``."""
        ctx = subset(context, rows)
        interacts = self._interacts(ctx)
        return self._base().fit(self._design(X[rows], ctx, interacts), y[rows], context=ctx), interacts

    def _predict_base(self, fitted: tuple, X, rows, context):
        est, interacts = fitted
        ctx = subset(context, rows)
        return est.predict(self._design(X[rows], ctx, interacts), context=ctx)

    def _intervals(self, ambient: np.ndarray, n: int) -> np.ndarray:
        """Boundaries of ``n`` intervals of the campaigns' initial ``ambient``, thin ones merged."""
        return np.array(_intervals_cached(tuple(np.asarray(ambient, float).tolist()), int(n),
                                          self.clustering, float(self.fuzziness),
                                          int(self.random_state), int(self.min_campaigns)), float)

    def fit(self, X, y, context=None):
        check_estimator(self)
        # a target measured now and then: NaN kept, each interval's base model fits on its
        # measured rows, the elbow's held-out Rsd is scored on them (metrics.rsd)
        X, y, _ = measured_rows(self, X, y)
        self.elbow_ = None
        if context is None or AMBIENT_C0 not in context:
            self.campaign_ambient_ = {}
            return self._fit_intervals(X, y, np.empty(0), np.zeros(len(y), int), context)
        campaign = groups_of(context)
        if campaign is None:
            campaign = np.zeros(len(y), dtype=object)
        a0_rows = self._ambient(context)
        a0 = pd.Series(a0_rows).groupby(campaign, sort=False).first()
        self.campaign_ambient_ = {str(k): float(v) for k, v in a0.items()}
        distinct = np.unique(a0.to_numpy()).size
        if self.n_intervals == "elbow":
            n = self._elbow(X, y, campaign, a0, context)
        else:
            n = int(self.n_intervals)
            if n > distinct:
                warnings.warn(f"ATI n_intervals={n}: the train campaigns have {distinct} distinct "
                              f"ambient level(s); {distinct} interval(s)", UserWarning, stacklevel=3)
        n = min(n, distinct)
        bounds = self._intervals(a0.to_numpy(), n) if n > 1 else np.empty(0)
        if self.n_intervals != "elbow" and bounds.size + 1 < n:
            warnings.warn(f"ATI n_intervals={n}: an interval needs {self.min_campaigns} train "
                          f"campaigns (min_campaigns); {bounds.size + 1} interval(s)", UserWarning,
                          stacklevel=3)
        return self._fit_intervals(X, y, bounds, interval_of(a0_rows, bounds), context, campaign)

    def _fit_intervals(self, X, y, bounds, row_interval, context, campaign=None):
        self.boundaries_ = bounds
        self.n_intervals_ = bounds.size + 1
        self.estimators_, self.intervals_, self.interactions_ = [], [], []
        edges = [None, *bounds.tolist(), None]
        for m in range(self.n_intervals_):
            rows = row_interval == m
            est, interacts = self._fit_base(X, y, rows, context)
            self.estimators_.append(est)
            self.interactions_.append(interacts)
            members = sorted(set(campaign[rows])) if campaign is not None else []
            amb = [self.campaign_ambient_[str(c)] for c in members]
            self.intervals_.append({"low": edges[m], "high": edges[m + 1],
                                    "ambient_min": min(amb) if amb else None,
                                    "ambient_max": max(amb) if amb else None,
                                    "campaigns": [str(c) for c in members]})
        self.context_columns_ = merge_columns([AMBIENT_C0] if self.n_intervals_ > 1
                                              or any(self.interactions_) else [],
                                              *(context_columns(e) for e in self.estimators_))
        return self

    @staticmethod
    def _ambient(context) -> np.ndarray:
        a0 = np.asarray(context[AMBIENT_C0], float)
        if not np.all(np.isfinite(a0)):
            groups = groups_of(context)
            odd = [] if groups is None else list(dict.fromkeys(map(str, groups[~np.isfinite(a0)])))
            which = ("no campaign has a" if groups is not None and len(odd) == len(set(groups))
                     else f"campaign {odd[0]} has no" if len(odd) == 1
                     else f"campaigns {listed(odd)} have no" if odd else "a campaign has no")
            raise ContractError("ATI models need each campaign's initial ambient temperature, "
                                f"but {which} valid T_amb / T_amb_* value (nor a manifest "
                                "ambient_c, its ambient where no sensor is): name the air "
                                "sensor, data.roles.ambient=[<its header>], or give each "
                                "campaign's ambient_c in campaigns.csv (columns campaign, file, "
                                "ambient_c; a folder of runs without one: write it)",
                                column="T_amb")
        return a0

    def _cv_rsd(self, X, y, campaign, a0: pd.Series, n: int, context, fits=None) -> np.ndarray:
        """Held-out Rsd of each campaign with ``n`` intervals rebuilt from the others; ``fits``
        (:class:`_HeldOutFits`) keeps the models by the campaigns they are fitted on, for the
        next campaign and count: where the held-out campaign's interval holds the same others,
        its model is the same (a sixth of the fits on a climate-room record)."""
        fits = _HeldOutFits(self, X, y, campaign, context) if fits is None else fits
        ids, ambient = a0.index.to_numpy(), a0.to_numpy()
        out = []
        # leave one campaign out, in order of appearance (a0's, LeaveOneCampaignOut's: with
        # the rows it split, 3 s of a diagnosis); a0.drop(k) in pandas was 15 % of the elbow
        for j, k in enumerate(ids):
            keep = np.arange(ids.size) != j
            others = ambient[keep]
            bounds = self._intervals(others, n) if n > 1 else np.empty(0)
            mine = interval_of([ambient[j]], bounds)[0]
            # train on the other campaigns of the held-out campaign's interval
            out.append(rsd(fits.residual(ids[keep][interval_of(others, bounds) == mine], k)))
        return np.array(out)

    def _elbow(self, X, y, campaign, a0: pd.Series, context) -> int:
        """Choose the number of intervals; fills ``elbow_``."""
        k = len(a0)
        feasible = [int(n) for n in self.candidates
                    if 1 <= int(n) <= min(k - 1, np.unique(a0.to_numpy()).size - 1)]
        if k < 3 or not feasible:
            self.elbow_ = {"n_intervals": [], "sm": [], "sd": [], "chosen": 1, "single_model": None,
                           "reason": f"{k} training campaign(s) with "
                                     f"{np.unique(a0.to_numpy()).size} distinct ambient(s): too few to "
                                     f"cross-validate {list(self.candidates)} intervals; one model"}
            # said, not only written into metrics.json: ati=cmeans then scores as ati=none does
            warnings.warn(f"ATI: {self.elbow_['reason']} (the model ati=none fits)", FallbackWarning,
                          stacklevel=3)
            return 1
        sm, sd, fits = [], [], _HeldOutFits(self, X, y, campaign, context)
        for n in feasible:
            m, s = sm_sd(self._cv_rsd(X, y, campaign, a0, n, context, fits))
            sm.append(m)
            sd.append(s)
        # one model: the first count's figures when 1 is among them (the same folds, refitted)
        one = feasible.index(1) if 1 in feasible else None
        single = (sm[one], sd[one]) if one is not None else sm_sd(
            self._cv_rsd(X, y, campaign, a0, 1, context, fits))
        score = np.array(sm, dtype=float) + np.array(sd, dtype=float)
        if not np.isfinite(score).any():    # no count could be scored (a held-out campaign
            # whose interval had no other campaign to fit on, for every count): one model
            self.elbow_ = {"n_intervals": feasible, "sm": sm, "sd": sd, "chosen": 1,
                           "single_model": {"sm": single[0], "sd": single[1]},
                           "reason": "no number of intervals could be cross-validated; one model"}
            return 1
        best = np.nanmin(score)
        chosen = feasible[int(np.flatnonzero(score <= (1 + self.elbow_tolerance) * best)[0])]
        self.elbow_ = {"n_intervals": feasible, "sm": sm, "sd": sd, "chosen": chosen,
                       "single_model": {"sm": single[0], "sd": single[1]}, "reason": None}
        return chosen

    # -- prediction -------------------------------------------------------------------------
    def _row_intervals(self, n_rows: int, context) -> np.ndarray:
        if self.n_intervals_ == 1:
            return np.zeros(n_rows, int)
        if context is None:
            raise ValueError("this ATI model has several intervals: predict needs `context` "
                             "with each row's `ambient_c0`")
        return interval_of(self._ambient(context), self.boundaries_)

    def predict(self, X, context=None):
        check_is_fitted(self)
        X = validate_data(self, X, reset=False)
        which = self._row_intervals(X.shape[0], context)
        out = np.empty(X.shape[0])
        for m in np.unique(which):
            rows = which == m
            out[rows] = self._predict_base((self.estimators_[m], self.interactions_[m]), X, rows,
                                           context)
        return out

    # -- streaming (deployment) -------------------------------------------------------------
    def stream_init(self, context=None):
        """State for :meth:`stream_step`: the interval of the context's ``ambient_c0`` and its
        model's state."""
        check_is_fitted(self)
        a0 = scalar(context, AMBIENT_C0)
        if AMBIENT_C0 in self.context_columns_ and not np.isfinite(a0):
            raise ContractError("this ATI model needs the campaign's initial ambient temperature "
                                "(°C) to start a stream: no T_amb / T_amb_* value", column=AMBIENT_C0)
        m = 0 if self.n_intervals_ == 1 else int(interval_of([a0], self.boundaries_)[0])
        return m, a0, self.estimators_[m].stream_init(context)

    def stream_step(self, x_row, state, context=None):
        """One sample: ``(y_hat, state)``, as :meth:`predict` in simulation mode."""
        m, a0, inner = state
        x = self._as_read(np.asarray(x_row, dtype=float).ravel(), m, a0)
        y_hat, inner = self.estimators_[m].stream_step(x, inner, context)
        return float(y_hat), (m, a0, inner)

    def stream_steps(self, X, state, context=None):
        """A block of rows at once (:func:`thermocomp.core.context.stream_steps`)."""
        m, a0, inner = state
        y, inner = stream_steps(self.estimators_[m], self._as_read(X, m, a0), inner, context)
        return y, (m, a0, inner)

    def stream_branches(self, blocks, state, context=None):
        """Blocks (b, n, p) each from the same state
        (:func:`thermocomp.core.context.stream_branches`), by the interval's model."""
        m, a0, inner = state
        return stream_branches(self.estimators_[m], self._as_read(blocks, m, a0), inner, context)

    def _as_read(self, X, m: int, a0: float) -> np.ndarray:
        """Streamed rows ``X`` (a row, a block or blocks: inputs on the last axis) as interval
        ``m``'s model reads them: with its ambient interaction, the inputs times ``A0`` less the
        centre, appended."""
        X = np.asarray(X, dtype=float)
        if not self.interactions_[m]:
            return X
        return np.concatenate([X, X * (a0 - AMBIENT_CENTRE_C)], axis=-1)

    def gain_terms(self, horizon_s: float = np.inf, lead=None, period_s: float = 1.0) -> list:
        """The step gain split by the campaign's initial ambient (:mod:`thermocomp.core.gains`):
        each interval's model's within its interval (``lo < A0 <= hi``, as :func:`interval_of`
        assigns it), with the ambient interaction its gain on ``x (A0 - 20)`` times ``A0 - 20``
        (``lead``, a lag of the held step per input, on both halves)."""
        check_is_fitted(self)
        edges = [-np.inf, *map(float, self.boundaries_), np.inf]
        out = []
        for m, est in enumerate(self.estimators_):
            both = bool(self.interactions_[m])
            lo, hi = edges[m], edges[m + 1]
            for t in gain_terms(est, horizon_s, None if lead is None else np.tile(lead, 1 + both),
                                period_s):
                if not both:
                    out += within([t], lo, hi)
                    continue
                n = 0 if t.gain is None else t.gain.size // 2
                for half in range(2):
                    part = None if t.gain is None else t.gain[half * n:(half + 1) * n]
                    out += within([t._replace(gain=part)], lo, hi, power=half)
        return out

    def step_gain(self, state=None, horizon_s: float = np.inf):
        """Gain per input of the stream's interval model (:func:`thermocomp.core.context.step_gain`),
        its ambient interactions at the campaign's ``ambient_c0`` (:meth:`gain_terms` there);
        ``None`` before a stream starts when there are several intervals."""
        return gain_at(self.gain_terms(horizon_s), state[1] if state is not None else np.nan)


class _HeldOutFits:
    """The base models of an ATI elbow's folds, by the campaigns each is fitted on.

    With an :class:`~thermocomp.core.models.MLR` base (``ATIRegressor._fast_elbow``) a fold's
    fit comes from the campaigns' QR factors (:class:`._campaign_ls.CampaignLeastSquares`:
    LinearRegression's solution up to rounding; on 14 climate-room runs the elbow's 11,644 fits
    were 40x the CPU of the rest of ``diagnose``), else from ``_fit_base`` on the rows.
    """

    def __init__(self, ati: ATIRegressor, X, y, campaign, context):
        self.ati, self.X, self.y, self.context = ati, X, y, context
        codes, ids = pd.factorize(campaign)    # rows by integer code: np.isin on the ids (objects)
        self.code = {c: i for i, c in enumerate(ids)}   # cost 15 % of the elbow on 39 lathe runs
        self.codes = codes
        base = ati._base()
        self.fast = ati._fast_elbow and type(base) is MLR and context is not None \
            and AMBIENT_C0 in context
        if self.fast:
            # a campaign's measured rows only: a target measured now and then (a tracker every
            # 5 min) is NaN between, and a NaN in the least squares made every fold NaN
            # (stranger76: "no number of intervals could be cross-validated"), as _fit_base
            # leaves them out through the base model's measured_rows
            measured = np.isfinite(np.asarray(y, float))
            self.rows = [np.flatnonzero((codes == i) & measured) for i in range(len(ids))]
            self.a0_rows = np.asarray(context[AMBIENT_C0], float)
            self.levels = [np.unique(self.a0_rows[r]) for r in self.rows]
            self.fit_intercept = base.fit_intercept
            self.designs: dict[bool, CampaignLeastSquares] = {}
        self.models: dict = {}

    def _design(self, interacts: bool) -> CampaignLeastSquares:
        if interacts not in self.designs:
            Z = self.ati._design(self.X, {AMBIENT_C0: self.a0_rows}, interacts)
            self.designs[interacts] = CampaignLeastSquares(Z, self.y, self.rows, self.fit_intercept)
        return self.designs[interacts]

    def _fit(self, train) -> tuple:
        """``("qr", fit, interacts)`` or ``("rows", fitted base, interacts)``."""
        if self.fast:
            codes = [self.code[c] for c in train]
            interacts = self.ati._interacts_at(np.concatenate([self.levels[c] for c in codes]))
            fitted = self._design(interacts).fit(codes)
            if fitted is not None:      # None: a singular value at lstsq's cut-off, the rows decide
                return "qr", fitted, interacts
        rows = np.isin(self.codes, [self.code[c] for c in train])
        return "rows", *self.ati._fit_base(self.X, self.y, rows, self.context)

    def residual(self, train, k) -> np.ndarray:
        """Campaign ``k``'s residual under the base model fitted on campaigns ``train``."""
        key = frozenset(train)
        if key not in self.models:
            self.models[key] = self._fit(train)
        how, fitted, interacts = self.models[key]
        if how == "qr":
            c = self.code[k]
            return self.y[self.rows[c]] - self._design(interacts).predict(fitted, c)
        rows = self.codes == self.code[k]
        return self.y[rows] - self.ati._predict_base((fitted, interacts), self.X, rows, self.context)
