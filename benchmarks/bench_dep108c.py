"""The correction guard's following bound for a model whose gain depends on the campaign's
ambient (stop 108, dep108c; issue 34 "deployed as scored").

diag108b traced climate room 10158 E_X: diagnosed (level law + a lag), batch test 0.950 µm, the
plain stream 1.089, deployed (adaptive) 1.955: the guard's bound stays at 67.04 µm on all 304 test
rows, since ``adaptive.input_gains`` asks ``step_gain`` with no state and an ambient law's gain
needs the campaign's initial ambient A0 (None -> a row of 0: the bound does not follow the inputs).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep108c.py families OUT          # which model x wrapper gets no guard gain
    python benchmarks/bench_dep108c.py simulate ROOT SEEDS    # fresh planted draws (KINDS below)
    python benchmarks/bench_dep108c.py rows OUT DATA...       # the CLI's diagnose: deployed vs batch
    python benchmarks/bench_dep108c.py code DATA TARGET OUT   # C vs served, the diagnosed model

``families``: a made room (six campaigns, four sensors on one source, ambient 14-26 °C, the error
with a level law ``0.4 (A0 - 20)`` per K of the inputs' rise) fitted with every family (mlr pcr arx
lagbank lstm) x wrapper (none; ``ati=cmeans`` with its ambient interaction; per-interval: cmeans,
two intervals, no interaction), deployed as replay deploys it: per target whether the guard's gain
row is 0 and whether the model has a step gain at the training campaigns' A0s.  ``rows``: ``thermocomp
diagnose`` as a user runs it on each DATA, per target the deployed ``test_rmse``, the batch
``test_rmse_as_run`` and the rows guarded.  ``code``: DATA's after-model (the CLI's composition,
bench_diag108b's ``stream``) exported as C, built (tests/cbuild.py), fed the test campaigns: max
|C - served| (µm).

BAR (written and committed before the change was measured; not to move):
  G1. 10158 planted E_X deployed (the CLI's after.test_rmse) within 10 % of its unguarded figure
      (the plain stream, 1.089 µm by diag108b): <= 1.198 µm.
  G2. no seen draw x target of bench_diag108b's 32 rows (10158, 10160, 10161, 10173-10177 x
      planted / clean) deployed worse than BASE (c117135c) by > 1 %.
  G3. the guard's own tests (grep tests for CorrectionGuard / guard) pass; a fault the guard must
      cap (test_deployed_guarded, test_adaptive_deploy) is still capped.
  G4. C and served equal on the diagnosed model (10158 planted after-model): |C - served| <= 1e-9 µm.
  G5. fresh 10192-10194, planted, kinds named now: 10192 climate_lag, 10193 climate_hydraulic,
      10194 climate_position (bench_diag107d's climate kinds), scored once: deployed / batch ratio
      no worse than BASE on any target.
  Verdict: KEPT when G1-G5 hold; else REFUSED (src reverted, benchmarks/dep108c_rule.patch kept).

MEASURED (2026-12-07, bar 9d128198 committed first; BASE = c117135c's src, the rule a37deb6e's;
2 shared cores, load 6-13; deterministic figures, CPU user + sys by ``/usr/bin/time`` / the CLI
children's rusage).  Seeds drawn: fresh 10192-10194 only (simulated once, scored once).
  Today's gap (``families``, BASE, 16.6 + 1.1 s CPU): every ``ati`` and per-interval wrapper of mlr,
  pcr, arx and lagbank gives a guard row of 0 on both targets (no gain without A0, a gain at 5/5
  training A0s); ``none`` of those has its gain; lstm has none anywhere (0, before and after).  The
  diagnosed level law: 10158 E_X (diag108b).  The rule: every ATI / per-interval row has a gain
  (max 2.6-47.8 on E_X), the ``none`` rows unchanged to the printed digit, lstm 0.
  G1 (``bench_diag108b.py stream``, 9.9 s CPU): 10158 planted E_X deployed 1.955 -> 1.0823 µm
      (<= 1.198; batch 0.9500, plain stream 1.089), rows guarded 304 -> 27.  Met.
  G2 (``rows`` on the 16 seen draws, BASE and rule): 31 of 32 rows deployed equal to the last
      digit, 10158 planted E_X -44.6 %; worst change 0.0 %.  Met.
  G3 the guard's tests and their neighbours (48 modules) pass: see the report.
  G4 (``code``, 8.9 s CPU): max |C - served| 2.84e-14 µm over the 4 test campaigns (2261 rows).  Met.
  G5 (``rows`` on 10192 climate_lag, 10193 climate_hydraulic, 10194 climate_position, planted):
      deployed / batch 1.0000 on all 6 targets, BASE and rule equal to the last digit (an ambient
      law accepted on 5 of 6 targets; no test row guarded either way).  Met.
"""

from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag106 as d106  # noqa: E402
import bench_diag107 as d107  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402

# the fresh seeds' kinds, named before any was drawn (bench_diag107d's climate kinds)
KINDS = {
    10192: ("climate_lag", d107.LAG),
    10193: ("climate_hydraulic", d107.HIDDEN),
    10194: ("climate_position", ["sim.generator.effects=[axis_position]"]),
}
FAMILIES = ("mlr", "pcr", "arx", "lagbank", "lstm")
WRAPPERS = {"none": (), "ati": ("ati=cmeans",),
            "per-interval": ("ati=cmeans", "ati.estimator.n_intervals=2",
                             "ati.estimator.ambient_interaction=false")}


def _room(root: Path) -> Path:
    """Six campaigns (five train, one test), ambient 14-26 °C, one heat source; E_X with a level
    law in A0 (the inputs' rise times ``0.4 (A0 - 20)``) and E_Z without."""
    root.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(108)
    splits = ["train"] * 5 + ["test"]
    for i, split in enumerate(splits):
        amb, power = 14.0 + 2.4 * i, (9.0 if split == "test" else 3.0 + 0.5 * i)
        t = np.arange(80) * 120.0
        rise, late = power * (1 - np.exp(-t / 2400)), power * (1 - np.exp(-t / 4800))
        noise = lambda: rng.normal(0, 0.03, len(t))       # noqa: E731
        f = pd.DataFrame({"time": t, "T_amb": amb + noise(), "T_a": amb + rise + noise(),
                          "T_b": amb + 0.6 * rise + noise(), "T_c": amb + 0.8 * late + noise(),
                          "T_d": amb + 0.4 * late + noise()})
        d = f - f.iloc[0]
        f["E_X"] = (3.0 + 0.4 * (amb - 20)) * d["T_a"] - d["T_b"] + rng.normal(0, 0.1, len(t))
        f["E_Z"] = 2.0 * d["T_c"] + rng.normal(0, 0.1, len(t))
        f.to_csv(root / f"K{i}.csv", index=False)
    pd.DataFrame({"campaign": [f"K{i}" for i in range(6)], "file": [f"K{i}.csv" for i in range(6)],
                  "split": splits, "notes": ""}).to_csv(root / "campaigns.csv", index=False)
    return root


def families(out: str) -> None:
    """Per family x wrapper and target: the guard's gain row 0?  A step gain at the training A0s?"""
    from hydra import compose, initialize_config_dir

    from thermocomp.base.paths import conf_dir
    from thermocomp.core.context import step_gain
    from thermocomp.core.frame import initial_ambient
    from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
    from thermocomp.shell.source import read_streamed

    data = _room(made_folder(out) / "room")
    for fam in FAMILIES:
        for wrap, words in WRAPPERS.items():
            with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
                cfg = compose(config_name="config", overrides=[
                    f"data.path={data}", "track=false", "monitor.adaptive=true", f"model={fam}", *words])
            ds, train_ids, _, _ = read_streamed(cfg)
            train = {c: ds.campaigns[c] for c in train_ids}
            stream = deploy_stream(cfg, build_compensator(cfg, ds=ds).fit(train), train)
            dep = deployable(cfg, stream, train, ds)
            g = getattr(dep, "guard", None)
            for k, (t, est, _) in enumerate(stream._plan):
                row = None if g is None or g.in_gain is None else g.in_gain[k]
                at = []
                for df in train.values():
                    state = est.stream_init({"campaign": "s", "time": 0.0,
                                             "ambient_c0": initial_ambient(df)})
                    at.append(step_gain(est, state, stream.envelope.horizon_s))
                none = step_gain(est, None, stream.envelope.horizon_s) is None
                print(f"{fam:8s} {wrap:13s} {t}: {type(est).__name__:18s} gain without A0 "
                      f"{'None' if none else 'set'}; at the training A0s "
                      f"{sum(a is not None for a in at)}/{len(at)}; guard row "
                      f"{'none' if row is None else ('ZERO' if not row.any() else 'max %.3g' % row.max())}",
                      flush=True)


def simulate(root: str, seeds: str) -> None:
    """Each fresh seed's planted draw (bench_diag106c's simulation, :data:`KINDS`) -> ROOT/<case>."""
    logs = made_folder(str(Path(root) / "logs"))
    for seed in seed_list(seeds):
        kind, words = KINDS[seed]
        data = Path(root) / f"{kind}-planted-{seed}"
        if not data.exists():
            d106._thermocomp(["simulate", *d106.CLIMATE, f"seed={seed}", f"data.path={data}", "track=false",
                              *words], logs / f"{data.name}-simulate.log")
        print(data)


def rows(out: str, *datas: str) -> None:
    """The CLI's diagnose of each DATA: per target deployed, batch, their ratio, rows guarded."""
    folder = made_folder(out)
    with open(folder / "rows.jsonl", "w") as f:
        for data in datas:
            case = Path(data).name
            target_out = folder / "out" / case
            cpu = d106._thermocomp(["diagnose", f"data.path={data}", f"out={target_out}", "plots=none",
                                    "track=false"], made_folder(str(folder / "logs")) / f"{case}.log")
            for p in sorted((target_out / "diagnosis").glob("diagnosis_*.json")):
                j, t = json.loads(p.read_text()), p.stem.removeprefix("diagnosis_")
                a = j["after"]
                row = {"case": case, "target": t, "deployed": a["test_rmse"], "batch": a["test_rmse_as_run"],
                       "guarded": a.get("test_rows_guarded"), "guarded_before": j["before"].get(
                           "test_rows_guarded"), "cpu_s": cpu}
                print(json.dumps(row), file=f, flush=True)
                print(f"{case:34s} {t}: deployed {row['deployed']:.4f} batch {row['batch']:.4f} "
                      f"ratio {row['deployed'] / row['batch']:.4f} guarded {row['guarded_before']} -> "
                      f"{row['guarded']}", flush=True)


def code(data: str, target: str, out: str) -> None:
    """DATA's after-model (the CLI's), adaptive as the CLI scores it: the C against served."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    from cbuild import compiled  # noqa: I001 (tests/ on the path first)
    from thermocomp.apps.deploy.export import exported_files
    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.apps.diagnose import diagnose
    from thermocomp.shell.builders import build_compensator, deploy_stream, deployable, search_options
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.source import open_source
    from thermocomp.shell.stages import diagnose as stage

    cfg = compose([f"data.path={data}", "plots=none", "track=false"], "diagnose")
    ds = open_source(cfg)
    inner, kept = stage._deployed_of(cfg, ds), {}

    def deployed_of(comp, train, ids):
        kept["before" if "before" not in kept else "after"] = (comp, train, ids)
        return inner(comp, train, ids)

    diagnose(ds, build_compensator(cfg), None, str(cfg.eval.mode), search_options(cfg.diagnose), None,
             deployed_of=deployed_of)
    comp, train, ids = kept["after"]
    dep = deployable(cfg, deploy_stream(cfg, comp, train), train, ds)
    folder = made_folder(out)
    for name, text in exported_files(dep, "c").items():
        (folder / name).write_text(text)
    binary = compiled(folder)
    worst = 0.0
    for c in ids:
        df = ds.campaigns[c]
        served = replay(dep, df)[dep.targets_].to_numpy(float)
        text = df[["time", *dep.columns_]].to_csv(index=False, float_format="%.17g")
        run = subprocess.run([str(binary)], input=text, text=True, capture_output=True, check=True)
        got = -pd.read_csv(io.StringIO(run.stdout)).to_numpy(float)
        k = dep.targets_.index(target)
        diff = float(np.max(np.abs(got - served)))
        worst = max(worst, diff)
        g = dep.guard
        print(f"{c}: max |C - served| {diff:.3g} µm over {len(df)} rows; {target} guard row "
              f"{np.round(g.in_gain[k], 3) if g.in_gain is not None else None}")
    print(f"max |C - served| {worst:.3g} µm")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"families": families, "simulate": simulate, "rows": rows, "code": code},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
