"""`thermocomp compare`: one table of every child run of a sweep, best first by validation.

The table (:mod:`thermocomp.core.scoring.comparison`) is printed (Markdown), saved as
``compare.csv``, ``compare.md`` and ``compare.json`` (a DVC metric) under ``compare.out``
(default: the sweep's folder), and logged as artifacts of the sweep's parent run.
"""

from __future__ import annotations

import shutil

import pandas as pd
from omegaconf import DictConfig, open_dict

from ...base.errors import ConfigError
from ...base.files import atomic_write_text, write_json
from ...base.log import say
from ...base.params import BOOLEAN, optional, text
from ...base.paths import resolve
from ...core.figures.plotdata import write_compare
from ...core.scoring.comparison import FAILED_WHERE, compare_json, headline_line, shown_table
from ...core.scoring.leaderboard import baseline_rows, fit_width, rank, ranked_by, to_markdown
from ..config.apart import check_apart
from ..config.checks import _check_writable
from ..config.rules import check_keys
from ..sweeps import failed_jobs, failed_note, parent_run_id, sweep_folder, sweep_rows
from ..tracking import client as mlflow_client
from ..tracking import connect, retry_locked

NO_SWEEP_FOLDER = "reports/compare"   # a sweep whose folder is not on this machine


def compare_sweep(cfg: DictConfig, parent_id: str, out=None) -> pd.DataFrame:
    """Rank the children of ``parent_id``; print, save and log the table."""
    check_keys(cfg, {"compare.descending": optional(BOOLEAN), "compare.target": text()})
    client, uri, opts = mlflow_client(cfg, existing=True), connect(cfg, existing=True), cfg.compare
    found: list = []
    rows = sweep_rows(client, uri, parent_id, str(opts.target), found)
    if not rows:
        note = failed_note(*failed_jobs(client, parent_id))
        raise ConfigError(f"sweep {parent_id} has no child runs"
                          + (f" ({note}: {FAILED_WHERE})" if note else ""))
    try:
        table = rank(rows, str(opts.sort_by), opts.get("descending"))
    except KeyError as exc:
        raise ConfigError(f"compare.sort_by: {exc.args[0]}") from None
    out = resolve(out if out is not None else opts.out)
    baselines = baseline_rows(found)
    shown = shown_table(table, baselines)
    out.mkdir(parents=True, exist_ok=True)
    atomic_write_text(out / "compare.csv", table.to_csv(index=False))
    atomic_write_text(out / "compare.md", to_markdown(shown) + "\n")
    basis = ranked_by(table, str(opts.sort_by))
    jobs = failed_jobs(client, parent_id)     # a job refused on its data has no row: said
    write_json(out / "compare.json", compare_json(table, str(opts.sort_by), str(opts.target),
                                                  parent_id, baselines, basis, jobs))
    write_compare(out, table)  # compare_plot.csv, for `dvc plots show`
    for name in ("compare.csv", "compare.md", "compare.json"):
        retry_locked(client.log_artifact, parent_id, str(out / name), "compare")
    datasets = table["dataset"].nunique() if "dataset" in table.columns else 1
    print(headline_line(parent_id, len(table), str(opts.sort_by), str(opts.target), basis, datasets,
                        failed_note(*jobs)))
    print(fit_width(shown, shutil.get_terminal_size().columns))   # a terminal's width
    say(f"comparison: {out / 'compare.md'}")
    return table


def compare(cfg: DictConfig) -> pd.DataFrame:
    """`thermocomp compare`: the comparison table of ``compare.sweep`` (default: latest sweep),
    written to ``compare.out``, by default beside the sweep it reads."""
    if cfg.compare.get("out") is not None:
        check_apart(cfg, ("compare.out",), ())
        _check_writable("compare.out", cfg.compare.out, folder=True)
    client = mlflow_client(cfg, existing=True)     # it reads the store: never creates one
    parent_id = parent_run_id(cfg, client)
    if cfg.compare.get("out") is None:
        folder = sweep_folder(cfg, client, parent_id)
        with open_dict(cfg):     # the log file follows (cli._log_folder)
            cfg.compare.out = str(folder if folder is not None else resolve(NO_SWEEP_FOLDER))
        _check_writable("compare.out", cfg.compare.out, folder=True)
    return compare_sweep(cfg, parent_id)
