"""Files that the ``denoise`` and ``select`` stages hand to ``train``.

``denoise`` writes ``data.processed``: the ingested dataset with the declared
inputs denoised offline (a contract folder of Parquet files that
``io.load_interim`` reads), the fitted denoiser (``denoiser.pkl``) and
``denoise.json``.  ``select`` writes ``selection.json`` next to the model.
Each file records a fingerprint of the settings and data it was made from;
``train`` uses a file only when the fingerprint matches its own config, and
otherwise lets the Compensator denoise / select itself -- the same
computation, so ``thermocomp run`` and ``dvc repro`` give the same model and
nothing is done twice on the DVC path.
"""

from __future__ import annotations

import json
from pathlib import Path

from omegaconf import DictConfig, OmegaConf
from sklearn.base import BaseEstimator
from sklearn.frozen import FrozenEstimator

from ...base import signing
from ...base.files import folder_digest
from ...base.log import say
from ...base.paths import resolve
from ...core import io
from ...core.compensator import Compensator
from ...core.scoring.evaluation import require_split
from ..source import reference
from .builders import build_compensator

DENOISE_JSON = "denoise.json"
DENOISER_PKL = "denoiser.pkl"
SELECTION_JSON = "selection.json"


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
    root = resolve(cfg.data.processed)
    report = root / DENOISE_JSON
    if not report.is_file():
        return None
    if json.loads(report.read_text()).get("fingerprint") != denoise_fingerprint(cfg):
        say(f"{root} was made with other settings or data; ignoring it")
        return None
    den = None
    if (root / DENOISER_PKL).is_file():
        den = signing.load(root / DENOISER_PKL, BaseEstimator)   # signature checked first
    return io.load_interim(root), den


def stored_selection(cfg: DictConfig) -> dict | None:
    """Selected inputs per target from ``selection.json`` if it matches the config."""
    path = selection_path(cfg)
    if not path.is_file():
        return None
    stored = json.loads(path.read_text())
    if stored.get("fingerprint") != selection_fingerprint(cfg):
        say(f"{path} was made with other settings or data; selecting again")
        return None
    return {t: entry["selected"] for t, entry in stored["targets"].items()}


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
    selected = stored_selection(cfg)
    if selected is not None and comp.targets is not None and sorted(selected) != sorted(comp.targets):
        selected = None
    comp.set_params(selection=selected)
    say(f"fitting {cfg.model.name} on {len(ids)} train campaigns "
        f"(denoiser: {'fitted by the denoise stage' if den is not None else 'as configured'}; "
        f"selection: {'selection.json' if selected is not None else cfg.select.name})")
    return comp.fit({c: ds.campaigns[c] for c in ids})
