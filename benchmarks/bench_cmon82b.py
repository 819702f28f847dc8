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
    deployed, ds, test_ids = deployed_on(data, model)
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
