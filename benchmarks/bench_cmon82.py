"""A drifting sensor in the exported C (cmon82, issue 34): a faulted record's corrections from the
compiled code with its sensor monitor, without it, and the served adaptive model's.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon82.py faults [ROOT] [SEEDS] [MODEL] \
        [KINDS] [SIM]

For each seed (default 8261-8275, not used before) ``thermocomp simulate`` (the default
``yearround_spindle``, healthy) into ``ROOT`` (default ``/tmp/cmon82-bench``), MODEL (default
``mlr``) fitted on the train split and deployed adaptive as ``replay`` deploys it, exported as C
(``gcc -std=c99 -Wall -Wextra -Werror -O2``) once with the monitor (``export.format=c``) and once
without it.  A fault planted on every test campaign from its middle row (the train split
untouched, one fit per seed; KINDS, default ``drift,ramp``): ``drift``, ``T_motor2`` reads
``+DRIFT_K_H`` K per hour more from there to the end (a thermocouple's junction ageing, a
loosened clamp), as the stranger benches' ``_faults.four_faults`` plant it; ``ramp``, the same
for ``RAMP_H`` hours, then back at as much per hour to its true reading and healthy after (a
clamp that loosened and was re-seated: the served monitor's re-admission).  SIM (default none:
``yearround_spindle``) another machine of ``conf/sim``, the drifting sensor then the first of the
pairs the code holds out (``monitor.pairs``: a sensor with its blind partner), else the first
sensor it holds out.

Prints per record the test RMSE (µm, pooled over the test campaigns) per target: fixed (the
plain stream), the served adaptive model, the C without and with its monitor, the largest |C
with monitor - served| over every row, the served monitor's drift exclusions (per campaign: its
row, and the re-admissions), the first row where the code's monitor flagged a rule it does not
hold (per campaign, with the rule) and the conformance pack's rows kept of all (the copies it
plants on the first test campaign listed apart).

This changes no rule of auto / diagnose / monitor (the served monitor is as shipped): the code
is measured against it, so no bar is written.

Traced (before cmon82) on this record: the served monitor's drift exclusion of ``T_motor2`` takes
its coupled ``T_motor1`` out in the same sample (its blind partner: no other sensor predicts it
once ``T_motor2`` is out; on 20 of the 120 drifted campaigns ``T_motor1`` is the culprit and
``T_motor2`` the partner), and ``T_amb`` (no other predicts it) weighs in the culprit rule's
``_explaining``; the culprit is often within its own band while its partner is out of it
(``_lone_fault``, then the excursion's hover against the field's memory).  So the slice the code
holds is the whole judgement while every sensor is in: ``_explaining``, ``_lone_fault``, the
veto, the hover (the memory of the field folded in by ``dt``), the culprit and its one blind
partner out (an operator per such pair, ``monitor.pairs``), the backoff of their return and the
sensors due back judged together; a new thermal state stays flagged (its guard bounds
``lo_new`` / ``hi_new`` are not in the export).

Scored (2026-12-04, sources of 45c06c88 and after; "before": the same bench on main at 996de40d,
the C that flagged the drift exclusion and read the drifting sensor on, its pack's rows in
brackets).  CPU of the bench process (gcc and ``stream`` not counted): drift 16.0 s, ramp 20.2 s
for the 15 seeds, the simulations cached (before: 25.0 s with the simulations, 16.6 s).  E_Z test
RMSE in µm pooled over the 8 test campaigns of each record (509-647 rows):

| record | fixed | served adaptive | C without monitor | C before | C with monitor | pack rows (before) |
|---|---|---|---|---|---|---|
| drift s8261 | 22.640 | 5.565 | 21.131 | 21.131 | 5.565 | 587 / 587 (339) |
| drift s8262 | 8.412 | 5.343 | 8.412 | 8.412 | 5.343 | 614 / 614 (347) |
| drift s8263 | 11.305 | 6.775 | 11.302 | 11.302 | 6.775 | 568 / 568 (332) |
| drift s8264 | 8.684 | 5.527 | 8.684 | 8.684 | 5.527 | 565 / 565 (331) |
| drift s8265 | 12.397 | 5.025 | 11.934 | 11.934 | 5.025 | 544 / 544 (314) |
| drift s8266 | 10.506 | 5.559 | 10.506 | 10.506 | 5.559 | 509 / 509 (300) |
| drift s8267 | 14.197 | 6.840 | 14.095 | 14.095 | 6.840 | 523 / 523 (298) |
| drift s8268 | 19.311 | 6.625 | 18.478 | 18.478 | 6.625 | 568 / 568 (330) |
| drift s8269 | 4.443 | 4.754 | 4.443 | 4.443 | 4.754 | 599 / 599 (337) |
| drift s8270 | 27.233 | 5.344 | 20.607 | 20.607 | 5.344 | 587 / 587 (335) |
| drift s8271 | 37.261 | 5.325 | 25.914 | 25.914 | 5.325 | 563 / 563 (320) |
| drift s8272 | 35.888 | 6.425 | 25.945 | 25.945 | 6.425 | 569 / 569 (330) |
| drift s8273 | 10.024 | 6.112 | 10.024 | 10.024 | 6.112 | 647 / 647 (368) |
| drift s8274 | 10.119 | 6.430 | 10.119 | 10.119 | 6.430 | 552 / 552 (313) |
| drift s8275 | 27.951 | 5.249 | 24.242 | 24.242 | 5.249 | 518 / 518 (299) |
| ramp s8261 | 7.516 | 5.450 | 7.516 | 7.516 | 5.450 | 587 / 587 (339) |
| ramp s8262 | 5.883 | 5.413 | 5.883 | 5.883 | 5.413 | 614 / 614 (347) |
| ramp s8263 | 7.774 | 6.811 | 7.774 | 7.774 | 6.811 | 568 / 568 (332) |
| ramp s8264 | 5.880 | 5.501 | 5.880 | 5.880 | 5.501 | 565 / 565 (331) |
| ramp s8265 | 5.595 | 4.965 | 5.595 | 5.595 | 4.965 | 544 / 544 (314) |
| ramp s8266 | 6.386 | 5.528 | 6.386 | 6.386 | 5.528 | 509 / 509 (300) |
| ramp s8267 | 8.357 | 6.852 | 8.357 | 8.357 | 6.852 | 523 / 523 (298) |
| ramp s8268 | 9.067 | 6.746 | 9.067 | 9.067 | 6.746 | 568 / 568 (330) |
| ramp s8269 | 4.259 | 4.649 | 4.259 | 4.259 | 4.649 | 599 / 599 (337) |
| ramp s8270 | 9.246 | 5.386 | 9.246 | 9.246 | 5.386 | 587 / 587 (335) |
| ramp s8271 | 11.578 | 5.348 | 11.526 | 11.526 | 5.348 | 563 / 563 (320) |
| ramp s8272 | 12.140 | 6.430 | 12.121 | 12.121 | 6.430 | 569 / 569 (330) |
| ramp s8273 | 6.273 | 6.075 | 6.273 | 6.273 | 6.075 | 647 / 647 (368) |
| ramp s8274 | 6.891 | 6.429 | 6.891 | 6.891 | 6.429 | 552 / 552 (313) |
| ramp s8275 | 8.953 | 5.174 | 8.953 | 8.953 | 5.174 | 518 / 518 (299) |

The C with its monitor gives the served adaptive corrections on every row of every test
campaign of all 30 records: largest |C with monitor - served| over the three targets 6.9e-13 µm
(before: 10.6-66.6 µm on a drift, 5.8-33.8 µm on a ramp), no rule it does not hold flagged, the
pack keeps every row, 8513 of 8513 per kind (before: 4893; it was cut at the served exclusion,
row 29-56 of each campaign).  The served monitor excluded the pair on all 120 campaigns of each
kind and, on the ramp, re-admitted both together (the same row) on 72 of them (the code alike).  The C
before equals the C without a monitor on every record (it read the drifting sensor on).  The
pack's copies planted on the first test campaign are cut where the record's own drift
exclusion comes while the planted sensor is out (a second sensor out: not in the code), but the
common step, whole on all 30 (before: cut there), and the freeze on 3 of 15 per kind.  On
s8269 the served monitor is worse than the fixed model (4.754 against 4.443 µm on the drift,
4.649 against 4.259 on the ramp): the C follows it, right or wrong.

A stranger machine, ``column_moving_source`` (seed 8275, the last of this range's, a draw of
another machine; ``faults /tmp/cmon82-bench 8275 mlr drift,ramp column_moving_source``, 10.4 s,
``T_front1`` drifted, one test cycle of 1441 rows): where the never-trained source Q3 sets in
(row 732) the served monitor excludes ``T_right4`` for drift, the C alike, and at row 733
re-admits it as the field followed it (a new thermal state): the code flags it there (not in
the code) and the pack keeps 732 of 1441 rows on either kind; largest |C - served| after that
26.7 µm (E_Y 71.701 against the served 72.599 µm on the drift).  A new thermal state needs the
monitor's state (declared, its calm count, the re-admission) and the guard's new-state bounds
in the export: not done here.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _ccode import built, built_without_monitor, deployed_on, rmse, streamed  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402

SEEDS = "8261-8275"
SENSOR = "T_motor2"
DRIFT_K_H = 1.0          # +1 K/h from the middle row (the stranger benches' drift)
RAMP_H = 1.0             # ramp: up for an hour, down for an hour


def _planted(frame: pd.DataFrame, kind: str = "drift", sensor: str = SENSOR) -> pd.DataFrame:
    out = frame.copy()
    half = len(out) // 2
    t = out["time"].to_numpy(float)
    hours = np.clip(t - t[half], 0.0, None) / 3600.0
    if kind == "ramp":
        hours = np.clip(RAMP_H - np.abs(hours - RAMP_H), 0.0, None)
    out[sensor] = out[sensor] + hours * DRIFT_K_H
    return out


def _first_flag(ss, frame: pd.DataFrame) -> str | None:
    """The row (1-based) where the code's monitor first flags a rule it does not hold, and the
    rule."""
    from thermocomp.apps.deploy.export import Simulator
    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE, RULES

    sim = Simulator(ss)
    sim.reset()
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        sim.step(u, t)
        if sim.watch.flags & NOT_IN_CODE or sim.refused:
            return f"{i + 1} {RULES[sim.watch.missed or sim.watch.rule]}"
    return None


def _drifts(events: list, times: np.ndarray) -> str:
    """The served monitor's drift exclusions and re-admissions (row numbers, 1-based)."""
    said = []
    for e in events:
        if not e.get("sensor") or e["to"] not in ("excluded", "ok"):
            continue
        why = e["reason"].split(":")[0]
        if e["to"] == "excluded" and why != "drift" and "re-admitted" not in e["reason"]:
            said.append(f"{e['sensor']} out ({why})@{int(np.searchsorted(times, e['time'])) + 1}")
        elif e["to"] == "excluded":
            said.append(f"{e['sensor']} out@{int(np.searchsorted(times, e['time'])) + 1}")
        elif why == "re-admitted":
            said.append(f"{e['sensor']} back@{int(np.searchsorted(times, e['time'])) + 1}")
    return " ".join(said)


def _sensor(ss) -> str:
    """The sensor to drift: ``SENSOR`` where monitored, else the first of a pair, else the first
    the code holds out."""
    m = ss.monitor
    names = [ss.inputs[i] for i in m["inputs"]]
    if SENSOR in names:
        return SENSOR
    ported = [k for k, p in enumerate(m["ported_out"]) if p]
    return names[m["pairs"][0][0] if m["pairs"] else ported[0]]


def record(root: Path, seed: int, model: str = "mlr", kinds: tuple = ("drift", "ramp"),
           sim: str = "") -> list[str]:
    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.shell.cli import main

    data = root / (f"{sim}-{seed}" if sim else f"healthy-{seed}")
    if not (data / "campaigns.csv").is_file():
        assert main(["-q", "simulate", f"seed={seed}", f"data.path={data}", "track=false",
                     *([f"sim={sim}"] if sim else [])]) == 0
    deployed, ds, test_ids = deployed_on(data, model)
    targets = deployed.targets_
    ss = state_space(deployed, monitor=True)
    sensor = _sensor(ss)
    out = []
    with tempfile.TemporaryDirectory(prefix="cmon82-") as tmp:
        with_mon = built(Path(tmp) / "with", exported_files(deployed, "c"))
        without = built_without_monitor(Path(tmp) / "without", deployed)
        cols = ["time", *ss.inputs]
        for kind in kinds:
            tests = {t: _planted(ds.campaigns[t].reset_index(drop=True), kind, sensor) for t in test_ids}
            errors, fixed, served, code0, code1, flags, moves = [], [], [], [], [], [], []
            for t, df in tests.items():
                errors.append(df[targets].to_numpy(float))
                fixed.append(-replay(deployed.streaming, df)[targets].to_numpy(float))
                rows = stream_rows(deployed, df, t)
                served.append(corrections(ss, rows.y))
                code0.append(streamed(without, df[cols]))
                code1.append(streamed(with_mon, df[cols]))
                if (said := _drifts(rows.events, df["time"].to_numpy(float))):
                    moves.append(f"{t}: {said}")
                if (row := _first_flag(ss, df)) is not None:
                    flags.append(f"{t}@{row}")
            _, summary = conformance_pack(deployed, ss, tests)
            listed = [e for e in summary["campaigns"] if "planted" not in e]
            kept = sum(e["rows"] for e in listed)
            total = sum(len(df) for df in tests.values())
            plants = [f"{e['campaign'].split('.', 1)[1]} {e['rows']}"
                      f"{'' if e['cut'] is None else ' cut'}"
                      for e in summary["campaigns"] if "planted" in e]
            worst = max(float(np.max(np.abs(a - b))) for a, b in zip(code1, served))
            out.append(f"{kind} {sensor} s{seed} {model}: pack rows {kept}/{total}; max|C monitor - served| "
                       f"{worst:.2e} um; flags {', '.join(flags) or 'none'}; planted: "
                       f"{', '.join(plants)}")
            out.append(f"  served: {'; '.join(moves) or 'no exclusion'}")
            for i, t in enumerate(targets):
                f, s, c0, c1 = (rmse(errors, x)[i] for x in (fixed, served, code0, code1))
                out.append(f"  {t}: fixed {f:.3f}  served adaptive {s:.3f}  C without monitor "
                           f"{c0:.3f}  C with monitor {c1:.3f}")
    return out


def faults(root: str = "/tmp/cmon82-bench", seeds: str = SEEDS, model: str = "mlr",
           kinds: str = "drift,ramp", sim: str = "") -> None:
    folder = made_folder(root)
    for seed in seed_list(seeds):
        print("\n".join(record(folder, seed, model, tuple(kinds.split(",")), sim)), flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"faults": faults}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
