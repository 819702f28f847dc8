"""Can the adaptive compensator tell a real step of the air from an offset of its sensor by what
the structure does after the jump?  Measured, no rule merged (session 55; prints numbers, no
assertions).

Records: ``yearround_spindle`` seeds 5353 (the record of ``tests/shell/test_ambient_step54.py``)
and 4242, 9 campaigns of 3-5 h, 5-min samples, test campaigns K03, K06, K09; MLR fitted by
``thermocomp run`` and deployed as ``replay`` deploys it (adaptive: sensor monitor + guard;
plain: ``monitor.adaptive=false``).  In each test campaign from its middle row: the air itself
stepped (``SteppedAmbient``, the simulation rerun, every other campaign identical; the ``T_amb``
sensor, 120 s lag, shows +5 K as 0.5 + 3.9 + 0.5 K over three rows and the monitor excludes it at
the 3.9 K row) or ``T_amb``'s column alone offset.

1. What following the air is worth.  RMS over E_X, E_Y, E_Z of measured minus predicted error from
   the middle row on (µm): adaptive today (the jump re-referenced for good) / adaptive taking the
   reading as measured at re-admission (an oracle that knows the step is real: what any rule
   deciding at re-admission can reach) / plain::

     seed 5353  K03                  K06                  K09
     real +5    13.22 / 13.22 / 14.67  10.77 /  7.08 /  6.46  12.70 / 13.22 / 14.57
     real +2     6.48 /  7.63 /  9.40   6.30 /  3.94 /  3.08   6.75 /  7.85 /  9.20
     real -5    10.98 /  9.36 / 10.02  10.14 / 11.16 / 13.08   9.76 /  9.76 / 11.74
     offset +5   3.68 /  9.73 / 13.08   4.70 /  5.75 /  8.01   3.49 /  8.72 / 11.78
     seed 4242
     real +5    14.65 / 14.56 / 12.26  12.57 / 11.50 /  8.20  17.69 / 17.49 / 13.80
     real +2    11.00 / 10.60 / 10.33   6.90 /  5.78 /  5.54  12.75 / 12.19 / 11.44
     real -5    10.36 /  7.89 /  8.84  11.45 /  6.37 /  5.55  10.67 /  8.00 /  8.46
     offset +5   9.46 /  9.98 / 16.13   4.91 /  6.77 / 14.81  10.20 / 10.45 / 15.80

   The strict xfail (adaptive < 1.1 x plain on seed 5353 K06 real +5) is met by the oracle by
   0.4 % (7.08 < 7.11); on 5353 K03 and K09 the MLR reading the true stepped air is worse than
   the re-referenced reading (12.70 -> 13.22, 6.75 -> 7.85); on 4242 it is better everywhere but
   not within 1.1 x plain at +5 K (K06 11.50 vs 8.20).  An offset taken as real costs 0.3-6 µm
   (3.68 -> 9.73 on 5353 K03).

2. The evidence: after the jump ``J`` each structure sensor is simulated over the monitor's
   window (10 samples, its hold before re-admission) by a first-order response fitted on the train
   campaigns (its change per sample on its two last changes, its gap to the air and an intercept;
   ``T + structure``: also the structure's mean gap to the air, each sensor exchanging heat with
   the air and with the rest of the machine; ``+ speed``: the standardised spindle speed and its
   square instead), once with the air re-referenced (an offset, alpha = 0) and once as measured
   (real, alpha = 1); alpha-hat is the share of the jump the sensors followed (least squares,
   each sensor weighted by its one-step residual).  Real when alpha-hat > 1/2 (the likelier
   hypothesis).  Printed: alpha-hat at the middle row of each test campaign, and the share of
   rows of the test and of the train campaigns at which an offset (injected at that row) would
   be taken as real -- the cost of the rule for the fault the monitor must keep holding off --
   for +5 / +2 / -5 / -2 K; the healthy band is the 99.5th percentile of |alpha-hat| per kelvin
   of a jump that is not there, on the train rows.

   T only (what the deployed MLR reads): coupling 0.000-0.011 per sample (the spindle's heat,
   unobserved, confounds the gap to the air), band 13.19 K (5353) / 7.65 K (4242).  Every real
   step gives alpha-hat above 1/2 (0.87-3.79, the xfail would pass), but so does an offset at
   0.0 / 10.0 / 0.9 / 30.9 % of the test rows and 21.3 / 35.6 / 11.1 / 33.8 % of the train rows
   (5353), 27.8 / 36.1 / 0.9 / 30.6 % and 3.1 / 33.8 / 11.1 / 29.3 % (4242).  Refused.

   T + structure (the temperature-only form with the smaller band: 4.76 / 0.66 K; it was tried
   after the two others had been scored on the test rows): no offset taken at any test row of
   either seed, nor at any train row of 4242, but at 0.0 / 8.8 / 5.1 / 9.7 % of 5353's train
   rows.  Real steps: 6 of 9 above 1/2 on 5353 (K06 +5 K 0.65: the xfail would pass at 7.08;
   K03 +5, +2 and K09 -5 at 0.46, 0.22, 0.48 not), none on 4242 (0.08-0.40: there the fit
   over-predicts how the structure follows the air).  The steps it takes on 5353 change the RMS
   by -3.69, -2.36, -1.62, +1.02, +0.52, +1.10 µm (K06 +5, +2, K03 -5, K06 -5, K09 +5, +2).
   Refused: a T_amb offset taken for air at up to 10 % of the rows of one record (where today
   none is), nothing detected on the other, and RMS changes of both signs where it detects.

   + speed: coupling 0.019-0.064 per sample, band 1.70 / 0.90 K; real +-5 K steps 0.16-0.98
   (9 of 12 above 1/2; 5353 K09 -5 K at 0.496, 4242 K03 and K09 -5 K at 0.16, 0.31), +2 K
   0.24-0.98 (3 of 6); offsets taken at 0 % of the test rows of 5353 and 0.0 / 16.7 / 0.0 / 0.0 %
   of 4242's, 0.0 / 8.3 / 0.0 / 13.0 % of 5353's train rows and none of 4242's.  +-5 K offsets
   are never taken; K06 +5 K (0.56) would be, and the xfail pass (7.08).  But the deployed MLR
   reads the ten temperatures only, not ``S_spindle_rpm``, so its monitor never sees the speed;
   reading a column the model does not use changes the deployed contract (every stream feeds
   ``columns_``: replay's input, the pyfunc signature, the server), not done here.  Where a model
   reads a machine-state input the evidence is at hand for +-5 K steps; +-2 K offsets are still
   taken at up to 17 % of the rows, and the 1.1 x plain criterion still fails on 4242 (part 1).

Run: ``PYTHONPATH=src .venv/bin/python benchmarks/bench_ambient_step55.py [--root /tmp/as55]``
(simulations and fits made once under ``--root``: 10 s of CPU with them made).  Measured
2026-11-30 (session 55): the numbers above; the run prints them.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import pandas as pd
from hydra import compose, initialize_config_dir

from thermocomp.apps.deploy import surveillance
from thermocomp.apps.deploy.report import stream_rows
from thermocomp.apps.sim.ambient import step_air
from thermocomp.apps.sim.scenario import write_scenario
from thermocomp.apps.sim.yearround import YearRoundSpindle
from thermocomp.base.paths import conf_dir
from thermocomp.shell.builders import deployable_model
from thermocomp.shell.cli import main
from thermocomp.shell.source import read_streamed

SEEDS, TARGETS, AIR, SPEED = (5353, 4242), ["E_X", "E_Y", "E_Z"], "T_amb", "S_spindle_rpm"
STEPS, OFFSETS, WINDOW, LAGS = (5.0, 2.0, -5.0), (5.0, 2.0, -5.0, -2.0), 10, 2


class _AirStepped(YearRoundSpindle):
    """The record with the air of campaign ``cid`` stepped by ``step_c`` from its middle row
    (over ``ramp_s`` seconds: bench_amb94)."""

    def __init__(self, *args, cid="K06", step_c=5.0, ramp_s=0.0, **kwargs):
        super().__init__(*args, **kwargs)
        self.cid, self.step_c, self.ramp_s = cid, step_c, ramp_s

    def plans(self, rng):
        return step_air(super().plans(rng), self.cid, self.step_c, self.ramp_s)


def _scenario(seed: int, **kwargs):
    kw = dict(n_campaigns=9, duration_h=(3.0, 5.0), seed=seed)
    return _AirStepped(**kw, **kwargs) if kwargs else YearRoundSpindle(**kw)


def _forms(root: Path, family: str = "mlr") -> dict:
    """The adaptive and the plain deployed ``family`` (``root/family/model.pkl``) of the record
    under ``root``."""
    forms = {}
    for adaptive in ("true", "false"):
        with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
            cfg = compose(config_name="config", overrides=[
                f"data.path={root / 'ys'}", "track=false", f"monitor.adaptive={adaptive}"])
        ds, train_ids, _, _ = read_streamed(cfg)
        forms[adaptive] = deployable_model(cfg, ds, train_ids, str(root / family / "model.pkl"),
                                           "replay.model")[0]
    return forms


def made(root: Path, seed: int) -> Path:
    """The healthy record of ``seed`` under ``root`` (``ys``) and its MLR (``mlr``), made once."""
    data = root / "ys"
    if not data.exists():
        write_scenario(_scenario(seed), data)
    if not (root / "mlr/model.pkl").exists():
        main(["run", f"data.path={data}", "model=mlr", "track=false", "plots=none",
              "eval.validation=false", f"out={root / 'mlr'}"])
    return data


def stepped_campaign(path: Path, seed: int, cid: str, step_c: float) -> pd.DataFrame:
    """Campaign ``cid`` of ``seed``'s record with its air stepped by ``step_c`` from its middle
    row (the simulation rerun, written under ``path`` once)."""
    if not path.exists():
        write_scenario(_scenario(seed, cid=cid, step_c=step_c), path)
    return pd.read_csv(path / f"{cid}.csv")


def record(root: Path, seed: int) -> tuple[dict, list[pd.DataFrame], dict]:
    """``(forms, train frames, {(cid, case): (readings, measured errors)})``."""
    data = made(root, seed)
    listed = pd.read_csv(data / "campaigns.csv")
    train = [pd.read_csv(data / f"{c}.csv") for c in listed.loc[listed["split"] == "train", "campaign"]]
    cases = {}
    for cid in listed.loc[listed["split"] == "test", "campaign"]:
        raw = pd.read_csv(data / f"{cid}.csv")
        for step in STEPS:
            df = stepped_campaign(root / f"air_{cid}_{step:+g}", seed, cid, step)
            cases[cid, f"real {step:+g}"] = (df, df)
        for dT in OFFSETS:
            f = raw.copy()
            f.loc[len(raw) // 2:, AIR] += dT
            cases[cid, f"offset {dT:+g}"] = (f, raw)
    return _forms(root), train, cases


class AirResponse:
    """Each structure sensor's change per sample on its ``LAGS`` last changes, its gap to the air,
    (``structure``) the structure's mean gap to the air, (``speed``) the standardised spindle
    speed and its square, and an intercept, fitted on ``frames``; :meth:`alpha`, the share of a
    jump of the air the sensors followed."""

    def __init__(self, frames: list[pd.DataFrame], speed: bool = False, structure: bool = False):
        self.sensors = [c for c in frames[0].columns if c.startswith("T_") and c != AIR]
        self.speed, self.structure = speed, structure
        s = np.concatenate([f[SPEED].to_numpy(float) for f in frames])
        self.mean, self.scale = s.mean(), s.std()
        A, Y = [], []
        for f in frames:
            T, air, Q = self._arrays(f)
            dT = np.diff(T, axis=0)
            for k in range(LAGS, len(T) - 1):
                A.append(self._row([dT[k - 1 - lag] for lag in range(LAGS)], air[k] - T[k], Q[k]))
                Y.append(dT[k])
        A, Y = np.array(A), np.array(Y)          # (rows, sensors, terms), (rows, sensors)
        self.coef = np.array([np.linalg.lstsq(A[:, i], Y[:, i], rcond=None)[0]
                              for i in range(len(self.sensors))])
        # the sensors' change per kelvin of air per sample (the structure's mean gap moves with it)
        self.coupling = self.coef[:, LAGS] + (self.coef[:, LAGS + 1] if structure else 0.0)
        res = Y - np.einsum("rst,st->rs", A, self.coef)
        self.weight = 1.0 / res.std(axis=0) ** 2

    def _arrays(self, f: pd.DataFrame):
        z = (f[SPEED].to_numpy(float) - self.mean) / self.scale
        Q = np.c_[z, z ** 2] if self.speed else np.empty((len(f), 0))
        return f[self.sensors].to_numpy(float), f[AIR].to_numpy(float), Q

    def _row(self, changes, gap, q):
        n = len(gap)
        mean = [np.full(n, gap.mean())] if self.structure else []
        return np.column_stack([*changes, gap, *mean, np.tile(q, (n, 1)), np.ones(n)])

    def _run(self, T, Q, air, k, w):
        """The sensors ``w`` rows on from their readings at row ``k`` under ``air``."""
        cur, changes, out = T[k].copy(), [T[k - lag] - T[k - 1 - lag] for lag in range(LAGS)], []
        for j in range(k, k + w):
            d = np.einsum("st,st->s", self._row(changes, air[j] - cur, Q[j]), self.coef)
            cur, changes = cur + d, [d, *changes[:-1]]
            out.append(cur)
        return np.array(out)

    def alpha(self, f: pd.DataFrame, air: np.ndarray, k: int, jump: float, w: int = WINDOW) -> float:
        """Share of the ``jump`` of ``air`` at row ``k`` the sensors followed over ``w`` rows."""
        T, _, Q = self._arrays(f)
        w = min(w, len(T) - 1 - k)
        back = air.copy()
        back[k:] -= jump
        s0, s1 = self._run(T, Q, back, k, w), self._run(T, Q, air, k, w)
        g, r = (s1 - s0) * self.weight, T[k + 1:k + 1 + w] - s0
        return float(np.sum(g * r) / np.sum(g * (s1 - s0)))


def healthy_band(m: AirResponse, frames: list[pd.DataFrame]) -> float:
    """99.5th percentile of |alpha-hat| per kelvin of a jump that is not there: +1 K on the air's
    reading at every row of the train campaigns (in sample)."""
    out = []
    for f in frames:
        air = f[AIR].to_numpy(float)
        for k in range(LAGS, len(f) - WINDOW - 1):
            shifted = air.copy()
            shifted[k:] += 1.0
            out.append(abs(m.alpha(f, shifted, k, 1.0)))
    return float(np.quantile(out, 0.995))


def _jump_row(air: np.ndarray) -> int:
    """The row the monitor excludes the air at: the largest step within two rows of the middle."""
    h = len(air) // 2
    return h + int(np.argmax(np.abs(np.diff(air)[h - 1:h + 2])))


def _rms(deployed, readings, errors, cid) -> float:
    s = stream_rows(deployed, readings, cid)
    h = len(readings) // 2
    r = errors[TARGETS].to_numpy(float)[h:] - s.y[h:]
    return float(np.sqrt((r ** 2).sum(axis=1).mean()))


def _accepting(deployed, readings, errors, cid) -> float:
    """RMS with the jump taken as real at re-admission (the monitor's own undo of a sensor no
    other predicts, forced: as if it had jumped twice)."""
    readmit = surveillance.SensorMonitor._readmit

    def forced(self, d, finite, instant, time, events):
        self._jumps[(self._jumps == 1) & ~self._predictable & ~self._active] = 2
        return readmit(self, d, finite, instant, time, events)
    surveillance.SensorMonitor._readmit = forced
    try:
        return _rms(deployed, readings, errors, cid)
    finally:
        surveillance.SensorMonitor._readmit = readmit


def main_(root: Path) -> None:
    for seed in SEEDS:
        forms, train, cases = record(root / f"s{seed}", seed)
        models = {"T only": AirResponse(train), "T + structure": AirResponse(train, structure=True),
                  "+ speed": AirResponse(train, speed=True)}
        for name, m in models.items():
            band = healthy_band(m, train)
            print(f"seed {seed} {name}: air coupling per sample {np.round(m.coupling, 3).tolist()}; "
                  f"healthy band (99.5th percentile of |alpha-hat| per K, train) {band:.2f} K")
        print(f"seed {seed}: RMS from the middle row (µm) adaptive / accepted at re-admission / plain;"
              f" alpha-hat {', '.join(models)}")
        for (cid, case), (df, errors) in cases.items():
            air = df[AIR].to_numpy(float)
            k = _jump_row(air)
            jump = air[k] - air[k - 1]
            a = [f"{m.alpha(df, air, k, jump):+.2f}" for m in models.values()]
            print(f"  {cid} {case:10s} {_rms(forms['true'], df, errors, cid):6.2f} / "
                  f"{_accepting(forms['true'], df, errors, cid):6.2f} / "
                  f"{_rms(forms['false'], df, errors, cid):6.2f}   alpha {' '.join(a)}")
        tests = sorted({cid for cid, _ in cases})
        recorded = {"test": [cases[cid, f"offset {OFFSETS[0]:+g}"][1] for cid in tests], "train": train}
        for name, m in models.items():
            for split, frames in recorded.items():
                cells = [f"{dT:+g} K {taken_for_real(m, frames, dT):5.1%}" for dT in OFFSETS]
                print(f"seed {seed} {name}: offset taken as real at every row of the {split} "
                      "campaigns: " + ", ".join(cells))


def taken_for_real(m: AirResponse, frames: list[pd.DataFrame], offset: float) -> float:
    """Share of the rows of ``frames`` (as recorded) at which an ``offset`` of the air's reading
    from that row on would be taken for a real change (alpha-hat > 1/2)."""
    taken = []
    for f in frames:
        air = f[AIR].to_numpy(float)
        for k in range(LAGS, len(f) - WINDOW - 1):
            shifted = air.copy()
            shifted[k:] += offset
            taken.append(m.alpha(f, shifted, k, offset) > 0.5)
    return float(np.mean(taken))

if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--root", default="/tmp/as55")
    main_(Path(parser.parse_args().root))
