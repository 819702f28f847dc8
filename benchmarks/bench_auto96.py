"""A TRAIN-SIDE signal telling a lag family that will fail on new data from one that will not, inside
``model=auto``'s blend (issue 34; stop 96, auto96; follow-up of bench_auto95b's "next").

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_auto96.py one OUT RECORD ...          # one-campaign records: fit, keep arrays
    python benchmarks/bench_auto96.py signals SIDE WORK ...       # per target with lag weight: signals
    python benchmarks/bench_auto96.py table SIDE SIGNAL LIMIT WORK ... # the prototype rule
    python benchmarks/bench_auto96.py amp ROOT OUT RECORD ...     # refits: amplification
    python benchmarks/bench_auto96.py leo ROOT OUT RECORD ...     # refits: leave the extremes out
    python benchmarks/bench_auto96.py stab ROOT OUT RECORD ...    # refits: fold models' spread

Two kinds of stored rows, both fitted on the record's train part only (nothing of a test is read
to compute a signal; the tests are only scored):

* bench_automore69's ``rows`` (bench_auto91's ``rows ROOT WORK RECORD ...``, a WORK holding
  ``automore.jsonl`` and ``pred/``): the 22-record table's records, scored on the 12-16 NEW
  campaigns of their machine; the record figure is the mean over targets of the pooled RMSE, auto
  over MLR (bench_remeasure62's).
* ``one`` (bench_auto_rank's ``main``: auto with ``keep_oof`` and every candidate alone, their
  out-of-fold and test predictions in OUT/RECORD.TARGET.npz, the weights in OUT/RECORD.json):
  bench_auto95's one-campaign records (:data:`RECORDS`: its 10 seen, and FRESH 9719-9728), scored
  on their own test; the record figure is the mean over targets of auto's RMSE / MLR's
  (bench_auto95's).

``signals``: per target where a lag family (``lagbank`` / ``hammerstein``: a ``tau_max_s``, 48 h)
holds weight, the heaviest such family L and, from its out-of-fold predictions against MLR's on the
validation folds (``fold_ratios``: the votes' own measure, fold k's summed squared error over
MLR's), the candidate signals (:data:`SIGNALS`), beside the target's test RMSE over MLR's: auto's
and L's alone.  ``table``: the prototype rule -- where SIGNAL of L exceeds LIMIT, L's weight goes
to MLR (the other members keep theirs) -- scored from the stored test predictions (a blend predicts
``sum w_i * member_i``: no refit), per record main -> rule.  ``amp`` / ``leo`` / ``stab`` (ROOT
as bench_auto91's, the records of either kind) refit on the train record only and write per record
a json under OUT, which ``signals`` / ``table`` read from SIDE/amp, SIDE/leo, SIDE/stab:

* ``amp``: amplification -- per target the sum over inputs of the RMS of each input's part of the
  train prediction (the prediction less the one with that input held at its first sample) over the
  RMS of their sum: a prediction that is a difference of large parts extrapolates badly; the lag
  family's over MLR's.
* ``leo``: leave the extremes out -- per input and tail (top / bottom tenth of its rows), MLR and
  the lag families fitted on the other rows, the record predicted in free run, scored on the held
  rows (:func:`extreme_folds`); the lag family's pooled squared error over MLR's (``leo_top``: the
  top tails only, inputs beyond the fitted envelope).
* ``stab``: coefficient stability -- each family fitted on each of auto's validation folds' fit
  rows predicts the WHOLE train record; the RMS over rows of the spread across the fold models, the
  lag family's over MLR's.
* from the stored out-of-fold predictions (:data:`SIGNALS`): the lag family's fold ratios'
  dispersion ``disp`` (fold-gain variance, log), ``last`` (the fold nearest the test), ``trend``
  (slope of the log ratio over the folds: a gain fading with more data), ``worst``, ``cv``.

BAR (written and committed before ``table`` was run on any signal, before any FRESH seed): a
prototype rule (one signal, one limit; :func:`_moved`: the lag family's weight to MLR) is built
into src only if on the SEEN records (the 22-record table's records stored here and bench_auto95's
10 one-campaign records) (1) no record's auto / MLR is > 1 % above main's, (2) the geometric mean of
auto / MLR is below main's, (3) fewer records lose to MLR (> 1.0) than on main.  Then FRESH 9719-9728
(bench_auto95's :data:`FRESH`) scored ONCE through src: no record > 2 % worse than main, geo not
above main's.  (1)-(3) failing for every signal: no src, no fresh seed drawn (TRACED), the
signal table kept as the finding.  Limits tried (named here, from the signal table's gaps on the
seen targets): ``last`` 0.9, ``trend`` 0.3, ``amp`` 0.9, ``disp`` 1.2.

REFUSED on the SEEN gate: src as on main; the rule built is ``benchmarks/auto96_rule.patch`` (against
bd118abf: ``model.estimator.lag_fade`` (0.3), ``blend.fading_gain``, conf, docs and its test; apply
it to run ``ways``, whose key main does not have).

Measured (2026-12-06, bd118abf + the bench; nice, ``OMP_NUM_THREADS=1``, 2 cores shared, load 5-15;
CPU: ``rows`` of the 22 (bench_auto91's, ROOT /tmp/auto96/root written by bench_iso67 / stranger68 /
stranger66 / automore69 / new_machines57, 59, 60 ``write`` + ``init``; col5791 / col1403 reused from
auto95b's WORK at 34af1fcb: no model src changed since) 79 + 21 + 37 + 71 s; ``one`` on the 10 seen
42.7 s; ``amp`` 36 s; ``ways`` on the fresh 57.4 s).  Every main figure reproduces the tables it
comes from (col5791 1.258, col1403 1.311, lab5401 1.070, iso_a 1.083, mtc_b 1.075, hmc 1.005; lr9587
1.059, sw9697 1.044, lr9641 0.637).

Signals per target where a lag family holds weight (L: hm hammerstein / lb lagbank, w its weight;
r_k its fold SSE / MLR's; amp / leo_top / stab measured on 19 / 14 / 19 records, ``-``: not run;
auto and L alone: test RMSE / MLR's, the 22's on their new campaigns, the one-campaign 10 own)::

  record     target    L  w    r_k (forward folds, in order)  disp trend  last   amp leo_t  stab  auto  L
  lr9211     E_Z       hm 0.54 0.27 2.26 0.09 0.66 0.19   1.11 -0.20  0.19  0.47  0.61  3.19  0.761 1.211
  lr9212     E_Z       hm 0.77 1.18 0.65 0.71 1.13 0.70   0.26 -0.05  0.70  0.99  0.51  1.79  0.760 0.736
  lr9587     E_Z       lb 0.10 0.79 0.10 0.37 0.57 6.39   1.34  0.59  6.39  0.54  0.35  1.31  1.059 1.545
  lr9640     E_Z       hm 0.13 6.86 0.05 0.09 0.38 0.93   1.72 -0.20  0.93  0.76  0.78  0.84  0.858 1.198
  lr9641     E_Z       hm 0.95 0.84 0.07 0.09 0.59 0.85   1.10  0.21  0.85  0.41  0.51  0.56  0.637 0.608
  lr9642     E_Z       hm 1.00 0.45 0.29 0.05 0.14 0.17   0.77 -0.27  0.17  0.72  0.43  1.05  0.674 0.674
  lr9643     E_Z       lb 1.00 0.21 0.71 0.90 0.22 0.04   1.14 -0.46  0.04  0.78  0.54  2.92  0.519 0.519
  sw9696     E_X       hm 1.00 0.61 0.47 0.20 0.33 0.58   0.41 -0.05  0.58  0.14  0.35  3.86  0.558 0.558
  sw9696     E_Y       hm 0.98 1.20 0.50 0.20 0.37 0.49   0.58 -0.21  0.49  0.14  0.30  6.80  0.575 0.575
  sw9697     E_X       hm 0.17 1.30 0.12 0.33 3.10 0.07   1.42 -0.26  0.07  0.19  0.03  0.56  1.040 0.589
  sw9697     E_Y       hm 0.38 0.23 0.17 0.24 1.34 2.07   1.02  0.64  2.07  0.18  0.14  0.31  1.048 1.015
  col5791    E_Z       hm 0.10 0.01 0.34 27.91 0.92 0.63  2.52  0.92  0.63  0.83  0.86  1.32  1.033 0.753
  col5791    E_Z_mid   lb 0.81 1.04 1.14 0.13 0.11 0.92   1.04 -0.25  0.92  1.26  0.47  1.12  2.944 3.357
  col1403    E_Y       lb 0.84 0.33 0.07 1.09 0.40 0.64   0.92  0.30  0.64  0.54  0.45  0.95  1.853 2.103
  col1403    E_Y_mid   hm 0.64 0.22 0.22 0.31 0.80 0.90   0.62  0.41  0.90  0.50  0.97  0.48  2.082 2.234
  col1403    E_Z_mid   hm 0.35 1.27 0.42 0.53 0.75 1.36   0.46  0.07  1.36  1.04  0.61  1.11  0.867 1.158
  swiss303   E_X       hm 1.00 0.47 0.50 0.24 0.30 0.31   0.29 -0.14  0.31  0.14  0.34  7.24  0.570 0.570
  swiss303   E_Y       hm 1.00 0.28 0.68 0.25 0.37 0.24   0.38 -0.09  0.24  0.13  0.31  6.07  0.567 0.567
  lab5401    E_Y       lb 0.04 1.48                       0.00  0.00  1.48  0.66  0.74  0.00  1.047 2.461
  col1514    E_Z_mid   hm 0.41 0.78 0.08 0.73 2.01 0.30   1.08  0.12  0.30  0.72  0.14  1.74  1.611 3.057
  swiss5454  E_X       lb 0.04 3.26 2.62 0.55 0.55 0.48   0.85 -0.54  0.48  0.14  0.49 21.92  0.964 0.648
  swiss5454  E_Y       lb 0.12 3.79 1.11 0.53 0.41 0.51   0.81 -0.50  0.51  0.13  0.49 19.91  0.929 0.711
  year6511   E_X       lb 0.28 0.76 1.27 1.31 0.59 0.83   0.31 -0.06  0.83  0.42  1.34  1.02  0.949 0.922
  year6_5411 E_X       hm 1.00 0.92 0.96 0.36 0.43        0.44 -0.33  0.43     -     -     -  1.187 1.187
  year6_5411 E_Y       lb 0.52 0.50 0.10 1.29 0.69        0.96  0.35  0.69     -     -     -  1.157 1.608
  col6511    E_Z_mid   lb 0.12 3.19 0.41 0.07 0.51 2.00   1.32 -0.07  2.00     -     -  2.63  0.959 0.430
  year6512   E_X       lb 0.37 0.58 0.84 1.16 0.93 0.83   0.22  0.08  0.83     -     -     -  0.926 0.905
  year6512   E_Y       lb 0.62 0.19 0.34 0.39 0.40 0.37   0.27  0.15  0.37     -     -     -  0.728 0.728
  iso_a      E_Y1      lb 0.23 1.19 0.13                  1.11 -2.22  0.13     -     -     -  1.018 0.714
  mtc_b      E_dX      hm 1.00 0.24 0.37 0.15             0.36 -0.21  0.15     -     -     -  1.119 1.119
  mtc_b      E_dY      hm 0.67 0.46 0.68 0.29             0.34 -0.22  0.29     -     -     -  0.860 1.056
  mtc_b      E_dZ      hm 1.00 0.30 0.27 0.19             0.20 -0.24  0.19     -     -     -  1.046 1.046
  iso_b      E_X1      hm 0.71 0.50 0.55                  0.05  0.10  0.55     -     -     -  1.220 1.394
  iso_b      E_Z       hm 0.78 0.76 0.02                  1.73 -3.47  0.02     -     -     -  0.550 0.555
  mtc_a      E_dX      hm 0.83 1.03 0.25 0.30             0.63 -0.62  0.30     -     -     -  0.630 0.684
  mtc_a      E_dY      lb 1.00 0.42 0.37 0.36             0.06 -0.07  0.36     -     -     -  0.703 0.703
  mtc_a      E_dZ      hm 0.96 0.75 0.19 0.31             0.57 -0.44  0.31     -     -     -  0.772 0.793
  tsc_a2     E_dX1     hm 0.23 0.34 1.62                  0.78  1.56  1.62     -     -     -  0.926 1.461
  tsc_a2     E_dZ1     hm 0.71 0.01 0.02                  0.38  0.75  0.02     -     -     -  0.096 0.106
  tsc_a2     E_dX2     lb 0.98 0.06 0.29                  0.82  1.65  0.29     -     -     -  0.416 0.420
  tsc_a2     E_dZ2     lb 0.79 0.40 0.53                  0.14  0.27  0.53     -     -     -  0.545 0.585
  grind_a    E_Y       lb 0.01 1.59 0.74 1.05 1.31 0.76   0.30 -0.09  0.76     -     -     -  0.995 0.969
  grind_b    E_X       hm 0.76 1.05 0.36 0.79 0.76 1.23   0.43  0.11  1.23     -     -     -  0.967 0.971
  hmc        CH15_Disp hm 1.00 0.39 0.92 0.48             0.36  0.10  0.48     -     -     -  1.082 1.082
  hmc        CH16_Disp hm 0.58 0.41 1.09 0.62             0.40  0.21  0.62     -     -     -  0.901 0.902
  jig_grinder E_DISP_Y  lb 0.18 1.02 0.46 1.10             0.39  0.04  1.10     -     -     -  0.885 1.039
  twin_lathe E_Z1      hm 0.33 1.12 0.91 1.44 0.99 0.36   0.47 -0.22  0.36     -     -     -  0.953 0.937
  twin_lathe E_Z2      lb 0.04 14.41 0.86 0.83 0.91 1.30  1.10 -0.48  1.30     -     -     -  0.995 0.905

  separation of the targets whose L alone loses to MLR on test (19) from those where it wins (29),
  AUC (1: every loser above every winner): disp 0.50, last 0.67, trend 0.64, worst 0.56, cv 0.50,
  trend3 0.65, amp 0.75 (10 / 13 targets), leo 0.70 (10 / 13; the column's lag families 140-2300 x
  MLR on every target, winners too), leo_top 0.58 (10 / 13: col5791 E_Z_mid 0.47, col1514 0.14 --
  each input's own top tenth is no Q3), stab 0.21 (10 / 14: the failing lag families' fold models
  spread LESS than the winners', relative to MLR's; ``leo`` 150 s CPU for the 5 column / lab / year).

No signal separates: the winners show each of them too.  ``trend`` (the gain fading over the folds)
catches col1403's two (+0.30, +0.41), lr9587 (+0.59) and sw9697 E_Y (+0.64), but col5791 E_Z_mid
fades the other way (-0.25: its loss is Q3's, which no fold holds) and tsc_a2's winners "fade" on
two folds from 0.01 to 0.02 (+0.75); ``amp`` catches col5791 E_Z_mid (1.26) but flags lr9212's
winning hammerstein (0.99); ``last`` splits lr9641 (0.85, a winner) from col1403 E_Y_mid (0.90, a
loser) by 0.05 and misses col1403 E_Y (0.64); ``leo_top`` does not see the column's Q3 losses at all.

The prototype rules, auto / MLR per record (geo over the records; losers = records above 1.0):

  rule (limit)    22-table geo      losers  > 1 % worse   one-campaign 10 geo   > 1 % worse
  main            0.8265                 8                0.7657
  trend > 0.3     0.8325                 7  1 (tsc_a2)    0.7622                0
  last > 0.9      0.8201                10  4             0.7740                1 (lr9640 +17 %)
  amp > 0.9       0.8182                 8  0             0.7870                1 (lr9212 +32 %)
  disp > 1.2      0.8336                10  2             0.7748                2

``trend`` 0.3, built in src (``lag_fade``, committed 418ebf27), record by record where it moves:
col1403 1.311 -> 0.977 (E_Y, E_Y_mid to MLR), lr9587 1.059 -> 1.007, year6_5411 0.518 -> 0.450,
sw9697 1.044 -> 1.048, col5791 1.258 -> 1.266, tsc_a2 0.376 -> 0.675 (+79.5 %: all four targets, two
campaign folds each); over the 32 geo 0.8070 -> 0.8098, losers 10 -> 9.  Against the bar: (1) fails
(tsc_a2), (2) fails on the 22 (0.8265 -> 0.8325; the 32: 0.8098 > 0.8070), (3) met (8 -> 7): REFUSED.
``fl_thermal`` 90/10 unchanged (2.481 both ways: no lag family fades there).

Fresh 9719-9728: NOT held back as the bar says -- ``ways`` ran them through the committed rule
(418ebf27) while the last seven seen records' rows were still running (the deadline), and they were
read after the seen gate had failed; the rule was not changed in between.  Auto / MLR main -> rule:
lr9719-9723 0.995 0.991 0.483 0.997 0.807, unchanged; sw9724-9726 1.003 1.000 1.017 unchanged; sw9727
1.049 -> 1.026; sw9728 1.380 -> 1.384; geo 0.9444 -> 0.9426, worst 1.003, losers 4 -> 4: the fresh
clause would have been met.  These seeds are spent.

After the fact (measurement, not a rule: chosen on the seen table above AND after the fresh score):
``trend3`` (the fade counted only with 3 folds or more: two folds are one difference) leaves tsc_a2
alone: the 22 geo 0.8265 -> 0.8106, losers 8 -> 7, none > 1 % worse (worst col5791 1.006); the 10
one-campaign records as ``trend``; on the fresh (5 folds each) identical to the rule.  A lead for the
next stop, to be scored on new fresh seeds (e.g. 9729-9738) -- not KEPT here.
"""

import json
import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
os.environ.setdefault("OMP_NUM_THREADS", "1")
from _cli import run_commands  # noqa: E402

LAG = ("lagbank", "hammerstein")


def _records():
    from bench_auto95 import RECORDS

    return RECORDS


def one(out: str, *records: str) -> None:
    import bench_auto_rank as rank

    os.environ["OUT"] = str(Path(out).resolve())
    recs = _records()
    for name in records:
        sys.argv[2:] = list(recs[name])           # rank._dataset reads sim= from argv
        rank.main(name, list(recs[name]))


def ways(root: str, out: str, *records: str) -> None:
    """(needs ``benchmarks/auto96_rule.patch`` applied) Each record fitted as ``run`` fits it with
    ``lag_fade`` off (main) and at its default (the rule), and MLR alone; OUT/RECORD.json: per
    target the test RMSEs and both weights; the record's auto / MLR both ways (bench_auto95's
    figure: the mean over targets of the ratio)."""
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.shell.builders import build_compensator

    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        cfg, ds, train = _setup(name, root)
        rep = {"weights": {}}
        for way, fade in (("main", None), ("rule", 0.3)):
            auto = build_compensator(cfg, ds=ds)
            auto.estimator.set_params(lag_fade=fade)
            auto.fit(train)
            meas, pred = rank._test(auto, ds)
            rep[way] = {t: _rmse(meas[t], pred[t]) for t in meas}
            rep["weights"][way] = {t: e.weights_ for t, e in auto.estimators_.items()}
        meas, pred = rank._test(clone(auto).set_params(estimator=rank._mlr()).fit(train), ds)
        rep["mlr"] = {t: _rmse(meas[t], pred[t]) for t in meas}
        Path(out, f"{name}.json").write_text(json.dumps(rep, indent=1, default=float))
        fig = {w: float(np.mean([rep[w][t] / rep["mlr"][t] for t in rep["mlr"]])) for w in ("main", "rule")}
        print(f"{name} auto/MLR main {fig['main']:.3f} rule {fig['rule']:.3f} rule/main "
              f"{fig['rule'] / fig['main']:.3f}; weights rule {rep['weights']['rule']}", flush=True)


def ways_table(out: str, *records: str) -> None:
    figs = {}
    for name in records:
        rep = json.loads(Path(out, f"{name}.json").read_text())
        figs[name] = {w: float(np.mean([rep[w][t] / rep["mlr"][t] for t in rep["mlr"]]))
                      for w in ("main", "rule")}
        f = figs[name]
        print(f"{name:8s} main {f['main']:.3f} rule {f['rule']:.3f} rule/main {f['rule'] / f['main']:.3f}")
    m, r = [f["main"] for f in figs.values()], [f["rule"] for f in figs.values()]
    print(f"geo auto/MLR main {_geo(m):.4f} rule {_geo(r):.4f}; worst rule/main "
          f"{max(np.divide(r, m)):.3f}; losers {sum(v > 1 for v in m)} -> {sum(v > 1 for v in r)}")


# --------------------------------------------------------------------------- amplification
def _setup(name: str, root: str):
    """``(cfg, dataset, train)`` of a record: bench_automore69's (ROOT) or bench_auto95's."""
    import bench_auto_rank as rank
    from bench_automore69 import OVERRIDES

    overrides = ([o.format(root=Path(root).resolve()) for o in OVERRIDES[name]] if name in OVERRIDES
                 else list(_records()[name]))
    sys.argv[2:] = overrides                      # rank._dataset reads sim= from argv
    return rank.setup(overrides)


def _train_predictions(comp, ds, frozen=()) -> dict:
    """Per target, ``comp``'s free-run prediction of the train campaigns (concatenated), the
    inputs named in ``frozen`` held at each campaign's first sample."""
    from dataclasses import replace

    from thermocomp.core import continuation

    ids = ds.ids("train")
    camps = dict(ds.campaigns)
    for c in ids:
        frame = camps[c].copy()
        for col in frozen:
            frame[col] = frame[col].iloc[0]
        camps[c] = frame
    pred, _ = continuation.predict(comp, replace(ds, campaigns=camps), ids, "simulation")
    return {t: np.concatenate([pred[c][t].to_numpy(float) for c in ids]) for t in comp.targets_}


def amplification(comp, ds) -> dict:
    """Per target, how much ``comp``'s train prediction is a difference of large parts: the sum
    over inputs of the RMS of each input's contribution (the prediction less the one with that
    input held at its first sample) over the RMS of their sum (less the one with all held); 1
    where the inputs' parts add up, large where they cancel on the train record."""
    inputs = [c for c in ds.columns_of("T_")]
    full, held = _train_predictions(comp, ds), _train_predictions(comp, ds, inputs)
    parts = {c: _train_predictions(comp, ds, [c]) for c in inputs}
    return {t: float(sum(np.sqrt(np.mean((full[t] - parts[c][t]) ** 2)) for c in inputs)
                     / max(np.sqrt(np.mean((full[t] - held[t]) ** 2)), 1e-300)) for t in comp.targets_}


def amp(root: str, out: str, *records: str) -> None:
    from sklearn.base import clone

    from thermocomp.shell.builders import build_compensator

    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        cfg, ds, train = _setup(name, root)
        auto = build_compensator(cfg, ds=ds)
        got = {}
        for fam in ("mlr", *LAG):
            cand = auto.estimator.candidates.get(fam)
            if cand is None and fam != "mlr":
                continue
            import bench_auto_rank as rank

            comp = clone(auto).set_params(estimator=clone(cand) if cand is not None else rank._mlr())
            got[fam] = amplification(comp.fit(train), ds)
        Path(out, f"{name}.json").write_text(json.dumps(got, indent=1))
        print(name, {f: {t: round(v, 2) for t, v in a.items()} for f, a in got.items()}, flush=True)


# --------------------------------------------------------------------------- leave the extremes out
TAIL = 0.1    # a fold holds out the rows where one input lies in its top (or bottom) tenth


def _extremes(X: np.ndarray, tail: float = TAIL) -> list:
    """``(side, held rows)``: per input column and tail (``"top"`` / ``"bottom"``), the rows beyond
    its ``tail`` quantile; identical masks once, columns with fewer than 3 values (states) none."""
    out, seen = [], set()
    for j in range(X.shape[1]):
        x = X[:, j]
        if np.unique(x).size < 3:
            continue
        lo, hi = np.quantile(x, [tail, 1 - tail])
        for side, held in (("top", x > hi), ("bottom", x < lo)):
            if held.sum() >= 10 and held.tobytes() not in seen:
                seen.add(held.tobytes())
                out.append((side, held))
    return out


def extreme_folds(X: np.ndarray, tail: float = TAIL) -> list:
    """``(fit, predict, score)`` masks: each of :func:`_extremes` held out (scored), every other
    row fitted, the whole record predicted in free run."""
    return [(~held, np.ones(len(held), bool), held) for _, held in _extremes(X, tail)]


def _lag_fitted(root: str, name: str):
    """``name``'s train record fitted by auto restricted to MLR and the lag families, each kept
    with its out-of-fold predictions (``combine='best'``: no blend), under the folds the caller
    gave ``AutoRegressor._folds``."""
    from sklearn.base import clone

    from thermocomp.shell.builders import build_compensator

    cfg, ds, train = _setup(name, root)
    auto = build_compensator(cfg, ds=ds)
    cands = {n: c for n, c in auto.estimator.candidates.items() if n in ("mlr", *LAG)}
    est = clone(auto.estimator).set_params(candidates=cands, combine="best", keep_oof=True, fallback="none")
    return clone(auto).set_params(estimator=est).fit(train)


def leo(root: str, out: str, *records: str) -> None:
    """Per record and target, MLR and the lag families fitted without each input's extreme rows,
    scored on them (:func:`extreme_folds`): the lag family's fold ratios to MLR."""
    from thermocomp.core.models.auto import AutoRegressor

    AutoRegressor._folds = lambda self, groups, n: extreme_folds(self._X_leo)
    fit0 = AutoRegressor.fit

    def fit(self, X, y, context=None):
        self._X_leo = np.asarray(X, float)
        return fit0(self, X, y, context)

    AutoRegressor.fit = fit
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        comp = _lag_fitted(root, name)
        got = {}
        for t, e in comp.estimators_.items():
            got[t] = {n: np.bincount(e.oof_fold_, (e.oof_y_ - e.oof_[n]) ** 2).tolist() for n in e.oof_}
            got[t]["tail"] = [side for side, _ in _extremes(e._X_leo)]
        Path(out, f"{name}.json").write_text(json.dumps(got, indent=1))
        print(name, {t: {n: round(_pooled(g, n), 3) for n in LAG if n in g} for t, g in got.items()},
              flush=True)


def stab(root: str, out: str, *records: str) -> None:
    """Per record and target, MLR and the lag families fitted on each of auto's own validation
    folds' fit rows, each predicting the WHOLE train record in free run: the spread of a family's
    fold models' predictions (RMS over rows of their standard deviation across folds) over MLR's,
    its coefficients' instability seen through what they predict."""
    from thermocomp.core.models.auto import AutoRegressor

    folds0 = AutoRegressor._folds
    AutoRegressor._folds = lambda self, groups, n: [(fit, np.ones(n, bool), np.ones(n, bool))
                                                    for fit, *_ in folds0(self, groups, n)]
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        comp = _lag_fitted(root, name)
        got = {}
        for t, e in comp.estimators_.items():
            k = int(e.oof_fold_.max()) + 1
            spread = {n: float(np.sqrt(np.mean(np.var(e.oof_[n].reshape(k, -1), axis=0))))
                      for n in e.oof_}
            got[t] = {n: spread[n] / max(spread["mlr"], 1e-300) for n in spread}
        Path(out, f"{name}.json").write_text(json.dumps(got, indent=1))
        print(name, {t: {n: round(v, 2) for n, v in g.items()} for t, g in got.items()}, flush=True)


def _pooled(g: dict, name: str, side: str | None = None) -> float:
    """The lag family's summed squared error over MLR's on the held-out extremes (``side``: the
    top or bottom tails only)."""
    keep = [side is None or s == side for s in g["tail"]]
    return float(np.sum(np.compress(keep, g[name])) / np.sum(np.compress(keep, g["mlr"])))


# --------------------------------------------------------------------------- stored rows
def _targets(work: Path):
    """Per record of WORK: ``(record, kind, [(target, weights, oof, oof_y, oof_fold, test_y,
    test)])``; ``oof`` / ``test`` dicts of candidate -> predictions (``test`` only on the scored
    rows: the new campaigns, or the own test)."""
    if (work / "automore.jsonl").exists():
        from bench_auto91 import _row, stored_targets

        names = [json.loads(line)["record"] for line in (work / "automore.jsonl").read_text().splitlines()]
        for name in dict.fromkeys(names):
            rows = []
            for t, w, a, y_new, new, members in stored_targets(work, name):
                test = {k[5:]: a[k][new] for k in a.files if k.startswith("pred_") and k != "pred_auto"}
                rows.append((t, w, members, a["oof_y"], a["oof_fold"], y_new[new], test))
            yield name, "new", rows, _row(work, name)
        return
    for rep_path in sorted(work.glob("*.json")):
        rep = json.loads(rep_path.read_text())
        rows = []
        for t, row in rep["targets"].items():
            a = np.load(work / f"{rep['record']}.{t}.npz")
            oof = {k[4:]: a[k] for k in a.files if k.startswith("oof_") and k not in (
                "oof_y", "oof_fold", "oof_in_range", "oof_group")}
            test = {k[5:]: a[k] for k in a.files if k.startswith("test_") and k != "test_y"}
            rows.append((t, row["auto"]["weights"], oof, a["oof_y"], a["oof_fold"], a["test_y"], test))
        yield rep["record"], "own", rows, rep


def _rmse(y, p) -> float:
    return float(np.sqrt(np.mean((y - p) ** 2)))


def _blend(weights: dict, test: dict) -> np.ndarray:
    return sum(w * test[n] for n, w in weights.items())


# --------------------------------------------------------------------------- signals
def _ratios(oof, y, fold, name) -> np.ndarray:
    from thermocomp.core.models.blend import fold_ratios

    return fold_ratios((y - oof[name]) ** 2, (y - oof["mlr"]) ** 2, fold)


def _slope(v: np.ndarray) -> float:
    return float(np.polyfit(np.arange(v.size), v, 1)[0]) if v.size > 1 else 0.0


SIGNALS = {   # of the lag family's fold ratios r_k (k = 1..K, forward folds in order)
    "disp": lambda r: float(np.std(np.log(r))),         # fold-gain variance (log scale)
    "last": lambda r: float(r[-1]),                     # the fold nearest the test, fitted on most
    "trend": lambda r: _slope(np.log(r)),               # the gain fading over later folds (> 0)
    "worst": lambda r: float(np.max(r)),                # its worst fold
    "cv": lambda r: float(np.std(r) / np.mean(r)),      # dispersion relative to its mean ratio
    "trend3": lambda r: _slope(np.log(r)) if r.size >= 3 else 0.0,   # trend, 3 folds or more (after)
}


def _side(side: Path, kind: str, name: str) -> dict | None:
    path = side / kind / f"{name}.json"
    return json.loads(path.read_text()) if path.exists() else None


def _trained(side: Path, name: str, t: str, L: str) -> dict:
    """The signals measured by refits on the train record (``amp``, ``leo``), where measured."""
    out = {}
    a, e = _side(side, "amp", name), _side(side, "leo", name)
    if a is not None:
        out["amp"] = a[L][t] / a["mlr"][t]
    if e is not None and "tail" in e[t]:
        out["leo"] = _pooled(e[t], L)
        out["leo_top"] = _pooled(e[t], L, "top")
    b = _side(side, "stab", name)
    if b is not None:
        out["stab"] = b[t][L]
    return out


def _lag_rows(side: Path, work: Path):
    for name, kind, rows, _ in _targets(work):
        for t, w, oof, y, fold, ty, test in rows:
            lag = [n for n in LAG if w.get(n, 0) > 0]
            if not lag:
                continue
            L = max(lag, key=w.get)
            r = _ratios(oof, y, fold, L)
            sig = {k: f(r) for k, f in SIGNALS.items()} | _trained(side, name, t, L)
            yield name, kind, t, w, L, r, sig, {
                "auto": _rmse(ty, _blend(w, test)) / _rmse(ty, test["mlr"]),
                "alone": _rmse(ty, test[L]) / _rmse(ty, test["mlr"])}


TRAINED = ("amp", "leo", "leo_top", "stab")


def signals(side: str, *works: str) -> None:
    print("record    kind target    L            w(L) w(lag) folds r_k (L / MLR)          "
          + " ".join(f"{s:>6s}" for s in (*SIGNALS, *TRAINED)) + "  auto/MLR L/MLR (test)")
    seen = []
    for work in works:
        for name, kind, t, w, L, r, sig, test in _lag_rows(Path(side), Path(work).resolve()):
            seen.append((sig, test["alone"] > 1.0))
            wl = sum(w.get(n, 0) for n in LAG)
            rs = " ".join(f"{v:.2f}" for v in r)
            print(f"{name:9s} {kind:4s} {t:9s} {L:12s} {w[L]:.2f} {wl:.2f}   {rs:28s} "
                  + " ".join(f"{sig[k]:6.2f}" if k in sig else "     -" for k in (*SIGNALS, *TRAINED))
                  + f"  {test['auto']:.3f}    {test['alone']:.3f}")
    print("separation of the targets whose lag family alone loses to MLR on test (L/MLR > 1) from "
          "those where it wins: AUC (1: every loser's signal above every winner's), n losers / winners")
    for k in (*SIGNALS, *TRAINED):
        lose = [sg[k] for sg, bad in seen if bad and k in sg]
        win = [sg[k] for sg, bad in seen if not bad and k in sg]
        if lose and win:
            auc = np.mean([(a > b) + 0.5 * (a == b) for a in lose for b in win])
            print(f"  {k:8s} AUC {auc:.2f}  ({len(lose)} / {len(win)}); losers {np.min(lose):.2f}.."
                  f"{np.max(lose):.2f}, winners {np.min(win):.2f}..{np.max(win):.2f}")


# --------------------------------------------------------------------------- the prototype rule
def _moved(w: dict, oof, y, fold, value) -> dict:
    """``w`` with each lag family whose signal (``value(name, fold ratios)``; None: not measured,
    kept) exceeds the limit handing its weight to MLR."""
    out = dict(w)
    for n in LAG:
        if out.get(n, 0) > 0 and value(n, _ratios(oof, y, fold, n)):
            out["mlr"] = out.get("mlr", 0.0) + out.pop(n)
    return out


def _figure(kind: str, rows, weights) -> float:
    auto = [_rmse(ty, _blend(w, test)) for (_, _, _, _, _, ty, test), w in zip(rows, weights)]
    mlr = [_rmse(ty, test["mlr"]) for *_, ty, test in rows]
    if kind == "new":
        return float(np.mean(auto) / np.mean(mlr))
    return float(np.mean(np.divide(auto, mlr)))


def _geo(v) -> float:
    return float(np.exp(np.mean(np.log(v))))


def table(side: str, signal: str, limit: str, *works: str) -> None:
    lim = float(limit)
    print(f"rule: a lag family with {signal} > {lim} hands its weight to MLR")
    print("record    kind main   rule   rule/main  moved")
    main_all, rule_all = [], []
    for work in works:
        for name, kind, rows, _ in _targets(Path(work).resolve()):
            def value(n, r, t):
                sig = {k: f(r) for k, f in SIGNALS.items()} | _trained(Path(side), name, t, n)
                return signal in sig and sig[signal] > lim

            base = [w for _, w, *_ in rows]
            new = [_moved(w, oof, y, fold, lambda n, r, t=t: value(n, r, t))
                   for t, w, oof, y, fold, *_ in rows]
            m, r = _figure(kind, rows, base), _figure(kind, rows, new)
            moved = [t for (t, *_), a, b in zip(rows, base, new) if a != b]
            main_all.append(m)
            rule_all.append(r)
            print(f"{name:9s} {kind:4s} {m:.3f}  {r:.3f}  {r / m:.3f}      {' '.join(moved)}")
    worse = int(np.sum(np.divide(rule_all, main_all) > 1.01))
    print(f"geo auto/MLR main {_geo(main_all):.4f} rule {_geo(rule_all):.4f}; losers (> 1.0) "
          f"{sum(v > 1.0 for v in main_all)} -> {sum(v > 1.0 for v in rule_all)}; > 1 % worse than "
          f"main {worse}; worst rule/main {max(np.divide(rule_all, main_all)):.3f}")


def main(argv: list[str]) -> int:
    commands = {"one": one, "amp": amp, "leo": leo, "stab": stab, "ways": ways, "ways_table": ways_table,
                "signals": signals, "table": table}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
