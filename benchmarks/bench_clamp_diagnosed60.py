"""A diagnosed model clamped by its step gain, as a plain one is (clampdiag60).

Per record (``simulate``: a planted ambient law, seed 6003, and the swiss lathe's door, seed 5971,
as benchmarks/bench_diagnosed_to_code59.py simulates them) and base (lag bank, MLR): the plain
model and the same base diagnosed with a fixed effect (the ambient law ``x (A0 - 20)``; the
door's lag, ``first_order_lag`` of ``S_door``), each deployed as ``promote`` deploys it
(envelope clamp, its pattern gate), streamed by ``replay`` on every test campaign with

* ``row``: one row (a third in) of one referenced input over its envelope bound by 0.15 K, each
  such input in turn;
* ``slow``: one input drifting from mid-campaign to 0.5 K over its bound at the end (a ramp),
  each in turn;

against the same stream with the clamp off (the model's own response, ``batch``).  Columns: the
largest ``|deployed - batch|`` (µm) over rows, targets, campaigns and inputs, and its ratio to
the plain rule's bound ``|gain @ e|`` of the row (> 1: the clamp took out more than the held
excess is worth; ``outright`` when the model has no gain).  Run it with the code before and
after the change (``PYTHONPATH``).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_clamp_diagnosed60.py

Measured (2026-11-30; test campaigns the stream does not clamp as recorded: 70 planted cases
per kind on ambientlaw6003, 12 on door5971; ~20 s of CPU a run).  The plain models and the
diagnosed MLR are the same before and after (a static model: the clamped stream's response is
the bound); the diagnosed lag bank, clamped outright before, took out up to 83x the plain
rule's bound (its opposed lag weights on the flattened input), now within it:

    max |deployed - batch| um (ratio to the plain bound)   before            after
    ambientlaw6003 lagbank  plain       row / slow          1.322 / 15.521 (1.000, unchanged)
    ambientlaw6003 lagbank  diagnosed   row                 0.408 (83.3)      0.359 (1.000)
    ambientlaw6003 lagbank  diagnosed   slow                1.149 (83.3)      0.738 (1.000)
    ambientlaw6003 mlr      diagnosed   row / slow          1.618 / 5.395 (1.000, unchanged)
    door5971       lagbank  plain       row / slow          0.472 / 1.615 (1.000, unchanged)
    door5971       lagbank  diagnosed   row                 0.618 (24.2)      0.201 (1.000)
    door5971       lagbank  diagnosed   slow                2.582 (88.5)      0.687 (1.000)
    door5971       mlr      diagnosed   row / slow          0.995 / 3.317 (1.000, unchanged)

``lowpass`` (gain61, measured 2026-12-01, ~36 s of CPU a run): the diagnosed effect a 3600 s
low-pass copy of the inputs, over an ARX base too (``model=arx``); the bound of a diagnosed model
is its streamed held unit step (:func:`_held_gain`, not the code's gain).  A diagnosed ARX was
clamped outright: on ambientlaw6003 (E_Z's feedback 0.97, E_X and E_Y static, all reading the
copy; 93 samples to the 27,900 s horizon) it took out up to 111x that bound; now its own gain.
The door record's ARX models are static, its horizon 80 h: the copy held whole, outright = bound.

    max |deployed - batch| um (ratio to the held bound)    before            after
    ambientlaw6003 arx      diagnosed   row                 2.062 (110.865)   2.062 (1.000)
    ambientlaw6003 arx      diagnosed   slow                8.128 (110.865)   8.128 (1.000)
    ambientlaw6003 lagbank  diagnosed   row / slow          1.269 / 14.740 (1.000, unchanged)
    ambientlaw6003 mlr      diagnosed   row / slow          1.651 / 17.586 (1.000, unchanged)
    door5971       arx      diagnosed   row / slow          2.611 / 9.750 (1.000, unchanged)
    door5971       lagbank  diagnosed   row / slow          0.477 / 1.635 (1.000, unchanged)
    door5971       mlr      diagnosed   row / slow          1.988 (0.370) / 13.104 (1.000, unchanged)
    (the plain models: as above for lagbank; mlr 3.536 / 11.787 and 2.601 / 9.096, arx 2.899 /
    9.665 and 2.602 / 9.099, ratio 1.000, unchanged)

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_clamp_diagnosed60.py lowpass
"""

from __future__ import annotations

import copy
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
from hydra import compose, initialize_config_dir
from sklearn.base import clone

ROOT = Path(os.environ.get("BENCH_ROOT", "/tmp/clampdiag60-root"))
REPO = Path(__file__).resolve().parents[1]
EXCESS_K, SLOW_K = 0.15, 0.5
RECORDS = {   # name: (simulate overrides, the diagnosed effect)
    "ambientlaw6003": (["sim=yearround_spindle", "seed=6003", "sim.generator.effects=[ambient_law]"],
                       {"kind": "ambient_interval", "transform": "ambient_linear"}),
    "door5971": (["sim=swiss_lathe_door", "seed=5971"],
                 {"kind": "signal", "transform": "first_order_lag", "column": "S_door",
                  "tau_s": 900.0}),
}


def _data(name: str) -> Path:
    path = ROOT / "data" / name
    if not path.exists():
        env = dict(os.environ, PYTHONPATH=str(REPO / "src"))
        subprocess.run([sys.executable, "-m", "thermocomp", "simulate", *RECORDS[name][0],
                        f"data.path={path}", "track=false"], cwd=REPO, env=env, check=True,
                       capture_output=True)
    return path


def _streams(path: Path, family: str, effect: dict):
    from thermocomp.apps.diagnose import AugmentedRegressor
    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import build_compensator, deploy_stream
    from thermocomp.shell.source import read_streamed
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"data.path={path}", f"model={family}",
                                                         "track=false", "monitor.adaptive=false"])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    plain = build_compensator(cfg, ds=ds)
    diagnosed = clone(plain)
    plain.fit(train)
    diagnosed.set_params(estimator=AugmentedRegressor(
        clone(plain.estimator), effects={t: [effect] for t in plain.targets_})).fit(train)
    tests = [ds.campaigns[c].reset_index(drop=True) for c in test_ids]
    return {kind: deploy_stream(cfg, comp, train)
            for kind, comp in (("plain", plain), ("diagnosed", diagnosed))}, tests


def _planted(stream, tests):
    """Per planted campaign ``(kind, df, input index)``, of the test campaigns the stream does
    not clamp as recorded (the planted excess the only one)."""
    from thermocomp.apps.deploy.streaming import replay
    env = stream.envelope
    for df in tests:
        if replay(stream, df)["n_clamped"].any():
            continue
        for j, col in enumerate(stream.columns_):
            if not col.startswith("T_"):
                continue
            one = df.copy()
            one.loc[len(df) // 3, col] = df.loc[0, col] + env.hi[j] + EXCESS_K
            yield "row", one, j
            slow = df.copy()
            dx = slow[col] - slow.loc[0, col]
            mid = len(df) // 2
            ramp = np.clip((np.arange(len(df)) - mid) / max(len(df) - 1 - mid, 1), 0, None)
            slow[col] = slow[col] + ramp * (env.hi[j] + SLOW_K - dx.iloc[-1])
            yield "slow", slow, j


def _plain_gain(est, a0: float, horizon_s: float) -> np.ndarray | None:
    """The plain rule's gain per input, written out (the same before and after the change): a
    plain model's step gain; a diagnosed one's base gain on x, plus A0 - 20 times its ambient
    law's block (a lag of S_door does not move with x); with a low-pass copy of the inputs the
    streamed response to a unit step held for the horizon (:func:`_held_gain`)."""
    from thermocomp.apps.diagnose import AugmentedRegressor
    from thermocomp.core.context import step_gain
    if not isinstance(est, AugmentedRegressor):
        return step_gain(est, None, horizon_s)
    if any(e.transform == "lowpass_inputs" for e in est.effects_):
        return _held_gain(est, a0, horizon_s)
    base = step_gain(est.estimator_, None, horizon_s)
    k = int(est.n_features_in_)
    law = any(e.transform == "ambient_linear" for e in est.effects_)
    return base[:k] + ((a0 - 20.0) * base[k:2 * k] if law else 0.0)


_HELD: dict = {}


def _held_gain(est, a0: float, horizon_s: float) -> np.ndarray:
    """Per input, the change of ``est``'s streamed prediction after a unit step of it held for
    ``horizon_s`` (one sample a period, from rest, the context's signals 0): the clamp's gain by
    its definition, whatever the code computes."""
    from thermocomp.core.context import RESERVED, context_columns, stream_steps
    key = (id(est), a0, horizon_s)
    if key not in _HELD:
        dt = float(est.sample_period_s_)
        rows, n = int(round(horizon_s / dt)) + 1, int(est.n_features_in_)
        context = {c: np.zeros(rows) for c in context_columns(est) if c not in RESERVED}
        context.update(campaign="held", time=np.arange(rows) * dt, ambient_c0=a0)
        start = {"campaign": "held", "time": 0.0, "ambient_c0": a0}

        def last(X):
            return stream_steps(est, X, est.stream_init(start), context)[0][-1]
        still = last(np.zeros((rows, n)))
        _HELD[key] = np.array([last(np.where(np.arange(rows)[:, None] > 0, np.eye(n)[j], 0.0))
                               for j in range(n)]) - still
    return _HELD[key]


def _case(stream, tests) -> dict:
    import pandas as pd

    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.core.frame import ambient_c0
    off = copy.deepcopy(stream)
    off.policy = "off"
    worst, n = {}, {}
    for kind, df, j in _planted(stream, tests):
        n[kind] = n.get(kind, 0) + 1
        got, own = replay(stream, df), replay(off, df)
        moved = (got[stream.targets_] - own[stream.targets_]).abs().to_numpy(float)
        col = stream.columns_[j]
        dx = (df[col] - df.loc[0, col]).to_numpy(float)
        excess = np.clip(dx - stream.envelope.hi[j], 0, None)
        held = pd.Series(np.where(excess > 0, excess, np.nan)).ffill().fillna(0.0).to_numpy()
        a0 = ambient_c0(df[[stream.columns_[i] for i in stream._amb_idx]].to_numpy(float)[0])
        ratio = 0.0
        for k, (_, est, idx) in enumerate(stream._plan):
            g = _plain_gain(est, a0, stream.envelope.horizon_s)
            gj = abs(g[j if idx is None else list(idx).index(j)])
            with np.errstate(divide="ignore", invalid="ignore"):
                r = np.where(moved[:, k] > 1e-12, moved[:, k] / (gj * held), 0.0)
            ratio = max(ratio, float(np.nanmax(r)))
        big, worst_ratio = worst.get(kind, (0.0, 0.0))
        worst[kind] = (max(big, float(moved.max())), max(worst_ratio, ratio))
    return {kind: (*w, n[kind]) for kind, w in worst.items()}


LOWPASS = {"kind": "dynamics", "transform": "lowpass_inputs", "tau_s": 3600.0}


def main(argv: list[str]) -> None:
    """``lowpass``: the diagnosed effect a low-pass copy of the inputs (gain61), over an ARX
    base too; else each record's own effect."""
    lowpass = "lowpass" in argv
    print("record          base      model      planted  cases  max|dep-batch| um  /plain bound")
    for name, (_, own) in RECORDS.items():
        path = _data(name)
        effect = LOWPASS if lowpass else own
        for family in ("lagbank", "mlr", "arx") if lowpass else ("lagbank", "mlr"):
            streams, tests = _streams(path, family, effect)
            for kind, stream in streams.items():
                for planted, (big, ratio, cases) in _case(stream, tests).items():
                    print(f"{name:15s} {family:9s} {kind:10s} {planted:8s} {cases:5d} {big:18.3f}  "
                          f"{ratio:.3f}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
