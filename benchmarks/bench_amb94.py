"""A real step of the air re-referenced for the rest of the campaign: judged again over the hours
after re-admission, by how far the re-referenced ``T_amb`` leaves the others' prediction of it
(amb94).  Prototype in the bench (the monitor patched in this process); src as on main.

Usage::

    python benchmarks/bench_amb94.py seen ROOT
    python benchmarks/bench_amb94.py fresh ROOT SEEDS

``seen``: seeds 5353 and 4242 (``bench_ambient_step55``'s records, made under ROOT): each test
campaign (K03, K06, K09) from its middle row with the air itself stepped +5 K, +2 K, +5 K over
30 min (``SteppedAmbient``, the simulation rerun) or ``T_amb``'s column offset +5 K, +2 K; the
deployed MLR / ARX / lag bank fitted by ``thermocomp run``; RMS over E_X, E_Y, E_Z of measured
minus predicted error from the middle row on (µm): adaptive as on main / adaptive with the rule /
plain; the row the rule decides at; the healthy test campaigns streamed with and without the rule
(must be identical: no jump, nothing to judge); and the rule's false-decision rate: the share of
the rows of the train and of the healthy test campaigns at which a ``T_amb`` offset of +-2 / +-5 K
starting there would be dropped as real air before the campaign's end.
``fresh``: the same on ``SEEDS`` (e.g. ``9671-9675``), scored once.

The rule (sequential, after re-admission).  Today a jump of ``T_amb`` (a sensor no other predicts)
is excluded, re-referenced by the jump ``J`` and re-admitted re-referenced 10-11 samples later, for
good.  With the rule, from re-admission on, the two hypotheses stay open: offset (the
re-referenced reading ``x - J`` is the air) and real (``x`` is the air).  The evidence is the
others' prediction ``p`` of the air (a least-squares fit of ``T_amb`` on the other temperatures
and an intercept, on the train campaigns): a real change of the air moves the structure and so
``p`` towards ``x`` over hours; an offset moves nothing.  The statistic is the share of the jump
the prediction has followed since the jump, ``f_t = -sign(J) * d_t / |J|`` with
``d_t = (x_t - J - p_t) - mean_{W rows before the jump}(x - p)``; the real hypothesis is taken
(the re-reference dropped) at the first row where ``f_t > 1/2`` (the likelier of the two under
equal Gaussian spread) AND ``-sign(J) d_t`` exceeds ``theta``, the healthy excursion: the
99th percentile, over every start row of the train campaigns, of the largest excursion of
``-/+ d`` (no jump) from that row's re-admission (``W`` rows on) to the campaign's end: a stated
false-decision rate of 1 % per start row and direction on the train campaigns.  On the decision
the re-reference is dropped at once (the reference, its window and its last value moved by
``J`` together, so no jump is seen): the MLR reads the air as measured from that row on, which is
what a confirmed real step calls for; ramping it would only keep a known wrong input longer.

BAR (written before any number of the rule was seen, seen or fresh):
  * offsets (+5, +2 K, every test campaign, every model): the rule's RMS not worse than main's by
    more than 2 % on any record;
  * real steps (+5, +2 K, ramp): the rule's RMS nearer the plain stream's than main's is, on the
    mean over the records where plain beats main (and not worse than main by > 2 % on the mean
    over all real-step records);
  * healthy: the healthy test campaigns streamed identical with and without the rule; the
    false-decision rate on the healthy test campaigns' rows <= 5 % for every offset size;
  * scored ONCE on FRESH 9671-9675 (``yearround_spindle``, 9 campaigns, stepped as the test
    does), MLR; KEPT only if the bar holds there (and then only with src, the xfail passing).

Measured 2026-12-05 (amb94; the bar above was committed before any run, feaa470e, and not changed;
one line printing the healthy test campaigns' own excursion was added after the fresh score, the
rule's numbers unchanged).  RMS (µm) main / rule / plain, the decisions only (every other record
of the tables reads main = rule; the run prints all of them):

  SEEN 5353 / 4242 (MLR, ARX, lag bank; theta 1.89 / 2.34 K): no offset taken (36 offset records
  rule = main), healthy test campaigns identical, false-decision rate on the healthy test rows
  0 % at +-5 K, 4.1 % / 0.0 % at +-2 K (train 0 % / 1.0-1.2 %); 15 of 54 real-step records decided
  (no ramp: the jump the monitor
  excludes and re-references there is the ramp's first 0.8-0.9 K sample, not its 5 K), 12 better, 3 worse:
    5353 MLR  K06 +5  10.29 -> 6.34 (6.46; the strict xfail's 1.1 x plain met), K09 +5 12.66 -> 13.07
              (14.57), K09 +2 6.81 -> 7.49 (9.20); 4242 MLR K03 +5 14.71 -> 14.40 (12.26), K06 +5
              12.60 -> 10.99 (8.20); ARX 5353 K06 +5 10.19 -> 7.47, K09 +5 15.62 -> 13.58, K09 +2
              9.84 -> 9.08; 4242 K03 +5 23.61 -> 24.42 (46.95); lag bank 5353 K06 +5 6.70 -> 4.77,
              K09 +5 15.32 -> 11.29; 4242 K06 +5 10.92 -> 9.35.
  Bar on seen: every check PASS (real-step mean 11.817 -> 11.465, plain 12.092; where plain beats
  main, mean distance to plain 3.426 -> 2.912).

  FRESH 9671-9675 (MLR, scored once): FAIL on two checks of five.
    * offsets: two +2 K offsets taken for real air: 9674 K09 5.79 -> 6.27 (+8.3 %, plain 8.88),
      9671 K09 8.55 -> 8.29 (plain 7.77); false-decision rate on the healthy test rows 7.1 % (+-5 K)
      and 16.1 % (+-2 K) on 9671, 7.5 % / 12.1 % on 9674 (0 % on 9672, 9673, 9675); train 0 % /
      1.0-1.3 %.  The cause: theta is the train campaigns' 99th percentile of the gap's
      excursion (1.88 / 2.12 K), the healthy test campaigns of 9671 and 9674 go to 3.02 / 3.04 K
      (spindle programmes the six train campaigns did not show): monitor68's limit again.
    * real steps: 10 of 45 decided, 8 better, 2 worse: 9671 K03 +5 15.35 -> 12.22 (7.39), +2
      10.63 -> 9.45 (7.20), K09 +5 17.76 -> 10.90 (8.39), +2 11.72 -> 10.11 (8.16); 9672 K03 +5
      12.56 -> 12.48, K09 +5 17.31 -> 17.28; 9674 K09 +2 5.79 -> 6.23 (7.84); 9675 K06 +5 11.21 ->
      9.27 (7.71), +2 9.03 -> 8.35, K09 +5 15.53 -> 16.36 (21.03).  Mean 10.819 -> 10.503 (plain
      10.287); where plain beats main (28) the mean distance to plain 2.230 -> 1.676 (PASS).
    * healthy streams identical (PASS).
  Verdict: REFUSED (no src was changed: the rule lives in this bench, ``_Rule`` and
  ``AirPrediction``; ``git diff 30f94c98 -- src`` is empty, so there is no rule patch).  CPU: 9 s
  (seen, fits and simulations made) / 23 s (fresh, made from nothing) for the whole bench; the
  rule itself is one least-squares prediction per row after a re-admission.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_ambient_step55 as s55  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402

from thermocomp.apps.deploy.adaptive import AdaptiveCompensator  # noqa: E402
from thermocomp.apps.deploy.surveillance import SensorMonitor  # noqa: E402
from thermocomp.apps.sim.scenario import write_scenario  # noqa: E402
from thermocomp.shell.cli import main as thermocomp  # noqa: E402

AIR, WINDOW, QUANTILE = s55.AIR, s55.WINDOW, 0.99
REAL = (("real +5", 5.0, 0.0), ("real +2", 2.0, 0.0), ("ramp +5/30min", 5.0, 1800.0))
OFFSETS = (5.0, 2.0)
FAMILIES = ("mlr", "arx", "lagbank")


class AirPrediction:
    """The others' prediction of the air, fitted on the train campaigns; the healthy bound."""

    def __init__(self, frames: list[pd.DataFrame]):
        self.others = [c for c in frames[0].columns if c.startswith("T_") and c != AIR]
        X = np.vstack([self._design(f) for f in frames])
        y = np.concatenate([f[AIR].to_numpy(float) for f in frames])
        self.coef = np.linalg.lstsq(X, y, rcond=None)[0]
        exc = [e for f in frames for e in self.excursions(f)]
        self.theta = float(np.quantile(exc, QUANTILE))

    def _design(self, f):
        return np.c_[f[self.others].to_numpy(float), np.ones(len(f))]

    def gap(self, f: pd.DataFrame) -> np.ndarray:
        """``x - p`` per row."""
        return f[AIR].to_numpy(float) - self._design(f) @ self.coef

    def excursions(self, f: pd.DataFrame) -> list[float]:
        """Per start row k and direction: the largest excursion of the gap from its mean over
        the W rows before k, from k + W to the end (no jump: what an offset sees)."""
        g, out = self.gap(f), []
        for k in range(WINDOW, len(g) - WINDOW - 1):
            d = g[k + WINDOW:] - g[k - WINDOW:k].mean()
            out += [float(d.max()), float(-d.min())]
        return out

    def decided(self, g: np.ndarray, k: int, jump: float, start: int) -> int | None:
        """The first row >= ``start`` at which the jump at row ``k`` is taken as real."""
        d = g[start:] - jump - g[max(0, k - WINDOW):k].mean()
        s = -np.sign(jump) * d
        hit = np.flatnonzero((s / abs(jump) > 0.5) & (s > self.theta))
        return start + int(hit[0]) if len(hit) else None

    def false_rate(self, frames, offset: float) -> float:
        """Share of start rows (both signs of ``offset``) at which an offset would be dropped."""
        taken = []
        for f in frames:
            g = self.gap(f)
            for k in range(WINDOW, len(g) - WINDOW - 1):
                for dT in (offset, -offset):
                    taken.append(self.decided(g + np.where(np.arange(len(g)) >= k, dT, 0.0),
                                              k, dT, k + WINDOW) is not None)
        return float(np.mean(taken))


class _Rule:
    """The monitor patched in this process: the sequential judgement after re-admission."""

    pred: AirPrediction | None = None
    log: list = []

    @classmethod
    def install(cls):
        update, reset = SensorMonitor.update, SensorMonitor.reset

        def patched_reset(self):
            reset(self)
            self._amb = {"rows": [], "k": None, "jump": None, "was": True}

        def patched_update(self, reading, time=float("nan")):
            if not hasattr(self, "_amb"):
                self._amb = {"rows": [], "k": None, "jump": None, "was": True}
            s, j = self._amb, list(self.names).index(AIR)
            clean, events = update(self, reading, time)
            s["rows"].append(np.asarray(reading, float))
            row = len(s["rows"]) - 1
            if s["was"] and not self._active[j]:
                s["k"] = row
            if not s["was"] and self._active[j] and cls.pred is not None:
                shift = self._ref[j] - self._ref0[j] if np.isfinite(self._ref0[j]) else 0.0
                if shift and s["jump"] is None:
                    s["jump"], s["start"] = shift, row
            s["was"] = bool(self._active[j])
            if s["jump"] is not None and cls.pred is not None and s["jump"] != "done":
                f = pd.DataFrame(s["rows"], columns=list(self.names))
                g = cls.pred.gap(f)
                at = cls.pred.decided(g, s["k"], s["jump"], s["start"])
                if at is not None:
                    J = s["jump"]
                    self._ref[j] -= J
                    self._prev[j] += J
                    self._hist[:, j] += J
                    clean = clean.copy()
                    clean[j] += J
                    cls.log.append((s["k"], row, J))
                    s["jump"] = "done"
            return clean, events

        SensorMonitor.update, SensorMonitor.reset = patched_update, patched_reset
        # row by row (the block path is a faster form of the same rows)
        AdaptiveCompensator._inputs_block = lambda self, *a, **k: 0


def _record(root: Path, seed: int):
    data = s55.made(root, seed)
    for fam in FAMILIES[1:]:
        if not (root / f"{fam}/model.pkl").exists():
            thermocomp(["run", f"data.path={data}", f"model={fam}", "track=false", "plots=none",
                  "eval.validation=false", f"out={root / fam}"])
    listed = pd.read_csv(data / "campaigns.csv")
    train = [pd.read_csv(data / f"{c}.csv") for c in listed.loc[listed["split"] == "train", "campaign"]]
    tests = list(listed.loc[listed["split"] == "test", "campaign"])
    cases = {}
    for cid in tests:
        raw = pd.read_csv(data / f"{cid}.csv")
        cases[cid, "healthy"] = (raw, raw)
        for name, step, ramp in REAL:
            path = root / f"air94_{cid}_{step:+g}_{ramp:g}"
            if not path.exists():
                write_scenario(s55._scenario(seed, cid=cid, step_c=step, ramp_s=ramp), path)
            df = pd.read_csv(path / f"{cid}.csv")
            cases[cid, name] = (df, df)
        for dT in OFFSETS:
            f = raw.copy()
            f.loc[len(raw) // 2:, AIR] += dT
            cases[cid, f"offset +{dT:g}"] = (f, raw)
    return data, train, tests, cases


def score(root: Path, seeds: list[int], families=FAMILIES) -> None:
    _Rule.install()
    rows, worst_rate = [], 0.0
    for seed in seeds:
        data, train, tests, cases = _record(root / f"s{seed}", seed)
        pred = AirPrediction(train)
        healthy = [cases[cid, "healthy"][0] for cid in tests]
        rates = {dT: (pred.false_rate(train, dT), pred.false_rate(healthy, dT)) for dT in OFFSETS}
        seen_exc = np.quantile([e for f in healthy for e in pred.excursions(f)], QUANTILE)
        print(f"seed {seed}: theta (healthy excursion, {QUANTILE:.0%}) {pred.theta:.2f} K "
              f"(the healthy test campaigns' own: {seen_exc:.2f} K); "
              "false-decision rate train / healthy test: "
              + ", ".join(f"+-{dT:g} K {a:.1%} / {b:.1%}" for dT, (a, b) in rates.items()), flush=True)
        worst_rate = max([worst_rate] + [b for _, b in rates.values()])
        for fam in families:
            forms = s55._forms(root / f"s{seed}", fam)
            for (cid, case), (df, err) in cases.items():
                _Rule.pred = None
                before = s55._rms(forms["true"], df, err, cid)
                _Rule.pred, _Rule.log = pred, []
                after = s55._rms(forms["true"], df, err, cid)
                log = _Rule.log[:]
                _Rule.pred = None
                plain = s55._rms(forms["false"], df, err, cid)
                at = f"decided at row {log[0][1]} (jump row {log[0][0]}, of {len(df)})" if log else "-"
                print(f"  {seed} {fam:8s} {cid} {case:14s} {before:6.2f} / {after:6.2f} / {plain:6.2f}"
                      f"   {at}", flush=True)
                rows.append((fam, case, before, after, plain))
    verdict(rows, worst_rate)


def verdict(rows, worst_rate: float) -> bool:
    """The BAR of the module doc on the scored ``rows`` (family, case, main, rule, plain)."""
    t = pd.DataFrame(rows, columns=["fam", "case", "main", "rule", "plain"])
    off = t[t["case"].str.startswith("offset")]
    real = t[t["case"].str.startswith(("real", "ramp"))]
    healthy = t[t["case"] == "healthy"]
    lose = real[real["plain"] < real["main"]]
    checks = {
        "offsets within 2 % of main (worst rule/main)": (off["rule"] / off["main"]).max() <= 1.02,
        "real steps nearer plain where plain beats main (mean |.-plain| main -> rule)":
            (lose["rule"] - lose["plain"]).abs().mean() < (lose["main"] - lose["plain"]).abs().mean(),
        "real steps' mean not worse than main by > 2 %": real["rule"].mean() <= 1.02 * real["main"].mean(),
        "healthy streams identical": bool((healthy["rule"] == healthy["main"]).all()),
        "false-decision rate on healthy test rows <= 5 %": worst_rate <= 0.05,
    }
    print(f"offsets worst rule/main {(off['rule'] / off['main']).max():.4f}; "
          f"real steps where plain beats main ({len(lose)}): mean |main-plain| "
          f"{(lose['main'] - lose['plain']).abs().mean():.3f} -> |rule-plain| "
          f"{(lose['rule'] - lose['plain']).abs().mean():.3f} µm; real-step mean main "
          f"{real['main'].mean():.3f} -> rule {real['rule'].mean():.3f} (plain {real['plain'].mean():.3f}); "
          f"records decided better / worse than main: {(real['rule'] < real['main']).sum()} / "
          f"{(real['rule'] > real['main']).sum()} of {len(real)}; worst false-decision rate {worst_rate:.1%}")
    for name, ok in checks.items():
        print(f"  {'PASS' if ok else 'FAIL'}  {name}")
    return all(checks.values())


def seen(root: str) -> None:
    score(made_folder(root), [5353, 4242])


def fresh(root: str, seeds: str) -> None:
    score(made_folder(root), seed_list(seeds), families=("mlr",))


def main(argv: list[str]) -> int:
    """Run the command ``argv`` names (the module doc's Usage); 2 and the usage without one."""
    return run_commands(__doc__, {"seen": seen, "fresh": fresh}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
