"""A new thermal state in the exported C (cmon82b, issue 34): on a machine whose heat source
training never saw sets in, the compiled code's corrections against the served adaptive model's.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon82b.py states [ROOT] [SEEDS] \
        [MODEL] [KINDS] [SIM]

For each seed (default 8371-8380, not used before) ``thermocomp simulate sim=SIM`` (default
``column_moving_source``: a source Q3 that never runs in training starts in the test cycle)
into ``ROOT`` (default ``/tmp/cmon82-bench``, shared with bench_cmon82), MODEL (default ``mlr``)
fitted on the train split, deployed adaptive and exported as C with its monitor, as
bench_cmon82 does; KINDS (default ``healthy,drift``): the test record as simulated, or with
bench_cmon82's drift planted (+1 K/h from each test campaign's middle row on the first sensor of
the pairs the code holds out).  Prints per record the E_* test RMSE (µm, pooled over the test
campaigns): fixed (the plain stream), the served adaptive model, the C with its monitor, the
largest |C - served| over every row, the served monitor's drift exclusions and re-admissions and
its new thermal states (row declared, row ended), the first row the code flags (not in the
code) and the conformance pack's rows kept of all.  "C before": the same bench with the sources
of main at 7fa763cc (``PYTHONPATH=/path/to/main/src``).

This changes no rule of the served monitor: the code is measured against it, so no bar is
written (the C must equal the served corrections, ~1e-9 µm, and the pack keep the rows).

Traced (cmon82b, the served monitor at 7fa763cc, surveillance/judgement.py):

* entry: the drift judgement (``_exclude_by_judgement``) vetoes an exclusion as a new thermal
  state (``_drift_vetoed``) when with the culprit out the others stay out of their warning band
  (declared: ``_declare``); or, after a drift exclusion, when within ``window`` samples of it
  ``new_state_others`` other judged sensors leave their band (``_follow_field``: the sensor is
  re-admitted at once, ``by_field`` off, its return wait back to one window, then declared);
* while it lasts (``_novel``): no drift exclusion at all (``_explaining`` skipped, every culprit
  vetoed); the fault signatures (jump, freeze, dropout, range) still exclude;
* exit (``_end_when_calm``, every sample the judgement runs): ``_calm_field`` counts the samples
  with no judged sensor out of its warning band (0 at the declaration and at any sample with
  one out); the state ends after a window of them;
* the guard (``adaptive._output``): while declared, the correction is bounded by ``lo_new`` /
  ``hi_new`` (the training range widened by ``new_state_margin``, the same as ``lo`` / ``hi``
  when it is unset), the state read after the sample's monitor step.

So the slice the code now holds (watch.py, watch_c.py): the state's two entries, the veto of
every drift exclusion while it lasts, the re-admission of the followed sensor, the calm count and
its end, and ``guard_lo_new`` / ``guard_hi_new`` in compensator.json and the C (where
``new_state_margin`` makes them differ; the default leaves them equal, so not on these records).

Scored (2026-12-04, sources of 3a2d6e55; "before": the same bench on main at 7fa763cc).  CPU of
the bench process (gcc and ``stream`` not counted): 93.4 s for the 11 records, the simulations
cached (before: 101.2 s with the 10 fresh simulations).  The served monitor (unchanged: its
events and RMSE the same digits in both runs) declares a new thermal state on all 22 records
(its end at row 1186-1276 of 1441), at the row where it re-admits a drift-excluded sensor
as the field followed it on 13 of them.  E_Y test RMSE in µm (one test cycle of 1441 rows), the
largest |C - served| over every row and target, the pack's rows kept:

| record | fixed | served adaptive | C before | C now | max abs(C - served), µm | pack rows |
|---|---|---|---|---|---|---|
| healthy s8371 | 24.608 | 24.635 | 24.608 | 24.608 | 24 -> 24 | 733 -> 733 |
| drift s8371 | 150.136 | 79.329 | 79.322 | 79.322 | 24 -> 24 | 733 -> 733 |
| healthy s8372 | 11.384 | 11.383 | 11.342 | 11.383 | 3.5 -> 1.7e-13 | 739 -> 1441 |
| drift s8372 | 92.083 | 66.504 | 130.236 | 66.504 | 3.6e+02 -> 3.4e-13 | 733 -> 1441 |
| healthy s8373 | 11.668 | 11.668 | 11.668 | 11.668 | 2e-13 -> 2e-13 | 1441 -> 1441 |
| drift s8373 | 138.025 | 92.772 | 30.649 | 92.772 | 2.9e+02 -> 3.4e-13 | 736 -> 1441 |
| healthy s8374 | 18.055 | 18.058 | 16.993 | 18.058 | 9.8 -> 3.1e-13 | 734 -> 1441 |
| drift s8374 | 109.594 | 69.407 | 64.590 | 64.590 | 82 -> 82 | 1075 -> 1075 |
| healthy s8375 | 18.013 | 17.890 | 17.890 | 18.013 | 20 -> 23 | 1179 -> 1232 |
| drift s8375 | 74.323 | 57.705 | 71.419 | 57.705 | 1.8e+02 -> 4.8e-13 | 736 -> 1441 |
| healthy s8376 | 17.223 | 17.240 | 17.223 | 17.223 | 3.5 -> 3.5 | 1256 -> 1256 |
| drift s8376 | 135.112 | 96.400 | 96.399 | 96.399 | 2 -> 2 | 1256 -> 1256 |
| healthy s8377 | 19.935 | 19.879 | 67.240 | 19.879 | 1.8e+02 -> 2.3e-13 | 732 -> 1441 |
| drift s8377 | 113.449 | 73.290 | 73.290 | 73.290 | 3.4e-13 -> 3.4e-13 | 1441 -> 1441 |
| healthy s8378 | 16.086 | 16.087 | 14.707 | 16.087 | 18 -> 2.3e-13 | 733 -> 1441 |
| drift s8378 | 122.106 | 68.509 | 102.626 | 68.676 | 2.6e+02 -> 27 | 733 -> 1149 |
| healthy s8379 | 9.001 | 9.001 | 9.003 | 9.001 | 9.8 -> 2.3e-13 | 1168 -> 1441 |
| drift s8379 | 148.087 | 67.602 | 67.602 | 67.602 | 2.6e-13 -> 2.6e-13 | 1441 -> 1441 |
| healthy s8380 | 22.864 | 22.860 | 15.066 | 22.860 | 70 -> 2.8e-13 | 732 -> 1441 |
| drift s8380 | 108.024 | 67.073 | 106.317 | 67.073 | 2.8e+02 -> 4e-13 | 733 -> 1441 |

On the 20 fresh records the C equals the served corrections on every row of 15 (largest
difference 4.8e-13 µm; before: 3 of 20) and the pack keeps 26167 of 28820 rows (before: 19064;
healthy 9447 -> 13308, drift 9617 -> 12859 of 14410 each).  The C before, cut at the
re-admission, was up to 3.6e+02 µm off the served corrections after it, its E_Y RMSE from
0.33x to 3.4x the served one's.  What is left flagged is no new-state rule: on s8371 (both
kinds), s8375 healthy (row 1233) and s8376 (both, row 1257) the served monitor excludes a
sensor no other predicts as explaining the others' errors (``_explaining``: ``T_front3``,
``T_amb``; held at its last reading, not in the code), on s8374 and s8378 drift a reading beyond
its range and another sensor's jump in one sample (a second sensor out).  On s8375 healthy the
pack now keeps 53 more rows and the C reaches that row with the served state (20 -> 23 µm after
it: it parts there instead of at row 735).

The found case, s8275 (cmon82's, ``T_right4`` excluded at row 732 and re-admitted at 733-734):
healthy E_Y 15.259 / 15.249 / 14.129 -> 15.249, max |C - served| 27 -> 2.6e-13 µm, pack 733 ->
1441 of 1441; drift 88.357 / 72.599 / 71.701 -> 72.599, 27 -> 4.5e-13 µm, 732 -> 1441.  No bar:
the served monitor is unchanged; the code is measured against it.  bench_cmon82 (``faults``,
8261-8275, both kinds) on these sources: as it scored, every pack whole (8513 of 8513 rows per
kind), largest |C with monitor - served| 6.9e-13 µm, 27.0 s CPU.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _ccode import built, deployed_on, rmse, streamed  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402
from bench_cmon82 import _drifts, _first_flag, _planted, _sensor  # noqa: E402

SEEDS = "8371-8380"
SIM = "column_moving_source"


def _states(events: list, times: np.ndarray) -> str:
    """The served monitor's new thermal states: ``new@row`` and ``end@row`` (1-based)."""
    from thermocomp.apps.deploy.surveillance import NEW_STATE, TRAINED

    said = []
    for e in events:
        if e.get("sensor") is None and e.get("to") in (NEW_STATE, TRAINED):
            said.append(f"{'new' if e['to'] == NEW_STATE else 'end'}@"
                        f"{int(np.searchsorted(times, e['time'])) + 1}")
    return " ".join(said)


def record(root: Path, seed: int, model: str = "mlr", kinds: tuple = ("healthy", "drift"),
           sim: str = SIM, overrides: tuple = ()) -> list[str]:
    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.shell.cli import main

    data = root / f"{sim}-{seed}"
    if not (data / "campaigns.csv").is_file():
        assert main(["-q", "simulate", f"seed={seed}", f"data.path={data}", "track=false",
                     f"sim={sim}"]) == 0
    deployed, ds, test_ids = deployed_on(data, model, overrides)
    targets = deployed.targets_
    ss = state_space(deployed, monitor=True)
    sensor = _sensor(ss)
    out = []
    with tempfile.TemporaryDirectory(prefix="cmon82b-") as tmp:
        code = built(Path(tmp) / "with", exported_files(deployed, "c"))
        cols = ["time", *ss.inputs]
        for kind in kinds:
            tests = {t: ds.campaigns[t].reset_index(drop=True) for t in test_ids}
            if kind != "healthy":
                tests = {t: _planted(df, kind, sensor) for t, df in tests.items()}
            errors, fixed, served, c1, flags, moves = [], [], [], [], [], []
            for t, df in tests.items():
                errors.append(df[targets].to_numpy(float))
                fixed.append(-replay(deployed.streaming, df)[targets].to_numpy(float))
                rows = stream_rows(deployed, df, t)
                served.append(corrections(ss, rows.y))
                c1.append(streamed(code, df[cols]))
                times = df["time"].to_numpy(float)
                said = " ".join(s for s in (_drifts(rows.events, times),
                                            _states(rows.events, times)) if s)
                if said:
                    moves.append(f"{t}: {said}")
                if (row := _first_flag(ss, df)) is not None:
                    flags.append(f"{t}@{row}")
            _, summary = conformance_pack(deployed, ss, tests)
            listed = [e for e in summary["campaigns"] if "planted" not in e]
            kept = sum(e["rows"] for e in listed)
            total = sum(len(df) for df in tests.values())
            worst = max(float(np.max(np.abs(a - b))) for a, b in zip(c1, served))
            name = kind if kind == "healthy" else f"{kind} {sensor}"
            out.append(f"{name} s{seed} {model}: pack rows {kept}/{total}; max|C - served| "
                       f"{worst:.2e} um; flags {', '.join(flags) or 'none'}")
            out.append(f"  served: {'; '.join(moves) or 'no exclusion, no new state'}")
            for i, t in enumerate(targets):
                f, s, c = (rmse(errors, x)[i] for x in (fixed, served, c1))
                out.append(f"  {t}: fixed {f:.3f}  served adaptive {s:.3f}  C {c:.3f}")
    return out


def states(root: str = "/tmp/cmon82-bench", seeds: str = SEEDS, model: str = "mlr",
           kinds: str = "healthy,drift", sim: str = SIM) -> None:
    folder = made_folder(root)
    for seed in seed_list(seeds):
        print("\n".join(record(folder, seed, model, tuple(kinds.split(",")), sim)), flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"states": states}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
