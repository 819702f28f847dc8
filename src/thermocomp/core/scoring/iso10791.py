r"""ISO 10791-10 Annex A.3 virtual machining test (paper 000, Sects. 2.4 and 4.4).

The test machines 16 slots S1..S16 one after the other, ``interval_s`` apart
(1 h here, so 15 h from the first slot to the last); S1 is the reference and
the test reports the axial error of S2..S16 relative to it.  Simulated on a
recorded error :math:`e(t)` (measured = before compensation, residual =
after), a test started at :math:`t_0` gives

.. math::

    r_k = e(t_0 + (k-1)\,\Delta) - e(t_0), \quad k = 2..16, \qquad
    R(t_0) = \max_{k=1..16} e(t_0 + (k-1)\Delta) - \min_{k=1..16} e(t_0 + (k-1)\Delta)

(:math:`e` linearly interpolated in time), and started at every sample of a
campaign long enough it gives the curve :math:`R(t_0)`, summarised by its mean
and maximum before and after compensation (paper 000, Fig. 26: 57.5 -> 29.5 µm
mean, 112 -> 54 µm max).  Pure core: arrays in, dicts out.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ..metrics import reduction_pct

N_SLOTS = 16
SLOT_INTERVAL_S = 3600.0


def _clean(time_s, *signals):
    t = np.asarray(time_s, float)
    arrays = [np.asarray(s, float) for s in signals]
    ok = np.isfinite(t)
    for a in arrays:
        ok &= np.isfinite(a)
    return t[ok], [a[ok] for a in arrays]


def a3_span_s(n_slots: int = N_SLOTS, interval_s: float = SLOT_INTERVAL_S) -> float:
    """Time from the first slot to the last (15 h for 16 slots 1 h apart)."""
    return (n_slots - 1) * interval_s


def slot_errors(time_s, error, start_s: float, n_slots: int = N_SLOTS,
                interval_s: float = SLOT_INTERVAL_S) -> np.ndarray:
    """Error of slots 2..n relative to slot 1, :math:`r_k = e(t_0+(k-1)\\Delta) - e(t_0)`.

    Raises ValueError when the record does not cover the whole test.
    """
    t, (e,) = _clean(time_s, error)
    slots = start_s + interval_s * np.arange(n_slots)
    if t.size == 0 or slots[0] < t[0] or slots[-1] > t[-1] + 1e-6:
        raise ValueError(f"the record ({_hours(t)}) does not cover {n_slots} slots "
                         f"{interval_s / 3600:g} h apart from t={start_s:g} s")
    values = np.interp(slots, t, e)
    return values[1:] - values[0]


def slot_ranges(time_s, error, n_slots: int = N_SLOTS, interval_s: float = SLOT_INTERVAL_S
                ) -> tuple[np.ndarray, np.ndarray]:
    """Range :math:`R(t_0)` of the slot errors for a test started at every sample.

    Returns ``(start_s, ranges)``, empty when the record is shorter than the test.
    Vectorised: one ``np.interp`` on the (starts x slots) grid of slot times.
    """
    t, (e,) = _clean(time_s, error)
    if t.size == 0:
        return np.empty(0), np.empty(0)
    starts = t[t + a3_span_s(n_slots, interval_s) <= t[-1] + 1e-6]
    grid = starts[:, None] + interval_s * np.arange(n_slots)[None, :]
    values = np.interp(grid, t, e)
    return starts, np.ptp(values, axis=1) if starts.size else np.empty(0)


def a3_campaign(time_s, measured, residual, n_slots: int = N_SLOTS,
                interval_s: float = SLOT_INTERVAL_S) -> dict:
    """The A.3 test on one campaign, before (measured) and after (residual) compensation.

    Returns ``{"available": False, "reason": ...}`` for a campaign shorter than
    the test (the default year-round campaigns last 4-8 h, the test 15 h);
    otherwise the test started at the first sample (``slot_time_s`` and the
    relative errors of slots 2..n, ``before``/``after``) and the moving test
    started at every sample (``start_s``, ``range_before``, ``range_after`` and
    their mean/max).
    """
    t, (y, r) = _clean(time_s, measured, residual)
    span = a3_span_s(n_slots, interval_s)
    duration = float(t[-1] - t[0]) if t.size else 0.0
    if duration + 1e-6 < span:
        return {"available": False,
                "reason": f"campaign spans {duration / 3600:.1f} h; the A.3 test needs "
                          f"{span / 3600:g} h ({n_slots} slots {interval_s / 3600:g} h apart)"}
    start = float(t[0])
    before, after = slot_errors(t, y, start, n_slots, interval_s), slot_errors(t, r, start, n_slots,
                                                                              interval_s)
    starts, rb = slot_ranges(t, y, n_slots, interval_s)
    _, ra = slot_ranges(t, r, n_slots, interval_s)
    return {"available": True,
            "first_test": {"slot_time_s": [float(start + k * interval_s) for k in range(1, n_slots)],
                           "before": before.tolist(), "after": after.tolist(),
                           "range_before": _ptp0(before), "range_after": _ptp0(after)},
            "moving": {"start_s": starts.tolist(), "range_before": rb.tolist(),
                       "range_after": ra.tolist(), **_summary(rb, ra)}}


def a3_report(times: Mapping[str, np.ndarray], measured: Mapping[str, np.ndarray],
              residual: Mapping[str, np.ndarray], n_slots: int = N_SLOTS,
              interval_s: float = SLOT_INTERVAL_S, keep_curves: bool = False) -> dict:
    """The A.3 virtual test on every campaign of a split, with the moving test pooled.

    ``summary`` pools the ranges of all start times of all long-enough
    campaigns (mean and max before/after and their reduction in %); it is
    ``None`` with a ``reason`` when no campaign is long enough.  The per-start
    curves (one value per sample) are dropped unless ``keep_curves``, to keep
    ``metrics.json`` small.
    """
    per = {c: a3_campaign(times[c], measured[c], residual[c], n_slots, interval_s) for c in measured}
    long = [p for p in per.values() if p["available"]]
    rb = np.concatenate([p["moving"]["range_before"] for p in long]) if long else None
    ra = np.concatenate([p["moving"]["range_after"] for p in long]) if long else None
    if not keep_curves:
        for p in long:
            for key in ("start_s", "range_before", "range_after"):
                p["moving"].pop(key)
    out = {"n_slots": n_slots, "slot_interval_s": float(interval_s),
           "test_span_s": a3_span_s(n_slots, interval_s), "per_campaign": per}
    if not long:
        out["summary"] = None
        out["reason"] = (f"no campaign of the split spans the {a3_span_s(n_slots, interval_s) / 3600:g} h "
                         f"of the test (longest: {max(_span_h(times[c]) for c in measured):.1f} h)")
        return out
    out["summary"] = {"n_campaigns": len(long), **_summary(rb, ra)}
    return out


def _summary(rb: np.ndarray, ra: np.ndarray) -> dict:
    rb, ra = np.asarray(rb, float), np.asarray(ra, float)
    s = {"n_starts": int(rb.size),
         "range_before_mean": float(rb.mean()), "range_after_mean": float(ra.mean()),
         "range_before_max": float(rb.max()), "range_after_max": float(ra.max())}
    s["mean_reduction_pct"] = reduction_pct(s["range_before_mean"], s["range_after_mean"])
    s["max_reduction_pct"] = reduction_pct(s["range_before_max"], s["range_after_max"])
    return s


def _ptp0(relative: np.ndarray) -> float:
    """Range of the 16 slots: the relative errors of slots 2..n and slot 1's zero."""
    return float(max(relative.max(), 0.0) - min(relative.min(), 0.0))


def _span_h(time_s) -> float:
    t = np.asarray(time_s, float)
    t = t[np.isfinite(t)]
    return float(t[-1] - t[0]) / 3600 if t.size else 0.0


def _hours(t: np.ndarray) -> str:
    return f"{(t[-1] - t[0]) / 3600:.1f} h" if t.size else "empty"
