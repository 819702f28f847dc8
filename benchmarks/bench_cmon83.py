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
