"""A drifting sensor in the exported C (cmon82, issue 34): a faulted record's corrections from the
compiled code with its sensor monitor, without it, and the served adaptive model's.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon82.py faults [ROOT] [SEEDS] [MODEL]

For each seed (default 8261-8275, not used before) ``thermocomp simulate`` (the default
``yearround_spindle``, healthy) into ``ROOT`` (default ``/tmp/cmon82-bench``), MODEL (default
``mlr``) fitted on the train split and deployed adaptive as ``replay`` deploys it, exported as C
(``gcc -std=c99 -Wall -Wextra -Werror -O2``) once with the monitor (``export.format=c``) and once
without it.  One fault planted on every test campaign from its middle row (the train split
untouched, one fit per seed): ``drift``, ``T_motor2`` reads ``+DRIFT_K_H`` K per hour more from
there to the end (a thermocouple's junction ageing, a loosened clamp), as the stranger benches'
``_faults.four_faults`` plant it.

Prints per record the test RMSE (µm, pooled over the test campaigns) per target: fixed (the
plain stream), the served adaptive model, the C without and with its monitor, the largest |C
with monitor - served| over every row, the served monitor's drift exclusions (per campaign: its
row, and the re-admissions), the first row where the code's monitor flagged a rule it does not
hold (per campaign, with the rule) and the conformance pack's rows kept of all (the copies it
plants on the first test campaign listed apart).

This changes no rule of auto / diagnose / monitor (the served monitor is as shipped): the code
is measured against it, so no bar is written.
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


def _planted(frame: pd.DataFrame) -> pd.DataFrame:
    out = frame.copy()
    half = len(out) // 2
    t = out["time"].to_numpy(float)
    out[SENSOR] = out[SENSOR] + np.clip(t - t[half], 0.0, None) / 3600.0 * DRIFT_K_H
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


def record(root: Path, seed: int, model: str = "mlr") -> list[str]:
    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.shell.cli import main

    data = root / f"healthy-{seed}"
    if not (data / "campaigns.csv").is_file():
        assert main(["-q", "simulate", f"seed={seed}", f"data.path={data}", "track=false"]) == 0
    deployed, ds, test_ids = deployed_on(data, model)
    targets = deployed.targets_
    ss = state_space(deployed, monitor=True)
    out = []
    with tempfile.TemporaryDirectory(prefix="cmon82-") as tmp:
        with_mon = built(Path(tmp) / "with", exported_files(deployed, "c"))
        without = built_without_monitor(Path(tmp) / "without", deployed)
        cols = ["time", *ss.inputs]
        tests = {t: _planted(ds.campaigns[t].reset_index(drop=True)) for t in test_ids}
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
        out.append(f"drift s{seed} {model}: pack rows {kept}/{total}; max|C monitor - served| "
                   f"{worst:.2e} um; flags {', '.join(flags) or 'none'}; planted: "
                   f"{', '.join(plants)}")
        out.append(f"  served: {'; '.join(moves) or 'no exclusion'}")
        for i, t in enumerate(targets):
            f, s, c0, c1 = (rmse(errors, x)[i] for x in (fixed, served, code0, code1))
            out.append(f"  {t}: fixed {f:.3f}  served adaptive {s:.3f}  C without monitor "
                       f"{c0:.3f}  C with monitor {c1:.3f}")
    return out


def faults(root: str = "/tmp/cmon82-bench", seeds: str = SEEDS, model: str = "mlr") -> None:
    folder = made_folder(root)
    for seed in seed_list(seeds):
        print("\n".join(record(folder, seed, model)), flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"faults": faults}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
