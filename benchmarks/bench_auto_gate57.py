"""``model=auto`` with blend weights gated by extrapolation, scored from ``bench_auto_rank.py``'s arrays.

Usage::

    python benchmarks/bench_auto_gate57.py DIR NAME [NAME ...]

``DIR`` holds ``NAME.json`` and ``NAME.<target>.npz`` (every candidate's out-of-fold and test
free-run predictions, ``oof_in_range``, ``oof_fold``, ``test_y``).  The test rows' in-range flags
are not saved there: each record is generated again from its overrides (``NAME.json``; the
simulators are deterministic), a compensator with MLR fitted on its train split (the inputs its
selector keeps per target, denoised as ``model=auto`` sees them), and each test row flagged by
:func:`~thermocomp.core.model_selection.extrapolation.within_range` of all the train rows (the
final fit's).  Checks: MLR's test predictions equal the saved ``test_mlr``, the votes on all rows
equal the shipped weights, and the out-of-fold flags recomputed on the forward folds equal the
saved ``oof_in_range`` (so the rows and the design are auto's).

Why (stop 57, ``bench_auto_rank.py``): where auto loses to MLR on ``column_moving_source``, the loss
sits in test rows beyond the training range (the source Q3 never trained); the lag families win the
folds and lose there.  The forward folds hold rows where the fold's fit extrapolates too.

The rule, fixed before any record was scored (the test only scores it):

* ``gated``: per target two weight vectors from the out-of-fold rows, ``vote_weights`` as shipped
  (candidates = every validated one, ``base_column`` = MLR, ``min_folds`` = 5):
  ``w_in`` on the rows where the fold does not extrapolate (``in_range_rows``, as
  ``validation_rows='in_range'`` takes them: a fold with fewer than 20 in-range rows scored whole);
  ``w_out`` on the rows where it does, of the folds with at least 20 such rows; with fewer than 2
  such folds, ``w_out`` is MLR alone.  A test row within range of the train rows is predicted with
  ``w_in``, another with ``w_out``.
* ``gated_mlr`` (the one variant, fixed with it): ``w_in`` as above, MLR alone out of range.

Acceptance into ``src`` (fixed with the rule): more records better than MLR than shipped auto, no
record more than 2 % worse than shipped auto, no fewer within 10 % of the best family (the family
with the lowest mean test RMSE over the targets, known after the fact).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
from hydra import compose, initialize_config_dir
from hydra.utils import instantiate

import thermocomp.shell.cli  # noqa: F401  (registers the config's resolvers)
from thermocomp.base.paths import conf_dir
from thermocomp.core.context import groups_of
from thermocomp.core.metrics import rmse
from thermocomp.core.model_selection import BlockedForward
from thermocomp.core.model_selection.extrapolation import within_range
from thermocomp.core.models import MLR
from thermocomp.core.models.auto import BASELINE, MIN_IN_RANGE_ROWS, in_range_rows
from thermocomp.core.models.blend import vote_weights
from thermocomp.shell.builders import build_compensator
from thermocomp.shell.source import resolve_reference

N_FOLDS = 5
LIGHT = ["track=false", "plots=none", "model=auto"]
FLAGS = Path("/tmp/gate57-flags")


def test_flags(name: str, overrides: list[str], saved: dict) -> dict:
    """``{target: test rows within range of the train rows}``, the record generated again."""
    cache = FLAGS / f"{name}.npz"
    if cache.exists():
        return dict(np.load(cache))
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[*LIGHT, *overrides])
    ds = instantiate(cfg.sim.generator).generate()[0]
    resolve_reference(cfg, ds)
    comp = build_compensator(cfg, ds=ds).set_params(estimator=MLR())
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    comp.fit(train)
    mtr, mte = comp.stacked(train), comp.stacked(test)
    mlr = comp.predict_stacked(mte)
    flags = {}
    for k, t in enumerate(comp.targets_):
        a = saved[t]
        assert np.allclose(mlr[:, k], a["test_mlr"], atol=1e-6 * (1 + np.abs(mlr[:, k]).max())), t
        Xtr, Xte = mtr.X[comp.selected_[t]].to_numpy(), mte.X[comp.selected_[t]].to_numpy()
        X = np.vstack([Xtr, Xte])
        is_train = np.arange(len(X)) < len(Xtr)
        flags[t] = within_range(X, is_train, ~is_train)[~is_train]
        folds = BlockedForward(N_FOLDS, 0.5, 0.5).folds(groups_of(mtr.context), len(Xtr))
        oof = np.concatenate([within_range(Xtr, fit, score)[score] for fit, _, score in folds])
        flags[f"{t}.oof_agree"] = np.array(np.mean(oof == a["oof_in_range"]))
    FLAGS.mkdir(parents=True, exist_ok=True)
    np.savez(cache, **flags)
    return flags


def votes(a: dict, names: list[str], rows: np.ndarray) -> np.ndarray:
    """``vote_weights`` as ``model=auto`` calls it, on the out-of-fold ``rows``."""
    P = np.column_stack([a[f"oof_{n}"] for n in names])
    return vote_weights(P[rows], a["oof_y"][rows], a["oof_fold"][rows], a[f"oof_{BASELINE}"][rows],
                        base_column=names.index(BASELINE), min_folds=N_FOLDS)


def out_rows(in_range: np.ndarray, fold: np.ndarray) -> np.ndarray | None:
    """Out-of-range rows of the folds with at least ``MIN_IN_RANGE_ROWS`` of them; None with
    fewer than two such folds."""
    keep = np.zeros(len(fold), bool)
    for f in np.unique(fold):
        out = (fold == f) & ~in_range
        if out.sum() >= MIN_IN_RANGE_ROWS:
            keep |= out
    return keep if np.unique(fold[keep]).size >= 2 else None


def score(name: str, report: dict, saved: dict, flags: dict) -> dict:
    """Per target test RMSE of shipped auto, the gated rules, MLR; the weights."""
    rows = {}
    for t, row in report["targets"].items():
        a = saved[t]
        names = [k[4:] for k in a if k.startswith("oof_") and k not in ("oof_y", "oof_fold", "oof_in_range")]
        T = np.column_stack([a[f"test_{n}"] for n in names])
        mlr_only = np.eye(len(names))[names.index(BASELINE)]
        shipped = votes(a, names, np.ones(len(a["oof_y"]), bool))
        kept = np.array([row["auto"]["weights"].get(n, 0.0) for n in names])
        assert np.allclose(shipped, kept, atol=1e-9), (name, t, shipped, kept)
        inside = in_range_rows(a["oof_in_range"], a["oof_fold"])
        w_in = votes(a, names, inside)
        out = out_rows(a["oof_in_range"], a["oof_fold"])
        w_out = mlr_only if out is None else votes(a, names, out)
        f = flags[t].astype(bool)
        y = a["test_y"]
        gated = np.where(f, T @ w_in, T @ w_out)
        gated_mlr = np.where(f, T @ w_in, T @ mlr_only)
        rows[t] = {"auto": rmse(y - T @ shipped), "gated": rmse(y - gated), "gated_mlr": rmse(y - gated_mlr),
                   "mlr": rmse(y - a["test_mlr"]), "in_range": float(f.mean()),
                   "oof_in_range": float(a["oof_in_range"].mean()),
                   "oof_agree": float(flags[f"{t}.oof_agree"]),
                   "w_auto": _w(names, shipped), "w_in": _w(names, w_in),
                   "w_out": "mlr (too few)" if out is None else _w(names, w_out)}
    fam = report["family_mean"]
    best = min(fam, key=fam.get)
    mean = {k: float(np.mean([r[k] for r in rows.values()])) for k in ("auto", "gated", "gated_mlr", "mlr")}
    return {"targets": rows, "mean": mean, "best_family": (best, fam[best])}


def _w(names, w) -> str:
    return " ".join(f"{n} {v:.2f}" for n, v in zip(names, w) if v > 0)


def main(out: Path, names: list[str]) -> None:
    results = {}
    for name in names:
        report = json.loads((out / f"{name}.json").read_text())
        saved = {t: dict(np.load(out / f"{name}.{t}.npz")) for t in report["targets"]}
        flags = test_flags(name, report["overrides"], saved)
        r = results[name] = score(name, report, saved, flags)
        for t, row in r["targets"].items():
            print(f"  {name} {t}: auto {row['auto']:.3g} gated {row['gated']:.3g} gated_mlr "
                  f"{row['gated_mlr']:.3g} mlr {row['mlr']:.3g} | test in range {row['in_range']:.2f}, "
                  f"oof {row['oof_in_range']:.2f} (recomputed agree {row['oof_agree']:.3f}) | "
                  f"w_auto {row['w_auto']} | w_in {row['w_in']} | w_out {row['w_out']}")
        m, (bf, bv) = r["mean"], r["best_family"]
        print(f"{name}: auto {m['auto']:.3g} gated {m['gated']:.3g} gated_mlr {m['gated_mlr']:.3g} "
              f"mlr {m['mlr']:.3g} best {bf} {bv:.3g}", flush=True)
    for rule in ("auto", "gated", "gated_mlr"):
        ms = [r["mean"] for r in results.values()]
        bests = [r["best_family"][1] for r in results.values()]
        worse = max(m[rule] / m["auto"] - 1 for m in ms)
        geo = np.exp(np.mean([np.log(m[rule] / b) for m, b in zip(ms, bests)]))
        print(f"{rule}: better than MLR {sum(m[rule] < m['mlr'] for m in ms)}/{len(ms)}, within 10 % "
              f"of the best family {sum(m[rule] <= 1.1 * b for m, b in zip(ms, bests))}/{len(ms)}, "
              f"geometric mean / best {geo:.3f}, "
              f"worst against auto {100 * worse:+.1f} %")
    FLAGS.mkdir(parents=True, exist_ok=True)
    (FLAGS.parent / "gate57-results.json").write_text(json.dumps(results, indent=1, default=float))


if __name__ == "__main__":
    main(Path(sys.argv[1]), sys.argv[2:])
