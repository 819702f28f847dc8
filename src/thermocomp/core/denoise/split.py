"""A dataset's inputs denoised as the ``denoise`` stage writes them (pure core).

The denoiser is fitted on the train campaigns (its causal filter learns from them) and every
campaign is denoised offline; the report says what was removed (°C RMS per sensor) and how far
the causal filter a stream runs is from the offline one.
"""

from __future__ import annotations

import time

import numpy as np

from .campaigns import denoise_campaigns, fit_denoiser


def rms(a) -> float:
    a = np.asarray(a, float)
    return float(np.sqrt(np.mean(a * a))) if a.size else 0.0


def removed_rms(raw: dict, den: dict, columns) -> dict:
    """RMS (°C) of what denoising removed, per sensor, pooled over campaigns."""
    return {c: rms(np.concatenate([raw[k][c].to_numpy() - den[k][c].to_numpy() for k in raw]))
            for c in columns}


def denoise_split(denoiser, campaigns: dict, train_ids, inputs) -> tuple[object, dict, dict]:
    """``(fitted denoiser or None, every campaign denoised offline, report)`` of ``denoiser``
    fitted on ``train_ids``; the report's ``seconds``, and with a denoiser ``denoised``,
    ``removed_rms_c`` and ``causal_vs_offline_rms_c`` (``denoise.json``)."""
    train = {c: campaigns[c] for c in train_ids}
    others = {c: df for c, df in campaigns.items() if c not in train}
    t0 = time.perf_counter()
    fitted, train_out = fit_denoiser(denoiser, train, inputs)
    out = {**train_out, **denoise_campaigns(fitted, others, causal=False)}
    report = {"seconds": time.perf_counter() - t0}
    if fitted is not None:
        causal = denoise_campaigns(fitted, train, causal=True)
        cols = [c for c, d in zip(fitted.feature_names_in_, fitted.denoised_) if d]
        report.update(denoised=cols, removed_rms_c=removed_rms(train, train_out, cols),
                      causal_vs_offline_rms_c=removed_rms(causal, train_out, cols))
    return fitted, out, report
