"""`thermocomp ingest`: validate a dataset folder, write Parquet + report to data.interim."""

from __future__ import annotations

from omegaconf import DictConfig

from .. import io
from ..paths import resolve
from ..tracking import stage_run
from .common import check_config, data_options, say


def ingest(cfg: DictConfig) -> dict:
    """Validate ``data.path`` and write it as Parquet to ``data.interim`` with a report."""
    check_config(cfg, outputs=("data.interim",))
    src, dest = resolve(cfg.data.path), resolve(cfg.data.interim)
    say(f"ingesting {src} -> {dest}")
    report = io.ingest(src, dest, data_options(cfg))
    say(f"{report['rows']} rows in {len(report['campaigns'])} campaigns; "
        f"repairs: {report['repairs'] or 'none'}")
    with stage_run(cfg, "ingest") as tr:
        tr.log_metrics({"rows": report["rows"], "campaigns": len(report["campaigns"])})
        tr.log_artifact(dest / "ingest_report.json")
    return report
