"""Campaign splitters: scikit-learn cross-validators over the campaigns of stacked rows.

Rows arrive stacked campaign after campaign and ``groups`` holds the
campaign of each row (None: one campaign).  Every splitter here works with
``cross_val_score(est, X, y, groups=campaign_per_row, cv=splitter)`` and, with
metadata routing enabled, requests ``groups`` by default.

The unit of cross-validation is a campaign.  When there is a single campaign
(one long record) the campaign splitters use ``n_blocks`` contiguous time
blocks of it instead (``shared/spec/CLI.md``; :func:`unit_labels`).
"""

from __future__ import annotations

import numpy as np
from sklearn.model_selection import BaseCrossValidator, TimeSeriesSplit
from sklearn.utils import indexable

from ...base.errors import ParameterError
from .schemes import CV_SCHEMES


def unit_labels(groups, n_blocks: int) -> np.ndarray:
    """CV unit of each row: its campaign, or ``<campaign>#<k>`` blocks for a single campaign.

    Parameters
    ----------
    groups : array-like of shape (n_samples,)
        Campaign of each row.
    n_blocks : int
        Number of contiguous, near-equal time blocks a single campaign is cut into.

    Returns
    -------
    ndarray of object, shape (n_samples,)
    """
    campaigns = np.asarray(groups, dtype=object)
    ids = list(dict.fromkeys(campaigns))
    if len(ids) > 1:
        return campaigns
    n = len(campaigns)
    block = np.minimum((np.arange(n) * n_blocks) // max(n, 1), n_blocks - 1)
    return np.array([f"{ids[0]}#{k + 1}" for k in block], dtype=object)


def _index_of(labels) -> tuple[np.ndarray, int]:
    """Position of each row's label in the order of first appearance, and the number of labels."""
    names = list(dict.fromkeys(labels))
    pos = {u: i for i, u in enumerate(names)}
    return np.array([pos[u] for u in labels], dtype=int), len(names)


def _campaigns(X, groups) -> np.ndarray:
    """``groups`` as an array, or one campaign for all rows of ``X`` when it is None."""
    if groups is not None:
        return np.asarray(groups, dtype=object)
    if X is None:
        raise ValueError("pass groups (the campaign of each row) or X")
    return np.zeros(len(X), dtype=object)


class _CampaignSplitter(BaseCrossValidator):
    """Common part: units of CV (campaigns or blocks) and the ``groups`` request."""

    # request ``groups`` under metadata routing, as scikit-learn's group splitters do
    __metadata_request__split = {"groups": True}

    def _units(self, X, groups) -> tuple[np.ndarray, int]:
        if int(self.n_blocks) < 2:
            raise ParameterError(f"n_blocks={self.n_blocks!r} must be >= 2")
        return _index_of(unit_labels(_campaigns(X, groups), int(self.n_blocks)))

    def _n_folds(self, n_units: int) -> int:
        raise NotImplementedError

    def fold_index(self, groups, X=None) -> np.ndarray:
        """Fold of each row: unit ``i`` (in order of appearance) -> fold ``i mod K``."""
        unit, n_units = self._units(X, groups)
        return unit % self._n_folds(n_units)

    def _iter_test_masks(self, X=None, y=None, groups=None):
        fold = self.fold_index(groups, X)
        if len(fold) and int(fold.max()) < 1:
            raise ValueError("campaign cross-validation needs at least 2 units (campaigns or blocks)")
        for k in range(int(fold.max()) + 1 if len(fold) else 0):
            yield fold == k

    def get_n_splits(self, X=None, y=None, groups=None):
        """Number of folds ``K`` for these ``groups`` (or the rows of ``X``: one campaign)."""
        return self._n_folds(self._units(X, groups)[1])


class LeaveCampaignsOut(_CampaignSplitter):
    """K-fold over whole campaigns, in turn: unit ``i`` -> fold ``i mod K``.

    With campaigns in calendar order every fold spans the seasons.
    ``K = max(2, min(n_folds, n_units))``; a single campaign is cut into
    ``n_blocks`` contiguous time blocks, the units then.

    Parameters
    ----------
    n_folds : int, default 10
    n_blocks : int, default 8
    """

    def __init__(self, n_folds: int = 10, n_blocks: int = 8):
        self.n_folds = n_folds
        self.n_blocks = n_blocks

    def _n_folds(self, n_units: int) -> int:
        if int(self.n_folds) < 1:
            raise ParameterError(f"n_folds={self.n_folds!r} must be >= 1")
        return max(2, min(int(self.n_folds), n_units))


class LeaveOneCampaignOut(_CampaignSplitter):
    """Every campaign held out once (in order of appearance); blocks of a single campaign.

    Parameters
    ----------
    n_blocks : int, default 8
    """

    def __init__(self, n_blocks: int = 8):
        self.n_blocks = n_blocks

    def _n_folds(self, n_units: int) -> int:
        return n_units


class TrainOnEachCampaign(BaseCrossValidator):
    """Train on one campaign, test on every campaign (itself included): one split per campaign.

    The splits of the mutual-prediction matrix (paper 003, Sect. 3.4): split
    ``i`` trains on campaign ``i`` (in order of appearance) and its test part
    is all rows, so entry ``(i, j)`` is read off the test rows of campaign
    ``j``.  Train and test overlap by design (the diagonal is the self-fit).
    The matrix is indexed by campaigns, so a single campaign is not cut into
    blocks: it gives one split, its self-fit.
    """

    __metadata_request__split = {"groups": True}

    def split(self, X, y=None, groups=None):
        """Yield ``(rows of campaign i, all rows)`` for each campaign ``i``."""
        X, y, groups = indexable(X, y, groups)
        unit, n_units = _index_of(_campaigns(X, groups))
        everything = np.arange(len(unit))
        for i in range(n_units):
            yield np.flatnonzero(unit == i), everything

    def get_n_splits(self, X=None, y=None, groups=None):
        """Number of campaigns."""
        return len(dict.fromkeys(_campaigns(X, groups)))


class CampaignHoldOut(BaseCrossValidator):
    """One split: a share of whole campaigns held out, or the tail of a single campaign.

    With two campaigns or more, ``round(validation_fraction * n_campaigns)``
    of them (at least 1, at most all but one), drawn with
    ``numpy.random.default_rng(random_state)``, are the test part.  With a
    single campaign the test part is its last ``round(validation_fraction *
    n_samples)`` rows (when that leaves both parts non-empty).  Otherwise --
    ``validation_fraction=0`` or fewer than 2 rows -- the test part is empty.
    This is the validation data of early stopping (:class:`~thermocomp.core.models.LSTM`).

    Parameters
    ----------
    validation_fraction : float in [0, 1), default 0.2
    random_state : int or None, default 0
    """

    __metadata_request__split = {"groups": True}

    def __init__(self, validation_fraction: float = 0.2, random_state=0):
        self.validation_fraction = validation_fraction
        self.random_state = random_state

    def test_mask(self, groups, X=None) -> np.ndarray:
        """Boolean mask of the held-out rows."""
        frac = float(self.validation_fraction)
        if not 0 <= frac < 1:
            raise ParameterError(f"validation_fraction={self.validation_fraction!r} must be in [0, 1)")
        unit, n_units = _index_of(_campaigns(X, groups))
        n = len(unit)
        held = np.zeros(n, dtype=bool)
        if frac == 0 or n < 2:
            return held
        if n_units >= 2:
            rng = np.random.default_rng(self.random_state)
            n_val = min(n_units - 1, max(1, round(frac * n_units)))
            held[np.isin(unit, rng.choice(n_units, size=n_val, replace=False))] = True
        else:
            n_val = int(round(frac * n))
            if n_val >= 1 and n - n_val >= 1:
                held[n - n_val:] = True
        return held

    def _iter_test_masks(self, X=None, y=None, groups=None):
        yield self.test_mask(groups, X)

    def get_n_splits(self, X=None, y=None, groups=None):
        return 1


class ForwardChaining(TimeSeriesSplit):
    """Expanding-window splits over one time-ordered record, ``gap`` samples between parts.

    Split ``i`` trains on the first rows and tests on the next block, after
    leaving out ``gap`` samples so that the test part does not start where the
    train part's slow thermal state still lingers.  scikit-learn's
    :class:`~sklearn.model_selection.TimeSeriesSplit`; rows must be in time
    order (``groups`` is ignored).

    With ``min_train_fraction`` the test blocks tile the last ``1 -
    min_train_fraction`` of the rows (``test_size`` is derived from it), so
    every split trains on at least about that share of the record, as the
    final model trains on all of it: a split trained on the first few percent
    of a drifting record extrapolates far worse than the final model will.

    Parameters
    ----------
    n_splits : int, default 5
    gap : int, default 0
        Samples dropped between the end of each train part and its test part.
    test_size : int or None, default None
        Rows per test part (default ``n_samples // (n_splits + 1)``).
    min_train_fraction : float in (0, 1) or None, default None
        Validate on the last ``1 - min_train_fraction`` of the rows only
        (overrides ``test_size``).
    """

    def __init__(self, n_splits: int = 5, gap: int = 0, test_size: int | None = None,
                 min_train_fraction: float | None = None):
        super().__init__(n_splits=n_splits, gap=gap, test_size=test_size)
        self.min_train_fraction = min_train_fraction

    def block_size(self, n_samples: int) -> int | None:
        """Rows per test part for ``n_samples`` rows (None: scikit-learn's default)."""
        f = self.min_train_fraction
        if f is None:
            return self.test_size
        if not 0 < float(f) < 1:
            raise ParameterError(f"min_train_fraction={f!r} must be in (0, 1)")
        return max(1, (n_samples - int(np.ceil(float(f) * n_samples))) // int(self.n_splits))

    def split(self, X, y=None, groups=None):
        """Yield ``(train, test)`` row indices, train strictly before test."""
        if int(self.gap) < 0:
            raise ParameterError(f"gap={self.gap!r} must be >= 0 samples")
        # groups are ignored (rows in time order); scikit-learn warns when it is handed them
        if self.min_train_fraction is None:
            yield from super().split(X, y)
            return
        X, y = indexable(X, y)
        inner = TimeSeriesSplit(n_splits=self.n_splits, gap=self.gap,
                                test_size=self.block_size(len(X)))
        yield from inner.split(X, y)


def forward_block(n: int, n_splits: int, min_train_fraction: float = 0.5) -> int:
    """Rows of a validation block: the last ``1 - min_train_fraction`` of ``n`` in ``n_splits`` blocks."""
    return ForwardChaining(n_splits=n_splits, min_train_fraction=min_train_fraction).block_size(n)


def forward_gap(longest_lag_samples: float, block_samples: int) -> int:
    """Gap of forward chaining: the longest lag in samples, at most half a validation block.

    A lag of time constant ``tau`` remembers ``tau`` worth of the past, so a
    gap that long keeps the validation rows from sharing that memory with the
    last training rows; time constants of days exceed most records, so the
    gap is capped at half a block (each split then loses at most that many
    training rows).
    """
    return int(max(0, min(np.ceil(longest_lag_samples), block_samples // 2)))


def cv_scheme(groups, cv: str = "auto") -> str:
    """``'campaigns'`` or ``'forward'``: how rows of these campaigns are cross-validated.

    ``auto``: several campaigns -> leave-campaigns-out (campaigns are the units
    that are independent of each other); one campaign (one long record) ->
    forward chaining, since time blocks of one drifting record held out in
    the middle are extrapolations a deployed model never faces.
    """
    if cv not in CV_SCHEMES:
        raise ParameterError(f"cv={cv!r} is not one of {list(CV_SCHEMES)}")
    if cv != "auto":
        return cv
    return "campaigns" if len(dict.fromkeys(_campaigns(None, groups))) > 1 else "forward"


class BlockedForward:
    """Forward-chaining validation folds, blocked: the later units validate, the earlier fit.

    Units are campaigns in order of appearance (the manifest's, calendar order),
    or for a single campaign its rows.  The last ``1 - min_train_fraction`` of
    the units are cut into ``n_folds`` consecutive blocks; fold ``k`` fits on
    every unit before block ``k`` and validates on the block, so no fold looks
    ahead and every fold fits on at least about ``min_train_fraction`` of the
    data, as the final model will.  Interleaved leave-campaigns-out folds fit
    on campaigns from after the held-out one: on a record whose behaviour
    drifts that rewards interpolation the test campaigns (later, outside the
    range) never get.

    Campaigns are predicted from their own start.  A single record is predicted
    from its start up to the block's end by the model fitted on the rows before
    the block less a gap of half a block (its slow states do not reach into the
    block), so the state carries over as on the machine, and scored on the block.

    Parameters
    ----------
    n_folds : int, default 5
    min_train_fraction : float in (0, 1), default 0.5
    gap_blocks : float >= 0, default 0.5
        The gap of a single record, in validation blocks.
    """

    def __init__(self, n_folds: int = 5, min_train_fraction: float = 0.5, gap_blocks: float = 0.5):
        self.n_folds = n_folds
        self.min_train_fraction = min_train_fraction
        self.gap_blocks = gap_blocks

    def folds(self, groups, n: int | None = None) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """``(fit, predict, score)`` boolean row masks of each fold (``groups``: campaign of each
        row, None for ``n`` rows of one record)."""
        f = float(self.min_train_fraction)
        if not 0 < f < 1:
            raise ParameterError(f"min_train_fraction={self.min_train_fraction!r} must be in (0, 1)")
        if int(self.n_folds) < 1:
            raise ParameterError(f"n_folds={self.n_folds!r} must be >= 1")
        unit, n_units = _index_of(_campaigns(np.zeros(n or 0), groups))
        if n_units >= 2:
            n_val = min(n_units - 1, max(1, int(n_units - np.ceil(f * n_units))))
            k = min(int(self.n_folds), n_val)
            edges = n_units - n_val + (np.arange(k + 1) * n_val) // k
            return [(unit < a, (unit >= a) & (unit < b), (unit >= a) & (unit < b))
                    for a, b in zip(edges[:-1], edges[1:])]
        rows = np.arange(len(unit))
        k = max(1, min(int(self.n_folds), len(rows) - 1))
        gap = int(forward_block(len(rows), k, f) * float(self.gap_blocks))
        out = []
        for fit, held in ForwardChaining(k, gap=gap, min_train_fraction=f).split(rows[:, None]):
            a, b = int(held[0]), int(held[-1]) + 1
            out.append((rows <= fit[-1], rows < b, (rows >= a) & (rows < b)))
        return out


class LeaveBlockOut:
    """One record: each of ``n_folds`` blocks held out in turn, the model fitted on the rest.

    The blocks tile the record's rows from ``start_fraction`` of it to its end.  Fold ``k``
    fits on every row outside block ``k`` less a gap of ``gap_blocks`` blocks on BOTH sides
    (the block's slow states reach neither the rows before nor those after it), predicts the
    record free-run from its start to the block's end (through fit rows too: a free run never
    reads the measured error) and is scored on the block.  Where the test is a separate
    campaign inside the train record's range, these folds interpolate as it does; forward
    chaining (:class:`BlockedForward`) grades the extrapolation of a drifting record.  The
    fit rows on both sides of the hole stay one record: a lag runs across the hole as the
    ``time`` column says (the first input after it held over it).

    Parameters
    ----------
    n_folds : int, default 5
    start_fraction : float in [0, 1), default 0.0
    gap_blocks : float >= 0, default 0.5
    """

    def __init__(self, n_folds: int = 5, start_fraction: float = 0.0, gap_blocks: float = 0.5):
        self.n_folds = n_folds
        self.start_fraction = start_fraction
        self.gap_blocks = gap_blocks

    def folds(self, n: int) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """``(fit, predict, score)`` boolean row masks of each fold over ``n`` rows."""
        f = float(self.start_fraction)
        if not 0 <= f < 1:
            raise ParameterError(f"start_fraction={self.start_fraction!r} must be in [0, 1)")
        rows = np.arange(n)
        first = int(np.ceil(f * n))
        k = max(1, min(int(self.n_folds), n - first))
        edges = first + (np.arange(k + 1) * (n - first)) // k
        gap = int((n - first) // k * float(self.gap_blocks))
        out = []
        for a, b in zip(edges[:-1], edges[1:]):
            fit = (rows < a - gap) | (rows >= b + gap)
            if not fit.any():
                raise ParameterError(f"n_folds={self.n_folds!r}, gap_blocks={self.gap_blocks!r}: "
                                     f"holding out rows {a}..{b - 1} of {n} leaves none to fit on")
            out.append((fit, rows < b, (rows >= a) & (rows < b)))
        return out
