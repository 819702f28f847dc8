"""`thermocomp ingest`: validate a dataset folder, write Parquet + report to data.interim."""

from __future__ import annotations

from omegaconf import DictConfig

from .. import io
from ..errors import ConfigError
from ..paths import resolve
from ..tracking import stage_run
from ..volumetric.artefact import SETUP_FILE
from .common import check_config, data_options, say


def ingest(cfg: DictConfig) -> dict:
    """Validate ``data.path`` and write it as Parquet to ``data.interim`` with a report."""
    check_config(cfg, outputs=("data.interim",))
    src, dest = resolve(cfg.data.path), resolve(cfg.data.interim)
    if (src / SETUP_FILE).is_file():
        # its targets are 1000+ distances: the separate stages would fit a model per distance
        raise ConfigError(f"{src} is a volumetric dataset ({SETUP_FILE}): `thermocomp run` calibrates "
                          "it and fits a thermal model per error parameter; `thermocomp calibrate` "
                          "writes the parameter series as a dataset the separate stages can read")
    say(f"ingesting {src} -> {dest}")
    report = io.ingest(src, dest, data_options(cfg))
    say(f"{report['rows']} rows in {len(report['campaigns'])} campaigns; "
        f"repairs: {report['repairs'] or 'none'}")
    with stage_run(cfg, "ingest") as tr:
        tr.log_metrics({"rows": report["rows"], "campaigns": len(report["campaigns"])})
        tr.log_artifact(dest / "ingest_report.json")
    return report
