"""Why the training-envelope clamp costs one target (``E_X``) on column records, with the
simulator's known truth; and one per-target rule that follows from it (env93, issue 34).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_env93.py trace ROOT SEEDS
    python benchmarks/bench_env93.py rule ROOT SEEDS

Both first run bench_env92's ``draw ROOT SEEDS`` (``column_moving_source`` seed by seed into
``ROOT/data/cms<seed>``; per family ``mlr``, ``arx``, ``lagbank`` the fitted model and its test
campaign replayed ``clamp`` / ``off`` / ``pattern`` (the shipped default), lines in
``ROOT/results.jsonl``; cells already there are not redone).

``trace`` (seen seeds only: 3141, 5003, 4253, 6007, 9406 (env92's and env92b's) and
9466-9475, 9412-9415 (env92's, spent there)): the same record simulated twice without noise
(``sim.generator.clean=true``), with and without the never-trained source Q3
(``sim.generator.q3``; into ``ROOT/truth``); the two differ only by Q3's part.  Per family and
target over the cells: the slope and correlation of the model's response to Q3's sensor change
(its prediction on the Q3 record less on the other) against the true Q3 part of the error, the
miss (RMS of their difference) over the true part's RMS, and in how many cells the clamp beats
``off`` on test (env92's replays).  Then which inputs the gate clamps (rows with an excess), each
input's share of ``|gain * excess|`` summed over those rows per target (the step gains the clamp
uses, ``adaptive.input_gains``), MLR's gains on the right face per target against the
thermoelastic map's own (E_X: -α Δz (H - h) / W per right-face node), and the lag-1
autocorrelation of each target's training residual (the model's simulation on its own train
campaign).

``rule``: the per-target rule below, decided per cell from the train campaign and the fitted
model alone; its test Σ² composed per target from the ``pattern`` / ``off`` replays (exact: these
families fit and stream one model per target, a target's prediction never depends on another's
clamp, bench_env92b); printed per cell against ``pattern``, with G, the cells either way and the
bar's verdict; "E_X alone unclamped" and the oracle (per target the better replay on test) beside.

THE RULE (chosen on the seen seeds above, from the trace; written before any fresh seed was drawn)
-------------------------------------------------------------------------------------------------
A target streams unclamped (its correction = ``off``'s) iff the lag-1 autocorrelation of its
training residual (measured error less the model's simulation on the train campaigns, pairs of
consecutive samples within a campaign) is below 0.5; every other target keeps the shipped gate.
Why: a target whose model leaves white noise on training has nothing left for an unmeasured node
to explain: its physics lies in the sensors (E_X: the left and right faces, both measured) and
its model carries a new source on as the physics does; a target whose residual keeps structure
(E_Y, E_Z: the back face and the base, unmeasured) is explained partly by proxies that hold only
for the training field, and a new source breaks them (the trace).  0.5 sits between the two
groups the seen cells form (E_X, E_X_mid: 0.06-0.41 for every family; E_Y, E_Y_mid, and E_Z,
E_Z_mid for MLR / ARX: 0.64-0.99); lagbank's E_Z / E_Z_mid (0.10-0.28) fall with E_X.  Not tuned
further.

BAR (bench_env92b's, unchanged; nothing added before scoring)
-----------------------------------------------------------
FRESH ``column_moving_source`` seeds 9506-9515 x mlr / arx / lagbank (30 cells), drawn once after
this was committed: G = geometric mean over the cells of Σ²(rule) / Σ²(pattern) <= 0.95 and the
cells > 10 % worse no more than the cells > 10 % better.  bench_envelope_policy's non-column lines
not worse: the rule only moves a target from the gate towards ``off``, and there the gate clamps
0-4 samples per line (``pattern`` = ``off`` to 1 %; spindel's lagbank, with no gate, clamped 0.373
against 0.048 ``off``), so that side holds by its published table and is not re-run (as bench_env92
argued).  bench_env92b's gate "the check must single out E_X": on the seen cells the rule unclamps
E_X in 57 of 57 and E_X_mid in 57 of 57 (E_X_mid is better clamped in 56 of 57, but its Σ² is
small: env92's pooled 103 against 327 ``off``), E_Z / E_Z_mid in the 19 lagbank cells, E_Y /
E_Y_mid never; said here, not hidden: it singles out the X pair, not E_X alone.
On the seen cells (``rule`` on the 19 seeds above, 57 cells): G 0.583, 1 cell > 10 % worse, 47 better
(E_X alone unclamped 0.567, the oracle 0.540; bench_env92b's train-part check 0.735 on its 15).
Verdict: the bar met -> the rule goes into src (stream, and the exported code mirrors it) with
tests and docs, else REFUSED with the rule as a patch (or TRACED if no src was written).

TRACE (``trace /tmp/env93/lines 3141,5003,4253,6007,9406,9466-9475,9412-9415``: env92's drawn lines
copied, the 38 noiseless records simulated here; 2026-12-05, main 5fe17063's src; CPU 9.5 s with the
lines and truth cached, ~80 s more to simulate the truth)::

  model's response to Q3 against the truth's, over the 19 cells (median [min, max])
  family   target    slope                   corr  miss/true  clamp better  lag-1 of train residual
  mlr      E_X        0.98 [  0.93,   1.08]  1.000      0.04      0/19       0.11 [ 0.06,  0.15]
  mlr      E_Y       -1.39 [-19.55,  24.09] -0.136     17.63     17/19       0.90 [ 0.88,  0.92]
  mlr      E_Z        1.27 [  0.86,   1.61]  0.921      0.36     12/19       0.78 [ 0.69,  0.83]
  mlr      E_X_mid    3.56 [  2.66,   4.91]  0.902      2.86     19/19       0.02 [-0.05,  0.08]
  mlr      E_Y_mid    3.17 [-15.28,  13.14]  0.247     21.10     17/19       0.89 [ 0.84,  0.91]
  mlr      E_Z_mid    0.56 [ -0.10,   1.04]  0.367      1.13     17/19       0.73 [ 0.64,  0.78]
  arx      E_X        0.95 [  0.80,   1.18]  1.000      0.06      0/19       0.22 [ 0.05,  0.41]
  arx      E_Y       -1.50 [-19.05,  25.69] -0.096     14.09     13/19       0.93 [ 0.89,  0.94]
  arx      E_Z        1.35 [  0.51,   2.24]  0.881      0.56     13/19       0.85 [ 0.65,  0.99]
  arx      E_X_mid    3.79 [  1.46,   4.99]  0.910      3.26     18/19       0.06 [-0.03,  0.13]
  arx      E_Y_mid    1.07 [ -3.74,   8.14]  0.193      7.07     14/19       0.89 [ 0.82,  0.92]
  arx      E_Z_mid    1.09 [  0.57,   1.80]  0.846      0.55     19/19       0.82 [ 0.67,  0.92]
  lagbank  E_X        0.69 [ -0.86,   1.35]  0.981      0.61      1/19       0.14 [ 0.12,  0.23]
  lagbank  E_Y       -4.18 [-15.76,  26.98] -0.273     14.89     17/19       0.78 [ 0.70,  0.86]
  lagbank  E_Z        1.18 [  0.97,   1.69]  0.957      0.20     12/19       0.21 [ 0.14,  0.28]
  lagbank  E_X_mid    4.23 [  1.48,   6.53]  0.846      2.81     19/19      -0.02 [-0.09,  0.05]
  lagbank  E_Y_mid   -6.61 [-28.15,   5.43] -0.495     13.50     19/19       0.81 [ 0.74,  0.86]
  lagbank  E_Z_mid    0.90 [ -2.37,   5.32]  0.716      0.93     19/19       0.16 [ 0.10,  0.20]

Which inputs: the gate clamps only rows Q3 moves (419-528 of 1441); the clamped inputs are the right
face's T_right2-5 and T_amb in every cell (T_front3 / T_edge5 in 48 of 57); of E_X's |gain * excess|
T_right3 carries 0.68 (mlr; arx 0.83, lagbank 0.43), T_right4 0.23 (0.12, 0.35): the sensors on
either side of Q3's node right_7.  MLR's step gains on T_right1..5 (µm/K, mean over the 19 cells):
E_X -10.0 -12.8 -11.3 -3.6 0.2 against the map's -16.2 -12.6 -9.0 -5.4 -1.8 (each sensor read for
its level and the odd one below): E_X's model weighs the right face as the physics does, the same sign
everywhere, so an out-of-envelope right face is carried on linearly and right (slope 0.98; the
clamp freezes a true extrapolation: 0 of 19 cells better clamped).  E_Y: -25.4 -12.4 -5.9 8.0 4.6 on
the same sensors, with +20 on the front ones: the right face stands in for the unmeasured back
face, which Q3 does not heat as training's sources did (slopes from -20 to +24).  The split is
physical: E_X is left face against right, both measured; E_Y front against the unmeasured back;
E_Z every node and the base.  And training shows it: a model whose target is in the sensors leaves
white noise (E_X lag-1 0.06-0.41); one that leans on stand-ins leaves structure (0.64-0.99).  The
candidates read off the gains alone did not separate E_X (sign against the marginal correlation;
the gain's share off the training pattern; a blocked CV of the off-pattern directions: E_Z_mid
and E_Z gain there as E_X does), so the rule is the residual's.

SCORED ONCE (``rule /tmp/env93/fresh 9506-9515``, 2026-12-05, after the rule and bar above were
committed in b89df99c; main's src for the draws, the rule composed; CPU 150.8 s, the 30 cells'
simulation, fits and 90 replays included)::

  record  model    pattern     off    rule  ratio  unclamped
  9506    mlr         1225    6552     636  0.519  E_X,E_X_mid
  9506    arx         1524    9210     941  0.617  E_X,E_X_mid
  9506    lagbank      699     532     509  0.727  E_X,E_Z,E_X_mid,E_Z_mid
  9507    mlr         1039    3292     669  0.644  E_X,E_X_mid
  9507    arx          882    1348     524  0.594  E_X,E_X_mid
  9507    lagbank      929     932     864  0.929  E_X,E_Z,E_X_mid,E_Z_mid
  9508    mlr         1191    3528     751  0.630  E_X,E_X_mid
  9508    arx          847     872     787  0.930  E_X,E_X_mid
  9508    lagbank     1539    1545    1405  0.913  E_X,E_Z,E_X_mid,E_Z_mid
  9509    mlr          985     279     308  0.312  E_X,E_X_mid
  9509    arx         1618    6484     930  0.574  E_X,E_X_mid
  9509    lagbank     1539    1727    1426  0.926  E_X,E_Z,E_X_mid,E_Z_mid
  9510    mlr          735     865     200  0.272  E_X,E_X_mid
  9510    arx          959    3458     429  0.448  E_X,E_X_mid
  9510    lagbank      916     926     850  0.928  E_X,E_Z,E_X_mid,E_Z_mid
  9511    mlr          905    1666     436  0.481  E_X,E_X_mid
  9511    arx          810     315     337  0.416  E_X,E_X_mid
  9511    lagbank     1194    1152    1145  0.959  E_X,E_Z,E_X_mid,E_Z_mid
  9512    mlr         1202    1716     617  0.513  E_X,E_X_mid
  9512    arx         1241    5897     991  0.799  E_X,E_X_mid
  9512    lagbank     1135    1357     980  0.863  E_X,E_Z,E_X_mid,E_Z_mid
  9513    mlr          716    1559     308  0.430  E_X,E_X_mid
  9513    arx         1043    6109     612  0.587  E_X,E_X_mid
  9513    lagbank      774     829     805  1.040  E_X,E_Z,E_X_mid,E_Z_mid
  9514    mlr         1164     737     819  0.704  E_X,E_X_mid
  9514    arx         1249     902     925  0.741  E_X,E_X_mid
  9514    lagbank     1099     971     981  0.892  E_X,E_Z,E_X_mid,E_Z_mid
  9515    mlr          980    2533     613  0.625  E_X,E_X_mid
  9515    arx          855     566     475  0.555  E_X,E_X_mid
  9515    lagbank      861     897     870  1.010  E_X,E_Z,E_X_mid,E_Z_mid
  pooled Σ² µm²: pattern 31 855, off 68 756, rule 22 143 (mlr 10 142 / 22 727 / 5 357, arx 11 028 /
  35 161 / 6 951, lagbank 10 685 / 10 868 / 9 835); G per family mlr 0.492, arx 0.609, lagbank 0.915

  rule: G 0.650, 0 cells > 10 % worse, 22 > 10 % better (worst 9513 lagbank 1.040); E_X alone
  unclamped 0.633, the oracle 0.604.  BAR MET (G <= 0.95, worse 0 <= better 22).

Against the shipped code: the rule built into src (``promote.envelope.per_target``, default true),
``replay`` with the defaults on the cached fits gives the composed Σ² to its rounding: fresh 9506
mlr 635.7 (composed 636), 9506 lagbank 508.6 (509), 9513 lagbank 804.8 (805), 9509 arx 929.5 (930);
seen 3141 mlr / lagbank 315.6 / 849.8, 9470 mlr / lagbank 427.0 / 1136.2 (composed the same).
Verdict: KEPT AS AN OPT-IN KEY (``promote.envelope.per_target=true``; default ``false``, the shipped
clamp unchanged).  The bar was met, but with the rule on by default the spike suite's ARX cases
failed (tests/shell/test_export_spike54.py, the export tests' record: after a +50 °C one-row spike
the white target's corrections differ from the ones the clamp gives by up to 2.89 µm, 17 of the 38
values (rows x targets) after it, in the plain stream and in the code): an unclamped target takes
a sensor's fault as it takes a new source, and the bar did not price faults.  Found after the
fresh score, so the default is left as it was rather than the rule changed after seeing numbers.
Left: a rule that unclamps a white target only for an excursion a heat source can make (e.g. an
excess within a few training widths: Q3's reaches 0.86-1.25 of a width on the 19 seen MLR cells,
or a rate a sensor's node can follow), so a spike stays clamped;
or the monitor's exclusion first (``monitor.adaptive``) measured with the key on.  src,
tests/apps/test_envelope_per_target93.py (3, failing on 5fe17063: the key is new; the behaviour
under it is asserted), docs.
"""

from __future__ import annotations

import json
import pickle
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_env92 as env92  # noqa: E402
import bench_envelope_policy as envelope_policy  # noqa: E402
from _cli import run_commands, seed_list  # noqa: E402

from thermocomp.apps.deploy.adaptive import input_gains  # noqa: E402
from thermocomp.apps.deploy.streaming import StreamingCompensator  # noqa: E402

WHITE = 0.5            # the rule's bound on the residual's lag-1 autocorrelation (docstring)
TRAIN, TEST = "train_cycle", "test_cycle"


def _cell(root: Path, record: str, family: str):
    """``(compensator, deployed stream, train campaigns)`` of a drawn cell."""
    model = pickle.loads((root / "fit" / f"{record}-{family}" / "model.pkl").read_bytes())
    train = {TRAIN: pd.read_csv(root / "data" / record / f"{TRAIN}.csv")}
    return model, StreamingCompensator.from_training(model, train), train


def residual_lag1(model, campaigns) -> dict[str, float]:
    """Per target the lag-1 autocorrelation of the training residual (measured less the model's
    simulation), over pairs of consecutive samples within a campaign: the rule as it was scored,
    on main's src (shipped since as ``streaming.white_targets``; the same on these records: the
    replays of the built rule give the composed Σ², below)."""
    m = model.stacked(campaigns)
    e = m.Y[model.targets_].to_numpy() - model.predict_stacked(m)
    same = m.groups[1:] == m.groups[:-1]
    out = {}
    for k, t in enumerate(model.targets_):
        a, b = e[:-1, k][same], e[1:, k][same]
        out[t] = float(np.corrcoef(a, b)[0, 1])
    return out


def _truth(root: Path, seed: int) -> dict[bool, Path]:
    """The record without noise, with (True) and without (False) Q3."""
    out = {}
    for q3 in (True, False):
        path = root / "truth" / f"cms{seed}-q3{str(q3).lower()}"
        if not path.exists():
            envelope_policy.cli("simulate", "sim=column_moving_source", f"seed={seed}",
                                f"sim.generator.q3={str(q3).lower()}", "sim.generator.clean=true",
                                f"data.path={path}", "track=false")
        out[q3] = path
    return out


def trace(root: str, seeds: str) -> None:
    env92.draw(root, seeds)
    base = Path(root)
    rows = {(r["record"], r["family"]): r for r in env92._rows(base / "results.jsonl")}
    cells, shares, right_gain, lag1 = {}, {}, {}, {}
    for seed in seed_list(seeds):
        record, paths = f"cms{seed}", _truth(base, seed)
        on, off = (pd.read_csv(paths[q] / f"{TEST}.csv") for q in (True, False))
        for fam in envelope_policy.FAMILIES:
            model, stream, train = _cell(base, record, fam)
            env, cols, targets = stream.envelope, list(stream.envelope.columns), model.targets_
            m_on, m_off = model.stacked({TEST: on}, []), model.stacked({TEST: off}, [])
            x_on, x_off = m_on.X[cols].to_numpy(), m_off.X[cols].to_numpy()
            q3 = np.abs(x_on - x_off).max(axis=1) > 0.01          # rows Q3 moves an input
            response = model.predict_stacked(m_on) - model.predict_stacked(m_off)
            true = _rise(on[targets]) - _rise(off[targets])        # Q3's part of each error
            excess = np.array([env.excess(x) for x in x_on])
            gains = input_gains(stream)
            lag1[record, fam] = residual_lag1(model, train)
            for k, t in enumerate(targets):
                d, y = true[q3, k], response[q3, k]
                line = rows[record, fam]["targets"][t]
                cells.setdefault((fam, t), []).append(
                    {"slope": np.polyfit(d, y, 1)[0], "corr": np.corrcoef(d, y)[0, 1],
                     "miss": np.sqrt(np.mean((y - d) ** 2)) / np.sqrt(np.mean(d ** 2)),
                     "clamp_wins": line["pattern"] < line["off"]})
                part = np.abs(excess * gains[k]).sum(axis=0)
                shares.setdefault((fam, t), []).append(part / part.sum() if part.sum() else part)
                if fam == "mlr":
                    right = [gains[k][cols.index(f"T_right{j}")] for j in range(1, 6)]
                    right_gain.setdefault(t, []).append(right)
            print(f"{record} {fam}: {int(q3.sum())} rows moved by Q3,"
                  f" {int(excess.any(axis=1).sum())} clamped", file=sys.stderr, flush=True)
    print("model's response to Q3 against the truth's, over the cells (median [min, max])")
    print(f"{'family':8} {'target':8} {'slope':>22} {'corr':>6} {'miss/true':>9} {'clamp better':>13}"
          f" {'lag-1 of train residual':>26}")
    for (fam, t), v in cells.items():
        sl, r1 = [c["slope"] for c in v], [lag1[k][t] for k in lag1 if k[1] == fam]
        print(f"{fam:8} {t:8} {np.median(sl):6.2f} [{min(sl):6.2f}, {max(sl):6.2f}]"
              f" {np.median([c['corr'] for c in v]):6.3f} {np.median([c['miss'] for c in v]):9.2f}"
              f" {sum(c['clamp_wins'] for c in v):6}/{len(v):<6}"
              f" {np.median(r1):6.2f} [{min(r1):5.2f}, {max(r1):5.2f}]")
    print("share of |gain * excess| over the clamped rows, by input (mean over the cells; >= 5 %)")
    for (fam, t), v in shares.items():
        mean = np.mean(v, axis=0)
        big = sorted(((s, c) for s, c in zip(mean, cols) if s >= 0.05), reverse=True)
        print(f"  {fam:8} {t:8} " + ", ".join(f"{c} {s:.2f}" for s, c in big))
    print("MLR's step gains on T_right1..5 (µm/K; mean over the cells) and the map's own for E_X")
    for t, g in right_gain.items():
        print(f"  {t:8} " + " ".join(f"{x:7.2f}" for x in np.mean(g, axis=0)))
    print("  E_X map " + " ".join(f"{x:7.2f}" for x in _map_right_gain()))


def _rise(errors: pd.DataFrame) -> np.ndarray:
    """The errors as the models see them: the change since the campaign's first sample."""
    return (errors - errors.iloc[0]).to_numpy()


def _map_right_gain() -> list[float]:
    """E_X's µm/K per right-face sensor by the thermoelastic map: the sensor on level 2k read for its
    level and the odd level below it (the unmeasured node it stands for, as the models must)."""
    from thermocomp.apps.sim.column import ALPHA, HEIGHT_M, LEVEL_M, WIDTH_M

    def node(level):
        return -ALPHA * LEVEL_M * (HEIGHT_M - (level - 0.5) * LEVEL_M) / WIDTH_M
    return [node(2 * k) + node(2 * k - 1) for k in range(1, 6)]


def _composed(per_target: dict, unclamp) -> float:
    """A cell's test Σ² with the targets ``unclamp(target, its replays)`` streamed ``off``, the
    others by the shipped gate (``pattern``)."""
    return sum(v["off" if unclamp(t, v) else "pattern"] ** 2 for t, v in per_target.items())


def rule(root: str, seeds: str) -> None:
    env92.draw(root, seeds)
    base = Path(root)
    rows = {(r["record"], r["family"]): r for r in env92._rows(base / "results.jsonl")}
    ratios, e_x, oracle = [], [], []
    unclamped: dict[str, int] = {}
    for seed in seed_list(seeds):
        record = f"cms{seed}"
        for fam in envelope_policy.FAMILIES:
            model, _, train = _cell(base, record, fam)
            lag1, line = residual_lag1(model, train), rows[record, fam]
            free = [t for t in model.targets_ if lag1[t] < WHITE]
            for t in free:
                unclamped[t] = unclamped.get(t, 0) + 1
            per = line["targets"]
            chosen = _composed(per, lambda t, v: t in free)
            ratios.append(chosen / line["pattern"])
            e_x.append(_composed(per, lambda t, v: t == "E_X") / line["pattern"])
            oracle.append(_composed(per, lambda t, v: v["off"] < v["pattern"]) / line["pattern"])
            print(f"{record} {fam:8} pattern {line['pattern']:7.0f} off {line['off']:7.0f} rule {chosen:7.0f}"
                  f"  ratio {ratios[-1]:.3f}  unclamped {','.join(free) or '-'}", flush=True)
    r = np.array(ratios)
    out = {"cells": len(r), "G": float(np.exp(np.log(r).mean())), "worse": int((r > env92.WORSE).sum()),
           "better": int((r < 1 / env92.WORSE).sum()), "unclamped": unclamped,
           "G_E_X_alone": float(np.exp(np.log(e_x).mean())), "G_oracle": float(np.exp(np.log(oracle).mean()))}
    out["bar"] = "met" if out["G"] <= env92.CONFIRM and out["worse"] <= out["better"] else "failed"
    print("rule:", json.dumps(out))


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"trace": trace, "rule": rule},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
