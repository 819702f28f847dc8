"""`thermocomp init <file-or-folder>`: what the reader detects in a lab's data, and the data
config that reads it (roles proposed from the units in the headers:
:mod:`thermocomp.core.io.detect`), written to ``<out>/conf/data/<name>.yaml`` with the command to
run next.  The data are read with it first: a config that would not read them is refused as
``run`` would refuse it.
"""

from __future__ import annotations

import yaml
from omegaconf import DictConfig, OmegaConf

from ...base.files import atomic_write_text
from ...base.paths import conf_dir, resolve
from ...core import io
from ...core.io.contract import TIME
from ...core.io.detect import (
    check_an_error_is_named,
    data_config,
    detection_lines,
    encoding,
    folder_manifest,
    head,
    proposed_campaign,
    proposed_roles,
    sample_file,
)
from ...core.io.roles import naming
from ...core.timerule import median_step
from ..config.checks import check_config, data_options
from ..source import check_declared, open_source


def init(cfg: DictConfig) -> dict:
    """Detect, propose, check by reading, write ``<out>/conf/data/<name>.yaml``; print the run
    command."""
    check_config(cfg)         # out never holds data.path: the lab's record is never written beside
    src = resolve(cfg.data.path)
    given = data_options(cfg)
    asked = io.ReadOptions.from_cfg(given)
    manifest = folder_manifest(src, asked)                  # a folder's, read once
    given["encoding"] = encoding(src, asked, manifest)      # a Windows export's
    sample = sample_file(src, manifest)
    opts, header, first, layout = head(sample, io.ReadOptions.from_cfg(given))
    roles = proposed_roles(header, dict(zip(header, first)), opts)
    check_an_error_is_named(header, dict(zip(header, first)), roles, opts, sample)
    roles = proposed_campaign(src, roles, opts)     # a long file's run-number column
    plan = naming(header, roles, opts.columns, dict(zip(header, first)), opts.decimal, sample,
                  opts.units)
    defaults = OmegaConf.to_container(OmegaConf.load(conf_dir() / "data" / "default.yaml"))
    config = data_config(src, given, opts, roles, defaults, manifest)
    ds = open_source(cfg, detected=config)      # refused here as `run` would refuse it
    check_declared(cfg, ds, model=False)        # (a folder's run with a sensor the others lack)
    report = ds.meta["read_report"]
    path = resolve(cfg.out) / "conf" / "data" / f"{ds.name}.yaml"
    text = yaml.safe_dump({"defaults": ["default"], **config}, allow_unicode=True, sort_keys=False)
    atomic_write_text(path, f"# written by `thermocomp init {src}`\n{text}")
    period = median_step([df[TIME].to_numpy(float) for df in ds.campaigns.values()]) or float("nan")
    print("\n".join(detection_lines(layout, opts, header, plan, ds, report, period, path, ds.name)))
    return {"config": str(path), "columns": plan.names}
