"""Where a held-out campaign's CV gain from an initial-state lag comes from (stop 84, diag84b;
issue 34: "diagnose ... accepts nothing on clean data, and never leaves a record's test error more
than 2 % worse").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag84b.py trace CASE       # every cleared initial-state lag, taken apart

CASE: bench_diag84's (``planted:SEED`` / ``clean:SEED``, ``memory:planted:SEED``,
``faults:SCENARIO:KIND``, ``grinder:ROOT:SEED``).  ``trace``: the diagnosis as shipped; in each
round, each initial-state lag that clears the shipped bar is refitted fold by fold
(:class:`~thermocomp.apps.diagnose.shrink.PartialRidgePath` on the fold's training rows, as
``CrossValidator.run``) and its held-out predictions are formed four ways, the fit untouched:

* ``full``: as shipped (the held-out campaign's own start state);
* ``mean``: the held-out campaign's start offsets ``c(0) - A_0`` replaced by the mean of the
  fold's training campaigns' (the transient's shape kept, its own start gone);
* ``none``: the start block held at its training mean on the held-out rows (no transient, no
  start: only what the training campaigns' fit changed in the other coefficients);
* ``permuted``: bench_diag84's ``permuted_starts`` (starts permuted among the campaigns, CV
  refitted), ``full`` and ``none`` over ``ORDERS`` orders (median).

Each as the CV gain % over the round's current model, at the search's penalty (least CV error
over :data:`~thermocomp.apps.diagnose.shrink.ALPHAS`) and with that penalty chosen out of fold
(``nested``: each fold's penalty by leave-one-fold-out on its own training folds).  The held-out
campaigns' means: the current model's residual means' sum of squares (per row), and what ``none``
and ``full`` leave of it.  The leak test: each fold's held-out target shifted by +1 µm, the CV
run again: how far its held-out predictions move (the current model's and the candidate's).

Traced (2026-12-04, f64f5729's src; SEEN cases, a trace, not a score)
--------------------------------------------------------------------
(filled below)
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402

ORDERS = 49     # permuted orders per lag (bench_diag84's seed-0 draws; it took 199)


def _fold_paths(search, effects):
    """Each fold's design and its fitted path on the fold's measured training rows."""
    from thermocomp.apps.diagnose.shrink import PartialRidgePath

    p, cv = search.problem, search.cv
    out = {}
    for k in p.fold_ids:
        names = cv.selection(search.inputs(), k)
        Z = cv.design(names, effects, k)
        tr = p.train_rows(k) & p.measured
        out[k] = (Z, PartialRidgePath(Z[tr], p.y[tr], len(names)))
    return out


def _nested(search, effects, paths) -> np.ndarray:
    """Held-out predictions with each fold's penalty chosen on its own training folds only."""
    from thermocomp.apps.diagnose.shrink import ALPHAS, PartialRidgePath

    p, cv = search.problem, search.cv
    pred = np.full(len(p.y), np.nan)
    for k in p.fold_ids:
        err = np.zeros(ALPHAS.size)
        Z = paths[k][0]
        for j in p.fold_ids:
            if j == k:
                continue
            rows = p.train_rows(k) & p.train_rows(j) & p.measured
            tj = p.test_rows(j) & p.measured
            path = PartialRidgePath(Z[rows], p.y[rows], len(cv.selection(search.inputs(), k)))
            err += ((p.y[tj, None] - path.predict(Z[tj], ALPHAS)) ** 2).sum(axis=0)
        te = p.test_rows(k)
        pred[te] = paths[k][1].predict(Z[te], ALPHAS[[int(np.argmin(err))]])[:, 0]
    return pred


def _variants(search, effect, alpha_index: int) -> dict:
    """Held-out predictions ``full`` / ``mean`` / ``none`` (module docstring) at one penalty."""
    from thermocomp.apps.diagnose.features import principal_directions, transient
    from thermocomp.apps.diagnose.shrink import ALPHAS

    p, cv = search.problem, search.cv
    q = effect.initial_directions or len(effect.initial_state)
    offsets = cv._offsets(effect.initial_state)
    camp = np.asarray(p.campaigns, dtype=str)
    time_s = p.context["time"].to_numpy(float)
    out = {v: np.full(len(p.y), np.nan) for v in ("full", "mean", "none")}
    paths = _fold_paths(search, search.effects + [effect])
    a = ALPHAS[[alpha_index]]
    for k, (Z, path) in paths.items():
        tr, te = p.train_rows(k), p.test_rows(k)
        out["full"][te] = path.predict(Z[te], a)[:, 0]
        _, first = np.unique(camp[tr], return_index=True)
        o = offsets.copy()
        o[te] = offsets[tr][first].mean(axis=0)
        weights = (principal_directions(offsets[tr], p.campaigns[tr], effect.initial_directions)
                   if effect.learns else None)
        Zm = Z.copy()
        Zm[:, -q:] = transient(o, weights, time_s, p.campaigns, effect.tau_s)
        out["mean"][te] = path.predict(Zm[te], a)[:, 0]
        Zn = Z.copy()
        Zn[te, -q:] = path.z_mean[-q:]
        out["none"][te] = path.predict(Zn[te], a)[:, 0]
    return out, paths


def _gain(p, current, pred) -> float:
    ok = p.validated
    return 100 * (current.rmse - np.sqrt(np.mean((p.y[ok] - pred[ok]) ** 2))) / current.rmse


def _means_ss(p, residual) -> float:
    """The held-out campaigns' residual means' sum of squares, per scored row."""
    ok = p.validated
    camp = np.asarray(p.campaigns, dtype=str)
    return sum((ok & (camp == c)).sum() * residual[ok & (camp == c)].mean() ** 2
               for c in np.unique(camp[ok])) / ok.sum()


def _moved(search, effects, ref, alpha=None) -> float:
    """Largest move of a held-out prediction when that fold's own target is shifted by +1 µm:
    the CV as shipped (its penalty chosen on the pooled CV error), or at the fixed ``alpha``."""
    from thermocomp.apps.diagnose.shrink import PartialRidgePath

    p, cv = search.problem, search.cv
    y0, most = p.y, 0.0
    paths = _fold_paths(search, effects) if alpha is not None else None
    for k in p.fold_ids:
        te = p.test_rows(k)
        try:
            p.y = y0.copy()
            p.y[te & p.measured] += 1.0
            if alpha is None:
                moved = cv.run(search.inputs(), effects).prediction[te] - ref.prediction[te]
            else:
                Z, path = paths[k]
                tr = p.train_rows(k) & p.measured
                again = PartialRidgePath(Z[tr], p.y[tr], path.n_free)
                moved = again.predict(Z[te], [alpha]) - path.predict(Z[te], [alpha])
        finally:
            p.y = y0
        most = max(most, float(np.nanmax(np.abs(moved))))
    return most


def _analyse(search, ev, current) -> None:
    from dataclasses import replace
    from itertools import permutations
    from math import factorial

    import bench_diag84

    from thermocomp.apps.diagnose.shrink import ALPHAS

    p, cv, effect = search.problem, search.cv, ev.effect
    cpu = time.process_time()
    ia = int(np.flatnonzero(np.isclose(ALPHAS, ev.alpha or 0.0))[0])
    pred, paths = _variants(search, effect, ia)
    g = {v: _gain(p, current, x) for v, x in pred.items()}
    nested = _nested(search, search.effects + [effect], paths)
    if search.effects:      # the current model's penalty out of fold too
        base = _nested(search, search.effects, _fold_paths(search, search.effects))
        ok = p.validated
        nested = 100 * (1 - np.sqrt(np.mean((p.y[ok] - nested[ok]) ** 2)
                                    / np.mean((p.y[ok] - base[ok]) ** 2)))
    else:
        nested = _gain(p, current, nested)
    curve = [_gain(p, current, _variants(search, effect, j)[0]["full"]) for j in range(ALPHAS.size)]
    alone = cv.run(search.inputs(), search.effects + [replace(effect, initial_state=None,
                                                               initial_directions=None)])
    ss = [_means_ss(p, r) for r in (current.residual, p.y - pred["none"], p.y - pred["full"])]
    moved = (_moved(search, search.effects, current), _moved(search, search.effects + [effect], ev.result),
             _moved(search, search.effects + [effect], ev.result, float(ALPHAS[ia])))
    # permuted starts (bench_diag84's override of CrossValidator.features), full and none
    shipped_orders, bench_diag84.ORDERS = bench_diag84.ORDERS, ORDERS
    perm = {"full": [], "none": []}
    original = cv.features
    try:
        rmse = bench_diag84.permuted_starts(search, effect)     # full, at each order's least error
        perm["full"] = 100 * (current.rmse - rmse) / current.rmse
        # none: re-run the orders with the held-out start block at its training mean
        _, first, which = np.unique(np.asarray(p.campaigns, dtype=str), return_index=True,
                                    return_inverse=True)
        n = first.size
        rng = np.random.default_rng(search.options.seed)
        orders = (list(permutations(range(n)))[1:] if factorial(n) - 1 <= ORDERS
                  else [rng.permutation(n) for _ in range(ORDERS)])
        for order in orders:
            cv.features = _permuted_features(search, effect, original, order, first, which)
            try:
                pv, _ = _variants(search, effect, ia)
            finally:
                del cv.features
            perm["none"].append(_gain(p, current, pv["none"]))
    finally:
        bench_diag84.ORDERS = shipped_orders
    n = len(np.unique(np.asarray(p.campaigns, dtype=str)))
    print(f"  {p.target} round {len(search.effects) + 1} ({n} campaigns) {effect.title[:64]}: alpha "
          f"{ev.alpha or 0.0:.2g}", flush=True)
    print(f"    gain % full {g['full']:.1f} (search {ev.gain_pct:.1f}), nested alpha {nested:.1f}; "
          f"mean start {g['mean']:.1f}; none {g['none']:.1f}; permuted median full "
          f"{np.median(perm['full']):.1f} none {np.median(perm['none']):.1f}; the lag alone "
          f"{100 * (current.rmse - alone.rmse) / current.rmse:.1f}", flush=True)
    print("    gain % by penalty (every fold alike): "
          + " ".join(f"{a:.0e}:{c:.1f}" for a, c in zip(ALPHAS, curve)), flush=True)
    print(f"    held-out means SS (um^2/row) current {ss[0]:.4f} none {ss[1]:.4f} full {ss[2]:.4f} "
          f"(current MSE {current.rmse ** 2:.4f}); held-out prediction moved by its own +1 um: "
          f"current {moved[0]:.3g}, candidate {moved[1]:.3g}, at its penalty fixed {moved[2]:.3g} "
          f"({time.process_time() - cpu:.1f} s CPU)",
          flush=True)


def _test_side(search, effect, ds, alpha: float) -> str:
    """The round's current model and the candidate refitted in batch on every train row (the
    search's penalty ``alpha``, one fit) and scored on the test campaigns: ``full`` / ``mean`` /
    ``none`` as in CV (the test campaign's own start; the train campaigns' mean start; the block
    at its train mean)."""
    from dataclasses import replace

    from thermocomp.apps.diagnose.cv import CrossValidator, Problem
    from thermocomp.apps.diagnose.features import principal_directions, transient
    from thermocomp.apps.diagnose.shrink import PartialRidgePath
    from thermocomp.core.frame import stack

    p = search.problem
    train_ids, test_ids = list(ds.ids("train")), list(ds.ids("test"))
    names = list(search.inputs())
    m = stack({c: ds.campaigns[c] for c in train_ids + test_ids}, list(p.X.columns), [p.target], p.reference)
    camp = np.asarray(m.groups, dtype=str)
    every = Problem(m.X, m.Y[p.target].to_numpy(float), m.context, m.groups, m.groups, p.target,
                    reference=p.reference)
    cv = CrossValidator(every, search.cv.estimator)
    tr, te = np.isin(camp, train_ids), np.isin(camp, test_ids)
    y = every.y
    ok = te & np.isfinite(y)

    def fit(effects, last=None):
        Z = np.hstack([cv.inputs_matrix(names)] + [cv.features(e, names) for e in effects] + (
            [] if last is None else [last]))
        rows = tr & np.isfinite(y)
        return Z, PartialRidgePath(Z[rows], y[rows], len(names))

    Zc, pc = fit(search.effects)
    a = np.array([alpha if search.effects else 0.0])
    rmse0 = np.sqrt(np.mean((y[ok] - pc.predict(Zc[ok], a)[ok[ok], 0]) ** 2))
    lag = cv.features(replace(effect, initial_state=None, initial_directions=None), names)
    offsets = cv._offsets(effect.initial_state)
    weights = (principal_directions(offsets[tr], every.campaigns[tr], effect.initial_directions)
               if effect.learns else None)
    time_s = every.context["time"].to_numpy(float)
    start = transient(offsets, weights, time_s, every.campaigns, effect.tau_s)
    Z, path = fit(search.effects, np.hstack([lag, start]))
    q = start.shape[1]
    _, first = np.unique(camp[tr], return_index=True)
    o = offsets.copy()
    o[te] = offsets[tr][first].mean(axis=0)
    Zm = Z.copy()
    Zm[:, -q:] = transient(o, weights, time_s, every.campaigns, effect.tau_s)
    Zn = Z.copy()
    Zn[te, -q:] = path.z_mean[-q:]
    _, pa = fit(search.effects + [replace(effect, initial_state=None, initial_directions=None)])
    Za = np.hstack([cv.inputs_matrix(names)] + [cv.features(e, names) for e in search.effects] + [lag])
    out = {"full": Z, "mean": Zm, "none": Zn}
    r = {k: np.sqrt(np.mean((y[ok] - path.predict(v[ok], np.array([alpha]))[:, 0]) ** 2))
         for k, v in out.items()}
    r["alone"] = np.sqrt(np.mean((y[ok] - pa.predict(Za[ok], np.array([alpha]))[:, 0]) ** 2))
    return (f"test (batch, {len(test_ids)} campaigns) current {rmse0:.3f} -> " +
            ", ".join(f"{k} {v:.3f} ({100 * (rmse0 - v) / rmse0:+.1f} %)" for k, v in r.items()))


def _permuted_features(search, effect, shipped, order, first, which):
    """bench_diag84's permuted ``CrossValidator.features`` for one order."""
    from dataclasses import replace

    from thermocomp.apps.diagnose.features import principal_directions, transient

    cv, p = search.cv, search.problem
    time_s = p.context["time"].to_numpy(float)

    def features(e, names, fold=None):
        if e != effect:
            return shipped(e, names, fold)
        fold = fold if e.learns else None
        lag = shipped(replace(e, initial_state=None, initial_directions=None), names)
        offsets = cv._offsets(e.initial_state)[first][np.asarray(order)][which]
        weights = None
        if e.learns:
            rows = p.train_rows(fold)
            weights = principal_directions(offsets[rows], p.campaigns[rows], e.initial_directions)
        return np.hstack([lag, transient(offsets, weights, time_s, p.campaigns, e.tau_s)])
    return features


def trace(case: str) -> None:
    """Every initial-state lag clearing the shipped bar in ``case``'s diagnosis, taken apart;
    the diagnosis itself as shipped (the test only measured)."""
    import bench_diag84

    from thermocomp.apps.diagnose import diagnose
    from thermocomp.apps.diagnose.search import Search

    ds, comp, targets, options, deployed_of = bench_diag84._case(case)
    shipped = Search._family_bar

    def bar(self, evals, current):
        shipped(self, evals, current)
        cleared = [ev for ev in evals if ev.effect.initial_state and ev.clears_bar]
        for ev in sorted(cleared, key=lambda e: -e.gain_pct)[:2]:
            _analyse(self, ev, current)
            if len(ds.ids("test")):
                print("    " + _test_side(self, ev.effect, ds, ev.alpha or 0.0), flush=True)

    Search._family_bar = bar
    try:
        d = diagnose(ds, comp, targets=targets, options=options, deployed_of=deployed_of)
    finally:
        Search._family_bar = shipped
    for t, x in d.targets.items():
        j = d.to_json(t)
        print(f"{case} {t}: accepted {[e.effect.title for e in x.accepted]}; test "
              f"{j['before']['test_rmse']:.4f} -> {j['after']['test_rmse']:.4f}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
