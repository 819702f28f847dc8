"""``model=auto``'s guard to MLR on a new source's rows, given a TRAIN-side reason: in auto's own
validation folds, who extrapolates better off the fold-train's widened pattern, auto's blend or
MLR?  Does that fold-level "extrapolation score" tell, per target, who wins the test rows
bench_auto93's ``both_wide`` guards?  (issue 34; stop 93, auto93b, follow-up of bench_auto93).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``; ROOT and WORK as bench_auto93's,
i.e. bench_auto91's ``rows`` already run into WORK)::

    python benchmarks/bench_auto93b.py guard ROOT WORK RECORD ...   # seen records, stored rows
    python benchmarks/bench_auto93b.py rooms RECORD ...             # rooms / bench_auto93's FRESH
    python benchmarks/bench_auto93b.py fresh                        # seeds 9571-9580, once (bar)

The extrapolation score (train side only, nothing from the test): auto refitted on the record's
train campaigns keeps, per target, its folds (``oof_folds_``: each fold's fit and scored rows) and
its candidates' out-of-fold free-run predictions.  Per fold, the fold-train's rows alone build
bench_auto93's gate -- an ``Envelope.from_data`` on the fit rows' inputs (margin
``promote.envelope.margin``), its pattern widened by the ambient-driven directions fitted on the
fit rows (:func:`bench_auto93.off_widened`; the ambient features are causal and referenced at each
campaign's first sample, so a fold's rows carry the same features as in the whole record) -- and
the fold's scored rows beyond the fit rows' bounds AND off that widened pattern are its
EXTRAPOLATING rows (``both_wide`` of the fold).  On them, per fold k, r_k = the kept blend's
summed squared error over MLR's (``AutoEstimator.out_of_fold`` against ``oof_['mlr']``).

Probes (each hands a target's ``both_wide`` test rows to MLR, or none of them; a target whose
folds hold no extrapolating row, or whose kept model is MLR, is never guarded):

* ``fold_sse``: guard where the pooled ratio over every fold's extrapolating rows is >= 1 (MLR
  extrapolates at least as well in the folds);
* ``fold_1se``: guard unless the blend is SURELY better there: mean r_k + SE >= 1 over the folds
  with extrapolating rows (auto's own one-SE rule, :meth:`AutoEstimator._one_se`, on those rows;
  with one such fold its r);
* ``raw_sse`` / ``raw_1se``: the same with the fold's extrapolating rows taken off the fit rows'
  RAW pattern (bench_auto92's ``both`` in the fold, no widening).  ADDED after the first trace
  (col9278 / col9280, before any other record and any fresh seed): on one record's forward folds
  the widened pattern excuses every fold row (the ambient filter fitted on a fold's prefix
  absorbs the record's own warming, with which its ambient drift co-occurs), so ``fold_*`` never
  guards there; the bar was not changed;
* ``both_wide``: bench_auto93's rule, every target guarded (reference).

``guard``: the 10 seen records of bench_auto92's ``guard`` (auto refitted for its folds; the test
from WORK's stored predictions of the new campaigns, as bench_auto92 scores them): per target the
fold score, the share of fold rows extrapolating, and the test's auto / MLR SSE on the guarded
rows; per record auto / MLR -> probe / MLR.  ``rooms``: the same on bench_auto88b's rooms and
bench_auto93's FRESH (auto and MLR refitted, each record's own test campaigns), guarded / auto.

Question first (the trace): does the fold score's side (>= 1 or < 1) match the side of the test's
guarded-row ratio, target by target, on the seen records and on bench_auto93's fresh set
(cr9271-9275, col9276-9280: SEEN now, auto93 scored them; used here to trace, said so)?

Bar (written here BEFORE any fold score was computed, the brief's): a probe is scored on fresh
seeds only if on the seen + traced records (the 23 of bench_auto93's bar and its 10 fresh) it
keeps col9278 and col9280 within 1 % of auto while guarding col5791 (1.258 -> <= 1.02 x MLR).
Fresh seeds 9571-9580 (9571-9575 ``sim=climate_room`` SMALL, 9576-9580
``sim=column_moving_source``, as bench_auto93's FRESH), scored ONCE by ``fresh``: (a) rooms geo
guarded / auto <= 1.002, and no fresh record worse than auto by > 1 %, geo over the 10 <= 1.002;
(b) the fresh records where auto loses to MLR counted with those the probe brings within 2 % of
MLR.  Pass = (a); (b) is reported.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto87 as auto87  # noqa: E402
import bench_auto88b as auto88b  # noqa: E402
import bench_auto91 as auto91  # noqa: E402
import bench_auto92c as auto92c  # noqa: E402
import bench_auto93 as auto93  # noqa: E402
from _cli import run_commands  # noqa: E402

FRESH = {**{f"cr{s}": ["sim=climate_room", f"seed={s}", *auto87.SMALL] for s in range(9571, 9576)},
         **{f"col{s}": ["sim=column_moving_source", f"seed={s}"] for s in range(9576, 9581)}}
PROBES = ("fold_sse", "fold_1se", "raw_sse", "raw_1se", "both_wide")


class _Inputs:
    """A record's train inputs as the gate reads them: the ``T_`` columns less each campaign's
    first sample (stacked, the compensator's row order), which are ambient, and the ambient
    features (bench_auto93's referenced ambient and its low-passes) per row."""

    def __init__(self, frames: list, columns: list[str]):
        from thermocomp.core.io.contract import is_ambient

        self.columns, self.frames = columns, frames
        self.x = np.vstack([auto91._inputs(f, columns) for f in frames])
        self.ambient = np.array([is_ambient(c) for c in columns])
        names = [c for c, a in zip(columns, self.ambient) if a]
        self.features = (np.vstack([auto93._ambient_features(f, names) for f in frames])
                         if names else np.zeros((len(self.x), 0)))

    def directions(self, rows: np.ndarray) -> np.ndarray:
        """bench_auto93's ambient-driven directions, fitted on ``rows`` alone."""
        out = np.zeros((len(self.columns), self.features.shape[1]))
        if self.ambient.any():
            coef, *_ = np.linalg.lstsq(self.features[rows], self.x[rows][:, ~self.ambient], rcond=None)
            out[~self.ambient], out[self.ambient, 0] = coef.T, 1.0
        return out

    def both_wide(self, rows: np.ndarray, x: np.ndarray, widened: bool = True) -> np.ndarray:
        """Per row of ``x``: beyond the bounds of ``rows``' inputs AND off their pattern widened by
        their ambient-driven directions (bench_auto93's ``both_wide`` with ``rows`` as train);
        ``widened=False``: off their raw pattern (bench_auto92's ``both``)."""
        from thermocomp.apps.deploy.streaming import Envelope

        envelope = Envelope.from_data(pd.DataFrame(self.x[rows]), margin=auto92c._margin())
        directions = self.directions(rows) if widened else np.zeros((len(self.columns), 0))
        return auto93.off_widened(envelope, directions, x) & envelope.outside(x).any(axis=1)


def fold_score(est, inputs: _Inputs, widened: bool = True) -> dict:
    """The target's extrapolation score in auto's folds (module doc): ``share`` of the scored rows
    extrapolating, ``pooled`` and ``ratios`` (per fold with such rows) of the kept blend's SSE
    over MLR's on them; empty where the folds or MLR's out-of-fold are missing."""
    oof = est.out_of_fold()
    if oof is None or "mlr" not in est.oof_:
        return {}
    n, folds, y, predicted = oof
    assert n == len(inputs.x), "the compensator's rows are not the stacked frames'"
    off = np.concatenate([inputs.both_wide(fit, inputs.x[score], widened) for fit, score in folds])
    fold = est.oof_fold_
    e_auto, e_mlr = (y - predicted) ** 2, (y - est.oof_["mlr"]) ** 2
    ratios = [e_auto[off & (fold == k)].sum() / e_mlr[off & (fold == k)].sum()
              for k in np.unique(fold[off])]
    pooled = e_auto[off].sum() / e_mlr[off].sum() if off.any() else np.nan
    return {"share": off.mean(), "pooled": pooled, "ratios": np.array(ratios)}


def _guards(score: dict, is_mlr: bool) -> tuple[bool, bool]:
    """``(pooled, one-SE)``: whether the target's ``both_wide`` test rows go to MLR by each."""
    ratios = score.get("ratios", np.array([]))
    if is_mlr or ratios.size == 0:
        return False, False
    se = np.std(ratios, ddof=1) / np.sqrt(ratios.size) if ratios.size > 1 else 0.0
    return bool(score["pooled"] >= 1.0), bool(ratios.mean() + se >= 1.0)


def _target_line(t: str, est, score: dict, test_ratio: float, guarded: float) -> str:
    kept = " + ".join(f"{w:.2f} {n}" for n, w in est.weights_.items())
    if not score:
        return f"   {t}: kept {kept}; no fold score; test guarded rows ({guarded:.2f}) auto/MLR SSE {test_ratio:.3f}"
    ratios = " ".join(f"{r:.2f}" for r in score["ratios"])
    return (f"   {t}: kept {kept}; folds extrapolating {score['share']:.2f}, auto/MLR SSE pooled "
            f"{score['pooled']:.3f} (per fold {ratios}); test guarded rows ({guarded:.2f}) auto/MLR "
            f"SSE {test_ratio:.3f}")


def _fit_auto(overrides: list[str]):
    """``(cfg, ds, train, auto)``: bench_auto_rank's setup and auto fitted on the train part."""
    import bench_auto_rank as rank

    from thermocomp.shell.builders import build_compensator

    sys.argv[2:] = overrides                  # bench_auto_rank simulates when sim= is asked
    cfg, ds, train = rank.setup(overrides)
    return cfg, ds, train, build_compensator(cfg, ds=ds).fit(train)


def _scored(name: str, auto, inputs: _Inputs, x_test: np.ndarray, tests: dict) -> dict[str, float]:
    """Print the record's per-target lines; return per figure (auto, mlr, probes) the mean over
    targets of the test RMSE.  ``tests``: per target ``(y, r_auto, r_mlr)`` on the scored rows."""
    gate = inputs.both_wide(np.arange(len(inputs.x)), x_test)
    print(f"  {name}: test rows guarded by both_wide {gate.mean():.2f}", flush=True)
    figures = {k: [] for k in ("auto", "mlr", *PROBES)}
    for t, (keep, r_auto, r_mlr) in tests.items():
        est = auto.estimators_[t]
        rows = keep & gate
        test_ratio = np.sum(r_auto[rows] ** 2) / np.sum(r_mlr[rows] ** 2) if rows.any() else np.nan
        is_mlr, guards = set(est.weights_) == {"mlr"}, {"both_wide": True}
        for fold_rows, widened in (("fold", True), ("raw", False)):
            score = fold_score(est, inputs, widened)
            print(f"  [{fold_rows}]" + _target_line(t, est, score, test_ratio, rows.sum() / keep.sum()),
                  flush=True)
            guards[f"{fold_rows}_sse"], guards[f"{fold_rows}_1se"] = _guards(score, is_mlr)
        figures["auto"].append(np.sqrt(np.mean(r_auto[keep] ** 2)))
        figures["mlr"].append(np.sqrt(np.mean(r_mlr[keep] ** 2)))
        for probe, on in guards.items():
            r = np.where(gate & on, r_mlr, r_auto)
            figures[probe].append(np.sqrt(np.mean(r[keep] ** 2)))
    return {k: float(np.mean(v)) for k, v in figures.items()}


def guard(root: str, work: str, *records: str) -> None:
    """Seen records of bench_auto92's ``guard``: the test from WORK's stored predictions."""
    work_path = Path(work).resolve()
    for name in records:
        row = auto91._row(work_path, name)
        overrides = [o.format(root=Path(root).resolve()) for o in auto91.automore.OVERRIDES[name]]
        cfg, ds, train, auto = _fit_auto(overrides)
        frames = list(train.values())
        inputs = _Inputs(frames, [c for c in frames[0].columns if c.startswith("T_")])
        news = auto91.automore.draws(auto91.automore.OF[name], work_path, cfg)
        tests = [ds.campaigns[c] for c in row["own"]] + [d.campaigns[c] for d in news for c in d.ids()]
        x_test = np.vstack([auto91._inputs(f, inputs.columns) for f in tests])
        series = {}
        for target in row["weights"]:
            a = np.load(work_path / "pred" / f"{name}.{target}.npz")
            y = auto91.automore.label(a, row["reference"])
            keep = (a["campaign"] >= len(row["own"])) & np.isfinite(y)
            series[target] = (keep, y - a["pred_auto"], y - a["pred_mlr"])
        mean = _scored(name, auto, inputs, x_test, series)
        print(f"  {name}: auto / MLR {mean['auto'] / mean['mlr']:.3f} -> "
              + ", ".join(f"{p} {mean[p] / mean['mlr']:.3f}" for p in PROBES), flush=True)


def rooms(*records: str) -> None:
    """Rooms (bench_auto88b's) and bench_auto93's / this bench's FRESH: own test campaigns."""
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.core.scoring.evaluation import split_residuals

    auto88b.RECORDS.update({**auto93.FRESH, **FRESH})
    for name in records:
        _, ds, train, auto = _fit_auto(list(auto88b.RECORDS[name]))
        mlr = clone(auto).set_params(estimator=rank._mlr()).fit(train)
        frames, ids = list(train.values()), ds.ids("test")
        inputs = _Inputs(frames, [c for c in frames[0].columns if c.startswith("T_")])
        x_test = np.vstack([auto91._inputs(ds.campaigns[c], inputs.columns) for c in ids])
        res = {k: split_residuals(m, ds, ids, "simulation")[2] for k, m in (("auto", auto), ("mlr", mlr))}
        series = {}
        for t in res["auto"]:
            y = np.concatenate([res["auto"][t][0][c] for c in ids])
            series[t] = (np.isfinite(y), *(np.concatenate([res[k][t][1][c] for c in ids])
                                           for k in ("auto", "mlr")))
        mean = _scored(name, auto, inputs, x_test, series)
        print(f"  {name}: auto {mean['auto']:.4f} MLR {mean['mlr']:.4f} (auto/MLR "
              f"{mean['auto'] / mean['mlr']:.3f}); probe / auto "
              + ", ".join(f"{p} {mean[p] / mean['auto']:.3f}" for p in PROBES), flush=True)


def fresh() -> None:
    """``rooms`` on :data:`FRESH`, once, for the bar."""
    rooms(*FRESH)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"guard": guard, "rooms": rooms, "fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
