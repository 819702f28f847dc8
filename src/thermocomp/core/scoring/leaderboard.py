"""Ranking fitted models by their validation figures (pure core: dicts in, table out).

A *row* summarises one run's ``metrics.json`` ``targets`` block for one target
(or the mean over targets): the validation RMSE and Rsd SM/SD (``val_*``, from
the ``val`` split or cross-validation on the train split, see
:func:`thermocomp.core.scoring.evaluation.validation_report`), then the test figures --
Rsd SM/SD, RMSE, RMS reduction, E_P95 of the residual at 1 h and 8 h --
reported beside them.  ``thermocomp compare`` ranks the runs of a sweep by a
validation figure and ``thermocomp promote`` gates on one, in simulation mode whatever
``eval.mode`` a run was scored in (a deployed compensator runs free): a choice made by
looking at the test split would flatter whatever it chose.
:func:`baseline_rows` gives the persistence baseline (previous measured error as
the prediction) in the same layout, shown beside the ranking, never ranked.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd

from ..metrics import PERSISTENCE, angular, validation_block
from .results import DEPLOYED_MODE, HEADLINES, RMS_REDUCTION, VAL_RMSE, TargetResult

FIGURES = tuple(name for name, _, _ in HEADLINES["baseline"])    # test
VAL_FIGURES = tuple(name for name, block, _ in HEADLINES["compare"]     # what ranks and gates
                    if block == "deployed")
VAL_PREFIX = "val_"
MEAN_OVER = "mean_over"     # a row's column where its mean leaves targets out (:func:`mean_label`)
HIGHER_IS_BETTER = {RMS_REDUCTION}
BASELINE = "persistence (baseline)"
# persistence predicts from the previous MEASURED error: a probe on the machine in service
ONLINE_NOTE = "needs measured error online"


def deployed_validation(m: Mapping) -> Mapping | None:
    """A target's validation in the deployed mode: ``validation_simulation`` of a run scored in
    ``one_step``, else ``validation`` (of a simulation run; of an old one_step run, see
    :func:`validation_mode`)."""
    return TargetResult(m).deployed.block or None


def validation_mode(metrics: Mapping) -> str:
    """The mode of the validation figures :func:`summary` gives for a run's ``metrics.json``:
    ``simulation``, unless the run was scored in another mode and has no simulation-mode
    validation (a run made before it was recorded)."""
    mode = str(metrics.get("mode", DEPLOYED_MODE))
    targets = metrics.get("targets") or {}
    if mode == DEPLOYED_MODE or (targets and all(
            m.get(validation_block(DEPLOYED_MODE)) for m in targets.values())):
        return DEPLOYED_MODE
    return mode


def _figures(m: Mapping) -> dict:
    return TargetResult(m).headline("compare")


def is_validation(criterion: str) -> bool:
    """Whether ``criterion`` names a validation figure (the only kind allowed to choose)."""
    return criterion in VAL_FIGURES


def mean_over(targets) -> tuple[list[str], list[str]]:
    """(the targets a mean over targets averages, those it leaves out).  Every target where they
    share a unit; where µm/m targets (angular: a sensor nest's tilts) stand beside µm ones, the
    µm ones (extension, isoleft67: a mean of µm and µm/m adds two units, and a tilt's
    figure moved a ranking of X, Y, Z as much as a µm of them did).  ``targets``: their names."""
    names = list(targets)
    lengths = [t for t in names if not angular(t)]
    if not lengths or len(lengths) == len(names):
        return names, []
    return lengths, [t for t in names if angular(t)]


def mean_label(targets, target: str = "mean") -> str:
    """What ``target`` ranks by, said: ``target`` itself, or where a ``mean`` leaves targets out
    (:func:`mean_over`), ``mean of E_X1, E_Y1, E_Z (µm; E_Tilt_A, E_Tilt_B in µm/m left out)``."""
    if target != "mean":
        return target
    kept, left = mean_over(targets)
    return target if not left else (f"mean of {', '.join(kept)} (µm; {', '.join(left)} in µm/m "
                                     f"left out)")


def validation_method(targets: Mapping, target: str = "mean") -> str | None:
    """How the validation figures were computed (``method`` of ``metrics.json``), or None."""
    entries = [targets[target]] if target != "mean" else [targets[t] for t in mean_over(targets)[0]]
    methods = {(deployed_validation(m) or {}).get("method") for m in entries} - {None}
    return " / ".join(sorted(methods)) or None


def summary(targets: Mapping, target: str = "mean") -> dict:
    """Validation and test figures of one target, or their mean over targets (``target='mean'``;
    over the µm targets where µm/m ones stand beside them: :func:`mean_over`).

    ``targets`` is the ``targets`` block of ``metrics.json``; the ``val_*`` figures are
    of the deployed mode (:func:`deployed_validation`).  A figure missing
    for some target is averaged over the others; ``None`` if missing for all
    (the ``val_*`` figures of a run made with ``eval.validation=false``).
    """
    if target != "mean":
        if target not in targets:
            raise KeyError(f"target {target!r} not in metrics (have {sorted(targets)})")
        return _figures(targets[target])
    per = [_figures(targets[t]) for t in mean_over(targets)[0]]
    out = {}
    for f in (*VAL_FIGURES, *FIGURES):
        vals = [p[f] for p in per if p[f] is not None and math.isfinite(p[f])]
        out[f] = float(np.mean(vals)) if vals else None
    return out


def persistence_summary(targets: Mapping, target: str = "mean") -> dict | None:
    """The persistence baseline's test figures in the layout of :func:`summary` (None if absent).

    Persistence predicts the previous measured error (``persistence`` block of
    a target in ``metrics.json``); its RMS reduction is against the target's
    RMS before compensation, E_P95 is not computed (None).
    """
    def figures(m: Mapping) -> dict | None:
        return TargetResult(m).headline("baseline") if m.get(PERSISTENCE) else None

    if target != "mean":
        return figures(targets[target]) if target in targets else None
    per = [figures(targets[t]) for t in mean_over(targets)[0]]
    if any(p is None for p in per) or not per:
        return None
    out = {}
    for f in FIGURES:
        vals = [p[f] for p in per if p[f] is not None and math.isfinite(p[f])]
        out[f] = float(np.mean(vals)) if vals else None
    return out


def baseline_rows(summaries: Sequence[Mapping | None]) -> list[dict]:
    """One ``persistence`` row per distinct baseline of the runs (one when they share the data)."""
    rows: list[dict] = []
    for s in summaries:
        if s is None:
            continue
        same = next((r for r in rows if all(_same(s[f], r[f]) for f in FIGURES)
                     and s.get("dataset") == r.get("dataset")), None)
        run = s.get("run_id")
        if same is None:
            rows.append({"model": BASELINE, "needs_measured_error_online": True,
                         **{k: v for k, v in s.items() if k != "run_id"},
                         "runs": [run] if run else []})
        elif run:
            same["runs"].append(run)
    return rows


def _same(a, b) -> bool:
    if a is None or b is None:
        return a is b
    return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)


def descending_for(criterion: str) -> bool:
    return criterion in HIGHER_IS_BETTER


def rank(rows: Sequence[Mapping], sort_by: str = VAL_RMSE,
         descending: bool | None = None) -> pd.DataFrame:
    """Rows as a table, best first by ``sort_by`` (missing values last).

    By a validation figure, rows whose ``val_mode`` is not the deployed mode
    (old one_step runs: :func:`validation_mode`) come after every other: their
    figure is not comparable, it ranks them only among themselves.  Rows of several datasets
    (a ``dataset`` column) are ranked within each, the dataset of the best row first: figures
    scored on different data do not compare.
    """
    table = pd.DataFrame(list(rows))
    if table.empty:
        return table
    if sort_by.startswith("test:") and sort_by[5:] in FIGURES:   # as the printed table heads it
        sort_by = sort_by[5:]
    # the figures a table ranks by (not its labels: run_id, model, settings ...)
    sortable = [f for f in (*VAL_FIGURES, *FIGURES, "fit_time_s") if f in table.columns]
    if sort_by not in sortable:
        raise KeyError(f"cannot sort by {sort_by!r}; validation (ranks): "
                       f"{', '.join(f for f in sortable if is_validation(f))}; test (reported, as "
                       f"test:<name>): {', '.join(f for f in sortable if f in FIGURES)}; or fit_time_s")
    desc = descending_for(sort_by) if descending is None else bool(descending)
    table = table.sort_values(sort_by, ascending=not desc, na_position="last", kind="stable")
    if is_validation(sort_by) and "val_mode" in table.columns:
        table = table.sort_values("val_mode", key=lambda m: m != DEPLOYED_MODE, kind="stable")
    if "dataset" in table.columns:
        first = {d: i for i, d in enumerate(dict.fromkeys(table["dataset"]))}
        table = table.sort_values("dataset", key=lambda d: d.map(first), kind="stable")
    return table.reset_index(drop=True)


def fallback_runs(table: pd.DataFrame) -> dict:
    """``{run_id: mode}`` of the ranked runs whose validation is not in the deployed mode."""
    if table.empty or "val_mode" not in table.columns:
        return {}
    other = table[table["val_mode"].notna() & (table["val_mode"] != DEPLOYED_MODE)]
    return dict(zip(other["run_id"], other["val_mode"]))


def beats(candidate: float | None, incumbent: float | None, criterion: str,
          min_improvement: float = 0.0) -> bool:
    """Whether ``candidate`` is strictly better than ``incumbent`` by more than
    ``min_improvement`` (absolute, in the criterion's unit)."""
    if candidate is None or not math.isfinite(candidate):
        return False
    if incumbent is None or not math.isfinite(incumbent):
        return True
    if descending_for(criterion):
        return candidate > incumbent + min_improvement
    return candidate < incumbent - min_improvement


def _cells(table: pd.DataFrame, digits: int) -> pd.DataFrame:
    """The table as text (``n/a`` for missing figures); test columns headed ``test:``."""
    shown = table.rename(columns={f: f"test:{f}" for f in FIGURES})
    def cell(v):                 # per cell: a column with a missing figure is of object dtype
        if v is None or (isinstance(v, float) and np.isnan(v)):
            return "n/a"
        return f"{v:.{digits}f}" if isinstance(v, float) else v

    for c in shown.columns:
        shown[c] = [cell(v) for v in shown[c]]
    return shown.fillna("n/a")


def to_markdown(table: pd.DataFrame, digits: int = 2) -> str:
    """GitHub Markdown table (``n/a`` for missing figures); test columns headed ``test:``."""
    return _cells(table, digits).to_markdown(index=False, disable_numparse=True)


def informative(table: pd.DataFrame) -> pd.DataFrame:
    """``table`` without its columns that hold nothing in any row (all missing or empty)."""
    empty = [c for c in table.columns
             if all(v is None or (isinstance(v, float) and np.isnan(v)) or str(v).strip() == ""
                    for v in table[c])]
    return table.drop(columns=empty)


def fit_width(table: pd.DataFrame, width: int, key: str = "run", digits: int = 2) -> str:
    """Markdown tables of at most ``width`` characters a line (a column wider alone excepted):
    the columns in blocks, one under the other, each led by the ``key`` column naming the rows."""
    text = _cells(table, digits)
    lead = [key] if key in text.columns else []

    def render(columns):
        return text[lead + columns].to_markdown(index=False, disable_numparse=True)

    blocks: list[list[str]] = []
    for c in (c for c in text.columns if c != key):
        if blocks and max(map(len, render(blocks[-1] + [c]).splitlines())) <= width:
            blocks[-1].append(c)
        else:
            blocks.append([c])
    return "\n\n".join(render(b) for b in blocks)


def ranked_by(table: pd.DataFrame, sort_by: str) -> dict:
    """Which figure ranked: ``figure``, ``mode`` (of a validation figure: the deployed mode) and
    ``fallback`` (``{run_id: mode}`` of runs without a simulation-mode validation, ranked after
    the others by their own)."""
    labels = sorted({v for v in table.get(MEAN_OVER, ()) if isinstance(v, str) and v})
    over = {"mean_over": labels} if labels else {}
    if not is_validation(sort_by):
        return {"figure": sort_by, "mode": None, "fallback": {}, **over}
    return {"figure": sort_by, "mode": DEPLOYED_MODE, "fallback": fallback_runs(table), **over}


def ranking_line(basis: dict) -> str:
    """The printed sentence of :func:`ranked_by`."""
    line = (f"{basis['figure']} of the {basis['mode']}-mode validation (the deployed mode, "
            f"whatever eval.mode a run was scored in)")
    if basis["fallback"]:
        line += (f"; {len(basis['fallback'])} run(s) without one (made before it was recorded: "
                 + ", ".join(f"{r[:8]} {m}" for r, m in basis["fallback"].items())
                 + ") ranked after the others by their own mode's validation")
    if basis.get("mean_over"):      # a mean over the µm targets alone (isoleft67)
        line += ("; target " + " / ".join(basis["mean_over"])
                 + ": rank by one with compare.target=<E_ column> (promote.target)")
    return line
