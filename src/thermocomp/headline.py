"""Headline numbers for ``dvc metrics show`` / ``dvc exp show``: a handful per target.

The full ``metrics.json`` / ``diagnosis.json`` (the CLI contract) hold hundreds of
numbers; DVC tabulates every one of them.  A stage therefore also writes one
small flat file per target, ``<out>/headline/<target>.json`` (``evaluate``,
``run``) and ``<out>/diagnosis_headline/<target>.json`` (``diagnose``), which
``dvc.yaml`` lists as ``metrics``: one row per target, a few columns.
"""

from __future__ import annotations

from pathlib import Path

from .files import atomic_dir, write_json
from .metrics import reduction_pct

HEADLINE, DIAGNOSIS_HEADLINE = "headline", "diagnosis_headline"


def evaluation_headline(metrics: dict) -> dict:
    """``{target: {test_rmse, test_rsd_mean, test_rsd_sd, rms_reduction_pct, val_rmse}}``
    from a ``metrics.json`` document (``val_rmse`` null without validation), plus
    ``volumetric`` (distance and VCE RMS, A.3 range, before/after) for a volumetric run."""
    out = {}
    for t, m in metrics["targets"].items():
        te = m["test"]
        out[t] = {"test_rmse": te["rmse"], "test_rsd_mean": te["rsd_mean"], "test_rsd_sd": te["rsd_sd"],
                  "rms_reduction_pct": reduction_pct(te["rms_before"], te["rms_after"]),
                  "val_rmse": (m.get("validation") or {}).get("rmse")}
    vol = metrics.get("volumetric")
    if vol:  # a volumetric run: the twin's own figures (headline/volumetric.json)
        out["volumetric"] = {
            "distance_rms_before": vol["distance_error"]["rms_before"],
            "distance_rms_after": vol["distance_error"]["rms_after"],
            "vce_rms_before": vol["vce"]["rms_before"], "vce_rms_after": vol["vce"]["rms_after"],
            "iso_a3_range_before": vol["iso_a3"].get("range_before"),
            "iso_a3_range_after": vol["iso_a3"].get("range_after")}
    return out


def diagnosis_headline(diagnoses: dict) -> dict:
    """``{target: {test_before, test_after, cv_before, cv_after}}``: the test and CV RMSE (µm)
    before and after the diagnosis, from the ``diagnosis.json`` document of each target (short
    names: ``dvc metrics show`` puts every file's columns side by side)."""
    return {t: {"test_before": d["before"]["test_rmse"], "test_after": d["after"]["test_rmse"],
                "cv_before": d["before"]["cv_rmse"], "cv_after": d["after"]["cv_rmse"]}
            for t, d in diagnoses.items()}


def write_headline(folder, per_target: dict) -> Path:
    """Replace ``folder`` by one ``<target>.json`` per target, atomically; returns ``folder``."""
    folder = Path(folder)
    with atomic_dir(folder) as tmp:
        for t, numbers in per_target.items():
            write_json(tmp / f"{t}.json", numbers)
    return folder
