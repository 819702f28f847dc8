"""`thermocomp denoise`: denoise the declared inputs of the ingested data -> data.processed.

The denoiser is fitted on the train split (its causal filter learns from it);
every campaign is written denoised offline, so ``data.processed`` is a
complete dataset to inspect.  ``train`` reads its train campaigns and the
fitted denoiser (``denoiser.pkl``) instead of denoising again.  With
``denoise=none`` the data pass through unchanged.  Figures (under
``<out>/denoise``): raw vs denoised and the IMFs of the noisiest sensor.
"""

from __future__ import annotations

import shutil
import time

import numpy as np
from omegaconf import DictConfig

from ...base import signing
from ...base.files import atomic_dir, write_json
from ...base.log import say
from ...base.paths import resolve
from ...core.denoise import EMDDenoiser, denoise_campaigns, fit_denoiser
from ...core.frame import resolve_columns
from ...core.io.contract import MANIFEST
from ...core.io.read import INGEST_REPORT
from ...core.scoring.evaluation import require_split
from ..tracking import stage_run
from .artifacts import DENOISE_JSON, DENOISER_PKL, denoise_fingerprint
from .common import build_denoiser, check_config, check_replaceable, load_ingested


def _rms(a) -> float:
    a = np.asarray(a, float)
    return float(np.sqrt(np.mean(a * a))) if a.size else 0.0


def _removed_rms(raw: dict, den: dict, columns) -> dict:
    """RMS (°C) of what denoising removed, per sensor, pooled over campaigns."""
    return {c: _rms(np.concatenate([raw[k][c].to_numpy() - den[k][c].to_numpy() for k in raw]))
            for c in columns}


def denoise(cfg: DictConfig) -> dict:
    """Write the denoised dataset to ``data.processed`` and figures to ``<out>/denoise``."""
    check_config(cfg, outputs=("out", "data.processed"), inputs=("data.interim",))
    check_replaceable(cfg, "data.processed", DENOISE_JSON)
    src, dest = resolve(cfg.data.interim), resolve(cfg.data.processed)
    ds = load_ingested(cfg)
    inputs, _ = resolve_columns(ds.columns, list(cfg.data.inputs), None)
    denoiser = build_denoiser(cfg)
    ids = require_split(ds, "train")
    train = {c: ds.campaigns[c] for c in ids}
    others = {c: df for c, df in ds.campaigns.items() if c not in train}
    t0 = time.perf_counter()
    fitted, train_out = fit_denoiser(denoiser, train, inputs)
    out = {**train_out, **denoise_campaigns(fitted, others, causal=False)}
    seconds = time.perf_counter() - t0
    report = {"denoiser": cfg.denoise.name, "fingerprint": denoise_fingerprint(cfg),
              "inputs": inputs, "seconds": seconds}
    if fitted is not None:
        causal = denoise_campaigns(fitted, train, causal=True)
        cols = [c for c, d in zip(fitted.feature_names_in_, fitted.denoised_) if d]
        report["denoised"] = cols
        report["removed_rms_c"] = _removed_rms(train, train_out, cols)
        report["causal_vs_offline_rms_c"] = _removed_rms(causal, train_out, cols)
        say(f"{cfg.denoise.name}: {len(cols)} sensors x {len(ds.campaigns)} campaigns "
            f"denoised in {seconds:.1f} s")
    else:
        say("denoise=none: inputs pass through")
    with atomic_dir(dest) as tmp:
        for cid, df in ds.campaigns.items():
            out[cid].to_parquet(tmp / f"{cid}.parquet", index=False)
        for name in (MANIFEST, INGEST_REPORT):
            shutil.copy2(src / name, tmp / name)
        if fitted is not None:
            signing.dump(fitted, tmp / DENOISER_PKL)   # + denoiser.pkl.sig
        write_json(tmp / DENOISE_JSON, report)
    figures = resolve(cfg.out) / "denoise"
    with atomic_dir(figures) as tmp:      # plots=none: emptied, not an earlier run's figures
        if cfg.plots != "none":
            _figures(ds, train, fitted, inputs, tmp)
    with stage_run(cfg, "denoise") as tr:
        tr.log_metrics({"denoise_seconds": seconds,
                        "removed_rms_c": report.get("removed_rms_c", {}),
                        "causal_vs_offline_rms_c": report.get("causal_vs_offline_rms_c", {})})
        tr.log_artifact(dest / DENOISE_JSON)
        tr.log_artifacts(figures, "denoise")
    say(f"processed data: {dest}" + (f"; figures: {figures}" if cfg.plots != "none" else ""))
    return report


def _figures(ds, train: dict, fitted, inputs, folder) -> None:
    """Raw vs denoised and the IMFs of the noisiest T_ sensor in the longest train campaign."""
    from ...core.figures.plots import imf_plot, raw_vs_denoised_plot

    den = fitted if fitted is not None else EMDDenoiser().fit(
        next(iter(train.values()))[inputs])  # illustration of what denoise=emd would remove
    cols = [c for c, d in zip(den.feature_names_in_, den.denoised_) if d]
    if not cols:
        return
    cid = max(train, key=lambda c: len(train[c]))
    df = train[cid]
    offline = den.transform(df[inputs])
    causal = den.transform_causal(df[inputs])
    sensor = max(cols, key=lambda c: _rms(df[c].to_numpy() - offline[c].to_numpy()))
    hours = df["time"].to_numpy() / 3600.0
    raw_vs_denoised_plot(hours, df[sensor].to_numpy(), offline[sensor].to_numpy(),
                         causal[sensor].to_numpy(), sensor, cid,
                         folder / f"raw_vs_denoised_{cid}_{sensor}.png", applied=fitted is not None)
    imf_plot(hours, df[sensor].to_numpy(), den.decompose(df[sensor].to_numpy(), max_imfs=5), sensor,
             cid, folder / f"imfs_{cid}_{sensor}.png")
