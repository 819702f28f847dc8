"""The guard's gain for an ATI model at a test A0 outside training's A0s (stop 112, guard112).

bench_guard111b measured on bench_dep108c's made room (train A0 14-23.6 C, test 26 C) E_X deployed
1.567 x unguarded for mlr/ati and lstm/ati: ``adaptive.input_gains`` takes an A0-dependent gain as
the largest |gain| over the TRAINING A0s (dep108c), the held steps likewise from training states.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_guard112.py trace OUT CASE [DATA]   # which rows are cut, and why

``trace``: CASE (bench_guard111b's CASES) on DATA (default: the made room), per target of the test
campaigns: rows guarded, the bound they hit (hi / lo), the inputs past training (max excess), the
guard's gain row served, and the gain of the interval model the stream runs at the test A0 (its
analytic ``step_gain`` from ``stream_init`` at that A0, or the held steps of ``held_gains`` with
the training prefixes read at that A0: what the served row would be had training been there),
and what-ifs: that gain served, no pattern gate on the widening, no rate limit, no envelope clamp.

MEASURED (2026-12-08; bar benchmarks/guard112_bar.md committed first, 12672e46; BASE = 277c06b1's
src, a detached worktree, each trace run there and here at once: outputs identical, src unchanged;
CPU user + sys 2.3 s mlr/ati, 7.3 s lstm/ati).  No seed drawn.
Made room, test K5 (A0 25.96 C; training 14.09-23.61), 80 rows, inputs past training on 65.
  E_X, mlr/ati (lstm/ati the same to 4 digits: its LSTM kept epoch 0, the linear skip path):
  deployed 12.1263, unguarded 7.7398 um (1.567 x); 61 rows cut, all at the hi bound 22.694 um.
  29 of them are rows past training OFF the envelope's training pattern (residual 0.037-0.042
  against tol 0.0355, the training maximum; test past-range median 0.034, 45 % over): there
  the guard does not widen (``widening`` -> None) and the plain stream's clamp acts (25.6 um
  against 40 unclamped; the clamp's output at in-range inputs is above the bound by the A0
  interaction's extrapolation); the other 32 are on the pattern, paced by the rate limit back up
  from the bound (e.g. 22.69 -> 25.10 -> 29.93 while the bound + allowance was 35.6-47.9).
  The gain row served [0.94 4.79 1.80 0.39 1.09] vs |gain| at A0 25.96 [0.59 6.08 2.54 0.52 1.55]:
  the gain at the test A0 IS larger, but served it changes 1 row: 12.1263 -> 12.1259 um.
  What-ifs: no pattern gate 6.6633; no rate limit 9.4505; both 7.7420 (= unguarded); plain stream
  without its envelope clamp 0.4723 um (the clamp's flips are the cost, unguarded included).
  E_Z: 27 rows cut, all rate pacing of the clamp's flips (no rate limit: = unguarded 1.5681).
Climate room 10158 (test A0 15.8-23.6 C, inside training's 15.4-29.5; 88 s CPU for lstm/ati):
  mlr/ati and lstm/ati deployed <= unguarded on every test campaign and target (C12 E_X 1.0822 vs
  1.2990, 1.0319 vs 1.2622; no other row cut); no A0 past training there.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_guard111b as g111b  # noqa: E402
from _cli import run_commands  # noqa: E402


def _gain_at(est, m, a0: float, horizon: float, period: float) -> np.ndarray | None:
    """|gain| of ``est`` in a campaign of initial ambient ``a0``: analytic, else held steps with
    every training campaign read at ``a0``."""
    from thermocomp.apps.deploy.held_gains import stepped_gain
    from thermocomp.core.context import AMBIENT_C0, step_gain
    from thermocomp.core.frame import context_record

    g = step_gain(est, est.stream_init(context_record("s", 0.0, a0, {})), horizon)
    if g is not None:
        return np.abs(g)
    ctx = m.context.assign(**{AMBIENT_C0: a0})
    return stepped_gain(est, m.X.to_numpy(float), ctx, horizon, period)


def _what_if(deployed, df, targets, **change) -> np.ndarray:
    """``deployed``'s outputs on ``df`` with one thing changed for the replay: ``gain`` (the guard's
    gain rows), ``gate=False`` (the bound widens past training off the training pattern too),
    ``rate=False`` (no rate limit), ``clamp=False`` (the plain stream without its envelope)."""
    from contextlib import ExitStack
    from unittest import mock

    from thermocomp.apps.deploy import guard as guard_mod
    from thermocomp.apps.deploy.streaming import replay

    g = deployed.guard
    with ExitStack() as stack:
        if "gain" in change:
            stack.enter_context(mock.patch.object(g, "in_gain", np.abs(change["gain"])))
        if change.get("gate") is False:
            stack.enter_context(mock.patch.object(guard_mod, "widening", _ungated))
        if change.get("rate") is False:
            stack.enter_context(mock.patch.object(g, "max_rate_per_s", np.full(len(targets), np.inf)))
        if change.get("clamp") is False:
            stack.enter_context(deployed.streaming.envelope_off())
            return replay(deployed.streaming, df)[targets].to_numpy(float)
        return replay(deployed, df)[targets].to_numpy(float)


def _ungated(x, lo, hi, gain, envelope):
    """:func:`thermocomp.apps.deploy.guard.widening` without its pattern gate (the what-if)."""
    d = np.maximum(np.maximum(x - hi, lo - x), 0.0)
    return gain @ d if d.max() > 0.0 else None


def trace(out: str, case: str, data: str = "room") -> None:
    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.core.frame import initial_ambient

    rooms = dict(zip(("room", "door_room"), g111b._rooms(out)))
    deployed, train, tests, _ = g111b._deployed(rooms.get(data, Path(data)), case)
    g, s = deployed.guard, deployed.streaming
    comp = s.compensator
    m = comp.stacked(train, targets=[])
    a0_train = sorted(initial_ambient(df) for df in train.values())
    print(f"{case}: training A0 {np.round(a0_train, 2).tolist()}; inputs {deployed.columns_}")
    for cid, df in tests.items():
        df = df.reset_index(drop=True)
        a0 = initial_ambient(df)
        dep = replay(deployed, df)[deployed.targets_].to_numpy(float)
        free = replay(s, df)[deployed.targets_].to_numpy(float)
        meas = comp.measured({cid: df})[cid][deployed.targets_].to_numpy(float)
        x = comp.stacked({cid: df}, targets=[]).X.to_numpy(float)
        d = np.maximum(np.maximum(x - g.in_hi, g.in_lo - x), 0.0)
        past = int((d > 0).any(axis=1).sum())
        print(f"  {cid}: A0 {a0:.2f}; rows {len(df)}; inputs past training on {past} rows, "
              f"max excess {np.round(d.max(axis=0), 3).tolist()}")
        for k, (t, est, _) in enumerate(s._plan):
            cut = ~np.isclose(dep[:, k], free[:, k], rtol=0, atol=1e-9)
            hi = cut & (free[:, k] > dep[:, k])
            at = _gain_at(est, m, a0, s.envelope.horizon_s, g.period_s)
            rms = lambda e: float(np.sqrt(np.nanmean(e ** 2)))  # noqa: E731
            print(f"    {t} ({type(est).__name__}): rows cut {int(cut.sum())} ({int(hi.sum())} at the hi "
                  f"bound {g.hi[k]:.3f}, {int((cut & ~hi).sum())} at lo {g.lo[k]:.3f}); deployed "
                  f"{rms(dep[:, k] - meas[:, k]):.4f} unguarded {rms(free[:, k] - meas[:, k]):.4f} um; "
                  f"largest model output {np.nanmax(np.abs(free[:, k])):.3f}")
            print(f"      gain row served {np.round(g.in_gain[k], 3).tolist()}")
            print(f"      |gain| at A0 {a0:.2f} {None if at is None else np.round(at, 3).tolist()}")
            for a in a0_train:
                ga = _gain_at(est, m, a, s.envelope.horizon_s, g.period_s)
                print(f"        at training A0 {a:.2f}: {None if ga is None else np.round(ga, 3).tolist()}")
            off = np.array([s.envelope.leaves_pattern(xi) for xi in x]) & (d > 0).any(axis=1)
            print(f"      rows cut off the training pattern (no widening there) {int((cut & off).sum())}, "
                  f"on it {int((cut & ~off).sum())}; the plain stream's clamp acts on "
                  f"{int(off.sum())} rows past training off the pattern")
            gain = g.in_gain.copy()
            if at is not None:
                gain[k] = np.maximum(gain[k], at)
            for name, change in (("gain max(served, at test A0)", {"gain": gain}),
                                 ("no pattern gate on the widening", {"gate": False}),
                                 ("no rate limit", {"rate": False}),
                                 ("both (gate, rate) off", {"gate": False, "rate": False}),
                                 ("plain stream, no envelope clamp", {"clamp": False})):
                y = _what_if(deployed, df, deployed.targets_, **change)[:, k]
                moved = int((~np.isclose(y, free[:, k], atol=1e-9)).sum())
                print(f"      what if {name}: deployed {rms(y - meas[:, k]):.4f} um "
                      f"(rows differing from the plain stream {moved})")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
