"""The served stream's per-row CPU (ci109b): ``AdaptiveCompensator._step`` row by row, as replay,
monitor, serve and the conformance pack stream it (``stream_campaign``: a campaign from its reset).

    python benchmarks/bench_ci109b.py fit ROOT      # simulate the default record, fit, pickle
    python benchmarks/bench_ci109b.py time ROOT [ROUNDS]   # per-row CPU; outputs to ROOT/out.pkl
    python benchmarks/bench_ci109b.py same A.pkl B.pkl     # bit-identical outputs, or exit 1

``fit``: the default simulated record (24 campaigns, 1755 rows), the deployed model of
``monitor.adaptive=true`` (monitor, re-admission, guard, fallbacks) of mlr, arx and lagbank fitted
on its train split, as ``replay`` builds it (:func:`~thermocomp.shell.builders.deployable_model`),
pickled (both trees stream the same pickles).  ``time``: every campaign, and of each test campaign
three copies with a fault planted on its first monitored sensor from its middle row (a jump of
+5 degC, a freeze, a dropout of a quarter of the rest), streamed through each model's
``stream_campaign``; CPU by ``time.process_time``, the median of ROUNDS (3) rounds, per row.
Outputs kept: corrections (compared with ``np.array_equal``), events, monitor states and errors
(``==`` / ``np.array_equal``).

Bar (stated before the change was measured): per-row CPU <= 0.6 x the base's (0326e79e) on this
bench, paired rounds, and ``same`` finds every output bit-identical.

Numbers (base 0326e79e -> after, same machine, paired, 3 rounds, us/row): see the commit that
scores it.
"""

from __future__ import annotations

import pickle
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

FAMILIES = ("mlr", "arx", "lagbank")


def fit(root: Path) -> None:
    from thermocomp.core.io.read import read_dataset
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.config.overrides import compose

    data = root / "data"
    if not data.is_dir():
        exe = Path(sys.executable).with_name("thermocomp")
        subprocess.run([str(exe), "simulate", "track=false", "plots=none", f"data.path={data}"],
                       check=True, capture_output=True)
    ds, _ = read_dataset(data)
    for family in FAMILIES:
        cfg = compose([f"model={family}", f"data.path={data}", "track=false"], "replay")
        deployed, _, _ = deployable_model(cfg, ds, ds.ids("train"), None, "replay.model")
        (root / f"{family}.pkl").write_bytes(pickle.dumps(deployed))
        print(family, type(deployed).__name__, "monitor", deployed.monitor is not None)


def streams(root: Path) -> dict:
    """Every campaign, and three planted copies of each test campaign."""
    from thermocomp.core.io.read import read_dataset

    ds, _ = read_dataset(root / "data")
    out = dict(ds.campaigns)
    for cid in ds.ids("test"):
        df = ds.campaigns[cid]
        sensor = next(c for c in df.columns if c.startswith("T_"))
        half = len(df) // 2
        rest = df.index[half:]
        jump, freeze, drop = df.copy(), df.copy(), df.copy()
        jump.loc[rest, sensor] += 5.0
        freeze.loc[rest, sensor] = df[sensor].iloc[half]
        drop.loc[rest[:max(1, len(rest) // 4)], sensor] = np.nan
        out.update({f"{cid}.jump": jump, f"{cid}.freeze": freeze, f"{cid}.dropout": drop})
    return out


def run(root: Path, rounds: int) -> None:
    from thermocomp.apps.monitor.report import stream_campaign

    campaigns = streams(root)
    rows = sum(len(df) for df in campaigns.values())
    outputs, cpu = {}, {}
    for family in FAMILIES:
        model = pickle.loads((root / f"{family}.pkl").read_bytes())
        took = []
        for _ in range(rounds):
            got = {}
            start = time.process_time()
            for cid, df in campaigns.items():
                got[cid] = stream_campaign(model, df)
            took.append(time.process_time() - start)
        outputs[family] = got
        cpu[family] = float(np.median(took)) / rows * 1e6
        print(f"{family:8s} {rows} rows x {rounds}: {cpu[family]:7.1f} us/row CPU "
              f"(rounds {', '.join(f'{t:.2f}' for t in took)} s)")
    print(f"all      {np.mean(list(cpu.values())):7.1f} us/row CPU (mean of the families)")
    (root / "out.pkl").write_bytes(pickle.dumps(outputs))


def same(a: Path, b: Path) -> int:
    x, y = pickle.loads(a.read_bytes()), pickle.loads(b.read_bytes())
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
    print(f"{n - len(bad)} / {n} streams bit-identical" + (f"; differ: {bad}" if bad else ""))
    return 1 if bad else 0


def main(argv: list[str]) -> int:
    if not argv or argv[0] not in ("fit", "time", "same") or len(argv) < 2:
        print(__doc__)
        return 2
    if argv[0] == "fit":
        fit(Path(argv[1]))
    elif argv[0] == "time":
        run(Path(argv[1]), int(argv[2]) if len(argv) > 2 else 3)
    else:
        return same(Path(argv[1]), Path(argv[2]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
