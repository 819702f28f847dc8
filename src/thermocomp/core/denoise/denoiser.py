"""EMD denoising of input sensors as a scikit-learn transformer with a causal twin."""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
from sklearn.base import BaseEstimator, TransformerMixin
from sklearn.utils.validation import check_is_fitted, validate_data

from ...base.errors import ContractError, ParameterError
from ...base.params import BOOLEAN, POSITIVE, check_estimator, choice, integer, texts
from ..io.contract import match_columns
from .causal import apply_fir, fit_fir, sliding_window
from .emd import END_EFFECTS, SPLINES, STOPPING, decompose, emd_engine, leading_imfs, remove_imfs

MAX_IMFS = 32      # ~log2 of the longest signal EMD could decompose here

CAUSAL = ("fir", "window")


def _segments(n: int, groups) -> list[np.ndarray]:
    """Row indices of each group (campaign) in order of appearance; rows are time-ordered."""
    if groups is None:
        return [np.arange(n)]
    groups = np.asarray(groups)
    if len(groups) != n:
        raise ValueError(f"groups has {len(groups)} entries for {n} rows")
    _, first, inverse = np.unique(groups, return_index=True, return_inverse=True)
    return [np.flatnonzero(inverse == g) for g in np.argsort(first)]


class EMDDenoiser(TransformerMixin, BaseEstimator):
    r"""Remove the first IMFs of each input sensor (EMD denoising, paper 004 Sect. 2.1).

    .. math:: \tilde x(t) = x(t) - \sum_{i=1}^{k} c_i(t)

    where :math:`c_i` is the *i*-th intrinsic mode function of the sensor's
    record (per campaign), found by sifting (PyEMD).  IMF-1 holds the fastest
    oscillation -- measurement noise, air-conditioning cycling -- and the
    residue keeps the slow thermal trend the model needs.

    Offline EMD looks at future samples.  :meth:`transform` is the offline
    method (training, figures, the ``denoise`` stage); :meth:`transform_causal`
    and the streaming pair :meth:`stream_init` / :meth:`stream_step` use past
    samples only and are what a running machine computes.  Inside a
    :class:`~thermocomp.core.compensator.Compensator` the estimator is trained on
    offline-denoised inputs, and ``predict`` uses the causal filter when
    ``online=True`` (the default: the honest figure, identical to deployment).

    Parameters
    ----------
    n_imfs : int, default 1
        Number of leading IMFs removed (*k*).
    sensors : list of glob patterns, default ``("T_*",)``
        Columns that are denoised, among those given (the declared inputs);
        others (``S_door`` ...) pass through.  With an ndarray every column is
        denoised.
    stopping : {'fixed', 'sd', 's_number'}, default 'fixed'
        Sifting stopping rule (:func:`thermocomp.core.denoise.emd.emd_engine`).
    max_siftings : int, default 10
        Siftings per IMF for ``'fixed'``; upper bound for the other rules.
    s_number : int, default 4
        *S* of the S-number rule.
    sd_threshold : float, default 0.2
        Threshold of the ``'sd'`` rule.
    end_effect : {'mirror_pad', 'mirror_extrema'}, default 'mirror_pad'
        End handling: odd mirror extension of ``pad`` samples, or only
        PyEMD's mirrored outer extrema.
    pad : int, default 50
        Samples of mirror extension at each end.
    spline : str, default 'cubic'
        Envelope interpolation (PyEMD ``spline_kind``).
    causal : {'fir', 'window'}, default 'fir'
        Causal method (:mod:`thermocomp.core.denoise.causal`): a unit-gain FIR
        fitted to reproduce the offline result from past samples, or
        sliding-window EMD.
    causal_taps : int, default 16
        FIR length (samples).
    causal_window : int, default 64
        Window length (samples) of ``causal='window'``.
    online : bool, default True
        Whether a Compensator predicts with the causal filter (else offline).

    Attributes
    ----------
    n_features_in_ : int
    feature_names_in_ : ndarray of str (DataFrame input only)
    denoised_ : ndarray of bool, shape (n_features,)
        Which columns are denoised.
    fir_ : ndarray, shape (causal_taps, n_features)
        Causal FIR per column (identity for columns that are not denoised).
    """

    def __init__(self, n_imfs: int = 1, sensors=("T_*",), stopping: str = "fixed",
                 max_siftings: int = 10, s_number: int = 4, sd_threshold: float = 0.2,
                 end_effect: str = "mirror_pad", pad: int = 50, spline: str = "cubic",
                 causal: str = "fir", causal_taps: int = 16, causal_window: int = 64,
                 online: bool = True):
        self.n_imfs = n_imfs
        self.sensors = sensors
        self.stopping = stopping
        self.max_siftings = max_siftings
        self.s_number = s_number
        self.sd_threshold = sd_threshold
        self.end_effect = end_effect
        self.pad = pad
        self.spline = spline
        self.causal = causal
        self.causal_taps = causal_taps
        self.causal_window = causal_window
        self.online = online

    # -- offline -----------------------------------------------------------------------
    # EMD halves the extrema from one IMF to the next: a signal has at most ~log2(N) of them
    param_rules = {"n_imfs": integer(1, at_most=MAX_IMFS), "sensors": texts("column names or glob patterns"),
                   "stopping": choice(*STOPPING), "max_siftings": integer(1),
                   "s_number": integer(1), "sd_threshold": POSITIVE,
                   "end_effect": choice(*END_EFFECTS), "pad": integer(0),
                   "spline": choice(*SPLINES), "causal": choice(*CAUSAL),
                   "causal_taps": integer(1, at_most=4096), "causal_window": integer(4),
                   "online": BOOLEAN}

    def check_params(self) -> None:
        """Raise :class:`~thermocomp.base.errors.ParameterError` for a parameter outside its rule
        (before any data is read)."""
        check_estimator(self)

    def _engine(self):
        return emd_engine(self.stopping, self.max_siftings, self.s_number, self.sd_threshold,
                          self.spline)

    def _denoise_1d(self, x: np.ndarray) -> np.ndarray:
        return remove_imfs(x, int(self.n_imfs), self._engine(), self.end_effect, int(self.pad))

    def decompose(self, x, max_imfs: int = 5) -> np.ndarray:
        """IMFs (up to ``max_imfs``) and residue of one signal, with this denoiser's settings."""
        return decompose(x, max_imfs, self._engine(), self.end_effect, int(self.pad))

    def _offline(self, A: np.ndarray, groups, found: list | None = None) -> np.ndarray:
        """``A`` less the leading IMFs of each denoised column, per campaign; ``found`` gets
        ``(IMFs found, first row, column)`` of each signal."""
        out = A.copy()
        for rows in _segments(len(A), groups):
            for j in np.flatnonzero(self.denoised_):
                imfs = leading_imfs(A[rows, j], int(self.n_imfs), self._engine(), self.end_effect,
                                    int(self.pad))
                if imfs.size:
                    out[rows, j] = A[rows, j] - imfs.sum(axis=0)
                if found is not None:
                    found.append((len(imfs), np.arange(len(A))[rows][0], j))
        return out

    def _check_found(self, found: list, names, groups) -> None:
        """Asking more IMFs than a signal has removes all of them, its trend alone left: the
        model changed without a word (n_imfs=1000: test E_Z 5.80 -> 8.47 µm).  Refused when no
        signal has that many, said when some have fewer (a signal without any, monotone, keeps
        all of itself: nothing to say)."""
        n = int(self.n_imfs)
        if not found:
            return
        most = max(found)
        if 0 < most[0] < n:          # (none at all: nothing is removed, nothing lost)
            raise ParameterError(f"EMDDenoiser.n_imfs={n}: no input signal has that many IMFs (at "
                                 f"most {most[0]}: {self._signal(most, names, groups)}); every IMF "
                                 "would be removed, the trend alone left")
        short = [f for f in found if 0 < f[0] < n]
        if short:
            warnings.warn(f"EMDDenoiser.n_imfs={n}: {len(short)} of {len(found)} input signals have "
                          f"fewer IMFs ({self._signal(min(short), names, groups)}: {min(short)[0]}); "
                          "all of theirs are removed, their trend alone left", UserWarning,
                          stacklevel=3)

    @staticmethod
    def _signal(entry, names, groups) -> str:
        _, row, j = entry
        return (f"{names[j] if names is not None else f'column {j}'}"
                + (f" of campaign {np.asarray(groups)[row]}" if groups is not None else ""))

    def _wrap(self, X, values):
        if isinstance(X, pd.DataFrame):
            return pd.DataFrame(values, index=X.index, columns=X.columns)
        return values

    def fit(self, X, y=None, groups=None):
        """Choose the denoised columns and fit the causal FIRs (per campaign in ``groups``)."""
        self.fit_transform(X, y, groups=groups)
        return self

    def fit_transform(self, X, y=None, groups=None):
        """Fit and return the offline-denoised ``X`` (EMD runs once)."""
        self.check_params()
        A = validate_data(self, X, dtype=np.float64)
        names = getattr(self, "feature_names_in_", None)
        if names is None:
            self.denoised_ = np.ones(A.shape[1], dtype=bool)
        else:
            hits = set(match_columns(list(names), self.sensors))
            if not hits:   # a typo in the pattern would otherwise denoise nothing, silently
                raise ContractError(f"the denoiser's sensors {list(self.sensors)} match none of "
                                    f"the inputs {list(names)}", column=str(self.sensors[0]))
            self.denoised_ = np.array([n in hits for n in names], dtype=bool)
        found = []
        out = self._offline(A, groups, found)
        self._check_found(found, names, groups)
        taps = int(self.causal_taps)
        self.fir_ = np.zeros((taps, A.shape[1]))
        self.fir_[0] = 1.0
        segments = _segments(len(A), groups)
        for j in np.flatnonzero(self.denoised_):
            self.fir_[:, j] = fit_fir([A[r, j] for r in segments], [out[r, j] for r in segments],
                                      taps)
        return self._wrap(X, out)

    def transform(self, X, groups=None):
        """Offline EMD denoising (uses the whole record of each campaign)."""
        check_is_fitted(self)
        A = validate_data(self, X, dtype=np.float64, reset=False)
        return self._wrap(X, self._offline(A, groups))

    # -- causal ------------------------------------------------------------------------
    def transform_causal(self, X, groups=None):
        """Causal denoising: each output sample depends on past and present samples only.

        Equal (to rounding) to running :meth:`stream_step` over each campaign.
        """
        check_is_fitted(self)
        A = validate_data(self, X, dtype=np.float64, reset=False)
        out = A.copy()
        for rows in _segments(len(A), groups):
            for j in np.flatnonzero(self.denoised_):
                if self.causal == "fir":
                    out[rows, j] = apply_fir(A[rows, j], self.fir_[:, j])
                else:
                    out[rows, j] = sliding_window(A[rows, j], int(self.causal_window),
                                                  self._denoise_1d)
        return self._wrap(X, out)

    def stream_init(self):
        """State of the causal filter before the first sample of a campaign."""
        check_is_fitted(self)
        return None

    def stream_step(self, x_row, state):
        """Denoise one sample (values in the fitted column order) -> (row, state)."""
        x = np.asarray(x_row, dtype=float).reshape(-1)
        if x.shape[0] != self.n_features_in_:
            raise ValueError(f"x_row has {x.shape[0]} values, the denoiser was fitted on "
                             f"{self.n_features_in_} columns")
        if self.causal == "fir":
            buf = np.repeat(x[None, :], len(self.fir_), axis=0) if state is None else \
                np.vstack([x[None, :], state[:-1]])
            return (buf * self.fir_).sum(axis=0), buf
        buf = x[None, :] if state is None else np.vstack([state, x[None, :]])[-int(self.causal_window):]
        out = x.copy()
        for j in np.flatnonzero(self.denoised_):
            out[j] = self._denoise_1d(buf[:, j])[-1]
        return out, buf
