"""Bands that widen with the sample's distance from training (shorttrain58): measured, refused.

    PYTHONPATH=src .venv/bin/python benchmarks/bench_monitor_shorttrain58.py ROOT

A monitor trained on less than the conditions it is judged in raises false alarms
(docs/monitoring.md, "Healthy records nobody tuned it on").  The direction measured here: the
band of a sensor's self-prediction error widens with how far the CURRENT sample lies from the
training samples in the space its prediction uses, as the prediction variance of least squares
at a new point does, :math:`\\sigma^2 (1 + x_0^\\top (X^\\top X)^{-1} x_0)`.  The predictors of sensor
``j`` are the other sensors, so a drifting sensor widens every band but its own.

The rules, written down before scoring (``w_j(t)`` multiplies both bands of sensor ``j`` at
sample ``t``; every distance is of the sample referenced to its campaign's first, as the POD's
snapshots are, with every sensor in the fit; "training max" = its largest value over the
training samples, so that every training sample keeps today's band):

* ``lsq``   -- the least-squares factor itself, :math:`\\sqrt{1 + a_{-j}^\\top (A_{-j}^\\top A_{-j})^{-1}
  a_{-j}}`, ``a_{-j}`` the sample's r mode coefficients fitted to every sensor but j, ``A_{-j}``
  the training samples' ones;
* ``modes`` -- ``max(1, D_j / training max of D_j)``, ``D_j`` the Mahalanobis distance of
  ``a_{-j}`` (training's uncentred second moment);
* ``resid`` -- ``max(1, sqrt(Q_j / training max of Q_j))``, ``Q_j`` the squared residual of the
  other sensors from their own r-mode fit (how far the predictors lie off training's subspace);
* ``full``  -- ``max(1, D_j / training max of D_j)`` with ``D_j`` the Mahalanobis distance of the
  other sensors' readings themselves (training's uncentred second moment, n - 1 dimensions).

Scored on the monitor's judged statistic (each sensor's smallest |leave-one-out error| of the
last ``confirm`` = 2 samples against its warning band, every sensor in the fit, the bands and
basis of ``monitor``'s defaults): on healthy test parts, the sensor-samples beyond the band
(plain: the monitor's warnings come from these); with 1 K/h planted on a sensor, the minutes
from the onset to its first sample beyond its band, and for a sensor no other predicts (its
drift leaks onto the judged ones) to the first judged sensor beyond its band.

Measured (2026-11-30, stop 58; 10 s of CPU once the records are written)::

    per rule plain/lsq/modes/resid/full -- healthy: sensor-samples beyond the
      (widened) warning band, the peak |E| / band; where the plain peak is: each distance
      over training's largest (lsq: its factor); drift: minutes from the onset to the
      first flag (per test campaign a/b/.., - none), lsq/modes/resid/full's factors then
    column no Q3 s5305 30 h r=11 n=20 20.0 h beyond 1/0/1/1/1  peak |E|/band 1.13/1.13/1.13/1.13/1.13
        plain peak 1.13, T_left1 at 17.81 h: lsq 1.01 modes 0.63 resid 0.94 full 0.98
        1 K/h on T_left1 (itself), min: 37  37  37  37  37
          factors at the plain flag: T_left1 1.009/1.000/1.000/1.000
        1 K/h on T_right3 (itself), min: 30  30  30  30  30
          factors at the plain flag: T_right3 1.009/1.000/1.000/1.000
    large_mill s5303 48 h   r= 6 n=52 24.0 h beyond 4/4/4/0/0  peak |E|/band 1.17/1.17/1.17/0.90/0.89
        plain peak 1.17, T_col_05 at 9.78 h: lsq 1.00 modes 0.94 resid 1.71 full 1.50
        1 K/h on T_col_11 (itself), min: 25  25  32  30  38
          factors at the plain flag: T_col_11 1.002/1.142/1.176/1.375
        1 K/h on T_col_05 (itself), min: 12  12  12  14  16
          factors at the plain flag: T_col_05 1.002/1.130/1.257/1.417
    large_mill s5303 24 h   r= 5 n=52 12.0 h beyond 8200/8185/8200/0/0  peak |E|/band 1.98/1.98/1.98/0.90/1.13
        plain peak 1.98, T_table_04 at 9.52 h: lsq 1.00 modes 0.28 resid 3.18 full 2.22
        1 K/h on T_col_11 (itself), min: 12  12  12  61  30
          factors at the plain flag: T_col_11 1.001/1.000/2.903/1.813
    swiss_lathe s5304 40 h  r= 7 n=12 24.0 h beyond 0/0/0/0/0  peak |E|/band 0.68/0.68/0.68/0.68/0.68
        plain peak 0.68, T_headstock at 14.68 h: lsq 1.00 modes 0.33 resid 0.35 full 0.52
        1 K/h on T_guidebush (itself), min: 51  51  51  51  51
          factors at the plain flag: T_guidebush 1.001/1.000/1.000/1.000
    long_record 3 d         r=11 n=14  7.2 h beyond 0/0/0/0/0  peak |E|/band 0.78/0.77/0.78/0.78/0.78
        plain peak 0.78, T_xdrive at 70.83 h: lsq 1.01 modes 0.14 resid 0.15 full 0.15
        1 K/h on T_table (first judged sensor), min: 150  -  150  150  150
          factors at the plain flag: T_xdrive 1.190/1.000/1.000/1.000
        1 K/h on T_xdrive (itself), min: 35  35  35  35  35
          factors at the plain flag: T_xdrive 1.004/1.000/1.000/1.000

The false alarms lie inside training's mode-coefficient cloud (``modes`` 0.63, 0.94, 0.28 of
training's largest where each healthy error peaks), so ``modes`` changes nothing and ``lsq``
(1.00-1.01 there, N = 1081-5761 training samples) quiets the column's one sample by a hair and
hides the leaked ``T_table`` drift (``T_xdrive``'s band x 1.19 at the plain flag).  ``resid`` and
``full`` quiet both mills (their samples lie off training's subspace: 1.71 and 3.18 of its
largest) and not the column (0.94, 0.98), at later drift flags.  docs/monitoring.md has ``resid``
in the monitor (not merged).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from thermocomp.apps.deploy.pod import ThermalPOD
from thermocomp.apps.deploy.surveillance import SensorMonitor

ROOT = Path(__file__).resolve().parents[1]
QUIET = ("track=false", "plots=none")
# name -> simulate overrides
SIM = {
    "column no Q3 s5305 30 h": ["sim=column_moving_source", "seed=5305", "sim.generator.q3=false",
                                "sim.generator.train_hours=30", "sim.generator.test_hours=20"],
    "large_mill s5303 48 h": ["sim=large_mill_week", "seed=5303", "sim.generator.train_hours=48",
                              "sim.generator.test_hours=24"],
    "large_mill s5303 24 h": ["sim=large_mill_week", "seed=5303", "sim.generator.train_hours=24",
                              "sim.generator.test_hours=12"],
    "swiss_lathe s5304 40 h": ["sim=swiss_lathe_door", "seed=5304",
                               "sim.generator.calibration_hours=40"],
    "long_record 3 d": ["sim=long_record", "sim.generator.duration_days=3",
                        "sim.generator.sample_period_s=300"],
}
# record -> sensors drifting 1 K/h from half of each test campaign (scored one at a time)
DRIFTS = {
    "column no Q3 s5305 30 h": ["T_left1", "T_right3"],
    "large_mill s5303 48 h": ["T_col_11", "T_col_05"],
    "large_mill s5303 24 h": ["T_col_11"],
    "swiss_lathe s5304 40 h": ["T_guidebush"],
    "long_record 3 d": ["T_table", "T_xdrive"],
}
RULES = ("plain", "lsq", "modes", "resid", "full")
WARNING_C, ALARM_C, WINDOW, CONFIRM = 0.4, 0.8, 10, 2


def build(root: Path) -> dict:
    """``{record: (train campaigns, test campaigns)}`` as DataFrames (simulated once in ``root``).
    ``long_record`` is cut as tests/apps/test_deployed_as_scored44.py's record: one file, its
    last 10 % the test part."""
    out = {}
    for name, sim in SIM.items():
        path = root / name.replace(" ", "_")
        if not (path / "campaigns.csv").exists():
            subprocess.run([sys.executable, "-m", "thermocomp", "-q", "simulate", *sim,
                            f"data.path={path}", *QUIET], cwd=ROOT, check=True, capture_output=True)
        man = pd.read_csv(path / "campaigns.csv")
        if name.startswith("long_record"):
            man = man.set_index("campaign")
            df = pd.concat([pd.read_csv(path / f"{c}.csv").assign(
                time=lambda d, c=c: d["time"] + man.loc[c, "record_offset_s"])
                for c in ("R1a", "R1b")], ignore_index=True)
            cut = int(round(0.9 * len(df)))
            out[name] = ({"train": df.iloc[:cut]}, {"test": df.iloc[cut:].reset_index(drop=True)})
            continue
        parts = {"train": {}, "test": {}}
        for row in man.itertuples():
            parts["train" if row.split == "train" else "test"][row.campaign] = pd.read_csv(
                path / row.file)
        out[name] = (parts["train"], parts["test"])
    return out


class Widening:
    """The four rules' factors for one monitor (module doc)."""

    def __init__(self, mon: SensorMonitor, snaps: np.ndarray):
        self.phi = mon.pod.phi_
        self.M = self.phi @ np.linalg.pinv(self.phi)
        self.h = np.diag(self.M).copy()
        n = len(self.h)
        self.others = [np.flatnonzero(np.arange(n) != j) for j in range(n)]
        A = self._coeffs(snaps)                        # (N, n, r)
        self.N = len(snaps)
        self.Sinv = [np.linalg.pinv(A[:, j].T @ A[:, j] / self.N) for j in range(n)]
        self.Finv = [np.linalg.pinv(snaps[:, o].T @ snaps[:, o] / self.N) for o in self.others]
        self.d2max = self._d2(A).max(0)
        self.qmax = self._q(snaps).max(0)
        self.fmax = self._full(snaps).max(0)

    def _loo(self, d):
        """Residual of every sensor and the leave-j-out coefficient shift (rank-one downdate)."""
        e = d - d @ self.M.T
        return e, e / np.maximum(1 - self.h, 1e-12)

    def _coeffs(self, d):
        a = d @ self.phi                       # orthonormal basis: the all-sensor coefficients
        _, ed = self._loo(d)
        return a[:, None, :] - ed[:, :, None] * self.phi[None, :, :]

    def _d2(self, A):
        return np.stack([np.einsum("ij,jk,ik->i", A[:, j], S, A[:, j])
                         for j, S in enumerate(self.Sinv)], 1)

    def _q(self, d):
        e, ed = self._loo(d)
        # residual of sensor i once j left the fit: e_i + H_ij e_j / (1 - h_jj)
        R = e[:, :, None] + self.M[None, :, :] * ed[:, None, :]
        n = len(self.h)
        R[:, np.arange(n), np.arange(n)] = 0.0
        return (R ** 2).sum(1)

    def _full(self, d):
        return np.stack([np.einsum("ij,jk,ik->i", d[:, o], F, d[:, o])
                         for o, F in zip(self.others, self.Finv)], 1)

    def ratios(self, d) -> dict:
        """Each distance over training's largest (unclipped); ``lsq``: the factor itself."""
        d2 = self._d2(self._coeffs(d))
        return {"lsq": np.sqrt(1 + d2 / self.N), "modes": np.sqrt(d2 / self.d2max),
                "resid": np.sqrt(self._q(d) / self.qmax),
                "full": np.sqrt(self._full(d) / self.fmax)}

    def factors(self, d) -> dict:
        return {"plain": np.ones_like(d),
                **{r: np.maximum(1, v) for r, v in self.ratios(d).items()}}


def judged_over(mon: SensorMonitor, d: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Sensor-samples whose last ``CONFIRM`` errors are all beyond their (widened) warning band."""
    M, h = mon.pod.operator(np.ones(d.shape[1], bool))
    e = np.abs(d - d @ M.T) / np.maximum(1 - h, 1e-12)
    beyond = e >= mon.warning_c * w
    out = beyond.copy()
    for k in range(1, CONFIRM):
        out[k:] &= beyond[:-k]
        out[:k] = False
    return out & (h < mon.pod.max_leverage)


def score(name: str, train: dict, test: dict) -> list[str]:
    names = [c for c in next(iter(train.values())).columns if c.startswith("T_")]
    raw = {c: df[names].to_numpy(float) for c, df in train.items()}
    pod = ThermalPOD(fit_band_c=0.5 * WARNING_C, window=WINDOW)
    mon = SensorMonitor.from_training(pod, names, raw, warning_c=WARNING_C, alarm_c=ALARM_C,
                                      window=WINDOW, confirm=CONFIRM, adaptive=False)
    snaps = np.vstack([a - a[0] for a in raw.values()])
    wide = Widening(mon, snaps)
    lines = []
    healthy = {r: 0 for r in RULES}
    peak = {r: 0.0 for r in RULES}
    where = (0.0, "")
    for df in test.values():
        d = df[names].to_numpy(float)
        d = d - d[0]
        f = wide.factors(d)
        for r in RULES:
            healthy[r] += int(judged_over(mon, d, f[r]).sum())
            M, h = mon.pod.operator(np.ones(len(names), bool))
            e = np.abs(d - d @ M.T) / np.maximum(1 - h, 1e-12) / (mon.warning_c * f[r])
            peak[r] = max(peak[r], float(np.max(e[:, h < mon.pod.max_leverage])))
            if r == "plain":          # the distances where the healthy error peaks
                e[:, h >= mon.pod.max_leverage] = 0
                k, j = np.unravel_index(int(np.argmax(e)), e.shape)
                if e[k, j] > where[0]:
                    raw = wide.ratios(d)
                    where = (float(e[k, j]), f"{names[j]} at {df['time'].iloc[k] / 3600:.2f} h: "
                             + " ".join(f"{q} {raw[q][k, j]:.2f}" for q in RULES[1:]))
    hours = sum(np.ptp(df["time"].to_numpy(float)) for df in test.values()) / 3600
    lines.append(f"{name:23s} r={mon.r_:2d} n={len(names):2d} {hours:4.1f} h beyond "
                 + "/".join(str(healthy[r]) for r in RULES) + "  peak |E|/band "
                 + "/".join(f"{peak[r]:.2f}" for r in RULES))
    lines.append(f"    plain peak {where[0]:.2f}, {where[1]}")
    for sensor in DRIFTS.get(name, []):
        j = names.index(sensor)
        unseen = not mon._observable[j]
        delays = {r: [] for r in RULES}
        at = []
        for df in test.values():
            t = df["time"].to_numpy(float)
            onset = t[len(t) // 2]
            d = df[names].to_numpy(float).copy()
            d[:, j] += np.clip(t - onset, 0, None) / 3600.0
            d = d - d[0]
            f = wide.factors(d)
            for r in RULES:
                over = judged_over(mon, d, f[r])
                hit = over.any(1) if unseen else over[:, j]
                hit &= t >= onset
                delays[r].append((t[np.argmax(hit)] - onset) / 60 if hit.any() else None)
                if r == "plain" and hit.any():   # each rule's factor on the sensor flagged first
                    k = int(np.argmax(hit))
                    first = int(np.argmax(over[k])) if unseen else j
                    at.append(f"{names[first]} " + "/".join(
                        f"{f[q][k, first]:.3f}" for q in RULES[1:]))
        what = "first judged sensor" if unseen else "itself"
        lines.append(f"    1 K/h on {sensor} ({what}), min: " + "  ".join(
            "/".join("-" if x is None else f"{x:.0f}" for x in delays[r]) for r in RULES)
)
        lines.append("      factors at the plain flag: " + "; ".join(at))
    return lines


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("root")
    args = parser.parse_args(argv)
    root = Path(args.root)
    root.mkdir(parents=True, exist_ok=True)
    print("per rule plain/lsq/modes/resid/full -- healthy: sensor-samples beyond the\n"
          "  (widened) warning band, the peak |E| / band; where the plain peak is: each distance\n"
          "  over training's largest (lsq: its factor); drift: minutes from the onset to the\n"
          "  first flag (per test campaign a/b/.., - none), lsq/modes/resid/full's factors then")
    for name, (train, test) in build(root).items():
        print("\n".join(score(name, train, test)), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
