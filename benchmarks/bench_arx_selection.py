"""ARX input/model selection speed: Gram-matrix search vs a straightforward statsmodels loop.

Usage::

    python benchmarks/bench_arx_selection.py [N_TARGETS] [N_SENSORS] [N_SAMPLES] [BASELINE_TARGETS]
    # default 24 50 28080 24

The paper-000 setting: 24 error parameters, 50 candidate sensors, a 234 h test
at 30 s (28,080 samples); per target, the split greedy search for 1..10 inputs,
with and without the AR term, and the lowest BICc wins.  Target <= 3 s.

1. ``ARX.fit`` (one Gram matrix per target, sweep operator) with
   ``selection_error='equation'`` (the pure selection, as the baseline does) and
   with the default ``'simulation'`` (AR models also run free once per size).
2. The same search written the straightforward way: every candidate of every
   step is a statsmodels OLS fit of the current residual, every model size a
   statsmodels OLS refit; the criteria from its SSR.  Run on
   ``BASELINE_TARGETS`` targets (and scaled to all of them when fewer).
   The chosen models must agree with 1 -- the script checks it.

Synthetic data: sensors are first-order lags (time constants 0.5-10 h) of 4
heat sources plus ambient, with noise (so they are strongly collinear, as on a
machine); each target mixes 2-5 of them plus noise, every 12th has AR dynamics.
Prints wall times with the machine load (the machine may be shared).
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np
import statsmodels.api as sm

from thermocomp.core.model_selection import information_criteria
from thermocomp.core.models._dynamics import free_run, previous
from thermocomp.core.models.arx import ARX


def synthetic(n_targets: int, n_sensors: int, n_samples: int, period_s: float = 30.0, seed: int = 0):
    rng = np.random.default_rng(seed)
    t = np.arange(n_samples) * period_s
    sources = np.column_stack([np.repeat(rng.uniform(0, 10, n_samples // 720 + 1), 720)[:n_samples]
                               for _ in range(4)] + [2 * np.sin(2 * np.pi * t / 86400)])
    X = np.empty((n_samples, n_sensors))
    for j in range(n_sensors):
        a = np.exp(-period_s / (3600 * rng.uniform(0.5, 10)))
        drive = sources @ rng.dirichlet(np.ones(5))
        X[:, j] = free_run(a, (1 - a) * drive, None) + rng.normal(0, 0.03, n_samples)
    X -= X[0]
    Y = np.empty((n_samples, n_targets))
    for m in range(n_targets):
        cols = rng.choice(n_sensors, size=rng.integers(2, 6), replace=False)
        u = X[:, cols] @ rng.normal(0, 3, len(cols))
        a = 0.95 if m % 12 == 0 else 0.0
        Y[:, m] = free_run(a, (1 - a) * u, None) + rng.normal(0, 0.5, n_samples)
    return X, Y


def statsmodels_selection(X, y, criterion="bicc", max_inputs=10):
    """The same search, every candidate fitted by statsmodels OLS: (ar, inputs) of the winner."""
    n, p = X.shape
    y_prev = previous(y, None)
    rows = np.arange(1, n)                   # y(t-1) unknown at the first sample
    Xr, yr, lag = X[rows], y[rows], y_prev[rows]
    tss = float(np.sum((yr - yr.mean()) ** 2))
    best = (np.inf, None)
    for with_ar in (False, True):
        forced = sm.add_constant(lag[:, None]) if with_ar else np.ones((len(yr), 1))
        partial = np.column_stack([sm.OLS(Xr[:, j], forced).fit().resid for j in range(p)])
        resid = sm.OLS(yr, forced).fit().resid
        order = []
        for _ in range(max_inputs):
            fits = {j: sm.OLS(resid, sm.add_constant(partial[:, j])).fit()
                    for j in range(p) if j not in order}
            j = min(fits, key=lambda k: fits[k].ssr)
            resid = resid - fits[j].params[1] * partial[:, j]
            order.append(j)
            joint = sm.OLS(yr, np.column_stack([Xr[:, order], forced])).fit()
            value = information_criteria(joint.ssr, len(yr), len(order) + forced.shape[1],
                                         tss=tss)[criterion]
            if value < best[0]:
                best = (value, (with_ar, list(order)))
    return best[1]


def main(argv: list[str]) -> None:
    defaults = ["24", "50", "28080", "24"]
    n_targets, n_sensors, n_samples, n_base = (int(a) for a in argv + defaults[len(argv):])
    X, Y = synthetic(n_targets, n_sensors, n_samples)
    print(f"{n_targets} targets x {n_sensors} candidate sensors x {n_samples} samples, 1..10 inputs "
          f"x with/without AR, BICc; load {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")

    chosen, times = {}, {}
    for selection_error in ("equation", "simulation"):
        t0, c0 = time.perf_counter(), time.process_time()
        models = [ARX(selection_error=selection_error).fit(X, Y[:, m]) for m in range(n_targets)]
        times[selection_error] = time.perf_counter() - t0
        cpu = time.process_time() - c0
        chosen[selection_error] = [(m.chosen_["ar"], [j for j, _ in m.terms_]) for m in models]
        n_ar = sum(ar for ar, _ in chosen[selection_error])
        print(f"ARX.fit, selection_error={selection_error:<10}: {times[selection_error]:6.2f} s wall, "
              f"{cpu:6.2f} s CPU (target <= 3 s); AR term chosen for {n_ar}/{n_targets} targets")

    t0, c0 = time.perf_counter(), time.process_time()
    base = [statsmodels_selection(X, Y[:, m]) for m in range(min(n_base, n_targets))]
    base_s = (time.perf_counter() - t0) * n_targets / len(base)
    base_cpu = (time.process_time() - c0) * n_targets / len(base)
    scaled = "" if len(base) == n_targets else f" (measured on {len(base)} targets, scaled)"
    print(f"statsmodels OLS loop          : {base_s:6.2f} s wall, {base_cpu:6.2f} s CPU{scaled}")
    print(f"speed-up (equation selection) : {base_s / times['equation']:6.0f} x wall")
    agree = sum(b == c for b, c in zip(base, chosen["equation"]))
    print(f"same winner (AR term and inputs, in order) for {agree}/{len(base)} targets; "
          f"load {os.getloadavg()[0]:.2f}")
    if agree != len(base):
        sys.exit("the fast search and the statsmodels loop disagree")


if __name__ == "__main__":
    main(sys.argv[1:])
