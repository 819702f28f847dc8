"""``model=auto``'s folds of one record compared: every fold scheme on the same record, one process.

Usage::

    python benchmarks/bench_auto_folds.py NAME [OVERRIDE ...]     # overrides as bench_auto_rank.py
    python benchmarks/bench_auto_rules.py $OUT/forward --tuning ...  # then the counts per scheme

``model=auto`` is fitted once per ``one_record`` scheme (``$SCHEMES``, default ``forward blocks
late_blocks``); every candidate it validates is fitted alone on the train split once (its test
predictions, shared by the schemes).  Each scheme's out-of-fold predictions are saved with those
under ``$OUT/<scheme>/`` (default ``OUT=/tmp/bench_auto_folds``) as ``bench_auto_rank.py`` saves
them, so ``bench_auto_rules.py`` scores each scheme's rules.  The test split only scores.

Measured (session 45; the counts and the analysis in ``bench_auto_rules.py``), mean test RMSE of
``auto`` over the targets (µm), forward / blocks / late_blocks | MLR | best family: col0 7.50 /
7.49 / 6.23 | 7.67 | 6.48; col101 5.26 / 5.16 / 4.75 | 5.29 | 5.24; col202 5.87 / 6.29 / 5.39 |
6.65 | 4.00; col303 12.4 / 13.9 / 15.7 | 14.9 | 7.43; col404 12.6 / 12.0 / 11.9 | 13.4 | 9.56;
col11 7.14 / 6.53 / 6.37 | 6.54 | 5.93; swiss0 0.908 / 1.24 / 0.822 | 1.37 | 0.822; swiss101
0.972 / 2.22 / 0.972 | 2.44 | 0.972; swiss202 0.786 / 1.41 / 0.786 | 1.72 | 0.786; swiss303 1.41
/ 1.28 / 1.41 | 1.37 | 0.835; swiss404 1.13 / 1.26 / 0.975 | 1.34 | 0.986; swiss11 1.19 / 0.924
/ 0.696 | 1.34 | 0.696; mill0 1.95 / 2.01 / 1.86 | 2.01 | 2.01; mill101 1.78 / 1.86 / 1.75 | 1.79
| 1.79; mill202 2.50 / 2.87 / 2.71 | 2.41 | 2.41; mill303 1.91 / 1.92 / 1.88 | 1.94 | 1.66;
mill404 1.87 / 1.86 / 1.81 | 1.90 | 1.88; mill11 1.25 / 1.17 / 1.20 | 1.29 | 1.28; fl9010 2.475
/ 3.99 / 3.92 | 4.06 | 2.95.

Fresh records, run once (2026-11-29, seeds 1736/1847, nothing tuned on them; ``SCHEMES="forward
late_blocks"``), forward / late_blocks | MLR | best family: col1736 9.41 / 8.62 | 9.44 | 8.98;
col1847 5.61 / 7.81 | 8.01 | 5.83; swiss1736 1.108 / 1.241 | 1.605 | 0.962; swiss1847 0.729 /
0.767 | 1.157 | 0.729; mill1736 2.118 / 2.203 | 2.215 | 2.015; mill1847 2.266 / 2.329 | 2.144 |
2.144.  Counts (better than MLR / within 10 % of the best family / geometric mean over it):
forward 5 / 5 / 1.043, late_blocks 5 / 4 / 1.129: the tuning records' gain of late_blocks (8 ->
12 within 10 %) did not hold, so it is not the default even where the test runs are separate
from the record.  CPU per record (both schemes + every family alone, user s): col 42-43, swiss
26-30, mill 190-208.
"""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

import numpy as np
from bench_auto_rank import _mlr, _test, setup
from sklearn.base import clone

from thermocomp.core.metrics import rmse
from thermocomp.shell.builders import build_compensator


def main(name: str, overrides: list[str]) -> None:
    cfg, ds, train = setup(overrides)
    template = build_compensator(cfg, ds=ds)
    meas, preds, walls = None, {}, {}
    for scheme in os.environ.get("SCHEMES", "forward blocks late_blocks").split():
        t0 = time.perf_counter()
        auto = clone(template).set_params(estimator__one_record=scheme).fit(train)
        wall = time.perf_counter() - t0
        for n in dict.fromkeys(n for e in auto.estimators_.values() for n in e.oof_):
            if n not in preds:      # every validated candidate alone, once for all schemes
                t0 = time.perf_counter()
                single = clone(template.estimator.candidates.get(n) or _mlr())
                meas, preds[n] = _test(clone(template).set_params(estimator=single).fit(train), ds)
                walls[n] = time.perf_counter() - t0
        out = Path(os.environ.get("OUT", "/tmp/bench_auto_folds")) / scheme
        out.mkdir(parents=True, exist_ok=True)
        report = {"record": name, "overrides": overrides, "scheme": scheme, "targets": {},
                  "wall_s": {**walls, "auto": wall}}
        for t, est in auto.estimators_.items():
            names = [n for n in preds if n in est.oof_]
            test = {n: rmse(meas[t] - preds[n][t]) for n in names}
            kept = sum(w * preds[n][t] for n, w in est.weights_.items())
            report["targets"][t] = {"test": test, "validation": dict(est.validation_),
                                    "auto": {"weights": est.weights_, "rmse": rmse(meas[t] - kept)},
                                    "mlr": test["mlr"], "scheme": est.scheme_}
            np.savez(out / f"{name}.{t}.npz", oof_y=est.oof_y_, oof_fold=est.oof_fold_, test_y=meas[t],
                     **{f"oof_{n}": est.oof_[n] for n in names}, **{f"test_{n}": preds[n][t] for n in names})
            print(f"{name} {scheme} {t}: auto {report['targets'][t]['auto']['rmse']:.3g} ("
                  + ", ".join(f"{n} {w:.2f}" for n, w in est.weights_.items()) + f") mlr {test['mlr']:.3g}"
                  + " | " + " ".join(f"{n} {v:.3g}" for n, v in test.items()))
        (out / f"{name}.json").write_text(json.dumps(report, indent=1, default=float))
        rows = report["targets"].values()
        print(f"{name} {scheme}: mean auto {np.mean([r['auto']['rmse'] for r in rows]):.4g} "
              f"mlr {np.mean([r['mlr'] for r in rows]):.4g}; wall auto {wall:.0f} s")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
