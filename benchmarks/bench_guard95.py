"""Why the correction guard's rate limit fires on a healthy room ramp beyond training (guard95; trace).

audit95 (bench_audit95.py, S4) found 2-9 monitor events in 9 of 11 cells of its fresh cr9762
(climate_room, 12 runs, test C10 / C11 / C12), every one the correction guard's rate limit, all
on C11: a room ramped +5 K, where training held rooms or ramped them -5 K.  This traces where the
limit is set, what it costs or saves on C11 and what trips it.  No source change, no fresh seed.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``; audit95's spent record and models,
copied: ``DATA`` its ``data/cr9762``, ``MODELS/<cell>/model.pkl`` its ``reports/cr9762/<cell>``)::

    python benchmarks/bench_guard95.py trace DATA MODELS mlr-none mlr-ati pcr-none ...
    python benchmarks/bench_guard95.py hysteresis DATA MODELS 0.8 mlr-none mlr-ati ...

``trace``: per cell, the model made deployable as ``replay`` makes it (default config) and the
test campaigns streamed from a reset three times: as deployed (``guard``), with the rate limit
off (``monitor.guard.rate_margin=1e9``: ``norate``) and with the envelope's training-pattern gate
off (``promote.envelope.pattern=false``: every excursion clamped, ``nogate``); beside them the
model's batch prediction (``raw``: no clamp, no guard).  Printed: the guard's limit (µm per 60 s
sample; ``guard.CorrectionGuard.from_training``: (1 + ``rate_margin`` 1.0) x the fastest change
in training of the measured error or of the model's correction), each train campaign's fastest
measured / model change, per test campaign the events, RMSE per target of each stream, the
fastest change of the measured error, of ``raw`` and of ``norate``; on C11 the rows where
``norate`` steps beyond the limit and the envelope clamp count before -> at them; the envelope's
inputs beyond their bound on C11, its gate's residual / tol there and how often the clamp
switches on or off; the room's fastest ramp (15-min slope of T_amb, K/h) per campaign.
``hysteresis``: the same deployed streams with the envelope's pattern gate patched in this
process only (``Envelope.leaves_pattern``: off the pattern above ``tol``, and stays off until
the residual falls below ``H`` x ``tol``; the state reset with each campaign; the guard's bound
allowance reads the same gate): C11's events, clamped rows, switches, RMSE; C10 / C12's.

Traced (2026-12-06, at bc37bd53, the 11 cells of audit95 less the 2 ``auto-none`` / ``lstm-none``
copies of ``mlr-none``; events as audit95's in every cell: 7 3 5 5 9 0 5 0 2)::

  limit: 2.80-3.20 µm/60 s (E_X), 3.40-4.43 (E_Z): 2 x the fastest training change, the
         measured error's (1.4 / 1.7, C02 / C08) or the model's where faster (mlr-none 1.60 /
         2.17, C02 / C03); pcr-none, pcr-ati, lagbank-none, lagbank-ati: 2.8 / 3.4 (measured)
  room:  fastest T_amb slope C11 1.79 K/h; train C08 1.70 (-5 K), C09 1.49; held 0.33-0.46
  C11, fastest change µm/60 s, E_X / E_Z: measured 1.4 / 1.5; raw model <= 1.21 / 1.65
         (every cell below its limit); norate stream 1.32-4.42 / 1.60-6.33 (the 7 cells with
         events)
  C11 envelope: T_amb and T_nc_cabinet (referenced) beyond their bound on 156 of 209 rows
         (+3.57 / +2.80 K at most over training's +0.64 / +0.91); clamped (beyond AND off the
         training pattern) 50 rows; the clamp switches on/off 58 times; residual / tol on the
         156 rows: median 0.909, 32 % within 0.9-1.1 (the gate sits on its threshold)
  every row where norate steps beyond the limit is a row where the clamp switches (0 <-> 2
         inputs clamped), in all 7 cells with events; the raw model moves <= 1.04 / 1.37 µm there

  C11 RMSE µm E_X / E_Z    guard             norate            nogate            raw
  mlr-none                 1.1963 / 2.0324   1.2150 / 2.0330   1.5009 / 2.2898   1.2895 / 2.3132
  mlr-ati                  2.1462 / 1.4843   2.1459 / 1.4843   1.2714 / 1.5026   2.5099 / 1.5239
  pcr-none                 1.6347 / 1.4107   1.6795 / 1.4107   1.1574 / 1.1566   2.0414 / 1.5609
  pcr-ati                  1.5607 / 2.2626   1.5607 / 2.3473   1.2994 / 1.5411   1.6789 / 2.7827
  arx-none                 1.1334 / 1.9157   1.1691 / 1.9157   1.4986 / 2.1280   1.2198 / 2.0588
  arx-ati                  1.6413 / 1.4813   1.6413 / 1.4813   1.5060 / 1.5420   1.7886 / 1.4322
  lagbank-none             1.4023 / 2.0078   1.4023 / 2.0761   1.0052 / 2.5464   1.3298 / 1.4115
  lagbank-ati              0.8549 / 1.3394   0.8549 / 1.3394   1.0292 / 1.2061   0.6926 / 1.4628
  lstm-ati                 1.9178 / 1.4959   1.9177 / 1.4959   1.1917 / 1.4125   2.2211 / 1.6024
  C10, C12: 0 events, guard = norate = nogate = raw in every cell; nogate: 0 events everywhere.

Verdict TRACED: the rate limit is a guard doing its job, not a bound a healthy extrapolation
should pass.  The room does not ramp faster than training (1.79 against 1.70 K/h) and the model's
own correction stays below the limit (<= 1.21 / 1.65 against >= 2.8 / 3.4 µm/60 s); what trips
it is the envelope clamp switching on and off from row to row (4.4 µm steps), its pattern gate
riding its threshold on the room's two inputs beyond training.  The limit saves up to 0.045 (E_X,
pcr-none) and 0.085 µm (E_Z, pcr-ati) of C11's RMSE and costs at most 0.0003 (mlr-ati E_X).
The defect, if one, is the gate's lack of hysteresis (streaming.Envelope.leaves_pattern), not the
guard.  Clamping every excursion (nogate) silences the chatter (0 events in all 9 cells) but is no
mend by itself: C11's RMSE falls in 10 of 18 cell-targets (pcr-ati E_Z 2.263 -> 1.541, lstm-ati
E_X 1.918 -> 1.192) and rises in 8 (lagbank-none E_Z 2.008 -> 2.546, arx-none E_X 1.133 -> 1.499).
A gate with hysteresis (``hysteresis`` 0.8, measured after the trace, no bar: a look, not a
rule) is no clear mend either: switches 58 -> 17, 95 rows clamped, events 36 -> 31 over the 9
cells (mlr-none 7 -> 3, lagbank-none 5 -> 0, lstm-ati 2 -> 0, but pcr-none 5 -> 7, pcr-ati 5 -> 9);
C11's RMSE falls in 12 of 18 cell-targets (pcr-ati E_Z 2.263 -> 1.496) and rises in 6
(lagbank-ati E_X 0.855 -> 1.001, lagbank-none E_Z 2.008 -> 2.178); C10 / C12 unchanged, 0 events.
Not built: a rule would want its bar on more than one ramped test campaign (one here).
CPU (this process, 2 shared cores): trace 55.7 s for the 9 cells (1 min 55 s wall), hysteresis
21.6 s (27 s wall).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402

VARIANTS = {"guard": [], "norate": ["monitor.guard.rate_margin=1e9"],
            "nogate": ["promote.envelope.pattern=false"]}


def _fastest(y: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Largest |change| per 60 s of each column of ``y`` (n, k) at times ``t`` (s)."""
    return np.nanmax(np.abs(np.diff(y, axis=0)) / np.diff(t)[:, None], axis=0) * 60.0


def _r(a) -> list:
    return np.round(np.asarray(a, float), 4).tolist()


def _streams(data: str, model: str, overrides: list[str]) -> tuple:
    """``(deployed, dataset, train ids, {test id: (y, clamped, events)})`` from a reset."""
    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.source import read_streamed

    cfg = compose([f"data.path={data}", "track=false", *overrides], "replay")
    ds, train, test, _ = read_streamed(cfg)
    dep, _, _ = deployable_model(cfg, ds, train, model, "replay.model")
    out = {}
    for c in test:
        s = stream_rows(dep, ds.campaigns[c], c)
        out[c] = (s.y, s.clamped, len(s.events))
    return dep, ds, train, out


def _gate(dep, ds, cid: str) -> str:
    """The envelope on ``cid``: inputs beyond their bound, the gate's residual / tol, switches."""
    env, comp = dep.streaming.envelope, dep.compensator
    x = comp.stacked({cid: ds.campaigns[cid]}, targets=[]).X.to_numpy(float)
    out = env.outside(x)
    beyond = out.any(axis=1)
    z = (x - env.mean) / env.scale
    r = z - (z @ env.basis) @ env.basis.T
    ratio = np.sqrt((r * r).sum(axis=1)) / env.tol
    clamped = beyond & (ratio > 1)
    cols = np.flatnonzero(out.any(axis=0))
    excess = (x - np.clip(x, env.lo, env.hi))[beyond][:, cols].max(axis=0)
    return (f"{cid} envelope: {[env.columns[j] for j in cols]} beyond bound on {int(beyond.sum())} "
            f"of {len(x)} rows, max excess {_r(excess)} over hi {_r(env.hi[cols])}; clamped "
            f"{int(clamped.sum())}; clamp switches {int(np.sum(np.diff(clamped.astype(int)) != 0))}; "
            f"residual/tol on those rows median {np.median(ratio[beyond]):.3f}, within 0.9-1.1 "
            f"{np.mean(np.abs(ratio[beyond] - 1) < 0.1):.2f}")


def trace(data: str, models: str, *cells: str) -> None:
    """Per cell (``MODELS/<cell>/model.pkl``): the guard's limit, where it came from, C10-C12
    streamed as deployed / rate limit off / gate off against the raw model (module doc)."""
    for cell in cells:
        model = str(Path(models) / cell / "model.pkl")
        runs = {k: _streams(data, model, ov) for k, ov in VARIANTS.items()}
        dep, ds, train, _ = runs["guard"]
        comp, g, tg = dep.compensator, dep.guard, dep.targets_
        print(f"== {cell}: rate limit {_r(g.max_rate_per_s * 60)} µm/60 s (period {g.period_s:g} s)")
        camps = {c: ds.campaigns[c] for c in train}
        pred = comp.predict(camps, mode="simulation")
        meas = comp.measured(camps, predicted=pred)
        for c in train:
            t = camps[c]["time"].to_numpy(float)
            print(f"   train {c}: fastest measured {_r(_fastest(meas[c][tg].to_numpy(float), t))}"
                  f" model {_r(_fastest(pred[c][tg].to_numpy(float), t))}")
        for c in runs["guard"][3]:
            df = ds.campaigns[c]
            t = df["time"].to_numpy(float)
            m = comp.measured({c: df})[c][tg].to_numpy(float)
            raw = comp.predict({c: df}, mode="simulation")[c][tg].to_numpy(float)
            ys = {k: runs[k][3][c][0] for k in runs}
            rmse = {k: _r(np.sqrt(np.nanmean((m - y) ** 2, axis=0))) for k, y in [*ys.items(), ("raw", raw)]}
            print(f"   {c}: events {[runs[k][3][c][2] for k in runs]} (guard/norate/nogate); RMSE {rmse}; "
                  f"fastest measured {_r(_fastest(m, t))} raw {_r(_fastest(raw, t))} "
                  f"norate {_r(_fastest(ys['norate'], t))}")
            if c != "C11":
                continue
            cl = runs["norate"][3][c][1]
            steps = np.abs(np.diff(ys["norate"], axis=0)) > g.max_rate_per_s * g.period_s
            rows = np.flatnonzero(steps.any(axis=1)) + 1
            print(f"   C11: norate beyond the limit at {len(rows)} rows; clamp switches there "
                  f"{int(sum(cl[i - 1] != cl[i] for i in rows))}; raw |step| there max "
                  f"{_r(np.abs(raw[rows] - raw[rows - 1]).max(axis=0)) if len(rows) else []}")
            print("   " + _gate(dep, ds, c))
        slope = {c: _room_slope(ds.campaigns[c]["T_amb"].to_numpy(float),
                                ds.campaigns[c]["time"].to_numpy(float))
                 for c in [*train, *runs["guard"][3]]}
        print("   T_amb fastest 15-min slope K/h: " + ", ".join(f"{c} {v:.2f}" for c, v in slope.items()))


def _room_slope(T: np.ndarray, t: np.ndarray, n: int = 15) -> float:
    """Largest |least-squares slope| of ``T`` over ``n`` consecutive samples, K/h."""
    win = np.lib.stride_tricks.sliding_window_view
    tt, TT = win(t, n), win(T, n)
    tc = tt - tt.mean(axis=1, keepdims=True)
    slope = (tc * (TT - TT.mean(axis=1, keepdims=True))).sum(axis=1) / (tc * tc).sum(axis=1)
    return float(np.max(np.abs(slope)) * 3600.0)


def hysteresis(data: str, models: str, h: str, *cells: str) -> None:
    """Per cell: the test campaigns streamed as deployed with the pattern gate given hysteresis
    ``h`` (module doc; patched in this process only)."""
    from thermocomp.apps.deploy import report, streaming

    state = {"off": False}
    h2 = float(h) ** 2

    def leaves(env, x):      # idempotent for one x: _step asks the clamp's and the bound's gate
        if env.basis is None:
            return True
        z = (x - env.mean) / env.scale
        r = z - env.basis @ (env.basis.T @ z)
        q = float(r @ r) / env.tol ** 2
        state["off"] = q > 1.0 or (state["off"] and q > h2)
        return state["off"]

    def fresh(*args, **kwargs):
        state["off"] = False
        return stream(*args, **kwargs)

    stream = report.stream_rows
    streaming.Envelope.leaves_pattern, report.stream_rows = leaves, fresh
    for cell in cells:
        dep, ds, _, out = _streams(data, str(Path(models) / cell / "model.pkl"), [])
        comp, tg = dep.compensator, dep.targets_
        line = []
        for c, (y, cl, ev) in out.items():
            m = comp.measured({c: ds.campaigns[c]})[c][tg].to_numpy(float)
            line.append(f"{c} events {ev} clamped {int((cl > 0).sum())} switches "
                        f"{int(np.sum(np.diff((cl > 0).astype(int)) != 0))} "
                        f"RMSE {_r(np.sqrt(np.nanmean((m - y) ** 2, axis=0)))}")
        print(f"{cell} H={h}: " + "; ".join(line))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "hysteresis": hysteresis}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
