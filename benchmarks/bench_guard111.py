"""The deploy guard's following bound for models without an analytic step gain (stop 111, guard111).

dep108c gave the guard a gain for models whose gain needs the campaign's A0 (the largest |gain|
over training's A0s); ``lstm`` has no ``step_gain`` and a diagnosed ``inputs_product`` (a held
state times the inputs' rises) has none without the stream's state: ``adaptive.input_gains``
writes a row of 0 and the bound stays as trained while the inputs go past training.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_guard111.py cost OUT [DATA...]   # deployed vs unguarded, seen rooms
    python benchmarks/bench_guard111.py healthy OUT          # the training campaigns replayed
    python benchmarks/bench_guard111.py code OUT WHICH       # lstm | product: C vs served

``cost``: per case x target the rows the guard changed on the test campaigns, the RMSE vs measured
of the deployed (adaptive) compensator and of its plain stream (unguarded), and the guard's gain
row.  Cases: ``lstm`` on bench_dep108c's made room (``families``) and on each DATA (a simulated
climate room), ``product`` (MLR + one ``inputs_product`` of ``S_pos`` on E_X) on that room with a
held factor added (and ``product_flat``: without the room's level law).  ``healthy``: the same
models, their training campaigns replayed (inputs within training): a digest of the deployed
corrections.  ``code``: the lstm or product model as C, built (tests/cbuild.py), fed the test
campaign: max |C - served| (µm).

MEASURED (2026-12-07; bar benchmarks/guard111_bar.md committed first, 0d630f04; BASE = 1a0fc91a's
src; 2 shared cores; CPU by the command's rusage line).  Seeds: 10158 seen; fresh 10227
climate_lag, 10228 climate_hydraulic, 10229 climate_position drawn once after the rule, scored once.
``cost`` (deployed / unguarded RMSE µm, rows guarded; BASE -> rule):
  lstm room E_X 18.197 / 18.130 (8) -> 18.128 (1); E_Z 2.242 / 1.586 (23) -> 1.625 (27: as MLR's
  own E_Z with its analytic gain); lstm 10158 E_X 3.654 / 3.256 (230) -> 3.249 (4), E_Z 1.414 = 1.414;
  product room E_X 20.578 / 20.561 (1) -> 20.561 (0); product_flat E_X 6.179 / 5.853 (22) -> 5.843 (2).
  CPU 8.5 -> 10.0 s (the held steps of lstm's two fits).
Fresh (``cost`` lstm; bench_dep108c ``rows``, the CLI's diagnose): every target equal to BASE to the
  printed / last digit, no row guarded either way.  ``healthy``: sha1 of the training replays equal.
``code``: max |C - served| lstm 4.97e-14 µm, product_flat 1.42e-14 µm (BASE the same, gain 0).
"""

from __future__ import annotations

import hashlib
import io
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_dep108c as dep  # noqa: E402
from _cli import made_folder, run_commands  # noqa: E402

LSTM = ("model=lstm", "model.estimator.hidden_size=4", "model.estimator.max_epochs=3")
PRODUCT = {"kind": "interaction", "transform": "inputs_product", "column": "S_pos", "frame": "absolute"}


def _product_room(root: Path, flat: bool = False) -> Path:
    """bench_dep108c's room with a held factor: a saddle position ``S_pos`` (mm, a new place every
    8 samples, 200-1800 in every campaign) through which ``T_a``'s rise reaches E_X; ``flat``: E_X
    without the room's level law in A0 (which the product model does not have: added after the
    bar, the first room's E_X being 20.6 µm off either way)."""
    dep._room(root)
    rng = np.random.default_rng(111)
    for f in sorted(root.glob("K*.csv")):
        df = pd.read_csv(f)
        pos = np.repeat(rng.uniform(200, 1800, len(df) // 8 + 1), 8)[:len(df)]
        df["S_pos"] = pos
        rise = df["T_a"] - df["T_a"].iloc[0]
        if flat:      # the law's 0.4 (A0 - 20) per K of T_a's rise out (the room's A0s by file)
            df["E_X"] -= 0.4 * (2.4 * int(f.stem[1:]) - 6.0) * rise
        df["E_X"] += 2e-3 * pos * rise
        df.to_csv(f, index=False)
    return root


def _deployed(data: Path, case: str):
    """``(deployed adaptive compensator, train campaigns, test campaigns)`` of ``case``."""
    from hydra import compose, initialize_config_dir
    from sklearn.base import clone

    from thermocomp.apps.diagnose import AugmentedRegressor
    from thermocomp.base.paths import conf_dir
    from thermocomp.core.models import MLR
    from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
    from thermocomp.shell.source import read_streamed

    words = LSTM if case == "lstm" else ("model=mlr",)
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[
            f"data.path={data}", "track=false", "monitor.adaptive=true", *words])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds)
    if case == "product":
        comp = clone(comp).set_params(estimator=AugmentedRegressor(MLR(), effects={"E_X": [PRODUCT]}))
    stream = deploy_stream(cfg, comp.fit(train), train)
    return deployable(cfg, stream, train, ds), train, {c: ds.campaigns[c] for c in test_ids}


def _scores(dep, campaigns: dict) -> dict:
    """Per target: rows guarded, RMSE deployed and unguarded (the plain stream) vs measured."""
    from thermocomp.apps.deploy.streaming import replay

    comp, targets = dep.compensator, dep.targets_
    err = {"dep": [], "free": []}
    guarded = np.zeros(len(targets), int)
    for cid, df in campaigns.items():
        df = df.reset_index(drop=True)
        meas = comp.measured({cid: df})[cid][targets].to_numpy(float)
        out = replay(dep, df)
        guarded += np.array([out.attrs["guarded"][t] for t in targets]) if "guarded" in out.attrs else 0
        err["dep"].append(out[targets].to_numpy(float) - meas)
        err["free"].append(replay(dep.streaming, df)[targets].to_numpy(float) - meas)
    rmse = {k: np.sqrt(np.nanmean(np.vstack(v) ** 2, axis=0)) for k, v in err.items()}
    return {t: (int(guarded[k]), rmse["dep"][k], rmse["free"][k]) for k, t in enumerate(targets)}


def _cases(out: str, datas: tuple) -> list:
    folder = made_folder(out)
    room = dep._room(folder / "room") if not (folder / "room").exists() else folder / "room"
    prod = folder / "product_room"
    prod = prod if prod.exists() else _product_room(prod)
    flat = folder / "product_flat"
    flat = flat if flat.exists() else _product_room(flat, flat=True)
    return [("lstm", room), ("product", prod), ("product", flat), *[("lstm", Path(d)) for d in datas]]


def cost(out: str, *datas: str) -> None:
    """Per case x target: rows guarded, deployed and unguarded RMSE, the guard's gain row."""
    for case, data in _cases(out, datas):
        deployed, _, tests = _deployed(data, case)
        g = deployed.guard
        for k, (t, (rows, d, f)) in enumerate(_scores(deployed, tests).items()):
            gain = g.in_gain[k] if g.in_gain is not None else None
            print(f"{case:8s} {data.name:30s} {t}: guarded {rows:4d} deployed {d:.4f} unguarded {f:.4f} "
                  f"ratio {d / f:.4f} gain max {0 if gain is None else gain.max():.4g}", flush=True)


def healthy(out: str) -> None:
    """The training campaigns replayed through each made case: a digest of the corrections."""
    from thermocomp.apps.deploy.streaming import replay

    for case, data in _cases(out, ())[:3]:
        deployed, train, _ = _deployed(data, case)
        ys = [replay(deployed, df.reset_index(drop=True))[deployed.targets_].to_numpy(float)
              for df in train.values()]
        y = np.vstack(ys)
        digest = hashlib.sha1(y.tobytes()).hexdigest()[:16]
        print(f"{case:8s} {data.name}: {len(y)} rows, sha1 {digest}", flush=True)


def code(out: str, which: str) -> None:
    """WHICH (``lstm``: the made room's, ``product``: the flat product room's) exported as C and
    fed its test campaign: max |C - served| (µm)."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    from cbuild import compiled  # noqa: I001 (tests/ on the path first)
    from thermocomp.apps.deploy.export import exported_files
    from thermocomp.apps.deploy.streaming import replay

    case, data = _cases(out, ())[0 if which == "lstm" else 2]
    deployed, _, tests = _deployed(data, case)
    folder = made_folder(str(Path(out) / f"c-{which}"))
    for name, text in exported_files(deployed, "c").items():
        (folder / name).write_text(text)
    binary = compiled(folder)
    for cid, df in tests.items():
        df = df.reset_index(drop=True)
        served = replay(deployed, df)[deployed.targets_].to_numpy(float)
        text = df[["time", *deployed.columns_]].to_csv(index=False, float_format="%.17g")
        run = subprocess.run([str(binary)], input=text, text=True, capture_output=True, check=True)
        got = -pd.read_csv(io.StringIO(run.stdout)).to_numpy(float)
        print(f"{cid}: max |C - served| {np.max(np.abs(got - served)):.3g} µm over {len(df)} rows; "
              f"guard gain {np.round(deployed.guard.in_gain, 3).tolist()}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cost": cost, "healthy": healthy, "code": code}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
