"""TCP error of 100 000 positions: small-angle and full HTM forms (issue 15).

The default moving-column machine (order 2, with the column-ram cross terms), one parameter
vector, positions uniform over the workspace; best of 5 runs each, against a plain NumPy
operation of similar size (a (100 000, 3) × (3, 3) product plus a row norm), and the
largest difference of the two forms.

    .venv/bin/python benchmarks/bench_kinematics.py
"""

from __future__ import annotations

import time

import numpy as np

from thermocomp.apps.volumetric import KinematicModel

N = 100_000


def best(fn, repeat=5) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    model = KinematicModel(cross_terms=True)
    rng = np.random.default_rng(0)
    lo = np.array([r[0] for r in model.ranges.values()])
    hi = np.array([r[1] for r in model.ranges.values()])
    q = lo + rng.random((N, 3)) * (hi - lo)
    p = rng.uniform(-10, 10, len(model.names))
    R = rng.normal(size=(3, 3))
    plain = best(lambda: np.linalg.norm(q @ R, axis=1))
    small = best(lambda: model.error(p, q, "small"))
    htm = best(lambda: model.error(p, q, "htm"))
    diff = np.abs(model.error(p, q, "htm") - model.error(p, q, "small")).max()
    print(f"{N} positions, {len(model.names)} parameters")
    print(f"small-angle: {small * 1e3:8.1f} ms  ({small / plain:5.1f} × the plain NumPy op)")
    print(f"HTM:         {htm * 1e3:8.1f} ms  ({htm / plain:5.1f} ×)")
    print(f"plain NumPy: {plain * 1e3:8.1f} ms  ((n,3)@(3,3) + row norm)")
    print(f"max |HTM - small| = {diff:.2e} µm")


if __name__ == "__main__":
    main()
