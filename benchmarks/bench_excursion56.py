"""A real excursion beyond training read as a sensor fault? The adaptive compensator on an overspeed.

Stop 55 (``bench_state_envelope.py``, aside) found the ADAPTIVE deployed compensator 1.2-6.8 x the
PLAIN stream's Σ² vs truth on the ``long_record`` overspeeds (long4253 lagbank 4.40 against 0.648
µm²), and took the cause for the ``out of range`` exclusion of the hot motor.  Here, on the same
records (``bench_state_envelope.py``'s ``long4253``, ``long7717``, its ``--root`` cache), the
mechanism is measured and a rule on ``out of range`` is scored.

Rules, written before scoring them (stop 56):

* ``R1`` (the brief's): an out-of-range reading excludes its sensor only when no other active
  sensor predicts it (leverage >= ``pod.max_leverage`` in the active set) or when its
  leave-one-out self-prediction error is beyond its alarm band; otherwise it stays in (the stream's
  envelope then handles it as in plain mode).
* ``R3`` (the field explains the excursion, whatever the leverage): an out-of-range reading stays
  in when the other active sensors' prediction of it lies beyond the same training edge, and the
  reading is nearer that prediction than half its distance from the edge; a spike, a unit change,
  a drifting or stuck sensor leave the others' prediction inside the training range: out.

Adopted only if every bar of the brief holds (overspeed: adaptive no worse than plain or much
closer; injected faults caught as before; healthy records as quiet; strict xfails as they are).
The rules are scored by :class:`RangeRule` (a subclass here: nothing in src changed).

Run (the records are ``bench_state_envelope.py``'s, simulated into ``--root`` when missing)::

    PYTHONPATH=src .venv/bin/python benchmarks/bench_excursion56.py [--runs long4253] [--out f.json]

Measured 2026-11-30 (stop 56; 88.8 s user + 1.3 s sys for both runs and the three families, the
records cached).  Σ² = sum over the targets of the mean squared error vs truth over the test part
R1b (µm²).  Forms: ``plain`` (the stream alone), ``adaptive`` (monitor + guard, as replay streams
it), ``guard`` (the guard, no monitor; ``bound`` / ``rate``: its bound alone, its rate limit
alone), ``monitor`` (the monitor, no guard), ``R1`` / ``R3`` (adaptive, the monitor with the rule)::

  run       family       plain  adaptive  guard  bound   rate  monitor      R1      R3
  long4253  hammerstein  1.397     4.439  4.056  4.056  1.397    1.346   4.439  33.069
            lagbank      0.648     4.397  3.734  3.734  0.648    2.422   4.397  32.664
            mlr          3.991     5.811  5.490  5.490  3.991    2.956   5.811  12.880
  long7717  hammerstein  0.190     0.604  0.595  0.595  0.190    0.201   0.604   0.604
            lagbank      0.238     0.667  0.668  0.668  0.238    0.237   0.667   0.667
            mlr          1.193     1.386  1.491  1.491  1.193    1.094   1.386   1.386

The mechanism, per record:

* ``long7717`` (up to 1.5 x the training speed): no sensor leaves its range (T_motor at most
  44.36 °C against 35.58 + 10).  Five sensors pass their training maximum (T_spindle_front 62
  samples, to 33.86 against 29.86; T_motor 67, to 44.36), none is excluded for it; the only
  exclusions are T_col_front_top's two jumps (5.48 h, 24.78 h: -4.01, -2.47 °C, re-referenced),
  which the plain stream with that column as the monitor gave it prices at 0.190 -> 0.201
  (hammerstein), 0.238 -> 0.237 (lagbank), 1.193 -> 1.094 (mlr).  The whole adaptive excess
  is the guard's bound (``bound`` = ``guard``; the rate limit alone changes nothing): the truth
  reaches 86.6 µm, the bound (training error range widened by 0.2 of its width) is 76.7 µm;
  26-41 samples bounded, by up to 12.4 µm.
* ``long4253`` (up to 2 x): one sensor leaves its range, T_motor, 41 samples from 27.85 h (16000
  rpm), 10.1-19.2 °C above its training maximum 35.32 (the limit is +10).  It is NOT rebuilt from
  the POD: its leverage with every sensor in is 0.990 (>= ``pod.max_leverage`` 0.9, no other
  sensor predicts it), so it is held at its last good reading, 45.0 °C, for 50 samples (to 28.67
  h), up to 9.49 °C below the reading.  Yet the others do follow it: their leave-one-out
  prediction of it is 41.8-51.0 °C (beyond its training maximum on every sample; the reading
  45.4-54.5), off the reading by 3.49 °C on average (4.26 at most; its alarm band 3.68, 56 % of
  the samples within it): a real state, where an offset fault (spike, unit change) leaves the others'
  prediction where the healthy field is (it does not depend on the sensor's own reading).  Before
  it (27.67 h), T_spindle_rear, within its range (at most 32.52 °C against 27.46 + 10) but hot for
  real and unobservable too (leverage 0.986), is excluded as "its reading explains the others'
  self-prediction errors" (T_zdrive -0.51 °C, band 0.407) and held; it is re-admitted at 27.85 h
  only because T_motor's exclusion changed the operator.  Priced one column at a time in the plain
  stream (that column as the monitor gave it): T_motor held 0.648 -> 2.025 (lagbank), 1.397 ->
  1.364 (hammerstein), 3.991 -> 2.611 (mlr); T_spindle_rear held 0.648 -> 0.935, 1.397 -> 1.204,
  3.991 -> 4.335.  The monitor alone is better than plain for hammerstein and mlr and 3.7 x worse for
  lagbank; the guard's bound alone is 82-87 % of the adaptive excess (truth to 115.9 µm, bound
  90.3 µm; 26-51 samples bounded, by up to 33.5 µm).

The rules: R1 changes nothing anywhere (its "no other sensor predicts it" keeps T_motor out: the
identical Σ² on every line).  R3 keeps T_motor in (the others predict it beyond its maximum), and
then T_spindle_rear's "explains the others" exclusion is no longer undone: it stays held from
27.67 to 28.72 h through the overspeed, and the adaptive Σ² goes 4.44 -> 33.07, 4.40 -> 32.66,
5.81 -> 12.88.  On long7717 neither rule has a reading to act on.

CONCLUSION.  Not adopted, nothing in src changed.  The premise does not hold: on these records
the adaptive compensator's excess over plain is the correction guard's bound (a real error beyond
the training error range is bounded as a fault would be): the guard alone gives 82-87 % of it
on long4253, 98-100 % on long7717 (154 % for mlr: there the monitor helps).  No rule on
``out of range`` meets bar (a): one that left every real excursion in would give the ``guard``
column (the monitor passing the readings as read), still 5.8 x (lagbank), 2.9 x (hammerstein),
1.4 x (mlr) plain on long4253.  The range exclusion of T_motor
is a real state read as a fault, but its held value costs only lagbank (and helps the other two),
and keeping it in, alone, undoes the one thing that cut T_spindle_rear's held period short.  Bars
(b)-(d) were not run: no rule passed (a).  What would: (1) the guard's bound in an excursion the
sensors show consistently (its ``new_state_margin`` is the existing hook, but no new thermal
state is declared on these records: 0 such events, the E_Z bound episodes at 27.9-28.8 h on
long4253 and 37.2-37.9 h on long7717 are the guard's only events); (2) the "explaining"
exclusion of an unobservable sensor whose reading the others predict beyond its range, before (3)
any consistency rule on ``out of range``.

Since then (stop 56, ``bench_guard56.py``): (1) is done, the bound widens by the model's response
to inputs beyond their training range on the training pattern (``monitor.guard.follow_inputs``);
the ``adaptive`` column above is the guard as it was (now it is the ``monitor`` column).
"""

from __future__ import annotations

import argparse
import copy
import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_state_envelope import SCENARIOS, _compose, simulate  # noqa: E402
from cpu import print_cpu  # noqa: E402

from thermocomp.apps.deploy.adaptive import AdaptiveCompensator  # noqa: E402
from thermocomp.apps.deploy.streaming import replay  # noqa: E402
from thermocomp.apps.deploy.surveillance import SensorMonitor  # noqa: E402
from thermocomp.core.continuation import lead_ins  # noqa: E402
from thermocomp.shell.builders import build_compensator, deploy_stream, deployable  # noqa: E402
from thermocomp.shell.source import read_streamed  # noqa: E402

RUNS = ("long4253", "long7717")
FAMILIES = ("hammerstein", "lagbank", "mlr")
DATA = SCENARIOS["long"][2]          # data.reference=none


class RangeRule(SensorMonitor):
    """The monitor with an out-of-range reading kept in where ``rule`` (R1, R3: module doc) says
    it is consistent with the other sensors: for that sample its range limits are lifted."""

    rule = "R1"

    def _update(self, x, time):
        keep = self.kept(x)
        if not keep.any():
            return super()._update(x, time)
        lo, hi = self._lo_lim, self._hi_lim
        self._lo_lim, self._hi_lim = np.where(keep, -np.inf, lo), np.where(keep, np.inf, hi)
        try:
            return super()._update(x, time)
        finally:
            self._lo_lim, self._hi_lim = lo, hi

    def kept(self, x: np.ndarray) -> np.ndarray:
        """Active sensors out of range whose reading the rule keeps in."""
        rng = (x < self._lo_lim) | (x > self._hi_lim)
        keep = np.zeros(len(x), dtype=bool)
        if self._ref is None or self._M is None or not (rng & self._active).any():
            return keep
        d = np.where(np.isfinite(x - self._ref), x - self._ref, self._clean)
        with np.errstate(divide="ignore", invalid="ignore"):
            e = (d - self._M @ d[self._active]) / (1 - self._lev)   # leave-one-out error
        cand = rng & self._active & np.isfinite(x) & np.isfinite(e)
        if self.rule == "R1":
            return cand & self._observable & (np.abs(e) < self.alarm_c)
        p = x - e                                                 # the others' prediction (°C)
        edge = np.where(x > self._hi_lim, self.hi_c, self.lo_c)
        same_side = np.sign(p - edge) == np.sign(x - edge)
        return cand & (self._lev < 1 - 1e-9) & same_side & (np.abs(x - p) < 0.5 * np.abs(x - edge))


def _with_rule(monitor: SensorMonitor, rule: str) -> RangeRule:
    m = copy.deepcopy(monitor)
    m.__class__ = RangeRule
    m.rule = rule
    return m


def _setup(root: Path, run: str, family: str):
    noisy, truth = simulate(root, run)
    cfg = _compose(f"data.path={noisy}", "track=false", *DATA, f"model={family}")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds).fit(train)
    stream = deploy_stream(cfg, comp, train)
    adaptive = deployable(cfg, copy.deepcopy(stream), train, ds)
    (cid,) = test_ids
    ds_t, _, _, _ = read_streamed(_compose(f"data.path={truth}", "track=false", *DATA))
    df = ds.campaigns[cid].reset_index(drop=True)
    true = comp.measured({cid: ds_t.campaigns[cid].reset_index(drop=True)})[cid]
    return comp, stream, adaptive, df, lead_ins(comp, ds, test_ids).get(cid), \
        true[comp.targets_].to_numpy(float)


def _sigma2(deployed, df, lead, true, targets) -> tuple[float, pd.DataFrame]:
    pred = replay(deployed, df, lead_in=lead)
    return float(((true - pred[targets].to_numpy(float)) ** 2).mean(0).sum()), pred


def mechanism(monitor: SensorMonitor, df: pd.DataFrame) -> dict:
    """Per sensor beyond its training maximum: samples, largest reading; beyond the range
    (maximum + margin): samples, first hour, and for it the others' leave-one-out prediction."""
    names = monitor.names
    T = df[names].to_numpy(float)
    D = T - T[0]
    hours = (df["time"].to_numpy(float) - df["time"].iloc[0]) / 3600
    M, lev = monitor._operator(np.ones(len(names), dtype=bool))
    with np.errstate(divide="ignore", invalid="ignore"):
        E = (D - D @ M.T) / (1 - lev)
    out = {}
    for j, name in enumerate(names):
        above = T[:, j] > monitor.hi_c[j]
        if not above.any():
            continue
        rng = T[:, j] > monitor.hi_c[j] + monitor.range_margin_c
        line = {"above_hi": int(above.sum()), "max": float(T[:, j].max()),
                "hi": float(monitor.hi_c[j]), "out_of_range": int(rng.sum()),
                "leverage": float(lev[j]), "alarm_c": float(monitor.alarm_c[j])}
        if rng.any():
            p = T[rng, j] - E[rng, j]
            line.update(first_out_h=float(hours[np.argmax(rng)]),
                        predicted_min=float(p.min()), predicted_max=float(p.max()),
                        loo_abs_mean=float(np.abs(E[rng, j]).mean()),
                        loo_abs_max=float(np.abs(E[rng, j]).max()),
                        share_within_alarm=float(np.mean(np.abs(E[rng, j]) < monitor.alarm_c[j])),
                        excess_over_hi=[float(np.min(T[rng, j] - monitor.hi_c[j])),
                                        float(np.max(T[rng, j] - monitor.hi_c[j]))])
        out[name] = line
    return out


def measure(root: Path, run: str, family: str) -> dict:
    """Σ² (sum over targets of the MSE vs truth, µm²) of each form, the events of the adaptive
    one, the input columns in which the monitor's field differs from the readings (and plain's
    Σ² with that column alone as the monitor gave it), and the guard's bounded samples."""
    comp, stream, adaptive, df, lead, true = _setup(root, run, family)
    targets, mon, guard = comp.targets_, adaptive.monitor, adaptive.guard
    forms = {"plain": stream, "adaptive": adaptive,
             "guard_only": AdaptiveCompensator(copy.deepcopy(stream), None, copy.deepcopy(guard),
                                               adaptive.period_s),
             "adaptive_R1": AdaptiveCompensator(copy.deepcopy(stream), _with_rule(mon, "R1"),
                                                copy.deepcopy(guard), adaptive.period_s),
             "adaptive_R3": AdaptiveCompensator(copy.deepcopy(stream), _with_rule(mon, "R3"),
                                                copy.deepcopy(guard), adaptive.period_s)}
    # the guard's two limits apart: its bound alone (no rate limit), its rate limit alone (no bound)
    for name, part in (("guard_bound_only", {"max_rate_per_s": np.inf}),
                       ("guard_rate_only", {"lo": -np.inf, "hi": np.inf, "lo_new": None})):
        g = copy.deepcopy(guard)
        for key, value in part.items():
            setattr(g, key, np.full_like(guard.lo, value) if value is not None else None)
        forms[name] = AdaptiveCompensator(copy.deepcopy(stream), None, g, adaptive.period_s)
    seen: list[np.ndarray] = []
    only = AdaptiveCompensator(copy.deepcopy(stream), copy.deepcopy(mon), None, adaptive.period_s)
    inner = only.streaming._step

    def spy(x, t, clocked=False):
        seen.append(np.array(x, float))
        return inner(x, t, clocked)

    only.streaming._step = spy
    forms["monitor_only"] = only
    s2, events, preds = {}, {}, {}
    for name, dep in forms.items():
        s2[name], preds[name] = _sigma2(dep, df, lead, true, targets)
        if name != "plain":
            t0 = float(df["time"].iloc[0])
            events[name] = [[round((e["time"] - t0) / 3600, 2), e["sensor"] or e.get("target"),
                             e["to"], e["reason"][:90]]
                            for row in preds[name]["events"] for e in json.loads(row)]
    X = np.array(seen[-len(df):])
    columns = {}
    for j, c in enumerate(stream.columns_):
        if c in df.columns and np.nanmax(np.abs(X[:, j] - df[c].to_numpy(float))) > 1e-9:
            diff = X[:, j] - df[c].to_numpy(float)
            columns[c] = {"samples": int((np.abs(diff) > 1e-9).sum()),
                          "max_abs_c": float(np.nanmax(np.abs(diff))),
                          "plain_s2": _sigma2(stream, df.assign(**{c: X[:, j]}), lead, true,
                                              targets)[0]}
    g = preds["guard_only"][targets].to_numpy(float) - preds["plain"][targets].to_numpy(float)
    return {"run": run, "family": family, "s2": s2, "events": events, "columns": columns,
            "mechanism": mechanism(mon, df),
            "guard": {"samples": int((np.abs(g) > 1e-9).any(axis=1).sum()),
                      "max_abs_um": float(np.abs(g).max()),
                      "bound": [guard.lo.tolist(), guard.hi.tolist()],
                      "truth_range": [true.min(0).tolist(), true.max(0).tolist()]}}


def main(argv=None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", default="/tmp/stateenv55-bench")
    ap.add_argument("--runs", nargs="+", default=list(RUNS))
    ap.add_argument("--families", nargs="+", default=list(FAMILIES))
    ap.add_argument("--out", default=None, help="write the results as JSON here")
    args = ap.parse_args(argv)
    root, results = Path(args.root), []
    for run in args.runs:
        for family in args.families:
            r = measure(root, run, family)
            results.append(r)
            print(run, family, {k: round(v, 3) for k, v in r["s2"].items()}, flush=True)
            for name, line in r["mechanism"].items():
                print("   ", name, {k: (round(v, 3) if isinstance(v, float) else v)
                                    for k, v in line.items()})
            for c, line in r["columns"].items():
                print("    monitor's field differs:", c, {k: round(v, 3) for k, v in line.items()})
            print("    guard:", r["guard"]["samples"], "samples moved, max",
                  round(r["guard"]["max_abs_um"], 2), "µm")
            for name in ("adaptive", "adaptive_R1", "adaptive_R3"):
                print(f"    {name} exclusions:", [e[:3] for e in r["events"][name]
                                                   if e[2] == "excluded" or e[3].startswith("re-admitted")])
    print_cpu()
    if args.out:
        Path(args.out).write_text(json.dumps(results))


if __name__ == "__main__":
    main()
