"""`thermocomp ingest`: validate a dataset folder, write Parquet + report to data.interim.

A volumetric dataset (``volumetric.json`` in ``data.path``) is opened through its adapter
(:func:`~thermocomp.shell.source.open_source`: calibrated as ``thermocomp calibrate`` does):
``data.interim`` then holds its error parameter series (one ``E_`` column per identified
parameter), which ``denoise`` .. ``train`` model like any dataset and ``evaluate`` validates
against the distances (the ``volumetric`` section).  Another folder is validated and written a
campaign at a time (:func:`thermocomp.core.io.ingest`: peak memory one campaign).
"""

from __future__ import annotations

from omegaconf import DictConfig

from ...apps.volumetric.source import ingest_series
from ...base.files import check_replaceable
from ...base.log import say
from ...base.paths import resolve
from ...core import io
from ..config.checks import check_config
from ..source import data_options, ingest_fingerprint, is_volumetric, open_source, resolve_reference
from ..tracking import stage_run


def ingest(cfg: DictConfig) -> dict:
    """Validate ``data.path`` and write it as Parquet to ``data.interim`` with a report."""
    check_config(cfg, outputs=("data.interim",))   # data.path: always an input
    src, dest = resolve(cfg.data.path), resolve(cfg.data.interim)
    check_replaceable(dest, io.INGEST_REPORT, "data.interim")
    say(f"ingesting {src} -> {dest}")
    made = {"ingested_with": ingest_fingerprint(cfg)}     # what train .. evaluate check

    def finish(ds) -> dict:     # as run's ingest_report.json records it
        return {"reference": resolve_reference(cfg, ds)}

    if is_volumetric(cfg):
        report = ingest_series(open_source(cfg), dest, made, finish)
    else:
        report = io.ingest(src, dest, data_options(cfg), extra=made, finish=finish)
    say(f"{report['rows']} rows in {len(report['campaigns'])} campaigns; "
        f"repairs: {report['repairs'] or 'none'}")
    with stage_run(cfg, "ingest") as tr:
        tr.log_metrics({"rows": report["rows"], "campaigns": len(report["campaigns"])})
        tr.log_artifact(dest / "ingest_report.json")
    return report

