"""`thermocomp ingest`: validate a dataset folder, write Parquet + report to data.interim.

A volumetric dataset (``volumetric.json`` in ``data.path``) is calibrated first, as
``thermocomp calibrate`` does: ``data.interim`` then holds its error parameter series (one
``E_`` column per identified parameter), which ``denoise`` .. ``train`` model like any dataset
and ``evaluate`` validates against the distances (the ``volumetric`` section).
"""

from __future__ import annotations

import tempfile

from omegaconf import DictConfig

from ...base.log import say
from ...base.paths import resolve
from ...core import io
from ..tracking import stage_run
from .common import (
    check_config,
    check_replaceable,
    data_options,
    ingest_settings,
    resolve_reference,
    volumetric_calibration,
)


def ingest(cfg: DictConfig) -> dict:
    """Validate ``data.path`` and write it as Parquet to ``data.interim`` with a report."""
    check_config(cfg, outputs=("data.interim",))   # data.path: always an input
    check_replaceable(cfg, "data.interim", io.INGEST_REPORT)
    src, dest = resolve(cfg.data.path), resolve(cfg.data.interim)
    say(f"ingesting {src} -> {dest}")
    volumetric = volumetric_calibration(cfg)
    made = {"ingested_with": ingest_settings(cfg)}     # what train .. evaluate check

    def finish(ds) -> dict:     # as run's ingest_report.json records it
        return {"reference": resolve_reference(cfg, ds)}

    if volumetric is None:
        report = io.ingest(src, dest, data_options(cfg), extra=made, finish=finish)
    else:
        report = _parameters(volumetric, dest, made, finish)
    say(f"{report['rows']} rows in {len(report['campaigns'])} campaigns; "
        f"repairs: {report['repairs'] or 'none'}")
    with stage_run(cfg, "ingest") as tr:
        tr.log_metrics({"rows": report["rows"], "campaigns": len(report["campaigns"])})
        tr.log_artifact(dest / "ingest_report.json")
    return report


def _parameters(volumetric, dest, made: dict, finish) -> dict:
    """The parameter series of a calibrated volumetric dataset, ingested as a dataset of its own."""
    params, _, calibration, raw = volumetric
    # written, then read back through the one validating reader (the splits and names are
    # already the configured ones: no data.* option applies twice)
    with tempfile.TemporaryDirectory(prefix="thermocomp-params-") as tmp:
        folder = io.write_dataset(params, f"{tmp}/{raw.name or 'parameters'}", "parquet")
        # the temperatures' repairs were made reading the distances' dataset, not this one
        return io.ingest(folder, dest, extra={"calibration": calibration,
                                              "repairs": calibration["repairs"], **made},
                         finish=finish)
