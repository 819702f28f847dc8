"""The fallback model in the exported C (cmon83, issue 34): where the served monitor switches the
correction to the model fitted without a sensor no other predicts, the compiled code's
corrections against the served adaptive model's.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon83.py fallback [ROOT] [SEEDS] \
        [MODEL] [KINDS] [SIM]

As bench_cmon82c's ``blind`` (bench_cmon82b's record: ``thermocomp simulate sim=SIM``, default
``column_moving_source``, into ``ROOT``, default ``/tmp/cmon83-bench``; MODEL, default ``mlr``,
fitted on the train split, deployed adaptive as by default, ``monitor.fallbacks=unobservable``,
and exported as C with its monitor, ``gcc -std=c99 -Wall -Wextra -Werror -O2``; KINDS, default
``healthy,drift``: the test record as simulated, or with bench_cmon82's drift planted) on fresh
seeds (default 8541-8550).  Prints per record: the rows where the served correction is a
fallback model's (``AdaptiveCompensator._fallen_back``: its switches, 1-based, ``T_amb@732-737``),
the rows where the C equals the served corrections (every target within 1e-9 µm), the largest
|C - served| over every row and over the rows from the first switch on, the first row the code
flags (not in the code) with its rule, the conformance pack's rows kept and the E_* test RMSE
(fixed, served adaptive, C).  "Before": the same bench with the sources of main at b79207b5
(``PYTHONPATH=/path/to/main/src``).

This changes no rule of the served monitor: the code is measured against it, so no bar is
written (the C must equal the served corrections, ~1e-9 µm, and the pack keep the rows).

Traced (the served side at b79207b5, adaptive.py, fallback.py): each fallback (``fallbacks_``,
one per monitored sensor no other predicts that the model reads) is the model's family refitted
without that sensor, a plain stream with the model's envelope and policy, stepped on every row
beside the model on the same inputs (the monitor's, the sensor out held at its last reading)
from the campaign's start; the correction before the guard is the fallback's of the first
sensor out (the monitor's order) that has one, while the monitor rebuilds the field (enough
sensors in) and the sensor is not one out for a dropout that reads again; the guard (the same)
follows.  Back in, the model's again (its own state stepped all along).  So the code (the C and
its numpy mirror, :mod:`thermocomp.apps.deploy.export.fallbacks`): each fallback's laws in the
same system after the model's (``law_set``), every law stepped with its own history, lags,
feedback and clamp bound, the output the served set's (``monitor.fallback_set``).

Scored (2026-12-04, sources of this branch; "before": the same bench on main at b79207b5).  CPU
of the bench process (gcc and ``stream`` not counted; it steps the served model once more per
campaign for the fallback's rows): 84.2 s for the 20 records on the last commit's sources
(before 84.1 s; a first run, under a heavier load of the shared cores, 95.2 s), the simulations
cached; the last run printed the same as the first, line for line.  The served monitor is
unchanged: its corrections, events and RMSE the same digits in both runs.  Of the 20 records
(10 seeds, healthy and drift), 4 have the served correction switch to a fallback model; E_Y test
RMSE in µm (one test cycle of 1441 rows), the rows where C = served (every target within 1e-9
µm), the largest |C - served| from the first switch on, the first flag:

| record | fallback served | fixed | served adaptive | C before | C now |
|---|---|---|---|---|---|
| healthy s8541 | T_amb, rows 732-737 | 13.875 | 13.861 | 13.875 | 13.861 |
| drift s8541 | T_amb, rows 732-735 | 121.539 | 79.913 | 79.915 | 79.913 |
| healthy s8549 | T_front3, rows 734-736 | 11.437 | 11.500 | 11.437 | 11.500 |
| drift s8549 | T_amb, rows 734-738 | 94.933 | 60.040 | 59.593 | 59.593 |

| record | rows C = served | max abs(C - served) from the switch, µm | flag | pack rows |
|---|---|---|---|---|
| healthy s8541 | 1435 -> 1441 | 3.7 -> 3.1e-13 | FALLBACK@732 -> none | 731 -> 1441 |
| drift s8541 | 1437 -> 1441 | 3.3 -> 4e-13 | FALLBACK@732 -> none | 731 -> 1441 |
| healthy s8549 | 1437 -> 1441 | 37 -> 2.3e-13 | FALLBACK@734 -> none | 733 -> 1441 |
| drift s8549 | 1318 -> 1323 | 56 -> 56 | FALLBACK@734 -> STEPPED@1082 | 733 -> 1081 |

The C now equals the served corrections on every row of 3 of the 4 (before none), and on the
fourth (s8549 drift) to row 1081, where a stepped self-prediction error fires (no rule of this
slice; the 56 µm are after it).  No ``FALLBACK`` flag is left (before 4).  Over the 20 records:
C = served on every row of 15 (before 12), on 28287 of 28820 rows (before 28268), the pack keeps
27141 rows (before 24665); the other 16 records' rows, flags and RMSE as before.

Other families, ``MODEL``, on the found seeds (healthy; before -> now; the switch as MLR's):

| record | fallback | rows C = served | max abs(C - served) after it, µm | E_Y C (served), µm | pack rows |
|---|---|---|---|---|---|
| lagbank s8541 | lags of its own | 1441 | 1.3e-12 | 31.300 (31.300) | 1441 |
| lagbank s8549 | lags of its own | 1441 | 4.8e-13 | 21.720 (21.720) | 1441 |
| hammerstein s8541 | another power | 1434 -> 1441 | 24 -> 1.3e-12 | 31.331 -> 31.300 (31.300) | 731 -> 1441 |
| hammerstein s8549 | its powers | 1436 -> 1441 | 60 -> 3.7e-13 | 26.146 -> 26.086 (26.086) | 733 -> 1441 |
| auto s8541 | an lstm member | 1435 -> 1441 | 1.3 -> 6.5e-13 | 13.297 -> 13.298 (13.298) | 731 -> 1441 |
| auto s8549 | an lstm member | 1437 -> 1441 | 39 -> 6.5e-13 | 11.205 -> 11.272 (11.272) | 733 -> 1441 |

(lagbank "before" not run; its fallbacks, like every one, flagged on main.)  CPU: lagbank 17.6 s,
hammerstein 32.2 s (before 28.1 s), auto 52.6 s (before 55.7 s) for the two records.  arx on
s8541 serves no fallback (C = served, 2e-13 µm).  The first Hammerstein fallback (s8541) keeps a
square the model's fit dropped: its power appended to the system's.  Left flagged: a fallback
with an arx_rf forest, an lstm network of another shape than the model's, other inputs or
derived inputs, a cascade of lags, or a state times the inputs' rises (none on these records).

Found besides (the served monitor, not the code): s8546 healthy, ``T_left1`` and ``T_left3`` out
as a drift at row 731 (Q3 setting in) and back only at 1247, the served E_Y 71.260 µm against
the fixed model's 16.489 (4.3x) on a healthy record; the C follows it (C = served on every row).

What remains: the served rule "a drift beyond the band with a sensor out already" (s8546
healthy's flag at row 761: a new thermal state declared with the pair out; traced, not in the
code: ``_explaining``, ``_lone_fault`` and the veto's ``_resolves`` with one sensor out need the
POD operator of a set with two or three out, of which the code holds only the blind pairs; all
of them would be n (n - 1) / 2 more n x n operators, 190 for these 20 sensors).

No bar: the served monitor is unchanged; the code is measured against it.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _ccode import built, deployed_on, rmse, streamed  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402
from bench_cmon82 import _first_flag, _planted, _sensor  # noqa: E402

SEEDS = "8541-8550"
SIM = "column_moving_source"


def _served_fallback(deployed, frame) -> np.ndarray:
    """Per row the sensor whose fallback gives the served correction (None: the model)."""
    X = frame[deployed.columns_].to_numpy(float)
    t = frame["time"].to_numpy(float)
    deployed.reset()
    out = []
    for x, tt in zip(X, t):
        deployed._step(x, tt)
        out.append(deployed._fallen_back(x[deployed._mon]))
    deployed.reset()
    return np.array(out, dtype=object)


def _spans(fallen: np.ndarray) -> str:
    """``sensor@first-last`` (1-based rows) of each run of rows served by a fallback."""
    said, i = [], 0
    while i < len(fallen):
        if fallen[i] is None:
            i += 1
            continue
        j = i
        while j + 1 < len(fallen) and fallen[j + 1] == fallen[i]:
            j += 1
        said.append(f"{fallen[i]}@{i + 1}-{j + 1}")
        i = j + 1
    return " ".join(said)


def record(root: Path, seed: int, model: str = "mlr", kinds: tuple = ("healthy", "drift"),
           sim: str = SIM) -> list[str]:
    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.shell.cli import main

    data = root / f"{sim}-{seed}"
    if not (data / "campaigns.csv").is_file():
        assert main(["-q", "simulate", f"seed={seed}", f"data.path={data}", "track=false",
                     f"sim={sim}"]) == 0
    deployed, ds, test_ids = deployed_on(data, model, ("monitor.fallbacks=unobservable",))
    targets = deployed.targets_
    ss = state_space(deployed, monitor=True)
    sensor = _sensor(ss)
    out = []
    with tempfile.TemporaryDirectory(prefix="cmon83-") as tmp:
        code = built(Path(tmp) / "with", exported_files(deployed, "c"))
        cols = ["time", *ss.inputs]
        for kind in kinds:
            tests = {t: ds.campaigns[t].reset_index(drop=True) for t in test_ids}
            if kind != "healthy":
                tests = {t: _planted(df, kind, sensor) for t, df in tests.items()}
            errors, fixed, served, c1, flags, spans = [], [], [], [], [], []
            same = after = 0
            worst_after = 0.0
            for t, df in tests.items():
                errors.append(df[targets].to_numpy(float))
                fixed.append(-replay(deployed.streaming, df)[targets].to_numpy(float))
                rows = stream_rows(deployed, df, t)
                served.append(corrections(ss, rows.y))
                c1.append(streamed(code, df[cols]))
                fallen = _served_fallback(deployed, df)
                if said := _spans(fallen):
                    spans.append(f"{t}: {said}")
                gap = np.abs(c1[-1] - served[-1]).max(axis=1)
                same += int((gap < 1e-9).sum())
                on = np.flatnonzero(fallen != None)  # noqa: E711 (object array)
                if len(on):
                    after += len(gap) - on[0]
                    worst_after = max(worst_after, float(gap[on[0]:].max()))
                if (row := _first_flag(ss, df)) is not None:
                    flags.append(f"{t}@{row}")
            _, summary = conformance_pack(deployed, ss, tests)
            kept = sum(e["rows"] for e in summary["campaigns"] if "planted" not in e)
            total = sum(len(df) for df in tests.values())
            worst = max(float(np.max(np.abs(a - b))) for a, b in zip(c1, served))
            name = kind if kind == "healthy" else f"{kind} {sensor}"
            out.append(f"{name} s{seed} {model}: fallback served {'; '.join(spans) or 'never'}; "
                       f"C = served on {same}/{total} rows; max|C - served| {worst:.2g} um, "
                       f"from the first switch on {worst_after:.2g} um ({after} rows); flags "
                       f"{', '.join(flags) or 'none'}; pack rows {kept}/{total}")
            out.append("  " + "  ".join(
                f"{t}: {' / '.join(f'{rmse(errors, x)[i]:.3f}' for x in (fixed, served, c1))}"
                for i, t in enumerate(targets)) + "  (fixed / served adaptive / C)")
    return out


def fallback(root: str = "/tmp/cmon83-bench", seeds: str = SEEDS, model: str = "mlr",
             kinds: str = "healthy,drift", sim: str = SIM) -> None:
    folder = made_folder(root)
    for seed in seed_list(seeds):
        print("\n".join(record(folder, seed, model, tuple(kinds.split(",")), sim)), flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"fallback": fallback}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
