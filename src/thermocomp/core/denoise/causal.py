"""Causal counterparts of offline EMD denoising (only past samples are used).

Two ways, both reproducible sample by sample through the streaming protocol:

* ``fir`` -- a causal FIR filter per sensor, fitted by least squares so that
  filtering the raw training signal reproduces its offline EMD-denoised
  version as well as any filter of ``taps`` past samples can (a Wiener
  filter).  Its DC gain is constrained to one, so a constant offset passes
  unchanged and the slow trend is only delayed by the filter's small group
  delay.  Cheap: one dot product per sensor and sample.
* ``window`` -- sliding-window EMD: at each sample, denoise the last
  ``window`` raw samples offline and keep the newest value.  The newest value
  is where the EMD end effect is worst, so it is noisier than ``fir``; it
  costs one EMD per sensor and sample.

Written by hand: least squares for the FIR weights (numpy), applied with
``scipy.signal.lfilter``; no library offers a causal stand-in for EMD.
"""

from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view


def lagged(x: np.ndarray, taps: int) -> np.ndarray:
    """Rows ``[x(t), x(t-1), ..., x(t-taps+1)]``; samples before the start repeat ``x(0)``."""
    xp = np.concatenate([np.full(taps - 1, x[0]), x])
    return sliding_window_view(xp, taps)[:, ::-1]


def fit_fir(raw_segments, target_segments, taps: int) -> np.ndarray:
    """Unit-DC-gain causal FIR ``h`` (length ``taps``) with ``lfilter(h, raw) ≈ target``.

    Segments (campaigns) are filtered separately, each starting from its first
    sample.  With ``h[0] = 1 - sum(h[1:])`` the fit is an unconstrained least
    squares of ``target(t) - x(t)`` on ``x(t-j) - x(t)``, ``j = 1..taps-1``,
    over the samples with a full history (the first ``taps - 1`` of a segment
    would only teach the artificial start-up padding).
    """
    if taps == 1:
        return np.ones(1)
    A, b = [], []
    for x, d in zip(raw_segments, target_segments):
        L = lagged(np.asarray(x, float), taps)[taps - 1:]
        A.append(L[:, 1:] - L[:, :1])
        b.append(np.asarray(d, float)[taps - 1:] - L[:, 0])
    A, b = np.concatenate(A), np.concatenate(b)
    # normal equations (taps x taps): an SVD of the tall matrix cost as much as the EMD itself
    rest = np.linalg.lstsq(A.T @ A, A.T @ b, rcond=None)[0] if np.any(A) else np.zeros(taps - 1)
    return np.concatenate([[1.0 - rest.sum()], rest])


def apply_fir(x: np.ndarray, h: np.ndarray) -> np.ndarray:
    """Causal filtering of one segment, started as if ``x(0)`` had always been there."""
    from scipy.signal import lfilter  # lazily: scipy.signal is slow to import

    x = np.asarray(x, float)
    if len(h) == 1:
        return h[0] * x
    xp = np.concatenate([np.full(len(h) - 1, x[0]), x])
    return lfilter(h, [1.0], xp)[len(h) - 1:]


def sliding_window(x: np.ndarray, window: int, denoise_window) -> np.ndarray:
    """Newest value of ``denoise_window(last window samples)`` at every sample."""
    x = np.asarray(x, float)
    out = np.empty_like(x)
    for t in range(len(x)):
        out[t] = denoise_window(x[max(0, t + 1 - window): t + 1])[-1]
    return out
