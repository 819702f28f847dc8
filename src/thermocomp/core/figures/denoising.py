"""The ``denoise`` stage's figures: raw vs denoised and the IMFs of the noisiest sensor."""

from __future__ import annotations

from ..denoise import EMDDenoiser
from ..denoise.split import rms


def denoise_figures(train: dict, fitted, inputs, folder) -> None:
    """Raw vs denoised and the IMFs of the noisiest T_ sensor in the longest train campaign
    (``fitted=None``: what ``denoise=emd`` would remove, as an illustration)."""
    from .plots import imf_plot, raw_vs_denoised_plot

    den = fitted if fitted is not None else EMDDenoiser().fit(next(iter(train.values()))[inputs])
    cols = [c for c, d in zip(den.feature_names_in_, den.denoised_) if d]
    if not cols:
        return
    cid = max(train, key=lambda c: len(train[c]))
    df = train[cid]
    offline = den.transform(df[inputs])
    causal = den.transform_causal(df[inputs])
    sensor = max(cols, key=lambda c: rms(df[c].to_numpy() - offline[c].to_numpy()))
    hours = df["time"].to_numpy() / 3600.0
    raw_vs_denoised_plot(hours, df[sensor].to_numpy(), offline[sensor].to_numpy(),
                         causal[sensor].to_numpy(), sensor, cid,
                         folder / f"raw_vs_denoised_{cid}_{sensor}.png", applied=fitted is not None)
    imf_plot(hours, df[sensor].to_numpy(), den.decompose(df[sensor].to_numpy(), max_imfs=5), sensor,
             cid, folder / f"imfs_{cid}_{sensor}.png")
