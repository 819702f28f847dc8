"""An independent check of autorep65's rule (``model=auto``'s votes on held-out runs re-referenced at
their first k samples) on fresh records nobody tuned on (issue 34; stop 65, autocheck65).

Usage::

    python benchmarks/bench_autocheck65.py write ROOT            # the lab-style records (once)
    python benchmarks/bench_autocheck65.py run ROOT [RECORD ...] # auto fitted once per record
    python benchmarks/bench_autocheck65.py score ROOT            # shipped against rule A, the verdict

The machinery is bench_autorep65's, unchanged: ``run`` is its ``run`` (bench_remeasure62's
``auto_row``: ``bench_auto_rank.main``, auto fitted once on the train split with ``keep_oof``, each
candidate alone after it; the campaign of each out-of-fold row kept where the folds hold out whole
campaigns), ``score`` its ``score`` on the stored arrays: the shipped votes (``vote_weights`` without
``squared``, asserted to give back the weights the fitted auto kept and its test RMSE) and rule A
(``squared=rereferenced_squares``, what src now ships) from the same fits.  One fit per record.
The test split is only scored: nothing here chooses on it.

The records (chosen and written here BEFORE anything was run or scored; fresh seeds 6531..6541,
on none of which anything was tuned; every one's auto folds meant to hold out whole campaigns,
each referenced to its first sample)
------------------------------------------------------------------------------------------------
* ``year6531``, ``year6532``, ``year6533``: ``sim=yearround_spindle`` (24 campaigns, 16 train),
  seeds 6531-6533;
* ``year6_6534``, ``year6_6535``, ``year6_6536``: the same with ``sim.generator.n_campaigns=6``
  (4 train campaigns), seeds 6534-6536;
* ``climate6537``, ``climate6538``: ``sim=climate_room`` (43 runs, 39 train), seeds 6537, 6538;
* ``lab6539``, ``lab6540``: bench_auto_losses56's lab record (how lab5401 is made:
  ``large_mill_week``, a 30 h train week cut into three 10 h runs each from its own time origin,
  a 12 h test run; read through ``data.path``), seeds 6539, 6540;
* ``trunnion6541``: bench_stranger63's trunnion mill (``benchmarks/conf63``, ``sim=trunnion63``)
  with ``sim.generator.weeks=4`` (W1-W3 train, W4 test), seed 6541;
* ``portal6542``: bench_stranger64's portal mill (``benchmarks/conf64``, ``sim=portal64``) with
  ``sim.generator.weeks=4``, seed 6542.

12 records.  Which of them the rule reaches (folds of whole campaigns whose held-out runs' first
label is 0) is read from the fits, not chosen: the others are unchanged by construction.

The verdict rule (written before scoring)
-----------------------------------------
Per record the mean test RMSE over its targets, as bench_autorep65.  Over the records the rule
reaches: the rule stays if the geometric mean of rule A / shipped is <= 1.00 AND the number of
records where auto beats MLR does not fall (A against shipped); otherwise revert is recommended
(src is not touched here; the lead decides).  Also reported, deciding nothing: per record and
target MLR, the best single family (after the fact), shipped / A; records within 10 % of the best
single family; CPU (user + sys).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import bench_autorep65 as autorep  # noqa: E402
import bench_remeasure62 as remeasure  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

LABS = {"lab6539": 6539, "lab6540": 6540}
RECORDS = {
    **{f"year{s}": ["sim=yearround_spindle", f"seed={s}"] for s in (6531, 6532, 6533)},
    **{f"year6_{s}": ["sim=yearround_spindle", "sim.generator.n_campaigns=6", f"seed={s}"]
       for s in (6534, 6535, 6536)},
    **{f"climate{s}": ["sim=climate_room", f"seed={s}"] for s in (6537, 6538)},
    **{name: [f"data.path={{root}}/{name}"] for name in LABS},
    "trunnion6541": [f"hydra.searchpath=[file://{HERE / 'conf63'}]", "sim=trunnion63",
                     "sim.generator.weeks=4", "seed=6541"],
    "portal6542": [f"hydra.searchpath=[file://{HERE / 'conf64'}]", "sim=portal64",
                   "sim.generator.weeks=4", "seed=6542"],
}
os.environ.setdefault("THERMOCOMP_TARGETS", "trunnion63.,portal64.")


def lab_record(path: Path, seed: int) -> Path:
    """bench_auto_losses56's ``lab_record`` with ``seed``: ``large_mill_week``, a 30 h train week
    in three 10 h runs (each from its own time origin), a 12 h test run."""
    import pandas as pd
    from hydra import compose, initialize_config_dir
    from hydra.utils import instantiate

    from thermocomp.base.paths import conf_dir
    from thermocomp.core.io.contract import Dataset, write_dataset

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[
            "sim=large_mill_week", f"seed={seed}", "sim.generator.train_hours=30",
            "sim.generator.test_hours=12"])
    ds = instantiate(cfg.sim.generator).generate()[0]
    week, test = ds.campaigns[ds.ids("train")[0]], ds.campaigns[ds.ids("test")[0]]
    rows = len(week) // 3
    runs = {}
    for k in range(3):
        part = week.iloc[k * rows:(k + 1) * rows].reset_index(drop=True)
        runs[f"Lauf_{k + 1}"] = part.assign(time=part["time"] - part["time"].iloc[0])
    runs["Lauf_4"] = test.reset_index(drop=True)
    manifest = pd.DataFrame({"split": ["train"] * 3 + ["test"], "file": ""},
                            index=pd.Index(list(runs), name="campaign"))
    return write_dataset(Dataset(manifest, runs, f"lab{seed}"), path)


def write(root: Path) -> None:
    for name, seed in LABS.items():
        if not (root / name).exists():
            lab_record(root / name, seed)


def run(root: Path, names: list[str]) -> None:
    autorep.keep_groups()
    remeasure.AUTO.update(RECORDS)
    remeasure.measure(root / "auto.jsonl", (("auto", remeasure.auto_row(root, n)) for n in names))


def verdict(root: Path, names: list[str]) -> list[str]:
    scored = autorep.score(root, names)
    cpu = {r["record"]: r["cpu_s"] for r in remeasure._read(root / "auto.jsonl")}
    lines = autorep.table([(n, s) for n, s in scored])
    lines = [ln for ln in lines if not ln.startswith(("B    :", "fl9010"))]
    means = []
    for name, s in scored:
        rows = s["targets"].values()
        reached = any(r["voted"] and r["k"] for r in rows)
        m = {k: float(np.mean([r[k] for r in rows])) for k in ("mlr", "auto", "A")}
        m["best"] = min(s["family_mean"].values())
        means.append((name, m, reached))
    lines += ["", "CPU s (user + sys) per record (auto fit + each candidate alone): "
              + ", ".join(f"{n} {cpu.get(n, float('nan')):.0f}" for n in names)
              + f"; total {sum(cpu.get(n, 0.0) for n in names):.0f}"]
    for label, subset in (("all", means), ("reached", [x for x in means if x[2]])):
        if not subset:
            continue
        n = len(subset)
        better = {k: sum(m[k] < m["mlr"] for _, m, _ in subset) for k in ("auto", "A")}
        near = {k: sum(m[k] <= 1.1 * m["best"] for _, m, _ in subset) for k in ("auto", "A")}
        geo = float(np.exp(np.mean([np.log(m["A"] / m["auto"]) for _, m, _ in subset])))
        lines.append(f"{label} ({n}: {' '.join(x[0] for x in subset)}): better than MLR shipped "
                     f"{better['auto']} / A {better['A']}; within 10 % of the best single shipped "
                     f"{near['auto']} / A {near['A']}; geometric mean A / shipped {geo:.4f}")
        if label == "reached":
            stays = geo <= 1.0 and better["A"] >= better["auto"]
            lines.append("verdict: " + ("the rule STAYS" if stays else "REVERT recommended")
                         + f" (geometric mean {geo:.4f} {'<=' if geo <= 1.0 else '>'} 1.00; records "
                         f"better than MLR {better['auto']} -> {better['A']})")
    return lines


def main(argv: list[str]) -> int:
    what, root, rest = argv[0], Path(argv[1]).resolve(), argv[2:]
    start = cpu_seconds()
    if what == "write":
        write(root)
    elif what == "run":
        run(root, rest or list(RECORDS))
    elif what == "score":
        print(remeasure._wrapped(verdict(root, rest or list(RECORDS)), 110))
    print(f"CPU s (user + sys) of this process: {cpu_seconds() - start:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
