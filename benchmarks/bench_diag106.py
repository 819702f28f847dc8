"""The closed loop from a stranger's side: ``thermocomp diagnose`` as a user runs it, on machines and
undeclared effects no diag bench drew (stop 106, diag106; issue 34: "``diagnose`` accepts a planted
position effect with 8 train campaigns, accepts nothing on clean data, and never leaves a record's
test error more than 2 % worse").  An audit, not a rule: no src change is proposed here.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag106.py audit ROOT SEEDS     # SEEDS' draws -> ROOT/rows.jsonl
    python benchmarks/bench_diag106.py table ROOT           # the rows and the bar

``audit``: for each seed of ``SEEDS`` (``10074-10078``) its kind of :data:`KINDS`, twice: PLANTED
(the kind's effect) and CLEAN (the same machine and campaigns, ``sim.generator.clean=true``, no
effect).  Each draw runs the user's commands (README / docs/diagnose.md / docs/cli.md) as
subprocesses, every one with ``track=false``: ``thermocomp simulate``; ``thermocomp diagnose
data.path=... out=... plots=none`` (defaults otherwise: MLR, every target, ``max_effects=3``,
``seed=0``); the ``rerun`` command ``diagnosis.json`` writes (``thermocomp run ...
experiment=diagnosed``, the diagnosed model); ``thermocomp replay replay.model=<that model.pkl>``.
Per (draw, target) a row: the candidate ranked first in round 1 (the lowest CV RMSE among the
refitted), its family-wise p and whether it cleared, the design's smallest reachable p, what was
accepted, test RMSE before -> after as diagnose scores it (deployed), run's and replay's figures of
the diagnosed model (deployed = replay's ``rmse`` against diagnose's after), the control signal.

Kinds (chosen BEFORE any draw, from ``docs/simulation.md``'s scenarios and effects; grep of the
diag / diagnose benches' sources: ``sensor_drift``, ``sensor_faults`` and ``climate_room`` with a
planted effect appear in none; every diag86..105 draw was the year-round VMC's lag / planted
position / clean).  8 train campaigns each, the rest test:

* 10074 ``climate_room`` (the lathe, ``n_runs=12``, the last 4 test) with ``hidden_source`` (a
  hydraulic unit on the spindle that only ``S_hydraulic_temp_C`` sees; on E_X).  Found if: a
  ``signal`` on S_hydraulic_temp_C accepted on E_X.
* 10075 ``climate_room`` with ``axis_position`` (a Z slide's lever times the headstock-frame tilt;
  on E_Z: a position effect on another machine, axis and target).  Found if: an ``interaction`` on
  S_pos_Z accepted on E_Z.
* 10076 ``yearround_spindle`` (``n_campaigns=12``, every 3rd test) with ``sensor_drift`` on T_box1
  (0.8 K/h from 30 % of each campaign, only in the later half of the calendar: an effect only in
  some campaigns, train and test).  Found if: T_box1 excluded (``sensor_fault``).
* 10077 ``yearround_spindle`` 12 with ``sensor_faults`` (a 3 °C jump at half of each affected
  campaign, the sensor drawn by the seed) in the later train campaigns K07 K08 K10 K11 only, the
  test files clean: an effect on a sensor that is no state column.  Found if: that sensor excluded.
* 10078 ``climate_room`` with ``lag_node`` (an unmeasured mass on the spindle motor, ~2.6 h, on
  E_X: a slow state on a lathe).  Found if: a ``dynamics`` effect accepted on E_X.

Not drawn: a machine of 30+ sensors.  ``large_mill_week`` (52) and ``column_moving_source`` (20)
write one train and one test campaign (``train_hours`` / ``test_hours``), ``fleet`` (40) plants no
effect and has no clean form: none gives 8 train campaigns with an effect and its clean twin
through the shipped scenario keys.

BAR (written and committed before any of 10074-10078 is simulated; not moved after):

* B1 the planted effect (its kind on its column -- for a sensor fault the sensor excluded -- on the
  target the truth names) accepted on >= 3 of the 5 PLANTED draws;
* B2 nothing accepted (no effect, no sensor excluded) on any target of the 5 CLEAN draws;
* B3 the control signal never clears the bar (``control_ever_clears_bar`` false) on any target of
  the 10 draws;
* B4 no (draw, target) of the 10 with its test RMSE after more than 2 % above before (diagnose's
  figures, deployed).
Reported, not the bar: run's / replay's figures against diagnose's (deployed = scored to 1e-6 µm),
CPU of each command (user + sys of the child, ``resource.RUSAGE_CHILDREN``).
Each break: a failing cheap test, the mend, the test passing (KEPT), or the break named with its
numbers (TRACED).  No constant is tuned on these seeds.
"""

from __future__ import annotations

import json
import os
import resource
import shlex
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import made_folder, run_commands, seed_list  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
CLIMATE = ["sim=climate_room", "sim.generator.n_runs=12", "sim.generator.test_fraction=0.34"]
VMC = ["sim=yearround_spindle", "sim.generator.n_campaigns=12"]
# seed -> (name, the machine's overrides, the effect's overrides, the expected finding)
KINDS = {
    10074: ("climate_hydraulic", CLIMATE, ["sim.generator.effects=[hidden_source]"],
            ("signal", "S_hydraulic_temp_C", "E_X")),
    10075: ("climate_position", CLIMATE, ["sim.generator.effects=[axis_position]"],
            ("interaction", "S_pos_Z", "E_Z")),
    10076: ("vmc_drift_later", VMC, ["sim.generator.effects=[sensor_drift]"],
            ("sensor_fault", "T_box1", None)),
    10077: ("vmc_jump_some", VMC, ["sim.generator.effects=[sensor_faults]",
                                   "sim.generator.effect_params.sensor_faults.splits=[train]",
                                   "sim.generator.effect_params.sensor_faults.campaigns=[K07,K08,K10,K11]"],
            ("sensor_fault", None, None)),
    10078: ("climate_lag", CLIMATE, ["sim.generator.effects=[lag_node]"], ("dynamics", None, "E_X")),
}


def _thermocomp(words: list[str], log: Path) -> float:
    """``python -m thermocomp WORDS`` from the repository root; its CPU (user + sys) seconds."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(log, "w") as f:
        done = subprocess.run([sys.executable, "-m", "thermocomp", *words], cwd=REPO, stdout=f,
                              stderr=subprocess.STDOUT, env=dict(os.environ))
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode:
        raise SystemExit(f"thermocomp {words[0]} exit {done.returncode}: see {log}")
    return round(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, 1)


def _expected(seed: int, truth: dict) -> tuple:
    kind, column, target = KINDS[seed][3]
    planted = truth.get("undeclared_effects") or []
    if column is None and planted:   # the sensor the seed drew, the truth's column
        column = planted[0].get("column")
    return kind, column, target


def _found(expected: tuple, per_target: dict) -> bool:
    kind, column, target = expected
    if kind == "sensor_fault":
        return any(column in t["excluded"] for t in per_target.values())
    row = per_target.get(target, {})
    return any(a["kind"] == kind and (column is None or a["column"] == column) for a in row["accepted"])


def _first_ranked(j: dict) -> dict | None:
    """Round 1's refitted candidate of least CV RMSE (the control left out)."""
    rounds = j.get("rounds") or []
    evaluated = (rounds[0].get("evaluated") or []) if rounds else []
    evaluated = [e for e in evaluated if e.get("family") != "control"]
    scored = [e for e in evaluated if (e.get("evidence") or {}).get("cv_rmse") is not None]
    if not scored:
        return None
    best = min(scored, key=lambda e: e["evidence"]["cv_rmse"])
    ev = best["evidence"]
    return {"title": best.get("title") or best.get("effect"), "kind": best.get("family"),
            "gain_pct": ev.get("cv_rmse_gain_pct"), "p_family": ev.get("p_value_family"),
            "clears": ev.get("clears_bar")}


def _target_row(j: dict, target: str, replay: dict, metrics: dict) -> dict:
    accepted = [{"title": e.get("title") or e.get("effect"), "kind": e.get("family"),
                 "column": e.get("column"), "p_family": (e.get("evidence") or {}).get("p_value_family")}
                for e in j.get("effects", []) if e.get("accepted")]
    designs = (j.get("cv") or {}).get("designs") or {}
    return {"before": j["before"]["test_rmse"], "after": j["after"]["test_rmse"],
            "after_as_run": j["after"].get("test_rmse_as_run"),
            "accepted": [a for a in accepted if a["kind"] != "sensor_fault"],
            "excluded": list(j.get("excluded_inputs") or []),
            "first": _first_ranked(j),
            "min_p": (designs.get(target) or {}).get("min_p", j["cv"].get("min_p")),
            "control_clears": bool(j.get("control_ever_clears_bar")),
            "run": _figure(metrics, target), "replay": _figure(replay, target)}


def _figure(doc: dict, target: str):
    """The test RMSE of ``target`` in a metrics.json / replay.json (None where absent)."""
    for key in ("targets", "per_target", "metrics"):
        block = doc.get(key)
        if isinstance(block, dict) and isinstance(block.get(target), dict):
            t = block[target]
            for name in ("rmse", "test_rmse", "rmse_test"):
                if isinstance(t.get(name), (int, float)):
                    return t[name]
    return None


def _draw(root: Path, seed: int, clean: bool) -> dict:
    name, machine, effect, _ = KINDS[seed]
    case = f"{name}-{'clean' if clean else 'planted'}-{seed}"
    data, out, logs = root / "data" / case, root / "out" / case, made_folder(str(root / "logs"))
    cpu = {"simulate": _thermocomp(["simulate", *machine, f"seed={seed}", f"data.path={data}", "track=false",
                                    *(["++sim.generator.clean=true"] if clean else effect)],
                                   logs / f"{case}-simulate.log")}
    cpu["diagnose"] = _thermocomp(["diagnose", f"data.path={data}", f"out={out}/diagnose", "plots=none",
                                   "track=false"], logs / f"{case}-diagnose.log")
    primary = json.loads((out / "diagnose" / "diagnosis.json").read_text())
    rerun = shlex.split(primary["rerun"])
    rerun = rerun[rerun.index("run"):]
    model = out / "run" / "model.pkl"
    cpu["run"] = _thermocomp([*rerun, f"out={out}/run", f"model_path={model}", "plots=none", "track=false"],
                             logs / f"{case}-run.log")
    cpu["replay"] = _thermocomp(["replay", f"replay.model={model}", f"data.path={data}", f"out={out}/replay",
                                 "track=false"], logs / f"{case}-replay.log")
    metrics = json.loads((out / "run" / "metrics.json").read_text())
    replay = json.loads((out / "replay" / "replay.json").read_text())
    truth = json.loads(Path(f"{data}.truth.json").read_text())
    per_target = {}
    for path in sorted((out / "diagnose" / "diagnosis").glob("diagnosis_*.json")):
        j = json.loads(path.read_text())
        target = path.stem.removeprefix("diagnosis_")
        per_target[target] = _target_row(j, target, replay, metrics)
    row = {"case": case, "seed": seed, "clean": clean, "train": primary["cv"].get("train_campaigns"),
           "test": primary["cv"].get("test_campaigns"), "truth": truth.get("undeclared_effects"),
           "cpu_s": cpu, "targets": per_target}
    if not clean:
        row["expected"] = _expected(seed, truth)
        row["found"] = _found(row["expected"], per_target)
    return row


def audit(root: str, seeds: str) -> None:
    """Each seed's PLANTED then CLEAN draw -> ROOT/rows.jsonl (a case already there is kept)."""
    folder = made_folder(root)
    path = folder / "rows.jsonl"
    done = {json.loads(line)["case"] for line in path.read_text().splitlines()} if path.exists() else set()
    for seed in seed_list(seeds):
        for clean in (False, True):
            case = f"{KINDS[seed][0]}-{'clean' if clean else 'planted'}-{seed}"
            if case in done:
                continue
            row = _draw(folder, seed, clean)
            with open(path, "a") as f:
                print(json.dumps(row, ensure_ascii=False), file=f)
            _print_row(row)


def _print_row(row: dict) -> None:
    head = f"{row['case']} ({len(row['train'] or [])} train / {len(row['test'] or [])} test)"
    if not row["clean"]:
        head += f": expected {row['expected']}, found {row['found']}"
    print(head, f"CPU {row['cpu_s']}", flush=True)
    for t, v in row["targets"].items():
        first = v["first"] or {}
        change = 100.0 * (v["after"] / v["before"] - 1.0)
        print(f"  {t}: first {first.get('title')} ({first.get('kind')}, gain {first.get('gain_pct')}, "
              f"p_fam {first.get('p_family')}, clears {first.get('clears')}); min_p {v['min_p']}; "
              f"accepted {[a['title'] for a in v['accepted']]} excluded {v['excluded']}; "
              f"test {v['before']:.4f} -> {v['after']:.4f} ({change:+.1f} %); as run {v['after_as_run']}; "
              f"run {v['run']} replay {v['replay']}; control clears {v['control_clears']}", flush=True)


def table(root: str) -> None:
    """The rows of ROOT/rows.jsonl and B1-B4."""
    rows = [json.loads(line) for line in (Path(root) / "rows.jsonl").read_text().splitlines()]
    for row in rows:
        _print_row(row)
    planted = [r for r in rows if not r["clean"]]
    clean = [r for r in rows if r["clean"]]
    found = [r["case"] for r in planted if r["found"]]
    taking = [(r["case"], t) for r in clean for t, v in r["targets"].items()
              if v["accepted"] or v["excluded"]]
    control = [(r["case"], t) for r in rows for t, v in r["targets"].items() if v["control_clears"]]
    worse = [(r["case"], t, round(100.0 * (v["after"] / v["before"] - 1.0), 1))
             for r in rows for t, v in r["targets"].items() if v["after"] > 1.02 * v["before"]]
    deployed = [(r["case"], t, v["replay"], v["after"]) for r in rows for t, v in r["targets"].items()
                if v["replay"] is None or abs(v["replay"] - v["after"]) > 1e-6]
    items = [(f"B1 planted found {len(found)} of {len(planted)} {found}",
              len(found) >= 3 and len(planted) == 5),
             (f"B2 clean (draw, target) accepting {taking}", not taking and len(clean) == 5),
             (f"B3 control clearing {control}", not control),
             (f"B4 (draw, target) > 2 % worse {worse}", not worse)]
    for text, ok in items:
        print(f"  {text}: {'met' if ok else 'FAILS'}")
    print(f"  reported: replay's rmse != diagnose's after (deployed) {deployed}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"audit": audit, "table": table}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
