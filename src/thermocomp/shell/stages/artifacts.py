"""Files that the ``denoise`` and ``select`` stages hand to ``train``: ``data.processed`` (the
ingested dataset with the declared inputs denoised offline, ``denoiser.pkl``, ``denoise.json``)
and ``selection.json`` next to the model, each with the fingerprint of the config it was made
with; ``train`` uses one only when it matches (:mod:`thermocomp.core.io.handoff`).
"""

from __future__ import annotations

import json
from pathlib import Path

from omegaconf import DictConfig, OmegaConf
from sklearn.frozen import FrozenEstimator

from ...base.files import folder_digest
from ...base.log import say
from ...base.paths import resolve
from ...core.compensator import Compensator
from ...core.io.handoff import (
    DENOISE_JSON,
    DENOISER_PKL,
    SELECTION_JSON,
    matching_processed,
    matching_selection,
)
from ...core.scoring.evaluation import require_split
from ..builders import build_compensator
from ..source import reference

__all__ = ["DENOISER_PKL", "DENOISE_JSON", "denoise_fingerprint", "fit_from_artifacts", "processed_data",
           "selection_fingerprint", "selection_path"]   # denoise and select read these here


def _plain(node) -> object:
    """Config node -> JSON-comparable plain data."""
    data = OmegaConf.to_container(node, resolve=True) if isinstance(node, DictConfig) else node
    return json.loads(json.dumps(data))


def denoise_fingerprint(cfg: DictConfig) -> dict:
    return {"denoise": _plain(cfg.denoise), "inputs": _plain(list(cfg.data.inputs)),
            "interim": folder_digest(resolve(cfg.data.interim))}


def selection_fingerprint(cfg: DictConfig) -> dict:
    targets = None if cfg.data.targets is None else _plain(list(cfg.data.targets))
    return {"select": _plain(cfg.select), "targets": targets, "reference": reference(cfg),
            **denoise_fingerprint(cfg)}


def selection_path(cfg: DictConfig) -> Path:
    """``selection.json`` sits next to the model file (``models/<name>/``)."""
    return resolve(cfg.model_path).parent / SELECTION_JSON


def processed_data(cfg: DictConfig):
    """``(dataset, fitted denoiser or None)`` from ``data.processed`` if it matches the config."""
    return matching_processed(resolve(cfg.data.processed), lambda: denoise_fingerprint(cfg))


def fit_from_artifacts(cfg: DictConfig, ds) -> Compensator:
    """Fit the configured compensator on the train split, reusing ``denoise``/``select`` outputs.

    ``ds`` is the ingested dataset (``data.interim``).  With a matching
    ``data.processed`` the fitted denoiser is used as fitted (frozen); with a
    matching ``selection.json`` the stored inputs.
    """
    comp = build_compensator(cfg, ds=ds)
    ids = require_split(ds, "train")
    processed = processed_data(cfg)
    den = processed[1] if processed is not None else None
    if den is not None:
        comp.set_params(denoiser=FrozenEstimator(den))
    selected = matching_selection(selection_path(cfg), lambda: selection_fingerprint(cfg), comp.targets)
    comp.set_params(selection=selected)
    say(f"fitting {cfg.model.name} on {len(ids)} train campaigns "
        f"(denoiser: {'fitted by the denoise stage' if den is not None else 'as configured'}; "
        f"selection: {'selection.json' if selected is not None else cfg.select.name})")
    return comp.fit({c: ds.campaigns[c] for c in ids})
