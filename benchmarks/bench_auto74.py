"""Can a family's memory against a fold's fit length tell the forward folds that mislead auto's
votes from those that inform them? (issue 34 item 3; stop 74, auto74)

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_auto74.py memory ROOT NAME TARGET[,TARGET...]   # per fold, per family

``NAME``: ``vgm<seed>`` (bench_auto73's grinder, ROOT its ``write`` folder), ``fl9010``
(``fl_thermal`` 90/10, ROOT unused: ``-``) or one of automore69's one-record records
(bench_auto73's ``ONE_RECORD``, ROOT bench_automore69's).  ``memory``: auto's forward folds over
the train part (its own ``BlockedForward``), and for each fold and family the fit's span (h), the
family's memory read from that fold's fitted candidate, and the fold's block MSE over MLR's (what
the votes see).  Two readings of the memory: *configured*, the longest lag the fitted model can
express (lagbank / hammerstein: ``taus_[-1]``; arx: its largest kept delay x the period and its AR
time constant ``-period / ln a``; lstm, not fitted: ``chunk`` x the period, the span its gradient is
carried over); *identified*, where the lag families put their weight: the time constants' geometric
centroid weighted by each lag's coefficient mass (``|b_jk| x std(x_j)`` over the fold's fit rows,
summed over inputs) and the share of that mass on time constants longer than the fold's span.
Nothing of the test is read.

The idea (the lead's, stop 73's "left")
---------------------------------------
A fold whose fit is shorter than k x a family's slowest mode is no fair trial of that family:
drop (or weigh down) that family's blocks there, MLR (memoryless) keeping every fold.  For it to
mend the grinder without breaking ``fl_thermal`` (stop 73's refused share rule: grinder -16 to -82 %,
``fl_thermal`` 90/10 +21.9 %, col5791 2.35x), the memory must mark grinder E_dZ's lag-bank folds 0-2
(fits 45-65 % of the record: block 4.54 / 0.03 / 7.10 x MLR's, their own fits 9-43x MLR's on the test)
as unfair and its folds 3-4 as fair, while keeping ``fl_thermal`` ch1's hammerstein fold 2 (0.06,
the vote that made its shipped 2.89 µm) and ch4's blend (1.99 µm; its last two folds alone gave
the lstm every vote, 2.82).

Measured (2026-12-02, main 4812ce97 = this bench's tree, ``memory``; CPU 3.2-6.5 s a record)
---------------------------------------------------------------------------------------------
Every record here is ~1.5 days: the forward folds' fits span 14.6 / 17.8 / 21.1 / 24.3 / 27.5 h on
the grinder (vgm7356, vgm7396: train 32.4 h at 15 s), 18.8 / 22.9 / 27.1 / 31.3 / 35.4 h on
``fl9010`` (train 41.7 h at 15 s), 18.0 / 22.0 / 26.0 / 30.0 / 34.0 h on col5791 (100 s).

* configured: lagbank and hammerstein ``taus_[-1]`` = 48 h (``tau_max_s``) on every fold of every
  record, longer than every fold's fit and every train part.  At any k >= 0.74 no fold of any of
  them qualifies for the lag families, so the rule is a no-op for them (fallback "every fold
  counts": grinder E_dZ stays 7.17 µm on 7356, 6.56 on 7396) or takes them out of the votes
  (fallback "no say": also E_dX, where the lag bank wins every fold, 0.00-0.03 x MLR on 7356, and
  is auto's right choice, 0.209 µm against MLR's 8.82 on 7396).  The only k splitting the grinder's
  folds 0-2 from 3-4 lies in (0.44, 0.51) x 48 h = 21.1-24.3 h; it also drops the first one or two
  folds of fl9010 and col5791: a fixed share of ~1.5 days, stop 73's refused rule under another
  name.  arx (no delay kept; its AR time constant 0-1.7 h where it has one) and lstm (``chunk`` 128
  x the period: 0.53 h at 15 s, 3.56 h at 100 s) are short against every fold: all fair, a no-op.
* identified: the lag families' weight sits at minutes to an hour, far inside every fold.
  Centroid (h) / share of the lag mass beyond the fold's span, folds 0-4, with the fold's block
  MSE over MLR's (what the votes see):

  vgm7356 E_dZ lagbank     0.02-0.03 / 0.02 0.02 0.03 0.03 0.03  blocks 4.54 0.03 7.09 0.07 0.17
  vgm7356 E_dZ hammerstein 1.80 0.35 0.37 1.03 0.61 / 0.15 0.09 0.10 0.13 0.14
                                                                 blocks 0.02 0.13 9.41 5.69 0.58
  vgm7396 E_dZ lagbank     0.04-0.06 / 0.04 0.05 0.04 0.04 0.04  blocks 23.4 0.63 6.14 0.21 0.20
  vgm7396 E_dZ hammerstein 0.23 1.09 0.32 0.61 0.56 / 0.08 0.14 0.08 0.13 0.09
                                                                 blocks 128 6.17 5.30 0.21 0.40
  fl9010 E_ch1 hammerstein 0.11 0.09 0.15 0.27 0.13 / 0.02 0.02 0.03 0.04 0.05
                                                                 blocks 1.01 0.57 0.06 0.35 1.13
  fl9010 E_ch4 lagbank     0.16 0.09 0.17 0.11 0.23 / 0.03 0.04 0.04 0.04 0.04
                                                                 blocks 0.28 1.56 0.09 0.23 5.17
  col5791 E_Y_mid lagbank  0.11-0.15 / 0.02 0.02 0.03 0.03 0.03  blocks 8.69 4.97 10.4 0.87 0.39

  The span / centroid ratio is >= 8 on every fold (hammerstein, vgm7356 fold 0: 14.6 / 1.80 h),
  >= 100 for the lag bank, so any k < 8 keeps every fold (a no-op), and neither figure orders the
  grinder's failing folds (E_dZ lagbank 0-2) apart from its good ones (3-4), nor the grinder (lag
  bank right on test) from col5791, whose E_Y_mid lag bank fails its early folds and wins its late
  ones as the grinder's does and is wrong on the new campaigns (7.96 against MLR's 3.25 µm where
  auto73's late folds kept it, bench_auto73): the same 48 h grid, the same centroid of minutes, the
  same 2-5 % of the lag bank's mass beyond the span on all three machines.

Verdict: NOT PROPOSED, not scored, no src change.  Neither reading of a family's memory separates
the folds that mislead from those that inform: the configured one is the same 48 h for the lag
families on every fold of every record (it reduces to a fixed share of the record, the refused
auto73 rule), the identified one is far shorter than every fold (a no-op).  What differs between
the grinder's folds is what the prefix holds (the base's one-way drift, time constant ~12 h,
bench_auto73's trace), which a fitted model's memory does not show.  The bar the task wrote
(grinder 7356 and fresh vgm73 seeds 7396-7400 each better or equal; ``fl_thermal`` 90/10 and
60/20/20 not worse than +2 %; automore69's instrument) was not scored: on these records the rule's
outcome is fixed by the trace above (identical weights, or the auto73 figures).

The fresh grinder seeds, shipped auto (``bench_auto73.py fit`` on 4812ce97, 57.3 s CPU for the
five; test RMSE µm, E_dZ / E_dX, auto's weights; MLR; the best single family per target)::

  vgm7396  6.558 (mlr 0.55, arx 0.45) / 0.209 (lagbank 0.93)   MLR 6.557 / 8.821   best 1.58 / 0.208
  vgm7397  2.003 (hammerstein 0.43, lagbank 0.30, mlr 0.25) / 0.364   MLR 11.375 / 5.444
                                                                   best 1.36 / 0.364
  vgm7398  1.209 (lagbank 0.52, hammerstein 0.48) / 0.307   MLR 8.121 / 2.400   best 0.558 / 0.307
  vgm7399  3.326 (lagbank 0.99) / 0.248   MLR 3.742 / 9.759   best 3.33 / 0.248
  vgm7400  1.004 (lagbank 0.65, hammerstein 0.31) / 0.215   MLR 5.835 / 3.526   best 0.718 / 0.212

Record means auto / MLR / best single family: 3.38 / 7.69 / 0.894, 1.18 / 8.41 / 0.863, 0.758 /
5.26 / 0.432, 1.79 / 6.75 / 1.79, 0.610 / 4.68 / 0.465: auto beats MLR on all five, is within 10 %
of the best single family on one (7399); E_dZ of 7396 is 7356's loss again (MLR and arx kept, the
lag bank's folds 0 and 2 at 23.4 and 6.14 x MLR's, its test 1.58 against 6.56).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402

LAG_FAMILIES = ("lagbank", "hammerstein")
FITTED = ("mlr", *LAG_FAMILIES, "arx")


def _overrides(root: str, name: str) -> list[str]:
    """The overrides ``bench_auto_rank`` fits record ``name`` with."""
    if name == "fl9010":
        return ["data=fl_thermal"]
    if name.startswith("vgm"):
        import bench_auto73

        return bench_auto73._overrides(root, name[3:])
    import bench_automore69 as automore

    return [o.format(root=Path(root).resolve()) for o in automore.OVERRIDES[name]]


def configured_memory_s(model, period_s: float) -> float:
    """The longest lag the fitted ``model`` can express (s), module doc."""
    lags = getattr(model, "lagbank_", model)
    if hasattr(lags, "taus_"):
        return float(lags.taus_[-1])
    if hasattr(model, "terms_"):                               # arx: delays, then its AR feedback
        delays = max([d for _, d in model.terms_] + [0]) * period_s
        a = float(getattr(model, "ar_coef_", 0.0) or 0.0)
        return delays + (-period_s / np.log(a) if 0.0 < a < 1.0 else 0.0)
    return 0.0


def identified_memory(model, X_fit: np.ndarray, span_s: float) -> tuple[float, float]:
    """A lag family's (centroid of its time constants by lag mass (s), share of the mass on time
    constants longer than ``span_s``); module doc."""
    lags = getattr(model, "lagbank_", model)
    taus = lags.taus_
    p = lags.coef_.size // (taus.size + 1)
    scale = np.ones(p)
    scale[:min(p, X_fit.shape[1])] = X_fit.std(axis=0)[:p]   # a Hammerstein's state powers: unscaled
    mass = (np.abs(lags.coef_[p:].reshape(taus.size, p)) * scale).sum(axis=1)
    centroid = float(np.exp((np.log(taus) * mass).sum() / mass.sum()))
    return centroid, float(mass[taus > span_s].sum() / mass.sum())


def memory(root: str, name: str, targets: str) -> None:
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.core.compensator import _simulation
    from thermocomp.core.context import subset
    from thermocomp.core.frame import resolve_columns, stack
    from thermocomp.core.model_selection import BlockedForward
    from thermocomp.core.models.linear import MLR
    from thermocomp.shell.builders import build_compensator

    overrides = _overrides(root, name)
    sys.argv[2:] = overrides
    cfg, ds, train = rank.setup(overrides)
    comp = build_compensator(cfg, ds=ds)
    inputs, all_targets = resolve_columns(list(next(iter(train.values())).columns), comp.inputs,
                                          comp.targets)
    m = stack(train, inputs, all_targets, comp.reference)
    X, ctx, est = np.asarray(m.X, float), _simulation(m.context), comp.estimator
    folds = BlockedForward(est.n_folds, est.min_train_fraction, est.gap_blocks).folds(None, len(X))
    for t in targets.split(","):
        y = np.asarray(m.Y[t], float)
        print(f"== {name} {t}")
        for k, (fit, pred, score) in enumerate(folds):
            models, sse = {}, {}
            for f in FITTED:
                if f != "mlr" and f not in est.candidates:
                    continue
                model = clone(est.candidates.get(f) or MLR()).fit(X[fit], y[fit], context=subset(ctx, fit))
                yhat = np.asarray(model.predict(X[pred], context=subset(ctx, pred)), float)
                models[f], sse[f] = model, np.sum((y[score] - yhat[score[pred]]) ** 2)
            period = float(getattr(models.get("lagbank"), "sample_period_s_", 60.0))
            span = fit.sum() * period
            print(f" fold {k}: fit {fit.sum()} rows = {span / 3600:.1f} h")
            for f, model in models.items():
                if f == "mlr":
                    continue
                line = (f"   {f:12s} block {sse[f] / sse['mlr']:6.2f} x MLR | configured "
                        f"{configured_memory_s(model, period) / 3600:7.2f} h")
                if f in LAG_FAMILIES:
                    centroid, beyond = identified_memory(model, X[fit], span)
                    line += f" | identified centroid {centroid / 3600:6.2f} h, beyond the span {beyond:.2f}"
                print(line)
            if "lstm" in est.candidates:
                chunk = est.candidates["lstm"].get_params().get("chunk", 0)
                print(f"   {'lstm':12s} configured {chunk * period / 3600:7.2f} h (chunk {chunk}, "
                      "not fitted)")


def main(argv: list[str]) -> int:
    os.environ.setdefault("OUT", "/tmp/auto74-out")   # bench_auto_rank's
    return run_commands(__doc__, {"memory": memory}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
