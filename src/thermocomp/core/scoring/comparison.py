"""The table of ``thermocomp compare`` (pure: the ranked runs and the baselines in, what is
shown and ``compare.json`` out).

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

from collections import Counter

import pandas as pd

from ...base.jsonsafe import json_safe
from .leaderboard import (
    FIGURES,
    MEAN_OVER,
    ONLINE_NOTE,
    VAL_FIGURES,
    informative,
    is_validation,
    ranking_line,
)

# where a sweep's failed jobs say why (each job's folder: shell.callbacks.FAILED_JOB)
FAILED_WHERE = "why in each one's folder, failed.json"


def shown_table(table: pd.DataFrame, baselines: list[dict]) -> pd.DataFrame:
    """The ranked runs as printed (short run ids), the persistence baseline below them (never
    ranked itself), marked: it predicts from the measured error, which a compensator in service
    does not have.  What holds nothing (e_p95_8h of campaigns under 8 h) is left out."""
    # (a mean leaving µm/m targets out is said above the table: ranking_line)
    shown = table.drop(columns=["run_id", MEAN_OVER], errors="ignore").assign(
        run=table["run_id"].str[:8])
    # several baselines of one dataset (a late first probe's label completed by each model's
    # own y_hat(m), firstprobe62): each names the runs it is the baseline of
    per_data = Counter(b.get("dataset") for b in baselines)
    marked = pd.DataFrame([{**b, "model": f"{b['model']}: {ONLINE_NOTE}",
                            "run": "baseline" + (f" of {', '.join(r[:8] for r in b['runs'])}"
                                                 if per_data[b.get("dataset")] > 1
                                                 and b.get("runs") else "")}
                           for b in baselines], columns=shown.columns)
    return informative(pd.concat([shown, marked], ignore_index=True) if baselines else shown)


def compare_json(table: pd.DataFrame, sort_by: str, target: str, parent_id: str,
                 baselines: list[dict], basis: dict, jobs: tuple[int, int] = (0, 0)) -> dict:
    """``compare.json``; ``basis``: :func:`~.leaderboard.ranked_by` of the table (printed too);
    ``jobs``: the sweep's ``(failed, jobs)`` (``failed_jobs``, ``jobs``: a grid with failed jobs
    is not whole)."""
    records = json_safe(table.to_dict(orient="records"))
    numeric = [c for c in (*VAL_FIGURES, *FIGURES, "fit_time_s") if c in table.columns]
    return {"parent_run_id": parent_id, "sort_by": sort_by, "target": target,
            "ranked_by_validation": is_validation(sort_by), "ranked_by": basis,
            "reported_not_used_to_choose": [c for c in FIGURES if c in table.columns],
            "n_runs": len(records), "failed_jobs": jobs[0], "jobs": jobs[1],
            "best": {k: records[0][k] for k in ("run_id", "model", "select", *numeric)} if records else {},
            "runs": {f"{i:02d}_{r['run_id'][:8]}": {k: r[k] for k in numeric} for i, r in
                     enumerate(records)},
            "baselines": json_safe([{k: b[k] for k in ("model", "needs_measured_error_online",
                                                       "dataset", "runs", *FIGURES) if k in b}
                                    for b in baselines]),
            # a sweep over several datasets: ranked within each (``best`` is the first's)
            **({"best_per_dataset": {d: str(g["run_id"].iloc[0]) for d, g in
                                     table.groupby("dataset", sort=False)}}
               if "dataset" in table.columns else {})}


def headline_line(parent_id: str, n_runs: int, sort_by: str, target: str, basis: dict,
                  datasets: int = 1, failed: str = "") -> str:
    """The line above the table: what sorted it (``basis``: :func:`~.leaderboard.ranked_by`),
    and ``failed``, what the sweep's failed jobs left out of it."""
    said = (ranking_line(basis) if is_validation(sort_by)
            else "a TEST figure, as asked: do not choose a model by it")
    within = (f" on {datasets} datasets, ranked within each (figures of different data do not "
              f"compare)" if datasets > 1 else "")
    failed = f" ({failed}: {FAILED_WHERE})" if failed else ""
    return (f"sweep {parent_id}: {n_runs} runs{failed}{within}, sorted by {sort_by} "
            f"(target {target}, {said}); test: columns are reported, not used to choose")
