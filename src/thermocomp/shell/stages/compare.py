"""`thermocomp compare`: one table of every child run of a sweep, best first by validation.

Columns: model, selection, ATI, the settings that vary across the sweep, the
validation RMSE and Rsd SM/SD with their method (``val_*``: what ranks), then
the test Rsd SM/SD, RMSE, RMS reduction, E_P95 of the residual at 1 h / 8 h
(``null`` when the campaigns are shorter) -- reported, never used to choose --
and the fit time.  Below the ranked runs, a ``persistence (baseline)`` row (the
previous measured error as the prediction, read from the runs' metrics;
``baselines`` in ``compare.json``); ``compare.csv`` holds the ranked runs only.
Printed (Markdown), saved as
``compare.csv``, ``compare.md`` and ``compare.json`` (a DVC metric) under
``compare.out`` (default: the sweep's folder), and logged as artifacts of the sweep's parent run.
"""

from __future__ import annotations

import shutil

import pandas as pd
from omegaconf import DictConfig, open_dict

from ...base.errors import ConfigError
from ...base.files import atomic_write_text, write_json
from ...base.jsonsafe import json_safe
from ...base.log import say
from ...base.params import BOOLEAN, optional, text
from ...base.paths import resolve
from ...core.figures.plotdata import write_compare
from ...core.scoring.leaderboard import (
    FIGURES,
    ONLINE_NOTE,
    VAL_FIGURES,
    baseline_rows,
    fit_width,
    informative,
    is_validation,
    rank,
    ranked_by,
    ranking_line,
    to_markdown,
)
from ..config.apart import check_apart
from ..sweeps import parent_run_id, sweep_folder, sweep_rows
from ..tracking import client as mlflow_client
from ..tracking import connect, retry_locked
from .common import _check_writable, check_keys

NO_SWEEP_FOLDER = "reports/compare"   # a sweep whose folder is not on this machine


def _json_table(table: pd.DataFrame, sort_by: str, target: str, parent_id: str,
                baselines: list[dict], basis: dict) -> dict:
    """compare.json; ``basis``: :func:`~thermocomp.core.scoring.leaderboard.ranked_by` of the table (printed
    too)."""
    records = json_safe(table.to_dict(orient="records"))
    numeric = [c for c in (*VAL_FIGURES, *FIGURES, "fit_time_s") if c in table.columns]
    return {"parent_run_id": parent_id, "sort_by": sort_by, "target": target,
            "ranked_by_validation": is_validation(sort_by), "ranked_by": basis,
            "reported_not_used_to_choose": [c for c in FIGURES if c in table.columns],
            "n_runs": len(records),
            "best": {k: records[0][k] for k in ("run_id", "model", "select", *numeric)} if records else {},
            "runs": {f"{i:02d}_{r['run_id'][:8]}": {k: r[k] for k in numeric} for i, r in
                     enumerate(records)},
            "baselines": json_safe([{k: b[k] for k in ("model", "needs_measured_error_online", *FIGURES)}
                                    for b in baselines])}


def compare_sweep(cfg: DictConfig, parent_id: str, out=None) -> pd.DataFrame:
    """Rank the children of ``parent_id``; print, save and log the table."""
    check_keys(cfg, {"compare.descending": optional(BOOLEAN), "compare.target": text()})
    client = mlflow_client(cfg)
    uri = connect(cfg)
    opts = cfg.compare
    found: list = []
    rows = sweep_rows(client, uri, parent_id, str(opts.target), found)
    if not rows:
        raise ConfigError(f"sweep {parent_id} has no child runs")
    try:
        table = rank(rows, str(opts.sort_by), opts.get("descending"))
    except KeyError as exc:
        raise ConfigError(f"compare.sort_by: {exc.args[0]}") from None
    out = resolve(out if out is not None else opts.out)
    baselines = baseline_rows(found)
    shown = table.drop(columns=["run_id"]).assign(run=table["run_id"].str[:8])
    # the persistence baseline below the ranked runs (never ranked itself), marked: it predicts
    # from the measured error, which a compensator in service does not have
    marked = pd.DataFrame([{**b, "model": f"{b['model']}: {ONLINE_NOTE}", "run": "baseline"}
                           for b in baselines], columns=shown.columns)
    # what holds nothing (e_p95_8h of campaigns under 8 h) is left out; compare.csv keeps it all
    shown = informative(pd.concat([shown, marked], ignore_index=True) if baselines else shown)
    md = to_markdown(shown)
    out.mkdir(parents=True, exist_ok=True)
    atomic_write_text(out / "compare.csv", table.to_csv(index=False))
    atomic_write_text(out / "compare.md", md + "\n")
    basis = ranked_by(table, str(opts.sort_by))
    write_json(out / "compare.json", _json_table(table, str(opts.sort_by), str(opts.target), parent_id,
                                                 baselines, basis))
    write_compare(out, table)  # compare_plot.csv, for `dvc plots show`
    for name in ("compare.csv", "compare.md", "compare.json"):
        retry_locked(client.log_artifact, parent_id, str(out / name), "compare")
    said = (ranking_line(basis) if is_validation(str(opts.sort_by))
            else "a TEST figure, as asked: do not choose a model by it")
    print(f"sweep {parent_id}: {len(table)} runs, sorted by {opts.sort_by} "
          f"(target {opts.target}, {said}); test: columns are reported, not used to choose")
    print(fit_width(shown, shutil.get_terminal_size().columns))   # a terminal's width
    say(f"comparison: {out / 'compare.md'}")
    return table


def compare(cfg: DictConfig) -> pd.DataFrame:
    """`thermocomp compare`: the comparison table of ``compare.sweep`` (default: latest sweep),
    written to ``compare.out``, by default beside the sweep it reads."""
    if cfg.compare.get("out") is not None:
        check_apart(cfg, ("compare.out",), ())
        _check_writable("compare.out", cfg.compare.out, folder=True)
    client = mlflow_client(cfg)
    parent_id = parent_run_id(cfg, client)
    if cfg.compare.get("out") is None:
        folder = sweep_folder(cfg, client, parent_id)
        with open_dict(cfg):     # the log file follows (cli._log_folder)
            cfg.compare.out = str(folder if folder is not None else resolve(NO_SWEEP_FOLDER))
        _check_writable("compare.out", cfg.compare.out, folder=True)
    return compare_sweep(cfg, parent_id)
