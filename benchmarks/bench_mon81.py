"""A drifting sensor no other predicts re-admitted and excluded again (mon81): the rule, its bar.

    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon81.py jig ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon81.py vtl ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon81.py spindle ROOT LABEL [SEEDS]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon81.py gantry ROOT LABEL [SEEDS]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon81.py swiss ROOT LABEL [SEEDS]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon81.py table ROOT SHIPPED RULE

The code measured is the tree on ``PYTHONPATH`` (``/work/main/src``: shipped; the branch: the
rule); each command runs ``thermocomp monitor`` (MLR, ``track=false plots=none``) in a child
process and appends a line per record to ``ROOT/<LABEL>.jsonl``: per campaign and sensor its
exclusions and re-admissions (count, first exclusion in h), the events, per target the RMSE
fixed / adaptive.  Data are written once under ``ROOT/data`` (the simulation does not depend on
the rule).

* ``jig``: stranger80's jig borer (``bench_stranger80.py write`` / ``faults``; ``init`` with no
  key once on the first seed's healthy folder, its data config read for every seed), kinds
  ``healthy,frozen,jump,drift,dropout`` (``Hydraulik Tank`` +1 K/h from 4.17 h: the found case is
  seed 8011).
* ``vtl``: stranger78's vertical turning lathe (``bench_stranger78.py``; ``Getriebe`` +1 K/h from
  8.33 h: the found case is seed 7846), the same kinds.
* ``spindle``: ``yearround_spindle`` healthy and ``T_motor2`` frozen / drifting 1 K/h / +3 °C
  (bench_mon77's records).
* ``gantry`` / ``swiss``: bench_range77's healthy gantry mill (``gantry76``) and
  ``swiss_lathe_door`` (40 h); 7781 / 7778, 7790 are range77's healthy records with drift
  exclusions (7781: ``Gabelkopf`` out four times as "explaining" ``Schlitten``).
* ``table``: the two labels' records side by side, and the bar's verdict.

Found (seed 8011, shipped 9e060125; traced with ``Readmission._pass_once_back`` wrapped, not
kept): ``Hydraulik Tank`` is excluded at 7.71 h by :meth:`Judgement._explaining` (with it out of
the fit ``Bett rechts``, -0.4 °C, is back within its band).  No other sensor predicts the tank,
so its re-admission is judged by the others' bands with it in (:meth:`_pass_once_back`,
``explains``): ``Bett rechts``'s worst error over the window 0.99 of its warning band at 7.74 h
(1.01-1.04 on the samples before): back in, out again 40 s later; again at 7.87 h (0.99), out at
7.91 h.  The band it left by is the band it came back by: no hysteresis, where a sensor judged by
its own error needs half its band (``READMIT``) for a window.  The tank's share of ``Bett
rechts``'s error (its error with the tank in the fit minus without) was 0.62-0.93 of the band
while it was out, and 1.3-1.6 by the end (3 K of drift).  vtl78's ``Getriebe`` goes out of
range (an instant detector) at 20.85 h and comes back at 23.13 h 14.8 K off: "no detector fired
for N samples", its reading judged by nothing.

The rule (written and committed before it was scored)
-----------------------------------------------------
A sensor no other predicts, excluded for anything but a dropout (its last detector not a missing
reading), is re-admitted only where, besides the test it passes now, its *leak* onto the judged
sensors is within their re-admission band over the whole window: for every sensor judged both in
the trial set and in the trial set without it, the difference of its leave-one-out error with the
sensor in and without, at most ``READMIT`` (half) of its warning band on every sample of the
window.  The leak is what the sensor's reading does to the field the others make: zero for a
reading consistent with them, the drift times its weight otherwise; a repaired sensor's leak is
its healthy one.  The hysteresis of a sensor judged by its own error (out at the warning band,
back within half of it), applied to the only evidence there is on a sensor no band judges: its
effect on the others.  A dropout's sensor is left as it is (it passed its judgement until its
reading went missing).  The reason of such a re-admission says the leak.  ``watch.py`` /
``watch_c.py`` (the exported monitor) have no drift rule and are not touched.

The bar (written before scoring; REFUSED if any part fails)
-----------------------------------------------------------
1. Drift: on jig 8011 and vtl 7846 ``drift`` and on the fresh drift records (jig 8091-8093, vtl
   8094-8096, spindle 8097-8098), the drifting sensor excluded at most once per campaign (no
   flapping) and no later than shipped; no sensor excluded more times than shipped; every
   target's adaptive RMSE <= shipped's x 1.02.
2. Healthy: every healthy record (jig 8011, 8091-8093; vtl 7846, 8094-8096; spindle 8097-8098;
   gantry 8099-8100; swiss 8101-8102: fresh seeds never tuned on) no event where shipped has
   none, adaptive RMSE equal to shipped's; range77's gantry 7781 and swiss 7778 / 7790 (drift
   exclusions on healthy records): no more exclusions than shipped, every target's adaptive RMSE
   <= shipped's x 1.02.
3. Repair: on every ``dropout``, ``jump`` and ``frozen`` record (jig, vtl, spindle), the faulty
   sensor re-admitted in every campaign where shipped re-admits it, every target's adaptive RMSE
   <= shipped's x 1.02.
4. ``tests/apps`` monitor tests and ``tests/shell/test_export*.py`` pass (the exported monitor
   untouched).

Scored (2026-12-04; shipped = 9e060125's ``src`` from ``git archive``, the rule = 49b52b70; MLR;
ROOT /tmp/m81/b; 55 records a tree, the two trees run side by side): **REFUSED** (part 2).
Exclusions x / re-admissions x of the faulty sensor in the test campaign, adaptive RMSE (µm)
shipped -> rule (fixed in brackets):

* Part 1, drift, passed.  jig 8011 ``Hydraulik Tank`` 3x / 2x -> 1x / 0x (out at 7.706 h both),
  dX / dY / dZ 12.434 / 4.095 / 5.271 -> 12.353 / 4.041 / 5.251 (16.349 / 6.330 / 6.665); fresh
  jig 8091 3x / 2x -> 1x / 0x, 15.407 / 7.857 / 4.640 -> 15.383 / 7.825 / 4.599; jig 8092 2x / 1x
  -> 1x / 0x, 5.409 / 4.263 / 3.487 -> 5.410 / 4.255 / 3.488; jig 8093 1x / 0x both, equal.  vtl
  7846 ``Getriebe`` (out of range at 20.85 h) re-admitted -> kept out, dX / dZ 18.900 / 1.626 ->
  17.971 / 1.498 (17.093 / 1.514; the healthy ``Support``'s false exclusion at 15.6 h as before);
  fresh vtl 8094 the same, 13.949 / 1.134 -> 13.311 / 1.058 (14.796 / 1.219); vtl 8095 / 8096:
  the drift never seen by either (no event); spindle 8097 / 8098 (``T_motor2``, a pair the others
  predict): equal.
* Part 3, repair, passed: every dropout (jig ``Mutter X``, vtl ``Support``) and jump (jig
  ``Ständer hinten oben``, vtl ``Ständer links oben``, spindle ``T_motor2`` in its 4 campaigns)
  re-admitted as shipped, the frozen ones kept out as shipped; every RMSE equal.
* Part 2, healthy, FAILED on range77's gantry 7781: its healthy ``Gabelkopf`` (no other sensor
  predicts it), out as "explaining" ``Schlitten``'s +0.66 °C at 8.847 h in a field hotter than
  training, was back 4 times (4x / 4x) and is now held 4.4 h (1x / 1x, back at 13.26 h) at its
  last reading, 9.75 °C referenced while it reads 14.4: E_dY 3.675 -> 4.271, E_dZ 5.614 -> 6.514
  (0.291 / 0.588 fixed), E_dX 0.355 -> 0.361.  Its leak onto ``Schlitten`` (traced: the rule's
  leak logged at each re-admission check, /tmp/m81/trace2.py, not kept) hovered at 0.50-0.73 of
  the band for 4.4 h, the tank's was 0.62-0.93 in its first half hour out and grew to 1.6: a
  level does not tell a healthy sensor in a new field from an early drift.  The rest of part 2
  passed: no event and equal RMSE on every fresh healthy record (jig 8011, 8091-8093, vtl 7846,
  8094-8096, spindle 8097-8098, gantry 8099-8100, swiss 8101-8102); swiss 7778 / 7790 equal.
* Part 4 passed with the rule: tests/apps monitor tests (70 passed, mon81's 3 among them; 1
  xfail) and the shell monitor / export tests (``test_monitor*.py``, ``test_export_monitor76``,
  ``cmon80``, ``cdrop77``, ``dropout53``, ``test_stranger78``, ``test_adapt``, ``test_alarms``: 148
  passed, 3 xfail).

The src change is reverted; the rule is ``benchmarks/mon81_rule.patch``, the gap
``tests/apps/test_monitor_leak81.py``'s strict xfail.  Left (proposed, not scored): the leak's
*growth*, not its level -- a drift grows its leak (the tank 0.7 -> 1.6 in 1.5 h) where a healthy
sensor in a new field hovers (``Gabelkopf`` 0.5-0.7 for 4.4 h); the excursion rule's test
(:mod:`.excursion`, ``EXCURSION_GROWTH`` over ``EXCURSION_TAU_S``) on the leak would keep the
tank out and let ``Gabelkopf`` flap back as shipped; its bar needs 7781 as a found case and fresh
seeds.  vtl 8095 / 8096's undetected ``Getriebe`` drift and vtl 7846's false ``Support``
exclusion are untouched.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands, seed_list  # noqa: E402
from bench_mon77 import _lines, thermocomp  # noqa: E402

BENCH = Path(__file__).resolve().parent
QUIET = ("track=false", "plots=none", "model=mlr")
KINDS = "healthy,frozen,jump,drift,dropout"
FAULTED = {"jig": {"frozen": "T_Pinole", "jump": "T_Ständer_hinten_oben",
                   "drift": "T_Hydraulik_Tank", "dropout": "T_Mutter_X"},
           "vtl": {"frozen": "T_Hydrostatik_Vorlauf", "jump": "T_Ständer_links_oben",
                   "drift": "T_Getriebe", "dropout": "T_Support"},
           "spindle": {"freeze": "T_motor2", "drift": "T_motor2", "jump": "T_motor2"}}
SPINDLE_SIM = ("sim=yearround_spindle", "sim.generator.n_campaigns=12")
SPINDLE_FAULT = {"freeze": (), "drift": ("sim.generator.effect_params.sensor_faults.rate_K_per_h=1.0",),
                 "jump": ("sim.generator.effect_params.sensor_faults.magnitude_c=3.0",)}
TOL = 1.02


def summary(report: dict) -> dict:
    """Per campaign and sensor (exclusions, re-admissions, first exclusion h); per target RMSE."""
    per: dict = {}
    for e in report["events"]:
        if not e.get("sensor") or "excluded" not in (e["to"], e["from"]):
            continue
        s = per.setdefault(e["campaign"], {}).setdefault(e["sensor"], [0, 0, None])
        if e["to"] == "excluded":
            s[0] += 1
            s[2] = s[2] if s[2] is not None else round(e["time"] / 3600, 3)
        else:
            s[1] += 1
    return {"sensors": per, "events": len(report["events"]), "campaigns": sorted(report["campaigns"]),
            "rmse": {t: (r["rmse_fixed"], r["rmse_adaptive"]) for t, r in report["targets"].items()}}


def monitored(root: Path, label: str, record: str, kind: str, sensor: str | None, *args: str) -> None:
    out = root / label / f"{record}_{kind}"
    thermocomp("monitor", *args, f"out={out}", *QUIET)
    row = {"record": record, "kind": kind, "sensor": sensor,
           **summary(json.loads((out / "monitor.json").read_text()))}
    with open(root / f"{label}.jsonl", "a") as f:
        f.write(json.dumps(row) + "\n")
    print(record, kind, row["sensors"], {t: round(a, 3) for t, (_, a) in row["rmse"].items()}, flush=True)


def _stranger(root: str, label: str, seeds: str, kinds: str, name: str, module: str) -> None:
    """A stranger's machine: its files, faults, ``init`` once, ``monitor`` per kind."""
    bench = __import__(module)
    root_ = Path(root)
    data = root_ / "data"
    conf = data / f"init_{name}"
    for seed in seed_list(seeds):
        if not (data / f"fault_dropout_{seed}").exists() or not (data / f"{name}{seed}").exists():
            bench.write(str(data), str(seed))
            bench.faults(str(data), str(seed))
        if not (conf / "conf").exists():
            thermocomp("init", str(data / f"{name}{seed}"), f"out={conf}")
    cfg = next((conf / "conf" / "data").glob("*.yaml")).stem
    given = (f"hydra.searchpath=[file://{conf}/conf]", f"data={cfg}")
    for seed in seed_list(seeds):
        for kind in kinds.split(","):
            folder = data / (f"{name}{seed}" if kind == "healthy" else f"fault_{kind}_{seed}")
            monitored(root_, label, f"{name}{seed}", kind, FAULTED[name].get(kind), *given,
                      f"data.path={folder}")


def jig(root: str, label: str, seeds: str = "8011,8091-8093", kinds: str = KINDS) -> None:
    """stranger80's jig borer, healthy and faulted (docstring)."""
    _stranger(root, label, seeds, kinds, "jig", "bench_stranger80")


def vtl(root: str, label: str, seeds: str = "7846,8094-8096", kinds: str = KINDS) -> None:
    """stranger78's vertical turning lathe, healthy and faulted (docstring)."""
    _stranger(root, label, seeds, kinds, "vtl", "bench_stranger78")


def spindle(root: str, label: str, seeds: str = "8097-8098") -> None:
    """``yearround_spindle``, healthy and ``T_motor2`` faulted (docstring)."""
    root_ = Path(root)
    for seed in seed_list(seeds):
        for kind in ("healthy", *SPINDLE_FAULT):
            path = root_ / "data" / f"spindle{seed}_{kind}"
            if not (path / "campaigns.csv").exists():
                fault = () if kind == "healthy" else (
                    "sim.generator.effects=[sensor_faults]",
                    f"sim.generator.effect_params.sensor_faults.kind={kind}",
                    "sim.generator.effect_params.sensor_faults.column=T_motor2", *SPINDLE_FAULT[kind])
                thermocomp("simulate", *SPINDLE_SIM, f"seed={seed}", *fault, f"data.path={path}")
            monitored(root_, label, f"spindle{seed}", kind, FAULTED["spindle"].get(kind),
                      f"data.path={path}")


def gantry(root: str, label: str, seeds: str = "7781,8099-8100") -> None:
    """bench_range77's healthy gantry mill (docstring)."""
    import bench_stranger76 as s76
    root_ = Path(root)
    data = root_ / "data"
    conf = data / "init_gantry"
    for seed in seed_list(seeds):
        if not (data / f"gantry{seed}").exists():
            s76.write(str(data), str(seed))
        if not (conf / "conf").exists():
            thermocomp("init", str(data / f"gantry{seed}"), f"out={conf}")
    cfg = next((conf / "conf" / "data").glob("*.yaml")).stem
    for seed in seed_list(seeds):
        monitored(root_, label, f"gantry{seed}", "healthy", None,
                  f"hydra.searchpath=[file://{conf}/conf]", f"data={cfg}",
                  f"data.path={data / f'gantry{seed}'}")


def swiss(root: str, label: str, seeds: str = "7778,7790,8101-8102") -> None:
    """``swiss_lathe_door`` (40 h calibration), healthy (docstring)."""
    root_ = Path(root)
    for seed in seed_list(seeds):
        path = root_ / "data" / f"swiss{seed}"
        if not (path / "campaigns.csv").exists():
            thermocomp("simulate", "sim=swiss_lathe_door", f"seed={seed}",
                       "sim.generator.calibration_hours=40", f"data.path={path}")
        monitored(root_, label, f"swiss{seed}", "healthy", None, f"data.path={path}")


# -- the verdict ----------------------------------------------------------------------------------
RANGE77 = {"gantry7781", "swiss7778", "swiss7790"}


def _cells(row: dict) -> str:
    return "; ".join(f"{s.removeprefix('T_')} {o}x/{b}x {h}h" for c in row["sensors"].values()
                     for s, (o, b, h) in c.items()) or "-"


def table(root: str, shipped: str, rule: str) -> None:
    """Both labels' records side by side and the bar's verdict (docstring, parts 1-3)."""
    a, b = _lines(Path(root) / f"{shipped}.jsonl"), _lines(Path(root) / f"{rule}.jsonl")
    fails: list[str] = []
    for key in sorted(set(a) & set(b)):
        ra, rb = a[key], b[key]
        record, kind = key
        sensor = ra["sensor"]
        worse = [f"{t} {ra['rmse'][t][1]:.4g} -> {rb['rmse'][t][1]:.4g}" for t in ra["rmse"]
                 if rb["rmse"][t][1] > TOL * ra["rmse"][t][1] + 1e-12]
        if worse:
            fails.append(f"{key}: adaptive RMSE worse than shipped x {TOL}: {', '.join(worse)}")
        for cid in ra["campaigns"]:
            sa, sb = ra["sensors"].get(cid, {}), rb["sensors"].get(cid, {})
            for s in set(sa) | set(sb):
                oa, ob = sa.get(s, [0, 0, None]), sb.get(s, [0, 0, None])
                if ob[0] > oa[0]:
                    fails.append(f"{key} {cid}: {s} excluded {oa[0]} -> {ob[0]} times")
            if sensor is not None and sensor in sa:
                oa, ob = sa[sensor], sb.get(sensor, [0, 0, None])
                if ob[2] is None or ob[2] > oa[2]:
                    fails.append(f"{key} {cid}: {sensor} out later ({oa[2]} -> {ob[2]})")
                if kind == "drift" and ob[0] > 1:
                    fails.append(f"{key} {cid}: {sensor} flaps ({ob[0]} exclusions)")
                if kind in ("dropout", "jump", "frozen", "freeze") and oa[1] and not ob[1]:
                    fails.append(f"{key} {cid}: {sensor} no longer re-admitted")
        if kind == "healthy" and record not in RANGE77:
            if rb["events"] and not ra["events"]:
                fails.append(f"{key}: {rb['events']} events on a healthy record (shipped none)")
            if any(abs(rb["rmse"][t][1] - ra["rmse"][t][1]) > 1e-9 for t in ra["rmse"]):
                fails.append(f"{key}: healthy adaptive RMSE changed")
        rm = "  ".join(f"{t} {ra['rmse'][t][0]:.3f}/{ra['rmse'][t][1]:.3f}->{rb['rmse'][t][1]:.3f}"
                       for t in ra["rmse"])
        print(f"{record:12s} {kind:8s} {rm}\n    shipped: {_cells(ra)}\n    rule:    {_cells(rb)}")
    print("BAR (parts 1-3):", "PASSED" if not fails else "FAILED\n  " + "\n  ".join(fails), flush=True)


def main(argv: list[str] | None = None) -> int:
    np.seterr(all="ignore")
    return run_commands(__doc__, {"jig": jig, "vtl": vtl, "spindle": spindle, "gantry": gantry,
                                  "swiss": swiss, "table": table},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
