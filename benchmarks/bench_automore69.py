"""``model=auto`` judged on more test campaigns of the same machines (issue 34 item 3; stop 69,
automore69): moretest68's instrument for auto.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_remeasure62.py write ROOT                 # the records (once)
    python benchmarks/bench_automore69.py rows ROOT WORK [RECORD ...] # -> WORK/automore.jsonl
    python benchmarks/bench_automore69.py table WORK                  # per record, the counts

Per record (bench_remeasure62's ``auto`` records and bench_autorep65's fresh ones, each with the
overrides those benches fit it with): auto, then every candidate it validated (MLR among them)
alone, all fitted once on the record's own train campaigns exactly as ``bench_auto_rank`` fits
them (``run``'s config, ``model=auto``), then each scored in simulation mode on the record's own
test campaigns AND on 12-24 NEW campaigns of the same machine drawn again (the same network, law
and sensors; new programmes, weather, noise), appended as test campaigns after its own
(moretest68's ``with_new``; nothing of the train split changes, so the fits are the record's).
Every model's squared errors are kept per campaign and target (WORK/automore.jsonl) and the
candidates' predictions as WORK/pred/RECORD.TARGET.npz (with auto's out-of-fold arrays), so a
rule on auto's weights can be scored again without a refit.  Nothing here reads a test campaign
to choose: it is only scored.  The draws are cached (WORK/draws/MACHINE-SEED.pkl).

A record's figure is the mean over its targets of the pooled test RMSE (bench_remeasure62's);
auto / MLR on the new campaigns comes with a 90 % interval: the new campaigns resampled with
replacement (2000 times, every target the same campaigns), the 5 % and 95 % of the ratio.  A
loss to MLR on the own test is REAL when that interval lies above 1, NOISE when it lies below or
contains 1 (auto not worse than MLR on more campaigns of the same machine).  The best single
family on the new campaigns is the family with the lowest record mean there (known after the
fact), auto / best with its interval likewise.

What is drawn again (fresh seeds 6911-6940 only; the simulators' machines do not depend on the
seed: each draws its network and sensors from a fixed generator)
-----------------------------------------------------------------------------------------------
* ``column`` (col5791, col1403, col1514, col6511, col6512: one machine): the test cycle (40 h,
  shifted ambient, the unseen source Q3 in its second half) of seeds 6911-6922: 12 campaigns.
* ``swiss`` (swiss303, swiss5454): the 24 h production run of seeds 6911-6922: 12.
* ``mill`` (mill1514: ``large_mill_week``, 120 s): the validation week of seeds 6911-6922: 12.
* ``lab_mill`` (lab5401: ``large_mill_week`` with a 30 h train week and a 12 h test, written as
  runs by bench_auto_losses56): the 12 h test of seeds 6911-6922: 12.
* ``year`` (year6511, year6512: ``yearround_spindle``): the 8 test campaigns of seeds 6911-6912:
  16.  ``year6`` (year6_5411: 6 campaigns): the 2 test campaigns of seeds 6911-6918: 16.
* ``twin_lathe``: bench_new_machines57's writer with seeds 6923-6928 (the same network and law;
  its two season files each): 12 campaigns, read with the record's own init config.
* ``jig`` (jig_grinder): bench_new_machines60's writer, seeds 6929-6930 (bench_jig68's draws: room,
  ceiling, schedule drawn again), 8 sessions each: 16, read with the record's init config.
The same seed integer in two machines is two unrelated draws (another generator).

Not drawn: ``fl9010`` (the measured fl_thermal record); ``hmc`` (bench_new_machines59's writer
draws its own sensor layout per seed: another machine); the stranger machines (tsc66, iso67,
mtc68, stable67): left for want of time, see the report below.
"""

from __future__ import annotations

import json
import os
import pickle
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]

import bench_autorep65 as autorep  # noqa: E402
import bench_remeasure62 as remeasure  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

SEEDS = list(range(6911, 6923))
YEAR_SEEDS, YEAR6_SEEDS = [6911, 6912], list(range(6911, 6919))
TWIN_SEEDS, JIG_SEEDS = list(range(6923, 6929)), [6929, 6930]
LAB_MILL = ["sim=large_mill_week", "sim.generator.train_hours=30", "sim.generator.test_hours=12"]
MACHINES = {       # machine -> (how a draw is made, its overrides or writer, seeds)
    "column": ("sim", ["sim=column_moving_source"], SEEDS),
    "swiss": ("sim", ["sim=swiss_lathe_door"], SEEDS),
    "mill": ("sim", remeasure.MILL, SEEDS),
    "lab_mill": ("sim", LAB_MILL, SEEDS),
    "year": ("sim", ["sim=yearround_spindle"], YEAR_SEEDS),
    "year6": ("sim", ["sim=yearround_spindle", "sim.generator.n_campaigns=6"], YEAR6_SEEDS),
    "twin_lathe": ("folder", "twin_lathe", TWIN_SEEDS),
    "jig": ("folder", "jig", JIG_SEEDS),
}
OF = {**{n: "column" for n in ("col5791", "col1403", "col1514", "col6511", "col6512")},
      "swiss303": "swiss", "swiss5454": "swiss", "mill1514": "mill", "lab5401": "lab_mill",
      "year6511": "year", "year6512": "year", "year6_5411": "year6", "twin_lathe": "twin_lathe",
      "jig_grinder": "jig"}
OVERRIDES = {**remeasure.AUTO, **autorep.EXTRA}
RESAMPLES, LEVELS = 2000, (5, 95)


def _test_only(ds):
    """``ds``'s test campaigns alone (a draw's train part is another calibration, not a test)."""
    from thermocomp.core.io.contract import Dataset

    ids = ds.ids("test")
    return Dataset(ds.manifest.loc[ids], {c: ds.campaigns[c] for c in ids}, ds.name, dict(ds.meta))


def _simulated(overrides: list[str], seed: int):
    from hydra import compose, initialize_config_dir
    from hydra.utils import instantiate

    from thermocomp.base.paths import conf_dir

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[*overrides, f"seed={seed}"])
    return _test_only(instantiate(cfg.sim.generator).generate()[0])


def _written(kind: str, seed: int, folder: Path, cfg):
    """A folder record drawn again by its bench's writer and read with the record's config:
    every campaign of it is new (each draw is a whole new record of the machine)."""
    from thermocomp.core import io
    from thermocomp.shell.config.checks import data_options

    if not folder.exists():
        if kind == "twin_lathe":
            import bench_new_machines57 as nm57
            nm57.write_twin_lathe(folder, seed)
        else:
            import bench_new_machines60 as nm60
            nm60.write_jig_grinder(folder, seed)
    return io.read_dataset(folder, data_options(cfg))[0]


def draws(machine: str, work: Path, cfg) -> list:
    """The new datasets of ``machine`` (cached as pickles under ``work/draws``)."""
    how, what, seeds = MACHINES[machine]
    out = []
    for seed in seeds:
        cache = work / "draws" / f"{machine}-{seed}.pkl"
        if not cache.exists():
            cache.parent.mkdir(parents=True, exist_ok=True)
            ds = (_simulated(what, seed) if how == "sim"
                  else _written(what, seed, work / "draws" / f"{machine}-{seed}", cfg))
            cache.write_bytes(pickle.dumps(ds))
        out.append(pickle.loads(cache.read_bytes()))
    return out


def _squares(comp, ds, ids) -> dict:
    """``{target: {campaign: (samples, SSE, SSE of no correction)}}`` in simulation mode, the
    measured rows only (``run``'s scoring), and the predictions (``{target: {campaign: array}}``)."""
    from thermocomp.core.scoring.evaluation import split_residuals

    _, _, series = split_residuals(comp, ds, ids, "simulation")
    out, pred = {}, {}
    for t, (y, r) in series.items():
        keep = {c: np.isfinite(y[c]) & np.isfinite(r[c]) for c in ids}
        out[t] = {c: (int(keep[c].sum()), float(np.sum(r[c][keep[c]] ** 2)),
                      float(np.sum(y[c][keep[c]] ** 2))) for c in ids}
        pred[t] = {c: y[c] - r[c] for c in ids}
    return out, pred


def record_row(root: Path, work: Path, name: str) -> dict:
    """Auto and each candidate alone fitted on ``name``'s train campaigns (bench_auto_rank), each
    scored per campaign on the own test campaigns and the new ones."""
    import bench_auto_rank as rank
    from bench_moretest68 import with_new
    from sklearn.base import clone

    from thermocomp.core.continuation import predecessors
    from thermocomp.shell.builders import build_compensator

    overrides = [o.format(root=root) for o in OVERRIDES[name]]
    sys.argv[2:] = overrides              # bench_auto_rank simulates when sim= is asked
    cfg, ds, train = rank.setup(overrides)
    news = draws(OF[name], work, cfg)
    full = with_new(ds, news)
    links = predecessors(full)
    assert links == predecessors(ds), (name, {c: p for c, p in links.items() if c not in ds.ids()})
    own, new = ds.ids("test"), [c for c in full.ids("test") if c not in ds.ids()]
    draw_of = [k for k, n in enumerate(news) for _ in n.ids()]
    auto = build_compensator(cfg, ds=ds).fit(train)
    names = list(dict.fromkeys(n for e in auto.estimators_.values() for n in e.oof_))
    models = {"auto": auto}
    for n in names:
        models[n] = clone(auto).set_params(estimator=clone(auto.estimator.candidates.get(n)
                                                              or rank._mlr())).fit(train)
    squares, preds = {}, {}
    for n, comp in models.items():
        squares[n], preds[n] = _squares(comp, full, own + new)
    weights = {t: {n: float(w) for n, w in e.weights_.items()} for t, e in auto.estimators_.items()}
    (work / "pred").mkdir(parents=True, exist_ok=True)
    for t, e in auto.estimators_.items():
        ys = {c: full.campaigns[c][t].to_numpy(float) for c in own + new}
        np.savez(work / "pred" / f"{name}.{t}.npz", oof_y=e.oof_y_, oof_fold=e.oof_fold_,
                 **{f"oof_{n}": e.oof_[n] for n in e.oof_},
                 campaign=np.concatenate([[k] * len(ys[c]) for k, c in enumerate(own + new)]),
                 y=np.concatenate([ys[c] for c in own + new]),
                 **{f"pred_{n}": np.concatenate([preds[n][t][c] for c in own + new]) for n in models})
    return {"record": name, "machine": OF[name], "own": own, "new": new, "draw_of_new": draw_of,
            "reference": str(cfg.data.reference), "weights": weights,
            "validation": {t: {n: float(v) for n, v in e.validation_.items()}
                           for t, e in auto.estimators_.items()},
            "squares": squares}


def rows(root: Path, work: Path, names: list[str]) -> None:
    work.mkdir(parents=True, exist_ok=True)
    os.environ.setdefault("OUT", str(work / "rank"))
    remeasure.measure(work / "automore.jsonl", (("auto", record_row(root, work, n)) for n in names))


# --- the table ---

def _arrays(row: dict, ids: list[str]) -> tuple[list[str], list[str], np.ndarray]:
    """``(models, targets, a)``: ``a[m, t, c]`` = (samples, SSE, SSE none) of campaign ``ids[c]``."""
    models, targets = list(row["squares"]), list(row["squares"]["auto"])
    a = np.array([[[row["squares"][m][t][c] for c in ids] for t in targets] for m in models], float)
    return models, targets, a


def record_rmse(a: np.ndarray, pick=None) -> np.ndarray:
    """Per model: the mean over targets of the pooled RMSE of campaigns ``pick`` (all)."""
    part = a if pick is None else a[:, :, pick]
    return np.sqrt(part[..., 1].sum(-1) / part[..., 0].sum(-1)).mean(-1)


def interval(a: np.ndarray, i: int, j: int, seed: int = 0) -> tuple[float, float]:
    """5 % and 95 % of model i's record RMSE over model j's, the campaigns resampled."""
    rng = np.random.default_rng(seed)
    picks = rng.integers(0, a.shape[2], (RESAMPLES, a.shape[2]))
    ratios = [record_rmse(a[[i, j]], p) for p in picks]
    r = np.array([x[0] / x[1] for x in ratios])
    return tuple(np.percentile(r, LEVELS))


def summary(row: dict) -> dict:
    """One record's figures: auto / MLR on its own test and on the new campaigns (interval),
    auto / best single family on both, the verdict of an own-test loss."""
    models, _, own = _arrays(row, row["own"])
    _, _, new = _arrays(row, row["new"])
    ia, im = models.index("auto"), models.index("mlr")
    own_r, new_r = record_rmse(own), record_rmse(new)
    families = [k for k, m in enumerate(models) if m != "auto"]
    best_own = families[int(np.argmin(own_r[families]))]
    best_new = families[int(np.argmin(new_r[families]))]
    lo, hi = interval(new, ia, im)
    blo, bhi = interval(new, ia, best_new)
    loss = own_r[ia] > own_r[im]
    verdict = ("real" if lo > 1.0 else "noise") if loss else ("win holds" if hi < 1.0 else
                                                              "lost on new" if lo > 1.0 else "tie")
    return {"record": row["record"], "own_n": len(row["own"]), "new_n": len(row["new"]),
            "mlr": (own_r[im], new_r[im]), "auto": (own_r[ia], new_r[ia]),
            "to_mlr": (own_r[ia] / own_r[im], new_r[ia] / new_r[im], lo, hi),
            "best": (models[best_own], own_r[best_own], models[best_new], new_r[best_new]),
            "to_best": (own_r[ia] / own_r[best_own], new_r[ia] / new_r[best_new], blo, bhi),
            "verdict": verdict, "cpu_s": row.get("cpu_s", np.nan)}


def table(work: Path) -> None:
    got = {r["record"]: r for r in remeasure._read(work / "automore.jsonl")}
    lines = ["record       own/new  MLR own -> new   auto own -> new   auto/MLR own | new [90 %]        "
             "best own; new (family)         auto/best own | new [90 %]    own-test loss"]
    sums = [summary(r) for r in got.values()]
    for s in sums:
        m, a, r, b, rb = s["mlr"], s["auto"], s["to_mlr"], s["best"], s["to_best"]
        lines.append(f"{s['record']:12s} {s['own_n']:2d}/{s['new_n']:2d}  {m[0]:6.3g} -> {m[1]:6.3g}  "
                     f"{a[0]:6.3g} -> {a[1]:6.3g}  {r[0]:5.2f} | {r[1]:5.2f} [{r[2]:.2f}, {r[3]:.2f}]  "
                     f"{b[1]:6.3g} {b[0][:5]:5s}; {b[3]:6.3g} {b[2][:5]:5s}  "
                     f"{rb[0]:5.2f} | {rb[1]:5.2f} [{rb[2]:.2f}, {rb[3]:.2f}]  {s['verdict']}")
    own_better = sum(s["to_mlr"][0] < 1 for s in sums)
    new_better = sum(s["to_mlr"][1] < 1 for s in sums)
    lines += ["", f"records {len(sums)}; auto better than MLR: own test {own_better}, new campaigns "
              f"{new_better}; interval above 1 (a real loss) {sum(s['to_mlr'][2] > 1 for s in sums)}, "
              f"below 1 (a real win) {sum(s['to_mlr'][3] < 1 for s in sums)}",
              f"within 10 % of the best single family: own {sum(s['to_best'][0] <= 1.1 for s in sums)}, "
              f"new {sum(s['to_best'][1] <= 1.1 for s in sums)}",
              "own-test losses to MLR: " + ", ".join(f"{s['record']} {s['verdict']}" for s in sums
                                                     if s["to_mlr"][0] > 1),
              f"CPU s {sum(s['cpu_s'] for s in sums):.0f} (" + ", ".join(
                  f"{s['record']} {s['cpu_s']:.0f}" for s in sums) + ")"]
    print(remeasure._wrapped(lines, 150))


def main(argv: list[str]) -> int:
    what, rest = (argv or [""])[0], argv[1:]
    start = cpu_seconds()
    if what == "rows":
        rows(Path(rest[0]).resolve(), Path(rest[1]).resolve(), rest[2:] or list(OF))
    elif what == "table":
        table(Path(rest[0]).resolve())
    else:
        print(__doc__)
        return 2
    print(f"CPU s (user + sys) of this process: {cpu_seconds() - start:.1f}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
