"""A frozen sensor's healthy coupled neighbour excluded with it (mon77): the rule, its bar, the score.

    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon77.py gantry ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon77.py spindle ROOT LABEL [SEEDS]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon77.py healthy ROOT LABEL [SEEDS]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon77.py table ROOT SHIPPED RULE

The code measured is the tree on ``PYTHONPATH`` (``/work/main/src``: shipped; the branch: the
rule); each command runs ``thermocomp monitor`` (MLR, ``track=false plots=none``) in a child
process and appends a line per record to ``ROOT/<LABEL>.jsonl``: per test campaign the sensors
excluded (first exclusion, h) and per target the RMSE fixed / adaptive.  The data are written
once under ``ROOT/data`` (the simulation does not depend on the rule).

* ``gantry``: ``benchmarks/gantry76.py`` (stranger76's gantry mill, its TwinCAT Scope exports;
  ``init`` once on the first seed, its data config read for every seed), seeds default
  ``7671-7673,7726-7735``: the healthy test run, and ``Temp Spindel vorn`` (coupled with ``Temp
  Spindel hinten``) frozen, drifting 1 K/h and jumping +2 K from row 2000 of the test run
  (stranger76's ``frozen`` case is row 2000 too).
* ``spindle``: ``yearround_spindle`` (12 campaigns, 4 test), seeds default 7726-7735, the
  simulator's ``sensor_faults`` on ``T_motor2`` (coupled with ``T_motor1``): ``freeze``,
  ``drift`` (1 K/h), ``jump`` (+3 °C) from the middle of every test campaign, and healthy.
* ``healthy``: ``fl_thermal`` (90/10) and ``swiss_lathe_door`` (40 h calibration) seeds
  default 7726-7735, healthy.
* ``table``: the two labels' lines side by side, and the bar's verdict.

Found at stop 76 (traced on gantry 7671's frozen ``Temp Spindel vorn``, row 2000 = 5.56 h): at
5.689 h ``Spindel vorn`` leaves its warning band (+0.504 against 0.449 °C, leverage 0.716), its
reading constant for 48 samples while its prediction moved; its coupled ``Spindel hinten`` is
within its band (-0.338 against 0.400, leverage 0.340).  The culprit rule's largest |E|(1 - h)
names ``hinten`` (0.223 against 0.143); its exclusion explains the bands only by leaving
``vorn`` unjudged (no other sensor predicts either once its partner is out), so the likelier
single fault, the largest standardised residual, decides: ``hinten`` 0.274 against ``vorn``
0.269 -- a coin toss, since a coupled pair's residuals mirror each other (smearing).  ``hinten``
goes out, and ``vorn`` one sample later by the freeze detector of a sensor no other predicts;
``hinten`` is never back (no set predicts it without ``vorn``).  The static field cannot tell the
two apart; their readings can: one has not moved for 48 samples while the other moves.  Where the
culprit rule names the frozen sensor itself (cmon76's ``T_motor2``), its moving partner goes out
as its blind partner (``T_motor1``): the same loss.

The rule (written and committed before it was scored)
-----------------------------------------------------
In the drift judgement (:meth:`Judgement._exclude_by_judgement`), after the culprit ``j`` is
chosen (paper 002's largest error, :meth:`_lone_fault`): a judged sensor ``k`` out of its
warning band whose reading has been constant for at least ``seen_run`` samples (the freeze
detector's length: training's longest constant run, at most a window) while the others'
prediction of it moved by at least half its warning band since the run began, is a freeze in
progress (the freeze detector waits for the whole band).  If such a ``k`` exists (of several,
the largest |E|(1 - h)) and ``j`` is not constant that long, ``k`` is the culprit instead of
``j`` when ``k``'s exclusion leaves every other judged sensor within its warning band (a sensor
it leaves unjudged allowed: its coupled partner).  When the culprit is such a ``k`` (chosen so, or
named by the culprit rule itself), its blind partners (active sensors no other predicts once it
is out) whose readings move are kept: the evidence is the culprit's own reading, and the partner
is then judged by its range, jump and freeze detectors as any sensor no other predicts.  The
event's reason still starts ``drift:`` (the exported C does not port it: it flags a drift beyond
the band as not in the code, as before).  Nothing else changes (a drift or a jump on a coupled
pair is as before: there the readings do not tell the two apart).

The bar (written before scoring; REFUSED if any part fails)
-----------------------------------------------------------
1. gantry 7671 ``frozen``: ``Spindel hinten`` never excluded, ``Spindel vorn`` excluded no later
   than shipped (5.69 h), every target's adaptive RMSE <= shipped's (E_dZ 1.96 µm).
2. ``bench_deploy_faults.py``, ``bench_cmon76.py`` (the served adaptive column and the fixed
   one), ``bench_faults71.py`` (mlr) and ``bench_fault70.py`` (its ``faults`` table): every
   detection no later and every RMSE no worse than shipped by more than 1 % (printed figures
   compared; the C columns of cmon76 are the code's, unchanged by a served rule).
3. Healthy (``healthy`` and the healthy lines of ``gantry`` and ``spindle``: ``fl_thermal``,
   gantry 7671-7673 and 7726-7735, ``yearround_spindle`` and ``swiss_lathe_door`` 7726-7735):
   no exclusion where shipped has none, never more exclusions than shipped, adaptive RMSE equal.
4. Faulty draws (``gantry``'s and ``spindle``'s faulted records, the fresh ones 7726-7735; freeze /
   drift / jump on a sensor with a coupled neighbour): over all campaigns, the faulty sensor excluded with no
   healthy sensor excluded in its campaign ("right alone") more often than shipped; on no
   record a healthy sensor excluded in more campaigns than shipped; the faulty sensor's first
   exclusion no later than shipped's on any campaign; per record ΣRMSE² adaptive <= shipped's
   × 1.01.

Measured 2026-12-03 (shipped = 3250ff79, its ``src`` from ``git archive``; MLR): REFUSED.
Part 1 passed: gantry 7671 frozen, ``vorn`` alone out at 5.689 h (shipped: ``hinten`` 5.689,
``vorn`` 5.692), E_dX / dY / dZ 0.342 / 0.311 / 1.963 -> 0.338 / 0.302 / 0.555 µm.  Part 2
failed: ``bench_deploy_faults.py`` printed the same; ``bench_cmon76.py`` freeze s7698 served
E_Y / E_Z 1.494 / 5.619 -> 1.474 / 5.574, freeze s7699 E_X / E_Y / E_Z 0.661 / 1.537 / 6.199 ->
0.669 / 1.478 / 6.302 (E_Z +1.7 %, ΣRMSE² +2.7 %), every other figure the same (faults71 and
fault70 not run).  Part 3 passed where run: the 12 gantry and 10 yearround healthy runs the same
(fl_thermal and swiss_lathe_door not run; gantry 7673 not run).  Part 4 failed: right alone 65
-> 69 campaigns (gantry 7671, 7731, 7735; yearround 7733 K03), no healthy sensor more often, no
detection later, but yearround 7733 freeze ΣRMSE² 27.20 -> 27.73 µm² (+1.9 %).  The rule fired
on one of 120 yearround faulted campaigns: there the frozen ``T_motor2`` is mostly still within
its band when ``T_motor1``'s mirrored error leaves it (not covered by the rule as written).
docs/measured/monitoring.md has the table.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands, seed_list  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
QUIET = ("track=false", "plots=none")
SPINDLE_SEEDS = "7726-7735"
GANTRY_SEEDS = "7671-7673,7726-7735"
KINDS = ("healthy", "freeze", "drift", "jump")


def thermocomp(*args: str) -> None:
    run = subprocess.run([sys.executable, "-m", "thermocomp", "-q", *args], cwd=REPO,
                         capture_output=True, text=True, env=os.environ.copy())
    if run.returncode:
        raise RuntimeError(f"thermocomp {' '.join(args)}: {run.stderr[-2000:]}")


def summary(report: dict, sensor: str | None) -> dict:
    """Per campaign the sensors excluded (first time, h); per target (fixed, adaptive) RMSE."""
    out: dict = {}
    for e in report["events"]:
        if e.get("sensor") and e["to"] == "excluded":
            first = out.setdefault(e["campaign"], {})
            first.setdefault(e["sensor"], round(e["time"] / 3600, 4))
    return {"sensor": sensor, "excluded": out, "campaigns": sorted(report["campaigns"]),
            "rmse": {t: (r["rmse_fixed"], r["rmse_adaptive"]) for t, r in report["targets"].items()}}


def monitored(root: Path, label: str, record: str, kind: str, sensor: str | None, *args: str) -> None:
    out = root / label / f"{record}_{kind}"
    thermocomp("monitor", *args, f"out={out}", *QUIET)
    row = {"record": record, "kind": kind, **summary(json.loads((out / "monitor.json").read_text()),
                                                      sensor)}
    with open(root / f"{label}.jsonl", "a") as f:
        f.write(json.dumps(row) + "\n")
    print(record, kind, row["excluded"], flush=True)


# -- the gantry mill ----------------------------------------------------------------------------
GANTRY_SENSOR = "Temp Spindel vorn"


def _gantry_data(data: Path, seed: int) -> None:
    import bench_stranger76 as s76
    from gantry76 import run_starts, sensors

    if (data / f"gantry{seed}_jump").exists():
        return
    s76.write(str(data), str(seed))
    start = run_starts()[-1]
    clean = pd.read_csv(data / f"raw{seed}" / f"run{len(run_starts())}.csv")
    column = {label: s.column for s, label in zip(sensors(), s76.LABELS, strict=True)}[GANTRY_SENSOR]
    hours = (clean.time - clean.time.iloc[2000]).clip(lower=0) / 3600.0
    cases = {"freeze": lambda v: v.where(v.index < 2000, v.iloc[2000]),
             "drift": lambda v: v + hours.to_numpy(),
             "jump": lambda v: v + 2.0 * (v.index >= 2000)}
    for kind, fault in cases.items():
        frame = clean.copy()
        frame[column] = fault(frame[column])
        folder = data / f"gantry{seed}_{kind}"
        folder.mkdir(parents=True, exist_ok=True)
        for earlier in run_starts()[:-1]:
            link = folder / f"Scope_Portal_{earlier:%Y%m%d}.csv"
            link.symlink_to((data / f"gantry{seed}" / link.name).resolve())
        text = s76.scope_text(s76.channels(frame, len(run_starts())), start.astimezone(s76.UTC),
                              "Thermo_Portal")
        (folder / f"Scope_Portal_{start:%Y%m%d}.csv").write_bytes(text.encode("cp1252"))


def gantry(root: str, label: str, seeds: str = GANTRY_SEEDS, kinds: str = ",".join(KINDS)) -> None:
    """The gantry mill's healthy and faulted test runs (docstring; ``kinds``: of ``KINDS``,
    comma-separated)."""
    root_ = Path(root)
    data = root_ / "data"
    data.mkdir(parents=True, exist_ok=True)
    conf = data / "init"
    for seed in seed_list(seeds):
        _gantry_data(data, seed)
        if not (conf / "conf").exists():
            thermocomp("init", str(data / f"gantry{seed}"), f"out={conf}")
    name = next((conf / "conf" / "data").glob("*.yaml")).stem
    given = (f"hydra.searchpath=[file://{conf}/conf]", f"data={name}")
    sensor = "T_" + GANTRY_SENSOR.replace(" ", "_")
    for seed in seed_list(seeds):
        for kind in kinds.split(","):
            folder = data / (f"gantry{seed}" if kind == "healthy" else f"gantry{seed}_{kind}")
            monitored(root_, label, f"gantry{seed}", kind, None if kind == "healthy" else sensor,
                      *given, f"data.path={folder}")


# -- yearround_spindle's motor pair ---------------------------------------------------------------
SPINDLE_SIM = ("sim=yearround_spindle", "sim.generator.n_campaigns=12")
SPINDLE_SENSOR = "T_motor2"
FAULT = {"freeze": (), "drift": ("sim.generator.effect_params.sensor_faults.rate_K_per_h=1.0",),
         "jump": ("sim.generator.effect_params.sensor_faults.magnitude_c=3.0",)}


def spindle(root: str, label: str, seeds: str = SPINDLE_SEEDS) -> None:
    """``yearround_spindle``, healthy and ``T_motor2`` faulted (docstring)."""
    root_ = Path(root)
    for seed in seed_list(seeds):
        for kind in KINDS:
            path = root_ / "data" / f"spindle{seed}_{kind}"
            if not (path / "campaigns.csv").exists():
                fault = () if kind == "healthy" else (
                    "sim.generator.effects=[sensor_faults]",
                    f"sim.generator.effect_params.sensor_faults.kind={kind}",
                    f"sim.generator.effect_params.sensor_faults.column={SPINDLE_SENSOR}", *FAULT[kind])
                thermocomp("simulate", *SPINDLE_SIM, f"seed={seed}", *fault, f"data.path={path}")
            monitored(root_, label, f"spindle{seed}", kind,
                      None if kind == "healthy" else SPINDLE_SENSOR, f"data.path={path}")


def healthy(root: str, label: str, seeds: str = SPINDLE_SEEDS) -> None:
    """``fl_thermal`` and ``swiss_lathe_door`` seeds ``seeds``, healthy (docstring)."""
    root_ = Path(root)
    monitored(root_, label, "fl_thermal", "healthy", None, "data=fl_thermal")
    for seed in seed_list(seeds):
        path = root_ / "data" / f"swiss{seed}"
        if not (path / "campaigns.csv").exists():
            thermocomp("simulate", "sim=swiss_lathe_door", f"seed={seed}",
                       "sim.generator.calibration_hours=40", f"data.path={path}")
        monitored(root_, label, f"swiss{seed}", "healthy", None, f"data.path={path}")


# -- the verdict ----------------------------------------------------------------------------------
def _lines(path: Path) -> dict:
    rows = [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
    return {(r["record"], r["kind"]): r for r in rows}


def _sq(row: dict) -> tuple[float, float]:
    fixed = sum(f ** 2 for f, _ in row["rmse"].values())
    return fixed, sum(a ** 2 for _, a in row["rmse"].values())


def table(root: str, shipped: str, rule: str) -> None:
    """Both labels' records side by side and the bar's verdict (docstring, parts 1, 3, 4)."""
    a, b = _lines(Path(root) / f"{shipped}.jsonl"), _lines(Path(root) / f"{rule}.jsonl")
    fails: list[str] = []
    right = {shipped: 0, rule: 0}
    for key in sorted(set(a) & set(b)):
        ra, rb = a[key], b[key]
        sensor = ra["sensor"]
        fa, sa = _sq(ra)
        _, sb = _sq(rb)
        cells = []
        for cid in ra["campaigns"]:
            xa, xb = ra["excluded"].get(cid, {}), rb["excluded"].get(cid, {})
            ha = sorted(s for s in xa if s != sensor)
            hb = sorted(s for s in xb if s != sensor)
            if sensor is not None:
                right[shipped] += sensor in xa and not ha
                right[rule] += sensor in xb and not hb
                if sensor in xa and (sensor not in xb or xb[sensor] > xa[sensor]):
                    fails.append(f"{key} {cid}: {sensor} out later ({xa[sensor]} -> {xb.get(sensor)})")
            if len(hb) > len(ha) or (set(hb) - set(ha)):
                fails.append(f"{key} {cid}: healthy excluded {ha} -> {hb}")
            if xa or xb:
                cells.append(f"{cid}: {_named(xa)} | {_named(xb)}")
        if sb > 1.01 * sa + 1e-12:
            fails.append(f"{key}: ΣRMSE² adaptive {sa:.4g} -> {sb:.4g}")
        if sensor is None and abs(sb - sa) > 1e-9:
            fails.append(f"{key}: healthy ΣRMSE² adaptive {sa:.6g} -> {sb:.6g}")
        print(f"{key[0]:14s} {key[1]:8s} ΣRMSE² fixed {fa:9.4g}  adaptive {sa:9.4g} -> {sb:9.4g}")
        for c in cells:
            print(f"    {c}")
    print(f"right sensor alone excluded (campaigns): {shipped} {right[shipped]}, {rule} {right[rule]}")
    if right[rule] <= right[shipped]:
        fails.append("right sensor alone not excluded more often")
    print("BAR (parts 1, 3, 4):", "PASSED" if not fails else "FAILED\n  " + "\n  ".join(fails))


def _named(first: dict) -> str:
    return ", ".join(f"{s.removeprefix('T_')} {t:.3g}" for s, t in sorted(first.items(),
                                                                        key=lambda kv: kv[1])) or "-"


def main(argv: list[str] | None = None) -> int:
    np.seterr(all="ignore")
    return run_commands(__doc__, {"gantry": gantry, "spindle": spindle, "healthy": healthy,
                                  "table": table}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
