"""A sensor no other predicts, out for explaining the others: back while its leak hovers (mon82).

    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82.py run ROOT LABEL
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82.py fresh ROOT LABEL
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82.py table ROOT SHIPPED RULE

The instrument is ``bench_mon81.py``'s (imported, not copied): each record runs ``thermocomp
monitor`` (MLR, ``track=false plots=none``) on the tree on ``PYTHONPATH`` and appends a line to
``ROOT/<LABEL>.jsonl``; data are written once under ``ROOT/data`` (mon81's records copied from
``/tmp/m81g/data``, the fresh ones written by the first tree that runs them).

* ``run``: bench_mon81's groups: jig 8011, 8091-8093 and vtl 7846, 8094-8096 in the five kinds
  (healthy, frozen, jump, drift, dropout), spindle 8097-8098 (healthy, freeze, drift, jump),
  range77's gantry 7781 and mon81's 8099-8100, swiss 7778, 7790, 8101-8102 (59 records).
* ``fresh``: new draws from mon82's seeds, never looked at: jig 8191-8194 and vtl 8195-8196
  healthy and drifting, gantry 8197-8198 healthy (14 records: 8 healthy, 6 drifts).
* ``table``: the two labels side by side and the bar's verdict (several labels joined by ``+``).

Found (traced on shipped 7b8e171a, the leak of the sensor onto every judged sensor logged on each
row and at each re-admission check, /tmp/m82/trace*.py, not kept).  jig 8011 ``drift``: the
``Hydraulik Tank`` (+1 K/h from 4.17 h) is out at 7.71 h as explaining ``Bett rechts``; shipped
lets it back at 7.73 and 7.87 h (the others' bands pass with it in) and keeps it out from 7.91 h
on (they do not).  Its leak onto ``Bett rechts`` grew with the field's warming from 4.2 h to
6.3 h (0.1 -> 0.7 of the band while the field's RMS rise went 0.9 -> 3.0 K) and has been about
0.65-0.7 since, the field flat at 3.2 K: at the two checks its leak's share of the field's rise
was 0.81 / 1.10 of the slow memory's (``EXCURSION_TAU_S``).  gantry 7781: ``Gabelkopf`` (healthy)
out at 8.85 h as explaining ``Schlitten``; its leak grew 0.25 -> 0.6 from 6 h to 9 h while the
field *cooled* (RMS rise 7.5 -> 5.5 K), then hovered at 0.6-0.7 while the field warmed to 9.4 K;
at shipped's four re-admissions (8.87, 9.12, 9.76, 12.32 h) the share was 1.00 / 1.24 / 0.96 /
0.75 of the memory's.  So the lever's found cases do not sit where the notes put them: the tank
is, near its exclusion, a leak grown in proportion to the field's warming, and the healthy
sensor's leak grew as the field cooled.  The rule is the lever as the notes propose it (not bent
to the trace; the bar was set with the trace in hand, before scoring).

The rule (written and committed before it was scored)
-----------------------------------------------------
A sensor no other predicts, excluded for anything but a dropout, is re-admitted only where,
besides the test it passes now (shipped's), its *leak* lets it back
(:meth:`Readmission._leak_passes`).  The leak of ``u`` onto a sensor ``k`` judged in the trial
set with ``u`` and without it: ``k``'s leave-one-out error with ``u`` minus without, as a share
of ``k``'s warning band (mon81's).  It lets ``u`` back where, over the re-admission window, it is
below ``READMIT`` (half) on every sample and sensor (mon81's level test), or, for a sensor out for
explaining the others' errors, where it *hovers against the field's rise*: for every ``k``, the
window's mean leak over the field's rise now (the RMS of the other trial sensors' referenced
readings over the window) at most ``EXCURSION_GROWTH`` (1.5) x the leak of the slow memory
(:mod:`.excursion`'s field ``EXCURSION_TAU_S`` = 30 min ago on the average) over the memory's
rise -- the excursion rule's test, on the leak.  A healthy sensor whose leak grows with the
field's warming comes back; a drift, whose leak grows where the field does not, stays out.  A
sensor out of range or for a jump keeps the level test (an offset hovers too: vtl78's
``Getriebe`` back 14.8 K off; ``test_monitor_leak81``'s nut).  No constant is new.  The exported C
monitor (``watch.py`` / ``watch_c.py``) carries no drift rule (no "explaining" exclusion) and no
re-admission by leak: it lacks this rule as it lacks mon81's; not touched.

The bar (written before scoring; REFUSED if any part fails)
-----------------------------------------------------------
1. Healthy (every healthy record of ``run`` and ``fresh``: jig 8011, 8091-8093, 8191-8194, vtl
   7846, 8094-8096, 8195-8196, spindle 8097-8098, gantry 7781, 8099-8100, 8197-8198, swiss 7778,
   7790, 8101-8102): no exclusion event where shipped has none and no sensor excluded more times
   than shipped; every target's adaptive RMSE <= shipped's x 1.01; gantry 7781's ``Gabelkopf``
   not held stale: E_dY (and every target) no worse than shipped.
2. Faults (frozen, jump, drift, dropout of ``run``; the fresh drifts): the faulty sensor excluded
   no later than shipped in every campaign shipped excludes it; every target's adaptive RMSE <=
   shipped's x 1.02; on every dropout / jump / frozen record the faulty sensor re-admitted where
   shipped re-admits it.
3. Drift stays out once out: jig 8011's ``Hydraulik Tank`` and the drifting sensor on every
   fresh drift record (>= 4) where it is excluded: excluded once per campaign (no flap).
4. ``tests/apps`` monitor tests pass (the leak81 strict xfail turned into a test).

Scored (2026-12-04; shipped = 7b8e171a's ``src``, the rule = 45651fa6's, each from ``git archive``;
MLR; ROOT /tmp/m82, mon81's data copied from /tmp/m81g/data; 69 records a tree, the two trees
run side by side; shipped's 25 lines that mon81 also ran equal to its ``shipped.jsonl``):
**REFUSED** (part 3).  Exclusions x / re-admissions x of the sensor, adaptive RMSE (µm) shipped ->
rule (fixed in brackets).  Three records moved, all by the level test on a sensor out of range:

* vtl 7846 ``drift``: ``Getriebe`` (out of range at 20.85 h) 1x / 1x -> 1x / 0x, dX / dZ 18.900 /
  1.626 -> 17.971 / 1.498 (17.093 / 1.514); vtl 8094 1x / 1x -> 1x / 0x, 13.949 / 1.134 -> 13.311
  / 1.058 (14.796 / 1.219); fresh vtl 8196 2x / 1x -> 1x / 0x, 22.149 / 1.452 -> 22.158 / 1.450
  (19.590 / 1.625).  mon81's level rule did the same on the first two.
* Part 3 FAILED: the drift's growth branch changed nothing.  jig 8011 ``Hydraulik Tank`` 3x / 2x
  in both trees (12.434 / 4.095 / 5.271 both), and the fresh drifts flap as shipped: jig 8191
  3x / 2x, 8193 2x / 1x, 8194 3x / 2x (8192 1x / 0x, vtl 8195 never excluded); RMSE equal.  The
  rule's own figures at the tank's two re-admissions (traced on the rule's ``_leak_passes``,
  /tmp/m82/trace3.py, not kept): the leak 0.73 / 0.75 of the band (so the level test fails), its
  share of the field's rise 1.136 / 1.097 of the memory's (within 1.5: back); at ``Gabelkopf``'s
  four (8.87, 9.12, 9.76, 12.32 h): 1.11 / 1.22 / 0.94 / 0.92.  No growth factor separates them:
  one below 1.097 that keeps the tank out holds ``Gabelkopf`` at 8.87 and 9.12 h (the stale hold
  mon81 and mon81g paid for).
* Part 1 passed: every one of the 25 healthy records (jig 8011, 8091-8093, fresh 8191-8194; vtl
  7846, 8094-8096, fresh 8195-8196; spindle 8097-8098; gantry 7781, 8099-8100, fresh 8197-8198;
  swiss 7778, 7790, 8101-8102) the same events and RMSE as shipped; gantry 7781's ``Gabelkopf``
  4x / 4x as shipped, E_dY 3.675 / E_dZ 5.614 both (0.291 / 0.588 fixed).
* Part 2 passed: every fault excluded when shipped excludes it, every dropout / jump re-admitted
  as shipped, frozen ones kept out as shipped, RMSE equal except the three above.
* Part 4 (the rule's ``src``, the 10 ``tests/apps/test_monitor*`` / ``readmit`` files): 28 passed,
  1 xfail (mon77's frozen pair), and leak81's nut test passes (it was turned into a test).

The src change is reverted; the rule is ``benchmarks/mon82_rule.patch``; leak81's strict xfail
stays.  Left (not scored): the level test for a sensor out of range alone (the three vtl records
above, and leak81's nut) is a rule of its own, with its own bar; the tank's drift, seen from its
start (4.2 h), grew its leak with a warming field for two hours, so a test that tells it from a
healthy sensor needs a longer memory than ``EXCURSION_TAU_S`` (the leak against hours, not 30
min) or another evidence than the leak; 3 of 4 fresh jig drifts flap (8191, 8193, 8194): the
case is common on this machine.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_mon81 as m81  # noqa: E402
from _cli import run_commands  # noqa: E402

HEALTHY_TOL, FAULT_TOL = 1.01, 1.02
FLAP_FOUND = {"jig8011"}


def run(root: str, label: str) -> None:
    """bench_mon81's groups (docstring)."""
    m81.jig(root, label, "8011,8091-8093")
    m81.vtl(root, label, "7846,8094-8096")
    m81.spindle(root, label, "8097-8098")
    m81.gantry(root, label, "7781,8099-8100")
    m81.swiss(root, label, "7778,7790,8101-8102")


def fresh(root: str, label: str) -> None:
    """Fresh draws from mon82's seeds (docstring)."""
    m81.jig(root, label, "8191-8194", "healthy,drift")
    m81.vtl(root, label, "8195-8196", "healthy,drift")
    m81.gantry(root, label, "8197-8198")


def _rows(root: str, labels: str) -> dict:
    out: dict = {}
    for label in labels.split("+"):
        out.update(m81._lines(Path(root) / f"{label}.jsonl"))
    return out


def _fails(key: tuple, ra: dict, rb: dict) -> list[str]:
    """The bar's parts 1-3 on one record (shipped ``ra``, rule ``rb``)."""
    record, kind = key
    healthy = kind == "healthy"
    tol = 1.0 if record == "gantry7781" else HEALTHY_TOL if healthy else FAULT_TOL
    fails = [f"{key}: {t} adaptive {ra['rmse'][t][1]:.4g} -> {rb['rmse'][t][1]:.4g} (> x {tol})"
             for t in ra["rmse"] if rb["rmse"][t][1] > tol * ra["rmse"][t][1] + 1e-12]
    if healthy and rb["events"] and not ra["events"]:
        fails.append(f"{key}: {rb['events']} events on a healthy record (shipped none)")
    sensor = ra["sensor"]
    for cid in ra["campaigns"]:
        sa, sb = ra["sensors"].get(cid, {}), rb["sensors"].get(cid, {})
        if healthy:
            fails += [f"{key} {cid}: {s} excluded {sa.get(s, [0])[0]} -> {n} times"
                      for s, (n, _, _) in sb.items() if n > sa.get(s, [0])[0]]
        if sensor is None or sensor not in sa:
            continue
        oa, ob = sa[sensor], sb.get(sensor, [0, 0, None])
        if ob[2] is None or ob[2] > oa[2]:
            fails.append(f"{key} {cid}: {sensor} out later ({oa[2]} -> {ob[2]})")
        if kind in ("dropout", "jump", "frozen", "freeze") and oa[1] and not ob[1]:
            fails.append(f"{key} {cid}: {sensor} no longer re-admitted")
        if kind == "drift" and (record in FLAP_FOUND or record[-4:] >= "8191") and ob[0] > 1:
            fails.append(f"{key} {cid}: {sensor} flaps ({ob[0]} exclusions)")
    return fails


def table(root: str, shipped: str, rule: str) -> None:
    """Both labels' records side by side and the bar's verdict (docstring, parts 1-3)."""
    side_by_side(root, shipped, rule, _fails)


def side_by_side(root: str, shipped: str, rule: str, fails_of) -> None:
    """:func:`table` with a bar's own ``fails_of(key, shipped row, rule row)`` (mon82b's too)."""
    a, b = _rows(root, shipped), _rows(root, rule)
    fails: list[str] = []
    for key in sorted(set(a) & set(b)):
        ra, rb = a[key], b[key]
        fails += fails_of(key, ra, rb)
        cells = "  ".join(f"{t} {ra['rmse'][t][0]:.3f}/{ra['rmse'][t][1]:.3f}->{rb['rmse'][t][1]:.3f}"
                          for t in ra["rmse"])
        moved = "" if m81._cells(ra) == m81._cells(rb) and ra["rmse"] == rb["rmse"] else "  MOVED"
        print(f"{key[0]:12s} {key[1]:8s} {cells}{moved}\n    shipped: {m81._cells(ra)}\n"
              f"    rule:    {m81._cells(rb)}")
    print(f"{len(set(a) & set(b))} records in both; missing: {sorted(set(a) ^ set(b))}")
    print("BAR (parts 1-3):", "PASSED" if not fails else "FAILED\n  " + "\n  ".join(fails), flush=True)


def main(argv: list[str] | None = None) -> int:
    np.seterr(all="ignore")
    return run_commands(__doc__, {"run": run, "fresh": fresh, "table": table},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
