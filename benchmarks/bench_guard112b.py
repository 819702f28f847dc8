"""Why the deploy guard costs ``arx_rf`` 12 % on the door room's E_Z (stop 112, guard112b): a trace.

guard111b left door-room arx_rf E_Z deployed 1.123 x unguarded and read it as the forest's bumps
past the linear held-step gain.  This bench asks which part of the guard cuts which rows, and
what the suggested rule (the band widened by the forest's leaf range: a forest outputs nothing
beyond the mean of its trees' extreme leaves) and other counterfactuals would give.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_guard112b.py trace OUT CASE         # the cut rows of E_Z, door room
    python benchmarks/bench_guard112b.py counter OUT CASE...    # deployed / unguarded per variant

CASE: a bench_guard111b case (``arx_rf/none``, ``arx/none``, ...), fitted on its door room (OUT as
bench_guard111b's: the rooms are made there once).  ``counter``'s variants, each on the fitted
deployment: ``as_is``; ``leaves``: E_Z's trained bound widened by its forest's leaf range;
``no_rate``: no rate limit; ``gain``: ``ARXRF.step_gain`` = its ARX's (the forest reads no
input: exact), refitted; ``unpaced``: the rate limit widened by the envelope clamp's own step
(``|take - last take|``); ``gain+unpaced``.

MEASURED (2026-12-08; bar benchmarks/guard112b_bar.md committed first, e67b3f37; src = 277c06b1's,
unchanged: the figures are BASE's and its counterfactuals').  ``trace arx_rf/none``: 65 of 80
test rows beyond training, 28 clamped (outside the envelope, off its pattern: outright, arx_rf has
no step gain); 27 rows cut, 9 off and 18 on the pattern; the free stream steps 2.309 um (median)
where the clamp switches, 0.247 elsewhere; rate limit 1.117 um per 120 s row; cut rows' SSE
133.92 deployed vs 90.69 unguarded, the on-pattern ones 54.33 vs 4.37, each >= 1.620 um under the
band (trained hi + allowance).  E_Z forest leaves [-0.0783, 0.0737] um; guard gain E_Z [1.3549,
0, 0, 1.9892, 0] = the ARX's analytic gain (|-1.3549|, 1.9892).
``counter`` deployed / unguarded E_Z: arx_rf/none as_is 1.1234, leaves 1.1074, no_rate 1.0006,
unpaced 1.1234, gain 1.1234, gain+unpaced 1.0006; arx/none (no forest) 1.1231, unpaced 1.0010;
mlr/none 1.0242, unpaced 1.0000 (``leaves`` moves the plain arx_rf only: a wrapper's forest is
inside it).  gain+unpaced elsewhere: arx_rf/ati and /diagnosed E_X 1.7597 -> 1.4142 (E_Z 1.1234
-> 1.0006), arx_rf/per-interval E_Z 1.0252 -> 1.0000 but E_X 0.9765 -> 1.0000 (deployed 12.5308
-> 12.8327 um: worse).  bench_guard111b ``cost``: arx_rf with ``state_column=null`` (no door)
E_Z 1.1228.
"""

from __future__ import annotations

import sys
from contextlib import contextmanager
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_guard111 as g111  # noqa: E402
import bench_guard111b as g111b  # noqa: E402
from _cli import run_commands  # noqa: E402


def _door(out: str) -> Path:
    return g111b._rooms(out)[1]


def _leaf_range(est) -> tuple[float, float]:
    """The forest's output bound: the mean over its trees of their smallest / largest leaf."""
    forest = getattr(est, "forest_", None)
    if forest is None:
        return 0.0, 0.0
    leaves = [e.tree_.value[e.tree_.children_left == -1, 0, 0] for e in forest.estimators_]
    return float(np.mean([v.min() for v in leaves])), float(np.mean([v.max() for v in leaves]))


def trace(out: str, case: str) -> None:
    """E_Z's test rows: beyond training, clamped, cut (on / off the pattern), by what."""
    from thermocomp.apps.deploy.streaming import replay

    dep, _, tests, _ = g111b._deployed(_door(out), case)
    g, env, comp = dep.guard, dep.envelope, dep.compensator
    k = dep.targets_.index("E_Z")
    est = dep.streaming._plan[k][1]
    print(f"{case}: rate limit {g.max_rate_per_s[k] * g.period_s:.4g} um per row, trained hi "
          f"{g.hi[k]:.4g}, guard gain {np.round(g.in_gain[k], 4).tolist()}, forest leaves "
          f"{np.round(_leaf_range(est), 4).tolist()}")
    for cid, df in tests.items():
        df = df.reset_index(drop=True)
        meas = comp.measured({cid: df})[cid]["E_Z"].to_numpy(float)
        dep_y = replay(dep, df)["E_Z"].to_numpy(float)
        free = replay(dep.streaming, df)["E_Z"].to_numpy(float)
        X = comp.stacked({cid: df}, targets=[]).X.to_numpy(float)
        d = np.maximum(X - g.in_hi, g.in_lo - X)
        clamped = ((X < env.lo) | (X > env.hi)).any(axis=1) & np.array([env.leaves_pattern(x) for x in X])
        cut = np.abs(dep_y - free) > 1e-9
        on = cut & ~clamped
        switch = clamped[1:] != clamped[:-1]
        step = np.abs(np.diff(free))
        n_off, n_on = int((cut & clamped).sum()), int(on.sum())
        print(f"{cid}: rows {len(df)}, beyond training {int((d.max(axis=1) > 0).sum())}, clamped "
              f"(off the pattern) {int(clamped.sum())}, cut {int(cut.sum())} (off {n_off}, on {n_on}); "
              f"free |step| at a clamp switch {np.median(step[switch]):.3f}, "
              f"else {np.median(step[~switch]):.3f} um")
        band = g.hi[k] + np.maximum(d, 0.0) @ g.in_gain[k]
        sq_dep, sq_free = (dep_y - meas) ** 2, (free - meas) ** 2
        print(f"  SSE cut rows deployed {sq_dep[cut].sum():.2f} vs unguarded {sq_free[cut].sum():.2f} "
              f"(on the pattern {sq_dep[on].sum():.2f} vs {sq_free[on].sum():.2f}); on-pattern cut rows "
              f"under the band by >= {np.min(band[on] - dep_y[on]):.3f} um")


@contextmanager
def _patched(obj, name: str, value):
    old = obj.__dict__.get(name)
    setattr(obj, name, value)
    try:
        yield
    finally:
        if old is None:
            delattr(obj, name)
        else:
            setattr(obj, name, old)


def _unpaced():
    """The guard's rate limit widened, at each row, by the clamp's own step since the last row."""
    from thermocomp.apps.deploy.guard import CorrectionGuard, rate_span

    step = CorrectionGuard.step

    def unpaced(self, y, dt, time, new_state=False, allowance=None, take=None):
        last, rate = getattr(self, "_last_take", None), self.max_rate_per_s
        if take is not None and last is not None:
            self.max_rate_per_s = rate + np.abs(take - last) / rate_span(float(dt), self.period_s)
        try:
            return step(self, y, dt, time, new_state, allowance, take)
        finally:
            self.max_rate_per_s, self._last_take = rate, take
    return _patched(CorrectionGuard, "step", unpaced)


def _arx_gain():
    """``ARXRF.step_gain``: its ARX's (the forest reads the machine state, never ``X``)."""
    from thermocomp.core.context import step_gain
    from thermocomp.core.models.arx_rf import ARXRF

    def gain(self, state=None, horizon_s=np.inf):
        return step_gain(self.arx_, None if state is None else state["arx"], horizon_s)
    return _patched(ARXRF, "step_gain", gain)


def _score(dep, tests, case: str, variant: str) -> None:
    for t, (rows, d, f) in g111._scores(dep, tests).items():
        print(f"{case:20s} {variant:13s} {t}: guarded {rows:3d} deployed {d:.4f} unguarded {f:.4f} "
              f"ratio {d / f:.4f}", flush=True)


def counter(out: str, *cases: str) -> None:
    """Per case and variant (module doc): per target deployed / unguarded."""
    for case in cases:
        dep, _, tests, _ = g111b._deployed(_door(out), case)
        g, k = dep.guard, dep.targets_.index("E_Z")
        _score(dep, tests, case, "as_is")
        lo, hi, rate = g.lo.copy(), g.hi.copy(), g.max_rate_per_s.copy()
        low, high = _leaf_range(dep.streaming._plan[k][1])
        g.lo[k], g.hi[k] = lo[k] + low, hi[k] + high
        _score(dep, tests, case, "leaves")
        g.lo, g.hi, g.max_rate_per_s = lo, hi, np.full_like(rate, np.inf)
        _score(dep, tests, case, "no_rate")
        g.max_rate_per_s = rate
        with _unpaced():
            _score(dep, tests, case, "unpaced")
        with _arx_gain():
            dep, _, tests, _ = g111b._deployed(_door(out), case)
            _score(dep, tests, case, "gain")
            with _unpaced():
                _score(dep, tests, case, "gain+unpaced")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "counter": counter}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
