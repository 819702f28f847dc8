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

Traced (2026-12-04, f64f5729's src; SEEN cases, a trace, not a score; no new draw, no seed used)
------------------------------------------------------------------------------------------------
The round's two best cleared initial-state lags (CV gain order; ``*``: the shipped choice's row
where it is one of them).  CV gain % over the round's current model: as searched (least-error
penalty), at penalty 0 (least squares: no penalty read from any held-out target), the same lag
without its start block (``alone``), the block fitted but held at its train mean on the
held-out campaign (``none``), its start set to the train campaigns' mean (``mean``), its own
(``own`` = as searched); bench_diag84's permuted starts (49 orders, median, ``full`` / ``none``);
the held-out campaigns' residual means' sum of squares per row (µm², current -> none -> own; the
current MSE); the batch refit on the 8 (39) train campaigns scored on the 4 test campaigns, %
over the current model (alone / none / mean / own)::

  case / target, lag              search   a=0  alone   none   mean    own  permuted full/none
  planted:8457 E_X T_amb 14400 s    46.9  46.9    6.7    9.7   12.5   46.9  13.5 / 14.7
    T_bearing_f2 900 s              46.6  46.6   41.4   35.9   36.5   46.6  32.0 / 35.8
  clean:8178 E_Z *T_bearing_f3 900  26.4  26.4   18.4   14.3   14.3   26.4   8.0 / 14.6
    T_bearing_f2 900 s              24.8  24.8   12.8   11.2   11.4   24.8   3.1 /  9.5
  clean:8075 E_Y *T_box1 3600 s     50.5  50.4    0.0   27.1   28.9   50.5   9.1 / 12.0
  clean:8170 E_X T_box1 1800 s      22.5  22.3   14.5   12.4   14.0   22.5   5.8 /  4.4
  planted:6 E_Y rd 2 *T_motor2 7200 21.0  20.7   -5.2  -14.6  -12.6   21.0 -13.1 / -13.0
  planted:959 E_Y rd 2 *T_motor2    18.8  18.3   19.3   12.3   14.5   18.8   5.9 / 14.2
  climate_room:drift E_Z *inputs    15.3  15.1   15.3   14.9   14.9   15.3  14.1 / 15.1
  climate_room:stuck E_X *inputs    25.3  24.5   24.7   23.7   23.7   25.3  23.7 / 24.4
  climate_room:stuck E_Z inputs     19.2  18.1   20.0   18.9   19.0   19.2  18.7 / 19.6

  case / target, lag              means SS current / none / own (MSE)   test % alone / none / mean / own
  planted:8457 E_X T_amb 14400 s  0.76 / 0.58 / 0.10 (1.05)             +3.0 / -25.8 / -14.5 / -57.6
    T_bearing_f2 900 s            0.76 / 0.21 / 0.08                   -60.2 / -47.2 / -46.9 / -72.9
  clean:8178 E_Z *T_bearing_f3    0.29 / 0.20 / 0.11 (0.49)             -0.3 / -15.0 / -17.5 / -23.0
    T_bearing_f2 900 s            0.29 / 0.23 / 0.12                    +2.8 / -15.1 / -17.6 / -23.9
  clean:8075 E_Y *T_box1 3600 s   0.69 / 0.31 / 0.06 (0.92)             -1.1 / +10.6 / +11.0 /  -6.5
  clean:8170 E_X T_box1 1800 s    0.14 / 0.08 / 0.03 (0.33)             -3.0 /  +4.2 /  +3.4 / -17.1
  planted:6 E_Y rd 2 *T_motor2    1.08 / 1.95 / 0.57 (2.44)            +12.9 / +19.0 / +22.7 / +34.4
  planted:959 E_Y rd 2 *T_motor2  1.40 / 1.03 / 0.83 (2.67)            +25.4 / +23.6 / +24.7 / +33.7
  climate_room:drift E_Z *inputs  .068 / .046 / .045 (.145)            +11.4 /  +5.8 /  +5.8 / +14.0
  climate_room:stuck E_X *inputs  .149 / .096 / .085 (.443)            +12.9 /  +8.8 /  +8.8 / +17.5
  climate_room:stuck E_Z inputs   .132 / .104 / .103 (.343)             +2.0 /  +1.2 /  +1.2 /  +8.6

(planted:6 / 959: the round-2 lag of T_motor2 7200 s, 2 directions; climate_room: the lag of
the model inputs 900 s, 39 campaigns (stuck E_Z's shipped T_nc_tool_motor 900 s was not of
its round's two best); 8075's T_box2 row is T_box1's to 0.4; 8170's shipped
T_nose 900 s was not of its round's two best; the test's "current" is the batch refit of the
round's model: 8075 0.656, 8457 0.606, 8178 0.638, 8170 0.797 -- the shipped befores --,
planted:6 1.828, 959 1.537, climate drift 0.386, stuck 0.602 / 0.531 with the removed sensor out:
bench_diag84's "nothing" rows.)

1. Nothing of the held-out campaign's own target reaches its prediction except one number: the
   penalty on the effect features, chosen on the CV error pooled over all folds.  The held-out
   target shifted by +1 µm moves that campaign's predictions by 0.16-1.51 µm as searched (the
   penalty switches, e.g. 8075 0.001 -> 1.0) and by exactly 0 at a fixed penalty, every case;
   the current model's by ~1e-14 (planted:959 round 2: 2.11, its own penalty on the position
   effect).  What that choice is worth: the gain at penalty 0 is 0-1.1 points under the searched
   one (46.9 / 46.9, 50.4 / 50.5, 18.3 / 18.8, 18.1 / 19.2, ...).  The lag's state (``z_0 = u_0``), the start
   offsets ``c(0) - A_0`` and the directions (the train campaigns' offsets) read inputs and
   context only.  So neither (1) a target-fitted reference nor (2) a start set from the
   campaign's own samples carries the gain.
2. What ANY campaign's start gains (the permuted orders) is mostly what the structure gains
   without a start.  The same lag with no start block gains 12.8-41.4 % in CV on 8 of the 11
   rows (8457's f2 41.4, 8178 18.4 / 12.8, 8170 14.5, 959 19.3, climate_room 15.3-24.7), 6.7
   on 8457's T_amb, 0.0 on 8075, -5.2 on planted:6; the block fitted on the train campaigns but
   given no start on the held-out one (``none``) gains 9.7-35.9 % (planted:6 -14.6), 27.1 on
   8075 where the lag alone gains nothing: there the block's fit re-estimates the other
   coefficients (the held-out levels' SS 0.69 -> 0.31 with nothing of the held-out campaign in
   it).  The permuted medians sit at or under ``none`` on 9 of the 11 rows (a wrong start costs),
   over it by 3.8 / 1.5 on 8457's T_amb / planted:6; the permuted ``none`` is within 2 points of
   the real ``none`` on 8 rows, under it on 8075 / 8170 (12.0 / 27.1, 4.4 / 12.4: the real starts
   re-fit the train campaigns better), over it on 8457's T_amb (14.7 / 9.7).  That is (3): a
   real part of the structure that is not the held-out start -- the lag's own dynamics and the
   block's fit on the train campaigns -- which permuting the starts keeps; diag84's
   randomization thus tested only the own start's part (own - permuted), as its null said.
3. The own start's part (own - mean start) is real CV evidence, not a leak: 34.4 (8457 T_amb),
   12.1 / 13.4 (8178), 21.6 (8075), 8.5 (8170), 33.6 (planted:6), 4.3 (959), 0.4 / 1.6 / 0.2
   (climate_room); it is where the held-out campaign's LEVEL comes from (means SS none -> own:
   0.58 -> 0.10, 0.20 -> 0.11, 0.31 -> 0.06, 1.95 -> 0.57, ...; at the searched penalty, whose
   choice is worth <= 1.1 points).  So the lead's inference holds for climate_room and mostly
   for 959 (own start +0.4 / +4.3 in CV), not for planted:6 (everything is the start: mean
   -12.6, own 21.0) nor for the spurious ones.
4. On test the own start's part has the sign of the verdict: -43.1 (8457), -5.5 (8178), -17.5
   (8075), -20.5 (8170) on the spurious, +11.7 (planted:6), +9.0 (959), +8.2 / +8.7 / +7.4
   (climate_room) on the kept -- while in CV it is positive on every row, its size no guide (8457's 34.4 and
   planted:6's 33.6).  The held-out-level prediction from the start that CV measures among the
   8 train campaigns does not carry to the 4 test campaigns of the clean draws (they start
   elsewhere: bench_diag83b item 5); nothing CV reads here separates the two.
5. ``none`` / ``mean`` as a deployed form (the block fitted, the new campaign given the train
   mean start) is no way out either: on test +10.6 / +4.2 on 8075 / 8170 but -15.0 / -25.8 on
   8178 / 8457, and it gives up 8-15 points of the kept rows' test gain.
6. The penalty chosen out of fold (``nested``: each fold's by leave-one-fold-out on its training
   folds, the current model's too) gives 44.2 / 23.6 (8457), 21.2 / 20.7 (8178), 48.4 (8075),
   21.2 (8170), 19.3 / 5.2 (planted:6), -25.8 / -26.9 (959: an inner choice of a large penalty
   shrinks the round's position effect too; at penalty >= 0.01 alike in every fold the gain is
   <= 0 there), 14.4 (climate drift), 25.0 / 23.6 / 18.2 (stuck).  With 7 inner campaigns the choice is
   noisy; as a fix of item 1's one read, by these numbers it would refuse the kept 959's lag
   (nested -26 %) and leave every spurious row at 21-48 % -- not made (no rule, no src change;
   not scored as a rule).

Verdict: (3).  No leak carries the gain: the one read of the held-out target (the pooled
penalty) is worth <= 1.1 points.  ANY start gains because most of such a candidate's CV gain
is not its start: the lag without a start, and the block's fit on the train campaigns.  The own
start's part is an honest CV gain in the held-out levels on every traced row, harmful on test
on the spurious rows and helpful on the kept; what separates them is not in these numbers.
CPU: 0.4-0.7 s per lag on 8 campaigns, 19-25 s on climate_room's 39 (49 orders, the nested
penalty, the shift test); each case traced twice, the same numbers.  What remains: why the own
start's CV prediction of the held-out levels among the 8 train campaigns fails on the clean
draws' test campaigns and holds on the kept rows' -- not answered here.
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
