"""The served monitor bounding the drift of a sensor "no other predicts" by a ridge on the other
temperatures and the states (monb92, issue 34; mon91b's variant B, traced offline).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_audit89.py healthy ROOT RECORDS  # first: simulate, run, monitor, healthy
    python benchmarks/bench_mon91b.py rooms ROOT SEEDS       # or: bench_mon88's long records, healthy
    python benchmarks/bench_monb92.py draw ROOT SEEDS        # or: the bar's fresh records, healthy
    python benchmarks/bench_monb92.py served ROOT RECORDS    # the served stream, B's exclusion forced
    python benchmarks/bench_monb92.py fresh                  # the bar's seeds and their generators

``RECORDS``: bench_audit89's (``9316-9325``) or ``all`` (every record of ``ROOT`` with a monitor
report; bench_mon88's ``lr9196`` .. ``lr9200`` after ``rooms``).

``served``: for the costliest sensor the healthy monitor calls not observable (bench_audit89's
``_costliest`` among ``observable: false``), mon91b's variant B (:func:`bench_mon91b.trace_sensor`:
``StandardScaler`` + ``RidgeCV`` on the states low-passed at 900 / 3600 / 14400 s, the ambient and
every other temperature, each referenced to the test part's first row; band max(0.4 degC, 3 x the
99.5th percentile of its windowed CV residual), crossed where 2 windowed residuals in a row are
beyond it) gives the first crossing row of each test campaign, healthy and with bench_audit89's
``drift`` (+0.5 degC/h from the part's middle row).  B is causal (trailing filters and window, a
ridge fixed at training), so a served B crosses where the offline one does; the served ``monitor``
stage (the healthy run's model.pkl, the SERVED ``SensorMonitor`` of ``PYTHONPATH``'s tree) is then
run on the drifted copy with the sensor EXCLUDED from that row on (:func:`forced_out`: a hook on
``SensorMonitor.update``, the monitor stage streams row by row; kept out while the band stays
crossed: the drift only grows).  Nothing else is changed: once out, the served compensator does
what it does today for an excluded sensor no other predicts -- its fallback family (the model
refitted without it, ``monitor.fallbacks=unobservable``, :mod:`thermocomp.apps.deploy.fallback`)
gives the correction, else its last good reading is held.  Cases: ``truth``; ``drift`` (main:
the drift read); ``drift+B-out`` (the rule's exclusion, the fallback's correction);
``truth+B-out`` (the same exclusion on the HEALTHY copy at the drifted copy's crossing row: the
cost of a false alarm there); ``truth+B-false`` where B crosses on a healthy test part (any blind
sensor of the record: each such crossing a new event), those sensors forced out there.  RMSE
fixed / adaptive (mean over targets, um), the events naming the sensor, all events, the test
campaigns with an event naming it at or after the fault's time.  ``fl_thermal`` (no manifest,
its costliest sensor predicted): the healthy crossings only.  -> ``ROOT/servedb92.json``.

``draw``: :data:`FRESH`'s seeds (``9396-9405``) drawn healthy into ROOT (kept):
``simulate`` (the kind's generator, :func:`generator`) -> ``run model=mlr`` -> ``monitor``.

``fresh``: prints the bar's fresh records (:data:`FRESH`), nothing run.

What the served monitor does today (read on 2b918bfd, the brief's part 1):

* ``observable``: ``SensorMonitor._set_operator``: a sensor is observable in the active set where
  its leverage in the POD operator of that set is below ``pod.max_leverage``; one that is not has
  NaN error scale (never judged, no band: ``_scale``), ``_predictable`` (every sensor in) is the
  same test with all in.  Bands: ``from_training`` -> ``max(warning_c, spread_factor x
  spread)`` per sensor, spread the 99.5th percentile of the windowed leave-one-out POD error
  (a blind sensor has one too, never read: its error scale is NaN, so no band bounds its drift);
  ``_bands_of`` rescales a sensor's floor for the active set (mon86).
* An excluded sensor's input: its POD reconstruction where predictable, else ``_last_good``
  (its last referenced reading while in; ``_fast`` / ``_update``); but in the adaptive
  compensator a blind sensor the model reads has a FALLBACK family (``fallbacks_``, fitted at
  deploy build) whose correction replaces the model's while it is out (per row:
  ``AdaptiveCompensator._fallen_back``; ``run_rows`` takes a block only while every sensor is in).
  So B needs no estimate in place of ``_last_good`` where a fallback exists: only the exclusion.
  ``_last_good`` matters only under ``monitor.fallbacks=none`` or where no fallback fits.
* The monitor is fitted (``AdaptiveCompensator.from_training``) and streamed
  (``_inputs``: ``monitor.update(x[self._mon], t)``; ``_inputs_block``: ``update_block``) on the
  monitored temperatures alone: B needs the states (the row's other columns, which
  ``AdaptiveCompensator`` holds as ``x[self._other]``) and the time step (``_check_time``'s dt),
  its three low-pass filters per state in the snapshot (``_snapshot`` / ``_restore``: the
  warm-up lead-in, deploy88) and a key beside ``fallbacks_`` (an older pickle: none, as before).
* mon88 / mon89 keys travel as: the served rule in ``surveillance/*``; its numpy mirror in
  ``export/watch.py`` (``CodeMonitor``), its C in ``export/watch_c.py``, each with a
  compensator.json key defaulting to 0 for an older export (``cleared`` mon88, ``spike`` mon89,
  ``blind_range`` cmon89b, ...).  The C holds no fallback family today: a blind sensor out with a
  fallback is flagged ``NOT_IN_CODE`` and the pack cuts there.  A B-carrying export must do the
  same explicitly (the mirror flagging B's exclusion, or export refusing the key with a message):
  the C following behind as "not in the C yet".

Bar (written before any fresh score, this commit; the brief's, with the generator per seed fixed
here before any draw): fresh seeds 9396-9405 drawn ONLY from kinds that carry a blind sensor, the
brief's order long_record / column / swiss / yearround cycled (:data:`FRESH`: 9396 lr, 9397 column,
9398 swiss, 9399 yearround, 9400 lr, 9401 column, 9402 swiss, 9403 yearround, 9404 lr, 9405 column;
long records as bench_mon88's ``LONG`` with ``data.reference=none``, the others as bench_audit89's
``KINDS``), each healthy and with bench_audit89's +0.5 degC/h drift in its costliest blind sensor.
KEPT only if: the drift detected (an event naming the sensor after the fault's row) on >= 5 of 10
where main detects it on 0; no drifted row's served RMSE (fixed and adaptive) worse than main's;
healthy: no new event on any of the 10, nor on bench_mon88's seen healthy rows (9196-9205) nor
datasets/fl_thermal; served RMSE on every healthy row identical to main's; monitor / export /
replay tests + tests/test_readme.py pass; a check pack of a B-carrying export passes or the export
is refused with a clear message.
(After the bar and before the fresh draw the bench gained ``draw`` and the healthy crossings of
EVERY blind sensor in ``served``, and the detection count became "an event naming the sensor at
or after the fault's time in a test campaign": measurement, not the bar's numbers.)

Measured (2026-12-05, src = main 2b918bfd, the rule a bench prototype: no src change).  Seen
(bench_audit89 ``healthy`` reproduces audit89 to the digit, col9316 9.4267 ...; bench_mon88's
9196-9205 drawn healthy; fl): adaptive RMSE um, main -> B's exclusion (the fallback's correction)
-> mon91b's B estimate written into the data (its fixed figure):

| record | sensor | truth | drift (main) | drift+B-out | mon91b estimate | truth+B-out (false alarm) |
|---|---|---|---|---|---|---|
| col9316 | T_front3 | 9.427 | 12.974 | 11.145 | 11.144 | 9.616 (+2.0 %; estimate: +17 %) |
| col9322 | T_front3 | 8.546 | 13.302 | 10.444 | 10.482 | 8.654 (+1.3 %; estimate: +28 %) |
| swiss9317 | T_nc_spindle_motor | 1.640 | 1.892 | 1.872 | 1.872 | 1.640 |
| yr9324 | T_amb (1 of 8 parts) | 3.105 | 3.765 | 3.645 | 3.646 | 3.086 |
| lr9196 | T_table | 1.045 | 9.457 | 1.876 | 1.821 | 0.993 |
| lr9197 | T_table | 1.763 | 6.987 | 2.677 | 1.756 | 2.695 (+53 %) |
| lr9198 | T_spindle_front | 1.851 | 6.354 | 2.572 | 2.198 | 1.942 |
| lr9199 | T_table | 0.988 | 8.737 | 3.574 | 3.064 | 1.377 |
| lr9200 | T_spindle_front | 1.293 | 6.228 | 2.321 | 2.187 | 1.311 |

Not found: swiss9323, yr9318 (0 of 8), cr9201-9205 (the drift <= 1 degC in 3-4 h).  Healthy: no
crossing of any blind sensor on the 54 seen blind sensor-records (audit89's six 10, fl 3,
bench_mon88's 41): the served stream there is main's to the bit.  Once B's exclusion is in, the
fallback family gives the correction on every row after it (counted by a hook on
``AdaptiveCompensator._fallen_back``: col9316 219 rows, lr9196 281, fresh swiss9398 53; every
blind sensor of these records has one).  So the served rule needs NO
estimate in place of ``_last_good``: the exclusion alone hands the correction to the fallback
family, which takes back as much of the drift as the estimate on the column and swiss
(11.145 / 10.444 against 11.144 / 10.482) and costs a false alarm on the column +1-2 % where the
estimate costs +17 / +28 %; on long records the estimate is the better input (1.76-3.06 against
1.88-3.57 um).

Fresh 9396-9405 (drawn after the bar, e32ebd8e; scored once, nothing changed after; adaptive RMSE
um; the healthy column: the truth's RMSE with B's false exclusions forced):

| record | sensor | truth | drift (main) | drift+B-out | main finds | B finds (h after) | healthy: crossings |
|---|---|---|---|---|---|---|---|
| lr9396 | T_table | 0.545 | 4.197 | 4.197 | yes | yes, 6.7 (main first) | none |
| column9397 | T_front3 | 14.148 | 18.663 | 17.209 | no | yes, 13.7 | T_front3, T_amb: -> 13.923 |
| swiss9398 | T_nc_spindle_motor | 1.572 | 1.539 | 1.543 (+0.28 %) | no | yes, 11.1 | none |
| yr9399 | T_amb | 2.868 | 3.014 | - | no | no (0 of 8) | none |
| lr9400 | T_table | 1.652 | 5.282 | 4.978 | yes | yes, 5.9 | none |
| column9401 | T_front3 | 9.595 | 15.825 | 11.265 | no | yes, 11.8 | T_front3, T_amb: -> 11.557 (+20 %) |
| swiss9402 | T_nc_spindle_motor | 1.232 | 1.248 | 1.220 | no | yes, 6.8 | none |
| yr9403 | T_amb | 2.981 | 3.443 | - | no | no (0 of 8) | none |
| lr9404 | T_table | 0.629 | 10.414 | 7.126 | no | yes, 5.6 | T_col_front_top: -> 0.631 |
| column9405 | T_front3 | 9.182 | 13.533 | 10.947 | no | yes, 15.7 | none |

Against the bar: detected on 6 of the 8 records where main detects nothing (>= 5: met); a drifted
row worse than main's: swiss9398 1.5391 -> 1.5434 (+0.28 %: failed); healthy: new events on 3 of
10 (column9397, column9401, lr9404: failed), none on bench_mon88's seen rows nor fl (met).  The
healthy crossings lie where B's inputs leave their training range (at the crossing 24-44 % of
B's inputs beyond it on the column, against a median 5-8 % over the part; lr9404 63 %) and on
the column's ``T_amb`` B predicts worse than its mean (CV R2 -0.67 / -1.25, band 12-14 degC,
the healthy part's windowed residual reaching 14-26 degC).  Fixed RMSE is main's in every row
(the fixed compensator reads no monitor).

After the score (all 20 records now seen; nothing re-scored, no bar moved): no simple guard
separates the healthy crossings from the found drifts.  A CV R2 > 0 floor drops the column's two
``T_amb`` crossings but not ``T_front3`` (CV R2 0.52 / 0.72: the healthy part's windowed residual
7.53 / 5.92 against bands 7.45 / 5.78, a 1-2 % margin) nor lr9404 ``T_col_front_top`` (CV R2 0.99,
band 0.49 degC); withholding judgement while B's inputs leave the training range would drop them
and also every long-record find (at the find 79-84 % of the inputs beyond it on lr9196 / 9198 /
9199 / 9200 / 9396; false crossings 23-63 %).

Verdict: TRACED -- the rule, prototyped in the served stream (B's exclusion at its causal
crossing, the fallback family taking over), FAILS its bar on the fresh seeds (3 of 10 healthy
records gain events, one drifted row +0.28 %); no src change, fresh 9396-9405 spent on this
score.  CPU: ``served`` 15-29 s a set (4-5 monitor stages a record), ``draw`` 17 s for the ten.
"""

from __future__ import annotations

import json
import os
import shutil
import sys
from pathlib import Path

import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands, seed_list  # noqa: E402
from bench_audit89 import KINDS, QUIET, _costliest, _mean_rmse, _named, _traced  # noqa: E402
from bench_deploy87 import stage  # noqa: E402
from bench_mon88 import LONG  # noqa: E402
from bench_mon91b import (  # noqa: E402
    _copy_fed,
    campaigns,
    drawn_run_monitored,
    first_crossing,
    labels_of,
    trace_sensor,
    windowed,
)

CYCLE = ("lr", "column", "swiss", "yearround")   # the brief's kinds with a blind sensor, its order
FRESH = {seed: CYCLE[k % len(CYCLE)] for k, seed in enumerate(range(9396, 9406))}


def generator(kind: str) -> tuple:
    """``thermocomp simulate`` overrides of ``kind`` (and the run's data overrides)."""
    return (LONG, ("data.reference=none",)) if kind == "lr" else (KINDS[kind], ())


def fresh(seeds: dict | None = None) -> None:
    """The bar's fresh records (``seeds``, {seed: kind}; None: :data:`FRESH`): seed, kind,
    simulate overrides (nothing run)."""
    for seed, kind in (seeds or FRESH).items():
        sim, extra = generator(kind)
        print(f"{seed} {kind:<10} {' '.join(sim)} {' '.join(extra)}".rstrip(), flush=True)


class forced_out:
    """In the ``with`` block the served ``SensorMonitor`` excludes each sensor of ``plan``
    (``{sensor: [time or None per campaign streamed]}``) at its first sample at or after its time
    in the k-th campaign it streams, and keeps it out (the reason names this bench).  A hook on
    ``update`` alone: the monitor stage streams row by row, and ``update_block`` takes rows only
    while every sensor is in."""

    REASON = "drift beyond the band of its ridge on the others and the states (monb92 prototype)"

    def __init__(self, plan: dict):
        self.plan, self.k, self.fresh = plan, -1, False

    def __enter__(self):
        from thermocomp.apps.deploy.surveillance.monitor import SensorMonitor

        self.cls, self.saved = SensorMonitor, (SensorMonitor.update, SensorMonitor.reset)
        update, reset, hook = *self.saved, self

        def hooked_reset(mon):
            hook.fresh = True
            return reset(mon)

        def hooked_update(mon, reading, time=float("nan")):
            if hook.fresh:              # the first sample of a campaign streamed
                hook.k, hook.fresh = hook.k + 1, False
            clean, events = update(mon, reading, time)
            for sensor, times in hook.plan.items():
                j = mon.names.index(sensor)
                at = times[hook.k] if hook.k < len(times) else None
                if at is not None and time >= at and mon._active[j]:
                    mon._exclude(j, hook.REASON, time, events, by_field=True)
            return clean, events

        SensorMonitor.update, SensorMonitor.reset = hooked_update, hooked_reset
        return self

    def __exit__(self, *exc):
        self.cls.update, self.cls.reset = self.saved
        return False


def _monitored(folder: Path, label: str, name: str, sensor: str, columns: list, plan=None,
               faults: dict | None = None, extra: tuple = ()):
    """``monitor`` (the healthy run's model) on a copy of ``label`` whose test files read
    ``columns`` as ``sensor``, the sensors of ``plan`` forced out (:class:`forced_out`; None:
    nothing forced); ``faults``: ``{campaign: the fault's time}`` (the events naming the sensor
    from then on are counted ``after``: a detection); ``extra``: more overrides (bench_monb93);
    ``served``: the report's targets and events (a stream compared to the bit)."""
    out = folder / "reports" / label
    copy = _copy_fed(folder, label, name, sensor, columns)
    args = ("monitor", f"data.path={copy}", f"out={out / ('monb92-' + name)}", *QUIET,
            *_overrides(label), f"monitor.model={out / 'run' / 'model.pkl'}", *extra)
    if plan is None:
        rc, said = stage(*args)
    else:
        with forced_out(plan):
            rc, said = stage(*args)
    shutil.rmtree(copy)
    if rc:
        return {"note": f"monitor exit {rc}: {said[:200]}"}
    got = json.loads((out / f"monb92-{name}" / "monitor.json").read_text())
    named = [e for e in got["events"] if sensor in _named(e)]
    return {"rmse_fixed": _mean_rmse(got, "rmse_fixed"), "rmse_adaptive": _mean_rmse(got, "rmse_adaptive"),
            "events": len(named), "first_event": _traced(named[0]) if named else "",
            "all_events": len(got["events"]), "served": {"targets": got["targets"],
                                                         "events": got["events"]},
            "after": {c: sum(e.get("campaign") == c and e["time"] >= t for e in named)
                      for c, t in (faults or {}).items()}}


def _overrides(label: str) -> tuple:
    """The data overrides a record ``label`` is run with: a long record's (bench_mon88's)."""
    return ("data.reference=none",) if label.startswith("lr") else ()


def _healthy_times(frame, first: int, part: dict) -> float | None:
    """The time B's band is first crossed on the HEALTHY test part (None: never)."""
    residual = (part["truth"] - part["estimate"])[first:]
    hit = first_crossing(windowed(residual), part["band"])
    return None if hit is None else float(frame["time"].iloc[first + hit])


def _b_parts(train, test, sensor: str) -> tuple[list[dict], dict]:
    """B's trace of ``sensor`` (mon91b's ``trace_sensor``), each part given its truth and band."""
    row = trace_sensor(train, test, sensor, "B")
    for (frame, _), p in zip(test, row["parts"]):
        p["truth"], p["band"] = frame[sensor].to_numpy(float), row["band_rule"]
    return row["parts"], row


def served(root: str, records: str) -> None:
    """The served stream with B's exclusion forced at its offline crossing (module doc) ->
    ROOT/servedb92.json."""
    folder = Path(root).resolve()
    os.environ["THERMOCOMP_ROOT"] = str(folder)
    rows = []
    print(f"{'record':<14}{'sensor':<20}{'case':<14}{'fixed':>9}{'adaptive':>9}{'events':>7}{'all':>5}"
          f"{'after':>8}"
          " B's crossing (h after the fault) / the first event naming the sensor", flush=True)
    for label in labels_of(folder, records):
        mon = json.loads((folder / "reports" / label / "monitor" / "monitor.json").read_text())
        train, test = campaigns(folder, label)
        blind = [s for s, v in mon["sensors"].items() if not v["observable"]]
        # healthy: B's crossings of every blind sensor on the true readings (a new event each)
        false = {}
        for s in blind:
            parts, _ = _b_parts(train, test, s)
            times = [_healthy_times(f, first, p) for (f, first), p in zip(test, parts)]
            if any(t is not None for t in times):
                false[s] = times
        sensor = _costliest(mon)
        if label == "fl_thermal" or mon["sensors"][sensor]["observable"] or not blind:
            # fl's costliest sensor is predicted (and its record no manifest): healthy only
            rows.append({"record": label, "blind": blind, "false": false})
            print(f"{label:<14}blind {len(blind)}: healthy crossings {sorted(false) or 'none'}",
                  flush=True)
            continue
        parts, _ = _b_parts(train, test, sensor)
        times = [None if p["row_rule"] is None else float(f["time"].iloc[p["row_rule"]])
                 for (f, _), p in zip(test, parts)]
        manifest = pd.read_csv(folder / "data" / label / "campaigns.csv")
        tests = list(manifest.loc[manifest["split"] == "test", "campaign"])
        faults = {c: float(f["time"].iloc[p["mid"]]) for c, (f, _), p in zip(tests, test, parts)}
        truth = [p["truth"] for p in parts]
        drifted = [p["drifted"] for p in parts]
        said = ", ".join("-" if d is None else f"{d:.1f}" for d in (p["delay_rule"] for p in parts))
        cases = [("truth", truth, None), ("drift", drifted, None)]
        if any(t is not None for t in times):
            cases += [("drift+B-out", drifted, {sensor: times}), ("truth+B-out", truth, {sensor: times})]
        if false:
            cases.append(("truth+B-false", truth, false))
        for name, columns, plan in cases:
            r = {"record": label, "sensor": sensor, "case": name, "crossing_h": said, "blind": blind,
                 "false": {s: t for s, t in false.items()}, "plan": plan,
                 **_monitored(folder, label, name.replace("+", "_"), sensor, columns, plan, faults)}
            rows.append(r)
            if "note" in r:
                print(f"{label:<14}{sensor:<20}{name:<14}{r['note']}", flush=True)
                continue
            print(f"{label:<14}{sensor:<20}{name:<14}{r['rmse_fixed']:>9.4f}{r['rmse_adaptive']:>9.4f}"
                  f"{r['events']:>7}{r['all_events']:>5}{sum(v > 0 for v in r['after'].values()):>4}/"
                  f"{len(r['after']):<3}{said if name.startswith('drift') else ''} "
                  f"{r['first_event'][:60]}", flush=True)
        print(f"{label:<14}blind {len(blind)}: healthy crossings {sorted(false) or 'none'}", flush=True)
    (folder / "servedb92.json").write_text(json.dumps(rows, indent=1))


def draw(root: str, seeds: str, kinds: dict | None = None) -> None:
    """The bar's fresh records (``kinds``, {seed: kind}; None: :data:`FRESH`; ``seeds`` of it)
    drawn healthy into ROOT (kept): ``simulate`` -> ``run model=mlr`` -> ``monitor``, each
    with its kind's overrides."""
    from bench_mon88 import _root

    folder, kinds = _root(root), kinds or FRESH
    for seed in seed_list(seeds):
        sim, extra = generator(kinds[seed])
        drawn_run_monitored(folder, f"{kinds[seed]}{seed}", seed, sim, extra)

def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"draw": lambda root, seeds: draw(root, seeds), "served": served,
                                  "fresh": lambda: fresh()},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
