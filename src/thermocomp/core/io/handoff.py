"""Files the ``denoise`` and ``select`` stages hand to ``train``, used only when the fingerprint
they record (the settings and data they were made from) is the one asked for: otherwise the
compensator denoises / selects itself -- the same computation, so ``thermocomp run`` and
``dvc repro`` give the same model and nothing is done twice on the DVC path."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

from sklearn.base import BaseEstimator

from ...base import signing
from ...base.log import say
from .read import load_interim

DENOISE_JSON = "denoise.json"
DENOISER_PKL = "denoiser.pkl"
SELECTION_JSON = "selection.json"


def matching_processed(root: Path, fingerprint: Callable[[], dict]):
    """``(dataset, fitted denoiser or None)`` of the processed folder ``root`` if it was made
    with ``fingerprint()`` (asked only when there is a folder), else None."""
    report = root / DENOISE_JSON
    if not report.is_file():
        return None
    if json.loads(report.read_text()).get("fingerprint") != fingerprint():
        say(f"{root} was made with other settings or data; ignoring it")
        return None
    den = None
    if (root / DENOISER_PKL).is_file():
        den = signing.load(root / DENOISER_PKL, BaseEstimator)   # signature checked first
    return load_interim(root), den


def matching_selection(path: Path, fingerprint: Callable[[], dict], targets=None) -> dict | None:
    """Selected inputs per target from ``selection.json`` at ``path`` if it was made with
    ``fingerprint()`` (asked only when there is one) for ``targets`` (None: any), else None."""
    if not path.is_file():
        return None
    stored = json.loads(path.read_text())
    if stored.get("fingerprint") != fingerprint():
        say(f"{path} was made with other settings or data; selecting again")
        return None
    selected = {t: entry["selected"] for t, entry in stored["targets"].items()}
    return None if targets is not None and sorted(selected) != sorted(targets) else selected
