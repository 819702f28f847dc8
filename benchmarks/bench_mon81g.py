"""A sensor no other predicts, out for explaining the others: back once its leak stops growing (mon81g).

    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon81g.py run ROOT LABEL
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon81g.py fresh ROOT LABEL
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon81g.py table ROOT SHIPPED MON81 RULE

The instrument is ``bench_mon81.py``'s (imported, not copied): each record runs ``thermocomp
monitor`` (MLR, ``track=false plots=none``) on the tree on ``PYTHONPATH`` and appends a line to
``ROOT/<LABEL>.jsonl``; data are written once under ``ROOT/data`` (mon81's, copied from
``/tmp/m81/b/data``).

* ``run``: mon81's records the rule can change (a sensor no other predicts): jig 8011, 8091-8093
  and vtl 7846, 8094-8096 in the five kinds (healthy, frozen, jump, drift, dropout), range77's
  gantry 7781 / swiss 7778, 7790 and mon81's fresh gantry 8099-8100 (45 records).
* ``fresh``: new healthy draws never looked at (jig 8103-8105, vtl 8106-8108, gantry 8109-8110).
* ``table``: shipped, mon81's refused rule and this rule side by side, and the bar's verdict
  (the labels' lines are read from ``ROOT/<LABEL>.jsonl``; several labels joined by ``+``).

The rule (written and committed before it was scored)
-----------------------------------------------------
mon81's rule (``benchmarks/mon81_rule.patch``: a sensor no other predicts, out for anything but
a dropout, comes back only once its *leak* -- the judged sensors' leave-one-out errors with it in
minus without, as a share of their warning band, the largest over the re-admission window -- is
below ``READMIT``, half), plus: a sensor out *for explaining the others' errors* whose leak is
above half the band is still re-admitted once its leak has not grown since its first
re-admission check, at least a whole window (``window`` samples: the two windows share no
sample) later -- the leak now at most the leak then.  A drift's leak grows with the drift (the
tank's 0.62 -> 1.6 of the band in 1.5 h); a healthy sensor in a field hotter than training
hovers (7781's ``Gabelkopf`` 0.50-0.73 for 4.4 h).  The window is the monitor's own re-admission
window, not a span fitted to these records.  A sensor out of range or for a jump keeps mon81's
level test: a reading come back off by an offset hovers as well (vtl78's ``Getriebe``, 14.8 K).
The reason of such a re-admission says the leak and its first level.

The bar (written before scoring; REFUSED if any part fails)
-----------------------------------------------------------
1. Faults (jig 8011, 8091-8093, vtl 7846, 8094-8096: frozen, jump, drift, dropout): in every
   campaign no sensor excluded more times than with mon81's rule; every target's adaptive RMSE
   <= shipped's x 1.02.
2. Healthy (jig 8011, 8091-8093, vtl 7846, 8094-8096, range77's gantry 7781 and swiss 7778 /
   7790, gantry 8099-8100 and the fresh 8103-8110): every target's adaptive RMSE <= shipped's x
   1.02, and no event on a record where shipped has none.
3. Repairs: on every dropout and jump record, the faulty sensor re-admitted in every campaign
   where shipped re-admits it.
4. ``tests/apps`` monitor tests pass.
Not run: spindle (its ``T_motor2`` is predicted by its pair: the rule does not reach it) and
swiss 8101-8102 (mon81: no event); the exported monitor (``watch.py``) is not touched.

Scored (2026-12-04; shipped = 39d18de5's ``src`` (the same as mon81's 9e060125 there: its lines
``/tmp/m81/b/shipped.jsonl`` reused, the fresh records run anew), mon81's rule its
``/tmp/m81/b/rule.jsonl``, this rule = d4fea9fe's ``src`` from ``git archive``; MLR; ROOT
/tmp/m81g, data copied from /tmp/m81/b/data; 53 records): **REFUSED** (parts 1 and 2).
Exclusions x / re-admissions x of the sensor, adaptive RMSE (µm) shipped -> mon81 -> this rule
(fixed in brackets):

* Part 2 FAILED on range77's gantry 7781: ``Gabelkopf`` 4x / 4x -> 1x / 1x -> 1x / 1x, E_dY
  3.675 -> 4.271 -> 3.788 (+3.1 %), E_dZ 5.614 -> 6.514 -> 5.777 (+2.9 %) (0.291 / 0.588), E_dX
  0.355 -> 0.361 -> 0.354.  Out at 8.847 h, its leak 0.62 of ``Schlitten``'s band at its first
  check, back at 12.319 h (leak 0.60): held 3.5 h where shipped had it in for about an hour of
  them (back at 8.875, 9.125, 9.758 h, out for good from 9.822 to 12.319 h in every tree).  The
  field kept warming, and a healthy sensor's leak grows with it: not below its first level for
  3.5 h.  The rest of part 2 passed: no event where shipped has none and every RMSE equal on jig
  8011, 8091-8093, vtl 7846, 8094-8096, gantry 8099-8100, swiss 7778 / 7790 and the fresh jig
  8103-8105, vtl 8106-8108, gantry 8109-8110 (none of them with an event in either tree).
* Part 1 FAILED on jig 8011 ``drift``: ``Hydraulik Tank`` 3x / 2x -> 1x / 0x -> 2x / 1x (out at
  7.706 h in all), dX / dY / dZ 12.434 / 4.095 / 5.271 -> 12.353 / 4.041 / 5.251 -> 12.388 /
  4.063 / 5.259 (16.349 / 6.330 / 6.665): its leak at its first check 0.73, 0.64 at 7.886 h (the
  field's noise over a 10-sample window is larger than the drift's growth over it): back, out
  again 1.2 min later.  The rest of part 1 passed: jig 8091 1x / 0x as mon81 (15.383 / 7.825 /
  4.599, shipped 15.407 / 7.857 / 4.640), 8092 1x / 0x, 8093 equal; vtl 7846 ``Getriebe`` kept
  out as mon81 (dX / dZ 18.900 / 1.626 -> 17.971 / 1.498), vtl 8094 the same (13.949 / 1.134 ->
  13.311 / 1.058); vtl 8095 / 8096's drift not seen by any tree; every frozen, jump and dropout
  record as mon81 and shipped.
* Part 3 passed: every dropout (jig ``Mutter X``, vtl ``Support``) and jump (jig ``Ständer
  hinten oben``, vtl ``Ständer links oben``) re-admitted as shipped, RMSE equal.
* Part 4 passed (the rule's ``src``; the 16 files of tests/apps that name the monitor): 156
  passed, 1 xfail (mon77's frozen pair), and ``test_monitor_leak81.py``'s strict xfail (the nut
  back 8 K off after an out-of-range) XPASSed: the out-of-range exclusion keeps mon81's level
  test.  The shell monitor / export tests were not run (``watch.py`` untouched).

The src change is reverted; the rule is ``benchmarks/mon81g_rule.patch``; the xfail stays.
Left (proposed, not scored): the leak's growth *against the field's rise* rather than against its
own first level -- 7781's field kept warming and a healthy ``Gabelkopf``'s leak with it (the
shape :mod:`.excursion` tests for an out-of-band error: ``EXCURSION_GROWTH`` of its share of the
rise over ``EXCURSION_TAU_S``), and a comparison over a span longer than the 10-sample window (the
tank's noise beat its growth over one); 7781 and 8011 are now both found cases for it, and its
bar needs fresh seeds.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_mon81 as m81  # noqa: E402
from _cli import run_commands  # noqa: E402

TOL = 1.02


def run(root: str, label: str) -> None:
    """mon81's records the rule can change (docstring)."""
    m81.jig(root, label, "8011,8091-8093")
    m81.vtl(root, label, "7846,8094-8096")
    m81.gantry(root, label, "7781,8099-8100")
    m81.swiss(root, label, "7778,7790")


def fresh(root: str, label: str) -> None:
    """Fresh healthy draws (docstring)."""
    m81.jig(root, label, "8103-8105", "healthy")
    m81.vtl(root, label, "8106-8108", "healthy")
    m81.gantry(root, label, "8109-8110")


def _rows(root: str, labels: str) -> dict:
    out: dict = {}
    for label in labels.split("+"):
        out.update(m81._lines(Path(root) / f"{label}.jsonl"))
    return out


def table(root: str, shipped: str, mon81: str, rule: str) -> None:
    """The three trees' records side by side and the bar's verdict (docstring, parts 1-3)."""
    a, m, b = _rows(root, shipped), _rows(root, mon81), _rows(root, rule)
    fails: list[str] = []
    for key in sorted(set(a) & set(b)):
        ra, rb, rm = a[key], b[key], m.get(key)
        record, kind = key
        worse = [f"{t} {ra['rmse'][t][1]:.4g} -> {rb['rmse'][t][1]:.4g}" for t in ra["rmse"]
                 if rb["rmse"][t][1] > TOL * ra["rmse"][t][1] + 1e-12]
        if worse:
            fails.append(f"{key}: adaptive RMSE worse than shipped x {TOL}: {', '.join(worse)}")
        if kind == "healthy" and rb["events"] and not ra["events"]:
            fails.append(f"{key}: {rb['events']} events on a healthy record (shipped none)")
        for cid in ra["campaigns"]:
            sa, sb = ra["sensors"].get(cid, {}), rb["sensors"].get(cid, {})
            if kind != "healthy" and rm is not None:
                sm = rm["sensors"].get(cid, {})
                fails += [f"{key} {cid}: {s} excluded {sm.get(s, [0])[0]} (mon81) -> {n} times"
                          for s, (n, _, _) in sb.items() if n > sm.get(s, [0])[0]]
            sensor = ra["sensor"]
            if kind in ("dropout", "jump") and sa.get(sensor, [0, 0])[1] \
                    and not sb.get(sensor, [0, 0])[1]:
                fails.append(f"{key} {cid}: {sensor} no longer re-admitted")
        cells = "  ".join(
            f"{t} {ra['rmse'][t][0]:.3f}/{ra['rmse'][t][1]:.3f}"
            f"->{rm['rmse'][t][1] if rm else float('nan'):.3f}->{rb['rmse'][t][1]:.3f}"
            for t in ra["rmse"])
        print(f"{record:12s} {kind:8s} {cells}\n    shipped: {m81._cells(ra)}\n"
              f"    mon81:   {m81._cells(rm) if rm else '(not run)'}\n    rule:    {m81._cells(rb)}")
    print("BAR (parts 1-3):", "PASSED" if not fails else "FAILED\n  " + "\n  ".join(fails), flush=True)


def main(argv: list[str] | None = None) -> int:
    np.seterr(all="ignore")
    return run_commands(__doc__, {"run": run, "fresh": fresh, "table": table},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
