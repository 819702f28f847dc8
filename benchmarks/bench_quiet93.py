"""The served monitor on healthy short records (stop 93, quiet93): dep93 found on seed 9559
(bench_data92's swiss-lathe ``contract.csv``, mlr, 58 rows at 300 s: 43 train, 15 test) the
adaptive compensator (``monitor.adaptive=true``, the default deployment) excluding ``T_amb`` at
data row 46, 600 s into the test part, where the simulator planted no fault (sim.truth.json).

Usage (from ``benchmarks/``, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_quiet93.py trace ROOT SEED [HOURS]              # one record's evidence
    python benchmarks/bench_quiet93.py count ROOT SEEDS [HOURS [VARIANT]]   # healthy exclusions
    python benchmarks/bench_quiet93.py planted ROOT SEEDS [HOURS [RATE [VARIANT]]]  # a drift's cost

``trace``: the record of SEED (``thermocomp simulate`` as bench_data88 writes it: 3 campaigns of
HOURS (4) to HOURS + 1 h at 300 s, the longest one the lab's record -- for 4 h the very rows of
bench_data92's ``contract.csv``; written once under ROOT/SEED-<HOURS>h), split as the reader
splits it (``data.test_fraction=0.25``, test rows counted half up: record.py's ``_counts``), the
monitor fitted as ``build_adaptive`` fits it (the default ``monitor`` group; ``select=all``: every
``T_`` column is an input and monitored) on the train rows, then the whole record streamed from a
reset (the test part warmed on the train rows, as ``replay`` streams a file that continues the
train one): per row from the last train rows the worst sensor's windowed self-prediction error
and T_amb's against the warning band, the events; then each sensor's leverage, its in-sample
training spread (99.5th percentile of its windowed leave-one-out error: what sets the band's
floor, ``spread_factor`` x it), its FORWARD spread (the same percentile of the errors of rows
after those the POD was refitted on, rolling origins at 50-90 % of the train rows), its band.
``count``: per seed and length (HOURS, default ``4,12``) every exclusion the monitor makes on the
healthy record (sim.truth.json: no effect, no fault).  VARIANT (default ``main``): ``widen``, the
CANDIDATE (bench only, not in src) -- each band's floor from the larger of the in-sample and the
forward spread (``spread_factor`` x, the alarm band twice it); ``unjudged``, the in-sample bands
but a sensor whose forward spread passes its warning band never out by its error; ``alarm``, main's own key
``monitor.exclude_at=alarm`` (a drift excludes past the alarm band, 0.8 °C, not the warning one).
``planted``: per seed and sensor, a drift of RATE (0.05) °C per sample added from the first test
row on: the test rows until that sensor is excluded, main's monitor / the candidate's (inf: never).

BAR (the brief's, held before any variant was run; never reached): a rule is scored on the FRESH
9619-9628 (5 short + 5 long) only if it makes 0 exclusions on the 30 healthy SEEN records; it is
KEPT only with 0 exclusions on the 10 healthy fresh ones and bench_bar91b's distance bar unchanged
on the faulted ones.  Below that on the seen records: not built, TRACED with the table.

Measured (2026-12-05, this tree = main 6911a8ee's src; SEEN seeds only: bench_data92's 9501-9505,
bench_data92b's 9531-9535, bench_data93's 9556-9560; the fresh 9619-9628 NOT drawn: no rule met
its bar on the seen ones, so there was nothing to score)
-------------------------------------------------------------------------------------------------
Trace (``trace /tmp/quiet93 9559``; 58 rows, every cell bench_data92's contract.csv's, train 43,
test 15; truth: no effect, no fault). The same event as dep93's trace of the deployed model
(replay: 600 s into the test; its pack: 13500 s): T_amb ``ok -> excluded`` at row index 45 (data
row 46, t 13500 s, 600 s into the test part), "drift: self-prediction error -0.47 °C over the last
2 samples" -- the ``drift`` detector (not band-by-jump, not range: T_amb read 21.31 -> 23.86 °C in
train, 24.43 at the test end, inside its range [21.26, 23.90] + 10; largest step 0.23), the
lone-fault path: with T_amb out every other sensor is within its band, so the new-state veto does
not hold it. T_amb's error (each the mean of the last 2 windowed errors): -0.095 / -0.211 on the
last two train rows, -0.317, -0.433, -0.466 (excluded: -0.47 past 0.400), then -0.45 ... -0.70 at
the test end: a steady trend, not noise. The limit is the CONFIGURED warning band 0.400 °C:
T_amb's in-sample spread 0.112 (floor 3 x = 0.337) is below it. Why too tight: the POD (2 modes)
is fitted on the SAME 43 rows of ONE campaign it judges, where the air warms with the day as the
machine heats (the simulator's ambient: 0.95 air + 0.05 column_back, a daily cycle and a slow
drift, no coupling to the spindle); T_amb's leverage 0.056 -- the others "predict" it entirely by
that co-trend --, and its FORWARD spread is 0.609 °C, 5.4x the in-sample 0.112 (the machine
sensors' 0.15-0.29 against 0.04-0.09, 2-5x). A single campaign's correlation of the air with the
machine is no physics; it breaks as soon as the stream leaves the rows it was fitted on.

Count on the healthy SEEN records (``count ... 4,12 [widen|alarm|unjudged]``): exclusions (all T_amb, all
``drift``, all in the test part; error at the exclusion, °C)

=======  =================  ================================  ==================  ==================
length   rows (train)       main                              widen (candidate)   alarm (main's key)
=======  =================  ================================  ==================  ==================
4-5 h    54-61 (40-46)      7 of 15: 9501 +0.47, 9502 +0.48,  2 of 15: 9533       2 of 15: 9533
                            9503 -0.47, 9533 +0.50, 9534      +0.96, 9556 +0.89   +0.85, 9556 +0.89
                            +0.46, 9556 +0.45, 9559 -0.47
12-13 h  150-157 (112-118)  3 of 15: 9502 -0.65, 9559 (T_amb  2 of 15: 9502       2 of 15: 9502
                            explains T_box1's error), 9560    -1.2, 9560 -1.4     -1.2, 9560 -1.9
                            -0.91
=======  =================  ================================  ==================  ==================

So the same rule fires on 7 of 15 healthy short records (every time T_amb, 0.45-0.50 °C against
0.40), and still on 3 of 15 three times longer: a short training part makes it likelier, not
unique to it -- the air wanders away from any machine field however long the one campaign.
No limit on the error reaches 0: the candidate (the band's floor from the forward spread, a limit
widened by its estimate's out-of-sample error) and main's ``monitor.exclude_at=alarm`` (0.8 °C)
each leave 2 + 2 of 30 healthy records excluding T_amb (0.85-1.9 °C: the air's error grows
without bound with the test part), and both cost detection: ``planted ... 4 0.05 VARIANT`` (15
short seen records x 10 sensors, 0.05 °C per sample from the first test row) missed 55 of 150 on
main (median 9 test rows to the exclusion, mean 8.57), 80 of 150 widened (median 9, mean 9.29),
140 of 150 at the alarm band (median 11.5, mean 10.30).  Both fail the brief's bar on the seen
records already (0 healthy exclusions), so neither was built and the fresh seeds 9619-9628 were
not drawn.  A third probe, ``unjudged`` (the in-sample floors, but a sensor whose forward spread
passes its warning band never out by its error -- the "too little evidence" form), leaves 4 + 3 of
30 (4 h: 9503 -0.47, 9533 +0.96, 9534 +0.46, 9556 +0.45; 12 h: 9502, 9559, 9560 as main): on
40-46 rows T_amb's forward spread is not always past its band, so it does not single the air out;
not scored for detection.  Verdict: TRACED.

What a rule would need (not tried here): the exclusion of a sensor the others predict only by a
one-campaign co-trend is no evidence -- e.g. no drift exclusion (judge and warn only; dropout /
range / jump / freeze still exclude) while the training part holds fewer than 2 campaigns, or for
a sensor whose forward spread exceeds its band (T_amb here, 0.61 > 0.40), scored on bench_bar91b's
distance bar since it gives up drift detection there.
CPU: ``count`` 15 seeds x 2 lengths 6 s (after the simulate runs, ~4 s per record once);
``planted`` 15 seeds 45 s per variant.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from _cli import run_commands, seed_list
from bench_data88 import LIGHT, _cli

FRACTION = 0.25    # bench_data92's data.test_fraction


def _record(root: str, seed: int, hours: float) -> tuple[pd.DataFrame, dict]:
    """The longest campaign of ``simulate seed=SEED`` (3 campaigns of HOURS to HOURS + 1 h) and
    its truth; written once under ROOT/SEED-<HOURS>h."""
    base = Path(root) / f"{seed}-{hours:g}h"
    ds = base / "sim"
    if not (ds / "campaigns.csv").exists():
        done = _cli("simulate", f"seed={seed}", f"data.path={ds}", "sim.generator.n_campaigns=3",
                    f"sim.generator.duration_h=[{hours:.1f},{hours + 1:.1f}]", *LIGHT)
        assert done.returncode == 0, done.stderr[-2000:]
    index = pd.read_csv(ds / "campaigns.csv")
    rows = pd.read_csv(ds / index.loc[index["duration_h"].idxmax(), "file"])
    return rows, json.loads((base / "sim.truth.json").read_text())


def _monitor(train: pd.DataFrame, names: list[str], **override):
    """The SensorMonitor ``build_adaptive`` fits with the default ``monitor`` group: its own
    options, caught on their way to ``AdaptiveCompensator.from_training`` (no model needed)."""
    from types import SimpleNamespace
    from unittest import mock

    from thermocomp.apps.deploy.adaptive import AdaptiveCompensator
    from thermocomp.apps.deploy.pod import ThermalPOD
    from thermocomp.apps.deploy.surveillance import SensorMonitor
    from thermocomp.shell.builders import build_adaptive
    from thermocomp.shell.config.overrides import compose

    caught = {}
    with mock.patch.object(AdaptiveCompensator, "from_training",
                           lambda *args, **kwargs: caught.update(kwargs)):
        build_adaptive(compose([*LIGHT], "replay"), SimpleNamespace(compensator=None), {})
    return SensorMonitor.from_training(ThermalPOD(**caught["pod"]), names,
                                       {"train": train[names].to_numpy(float)},
                                       learned_bands=caught["learned_bands"],
                                       **{**caught["monitor"], **override})


def _split(rows: pd.DataFrame) -> int:
    """Train rows as the reader counts them (test: half up)."""
    from thermocomp.core.io.options import ReadOptions
    from thermocomp.core.io.record import _counts

    return len(rows) - _counts(len(rows), ReadOptions(test_fraction=FRACTION))["test"]


def _forward_spread(mon, snaps: np.ndarray) -> np.ndarray:
    """Each sensor's spread as the POD predicts rows AFTER those it was fitted on: rolling
    origins at 50-90 % of the train rows, the POD refitted (its modes) on the rows before, the
    windowed leave-one-out error of the rows after; the 99.5th percentile of them pooled."""
    from thermocomp.apps.deploy.pod import ThermalPOD, windowed_mean

    held = []
    for share in (0.5, 0.6, 0.7, 0.8, 0.9):
        cut = int(round(share * len(snaps)))
        pod = ThermalPOD(modes=mon.pod.n_modes_, window=mon.pod.window,
                         max_leverage=mon.pod.max_leverage).fit(snaps[:cut])
        E = np.nan_to_num(pod.deleted_residuals(snaps[cut:]))
        held.append(windowed_mean(E, np.zeros(len(E), int), pod.window))
    return np.nanquantile(np.abs(np.vstack(held)), 0.995, axis=0)


def _widened(mon, train: np.ndarray, unjudged: bool = False):
    """CANDIDATES (probes on SEEN records only, not in src): ``mon`` with each floor taken from
    the larger of the in-sample and the forward spread (``spread_factor`` x, alarm twice); or
    (``unjudged``) the in-sample floors, but a sensor whose forward spread passes its warning
    band given bands no error reaches (1e6 °C: never out by its self-prediction)."""
    from thermocomp.apps.deploy.surveillance import SensorMonitor

    forward = _forward_spread(mon, train - train[0])
    floor = (np.where(forward > mon.warning_c, 1e6, mon.floor_c) if unjudged
             else np.maximum(mon.floor_c, 3.0 * forward))
    return SensorMonitor(mon.pod, mon.names, warning_c=np.maximum(mon.warning_c, floor),
                         alarm_c=np.maximum(mon.alarm_c, 2 * floor), window=mon.window,
                         confirm=mon.confirm, adaptive=mon.adaptive, exclude_at=mon.exclude_at,
                         max_step_c=mon.max_step_c, longest_run=mon.longest_run, lo_c=mon.lo_c,
                         hi_c=mon.hi_c, first_c=mon.first_c, jump_factor=mon.jump_factor,
                         freeze_factor=mon.freeze_factor, range_margin_c=mon.range_margin_c,
                         new_state=mon.new_state, new_state_others=mon.new_state_others,
                         rounding_c=mon.rounding_c, floor_c=floor, moment=mon.moment)


def _stream(rows: pd.DataFrame, n_train: int, verbose: bool = False, variant: str = "main"):
    """Fit on the first ``n_train`` rows (``variant``: main's monitor, ``widen`` or ``alarm``,
    module docstring), stream every row from a reset: the events."""
    names = [c for c in rows.columns if c.startswith("T_")]
    mon = _monitor(rows.iloc[:n_train], names, **({"exclude_at": "alarm"} if variant == "alarm"
                                                   else {}))
    if variant in ("widen", "unjudged"):
        mon = _widened(mon, rows[names].to_numpy(float)[:n_train], variant == "unjudged")
    mon.reset()
    events = []
    for i, (t, x) in enumerate(zip(rows["time"].to_numpy(float), rows[names].to_numpy(float))):
        _, ev = mon.update(x, t)
        err = mon.last_error_
        for e in ev:
            events.append({**e, "row": i, "error": err.copy(), "band": mon._warn.copy()})
        if verbose and i >= n_train - 2:
            worst = int(np.nanargmax(np.abs(err))) if np.isfinite(err).any() else 0
            print(f"  row {i:3d} t {t:7g} {'test ' if i >= n_train else 'train'} worst "
                  f"{names[worst]} {err[worst]:+.3f} band {mon._warn[worst]:.3f}; T_amb "
                  f"{err[names.index('T_amb')]:+.3f}; events "
                  f"{[(e['sensor'], e['to']) for e in ev]}")
    return mon, names, events


def trace(root: str, seed: str, hours: str = "4") -> None:
    """The exclusion's evidence on SEED's record (module docstring)."""
    rows, truth = _record(root, int(seed), float(hours))
    n_train = _split(rows)
    print(f"seed {seed} {hours} h: {len(rows)} rows, train {n_train}, test {len(rows) - n_train}; "
          f"truth: effects {truth['params'].get('effects')}, undeclared "
          f"{truth.get('undeclared_effects')}")
    mon, names, events = _stream(rows, n_train, verbose=True)
    spread = mon.floor_c / 3.0
    lev = mon.pod.operator(np.ones(len(names), dtype=bool))[1]
    fwd = _forward_spread(mon, rows[names].to_numpy(float)[:n_train]
                          - rows[names].to_numpy(float)[0])
    amb = rows["T_amb"].to_numpy(float)
    print(f"  POD modes {mon.pod.n_modes_}, max leverage {mon.pod.max_leverage}; T_amb read "
          f"{amb[0]:.2f} -> {amb[n_train - 1]:.2f} (train) -> {amb[-1]:.2f} (test end)")
    for j, c in enumerate(names):
        print(f"  {c:14s} leverage {lev[j]:.3f} forward spread {fwd[j]:.3f}")
    for j, c in enumerate(names):
        print(f"  {c:14s} spread {spread[j]:.3f} floor {mon.floor_c[j]:.3f} warning "
              f"{mon.warning_c[j]:.3f} range [{mon.lo_c[j]:.2f}, {mon.hi_c[j]:.2f}] max step "
              f"{mon.max_step_c[j]:.2f}")
    for e in events:
        print(f"  event row {e['row']} (data row {e['row'] + 1}) t {e['time']:g} {e['sensor']} "
              f"{e['from']} -> {e['to']}: {e['reason']}")


def count(root: str, seeds: str, hours: str = "4,12", variant: str = "main") -> None:
    """Exclusions on the healthy records of SEEDS at each length (module docstring)."""
    for h in (float(v) for v in hours.split(",")):
        total = records = 0
        for seed in seed_list(seeds):
            rows, _ = _record(root, seed, h)
            n_train = _split(rows)
            _, names, events = _stream(rows, n_train, variant=variant)
            out = [e for e in events if e["to"] == "excluded"]
            said = "; ".join(f"row {e['row']} {'test' if e['row'] >= n_train else 'train'} "
                             f"{e['sensor']} {e['reason'][:70]}" for e in out)
            print(f"seed {seed} {h:g} h: {len(rows)} rows, train {n_train}: {len(out)} "
                  f"exclusions{': ' + said if said else ''}")
            total += len(out)
            records += bool(out)
        print(f"{h:g} h: {records} records of {len(seed_list(seeds))} with an exclusion, {total} "
              "exclusions")


def planted(root: str, seeds: str, hours: str = "4", rate: str = "0.05",
            variant: str = "widen") -> None:
    """A drift planted on each sensor from the first test row (RATE °C per sample): the rows
    until that sensor is excluded, main's monitor against VARIANT's (module docstring)."""
    for h in (float(v) for v in hours.split(",")):
        delays = {False: [], True: []}
        for seed in seed_list(seeds):
            rows, _ = _record(root, seed, h)
            n_train = _split(rows)
            names = [c for c in rows.columns if c.startswith("T_")]
            said = []
            for name in names:
                bad = rows.copy()
                ramp = float(rate) * np.maximum(np.arange(len(rows)) - n_train + 1, 0)
                bad[name] = bad[name] + ramp
                for widen in (False, True):
                    _, _, events = _stream(bad, n_train, variant=variant if widen else "main")
                    hit = [e["row"] - n_train for e in events
                           if e["to"] == "excluded" and e["sensor"] == name and e["row"] >= n_train]
                    delays[widen].append(hit[0] if hit else np.inf)
                said.append(f"{name[2:]} {delays[False][-1]:g}/{delays[True][-1]:g}")
            print(f"seed {seed} {h:g} h (rows to exclusion, main/{variant}): {', '.join(said)}")
        for widen, d in delays.items():
            d = np.asarray(d)
            print(f"{h:g} h {variant if widen else 'main'}: missed {int(np.isinf(d).sum())} of "
                  f"{len(d)}, median rows to exclusion {np.median(d[np.isfinite(d)]):g}, "
                  f"mean {np.mean(d[np.isfinite(d)]):.2f}")


def main(argv: list[str]) -> int:
    commands = {"trace": trace, "count": count, "planted": planted}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
