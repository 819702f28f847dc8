"""`thermocomp init <file-or-folder>`: what the reader detects in a lab's data, and the data
config that reads it, written to ``<out>/conf/data/<name>.yaml`` with the command to run next.

Roles not given (``data.roles.*``) are proposed from the units in the headers (µm/mm: an error,
°C/K/°F: a temperature, rpm, %, ...: a state); a text column is proposed ``ignore``.  The data are
read with the proposed config before anything is written, so a config that would not read them
(no time column and no ``data.sample_period_s``, ...) is refused as ``run`` would refuse it.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import yaml
from omegaconf import DictConfig, OmegaConf

from ...base.files import atomic_write_text
from ...base.paths import conf_dir, resolve
from ...core import io
from ...core.continuation import campaign_period
from ...core.io.options import ROLE_PATTERNS
from ...core.io.roles import UNITS, _numeric, naming, split_unit
from ...core.io.sniff import resolved
from ...core.io.tables import _peek_csv
from .common import check_config, data_options

# units that say "a machine state" (speeds, loads, positions, on/off)
STATE_UNITS = {"rpm", "1/min", "min-1", "u/min", "%", "hz", "a", "w", "kw", "nm", "bar", "v",
               "on/off", "0/1", "mm/min"}
_GLOB = re.compile(r"([*?\[])")
_WHERE = ("interim", "processed")     # where stages write: the project's, not the data's


def init(cfg: DictConfig) -> dict:
    """Detect, propose, check by reading, write ``<out>/conf/data/<name>.yaml``; print the run
    command."""
    check_config(cfg)         # out never holds data.path: the lab's record is never written beside
    src = resolve(cfg.data.path)
    given = data_options(cfg)
    sample = _sample_file(src, io.ReadOptions.from_cfg(given))
    opts = resolved(sample, io.ReadOptions.from_cfg(given)) if sample.suffix.lower() == ".csv" \
        else io.ReadOptions.from_cfg(given)
    header, first = _peek_csv(sample, opts.delimiter) if sample.suffix.lower() == ".csv" \
        else _parquet_head(sample)
    roles = _proposed_roles(header, dict(zip(header, first)), opts)
    plan = naming(header, roles, opts.columns, dict(zip(header, first)), opts.decimal, sample)
    config = _config(src, given, opts, roles)
    ds, report = io.read_dataset(src, config)           # refused here as `run` would refuse it
    name = ds.name
    path = resolve(cfg.out) / "conf" / "data" / f"{name}.yaml"
    text = yaml.safe_dump({"defaults": ["default"], **config}, allow_unicode=True, sort_keys=False)
    atomic_write_text(path, f"# written by `thermocomp init {src}`\n{text}")
    _print(sample, opts, header, plan, ds, report, path, name)
    return {"config": str(path), "columns": plan.names}


def _sample_file(src: Path, opts) -> Path:
    """The file whose header is shown: the record itself, or a folder's first campaign."""
    if src.is_file():
        return src
    manifest = io.read_manifest(src, opts)
    return src / manifest["file"].iloc[0]


def _parquet_head(path: Path) -> tuple[list[str], list[str]]:
    import pyarrow.parquet as pq

    table = pq.read_table(path).slice(0, 1)
    return table.column_names, [str(v[0].as_py()) for v in table.columns]


def _proposed_roles(header: list[str], first: dict, opts) -> dict:
    """``data.roles`` as given, else patterns proposed from the headers' units."""
    roles = {k: list(opts.roles.get(k, [])) for k in ROLE_PATTERNS}
    roles["time"] = opts.roles.get("time", "auto")
    if any(roles[k] for k in ROLE_PATTERNS):
        return roles
    for h in header:
        base, unit = split_unit(h)
        unit = (unit or "").lower().replace(" ", "")
        pattern = _GLOB.sub(r"[\1]", base)
        if unit in UNITS["E"]:
            roles["error"].append(pattern)
        elif unit in STATE_UNITS:
            roles["state"].append(pattern)
        elif not _numeric(first.get(h), opts.decimal) and not re.match(r"\d{4}-\d\d-\d\d", str(first.get(h))):
            roles["ignore"].append(pattern)
    return roles


def _config(src: Path, given: dict, opts, roles: dict) -> dict:
    config = {"path": str(src), "delimiter": opts.delimiter, "decimal": opts.decimal,
              "roles": roles}
    # every other key the user set (data.thousands, data.time, ...): what reads the data
    defaults = OmegaConf.to_container(OmegaConf.load(conf_dir() / "data" / "default.yaml"))
    for key, value in given.items():
        if key not in config and key not in _WHERE and key in defaults and value != defaults[key]:
            config[key] = value
    if src.is_file() and given.get("test_fraction") is None:
        config["test_fraction"] = 0.1        # one record: its last tenth is the test campaign
    return config


def _print(sample, opts, header, plan, ds, report, path, name) -> None:
    print(f"{sample.name}: delimiter {opts.delimiter!r}, decimal {opts.decimal!r}")
    times = [h for h, n in plan.names.items() if n == "time"]
    periods = [campaign_period(df) for df in ds.campaigns.values() if len(df) > 1]
    print(f"time: {times[0]!r}" if times else "time: none in the file, data.sample_period_s rows apart")
    print(f"sample period: {np.median(periods):g} s, {report['rows']} rows")
    width = max(len(h) for h in header)
    for h in header:
        contract = plan.names.get(h)
        role = plan.roles.get(h, "ignore") if contract else "ignore (left out)"
        print(f"  {h:<{width}}  {role:<12} {contract or '-'}")
    for cid in ds.ids():
        entry = report["campaigns"][cid]
        print(f"campaign {cid}: {ds.manifest.loc[cid, 'split']}, {entry['rows']} rows")
    print(f"data config written to {path}")
    print(f"next: thermocomp run 'hydra.searchpath=[file://{path.parent.parent}]' data={name}")
