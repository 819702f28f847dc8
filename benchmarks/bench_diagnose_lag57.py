"""The twin lathe's 4 h lag (``bench_new_machines57``): where its CV gain came from, why no bar
stopped it, and the penalty rule that keeps its gain without its harm (issue 34, item 4).

Usage::

    python benchmarks/bench_diagnose_lag57.py write ROOT       # the three benches' records + init
    python benchmarks/bench_diagnose_lag57.py [before,after] [CASE ...] [--root ROOT]
    # CASE: bench_diagnose_memory's (planted:SEED, clean:SEED, scenario, record) or
    # machine:NAME (lathe43, lathe43m, rig40, vendor5 of bench_other_machine; grinder,
    # grinder-nocoolant, gantry, gantry-noY of bench_new_machines56; boring_mill, boring_mill-noW,
    # twin_lathe, twin_lathe-noair of bench_new_machines57); none: every one
    python benchmarks/bench_diagnose_lag57.py forensics --root ROOT   # twin_lathe, per block and
                                                                      # per penalty

``before``: the penalty on the effect features of least CV MSE (as shipped up to this session);
``after``: :func:`thermocomp.apps.diagnose.shrink.one_se_penalty`.  Every case is ``diagnose``
with MLR in process (the machines with ``init``'s config, as their benches run the CLI).

The rule, written down before any case was scored
-------------------------------------------------
**One-standard-error penalty.**  Among the penalties the CV tries on the effect features, take
the LARGEST whose CV MSE is at most the least CV MSE plus one standard error of it (the standard
error of the mean of the test blocks' MSE at the least-error penalty; the blocks of
:mod:`~thermocomp.core.model_selection.blocks`).  The simplest fit the CV cannot tell from the
best (ESL 7.10, glmnet's ``lambda.1se``); the bar, the test, the candidates are unchanged: a
candidate's evidence is taken at that penalty.  Adopt only if no planted-right case is lost, no
clean acceptance is added, no record's test error is made more than 2 % worse, the known real
gains are kept (vendor5's ambient law, gantry's yaw and 4 h lag, boring_mill's W x rises).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "apps"))

import bench_diagnose_memory as memory  # noqa: E402

from thermocomp.apps.diagnose import diagnose  # noqa: E402
from thermocomp.apps.diagnose.cv import CrossValidator  # noqa: E402

VARIANTS = ["before", "after"]
MACHINES = {"om": ["lathe43", "lathe43m", "rig40", "vendor5"],
            "nm56": ["grinder", "grinder-nocoolant", "gantry", "gantry-noY"],
            "nm57": ["boring_mill", "boring_mill-noW", "twin_lathe", "twin_lathe-noair"]}
CASES = memory.CASES + [f"machine:{n}" for names in MACHINES.values() for n in names]
SHIPPED_PICK = CrossValidator.pick_penalty


def least_error(self, mse, block_mse) -> int:
    """``before``: the penalty of least CV MSE (ties: the smallest)."""
    return int(np.argmin(mse))


def variant(name: str):
    CrossValidator.pick_penalty = least_error if name == "before" else SHIPPED_PICK


def write(root: Path) -> None:
    import bench_new_machines56 as nm56
    import bench_new_machines57 as nm57
    import bench_other_machine as om
    om.write(root / "om")
    status, *_ = om.thermocomp("init", str(root / "om" / "lathe43"), "data.max_gap_samples=2",
                               f"out={root}/om/init")
    assert status == 0
    for bench, sub in ((nm56, "nm56"), (nm57, "nm57")):
        bench.write(root / sub)
        for name, extra in bench.INIT_ARGS.items():
            status, *_ = bench.thermocomp("init", str(root / sub / name), *extra,
                                          f"out={root}/{sub}/init-{name}")
            assert status == 0, name


def machine_args(root: Path, name: str) -> list[str]:
    """The overrides its bench gives ``thermocomp diagnose`` (minus the CLI's quiet ones)."""
    import bench_new_machines56 as nm56
    import bench_new_machines57 as nm57
    import bench_other_machine as om
    sub = next(s for s, names in MACHINES.items() if name in names)
    bench = {"om": om, "nm56": nm56, "nm57": nm57}[sub]
    return bench.data_args(root / sub, name)


def machine_data(root: Path, name: str):
    """(dataset, compensator, search options) of ``machine:NAME``, as ``thermocomp diagnose``."""
    from thermocomp.shell.builders import build_compensator
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.source import open_source
    from thermocomp.shell.stages.diagnose import search_options

    cfg = compose(machine_args(root, name), "diagnose")
    return open_source(cfg), build_compensator(cfg), search_options(cfg.diagnose)


def machine_row(root: Path, name: str, variant_name: str) -> dict:
    variant(variant_name)
    try:
        ds, comp, options = machine_data(root, name)
        d = diagnose(ds, comp, None, "simulation", options)
    finally:
        variant("after")
    out = {}
    for t in d.targets:
        j = d.to_json(t)
        out[t] = {"accepted": [f'{e["kind"]} {e["column"]} {e["transform"]}' for e in j["effects"]
                               if e["accepted"]],
                  "test_rmse": [round(j["before"]["test_rmse"], 4), round(j["after"]["test_rmse"], 4)],
                  "shrink_alpha": j["cv"]["shrink_alpha"][t]}
    return {"case": f"machine:{name}", "variant": variant_name, "targets": out}


def row(case: str, variant_name: str, root: Path) -> dict:
    if case.startswith("machine:"):
        return machine_row(root, case.split(":", 1)[1], variant_name)
    variant(variant_name)
    try:
        return memory.row(case, "shipped") | {"variant": variant_name}
    finally:
        variant("after")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", nargs="*")
    parser.add_argument("--root", type=Path, default=Path("/tmp/bench_diagnose_lag57"))
    args = parser.parse_args(argv)
    what = list(args.what)
    if what[:1] == ["write"]:
        write(args.root.resolve() if len(what) < 2 else Path(what[1]).resolve())
        return 0
    memory.print_rows(what, VARIANTS, CASES, lambda c, v: row(c, v, args.root.resolve()))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
