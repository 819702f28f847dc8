"""The envelope's pattern gate on its edge: its price across records (stop 77, gate77; issue 34).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_gate77.py price ROOT RECORD FAMILY   # one record -> ROOT/price.jsonl
    python benchmarks/bench_gate77.py faults ROOT RECORD FAMILY  # sensor faults in its test part
    python benchmarks/bench_gate77.py candidate ROOT RECORD FAMILY  # a rank-robust tol, explored
    python benchmarks/bench_gate77.py table ROOT                 # the rows written, summarised

RECORD is ``tcm74:SEED`` (bench_stranger74's ``write ROOT SEED 24 60``: 22 sensors, one record
cut 70/30), ``cms:SEED`` (``column_moving_source``: a heat source training never saw, the gate's
reason to exist), ``mill:SEED`` (``large_mill_week``'s train week as one file cut 90/10),
``year:SEED`` (``yearround_spindle``, its summer campaigns K10-K16 held out, bench_envelope_policy's
split), ``gantry:SEED`` (``benchmarks/gantry76.py`` written as a contract folder, its last two runs
the test), ``fl90`` (``data=fl_thermal``, 90/10) or ``fl602020`` (its authors' 60/20/20 split).

``price``: the config's chain fitted once (``fit_chain``, ``model=FAMILY``), its test figures as
run (``score``, simulation) and as deployed by promote's own steps (``diagnose``'s
``_deployed_of``: ``deploy_stream`` -> ``deployable``, the adaptive compensator with its monitor and
guard, ``stream_scores`` of the test campaigns warmed on what they continue) under six settings
of the envelope, the same fitted model each time: the pattern gate's rank at 99.5 / 99.9
(shipped) / 99.95 / 99.99 % of the scaled training variance (``PATTERN_ENERGY``), the pattern
off (``promote.envelope.pattern=false``: the range clamp of every excursion) and the envelope off
(``promote.envelope.policy=off``: the same deployable with no clamp; the clamp's price is
measured against it).  Per target: test RMSE per setting, clamped test rows per setting, the
gate's rank, the cumulative energy there, ``tol`` and the test rows' median residual off the
pattern.

``faults``: the shipped scenario's out-of-pattern cases the gate is for (bench_deploy_faults'
kinds, on this record): from each test campaign's middle row, a sensor reads +5 K (``offset5``),
is stuck (``stuck``) or drifts +2 K/h (``drift2``), one at a time, for the record's first, middle and
last declared input (by name: chosen before measuring, not by effect); the machine is unchanged,
so the measured errors are the truth.  Per setting: test RMSE over the faulty campaigns.

``table``: per setting, how many (record, target) rows are > 2 % worse than the envelope off and
than as run; the shipped gate against each other setting.

The records and seeds (written before any measurement, 2026-12-03; fresh 7761-7775 split):

* step 1 (this measurement): ``tcm74:7761`` .. ``tcm74:7764``, ``cms:7765``, ``cms:7766``,
  ``mill:7767``, ``year:7768``, ``gantry:7769``, ``fl90``, ``fl602020``; families ``mlr`` (every
  record) and ``lagbank`` where its CPU fits (tcm74, cms, fl90; tcm74 7763, 7764 and cms 7766
  added once the first rows were in, the same seeds);
* kept for a rule's scoring (step 2), not run in step 1: 7770-7775.

Measured 2026-12-03 (2 shared cores; ``price`` 7-43 s CPU a row, ``table`` over ROOT): the
figures are in docs/measured/to-the-machine.md, "The pattern gate's price across records".  In
short: the shipped gate > 2 % worse than the envelope off on 21 of 72 targets, > 2 % better on
23; every excursion clamped worse still (26); the rank moves 15 targets by > 2 % over
99.5-99.99 % (tcm74 7761, 7763, 7764, the gantry).  ``candidate`` (explored on step-1 records
only, no bar written): tcm74 and the gantry nearer the envelope off, still rank-dependent on
7761, and bench_deploy_faults' plain mlr on a real +5 K air step 6.46 -> 6.84 µm (run with
``streaming._pattern`` patched as ``candidate`` does): it fails the bar it would have had, so no
rule was written and 7770-7775 stay unused.
"""

from __future__ import annotations

import contextlib
import io
import json
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import made_folder, run_commands  # noqa: E402

ENERGIES = (0.995, 0.999, 0.9995, 0.9999)
SHIPPED = "e0.999"
SETTINGS = (*(f"e{e}" for e in ENERGIES), "pattern_off", "envelope_off")
SUMMER = {f"K{k:02d}": "test" for k in range(10, 17)}          # bench_envelope_policy's split
OTHERS = {k: "train" for k in ("K03", "K06", "K09", "K18", "K21", "K24")}
YEAR_SPLIT = "++data.split_overrides={" + ",".join(f"{k}:{v}" for k, v in {**OTHERS, **SUMMER}.items()) + "}"
FL = ["data=fl_thermal"]


def _quiet_cli(*args: str) -> None:
    from thermocomp.shell.cli import main

    with contextlib.redirect_stdout(io.StringIO()):
        code = main(["-q", *args])
    if code not in (0, None):
        raise RuntimeError(f"thermocomp {' '.join(args)} exited {code}")


def _simulate(folder: Path, scenario: str, seed: str) -> Path:
    out = folder / f"{scenario}{seed}"
    if not out.exists():
        _quiet_cli("simulate", f"sim={scenario}", f"seed={seed}", f"data.path={out}", "track=false")
    return out


def record(folder: Path, name: str) -> list[str]:
    """The data overrides of ``name`` (module doc), its files written under ``folder`` first."""
    kind, _, seed = name.partition(":")
    if kind == "tcm74":
        if not (folder / "conf" / "data" / f"fs{seed}.yaml").exists():
            subprocess.run([sys.executable, str(HERE / "bench_stranger74.py"), "write", str(folder), seed,
                            "24", "60"], check=True, capture_output=True)
        return [f"hydra.searchpath=[file://{folder / 'conf'}]", f"data=fs{seed}"]
    if kind == "cms":
        return [f"data.path={_simulate(folder, 'column_moving_source', seed)}"]
    if kind == "mill":
        return [f"data.path={_simulate(folder, 'large_mill_week', seed)}/train_week.csv",
                "data.test_fraction=0.1"]
    if kind == "year":
        return [f"data.path={_simulate(folder, 'yearround_spindle', seed)}", YEAR_SPLIT]
    if kind == "gantry":
        out = folder / f"gantry{seed}"
        if not out.exists():
            from gantry76 import Gantry76

            from thermocomp.apps.sim.scenario import write_scenario
            write_scenario(Gantry76(seed=int(seed)), out)
        return [f"data.path={out}", "++data.split_overrides={run5:test,run6:test}"]
    if name == "fl90":
        return list(FL)
    if name == "fl602020":
        return [*FL, "data.split_order=[train,test,val]", "data.test_fraction=0.2", "data.val_fraction=0.2"]
    raise SystemExit(f"unknown record {name!r} (module doc)")


def _setting_cfg(base: list[str], setting: str):
    import thermocomp.apps.deploy.streaming as streaming
    from thermocomp.shell.config.overrides import compose

    streaming.PATTERN_ENERGY = float(setting[1:]) if setting[1:2].isdigit() else 0.999
    extra = {"pattern_off": ["promote.envelope.pattern=false"],
             "envelope_off": ["promote.envelope.policy=off"]}.get(setting, [])
    return compose([*base, *extra])


def _fitted(folder: Path, name: str, family: str):
    """``(base overrides, cfg, ds, fitted compensator, train, test ids)``."""
    import thermocomp.shell.cli  # noqa: F401  (the config's resolvers)
    from thermocomp.core.scoring.evaluation import require_split
    from thermocomp.shell.chain import fit_chain
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.source import open_source

    base = [*record(folder, name), f"model={family}", "track=false"]
    cfg = compose(base)
    ds = open_source(cfg)
    comp = fit_chain(cfg, ds)
    train = {c: ds.campaigns[c] for c in require_split(ds, "train")}
    return base, cfg, ds, comp, train, require_split(ds, "test")


def _gate(cfg, comp, train, ds, test_ids) -> dict:
    """The shipped gate's rank, energy there, tol, and the test rows' median residual off it."""
    import thermocomp.apps.deploy.streaming as streaming
    from thermocomp.shell.builders import deploy_stream

    streaming.PATTERN_ENERGY = 0.999
    env = deploy_stream(cfg, comp, train).envelope
    if env.basis is None:
        return {"rank": None, "inputs": len(env.columns)}
    A = comp.stacked({c: ds.campaigns[c] for c in test_ids}, targets=[]).X.to_numpy(float)
    X = comp.stacked(train, targets=[]).X.to_numpy(float)
    Z = (X - env.mean) / env.scale
    s = np.linalg.svd(Z, compute_uv=False) ** 2
    rank = env.basis.shape[1]
    Zt = (A - env.mean) / env.scale
    res = np.linalg.norm(Zt - Zt @ env.basis @ env.basis.T, axis=1)
    return {"rank": rank, "inputs": len(env.columns),
            "energy_at_rank": float(np.cumsum(s)[rank - 1] / s.sum()), "tol": env.tol,
            "test_residual_median": float(np.median(res)), "test_rows": len(A),
            "test_rows_within_2pct_of_tol": int((np.abs(res / env.tol - 1) < 0.02).sum())}


def price(root: str, name: str, family: str) -> None:
    """One record's test RMSE as run and as deployed under every setting -> ROOT/price.jsonl."""
    from thermocomp.core.scoring.evaluation import score
    from thermocomp.shell.stages.diagnose import _deployed_of

    folder = made_folder(root)
    base, cfg, ds, comp, train, test_ids = _fitted(folder, name, family)
    as_run = score(comp, ds, "simulation", iso_a3=False)[0]
    row = {"record": name, "family": family, "gate": _gate(cfg, comp, train, ds, test_ids), "targets": {
        t: {"as_run": as_run[t]["test"]["rmse"]} for t in comp.targets_}, "clamped": {}}
    for setting in SETTINGS:
        scores = _deployed_of(_setting_cfg(base, setting), ds)(comp, train, test_ids)
        for t, s in scores.items():
            row["targets"][t][setting] = s["test"]["rmse"]
        row["clamped"][setting] = next(iter(scores.values()))["clamped_samples"]
    row["test_rows"] = int(sum(len(ds.campaigns[c]) for c in test_ids))
    with open(folder / "price.jsonl", "a") as out:
        print(json.dumps(row), file=out)
    print(f"  {name} {family}: gate {row['gate']}")
    print(f"    clamped rows of {row['test_rows']}: {row['clamped']}")
    for t, v in row["targets"].items():
        print(f"    {t}: as run {v['as_run']:.4g}; " + ", ".join(f"{s} {v[s]:.4g}" for s in SETTINGS))


def _faulty(df, column: str, kind: str):
    df = df.copy()
    n = len(df)
    mid = n // 2
    col = df.columns.get_loc(column)
    if kind == "offset5":
        df.iloc[mid:, col] = df.iloc[mid:, col] + 5.0
    elif kind == "stuck":
        df.iloc[mid:, col] = df.iloc[mid, col]
    elif kind == "drift2":
        t = df["time"].to_numpy(float)
        df.iloc[mid:, col] = df.iloc[mid:, col] + 2.0 * (t[mid:] - t[mid]) / 3600.0
    return df


def faults(root: str, name: str, family: str) -> None:
    """Sensor faults in the test part, every setting -> ROOT/faults.jsonl."""
    from thermocomp.shell.stages.diagnose import _deployed_of

    folder = made_folder(root)
    base, cfg, ds, comp, train, test_ids = _fitted(folder, name, family)
    inputs = sorted(c for c in comp.inputs_ if c.startswith("T_") and c in ds.campaigns[test_ids[0]].columns)
    chosen = sorted({inputs[0], inputs[len(inputs) // 2], inputs[-1]})
    healthy = {c: ds.campaigns[c] for c in test_ids}
    with open(folder / "faults.jsonl", "a") as out:
        for column in chosen:
            for kind in ("offset5", "stuck", "drift2"):
                for c in test_ids:
                    ds.campaigns[c] = _faulty(healthy[c], column, kind)
                row = {"record": name, "family": family, "sensor": column, "fault": kind, "targets": {}}
                for setting in SETTINGS:
                    scores = _deployed_of(_setting_cfg(base, setting), ds)(comp, train, test_ids)
                    for t, s in scores.items():
                        row["targets"].setdefault(t, {})[setting] = s["test"]["rmse"]
                    row.setdefault("clamped", {})[setting] = next(iter(scores.values()))["clamped_samples"]
                for c in test_ids:
                    ds.campaigns[c] = healthy[c]
                print(json.dumps(row), file=out, flush=True)
                sig = {s: float(np.sum([v[s] ** 2 for v in row["targets"].values()])) for s in SETTINGS}
                print(f"  {column} {kind}: Σ² " + ", ".join(f"{s} {v:.4g}" for s, v in sig.items())
                      + f"; clamped {row['clamped']}", flush=True)


def _heldout_of(shipped):
    """Candidate ``heldout``: ``shipped`` (the tree's ``_pattern``) with ``tol`` the largest
    residual of a training row off the subspace (same rank) fitted on the other four of five
    contiguous blocks of the training rows: a row's own fit no longer sets the edge it is
    judged by."""
    return lambda X, scale: _heldout_pattern(shipped, X, scale)


def _heldout_pattern(shipped, X: np.ndarray, scale: np.ndarray, blocks: int = 5) -> dict:
    shape = shipped(X, scale)
    if not shape:
        return shape
    rank = shape["basis"].shape[1]
    worst = 0.0
    for rows in np.array_split(np.arange(len(X)), blocks):
        rest = np.setdiff1d(np.arange(len(X)), rows)
        mean = X[rest].mean(axis=0)
        _, _, Vt = np.linalg.svd((X[rest] - mean) / scale, full_matrices=False)
        B = Vt[:rank].T
        Z = (X[rows] - mean) / scale
        worst = max(worst, float(np.linalg.norm(Z - Z @ B @ B.T, axis=1).max()))
    return {**shape, "tol": max(shape["tol"], worst)}


def candidate(root: str, name: str, family: str) -> None:
    """Candidate ``heldout`` (``_heldout_pattern``) against the shipped gate at every energy
    -> ROOT/candidate.jsonl."""
    import thermocomp.apps.deploy.streaming as streaming
    from thermocomp.shell.stages.diagnose import _deployed_of

    folder = made_folder(root)
    base, cfg, ds, comp, train, test_ids = _fitted(folder, name, family)
    row = {"record": name, "family": family, "targets": {}, "clamped": {}}
    shipped = streaming._pattern
    for design, pattern in (("shipped", shipped), ("heldout", _heldout_of(shipped))):
        streaming._pattern = pattern
        for e in ENERGIES:
            key = f"{design}@{e}"
            scores = _deployed_of(_setting_cfg(base, f"e{e}"), ds)(comp, train, test_ids)
            for t, s in scores.items():
                row["targets"].setdefault(t, {})[key] = s["test"]["rmse"]
            row["clamped"][key] = next(iter(scores.values()))["clamped_samples"]
    streaming._pattern = shipped
    with open(folder / "candidate.jsonl", "a") as out:
        print(json.dumps(row), file=out)
    print(f"  {name} {family}: clamped {row['clamped']}")
    for t, v in row["targets"].items():
        print(f"    {t}: " + ", ".join(f"{k} {x:.4g}" for k, x in v.items()))


def table(root: str) -> None:
    """The rows of ROOT/price.jsonl (and faults.jsonl) summarised."""
    folder = Path(root)
    rows = [json.loads(line) for line in (folder / "price.jsonl").read_text().splitlines()]
    cells = [(r["record"], r["family"], t, v, r) for r in rows for t, v in r["targets"].items()]
    print(f"{len(rows)} record-family rows, {len(cells)} targets")
    print("setting        >2% worse than envelope off | than as run | better than off by >2% | "
          "geo-mean ratio to off")
    for s in SETTINGS:
        worse_off = sum(v[s] > 1.02 * v["envelope_off"] for *_, v, _ in cells)
        worse_run = sum(v[s] > 1.02 * v["as_run"] for *_, v, _ in cells)
        better = sum(v[s] < 0.98 * v["envelope_off"] for *_, v, _ in cells)
        gm = float(np.exp(np.mean([np.log(v[s] / v["envelope_off"]) for *_, v, _ in cells])))
        print(f"  {s:13} {worse_off:3} | {worse_run:3} | {better:3} | {gm:.4f}")
    spread = [(rec, fam, t) for rec, fam, t, v, _ in cells
              if max(v[f"e{e}"] for e in ENERGIES) > 1.02 * min(v[f"e{e}"] for e in ENERGIES)]
    print(f"targets whose RMSE moves > 2 % over the four energies: {len(spread)} of {len(cells)}: {spread}")
    print("per record (shipped / pattern off / envelope off / as run; clamped rows shipped, pattern off):")
    for rec, fam, t, v, r in cells:
        g = r["gate"]
        print(f"  {rec:13} {fam:8} {t:8} {v[SHIPPED]:.4g} / {v['pattern_off']:.4g} / {v['envelope_off']:.4g}"
              f" / {v['as_run']:.4g}  ({r['clamped'][SHIPPED]}, {r['clamped']['pattern_off']} of "
              f"{r['test_rows']}; rank {g.get('rank')} of {g['inputs']}, energy "
              f"{g.get('energy_at_rank', float('nan')):.5f}); energies "
              + " ".join(f"{v[f'e{e}']:.4g}" for e in ENERGIES))
    path = folder / "faults.jsonl"
    if path.exists():
        print("faults (Σ² over targets, µm²):")
        for line in path.read_text().splitlines():
            r = json.loads(line)
            sig = {s: float(np.sum([v[s] ** 2 for v in r["targets"].values()])) for s in SETTINGS}
            print(f"  {r['record']:11} {r['family']:7} {r['sensor']:22} {r['fault']:8} "
                  + " ".join(f"{s} {v:.4g}" for s, v in sig.items()))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"price": price, "faults": faults, "candidate": candidate, "table": table},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
