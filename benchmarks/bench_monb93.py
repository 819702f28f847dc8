"""The blind-sensor drift rule built in the served monitor (monb93, issue 34): monb92b's prototype
(``grow6``) with its two seen false crossings fixed, in ``AdaptiveCompensator``.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_monb93.py horizons ROOT ...        # the choice, offline, seen records
    python benchmarks/bench_monb93.py draw ROOT SEEDS          # the bar's fresh records, healthy
    python benchmarks/bench_monb93.py served ROOT MODE         # the served monitor, healthy + drifted
    python benchmarks/bench_monb93.py score ROOT               # the bar, rule against main
    python benchmarks/bench_monb93.py fresh                    # the bar's seeds and their generators

``ROOT``: a folder of records drawn and monitored healthy as bench_monb92's (``data/<label>``,
``reports/<label>/{run,monitor}``); bench_monb92b's seen roots (bench_audit89 ``healthy``
9316-9318 / 9322-9324, bench_mon91b ``rooms`` 9196-9205, bench_monb92 ``draw`` 9396-9405, fl).

``horizons``: for every blind sensor (``observable: false`` in the healthy monitor) of every
record, offline as bench_monb92b ``seen`` (mon91b's ridge B, its band, bench_audit89's +0.5 degC/h
drift from the test part's middle row), the ridge's CV R2 and, per growth spacing (``grow6``'s
fixed 10 samples; a share of the sensor's own e-folding time in training), the healthy parts
crossed and the drifted parts found.  CPU ~40 s over the seen roots.

``served``: the ``monitor`` stage (the healthy run's model.pkl, ``PYTHONPATH``'s tree) on copies
of each record whose costliest blind sensor reads the truth and the drift (bench_monb92's
``_monitored``): ``MODE`` = ``rule`` (the tree's defaults: a tree with ``monb93_rule.patch``
applied, ``git apply benchmarks/monb93_rule.patch``; the rule was REFUSED, main has no key),
``off`` (``monitor.blind_drift=false``, the patched tree) or ``main`` (no override: run it with
``PYTHONPATH`` on main's tree) -> ROOT/servedb93-MODE.json.  fl_thermal (no manifest) is not
streamed by ``served``: its healthy check is ``thermocomp monitor data=fl_thermal model=mlr`` on
both trees, the two monitor.json compared.
``score``: rule against main: per drifted record the served RMSE (fixed, adaptive) and whether
an event names the sensor at or after the fault's time in a test campaign; per healthy copy
whether the served report (every target's figures and every event) is main's to the bit; the
events the rule adds (its reason starts ``blind drift``).

The rule (src/thermocomp/apps/deploy/blind_drift.py, ``monitor.blind_drift``, default true): for
each sensor with a fallback family (those the POD cannot predict, :mod:`.fallback`), a ridge
(``StandardScaler`` + ``RidgeCV``) of its change since the campaign's first row on the same
change of the other temperatures THE MODEL READS and of every state's (and the ambient's)
low-pass response at 900 / 3600 / 14400 s (bench_mon91b's variant B, from the model's inputs: the
served stream has no other columns); band max(0.4 degC, 3 x the 99.5th percentile of its windowed
CV residual, campaigns out where >= 3, else 5 blocks); a crossing is 2 windowed residuals beyond
the band AND 6 growths in a row in its direction read every ``spacing`` samples back.  Changed
from monb92b, on the seen records only: (a) no rule for a sensor whose ridge's CV R2 <= 0
(column9397 / 9401 ``T_amb``, -0.67 / -1.25: a model that predicts nothing does not judge);
(b) ``spacing`` = max(10, a third of the sensor's e-folding time in training: the lag where the
autocorrelation of its reading falls below 1/e), so the 6 growths span twice the time the sensor
itself takes to decorrelate (monb92b: 10 samples); found building it (served, seen records):
(c) the judged sensors are those with CV R2 > 0 on the temperatures the monitor's bands judge;
each judged sensor's ridge then reads every temperature but the judged ones (lr9396: with every
other temperature, ``T_table``'s drift took the healthy ``T_spindle_front`` out through its
ridge, 4.197 -> 4.548 um; with the bands' temperatures alone the column's ``T_front3`` lost its
``T_amb`` and crossed healthy on col9316 / col9322); (d) judged only while the monitor's field is
quiet (every sensor in and ok, no new thermal state): col9322's healthy ``T_front3`` under its
test's new source Q3 still crossed (8.555 -> 16.588 um adaptive, the fallback from 85700 s on),
at any spacing up to the e-folding time itself; a sensor out is a faulty input of every ridge.
The exclusion is held to the campaign's end (``SensorMonitor.exclude_pinned``: no re-admission;
the drift only grows) and its fallback corrects; a sensor without a fallback is not judged.
Served only: the C does not hold it, ``provenance.not_in_code`` names it.

Choice (part 1; ``horizons`` on the seen roots, before any fresh draw; healthy parts crossed /
costliest drifted records found, of 86 blind sensor-records, 26 drifted):

| spacing | healthy crossings | costliest found |
|---|---|---|
| 10 (monb92b grow6) | 2 (column9397 T_amb, column9401 T_front3) | 17 of 26 |
| e-folding / 6, R2 > 0 | 1 (column9401 T_front3) | 17 of 26 |
| e-folding / 4, R2 > 0 | 1 (column9397 T_front3) | 15 of 26 |
| e-folding / 3, R2 > 0 (CHOSEN) | 0 | 14 of 26 (lr9196, lr9197, lr9400 T_table lost) |
| e-folding / 2, R2 > 0 | 0 | 12 of 26 |

(``fixed10`` applies no R2 floor; with it, column9397 ``T_amb`` (R2 -0.67) goes and column9401
``T_front3`` stays.)  Fixed growth spacings (20 / 30 / 45 / 60 / 90 samples) were tried too:
column9397 ``T_front3`` is crossed at 30 and 60 and not at 20 / 45 / 90 (no monotone trade);
the share of the sensor's own time scale is the one that leaves no seen false crossing while
keeping most finds (part1c / horizons: the fixed spacings were tried in a scratch script).

BAR (written here before any fresh score; monb92b's unchanged, on the BUILT code): fresh seeds
9536-9545 drawn only from kinds that carry a blind sensor, lr / column / swiss / yearround cycled
(:data:`FRESH`), each healthy and with bench_audit89's +0.5 degC/h drift in its costliest blind
sensor.  KEPT only if: the drift detected (an event naming the sensor at or after the fault's time
in a test campaign) on >= 5 of 10 where main detects it on 0 (of those where main detects none,
if fewer than 10); no drifted row's served RMSE (fixed and adaptive) worse than main's; healthy:
no new event on any of the 10, the served stream (every target's figures, every event) identical
to main's on every healthy record where the rule never fires; fl_thermal's healthy record quiet
(no rule event); the monitor / export tests this change touches pass.

Measured (2026-12-05; base 5fe17063, the rule as in :data:`PATCH`, committed (de74b50a) before
the fresh draw was scored; fresh drawn by ``draw`` CPU 26 s, ``served`` rule + main ~60 s CPU).
Fresh 9536-9545, scored ONCE, nothing changed after; served RMSE um (mean over targets; fixed is
main's in every row: the fixed compensator reads no monitor), main -> rule:

| record | sensor | healthy adaptive (main = rule) | drift adaptive main -> rule | main finds | rule at (s) |
|---|---|---|---|---|---|
| column9537 | T_front3 | 9.1570 | 17.3394 -> 16.8764 | no | yes, 141300 |
| column9541 | T_front3 | 8.3753 | 13.6385 -> 11.6279 | no | yes, 124700 |
| column9545 | T_front3 | 11.4785 | 14.4134 -> 13.8647 | no | yes, 134300 |
| lr9536 | T_table | 1.1130 | 7.7465 -> 3.4580 | no | yes, 32760 |
| lr9540 | T_table | 2.2696 | 4.9967 -> 5.3020 (+6.1 %) | yes | yes, 31620 |
| lr9544 | T_spindle_front | 2.1605 | 5.9190 -> 4.2226 | no | yes, 47400 |
| swiss9538 | T_guidebush (observable: no drift case) | 1.4558 | - | - | - |
| swiss9542 | T_nc_spindle_motor | 1.2947 | 1.3916 -> 1.3916 | no | no |
| yr9539 | T_amb | 2.4968 | 2.6331 -> 2.6331 | no | no |
| yr9543 | T_amb | 2.4055 | 2.6703 -> 2.6703 | no | no |

Against the bar: drift found on 5 of the 8 drifted records where main finds none (>= 5: met);
a drifted row worse than main's: lr9540 adaptive 4.9967 -> 5.3020 (+6.1 %: FAILED; main finds
that drift too, later, and its own handling beats the fallback from 31620 s on); healthy: no
rule event on any of the 10, the served report (every target's figures and every event)
main's to the bit on all 10 (met); fl_thermal healthy (``monitor data=fl_thermal model=mlr``):
no event, targets and events main's to the bit (met); tests with the rule: its own
tests/apps/test_blind_drift93.py (2, fail on 5fe17063: no module), test_monitor_blame44.py (the
culprit rule kept under ``blind_drift=false``; the default takes T_table out first by the rule,
fails on 5fe17063), the 16 tests/apps/test_monitor* + 2 fallback files + its own 55 passed / 4
xfailed (blame44 once changed), the 12 tests/shell/test_monitor* + test_benchmarks_cli 621
passed / 2 xfailed, 8 C export files (not_in_code, watch, fallbacks, guard) 59 passed (met).

The seen records through the built rule (``served`` rule vs main; chosen on these, not a score):
9396-9405 found 3 of 8 where main finds none (col9397 18.663 -> 17.238, col9401 15.825 ->
14.837, col9405 13.533 -> 10.600; lr9400, which main finds, 5.282 -> 4.998), no healthy event,
every healthy stream main's; audit89's six: col9316 12.974 -> 12.769, col9322 13.302 -> 12.006
(found), swiss / yearround not; no healthy event; bench_mon88's ten: lr9197 6.987 -> 2.642,
lr9199 8.737 -> 6.458 found, no healthy event (the cr rooms' drifts stay < 1 degC).  Fewer
finds than monb92b's prototype on the same records (17 of 26 offline): the quiet-field veto
delays or drops finds where the monitor is warning (lr9404, 9396-9405), and the ridge reads only
the model's inputs (the swiss MLR reads no state: swiss9398's spindle motor, band 13.8 degC, CV R2
0.90, against mon91b's prototype with the states on swiss9317, 5.36 degC, R2 1.00).

Verdict: REFUSED on its bar (one drifted row worse than main: lr9540 +6.1 %, where main's own
drift rule finds the drift); src, conf, tests and docs as main; the rule (blind_drift.py, the
compensator's wiring, ``SensorMonitor.exclude_pinned``, the C's ``not_in_code`` entry, the key,
its tests and docs/cli.md row, bench_mon91b reading the src's CV residual) in :data:`PATCH`.
Fresh 9536-9545 spent on this score.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_audit89 import faulted  # noqa: E402
from bench_mon91b import (  # noqa: E402
    BLOCKS,
    WINDOW,
    _fit,
    campaigns,
    cv_residual,
    features,
    labels_of,
    target,
    windowed,
)
from bench_monb92 import CYCLE, _monitored  # noqa: E402
from bench_monb92 import draw as draw_kinds  # noqa: E402
from bench_monb92 import fresh as print_kinds  # noqa: E402
from bench_monb92b import _blind, band_of, blind_sensor_records, crossing  # noqa: E402

FRESH = {seed: CYCLE[k % len(CYCLE)] for k, seed in enumerate(range(9536, 9546))}
GROWTHS = 6
SHARES = (None, 6, 4, 3, 2)      # None: monb92b's fixed 10-sample spacing
MODES = {"rule": (), "off": ("monitor.blind_drift=false",), "main": ()}
RULE_REASON = "blind drift"
PATCH = HERE / "monb93_rule.patch"     # the rule (refused): src, conf, its tests, docs/cli.md


def _efolding(x: np.ndarray) -> int:
    """Lag (samples) where the autocorrelation of ``x`` first falls below 1/e (as the rule's
    ``blind_drift._efolding`` in :data:`PATCH`)."""
    x = x - x.mean()
    v = float(x @ x)
    for lag in range(1, len(x)):
        if float(x[lag:] @ x[:-lag]) < v / np.e:
            return lag
    return len(x)


def horizons(*roots: str) -> None:
    """Each spacing's healthy crossings and finds on every blind sensor of each ROOT."""
    tally = {s: [0, set(), 0, 0] for s in SHARES}     # false parts, false records, found, drifted
    print(f"{'record':<15}{'sensor':<21}{'R2':>6}{'e-fold':>7}" + "".join(
        f"{'/' + str(s) if s else 'fixed10':>9}" for s in SHARES) + "  (false/found)", flush=True)
    for label, s, costliest, train, test in blind_sensor_records(roots):
        F = [features(f, s, variant="B") for f in train]
        Y = [target(f, s) for f in train]
        r, y = cv_residual(F, Y, BLOCKS), np.concatenate(Y)
        r2 = 1 - float(r @ r) / float(((y - y.mean()) ** 2).sum())
        tau = max(_efolding(f[s].to_numpy(float)) for f in train)
        model, band = _fit(np.vstack(F), y), band_of(F, Y, BLOCKS)
        drifted = s == costliest and label != "fl_thermal"
        cells = []
        for share in SHARES:
            spacing = WINDOW if share is None else max(WINDOW, int(np.ceil(tau / share)))
            false = found = 0
            if share is None or r2 > 0:
                for frame, first in test:
                    fit = model.predict(features(frame, s, first, "B"))
                    t, x = frame["time"].to_numpy(float), frame[s].to_numpy(float)
                    xd, mid = faulted(x, t, first, "drift")
                    wt = windowed(target(frame, s, first) - fit)
                    wd = windowed(xd[first:] - xd[first] - fit)
                    false += crossing(wt, band, GROWTHS, 0, spacing) is not None
                    found += crossing(wd, band, GROWTHS, mid - first, spacing) is not None
            tally[share][0] += false
            if false:
                tally[share][1].add(f"{label} {s}")
            if drifted:
                tally[share][3] += 1
                tally[share][2] += found > 0
            cells.append(f"{false}/{found}")
        print(f"{label:<15}{s[:20]:<21}{r2:>6.2f}{tau:>7}" + "".join(f"{c:>9}" for c in cells)
              + ("  *" if drifted else ""), flush=True)
    for share, (false, where, found, drifted) in tally.items():
        print(f"{'fixed 10' if share is None else 'e-fold/' + str(share):<10} healthy crossings "
              f"{false} {sorted(where)}; costliest found {found} of {drifted}", flush=True)


def served(root: str, mode: str) -> None:
    """The served monitor on the truth and the drift of each record's costliest blind sensor
    (module doc) -> ROOT/servedb93-MODE.json."""
    folder = Path(root).resolve()
    os.environ["THERMOCOMP_ROOT"] = str(folder)
    rows = []
    for label in labels_of(folder, "all"):
        blind, sensor = _blind(folder, label)
        train, test = campaigns(folder, label)
        if label == "fl_thermal":
            sensor = blind[0] if blind else sensor
            parts = [(frame[sensor].to_numpy(float), None, None) for frame, _ in test]
        else:
            parts = []
            for frame, first in test:
                t, x = frame["time"].to_numpy(float), frame[sensor].to_numpy(float)
                xd, mid = faulted(x, t, first, "drift")
                parts.append((x, xd, float(t[mid])))
        cases = [("truth", [p[0] for p in parts])]
        faults = None
        if label != "fl_thermal" and sensor in blind:
            manifest = pd.read_csv(folder / "data" / label / "campaigns.csv")
            tests = list(manifest.loc[manifest["split"] == "test", "campaign"])
            faults = {c: p[2] for c, p in zip(tests, parts)}
            cases.append(("drift", [p[1] for p in parts]))
        for case, columns in cases:
            r = {"record": label, "sensor": sensor, "blind": blind, "case": case, "mode": mode,
                 **_monitored(folder, label, f"b93{mode}-{case}", sensor, columns, None,
                              faults if case == "drift" else None, MODES[mode])}
            rows.append(r)
            if "note" in r:
                print(f"{label:<14}{sensor:<20}{case:<7}{r['note']}", flush=True)
                continue
            rule = [e for e in r["served"]["events"] if str(e.get("reason", "")).startswith(RULE_REASON)]
            print(f"{label:<14}{sensor:<20}{case:<7}{r['rmse_fixed']:>9.4f}{r['rmse_adaptive']:>9.4f}"
                  f"{r['events']:>4}{r['all_events']:>5} found {sum(v > 0 for v in r['after'].values())}"
                  f"/{len(r['after'])} rule events {[(e['sensor'], e['time']) for e in rule]}",
                  flush=True)
    (folder / f"servedb93-{mode}.json").write_text(json.dumps(rows, indent=1))


def score(root: str) -> None:
    """The bar: ``served`` rule against main (module doc)."""
    folder = Path(root).resolve()
    got = {m: {(r["record"], r["case"]): r for r in json.loads(
        (folder / f"servedb93-{m}.json").read_text())} for m in ("rule", "main")}
    found_new = missed_by_main = worse = new_events = differ = 0
    print(f"{'record':<14}{'sensor':<20}{'case':<7}{'main fixed':>11}{'rule':>9}{'main adapt':>11}"
          f"{'rule':>9}  main finds / rule finds / rule events / served as main", flush=True)
    for key, r in got["rule"].items():
        m = got["main"][key]
        rule = [(e["sensor"], e["time"]) for e in r["served"]["events"]
                if str(e.get("reason", "")).startswith(RULE_REASON)]
        same = r["served"] == m["served"]
        main_finds = any(v > 0 for v in m["after"].values())
        rule_finds = any(v > 0 for v in r["after"].values())
        if key[1] == "drift":
            missed_by_main += not main_finds
            found_new += rule_finds and not main_finds
            worse += (r["rmse_fixed"] > m["rmse_fixed"]) or (r["rmse_adaptive"] > m["rmse_adaptive"])
        else:
            new_events += bool(rule)
            differ += not same
        print(f"{key[0]:<14}{r['sensor']:<20}{key[1]:<7}{m['rmse_fixed']:>11.4f}{r['rmse_fixed']:>9.4f}"
              f"{m['rmse_adaptive']:>11.4f}{r['rmse_adaptive']:>9.4f}  {main_finds} / {rule_finds} / "
              f"{rule} / {same}", flush=True)
    print(f"drift found by the rule where main finds none: {found_new} of {missed_by_main}; drifted "
          f"rows worse than main: {worse}; healthy records with a rule event: {new_events}; healthy "
          f"served streams not main's: {differ}", flush=True)


def main(argv: list[str] | None = None) -> int:
    commands = {"horizons": horizons, "served": served, "score": score,
                "fresh": lambda: print_kinds(FRESH),
                "draw": lambda root, seeds: draw_kinds(root, seeds, FRESH)}
    return run_commands(__doc__, commands, sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
