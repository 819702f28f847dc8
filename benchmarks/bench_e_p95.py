"""Time of the E_P95 / E_max / E_mean curves for every window length of a week-long record.

Usage::

    python benchmarks/bench_e_p95.py [HOURS] [PERIOD_S] [REPEATS]   # default 168 30 3

A 30 s x 168 h series (20,160 samples, paper 000's validation test) gives
20,159 window lengths (one sample step .. the whole record); for each the
statistic of every sliding window is computed and reduced to its 95th
percentile, maximum and mean (``thermocomp.core.metrics.window_curves``), for the
range and for sigma.  Prints the best of ``REPEATS`` wall times and the
machine load (the machine may be shared: read times next to the load), and
checks a few lengths against a brute-force ``np.percentile``.
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np

from thermocomp.core import metrics as M


def series(hours: float, period_s: float, seed: int = 0) -> np.ndarray:
    """A thermal-error-like record: daily cycle + drift + random walk + noise (µm)."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, hours * 3600.0, period_s)
    return (8 * np.sin(2 * np.pi * t / 86400) + 2e-4 * t + 0.05 * rng.normal(size=t.size).cumsum()
            + 0.3 * rng.normal(size=t.size))


def main(hours: float = 168.0, period_s: float = 30.0, repeats: int = 3) -> None:
    x = series(hours, period_s)
    lengths = M.window_lengths(x.size)  # every length, 2 .. n samples
    print(f"series: {x.size} samples ({hours:g} h at {period_s:g} s), {lengths.size} window lengths")
    for statistic in ("range", "std"):
        best = np.inf
        for _ in range(repeats):
            t0 = time.perf_counter()
            curves = M.window_curves([x], lengths, statistic)
            best = min(best, time.perf_counter() - t0)
        check = lengths[:: max(1, lengths.size // 25)]
        brute = [np.percentile(M.window_statistic(x, int(n), statistic), 95) for n in check]
        err = np.max(np.abs(np.asarray(brute) - curves["percentile"][np.searchsorted(lengths, check)]))
        print(f"{statistic:>5}: E_P95 + E_max + E_mean for all lengths in {best:6.2f} s "
              f"(best of {repeats}); max |error| vs np.percentile on {check.size} lengths: {err:.1e} µm")
    load = os.getloadavg()
    print(f"load average (1, 5, 15 min): {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} on {os.cpu_count()} cores")


if __name__ == "__main__":
    args = sys.argv[1:]
    main(float(args[0]) if args else 168.0, float(args[1]) if len(args) > 1 else 30.0,
         int(args[2]) if len(args) > 2 else 3)
