"""Headline numbers for ``dvc metrics show`` / ``dvc exp show``: a handful per target.

The full ``metrics.json`` / ``diagnosis.json`` (the CLI contract) hold hundreds of
numbers; DVC tabulates every one of them.  A stage therefore also writes one
small flat file per target, ``<out>/headline/<target>.json`` (``evaluate``,
``run``) and ``<out>/diagnosis_headline/<target>.json`` (``diagnose``), which
``dvc.yaml`` lists as ``metrics``: one row per target, a few columns.
"""

from __future__ import annotations

from pathlib import Path

from ...base.files import atomic_dir, write_json
from .results import TEST_RMSE

HEADLINE, DIAGNOSIS_HEADLINE = "headline", "diagnosis_headline"


def diagnosis_headline(diagnoses: dict) -> dict:
    """``{target: {test_before, test_after, cv_before, cv_after}}``: the test and CV RMSE (µm)
    before and after the diagnosis, from the ``diagnosis.json`` document of each target (short
    names: ``dvc metrics show`` puts every file's columns side by side)."""
    return {t: {"test_before": d["before"][TEST_RMSE], "test_after": d["after"][TEST_RMSE],
                "cv_before": d["before"]["cv_rmse"], "cv_after": d["after"]["cv_rmse"]}
            for t, d in diagnoses.items()}


def write_headline(folder, per_target: dict) -> Path:
    """Replace ``folder`` by one ``<target>.json`` per target, atomically; returns ``folder``."""
    folder = Path(folder)
    with atomic_dir(folder) as tmp:
        for t, numbers in per_target.items():
            write_json(tmp / f"{t}.json", numbers)
    return folder
