"""auto's validation against the test on the vtl and the jig grinder (issue 34, stop 60): forensics.

    .venv/bin/python benchmarks/bench_historian60.py write ROOT; ... init ROOT --data vtl
    .venv/bin/python benchmarks/bench_new_machines60.py write ROOT; ... init ROOT --data jig_grinder
    .venv/bin/python benchmarks/bench_auto_vtl60.py folds ROOT vtl [FAMILY ...]
    .venv/bin/python benchmarks/bench_auto_vtl60.py folds ROOT jig_grinder [FAMILY ...]
    .venv/bin/python benchmarks/bench_auto_vtl60.py folds ROOT vtl gap=0     # the refused rule's folds

One process per record: auto's own folds (``AutoRegressor._folds`` of the train split, as its
``fit`` makes them, the scheme the stage sets), every family fitted on each fold's fit rows and
predicted as ``_validate`` predicts (the same rows, the same frame); then every family fitted on
the whole train split and scored on the test as ``run`` scores it (``split_residuals``: the
state carried over where the test continues the train record).  Printed per target: each
fold's fit rows, scored rows, each family's RMSE there and its ratio to MLR's, the penalty a
lag family chose (``alpha_``), and the RMSE by hours since the start of the scored stretch
(a fold's block, or each campaign of it; the test's campaign) -- where a lag family would lose
its scores to a cold start.  The test split chooses nothing here: it is only scored.

Cut to save CPU (a shared 2-core machine): the families default to mlr, lagbank and hammerstein
(the two lag families auto's blend on the vtl missed, and the baseline); lstm, arx and pcr are
left out (the vtl's auto run took 374 s CPU, most of it lstm's folds).

The rule written down before it was scored (22:02 UTC, after the fold forensics below, which
read the validation folds only, and before any test RMSE of it): **one record whose test continues
it, the forward folds leave no gap** (``gap_blocks`` 0 where the test campaign continues the train
record, ``data.reference`` none).  Why: the gap (half a block, 19 h on the vtl) was put between a
fold's fit and its block so that the fit's slow states "do not reach into the block"; but the
test a continued record is scored on starts at the very row after the final fit's last one, its
slow states reaching into it, so the folds grade a harder extrapolation (19 h further from the
fit, on a fit 19 h shorter) than the test asks of the final model.  Where the test is a separate
campaign (its state restarted) the gap stays.  Scored on (chosen now): the records this rule can
move, one record with a continuing test -- ``vtl`` (auto before: 0.379 / 0.637, the historian60
docstring, the same code) and ``fl_thermal`` 90/10 (before 2.475, README) -- with
``model.estimator.gap_blocks=0`` on the command line (the rule's effect there exactly); every
other record judged (the jig grinder's and hmc/edm's campaigns, bench_auto_rank's multi-campaign
records, fl_thermal's authors' split, scored by its val split) is untouched by construction (the
gap is used only by one record's forward folds).  Adopt only if: better than MLR on at least as
many records as now, no record > 2 % worse than now, the geometric mean over the best family not
worse, fl_thermal's acceptance kept (90/10 below MLR's 4.06).

Measured (2026-11-30, ``folds``: vtl 66 s + 19 s CPU, jig 5 s).  **How the folds are predicted.**
vtl: one record, ``data.reference=auto`` -> none (``run``: "VTL01_history_test continues
VTL01_history_train: its state is carried over"), 5 forward-chaining folds, each predicted from
row 0 (the record's start) through its fit rows and the gap to the block's end: WARM, in the
test's frame, as the test is (the state carried over from the train record).  jig: 8 sessions,
reference first_sample (the program zeroes the probes), 3 blocked forward folds (sessions 4, 5, 6
held out in turn), each session predicted from its own first row, as the 2 test sessions are.
So the folds are scored as the test is on both machines; no cold start anywhere.  **Error by hours
since the stretch's start** (0-1 / 1-4 / 4-12 / 12+ h): the lag families do NOT lose their fold
scores in the first hours; they lose them late: vtl E_Z fold 1 lagbank 0.32 / 0.36 / 0.54 / 1.60
(MLR 0.81 / 0.79 / 0.81 / 0.77), hammerstein 0.90 .. 1.56; vtl E_X fold 0 lagbank 0.31 / 0.35 /
0.54 / 1.37 (MLR 0.55 .. 0.58); jig E_Z fold 1 lagbank 0.49 / 0.63 / 0.85 / 1.09 (MLR 0.49 /
0.48 / 0.42 / 0.47), its mean residual -0.84 µm.  Per fold, RMSE over MLR's (fit rows):

    vtl E_X      fit  61k   75k   88k  102k  116k | test (136k)
      lagbank        1.96  0.70  0.68  0.73  0.69 | 0.58
      hammerstein    1.68  0.79  0.41  0.58  0.36 | 0.51
    vtl E_Z
      lagbank        0.79  1.74  1.25  0.52  0.58 | 0.53
      hammerstein    0.68  1.88  0.92  0.64  0.46 | 0.59
    jig E_Z      fit 3 / 4 / 5 sessions           | test (6)
      lagbank        1.52  2.04  1.05             | 0.84
      hammerstein    1.42  1.50  0.82             | 1.42

Pooled (auto's validation_): vtl E_X mlr 0.672, lagbank 0.675, hammerstein 0.545 (test 0.586 /
0.339 / 0.301); E_Z 0.962 / 0.952 / 0.899 (test 0.737 / 0.391 / 0.435); jig E_Z 0.411 / 0.646 /
0.506 (test 0.464 / 0.389 / 0.661).  The vtl's first fold (fit on the first 7.1 days, Mon 0 h to
Mon 2 h of week 2) extrapolates on every row of its block (0.00 / 0.00 / 0.00 / 0.07 of the rows
inside the fit's input range, by leverage); every later fold and the test lie inside (1.00).  The
jig's folds lie inside too (0.88-1.00; its test 0.73-0.91).  The vtl's last two folds (fits of
75-85 % of the train) rank as the test does (lagbank 0.52 / 0.58 against 0.53 on E_Z); the early
ones, on 45-65 %, do not: a learning curve of the lag families, whose fits on a short record
drift late in the next block (mean residual -1.1 µm, vtl E_Z fold 1).  Penalties: lagbank
alpha 3.16 in every vtl E_X fold against 1 finally, 0.316 on E_Z in folds 0-3 and the final
(3.16 in fold 4); on the jig E_Z 0.316 / 1 / 0.01 against 0.0316.  lstm not run here (CPU).

**The gap rule, scored once (``thermocomp run model=auto model.estimator.gap_blocks=0``, every
default candidate; test RMSE µm, auto before -> after; MLR; best single family).**  ``vtl`` E_X
0.379 -> 0.3014 (MLR 0.586, hammerstein 0.301), E_Z 0.637 -> 0.4136 (MLR 0.737, lagbank 0.391):
within 10 % of the best family on both (+0.1 %, +5.8 %; before +26 %, +63 %); its validation
E_X hammerstein 0.412 / lstm 0.663 / mlr 0.669 / lagbank 0.761, blend hammerstein 0.98; E_Z
hammerstein 0.607 / mlr 0.770 / lstm 0.770 / lagbank 0.796, blend hammerstein 0.67 / mlr 0.23 /
lagbank 0.09; 284 + 39 s CPU.  ``fl_thermal`` 90/10 (mean over 5 channels) 2.475 -> **3.186**
(MLR 4.06; before re-measured on this code with ``model.estimator.scheme=forward``: 2.4753, 54 s
CPU; after 45 s): ch1 2.893 -> 3.867, ch3 1.969 -> 3.392, ch4 1.876 -> 2.418, ch5 2.194 -> 2.872
(ch3 / ch4 lost lstm's 0.41 / 0.57 for hammerstein 0.99).  **Refused**: +28.7 % on fl_thermal,
far above the 2 % bound (better than MLR on both records either way; the jig, hmc / edm,
bench_auto_rank's campaign records and the authors' split are untouched by construction).  The
vtl's folds without the gap (``folds ROOT vtl gap=0``, 70 + 18 s CPU, validation only): the first fold's
fit now takes in week 2's Monday and its block lies inside its inputs (1.00 / 1.00 / 0.94 / 1.00
of the rows, before 0.00); RMSE over MLR's per fold, E_X lagbank 2.34 / 1.28 / 0.55 / 0.62 / 0.65,
hammerstein 1.20 / 0.55 / 0.39 / 0.56 / 0.37 (test 0.58 / 0.51); E_Z lagbank 0.46 / 2.02 / 0.47 /
0.59 / 0.60, hammerstein 1.23 / 0.83 / 0.52 / 0.53 / 0.47 (test 0.53 / 0.59): hammerstein's
second fold no longer fails (E_Z 1.88 -> 0.83), so it takes the votes.  On fl_thermal the same
shift of every block to its fit's end took the votes from lstm: a gap is no
difference between folds and test that one record can settle.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402

ARGS = {"vtl": lambda root: [f"hydra.searchpath=[file://{root}/init-vtl/conf]", "data=VTL01_history"],
        "jig_grinder": lambda root: [f"hydra.searchpath=[file://{root}/init-jig_grinder/conf]",
                                     "data=jig_grinder"]}
FAMILIES = ("mlr", "lagbank", "hammerstein")
HOURS = (0.0, 1.0, 4.0, 12.0, np.inf)      # bins of hours since a scored stretch's start


def _since_start(time_s: np.ndarray, groups, rows: np.ndarray) -> np.ndarray:
    """Hours since the start of each contiguous stretch of ``rows`` within one campaign."""
    idx = np.asarray(rows)
    camp = np.zeros(len(time_s)) if groups is None else np.asarray(groups, dtype=object)
    out = np.empty(len(idx))
    start = 0
    for k in range(1, len(idx) + 1):
        if k == len(idx) or idx[k] != idx[k - 1] + 1 or camp[idx[k]] != camp[idx[k - 1]]:
            out[start:k] = (time_s[idx[start:k]] - time_s[idx[start]]) / 3600.0
            start = k
    return out


def _share_by_hours(flags: np.ndarray, hours: np.ndarray) -> str:
    """Share of rows per bin of hours (here: rows inside the fit's range of inputs)."""
    return " ".join(f"{flags[(hours >= lo) & (hours < hi)].mean():.2f}"
                    if ((hours >= lo) & (hours < hi)).any() else "  -  "
                    for lo, hi in zip(HOURS[:-1], HOURS[1:]))


def _by_hours(resid: np.ndarray, hours: np.ndarray) -> str:
    parts = []
    for lo, hi in zip(HOURS[:-1], HOURS[1:]):
        sel = (hours >= lo) & (hours < hi)
        parts.append(f"{np.sqrt(np.mean(resid[sel] ** 2)):.3f}" if sel.any() else "  -  ")
    return " ".join(parts)


def folds(root: Path, record: str, families=FAMILIES, gap_blocks: float | None = None) -> None:
    from bench_auto_rank import _test, setup
    from sklearn.base import clone

    from thermocomp.core.compensator import _simulation
    from thermocomp.core.context import TIME, groups_of, subset
    from thermocomp.core.metrics import rmse
    from thermocomp.core.model_selection.extrapolation import within_range
    from thermocomp.core.models import MLR
    from thermocomp.core.models.auto import BLOCKS_ONE, FORWARD_ONE, _scheme
    from thermocomp.shell.builders import build_compensator

    cfg, ds, train = setup(ARGS[record](root) + [f"model.candidates=[{','.join(families)}]"])
    comp = build_compensator(cfg, ds=ds)
    auto = comp.estimator
    ests = {n: (MLR() if n == "mlr" else auto.candidates[n]) for n in families}
    print(f"{record}: reference {comp.reference}, train {ds.ids('train')}, test {ds.ids('test')}")
    m = clone(comp).set_params(estimator=MLR()).fit(train).stacked(train)
    ctx = _simulation(m.context)
    X = m.X.to_numpy(float)
    groups = groups_of(ctx)
    time_s = np.asarray(ctx[TIME], float) if TIME in ctx else np.arange(len(X)) * 1.0
    a = clone(auto) if gap_blocks is None else clone(auto).set_params(gap_blocks=gap_blocks)
    a.scheme_ = _scheme(a.scheme, groups)
    if a.scheme_ == FORWARD_ONE:
        a.scheme_ = BLOCKS_ONE.get(a.one_record, FORWARD_ONE)
    fold_rows = a._folds(groups, len(X))
    print(f"scheme {a.scheme_}, {len(fold_rows)} folds, {len(X)} train rows")
    singles = {n: clone(comp).set_params(estimator=clone(e)).fit(train) for n, e in ests.items()}
    tests = {n: _test(s, ds) for n, s in singles.items()}
    test_ctx = _simulation(singles["mlr"].stacked({c: ds.campaigns[c] for c in ds.ids("test")}).context)
    t_test = np.asarray(test_ctx[TIME], float)
    h_test = _since_start(t_test, groups_of(test_ctx), np.arange(len(t_test)))
    for target in m.Y.columns:
        y = m.Y[target].to_numpy(float)
        print(f"\n== {target}   (RMSE µm; by hours since the stretch's start "
              f"{'/'.join(f'{lo:g}-{hi:g}' for lo, hi in zip(HOURS[:-1], HOURS[1:]))})")
        pooled = {n: [] for n in families}
        for k, (fit, pred, score) in enumerate(fold_rows):
            srows = np.flatnonzero(score)
            hours = _since_start(time_s, groups, srows)
            first = np.flatnonzero(pred)[0]
            inside = within_range(X, fit, score)[score]
            print(f"fold {k}: fit {fit.sum()} rows, predicted from row {first}, scored rows "
                  f"{srows[0]}..{srows[-1]} ({len(srows)}), {hours.max():.1f} h; inside the fit's "
                  f"input range [{_share_by_hours(inside, hours)}]")
            base = None
            for n in families:
                est = clone(ests[n]).fit(X[fit], y[fit], context=subset(ctx, fit))
                yhat = np.asarray(est.predict(X[pred], context=subset(ctx, pred)), float)[score[pred]]
                r = y[score] - yhat
                pooled[n].append(r)
                base = rmse(r) if n == "mlr" else base
                alpha = getattr(est, "alpha_", getattr(getattr(est, "lagbank_", None), "alpha_", None))
                print(f"  {n:12s} {rmse(r):.3f}  x{rmse(r) / base:.2f}  [{_by_hours(r, hours)}]"
                      f"  mean {r.mean():+.3f}"
                      + (f"  alpha {alpha:.3g}" if alpha is not None else ""))
        print("pooled validation: " + ", ".join(
            f"{n} {rmse(np.concatenate(pooled[n])):.3f}" for n in families))
        meas = tests["mlr"][0][target]
        Xall = np.vstack([X, singles["mlr"].stacked({c: ds.campaigns[c] for c in ds.ids("test")}
                                                    ).X.to_numpy(float)])
        fit_all = np.arange(len(Xall)) < len(X)
        inside = within_range(Xall, fit_all, ~fit_all)[~fit_all]
        print(f"test ({len(meas)} rows, {h_test.max():.1f} h; inside the train's input range "
              f"[{_share_by_hours(inside, h_test)}]):")
        for n in families:
            r = meas - tests[n][1][target]
            est = singles[n].estimators_[target]
            alpha = getattr(est, "alpha_", getattr(getattr(est, "lagbank_", None), "alpha_", None))
            print(f"  {n:12s} {rmse(r):.3f}  x{rmse(r) / rmse(meas - tests['mlr'][1][target]):.2f}  "
                  f"[{_by_hours(r, h_test)}]  mean {r.mean():+.3f}"
                  + (f"  alpha {alpha:.3g}" if alpha is not None else ""))


def main(argv=None) -> int:
    def folds_of(root: str, record: str, *words: str) -> None:
        """``gap=H`` among the words: the gap in blocks; the others the families."""
        gap = next((float(g.split("=", 1)[1]) for g in words if g.startswith("gap=")), None)
        folds(Path(root), record, tuple(g for g in words if "=" not in g) or FAMILIES, gap)

    return run_commands(__doc__, {"folds": folds_of}, sys.argv[1:] if argv is None else argv)


if __name__ == "__main__":
    raise SystemExit(main())
