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

The second rule (``paired``), written down after the first was scored (below) and before it
was scored itself: the same, but "within one standard error" judged PAIRED, as the search judges
candidates -- the largest penalty whose CV MSE exceeds the least one by at most the standard error
of the mean over the test blocks of ITS blocks' MSE minus the best penalty's.  The blocks share
their difficulty across penalties (a hot block is hard at every penalty); the unpaired error
counts that spread as doubt about the penalty, the paired one does not.
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

VARIANTS = ["before", "after", "paired"]
MACHINES = {"om": ["lathe43", "lathe43m", "rig40", "vendor5"],
            "nm56": ["grinder", "grinder-nocoolant", "gantry", "gantry-noY"],
            "nm57": ["boring_mill", "boring_mill-noW", "twin_lathe", "twin_lathe-noair"]}
CASES = memory.CASES + [f"machine:{n}" for names in MACHINES.values() for n in names]
SHIPPED_PICK = CrossValidator.pick_penalty


def least_error(self, mse, block_mse) -> int:
    """``before``: the penalty of least CV MSE (ties: the smallest)."""
    return int(np.argmin(mse))


def paired_one_se(self, mse, block_mse) -> int:
    """``paired``: the largest penalty within one paired standard error of the least CV MSE."""
    mse, block_mse = np.asarray(mse, float), np.asarray(block_mse, float)
    best, n = int(np.argmin(mse)), block_mse.shape[0]
    if n < 2:
        return best
    d = block_mse - block_mse[:, [best]]
    return int(np.flatnonzero(mse - mse[best] <= d.std(axis=0, ddof=1) / np.sqrt(n)).max())


def variant(name: str):
    CrossValidator.pick_penalty = {"before": least_error, "paired": paired_one_se}.get(name, SHIPPED_PICK)


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


def forensics(root: Path, name: str = "twin_lathe") -> None:
    """The accepted lag of every target of ``machine:NAME`` (as shipped before): its gain per
    test block (time, in-range rows, gain there), the bar's quantities, and per penalty the CV
    RMSE, the blocks' standard error, the last block's RMSE and the TEST RMSE of the same
    effects (trained on the train split by the CV code, as ``penalty:SEED`` of
    ``bench_diagnose_memory``), the largest coefficients at the least-error and one-SE penalties."""
    import thermocomp.apps.diagnose.cv as cv_module
    from thermocomp.apps.diagnose.cv import Problem
    from thermocomp.apps.diagnose.search import Search, _pct
    from thermocomp.apps.diagnose.shrink import ALPHAS, PartialRidgePath, one_se_penalty
    from thermocomp.core.frame import stack

    ds, comp, options = machine_data(root, name)
    shipped, seen = Search._family_bar, []

    def recording(self, evals, current):
        shipped(self, evals, current)
        seen.append((self, list(evals), current))

    variant("before")
    Search._family_bar = recording
    try:
        d = diagnose(ds, comp, None, "simulation", options)
    finally:
        Search._family_bar = shipped
        variant("after")
    before = d.before_model
    train, test = d.cv["train_campaigns"], d.cv["test_campaigns"]
    m = stack({c: ds.campaigns[c] for c in train + test}, before.inputs_, before.targets_, before.reference)
    groups = np.asarray(m.groups, dtype=object)
    for search, evals, current in seen:
        ev = next((e for e in evals if e.accepted and e.effect.kind == "dynamics"), None)
        if ev is None:
            continue
        p, t = search.problem, search.problem.target
        print(f"{t}: {ev.effect.title}: CV gain {ev.gain_pct:.1f} %, in range {ev.gain_pct_in_range:.1f} %, "
              f"p family {ev.p_family:.2g}, 99 % bound {_pct(ev.gain_lcb_alpha, current.rmse):.1f} %, "
              f"penalty {ev.alpha:g}, {ev.n_features} features; {p.n_units} folds in "
              f"{p.n_blocks_tested} test blocks (ranked: {p.n_blocks_tested > p.n_units}), "
              f"units_trained {p.units_trained} (saturates: {search.saturates(ev.n_features)})")
        hours, inside = p.context["time"].to_numpy(float) / 3600, p.in_range
        r0, r1 = current.residual, ev.result.residual
        for b in range(p.n_blocks_tested):
            rows = p.block_index == b
            ins = rows & inside
            gain_in = 100 * (1 - np.mean(r1[ins] ** 2) / np.mean(r0[ins] ** 2)) if ins.any() else np.nan
            print(f"  block {b:2d}  day {int(hours[rows][0] // 24)} {hours[rows][0] % 24:4.1f} h  RMSE "
                  f"{np.sqrt(np.mean(r0[rows] ** 2)):.3f} -> {np.sqrt(np.mean(r1[rows] ** 2)):.3f}  "
                  f"gain {100 * (1 - np.mean(r1[rows] ** 2) / np.mean(r0[rows] ** 2)):+5.1f} %  in range "
                  f"{ins.sum()}/{rows.sum()}, gain there {gain_in:+5.1f} %")
        names = search.cv.selection(search.inputs(), None)
        effects = search.effects[:search.effects.index(ev.effect) + 1]
        err = np.full((len(p.y), ALPHAS.size), np.nan)
        for k in p.fold_ids:
            tr, te = p.train_rows(k), p.test_rows(k)
            Z = search.cv.design(search.cv.selection(search.inputs(), k), effects, k)
            fit = PartialRidgePath(Z[tr], p.y[tr], len(names))
            err[te] = (p.y[te, None] - fit.predict(Z[te], ALPHAS)) ** 2
        mse, blocks = np.nanmean(err, axis=0), search.cv._block_mse(err)
        held = Problem(m.X, m.Y[t].to_numpy(float), m.context, groups, groups, t,
                       reference=before.reference, n_folds=2)
        scored = np.isin(groups, test)
        held.folds, held.validated, held.unit_names = np.where(scored, 0, -1), scored, list(test)
        held.unit_index = held.block_index = np.array([test.index(c) if ok else -1
                                                       for c, ok in zip(groups, scored)])
        tester = CrossValidator(held, comp.estimator)
        print(f"  no effect: test RMSE {tester.run(search.inputs(), effects[:-1]).rmse:.4f}")
        for i, alpha in enumerate(ALPHAS):
            cv_module.ALPHAS = np.array([alpha])
            try:
                on_test = tester.run(search.inputs(), effects).rmse
            finally:
                cv_module.ALPHAS = ALPHAS
            print(f"  penalty {alpha:7.1e}  CV RMSE {np.sqrt(mse[i]):.4f}  blocks' SE of MSE "
                  f"{blocks[:, i].std(ddof=1) / np.sqrt(len(blocks)):.4f}  last block "
                  f"{np.sqrt(blocks[-1, i]):.3f}  test RMSE {on_test:.4f}")
        Z = search.cv.design(names, effects)
        path = PartialRidgePath(Z, p.y, len(names))
        for label, i in (("least error", int(np.argmin(mse))), ("one SE", one_se_penalty(mse, blocks))):
            coef, _ = path.coefficients(ALPHAS[i])
            top = np.argsort(-np.abs(coef))[:4]
            cols = list(names) + [f"lag {c}" for c in names] * len(effects)
            print(f"  {label} ({ALPHAS[i]:g}): largest |coef| (µm/K)",
                  [(cols[j], round(float(coef[j]), 2)) for j in top])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", nargs="*")
    parser.add_argument("--root", type=Path, default=Path("/tmp/bench_diagnose_lag57"))
    args = parser.parse_intermixed_args(argv)
    what = list(args.what)
    if what[:1] == ["write"]:
        write(args.root.resolve() if len(what) < 2 else Path(what[1]).resolve())
        return 0
    if what[:1] == ["forensics"]:
        forensics(args.root.resolve(), *what[1:])
        return 0
    memory.print_rows(what, VARIANTS, CASES, lambda c, v: row(c, v, args.root.resolve()))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
