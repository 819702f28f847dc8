"""The drift of a sensor no other predicts, bounded by a ridge on the others (monb92 / monb93).

The monitor's POD judges a sensor by what the other temperatures predict of it through its
modes; one whose leverage is at least ``max_leverage`` (its own mode) has no band, and a slow
drift of it is read by the model unseen (bench_audit89: +0.5 °C/h on a column's ``T_front3``,
adaptive 9.4 -> 13.0 µm, no event).  A linear regression on the other temperatures AND the
machine's states predicts many such sensors where the POD cannot (bench_mon91b variant B).

:class:`BlindDrift` holds, per such sensor that has a fallback family (:mod:`.fallback`: once
out, its correction is the family fitted without it), a ridge (``StandardScaler`` +
``RidgeCV``, folded into one coefficient vector) of its change since the campaign's first row
on the same change of the other temperatures the model reads and of each state's (and the
ambient's) first-order low-pass response at :data:`TAUS`; a band ``max(0.4 °C, 3 x the 99.5th
percentile of its windowed cross-validated residual)`` (the monitor's own rule for a band); and a
growth spacing.  Judged are the sensors whose ridge on the temperatures the monitor's bands judge
predicts better than their mean (cross-validated R² > 0: a model that predicts nothing judges
nothing, the column's ``T_amb``); each judged sensor's ridge is then fitted on every temperature
but the judged ones (a drift of one is in no other's inputs; an ambient no state drives, not
judged, is read).  A sensor is excluded where its windowed residual is beyond the band 2 samples
in a row AND, read every ``spacing`` samples back, grew :data:`GROWTHS` times in a row in the
crossing's direction: a drift only grows, a healthy excursion comes back.  ``spacing`` is a third
of the sensor's own e-folding time in training (the lag where the autocorrelation of its reading
falls below 1/e): the growths span twice the time the sensor itself takes to decorrelate, so a
column that warms over hours is read over hours, not over 60 samples.  The compensator judges
only while the monitor's field is quiet (:meth:`~.adaptive.AdaptiveCompensator._blind_drifts`).
Everything is causal: trailing filters, a trailing window, a ridge fixed at training.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
from scipy.signal import lfilter
from sklearn.linear_model import RidgeCV
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

TAUS = (900.0, 3600.0, 14400.0)   # s: a quarter hour to four hours, a machine's thermal range
ALPHAS = np.logspace(-3, 3, 13)
BLOCKS = 5          # contiguous CV blocks where the training holds fewer than 3 campaigns
WARNING_C, SPREAD_FACTOR, WINDOW, CONFIRM = 0.4, 3.0, 10, 2   # the monitor's defaults
GROWTHS = 6         # growths in a row a crossing needs (bench_monb92b grow6)
SPAN_SHARE = 3      # spacing = the sensor's e-folding time / this: GROWTHS reads span 2 of it
AMBIENT = "T_amb"


def _drivers(columns: Sequence[str], readable: set) -> list[int]:
    """Columns whose low-pass responses are features: the states and the ambient (if read)."""
    return [j for j, c in enumerate(columns) if c.startswith("S_") or (c == AMBIENT and c in readable)]


def _temperatures(columns: Sequence[str], readable: set) -> list[int]:
    return [j for j, c in enumerate(columns) if c.startswith("T_") and c in readable]


def _filtered(U: np.ndarray, dt, start: np.ndarray, state: np.ndarray | None = None
              ) -> tuple[np.ndarray, np.ndarray]:
    """First-order responses (exact for a zero-order hold) of the columns of ``U`` at each of
    :data:`TAUS` (columns: driver-major), from ``state`` (else settled at ``start``); ``dt``
    scalar or per row.  Returns ``(responses, last state)``."""
    n, d = U.shape
    y0 = np.repeat(start, len(TAUS)) if state is None else state
    dt = np.broadcast_to(np.asarray(dt, float), (n,))
    a = np.exp(-dt[:, None] / np.tile(np.asarray(TAUS), d)[None, :])
    u = np.repeat(U, len(TAUS), axis=1)
    out = np.empty((n, d * len(TAUS)))
    if n and np.all(dt == dt[0]):         # one coefficient: lfilter per column
        for k in range(out.shape[1]):
            out[:, k] = lfilter([1 - a[0, k]], [1, -a[0, k]], u[:, k], zi=[a[0, k] * y0[k]])[0]
    else:
        y = y0.astype(float).copy()
        for i in range(n):
            y = a[i] * y + (1 - a[i]) * u[i]
            out[i] = y
    return out, (out[-1].copy() if n else np.asarray(y0, float).copy())


def _efolding(x: np.ndarray) -> int:
    """Lag (samples) where the autocorrelation of ``x`` first falls below 1/e."""
    x = x - x.mean()
    v = float(x @ x)
    for lag in range(1, len(x)):
        if float(x[lag:] @ x[:-lag]) < v / np.e:
            return lag
    return len(x)


def _windowed(r: np.ndarray, lengths: Sequence[int]) -> np.ndarray:
    """Trailing mean over :data:`WINDOW` samples (fewer at a campaign's start), per campaign."""
    out, a = [], 0
    for m in lengths:
        c = np.cumsum(np.insert(r[a:a + m], 0, 0.0))
        k = np.minimum(np.arange(1, m + 1), WINDOW)
        out.append((c[1:] - c[np.arange(1, m + 1) - k]) / k)
        a += m
    return np.concatenate(out) if out else np.zeros(0)


def _copy(v):
    return None if v is None else np.copy(v)


class BlindDrift:
    """The blind-sensor drift rule (module doc): fitted by :meth:`from_training`, streamed by
    :meth:`scan` / :meth:`advance` on the compensator's rows (order of ``columns``)."""

    def __init__(self, columns: Sequence[str], readable: Sequence[str], sensors: Sequence[str],
                 coef: np.ndarray, intercept: np.ndarray, band: np.ndarray, spacing: np.ndarray,
                 r2: np.ndarray):
        self.columns, self.readable = list(columns), list(readable)
        self.sensors = list(sensors)
        self.idx_ = np.array([self.columns.index(s) for s in self.sensors], dtype=int)
        self.temps_ = np.array(_temperatures(self.columns, set(readable)), dtype=int)
        self.drivers_ = np.array(_drivers(self.columns, set(readable)), dtype=int)
        self.coef_ = np.asarray(coef, float).reshape(len(self.sensors), -1)
        self.intercept_ = np.asarray(intercept, float)
        self.band_ = np.asarray(band, float)
        self.spacing_ = np.asarray(spacing, dtype=int)
        self.r2_ = np.asarray(r2, float)
        self._memory = int(GROWTHS * self.spacing_.max()) + 1 if len(self.sensors) else 1
        self.reset()

    # -- fitting ----------------------------------------------------------------------------
    @classmethod
    def from_training(cls, columns: Sequence[str], campaigns: Mapping[str, pd.DataFrame],
                      candidates: Sequence[str], readable: Sequence[str], period_s: float
                      ) -> "BlindDrift | None":
        """The rule for each of ``candidates`` (the sensors with a fallback) whose ridge on the
        ``readable`` temperatures (those the monitor's bands judge) and the states predicts
        better than its mean in cross-validation (R² > 0); each such sensor's ridge then refitted
        on every temperature but those judged sensors (a drift of one is then in no other's
        inputs, while a sensor not judged -- an ambient no state drives -- is read again: the
        column's ``T_front3`` crossed healthy without its ``T_amb``).  ``None``: none judged."""
        columns, frames = list(columns), list(campaigns.values())
        judged = list(_ridges(frames, columns, candidates, set(readable) - set(candidates),
                              period_s))
        others = {c for c in columns if c.startswith("T_")} - set(judged)
        fitted = _ridges(frames, columns, judged, others, period_s)
        if not fitted:
            return None
        sensors = list(fitted)
        coef, intercept, band, spacing, r2 = (np.array(v) for v in zip(*fitted.values()))
        return cls(columns, sorted(others), sensors, coef, intercept, band, spacing, r2)

    # -- streaming state --------------------------------------------------------------------
    def reset(self) -> None:
        """New campaign: the next row is the reference."""
        k = len(self.sensors)
        self._ref = self._zref = None
        self._state = None
        self._last = None                               # the last finite input per column
        self._r = np.full((WINDOW - 1, k), np.nan)      # the last residuals (oldest first)
        self._w = np.full((self._memory, k), np.nan)    # the last windowed residuals
        self._n = 0
        self.out_ = np.zeros(k, dtype=bool)             # excluded by the rule this campaign

    def snapshot(self) -> tuple:
        return (_copy(self._ref), _copy(self._zref), _copy(self._state), _copy(self._last),
                self._r.copy(), self._w.copy(), self._n, self.out_.copy())

    def restore(self, snap: tuple) -> None:
        ref, zref, state, last, r, w, n, out = snap
        self._ref, self._zref = _copy(ref), _copy(zref)
        self._state, self._last = _copy(state), _copy(last)
        self._r, self._w, self._n, self.out_ = r.copy(), w.copy(), int(n), out.copy()

    def _run(self, X: np.ndarray, dt) -> tuple[np.ndarray, tuple]:
        """Windowed residuals of the rows ``X`` (n x columns) from the current state, without
        changing it; the state after them."""
        X = np.array(X, dtype=float, copy=True)
        last = self._last
        for i in range(len(X)):          # a missing reading: its last value (inputs are held)
            bad = ~np.isfinite(X[i])
            if bad.any():
                X[i, bad] = np.nan if last is None else last[bad]
            last = np.where(np.isfinite(X[i]), X[i], np.nan if last is None else last)
        ref = X[0].copy() if self._ref is None else self._ref
        D = X[:, self.drivers_]
        start = np.where(np.array([self.columns[j] == AMBIENT for j in self.drivers_]),
                         ref[self.drivers_], 0.0)
        filt, state = _filtered(np.nan_to_num(D), dt, start, self._state)
        z = np.hstack([X[:, self.temps_], filt])
        z0 = z[0].copy() if self._ref is None else self._zref   # the reference row's
        resid = (X[:, self.idx_] - ref[self.idx_]) - (self.intercept_ + (z - z0) @ self.coef_.T)
        r = np.vstack([self._r, resid])
        c = np.nancumsum(np.vstack([np.zeros((1, r.shape[1])), r]), axis=0)
        cnt = np.cumsum(np.vstack([np.zeros((1, r.shape[1])), np.isfinite(r)]), axis=0)
        hi = np.arange(WINDOW, len(r) + 1)
        with np.errstate(invalid="ignore", divide="ignore"):
            w = (c[hi] - c[hi - WINDOW]) / (cnt[hi] - cnt[hi - WINDOW])
        return w, (ref, z0, state, last, r[-(WINDOW - 1):], w)

    def scan(self, X: np.ndarray, dt) -> tuple[int | None, list[int]]:
        """``(row, sensors)``: the first row of ``X`` where a sensor not yet out crosses (and
        the sensor positions crossing there), else ``(None, [])``; the state unchanged."""
        if not len(X):
            return None, []
        w, _ = self._run(X, dt)
        W = np.vstack([self._w, w])
        base = len(self._w)
        with np.errstate(invalid="ignore"):
            beyond = np.abs(W) > self.band_
            ok = beyond[base:] & beyond[base - 1:-1]
            sign = np.sign(W[base:])
            for k, sp in enumerate(self.spacing_):
                for g in range(GROWTHS):
                    a = W[base - g * sp:len(W) - g * sp, k]
                    b = W[base - (g + 1) * sp:len(W) - (g + 1) * sp, k]
                    ok[:, k] &= sign[:, k] * (a - b) > 0
        ok &= ~self.out_
        rows = np.flatnonzero(ok.any(axis=1))
        if not rows.size:
            return None, []
        return int(rows[0]), [int(k) for k in np.flatnonzero(ok[rows[0]])]

    def advance(self, X: np.ndarray, dt) -> None:
        """Take the rows ``X`` into the state."""
        if not len(X):
            return
        w, (ref, z0, state, last, r, _) = self._run(X, dt)
        self._ref, self._zref, self._state, self._last, self._r = ref, z0, state, last, r
        self._w = np.vstack([self._w, w])[-self._memory:]
        self._n += len(X)


def _period(df: pd.DataFrame, period_s: float) -> float:
    if "time" in df.columns and len(df) > 1:
        dt = float(np.median(np.diff(df["time"].to_numpy(float))))
        if np.isfinite(dt) and dt > 0:
            return dt
    return float(period_s)


def _features(A: np.ndarray, columns: Sequence[str], readable: set, dt: float) -> np.ndarray:
    """The readable temperatures and every driver's responses (:func:`_filtered`), referenced
    at row 0: the inputs of every ridge of :class:`BlindDrift`."""
    temps, drivers = _temperatures(columns, readable), _drivers(columns, readable)
    start = np.array([A[0, j] if columns[j] == AMBIENT else 0.0 for j in drivers])
    filt = _filtered(A[:, drivers], dt, start)[0]
    z = np.hstack([A[:, temps], filt])
    return z - z[0]


def _ridges(frames: list[pd.DataFrame], columns: list[str], sensors: Sequence[str],
            readable: set, period_s: float) -> dict[str, tuple]:
    """``{sensor: (coefficients over :func:`_features`, intercept, band, spacing, CV R²)}`` of
    each of ``sensors`` whose ridge on the ``readable`` temperatures and the drivers has a CV
    R² > 0 (module doc)."""
    Z = [_features(df[columns].to_numpy(float), columns, readable, _period(df, period_s))
         for df in frames]
    X, lengths = np.vstack(Z), [len(z) for z in Z]
    out = {}
    for s in sensors:
        y = np.concatenate([df[s].to_numpy(float) - df[s].to_numpy(float)[0] for df in frames])
        if len(y) < 2 * BLOCKS or not np.isfinite(X).all() or not np.isfinite(y).all():
            continue
        r = _cv_residual(X, y, lengths)
        r2 = 1.0 - float(r @ r) / max(float(((y - y.mean()) ** 2).sum()), 1e-300)
        if not r2 > 0.0:         # predicts nothing: judges nothing
            continue
        w = _windowed(r, lengths)
        band = max(WARNING_C, SPREAD_FACTOR * float(np.quantile(np.abs(w), 0.995)))
        model = _fit(X, y)
        scaler, ridge = model[0], model[-1]
        coef = ridge.coef_ / scaler.scale_      # the scaler folded in: one product a row
        tau = max(_efolding(df[s].to_numpy(float)) for df in frames)
        out[s] = (coef, float(ridge.intercept_ - coef @ scaler.mean_), band,
                  max(WINDOW, int(np.ceil(tau / SPAN_SHARE))), r2)
    return out


def _fit(X: np.ndarray, y: np.ndarray):
    return make_pipeline(StandardScaler(), RidgeCV(alphas=ALPHAS)).fit(X, y)


def _cv_residual(X: np.ndarray, y: np.ndarray, lengths: Sequence[int],
                 blocks: int = BLOCKS) -> np.ndarray:
    """Out-of-fold residual: one campaign out where there are >= 3 (``lengths``: their rows),
    else ``blocks`` contiguous blocks."""
    if len(lengths) >= 3:
        groups = np.concatenate([np.full(m, k) for k, m in enumerate(lengths)])
    else:
        groups = np.minimum(np.arange(len(y)) * blocks // len(y), blocks - 1)
    out = np.empty_like(y)
    for g in np.unique(groups):
        held = groups == g
        out[held] = y[held] - _fit(X[~held], y[~held]).predict(X[held])
    return out
