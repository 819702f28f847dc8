"""The guard's numerical gain for every model without an analytic one (stop 111, guard111b).

guard111 gave ``lstm`` a held-step gain (``held_gains.stepped_gain``) behind a per-family flag;
an ATI / per-interval lstm, a blend holding one (``model=auto``'s vote, its hedge), a diagnosed
lstm and ``arx_rf`` kept a guard row of 0 (the bound as trained while the inputs go past it).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_guard111b.py simulate ROOT SEEDS     # fresh climate rooms (KINDS)
    python benchmarks/bench_guard111b.py table OUT              # family x wrapper: the guard's rows
    python benchmarks/bench_guard111b.py cost OUT CASE DATA...  # deployed vs unguarded per target
    python benchmarks/bench_guard111b.py lathe OUT CASE         # deploy-time CPU, lathe-sized set
    python benchmarks/bench_guard111b.py code OUT CASE          # C vs served, the made room

``table``: bench_dep108c's made room (every input past training in test) fitted with every
family x wrapper (:data:`CASES`): per target the guard's gain row (ZERO or its max) and the
deployed outputs' sha1 on the test campaign.  ``cost``: CASE (``CASE,key=value...``: overrides
added) on each DATA (a room folder; ``room``, ``door_room``: the made ones): per target rows
guarded, deployed and unguarded RMSE vs measured.  ``lathe``:
bench_lagbank's writer (43 campaigns x 600 rows x 24 sensors), CASE fitted, then the CPU of
``deployable`` (the adaptive compensator's training: POD, guard, its gains) alone.

MEASURED (2026-12-07; bar benchmarks/guard111b_bar.md committed first, ee7594f1; BASE = 10826370's
src; 2 cores shared with other helpers' runs; CPU user + sys by rusage).  Seeds: 10158 seen;
fresh 10230 climate_lag, 10231 climate_hydraulic, 10232 climate_position drawn once after the rule
(8d2887a9), scored once.
``table`` (62 case x target rows): ZERO on BASE: arx_rf x {none, ati, per-interval, diagnosed},
  lstm x {ati, per-interval, diagnosed} (both targets), auto vote / hedge E_Z (an lstm blend); all
  have a gain after.  Every other row: gain and deployed sha1 equal to BASE.
``cost`` (deployed / unguarded RMSE, BASE -> rule): 10158 E_X lstm/ati 1.275 -> 0.983,
  lstm/per-interval 1.055 -> 0.988, lstm/diagnosed 1.275 -> 0.983, arx_rf (S_spindle_rpm) 1.118 ->
  0.998, arx_rf/ati 1.091 -> 0.980; made room E_Z lstm/ati 1.424 -> 1.030, auto 1.413 ->
  1.024, lstm/per-interval E_X 1.180 -> 0.977; left: made room E_X of the ATI / diagnosed wrappers
  1.794 -> 1.567 (as MLR's analytic ATI: test A0 26 C past training's 14-23.6, the gain taken at
  training's A0s), door room arx_rf E_Z 1.481 -> 1.123 (the forest's bumps past the linear gain).
Fresh: every case x target equal to BASE to the printed digit, no row guarded either way.
``code``: max |C - served| 7e-15 - 4.6e-14 um (lstm ati / per-interval / diagnosed, auto, arx_rf).
``lathe`` (deployable CPU, BASE -> rule): lstm 10.0 / 8.7 (its held steps already on BASE),
  arx_rf 2.8 -> 9.9 (+7.1 s), lstm per-interval 3.2 -> 15.4 (+12.3 s: over the bar's 10 s).

guard111c (bar benchmarks/guard111c_bar.md, 9142ea0c; BASE = f34c934f's src, each pair run at
once on the same load): the held steps from each campaign's last stream state, the prefix
streamed once.  ``table``: all 60 rows (printed max, sha1) identical to BASE; full rows equal to
<= 2.8e-15 of the row's max (lstm exact; arx_rf's ARX streamed, not batch-predicted: an input it
does not read 0 where BASE had 8.9e-16 of rounding).  ``lathe`` (arx_rf with
``model.estimator.state_column=null``: the set has no S_ column), BASE -> branch, two pairs:
lstm per-interval 15.10 / 12.25 -> 4.92 / 4.46 s, arx_rf 9.61 / 9.10 -> 3.21 / 3.05 s, lstm
10.77 / 10.45 -> 4.52 / 4.20 s.  ``code``: max |C - served| 7.1e-15 - 4.6e-14 um.
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
import bench_guard111 as g111  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

NET = ("model.estimator.hidden_size=4", "model.estimator.max_epochs=3")
FAMILY = {"arx_rf": (), "lstm": NET, "mlr": (), "pcr": (), "arx": (), "lagbank": (), "hammerstein": ()}
WRAP = {"none": (), **{k: v for k, v in dep.WRAPPERS.items() if k != "none"}, "diagnosed": ()}
AUTO = ("model=auto", "model.candidates=[mlr,lstm]",
        "model.candidate_params={lstm:{hidden_size:4,max_epochs:3}}")
CASES = {**{f"{f}/{w}": (f"model={f}", *FAMILY[f], *WRAP[w]) for f in FAMILY for w in WRAP},
         "auto/vote": (*AUTO, "model.estimator.hedge=none"), "auto/hedge": AUTO}
# the fresh seeds' kinds, named before any was drawn (bench_guard111's climate kinds)
KINDS = {10230: ("climate_lag", dep.d107.LAG), 10231: ("climate_hydraulic", dep.d107.HIDDEN),
         10232: ("climate_position", ["sim.generator.effects=[axis_position]"])}
AMBIENT_LAW = {"kind": "ambient_interval", "transform": "ambient_linear"}


def _deployed(data: Path, case: str):
    """``(deployed adaptive compensator, train campaigns, test campaigns)`` of ``case``."""
    from hydra import compose, initialize_config_dir
    from sklearn.base import clone

    from thermocomp.apps.diagnose import AugmentedRegressor
    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
    from thermocomp.shell.source import read_streamed

    case, *more = case.split(",")       # (CASE,key=value...: overrides added to the case's)
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[
            f"data.path={data}", "track=false", "monitor.adaptive=true", *CASES[case], *more])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds)
    if case.endswith("/diagnosed"):     # the level law on every target, around the family
        law = {t: [AMBIENT_LAW] for t in ("E_X", "E_Z")}
        comp = clone(comp).set_params(estimator=AugmentedRegressor(comp.estimator, effects=law))
    stream = deploy_stream(cfg, comp.fit(train), train)
    start = cpu_seconds()
    out = deployable(cfg, stream, train, ds)
    return out, train, {c: ds.campaigns[c] for c in test_ids}, cpu_seconds() - start


def _door_room(root: Path) -> Path:
    """bench_dep108c's room with a door ``S_door`` (0/1, a new state every 10 samples) for
    ``arx_rf``'s machine-state signal; the errors as they were."""
    dep._room(root)
    rng = np.random.default_rng(1112)
    for f in sorted(root.glob("K*.csv")):
        df = pd.read_csv(f)
        df["S_door"] = np.repeat(rng.integers(0, 2, len(df) // 10 + 1), 10)[:len(df)].astype(float)
        df.to_csv(f, index=False)
    return root


def _rooms(out: str) -> tuple[Path, Path]:
    folder = made_folder(out)
    room, door = folder / "room", folder / "door_room"
    return (room if room.exists() else dep._room(room)), (door if door.exists() else _door_room(door))


def simulate(root: str, seeds: str) -> None:
    """Each fresh seed's climate room (bench_dep108c's simulation, :data:`KINDS`) -> ROOT/<case>."""
    import bench_diag106 as d106

    logs = made_folder(str(Path(root) / "logs"))
    for seed in seed_list(seeds):
        kind, words = KINDS[seed]
        data = Path(root) / f"{kind}-planted-{seed}"
        if not data.exists():
            d106._thermocomp(["simulate", *d106.CLIMATE, f"seed={seed}", f"data.path={data}", "track=false",
                              *words], logs / f"{data.name}-simulate.log")
        print(data)


def table(out: str) -> None:
    """Per case x target: the guard's gain row and the deployed outputs' digest on the test."""
    from thermocomp.apps.deploy.streaming import replay

    room, door = _rooms(out)
    for case in CASES:
        deployed, _, tests, _ = _deployed(door if case.startswith("arx_rf") else room, case)
        g = deployed.guard
        y = np.vstack([replay(deployed, df.reset_index(drop=True))[deployed.targets_].to_numpy(float)
                       for df in tests.values()])
        for k, t in enumerate(deployed.targets_):
            row = g.in_gain[k]
            est = type(deployed.streaming._plan[k][1]).__name__
            print(f"{case:22s} {t} {est:18s} row {'ZERO' if not row.any() else 'max %.4g' % row.max():12s} "
                  f"sha1 {hashlib.sha1(y[:, k].tobytes()).hexdigest()[:12]}", flush=True)


def cost(out: str, case: str, *datas: str) -> None:
    """CASE on each DATA: per target rows guarded, deployed and unguarded RMSE."""
    rooms = dict(zip(("room", "door_room"), _rooms(out)))
    for data in datas:
        path = rooms.get(data, Path(data))
        deployed, _, tests, _ = _deployed(path, case)
        for t, (rows, d, f) in g111._scores(deployed, tests).items():
            print(f"{case:18s} {path.name:30s} {t}: guarded {rows:4d} deployed {d:.4f} unguarded {f:.4f} "
                  f"ratio {d / f:.4f}", flush=True)


def lathe(out: str, case: str) -> None:
    """CASE on the lathe-sized set: the CPU of ``deployable`` (its gains included)."""
    import bench_lagbank

    data = made_folder(out) / "lathe"
    if not data.exists():
        bench_lagbank.write_campaigns(data, 43, 600, 24)
        # each campaign's ambient for the ATI wrappers: its sensors' first row (they start there)
        manifest = pd.read_csv(data / "campaigns.csv")
        manifest["ambient_c"] = [pd.read_csv(data / f).filter(like="T_").iloc[0].mean()
                                 for f in manifest["file"]]
        manifest.to_csv(data / "campaigns.csv", index=False)
    deployed, *_, cpu = _deployed(data, case)
    row = deployed.guard.in_gain
    zero = int((~row.any(axis=1)).sum())
    print(f"{case}: deployable CPU {cpu:.2f} s; guard rows zero {zero} of {len(row)}", flush=True)


def code(out: str, case: str) -> None:
    """CASE on the made room (``door_room`` for arx_rf) exported as C, built, fed the test
    campaign: max |C - served| (µm)."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    from cbuild import compiled  # noqa: I001 (tests/ on the path first)
    from thermocomp.apps.deploy.export import exported_files
    from thermocomp.apps.deploy.streaming import replay

    room, door = _rooms(out)
    deployed, _, tests, _ = _deployed(door if case.startswith("arx_rf") else room, case)
    folder = made_folder(str(Path(out) / f"c-{case.replace('/', '-')}"))
    for name, text in exported_files(deployed, "c").items():
        (folder / name).write_text(text)
    binary = compiled(folder)
    for cid, df in tests.items():
        df = df.reset_index(drop=True)
        served = replay(deployed, df)[deployed.targets_].to_numpy(float)
        text = df[["time", *deployed.columns_]].to_csv(index=False, float_format="%.17g")
        run = subprocess.run([str(binary)], input=text, text=True, capture_output=True, check=True)
        got = -pd.read_csv(io.StringIO(run.stdout)).to_numpy(float)
        print(f"{case} {cid}: max |C - served| {np.max(np.abs(got - served)):.3g} µm over {len(df)} rows; "
              f"guard gain max {np.round(deployed.guard.in_gain.max(axis=1), 3).tolist()}", flush=True)


def main(argv: list[str]) -> int:
    commands = {"simulate": simulate, "table": table, "cost": cost, "lathe": lathe, "code": code}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
