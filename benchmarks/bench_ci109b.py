"""The served stream's per-row CPU (ci109b): ``AdaptiveCompensator._step`` row by row, as replay,
monitor, serve and the conformance pack stream it (``stream_campaign``: a campaign from its reset).

    python benchmarks/bench_ci109b.py fit ROOT              # simulate, fit, pickle (both trees stream these)
    python benchmarks/bench_ci109b.py time ROOT [ROUNDS]    # per-row CPU; outputs to ROOT/out.pkl
    python benchmarks/bench_ci109b.py same A.pkl B.pkl      # bit-identical outputs, else exit 1

``fit``: the default simulated record (24 campaigns, 1755 rows) and the deployed model of
``monitor.adaptive=true`` (monitor, re-admission, guard, sensor fallbacks) fitted on its train
split as ``replay`` builds it (:func:`~thermocomp.shell.builders.deployable_model`) for mlr, arx
and lagbank (timed), and, for bit-identity only, ``ati=cmeans`` (mlr), the model ``diagnose``
deploys and an lstm (``model=lstm``, where torch is installed).  ``time``: every campaign, and of
each test campaign three copies with a fault planted from its middle row (a jump of +5 degC, a
freeze, a dropout of a quarter of the rest) on its first monitored sensor, and three on ``T_amb``
(whose fallback then gives the correction): 5283 rows through each model's ``stream_campaign``;
CPU by ``time.process_time`` per row, the median and the least of ROUNDS (3) rounds (the least:
the round the machine's other processes disturbed least); the extra models once, untimed.
``same``: corrections (``np.array_equal``), events (their ``repr``: a float's gives it back bit
for bit), monitor states and errors per row.

Bar (stated before the change was measured, 0326e79e -> fix/ci109b): per-row CPU (the mean of the
three families) <= 0.6 x the base's, paired runs on this machine, and ``same`` finds every stream
of every model bit-identical.

Numbers (us/row CPU, mean of the families, median of rounds; base -> after, paired runs in turn on
a machine shared with up to 7 others; 2 cores):

* the tree before the settled / ARX / guard commit, 3 runs x 3 rounds (pytest on 2 workers
  beside): 374.3 -> 200.9, 324.5 -> 186.3, 253.0 -> 201.7 (0.54, 0.57, 0.80);
* this tree, load 2.8 -> 4.6, 3 runs x 3 rounds: 292.9 -> 194.9, 301.1 -> 172.8, 339.6 -> 231.6
  (0.67, 0.57, 0.68);
* this tree, load ~5.6, 4 runs x 5 rounds: 312.9 -> 242.7, 281.2 -> 213.3, 328.3 -> 263.5,
  348.7 -> 261.9 (0.78, 0.76, 0.80, 0.75; the least rounds 0.77, 0.75, 0.80, 0.74).
* Python calls per row (cProfile, deterministic): mlr 248 -> 212, arx 401 -> 229, lagbank 492 -> 256.
* ``same``: 432 / 432 streams of mlr, arx, lagbank, ati, diagnosed, lstm bit-identical.
"""

from __future__ import annotations

import pickle
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402 (benchmarks/ on the path first)

FAMILIES = ("mlr", "arx", "lagbank")
EXTRAS = {"ati": ["model=mlr", "ati=cmeans"], "lstm": ["model=lstm"]}   # (+ "diagnosed")


def fit(root: str) -> None:
    from thermocomp.core.io.read import read_dataset
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.config.overrides import compose

    root = Path(root)
    data = root / "data"
    if not data.is_dir():
        exe = Path(sys.executable).with_name("thermocomp")
        subprocess.run([str(exe), "simulate", "track=false", "plots=none", f"data.path={data}"],
                       check=True, capture_output=True)
    ds, _ = read_dataset(data)
    models = {f: [f"model={f}"] for f in FAMILIES} | EXTRAS
    for name, overrides in models.items():
        try:
            cfg = compose([*overrides, f"data.path={data}", "track=false"], "replay")
            deployed, _, _ = deployable_model(cfg, ds, ds.ids("train"), None, "replay.model")
        except ImportError as exc:        # (lstm: torch is an extra)
            print(name, "skipped:", exc)
            continue
        (root / f"{name}.pkl").write_bytes(pickle.dumps(deployed))
        print(name, type(deployed).__name__, "fallbacks", sorted(deployed.fallbacks_))
    (root / "diagnosed.pkl").write_bytes(pickle.dumps(diagnosed(data)))
    print("diagnosed written")


def diagnosed(data: Path):
    """The deployed model ``diagnose`` builds on the record (its model after the diagnosis), as
    benchmarks/bench_dep108c.py builds it."""
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

    diagnose(ds, build_compensator(cfg), None, str(cfg.eval.mode), search_options(cfg.diagnose),
             None, deployed_of=deployed_of)
    comp, train, _ = kept.get("after", kept["before"])
    return deployable(cfg, deploy_stream(cfg, comp, train), train, ds)


def streams(root: Path) -> dict:
    """Every campaign, and three planted copies of each test campaign per planted sensor: its
    first monitored one, and ``T_amb`` (the sensor every model here has a fallback for: its
    correction read while the sensor is out)."""
    from thermocomp.core.io.read import read_dataset

    ds, _ = read_dataset(root / "data")
    out = dict(ds.campaigns)
    for cid in ds.ids("test"):
        df = ds.campaigns[cid]
        first = next(c for c in df.columns if c.startswith("T_"))
        for sensor in dict.fromkeys([first, *(["T_amb"] if "T_amb" in df.columns else [])]):
            half = len(df) // 2
            rest = df.index[half:]
            jump, freeze, drop = df.copy(), df.copy(), df.copy()
            jump.loc[rest, sensor] += 5.0
            freeze.loc[rest, sensor] = df[sensor].iloc[half]
            drop.loc[rest[:max(1, len(rest) // 4)], sensor] = np.nan
            out.update({f"{cid}.jump.{sensor}": jump, f"{cid}.freeze.{sensor}": freeze,
                        f"{cid}.dropout.{sensor}": drop})
    return out


def run(root: str, rounds: str = "3") -> None:
    from thermocomp.apps.monitor.report import stream_campaign

    root, rounds = Path(root), int(rounds)
    campaigns = streams(root)
    rows = sum(len(df) for df in campaigns.values())
    outputs, cpu, least = {}, {}, {}
    names = [*FAMILIES, *(n for n in (*EXTRAS, "diagnosed") if (root / f"{n}.pkl").is_file())]
    for name in names:
        model = pickle.loads((root / f"{name}.pkl").read_bytes())
        took = []
        for _ in range(rounds if name in FAMILIES else 1):
            got = {}
            start = time.process_time()
            for cid, df in campaigns.items():
                got[cid] = stream_campaign(model, df)
            took.append(time.process_time() - start)
        outputs[name] = got
        cpu[name] = float(np.median(took)) / rows * 1e6
        least[name] = min(took) / rows * 1e6
        print(f"{name:9s} {rows} rows x {len(took)}: {cpu[name]:7.1f} us/row CPU, least "
              f"{least[name]:7.1f} (rounds {', '.join(f'{t:.2f}' for t in took)} s)")
    print(f"families  {np.mean([cpu[f] for f in FAMILIES]):7.1f} us/row CPU, least "
          f"{np.mean([least[f] for f in FAMILIES]):7.1f} (mean of {FAMILIES})")
    (root / "out.pkl").write_bytes(pickle.dumps(outputs))


def same(a: str, b: str) -> None:
    x, y = pickle.loads(Path(a).read_bytes()), pickle.loads(Path(b).read_bytes())
    bad = []
    for family in x:
        for cid in x[family]:
            (ya, ea, (sa, ra)), (yb, eb, (sb, rb)) = x[family][cid], y[family][cid]
            # events by repr (a float's repr gives it back bit for bit; NaN == NaN there)
            if not (np.array_equal(ya, yb, equal_nan=True) and repr(ea) == repr(eb)
                    and len(sa) == len(sb) and len(ra) == len(rb)
                    and all(np.array_equal(p, q) for p, q in zip(sa, sb))
                    and all(np.array_equal(p, q, equal_nan=True) for p, q in zip(ra, rb))):
                bad.append(f"{family}/{cid}")
    n = sum(len(v) for v in x.values())
    print(f"{n - len(bad)} / {n} streams of {sorted(x)} bit-identical"
          + (f"; differ: {bad}" if bad else ""))
    if bad:
        sys.exit(1)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"fit": fit, "time": run, "same": same}, argv)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
