"""The sensor monitor in the exported C (cmon76, issue 34): a faulted record's corrections from the
compiled code with its monitor, without it, and the served adaptive model's.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon76.py faults [ROOT] [SEEDS]

For each seed (default 7696-7700) and fault kind (``freeze``, ``jump``: the simulator's
``sensor_faults`` effect on ``T_motor2``, every test campaign, the default ``yearround_spindle``),
``thermocomp simulate`` into ``ROOT`` (default ``/tmp/cmon76-bench``), MLR fitted on the train
split and deployed adaptive as ``replay`` deploys it, exported as C (``gcc -O2``) once with the
monitor (``export.format=c``) and once without it (the code before cmon76), each test campaign
streamed through both builds.  Prints per record the test RMSE (µm, pooled over the test
campaigns) per target: fixed (the plain stream), the served adaptive model, the C without and
with its monitor, the largest |C with monitor - served| over every row, and the conformance
pack's rows kept of all (the cut: the first row where the code's monitor parts from the
served one; the faults the pack plants on the first test campaign, listed apart).

This changes no rule of auto / diagnose / monitor (the served monitor is as shipped): the code
is measured against it, so no bar is written; the figures are in docs/to-the-machine.md.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _ccode import built, built_without_monitor, deployed_on, rmse, streamed  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402

SEEDS = "7696-7700"
KINDS = ("freeze", "jump")


def record(root: Path, seed: int, kind: str) -> str:
    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.shell.cli import main

    data = root / f"{kind}-{seed}"
    fault = ("sim.generator.effects=[sensor_faults]",
             f"sim.generator.effect_params.sensor_faults.kind={kind}",
             "sim.generator.effect_params.sensor_faults.column=T_motor2")
    if not (data / "campaigns.csv").is_file():
        assert main(["-q", "simulate", *fault, f"seed={seed}", f"data.path={data}",
                     "track=false"]) == 0
    deployed, ds, test_ids = deployed_on(data, "mlr")
    tests = {k: ds.campaigns[k].reset_index(drop=True) for k in test_ids}
    targets = deployed.targets_
    ss = state_space(deployed, monitor=True)
    with tempfile.TemporaryDirectory(prefix="cmon76-") as tmp:
        with_mon = built(Path(tmp) / "with", exported_files(deployed, "c"))
        without = built_without_monitor(Path(tmp) / "without", deployed)
        cols = ["time", *ss.inputs]
        errors, fixed, served, code0, code1 = [], [], [], [], []
        for k, df in tests.items():
            errors.append(df[targets].to_numpy(float))
            fixed.append(-replay(deployed.streaming, df)[targets].to_numpy(float))
            served.append(corrections(ss, stream_rows(deployed, df, k).y))
            code0.append(streamed(without, df[cols]))
            code1.append(streamed(with_mon, df[cols]))
    _, summary = conformance_pack(deployed, ss, tests)
    listed = [e for e in summary["campaigns"] if "planted" not in e]
    kept = sum(e["rows"] for e in listed)
    total = sum(len(df) for df in tests.values())
    cuts = [f"{e['campaign']}@{e['cut']['row']}" for e in listed if e["cut"]]
    plants = [f"{e['campaign']} {e['rows']} rows, cut {e['cut']['row'] if e['cut'] else 'none'}"
              for e in summary["campaigns"] if "planted" in e]
    worst = max(float(np.max(np.abs(a - b))) for a, b in zip(code1, served))
    lines = [f"{kind} s{seed}: pack rows {kept}/{total}, cuts {', '.join(cuts) or 'none'}; "
             f"max|C monitor - served| {worst:.2e} um; planted: {'; '.join(plants)}"]
    for i, t in enumerate(targets):
        f, s, c0, c1 = (rmse(errors, x)[i] for x in (fixed, served, code0, code1))
        lines.append(f"  {t}: fixed {f:.3f}  served adaptive {s:.3f}  C without monitor {c0:.3f}"
                     f"  C with monitor {c1:.3f}")
    return "\n".join(lines)


def faults(root: str = "/tmp/cmon76-bench", seeds: str = SEEDS) -> None:
    folder = made_folder(root)
    for seed in seed_list(seeds):
        for kind in KINDS:
            print(record(folder, seed, kind), flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"faults": faults}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
