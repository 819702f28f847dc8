"""`thermocomp denoise`: denoise the declared inputs of the ingested data -> data.processed.

The denoiser is fitted on the train split (its causal filter learns from it); every campaign
is written denoised offline (:func:`thermocomp.core.denoise.split.denoise_split`), so
``data.processed`` is a complete dataset to inspect.  ``train`` reads its train campaigns and
the fitted denoiser (``denoiser.pkl``) instead of denoising again.  With ``denoise=none`` the
data pass through unchanged.  Figures (under ``<out>/denoise``): raw vs denoised and the IMFs
of the noisiest sensor.
"""

from __future__ import annotations

import shutil

from omegaconf import DictConfig

from ...base import signing
from ...base.files import atomic_dir, check_replaceable, write_json
from ...base.log import say
from ...base.paths import resolve
from ...core.io.contract import MANIFEST
from ...core.io.read import INGEST_REPORT
from ..chain import denoise_step
from ..config.checks import check_config
from ..source import open_source
from ..tracking import stage_run
from .artifacts import DENOISE_JSON, DENOISER_PKL, denoise_fingerprint


def denoise(cfg: DictConfig) -> dict:
    """Write the denoised dataset to ``data.processed`` and figures to ``<out>/denoise``."""
    check_config(cfg, outputs=("out", "data.processed"), inputs=("data.interim",))
    src, dest = resolve(cfg.data.interim), resolve(cfg.data.processed)
    check_replaceable(dest, DENOISE_JSON, "data.processed")
    ds = open_source(cfg, ingested=True)
    step = denoise_step(cfg, ds, every=True)
    fitted, out, made, inputs = step.fitted, step.campaigns, step.report, step.inputs
    report = {"denoiser": cfg.denoise.name, "fingerprint": denoise_fingerprint(cfg, ds),
              "inputs": inputs, **made}
    say(f"{cfg.denoise.name}: {len(made['denoised'])} sensors x {len(ds.campaigns)} campaigns "
        f"denoised in {made['seconds']:.1f} s" if fitted is not None else
        "denoise=none: inputs pass through")
    with atomic_dir(dest) as tmp:
        for cid in ds.campaigns:
            out[cid].to_parquet(tmp / f"{cid}.parquet", index=False)
        for name in (MANIFEST, INGEST_REPORT):
            shutil.copy2(src / name, tmp / name)
        if fitted is not None:
            signing.dump(fitted, tmp / DENOISER_PKL)   # + denoiser.pkl.sig
        write_json(tmp / DENOISE_JSON, report)
    figures = resolve(cfg.out) / "denoise"
    with atomic_dir(figures) as tmp:      # plots=none: emptied, not an earlier run's figures
        if cfg.plots != "none":
            from ...core.figures.denoising import denoise_figures

            denoise_figures({c: ds.campaigns[c] for c in ds.ids("train")}, fitted, inputs, tmp)
    with stage_run(cfg, "denoise") as tr:
        tr.log_metrics({"denoise_seconds": made["seconds"],
                        **{k: made.get(k, {}) for k in ("removed_rms_c", "causal_vs_offline_rms_c")}})
        tr.log_artifact(dest / DENOISE_JSON)
        tr.log_artifacts(figures, "denoise")
    say(f"processed data: {dest}" + (f"; figures: {figures}" if cfg.plots != "none" else ""))
    return report
