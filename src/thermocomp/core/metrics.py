r"""Accuracy metrics of a thermal error compensation.

All take the measured error ``y`` and/or the residual ``r = y - \hat y`` of
one campaign in the target's unit (µm, or µm/m for an angular error: :func:`unit`), in the
reference frame of the data.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence

import numpy as np

from ..base.jsonsafe import json_safe

_ANGULAR = re.compile(r"^E_[ABC][XYZ]")   # ISO 230-1: E_AX .. E_CZ, rotations (+ order, cross axis)
# extension (iso67): or a name with a word saying a rotation ('E_Tilt_A', a sensor nest's tilt
# about X of ISO 230-3; 'E_tilt_ch4', the name a header in µrad or arcsec is read under)
TILT_WORDS = frozenset({"tilt", "tilts", "pitch", "roll", "yaw", "angle", "angular", "neigung",
                        "kippung", "winkel"})
_WORD = re.compile(r"[_.\-]+")

# The keys of the scores in ``metrics.json`` (CLI.md), named here once: the figures of a split
# and of a campaign, and the blocks of a target beside ``train``/``test``.  Elsewhere they are
# read through :mod:`thermocomp.core.scoring.results` or these names (tests/shell/test_results.py checks).
RMSE, MAE, RSD, RSD_MEAN, RSD_SD = "rmse", "mae", "rsd", "rsd_mean", "rsd_sd"
RMS_BEFORE, RMS_AFTER, P2P_BEFORE, P2P_AFTER = "rms_before", "rms_after", "p2p_before", "p2p_after"
RMS_REDUCTION, P2P_REDUCTION = "rms_reduction_pct", "p2p_reduction_pct"
E_P95, E_MAX, E_MEAN, ISO_A3, PER_UNIT = "e_p95", "e_max", "e_mean", "iso10791_a3", "per_unit"
PER_CAMPAIGN, VALIDATION, PERSISTENCE = "per_campaign", "validation", "persistence"
OTHER_BLOCKS = ("test_one_step", "test_simulation", "validation_simulation")
SCORE_KEYS = (RMSE, MAE, RSD, RSD_MEAN, RSD_SD, RMS_BEFORE, RMS_AFTER, P2P_BEFORE, P2P_AFTER,
              RMS_REDUCTION, P2P_REDUCTION, E_P95, E_MAX, E_MEAN, ISO_A3, PER_UNIT, PERSISTENCE,
              *OTHER_BLOCKS)


def test_block(mode: str) -> str:
    """The key of a target's test figures in ``mode`` when the run was scored in the other."""
    return f"test_{mode}"


def validation_block(mode: str) -> str:
    """The key of a target's validation in ``mode`` when the run was scored in the other."""
    return f"{VALIDATION}_{mode}"


def unit(target: str) -> str:
    """The unit of an ``E_`` column (DATA_FORMAT.md): µm/m for an angular error, else µm."""
    return "µm/m" if angular(target) else "µm"


def angular(target: str) -> bool:
    """``target`` is an angular error (µm/m = µrad): ISO 230-1's name (``E_AX`` .. ``E_CZ``) or,
    extension (iso67), a name with a word of :data:`TILT_WORDS` (``E_Tilt_A``)."""
    return bool(_ANGULAR.match(target)) or (
        target.startswith("E_") and any(w.lower() in TILT_WORDS for w in _WORD.split(target[2:])))


def rmse(residual) -> float:
    r"""Root-mean-square error :math:`\sqrt{\tfrac1n\sum_j r_j^2}`."""
    r = np.asarray(residual, float)
    return float(np.sqrt(np.mean(r**2)))


rms = rmse  # RMS of a signal is the same formula; named apart for "before" (measured error)


def mae(residual) -> float:
    r"""Mean absolute error :math:`\tfrac1n\sum_j |r_j|` (what published comparisons often
    report beside, or instead of, the RMSE)."""
    return float(np.mean(np.abs(np.asarray(residual, float))))


def rsd(residual) -> float:
    r"""Residual standard deviation of paper 003, Eq. (10).

    .. math:: R_{sd} = \sqrt{\frac{\sum_{j=1}^{n} (\hat y_j - y_j)^2}{n - 1}}

    (not mean-centred: an offset counts as error, as on the machine).  Over the rows where
    the residual is defined: a target measured now and then (``data.sparse_targets``) is NaN
    between its measurements.
    """
    r = np.asarray(residual, float)
    r = r[~np.isnan(r)]
    if r.size < 2:
        return float("nan")
    return float(np.sqrt(np.sum(r**2) / (r.size - 1)))


def p2p(signal) -> float:
    """Peak-to-peak value ``max - min``."""
    s = np.asarray(signal, float)
    return float(np.max(s) - np.min(s))


def sm_sd(values: Sequence[float]) -> tuple[float | None, float | None]:
    r"""SM and SD of paper 003: mean and sample standard deviation of per-campaign Rsd.

    ``(None, None)`` for SD when there is a single campaign (JSON never holds NaN).
    """
    v = np.asarray(list(values), float)
    if v.size == 0:
        return None, None
    mean = float(np.mean(v))
    sd = float(np.std(v, ddof=1)) if v.size > 1 else None
    return mean, sd


def _sparse_table(x: np.ndarray, op) -> list[np.ndarray]:
    """Level k holds op over windows of 2**k samples starting at each index."""
    table = [x]
    k = 1
    while 2**k <= x.size:
        prev = table[-1]
        half = 2 ** (k - 1)
        table.append(op(prev[:-half], prev[half:]))
        k += 1
    return table


def _cumsums(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Running sums of x and x² (of x minus its mean, against cancellation)."""
    xc = x - x.mean() if x.size else x
    return np.concatenate([[0.0], np.cumsum(xc)]), np.concatenate([[0.0], np.cumsum(xc**2)])


def window_statistic(x, length: int, statistic: str = "range",
                     tables=None, cumsums=None) -> np.ndarray:
    r"""Statistic of every sliding window of ``length`` samples of ``x``.

    ``range``: :math:`\max - \min` over the window; ``std``: population σ.
    Range uses sparse tables (two table look-ups per window, O(n) per length)
    so all window lengths cost O(n²) vectorised work instead of a Python loop.
    """
    x = np.asarray(x, float)
    n = x.size
    if length < 1 or length > n:
        return np.empty(0)
    if statistic == "range":
        tmax, tmin = tables if tables is not None else (_sparse_table(x, np.maximum),
                                                         _sparse_table(x, np.minimum))
        k = int(np.floor(np.log2(length)))
        span = length - 2**k
        count = n - length + 1
        hi = np.maximum(tmax[k][:count], tmax[k][span:span + count])
        hi -= np.minimum(tmin[k][:count], tmin[k][span:span + count])
        return hi
    if statistic == "std":
        c1, c2 = cumsums if cumsums is not None else _cumsums(x)
        s1 = c1[length:] - c1[:-length]
        var = c2[length:] - c2[:-length]
        s1 *= s1
        s1 /= length
        var -= s1
        var /= length
        # Running sums lose ~eps·scale² to cancellation: below that, σ is 0.
        var[var < 1e-12 * max(c2[-1] / n, 1e-300)] = 0.0
        return np.sqrt(var, out=var)
    raise ValueError(f"statistic must be 'range' or 'std', got {statistic!r}")


def _prepare(x: np.ndarray, statistic: str):
    if statistic == "range":
        return (_sparse_table(x, np.maximum), _sparse_table(x, np.minimum)), None
    if statistic == "std":
        return None, _cumsums(x)
    raise ValueError(f"statistic must be 'range' or 'std', got {statistic!r}")


def _percentile(values: np.ndarray, q: float, guess: float | None) -> tuple[float, float]:
    """``np.percentile(values, q)`` (linear method) and the lower order statistic used.

    Written by hand because numpy has no incremental percentile: ``values`` is
    first cut to the elements >= ``guess`` (the previous window length's
    answer; E_P95 curves are smooth in Δt) and only that tail is partitioned.
    The cut is checked by counting, so the answer is exact whatever the guess.
    ``values`` is reordered in place.
    """
    m = values.size
    k = q / 100.0 * (m - 1)
    lo = int(np.floor(k))
    ranks = [lo, min(lo + 1, m - 1)]
    part = values
    if guess is not None and m > 2048:
        tail = values[values >= guess]
        below = m - tail.size
        if below <= lo:
            part, ranks = tail, [r - below for r in ranks]
    part.partition(ranks)
    a, b = part[ranks[0]], part[ranks[1]]
    return float(a + (k - lo) * (b - a)), float(a)


def window_curves(series: Sequence, lengths: Sequence[int], statistic: str = "range",
                  q: float = 95.0) -> dict[str, np.ndarray]:
    r"""E_P95, E_max and E_mean curves (paper 000, Sect. 2.3) in one pass.

    For each window length :math:`\Delta t` (in samples), every sliding window
    :math:`[t, t+\Delta t)` of every series gives one statistic :math:`S`
    (``range`` = max - min, or ``std`` = population σ); pooled over series,

    .. math::

        E_{P95}(\Delta t) = P_{q}\{S\},\quad E_{max}(\Delta t) = \max\{S\},\quad
        E_{mean}(\Delta t) = \operatorname{mean}\{S\}

    Parameters
    ----------
    series : list of 1-D arrays (one per campaign, uniformly sampled; NaN dropped)
    lengths : window lengths in samples (>= 1)
    statistic : 'range' or 'std'
    q : percentile of the ``"percentile"`` curve (95 for E_P95)

    Returns
    -------
    dict with ``"percentile"``, ``"max"``, ``"mean"``: arrays of shape
    (len(lengths),), NaN where no series is that long.
    """
    prepared = []
    for s in series:
        x = np.asarray(s, float)
        x = x[np.isfinite(x)]
        prepared.append((x, *_prepare(x, statistic)))
    out = {key: np.full(len(lengths), np.nan) for key in ("percentile", "max", "mean")}
    guess = None
    from ..base.progress import bar

    for i, length in enumerate(bar(lengths, desc="E_P95 windows", unit="window",
                                   disable=True if len(lengths) < 500 else None)):
        parts = [window_statistic(x, int(length), statistic, t, c) for x, t, c in prepared]
        parts = [p for p in parts if p.size]
        if not parts:
            continue
        values = parts[0] if len(parts) == 1 else np.concatenate(parts)
        out["max"][i] = values.max()
        out["mean"][i] = values.mean()
        out["percentile"][i], low = _percentile(values, q, guess)
        guess = 0.98 * low
    return out


def e_p95(series: Sequence, lengths: Sequence[int], statistic: str = "range",
          q: float = 95.0) -> np.ndarray:
    r"""E_P95 curve (paper 000, Sect. 2.3): for each window length, the ``q``-th
    percentile of the window statistic over all sliding windows, pooled over series.

    .. math:: E_{P95}(\Delta t) = P_{95}\{\,S(e[t, t+\Delta t)) : t\,\}

    Parameters
    ----------
    series : list of 1-D arrays (one per campaign, uniformly sampled)
    lengths : window lengths in samples (>= 1)
    statistic : 'range' or 'std'

    Returns
    -------
    ndarray of shape (len(lengths),); NaN where no series is that long.
    """
    return window_curves(series, lengths, statistic, q)["percentile"]


def e_max(series: Sequence, lengths: Sequence[int], statistic: str = "range") -> np.ndarray:
    r"""E_max curve: the largest window statistic, :math:`\max_t S(e[t, t+\Delta t))`
    (the worst case of paper 000, Sect. 2.3); same arguments as :func:`e_p95`."""
    return window_curves(series, lengths, statistic)["max"]


def e_mean(series: Sequence, lengths: Sequence[int], statistic: str = "range") -> np.ndarray:
    r"""E_mean curve: the mean window statistic, :math:`E_\mu = \operatorname{mean}_t
    S(e[t, t+\Delta t))`; same arguments as :func:`e_p95`."""
    return window_curves(series, lengths, statistic)["mean"]


def window_lengths(max_len: int, max_points: int | None = None) -> np.ndarray:
    """Window lengths in samples, 2..max_len (a window of n samples spans (n-1)·Δt).

    Every length, or ``max_points`` log-spaced unique ones when there are more.
    """
    if max_len < 2:
        return np.empty(0, int)
    if max_points is None or max_len - 1 <= max_points:
        return np.arange(2, max_len + 1)
    return np.unique(np.round(np.geomspace(2, max_len, max_points)).astype(int))


def reduction_pct(before: float, after: float) -> float | None:
    r"""Reduction by the compensation in %: :math:`100\,(1 - \text{after}/\text{before})`.

    ``None`` when ``before`` is 0 (nothing to reduce).
    """
    if before is None or after is None or not before:
        return None
    return json_safe(100.0 * (1.0 - after / before))


def split_scores(measured: Mapping[str, np.ndarray], residual: Mapping[str, np.ndarray],
                 sample_period_s: float, e_p95_statistic: str = "range",
                 e_p95_points: int | None = 200, with_before_after: bool = True) -> dict:
    """All ``metrics.json`` figures of one target on one split.

    ``rmse``, ``mae``, ``rms_*`` and ``p2p_*`` are pooled over all samples of the split's
    campaigns (in the reference frame); ``rsd_mean``/``rsd_sd`` are SM/SD of the
    per-campaign Rsd; ``*_reduction_pct`` is :func:`reduction_pct` of before/after.
    Window lengths of ``e_p95`` run from one sample step to the longest campaign
    (``window_s`` in seconds); ``e_max`` and ``e_mean`` have the same layout and
    hold the largest and the mean window statistic instead of the 95th percentile.
    """
    ids = list(measured)
    measured, residual, sample_period_s, counted = on_measured_rows(measured, residual,
                                                                    sample_period_s)
    y_all = np.concatenate([np.asarray(measured[c], float) for c in ids])
    r_all = np.concatenate([np.asarray(residual[c], float) for c in ids])
    sm, sd = sm_sd([rsd(residual[c]) for c in ids])
    out = {RMSE: rmse(r_all), MAE: mae(r_all), RSD_MEAN: sm, RSD_SD: sd, **counted}
    if not with_before_after:
        return out
    out.update(before_after(y_all, r_all))
    out[PER_CAMPAIGN] = {c: _campaign_scores(measured[c], residual[c]) for c in ids}
    lengths = window_lengths(max(len(measured[c]) for c in ids), e_p95_points)
    window_s = [float((n - 1) * sample_period_s) for n in lengths]
    before = window_curves([measured[c] for c in ids], lengths, e_p95_statistic)
    after = window_curves([residual[c] for c in ids], lengths, e_p95_statistic)
    for key, curve in ((E_P95, "percentile"), (E_MAX, "max"), (E_MEAN, "mean")):
        out[key] = {"statistic": e_p95_statistic, "window_s": window_s,
                    "before": json_safe(before[curve]), "after": json_safe(after[curve])}
    return out


def on_measured_rows(measured: Mapping[str, np.ndarray], residual: Mapping[str, np.ndarray],
                     sample_period_s: float) -> tuple[dict, dict, float, dict]:
    """The rows where the target was measured, of every campaign: a target measured now and
    then (``data.sparse_targets``, NaN between its measurements) is scored there only.

    Returns ``(measured, residual, period, counted)``: the arrays on those rows, the sample
    period of the measured rows (``sample_period_s`` times their median spacing: a window of
    the E_P95 curves spans measurements) and ``{"measured_rows": n, "rows": N}`` ({} where
    every row is measured: a dense target's figures as before)."""
    keep = {c: np.isfinite(np.asarray(measured[c], float)) for c in measured}
    if all(k.all() for k in keep.values()):
        return dict(measured), dict(residual), sample_period_s, {}
    spacing = [np.diff(np.flatnonzero(k)) for k in keep.values() if k.sum() > 1]
    spacing = np.concatenate(spacing) if spacing else np.ones(1)
    measured = {c: np.asarray(measured[c], float)[keep[c]] for c in measured}
    residual = {c: np.asarray(residual[c], float)[keep[c]] for c in residual}
    counted = {"measured_rows": int(sum(k.sum() for k in keep.values())),
               "rows": int(sum(k.size for k in keep.values()))}
    return measured, residual, float(sample_period_s * np.median(spacing)), counted


def before_after(measured, residual) -> dict:
    """RMS and peak-to-peak of ``measured`` (before) and ``residual`` (after), and their
    reductions: the compensation's figures of one signal."""
    out = {RMS_BEFORE: rms(measured), RMS_AFTER: rms(residual),
           P2P_BEFORE: p2p(measured), P2P_AFTER: p2p(residual)}
    out[RMS_REDUCTION] = reduction_pct(out[RMS_BEFORE], out[RMS_AFTER])
    out[P2P_REDUCTION] = reduction_pct(out[P2P_BEFORE], out[P2P_AFTER])
    return out


def _campaign_scores(measured, residual) -> dict:
    return {RMSE: rmse(residual), MAE: mae(residual), RSD: json_safe(rsd(residual)),
            **before_after(measured, residual)}


def rsd_summary(per_unit: Mapping[str, float], key: str = PER_CAMPAIGN, skip_nan: bool = True
                ) -> dict:
    """SM and SD of per-unit Rsd (:func:`sm_sd`; a NaN left out, or making them NaN with
    ``skip_nan=False``) with the per-unit values."""
    values = list(per_unit.values())
    sm, sd = sm_sd([v for v in values if np.isfinite(v)] if skip_nan else values)
    return {RSD_MEAN: sm, RSD_SD: sd, key: json_safe(dict(per_unit))}


def pooled_scores(n: int, sum_sq: float, rsds: Sequence[float]) -> dict:
    """RMSE of ``n`` residuals whose squares sum to ``sum_sq``, SM/SD of their units' Rsd."""
    sm, sd = sm_sd(rsds)
    return {RMSE: float(np.sqrt(sum_sq / n)), RSD_MEAN: sm, RSD_SD: sd}


def validation_scores(residual: Mapping[str, np.ndarray], method: str, n_folds: int) -> dict:
    """One target's validation figures: RMSE pooled over the held-out units, SM/SD of their Rsd."""
    pooled = np.concatenate([np.asarray(r, float) for r in residual.values()])
    pooled = pooled[~np.isnan(pooled)]      # (the measured rows of a sparse target)
    summary = rsd_summary({u: rsd(r) for u, r in residual.items()}, PER_UNIT)
    return {RMSE: float(np.sqrt(np.mean(pooled ** 2))) if pooled.size else None,
            RSD_MEAN: summary[RSD_MEAN], RSD_SD: summary[RSD_SD], "method": method,
            "n_folds": int(n_folds), PER_UNIT: summary[PER_UNIT]}

