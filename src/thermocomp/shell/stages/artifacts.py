"""Files that the ``denoise`` and ``select`` stages hand to ``train``: ``data.processed`` (the
ingested dataset with the declared inputs denoised offline, ``denoiser.pkl``, ``denoise.json``)
and ``selection.json`` next to the model, each with the fingerprint of the config it was made
with; ``train`` uses one only when it matches (:mod:`thermocomp.core.io.handoff`).
"""

from __future__ import annotations

from pathlib import Path

from omegaconf import DictConfig

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
from ..chain import fit_chain, handed_denoised
from ..fingerprint import DENOISE_KEYS, SELECT_KEYS, fingerprint
from ..source import declared_columns

__all__ = ["DENOISER_PKL", "DENOISE_JSON", "denoise_fingerprint", "fit_from_artifacts", "processed_data",
           "selection_fingerprint", "selection_path"]   # denoise and select read these here


def denoise_fingerprint(cfg: DictConfig, ds) -> dict:
    """What ``data.processed`` is made from: the ingest ``ds`` and the denoise settings."""
    return fingerprint(ds.meta["digest"], cfg, DENOISE_KEYS)


def selection_fingerprint(cfg: DictConfig, ds) -> dict:
    """What ``selection.json`` is made from: the ingest ``ds``, the denoise and select settings."""
    return fingerprint(ds.meta["digest"], cfg, SELECT_KEYS)


def selection_path(cfg: DictConfig) -> Path:
    """``selection.json`` sits next to the model file (``models/<name>/``)."""
    return resolve(cfg.model_path).parent / SELECTION_JSON


def processed_data(cfg: DictConfig, ds):
    """``(dataset, fitted denoiser or None)`` from ``data.processed`` if it was made from the
    ingest ``ds`` with this config."""
    return matching_processed(resolve(cfg.data.processed), lambda: denoise_fingerprint(cfg, ds))


def fit_from_artifacts(cfg: DictConfig, ds) -> Compensator:
    """Fit the configured compensator on the train split (:func:`~.chain.fit_chain`), reusing
    ``denoise``/``select`` outputs.

    ``ds`` is the ingested dataset (``data.interim``).  With a matching
    ``data.processed`` the fitted denoiser is used as fitted (frozen); with a
    matching ``selection.json`` the stored inputs.
    """
    processed = processed_data(cfg, ds)
    selected = matching_selection(selection_path(cfg), lambda: selection_fingerprint(cfg, ds),
                                  declared_columns(cfg, ds)[1])
    say(f"fitting {cfg.model.name} on {len(require_split(ds, 'train'))} train campaigns "
        f"(denoiser: {'fitted by the denoise stage' if processed is not None else 'as configured'}; "
        f"selection: {'selection.json' if selected is not None else cfg.select.name})")
    return fit_chain(cfg, ds, None if processed is None else handed_denoised(cfg, ds, processed),
                     selected)
