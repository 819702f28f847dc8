"""Apply a denoiser to campaign frames (what the Compensator and the ``denoise`` stage share)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd
from sklearn.base import clone
from sklearn.frozen import FrozenEstimator
from sklearn.utils.validation import check_is_fitted


def _replaced(campaigns: Mapping[str, pd.DataFrame], columns, values: dict) -> dict:
    out = {}
    for cid, df in campaigns.items():
        df = df.copy()
        df[list(columns)] = np.asarray(values[cid], dtype=float)
        out[cid] = df
    return out


def fit_denoiser(denoiser, campaigns: Mapping[str, pd.DataFrame], columns, denoised: bool = False):
    """Fit ``denoiser`` on ``columns`` of the campaigns; return it and the denoised campaigns.

    Every campaign is one time series (groups).  A denoiser fitted elsewhere
    (the ``denoise`` stage) comes wrapped in :class:`sklearn.frozen.FrozenEstimator`:
    it is checked against ``columns`` and only applies its offline transform, or none when the
    campaigns are ``denoised`` by it already.  ``denoiser=None`` passes through.
    """
    columns = list(columns)
    if denoiser is None:
        return None, dict(campaigns)
    den = clone(denoiser)               # a FrozenEstimator clones to itself
    if denoised:
        if not isinstance(den, FrozenEstimator):
            raise ValueError("denoised campaigns need the denoiser that denoised them, frozen")
        return _prefitted(den.estimator, columns), dict(campaigns)
    X = pd.concat([df[columns] for df in campaigns.values()], ignore_index=True)
    groups = np.concatenate([np.full(len(df), cid, dtype=object) for cid, df in campaigns.items()])
    if isinstance(den, FrozenEstimator):
        den = _prefitted(den.estimator, columns)
        out = den.transform(X, groups=groups).to_numpy()
    else:
        out = den.fit_transform(X, groups=groups).to_numpy()
    return den, _replaced(campaigns, columns, {c: out[groups == c] for c in campaigns})


def _prefitted(den, columns: list):
    """``den`` (fitted elsewhere), checked to denoise ``columns``."""
    check_is_fitted(den)
    fitted = list(getattr(den, "feature_names_in_", []))
    if fitted != columns:
        raise ValueError(f"the prefitted denoiser was fitted on {fitted}, the model's inputs "
                         f"are {columns}")
    return den


def denoise_campaigns(denoiser, campaigns: Mapping[str, pd.DataFrame], causal: bool | None = None
                      ) -> dict:
    """Denoise the fitted columns of each campaign; ``causal=None`` follows ``denoiser.online``."""
    if denoiser is None:
        return dict(campaigns)
    causal = bool(getattr(denoiser, "online", True)) if causal is None else causal
    columns = list(denoiser.feature_names_in_)
    method = denoiser.transform_causal if causal else denoiser.transform
    return _replaced(campaigns, columns, {cid: method(df[columns]).to_numpy()
                                          for cid, df in campaigns.items()})
