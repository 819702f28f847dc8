"""An independent check of autorep65's rule (``model=auto``'s votes on held-out runs re-referenced at
their first k samples) on fresh records nobody tuned on (issue 34; stop 65, autocheck65).

Usage::

    python benchmarks/bench_autocheck65.py write ROOT            # the lab-style records (once)
    python benchmarks/bench_autocheck65.py run ROOT [RECORD ...] # auto fitted once per record
    python benchmarks/bench_autocheck65.py score ROOT            # shipped against rule A, the verdict

The machinery is bench_autorep65's: ``run`` is its ``run`` (bench_remeasure62's ``auto_row``:
``bench_auto_rank.main``, auto fitted once on the train split with ``keep_oof``, each candidate
alone after it; the campaign of each out-of-fold row kept where the folds hold out whole campaigns),
and ``score`` computes, as its ``target_row`` does, the shipped votes (``vote_weights`` without
``squared``) and rule A (``squared=rereferenced_squares``) from the same fit's stored arrays.  One
fit per record.  Two changes, both found when the machinery first ran, neither choosing anything:
(1) the fits here ran src with rule A (91ec8834), so the weights the fitted auto kept and its
test RMSE were asserted to be rule A's and shipped was recomputed (since the lead's revert, the fit
runs the shipped votes and ``target_row`` asserts those); (2) ``measured_test_only``:
bench_auto_rank's test series on the measured rows only (trunnion63 / portal64 log a sparse probe,
empty cells between, which broke its blend check on NaN; dense records unchanged).  The test split
is only scored: nothing here chooses on it.

The records (chosen and written here BEFORE anything was run or scored; fresh seeds 6531..6542,
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

Measured 2026-12-01 (stop 65; main e8f93ec7, rule A in src; 2 shared cores, AMD EPYC; run once:
``write`` 2.3 s, ``run`` 195 s CPU user + sys for the 12 records, ``score`` 0.5 s).  Every voted
target's kept weights and test RMSE equal rule A's from the arrays (asserted).  Test RMSE (µm) per
record and target: MLR, the best single family (after the fact), auto shipped / rule A; k: the
campaigns re-referenced x their k; the weights::

  record       target    MLR   best (family)       auto      A  k             weights shipped | A
  year6531     E_X     0.677  0.674 arx           0.674  0.672  16 x 2-4      arx 1.00 | mlr 0.03 arx 0.92
      lagb 0.01 hamm 0.03
  year6531     E_Y      1.62   1.01 ati           0.834  0.863  16 x 2-4      mlr 0.02 lagb 0.12 hamm 0.30
      lstm 0.02 ati 0.54 | arx 0.06 lagb 0.02 hamm 0.48 ati 0.44
  year6531     E_Z      5.26   1.06 ati            1.06    1.1  16 x 2-4      ati 1.00 | hamm 0.13 ati 0.87
  year6532     E_X     0.767  0.681 ati           0.809  0.748  16 x 2-4      mlr 0.07 lagb 0.84 ati 0.09 |
      mlr 0.37 lagb 0.44 hamm 0.14 ati 0.04
  year6532     E_Y      1.38  0.977 ati           0.977  0.977  16 x 2-4      ati 1.00 (both)
  year6532     E_Z      5.02  0.955 ati           0.955  0.869  16 x 2-4      ati 1.00 | hamm 0.07 ati 0.93
  year6533     E_X     0.829  0.668 lagbank       0.679  0.676  16 x 2-4      mlr 0.13 arx 0.04 lagb 0.83 |
      mlr 0.08 arx 0.05 lagb 0.84 ati 0.03
  year6533     E_Y      1.39  0.962 ati           0.863  0.962  16 x 2-4      mlr 0.01 arx 0.02 hamm 0.35
      ati 0.62 | ati 1.00
  year6533     E_Z      4.95   1.01 ati            1.01   1.14  16 x 2-4      ati 1.00 | hamm 0.37 ati 0.63
  year6_6534   E_X     0.642  0.507 pcr           0.514  0.489  4 x 2-4       mlr 0.26 pcr 0.50 lstm 0.24 |
      mlr 0.24 pcr 0.08 lagb 0.02 hamm 0.37 lstm 0.29
  year6_6534   E_Y      1.99   1.45 pcr            1.41  0.879  4 x 2-4       mlr 0.07 pcr 0.77 hamm 0.03
      ati 0.13 | mlr 0.02 pcr 0.71 lagb 0.28
  year6_6534   E_Z      3.21  0.889 ati           0.889   0.92  4 x 2-4       ati 1.00 | pcr 0.08 ati 0.92
  year6_6535   E_X     0.683  0.569 pcr           0.802  0.872  4 x 2-3       mlr 0.18 lagb 0.11 hamm 0.42
      lstm 0.12 ati 0.17 | mlr 0.05 lagb 0.24 hamm 0.63 ati 0.08
  year6_6535   E_Y      1.76   1.12 ati            1.52   1.65  4 x 2-3       mlr 0.30 pcr 0.04 lagb 0.27
      hamm 0.09 lstm 0.29 | mlr 0.46 pcr 0.17 arx 0.04 lagb 0.07 hamm 0.04 lstm 0.22
  year6_6535   E_Z      8.19   1.58 ati             1.7   3.31  4 x 2-3       mlr 0.02 ati 0.98 | mlr 0.28
      ati 0.72
  year6_6536   E_X     0.616  0.561 lagbank       0.602  0.565  4 x 3-4       mlr 0.65 arx 0.24 lagb 0.09
      lstm 0.03 | mlr 0.09 pcr 0.17 lagb 0.71 hamm 0.03
  year6_6536   E_Y      1.77   1.07 arx           0.926  0.896  4 x 3-4       mlr 0.13 arx 0.67 ati 0.20 |
      mlr 0.08 arx 0.71 ati 0.21
  year6_6536   E_Z      5.21    1.2 ati             1.2    1.2  4 x 3-4       ati 1.00 (both)
  climate6537  E_X      1.38  0.574 ati           0.574  0.574  19 x 10-10    ati 1.00 (both)
  climate6537  E_Z      2.21  0.666 ati           0.666  0.666  19 x 10-10    ati 1.00 (both)
  climate6538  E_X      1.03  0.435 ati           0.435  0.435  19 x 10-10    ati 1.00 (both)
  climate6538  E_Z       2.2  0.861 ati           0.861  0.861  19 x 10-10    ati 1.00 (both)
  lab6539      E_X      2.01   2.01 lstm           2.01   2.01  1 x 10-10     mlr 0.02 lstm 0.98 | mlr 0.11
      arx 0.03 lstm 0.86
  lab6539      E_Y      1.76   1.69 lstm           1.85   1.84  1 x 10-10     mlr 0.04 pcr 0.04 arx 0.90
      lstm 0.02 | arx 1.00
  lab6539      E_Z      1.62   1.54 lstm            2.7   2.77  1 x 10-10     arx 0.97 lagb 0.03 | mlr 0.02
      arx 0.85 lagb 0.09 lstm 0.04
  lab6540      E_X      1.97   1.97 lstm           2.32   2.85  1 x 10-10     mlr 0.52 arx 0.48 | mlr 0.09
      arx 0.91
  lab6540      E_Y      1.96   1.79 arx            1.68   1.75  1 x 10-10     mlr 0.26 arx 0.69 lstm 0.05 |
      mlr 0.49 arx 0.32 lstm 0.19
  lab6540      E_Z      1.25   1.04 pcr            1.29   1.34  1 x 10-10     mlr 0.48 arx 0.52 | mlr 0.35
      arx 0.65
  trunnion6541 E_X     0.243   0.24 lstm           0.24   0.24  -             lstm 1.00 (both)
  trunnion6541 E_Y     0.278  0.278 mlr           0.382  0.382  -             lagb 1.00 (both)
  trunnion6541 E_Z      2.45   1.21 hammerstein    1.21   1.21  -             hamm 1.00 (both)
  portal6542   E_X      9.46   4.65 lagbank        4.65   4.65  -             lagb 1.00 (both)
  portal6542   E_Y       5.3    5.3 mlr            6.66   6.66  -             mlr 0.05 lagb 0.88 lstm 0.07
      (both)
  portal6542   E_Z      24.8   16.8 hammerstein    16.8   16.8  -             hamm 1.00 (both)

  per record, mean over its targets: MLR, best single family, auto shipped / A, A / shipped (*: reached)
    year6531      2.518 0.9726  0.8572  0.878  1.024 *
    year6532       2.39  0.871  0.9135  0.865  0.947 *
    year6533      2.389 0.9095  0.8501 0.9247  1.088 *
    year6_6534     1.95  1.002  0.9369 0.7627  0.814 *
    year6_6535    3.543  1.132   1.344  1.944  1.446 *
    year6_6536    2.532  1.153  0.9093 0.8869  0.975 *
    climate6537   1.798 0.6196  0.6196 0.6196  1.000 *
    climate6538   1.618 0.6479  0.6479 0.6479  1.000 *
    lab6539       1.797  1.748   2.186  2.205  1.009 *
    lab6540       1.728  1.728   1.765  1.981  1.122 *
    trunnion6541 0.9887 0.6131  0.6103 0.6103  1.000
    portal6542    13.19  9.452   9.373  9.373  1.000

  CPU s (user + sys) per record (auto fit + each candidate alone): year6531 9, year6532 6, year6533 4,
      year6_6534 5, year6_6535 2, year6_6536 2, climate6537 59, climate6538 66, lab6539 6, lab6540 7,
      trunnion6541 14, portal6542 15; total 195
  all (12 records): better than MLR shipped 10 / A 10; within 10 % of the best single shipped 10 / A 9;
      geometric mean A / shipped 1.0266
  reached (10 records): better than MLR shipped 8 / A 8; within 10 % of the best single shipped 8 / A 7;
      geometric mean A / shipped 1.0321
  verdict: REVERT recommended (geometric mean 1.0321 > 1.00; records better than MLR 8 -> 8)
  targets: 34, reached 28; better than MLR shipped 26 / A 27; within 10 % of the best single shipped 26 / A
      25

**Verdict: revert recommended** (the rule written above: over the 10 reached records the geometric
mean A / shipped is 1.032 > 1.00; records better than MLR 8 -> 8; within 10 % of the best single
8 -> 7).  The rule reaches 10 of the 12 records: trunnion6541 and portal6542 are not reached
(their weekly campaigns continue each other in time, so ``reference=auto`` resolves to ``none``;
one blocked-forward fold) and are unchanged.  Per reached record A / shipped: year6_6534 0.814,
year6532 0.947, year6_6536 0.975, climate6537 / climate6538 1.000 (ati 1.00 either way), lab6539
1.009, year6531 1.024, year6533 1.088, lab6540 1.122, year6_6535 1.446.  The losses are the ones
autorep65 named: A forgives a family's offset over a run's first k samples, which the test (in the
first-sample frame) does not: year6_6535 E_Z 1.70 -> 3.31 (mlr 0.02 -> 0.28; in held-out campaign
2 MLR's squared error 11.9 -> 2.85 re-referenced, ati's 0.45 -> 1.52; MLR's test 8.19, mean
residual -6.7); lab6540 E_X 2.32 -> 2.85 (arx 0.48 -> 0.91, one fold, one held-out run; arx alone
2.98 on the test), as lab5401 (+10.7 %) did.  With 4 train campaigns (k 2-4) the effect is the
largest either way (0.814 and 1.446).  Targets (all 34): better than MLR 26 -> 27, within 10 % of
the best single 26 -> 25.  Pooled with bench_autorep65's 6 reached records (deciding nothing):
geometric mean 0.987 over the 16, 1.020 without hmc, the record that motivated the rule.
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
from _cli import run_commands  # noqa: E402
from rereference65 import rereferenced_squares  # noqa: E402

from thermocomp.core.metrics import rmse  # noqa: E402
from thermocomp.core.models.auto import BASELINE  # noqa: E402
from thermocomp.core.models.blend import vote_weights  # noqa: E402

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


def measured_test_only() -> None:
    """bench_auto_rank's test series on the measured rows only: a sparse target (a probe cycle,
    empty cells between: trunnion63, portal64) is scored on its measured rows, as ``thermocomp
    run`` scores it; a dense record's series are unchanged."""
    import bench_auto_rank as rank

    shipped = rank._test

    def test(comp, ds):
        meas, pred = shipped(comp, ds)
        keep = {t: np.isfinite(m) for t, m in meas.items()}
        return {t: m[keep[t]] for t, m in meas.items()}, {t: p[keep[t]] for t, p in pred.items()}

    rank._test = test


def run(root: Path, names: list[str]) -> None:
    autorep.keep_groups()
    measured_test_only()
    remeasure.AUTO.update(RECORDS)
    remeasure.measure(root / "auto.jsonl", (("auto", remeasure.auto_row(root, n)) for n in names))


def target_row(report: dict, a) -> dict:
    """One target from the fit's stored arrays: MLR, the best single, auto shipped (the votes
    without ``squared``) and rule A (``squared=rereferenced_squares`` where the folds hold out
    whole campaigns).  Measured with rule A in src (91ec8834: the fit's weights were A's); since
    the revert the fit runs the shipped votes, and its kept weights and test RMSE must be those
    (asserted)."""
    members, y, fold, base, group, preds, test, kept = autorep.stored(report, a)
    row = {"mlr": report["mlr"], "best_single": report["best_single"], "best_family": min(
        report["test"], key=report["test"].get)}
    if len(members) < 2 or BASELINE not in members:      # 'best' kept one: no votes
        return {**row, "auto": report["auto"]["rmse"], "A": report["auto"]["rmse"], "k": [],
                "voted": False, "w": kept, "wA": kept}
    col = members.index(BASELINE)
    shipped = vote_weights(preds, y, fold, base, base_column=col, min_folds=autorep.N_FOLDS)
    residual = np.column_stack([y[:, None] - preds, y - base])
    ks = autorep.rereferenced(residual, y, group, "A")[1]
    wA = shipped if group is None else vote_weights(
        preds, y, fold, base, base_column=col, min_folds=autorep.N_FOLDS,
        squared=rereferenced_squares(residual, y, group))
    assert all(abs(shipped[i] - kept.get(n, 0.0)) < 1e-9 for i, n in enumerate(members)), (members, kept)
    s_rmse, a_rmse = rmse(a["test_y"] - test @ shipped), rmse(a["test_y"] - test @ wA)
    assert abs(s_rmse - report["auto"]["rmse"]) < 1e-6 * (1 + s_rmse)
    return {**row, "auto": s_rmse, "A": a_rmse, "k": ks, "voted": True,
            "w": {n: round(float(v), 2) for n, v in zip(members, shipped) if v >= 0.005},
            "wA": {n: round(float(v), 2) for n, v in zip(members, wA) if v >= 0.005}}


def score(root: Path, names: list[str]) -> list[tuple[str, dict]]:
    return autorep.score(root, names, target_row)


def _w(weights: dict) -> str:
    return " ".join(f"{remeasure._ABBREVIATED.get(n, n)} {v:.2f}" for n, v in weights.items())


def verdict(root: Path, names: list[str]) -> list[str]:
    scored = score(root, names)
    cpu = {r["record"]: r["cpu_s"] for r in remeasure._read(root / "auto.jsonl")}
    lines = [f"{'record':12s} {'target':6s} {'MLR':>6s} {'best':>6s} {'(family)':12s} {'auto':>6s} "
             f"{'A':>6s}  k             weights shipped | A"]
    means = []
    for name, s in scored:
        rows = s["targets"]
        for t, r in rows.items():
            ks = r["k"]
            kk = f"{len(ks)} x {min(ks)}-{max(ks)}" if ks else "-"
            lines.append(f"{name:12s} {t[:6]:6s} {r['mlr']:6.3g} {r['best_single']:6.3g} "
                         f"{r['best_family'][:12]:12s} {r['auto']:6.3g} {r['A']:6.3g}  {kk:13s} "
                         + (f"{_w(r['w'])} | {_w(r['wA'])}" if r["w"] != r["wA"] else
                            f"{_w(r['w'])} (both)"))
        reached = any(r["voted"] and r["k"] for r in rows.values())
        m = {k: float(np.mean([r[k] for r in rows.values()])) for k in ("mlr", "auto", "A")}
        m["best"] = min(s["family_mean"].values())
        means.append((name, m, reached))
    lines += ["", "per record, mean over its targets: MLR, best single family, auto shipped / A, "
              "A / shipped (*: reached)"]
    lines += [f"  {n:12s} {m['mlr']:6.4g} {m['best']:6.4g}  {m['auto']:6.4g} {m['A']:6.4g}  "
              f"{m['A'] / m['auto']:.3f}{' *' if hit else ''}" for n, m, hit in means]
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
        lines.append(f"{label} ({n} records): better than MLR shipped {better['auto']} / A "
                     f"{better['A']}; within 10 % of the best single shipped {near['auto']} / A "
                     f"{near['A']}; geometric mean A / shipped {geo:.4f}")
        if label == "reached":
            stays = geo <= 1.0 and better["A"] >= better["auto"]
            lines.append("verdict: " + ("the rule STAYS" if stays else "REVERT recommended")
                         + f" (geometric mean {geo:.4f} {'<=' if geo <= 1.0 else '>'} 1.00; records "
                         f"better than MLR {better['auto']} -> {better['A']})")
    targets = [r for _, s in scored for r in s["targets"].values()]
    hit = [r for r in targets if r["voted"] and r["k"]]
    lines.append(f"targets: {len(targets)}, reached {len(hit)}; better than MLR shipped "
                 f"{sum(r['auto'] < r['mlr'] for r in targets)} / A {sum(r['A'] < r['mlr'] for r in targets)}"
                 f"; within 10 % of the best single shipped "
                 f"{sum(r['auto'] <= 1.1 * r['best_single'] for r in targets)} / A "
                 f"{sum(r['A'] <= 1.1 * r['best_single'] for r in targets)}")
    return lines


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "write": lambda root, *_: write(Path(root).resolve()),
        "run": lambda root, *names: run(Path(root).resolve(), list(names) or list(RECORDS)),
        "score": lambda root, *names: print(remeasure._wrapped(
            verdict(Path(root).resolve(), list(names) or list(RECORDS)), 106)),
    }, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
