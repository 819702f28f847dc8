"""``model=auto`` judged on more test campaigns of the same machines (issue 34 item 3; stop 69,
automore69): moretest68's instrument for auto.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_remeasure62.py write ROOT                 # the records (once)
    python benchmarks/bench_automore69.py rows ROOT WORK [RECORD ...] # -> WORK/automore.jsonl
    python benchmarks/bench_automore69.py table WORK [WORK ...]       # per record, the counts
    python benchmarks/bench_automore69.py halves WORK RECORD ...      # auto / MLR per half campaign

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

* ``hmc``: bench_new_machines59's writer, seeds 6939-6940 (the same networks and sensors; runs,
  speeds and the logger's overloads drawn again), 8 runs each: 16, read with its init config.
* the strangers' lab records (``ROOT/labs``: ``bench_stranger66.py write ROOT/labs``, ``init
  ROOT/labs tsc_a2 data.max_gap_samples=4``; bench_iso67 ``write`` + ``init`` iso_a, iso_b;
  bench_stranger68 ``write`` + ``init`` mtc_a, mtc_b), fitted with lab_matrix's auto candidates
  ``[mlr,pcr,arx,lagbank,hammerstein,ati]``: each bench's own ``write`` (the lab's format) of one
  record simulated with a new seed and its variant's overrides (iso_b two weeks later, mtc_b
  three), read with the record's init config: tsc66 6931-6932 (12 runs), iso67 6933-6934 (12
  tests, the same draws for iso_a and iso_b, each in its own format), mtc68 6935-6936 (16 runs,
  likewise).  stable67's grinder as bench_zerofew67 writes it (``write ROOT``: grind_a / grind_b,
  14 runs, the last 3 test): its 14 runs of seeds 6937-6938 (28), dated 4 / 8 weeks on.
The same seed integer in two machines is two unrelated draws (another generator).  Checked on
every record: the own campaigns' continuation links are those of the record alone, a new
campaign continues at most one of its own draw.

Not drawn: ``fl9010`` (the measured fl_thermal record).

Measured (2026-12-01, stop 69, main 3d65c78c = the shipped code; 2 shared cores, load 11-15;
every record once; CPU user + sys of the rows, the draws' simulation included: 417 s, 6-28 s a
record, mill1514 57)
-----------------------------------------------------------------------------------------------
Every record's own test equals the shipped rows (bench_autorep65's table, MLR and auto to 4
digits; col6511's auto 8.119 there 8.115).  Record mean test RMSE, auto / MLR and auto / the
best single family (after the fact: the family best on the own test, resp. on the new
campaigns)::

  record      own/new  auto/MLR own | new [90 %]   auto/best own | new [90 %] (family)   own loss
  swiss303     1/12    0.56 | 0.57 [0.54, 0.60]    1.00 | 1.00 [1.00, 1.00] hammerstein
  swiss5454    1/12    0.93 | 0.95 [0.94, 0.96]    1.50 | 1.54 [1.45, 1.62] hammerstein
  year6_5411   2/16    0.68 | 0.52 [0.43, 0.62]    1.53 | 1.40 [1.20, 1.59] ati
  year6511     8/16    0.37 | 0.35 [0.30, 0.41]    1.08 | 0.92 [0.86, 0.97] ati
  year6512     8/16    0.47 | 0.38 [0.34, 0.42]    1.26 | 0.91 [0.81, 1.01] ati
  lab5401      1/12    1.02 | 1.07 [1.07, 1.07]    1.04 | 1.07 [1.07, 1.07] mlr          real
  mill1514     1/12    1.01 | 1.01 [1.01, 1.01]    1.01 | 1.01 [1.01, 1.01] mlr          real
  col5791      1/12    1.32 | 1.33 [1.32, 1.34]    1.32 | 1.33 [1.32, 1.34] mlr          real
  col1403      1/12    1.27 | 1.31 [1.29, 1.33]    1.27 | 1.31 [1.29, 1.33] mlr          real
  col1514      1/12    1.03 | 1.02 [1.01, 1.03]    1.14 | 1.21 [1.20, 1.23] arx          real
  col6511      1/12    1.05 | 1.04 [1.04, 1.05]    1.05 | 1.04 [1.04, 1.05] mlr          real
  col6512      1/12    1.02 | 1.01 [1.01, 1.01]    1.02 | 1.01 [1.01, 1.01] mlr          real
  twin_lathe   1/12    0.96 | 0.97 [0.95, 0.99]    0.96 | 1.07 [1.01, 1.13] lagbank
  jig_grinder  2/16    0.97 | 0.94 [0.92, 0.96]    1.03 | 0.99 [0.97, 1.01] arx
  hmc          2/16    1.62 | 1.01 [0.86, 1.16]    1.66 | 1.15 [1.00, 1.29] lagbank      noise
  tsc_a2       1/12    0.32 | 0.38 [0.35, 0.40]    1.05 | 1.04 [0.99, 1.11] hammerstein
  iso_a        1/12    0.95 | 0.96 [0.95, 0.97]    1.42 | 0.97 [0.96, 0.99] arx
  iso_b        1/12    0.56 | 0.87 [0.72, 1.01]    0.96 | 1.00 [0.96, 1.06] hammerstein
  mtc_a        1/16    0.62 | 0.70 [0.64, 0.77]    0.92 | 0.95 [0.93, 0.97] hammerstein
  mtc_b        1/16    1.12 | 1.07 [0.79, 1.33]    1.12 | 1.08 [0.79, 1.33] arx          noise
  grind_a      3/28    0.98 | 0.94 [0.92, 0.97]    1.00 | 0.95 [0.92, 0.97] arx
  grind_b      3/28    0.99 | 0.99 [0.96, 1.03]    1.00 | 1.00 [0.97, 1.04] arx

22 records: auto better than MLR on its own test 13, on the new campaigns 13 (interval below 1:
11; above 1: 7); within 10 % of the best single family own 13, new 16.  Of the 9 own-test
losses to MLR, 7 are real (lab5401, mill1514 and the five columns: two machines) and 2 noise:
hmc, auto's worst (1.62; its E_Y, hammerstein alone, 2.03 x MLR on the 2 test runs, 1.08 on 16
new ones) and mtc_b (its test run at B = 90 deg; 1.07 with the interval from 0.79 to
1.33 on 16 runs).  No win turns into a loss (iso_b: 0.56 on its test,
0.87 with the interval reaching 1.01).  Where the test programme is fixed and only its switching
times and noise are drawn (the column, the mill), the new campaigns vary little: their intervals
are narrow by construction and say the loss is not the test draw's, not that another test
programme would show it.

Do the real losses share a mechanism?  ``halves``: auto / MLR on the new campaigns' first half,
then their second (the column's test cycle runs the unseen source Q3 from 50 to 75 % of it):
col5791 0.98 -> 1.38, col1514 0.98 -> 1.02, col6511 1.01 -> 1.05 (the loss in Q3's half: a
condition no train fold holds, which no rule on the folds can see; bench_auto_rank's (stop 57)
and remeasure62's forensics of the column say the same), col6512 1.02 -> 1.02 (+1 %); col1403
1.40 -> 1.32 (both halves: its forward folds put lagbank / hammerstein at 0.55-0.68 of MLR's
validation on E_Y and E_Y_mid, tested 1.85 / 2.08 x MLR: a misranking by the folds of its one
train record); the mill lab5401 1.03 -> 1.09, mill1514 1.01 -> 1.01 (spread over its validation
week; mill1514's +1 % is within 2 %).  Three mechanisms, one of them (Q3) invisible to the fit:
**no rule proposed, no src change**.  (Lead, after autorule69: ``halves`` took the label as
measured against predictions referenced to each campaign's first sample; now referenced as the
scores are, ``label``: the ratios above re-read so, at most 0.01 moved.)
"""

from __future__ import annotations

import os
import pickle
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_autorep65 as autorep  # noqa: E402
import bench_remeasure62 as remeasure  # noqa: E402
from _cli import run_commands  # noqa: E402

SEEDS = list(range(6911, 6923))
YEAR_SEEDS, YEAR6_SEEDS = [6911, 6912], list(range(6911, 6919))
TWIN_SEEDS, JIG_SEEDS, HMC_SEEDS = list(range(6923, 6929)), [6929, 6930], [6939, 6940]
LAB_CANDIDATES = "model.candidates=[mlr,pcr,arx,lagbank,hammerstein,ati]"   # lab_matrix's auto
LABS = {    # a stranger's lab record -> (its bench, the folder its write names, the simulate
            # overrides of its variant, the seeds drawn again); ROOT/labs: the benches' ROOT
    "tsc_a2": ("bench_stranger66", "tsc_a", ("tsc66", "conf66"), [6931, 6932]),
    "iso_a": ("bench_iso67", "iso_a", ("iso67", "conf67"), [6933, 6934]),
    "iso_b": ("bench_iso67", "iso_b", ("iso67", "conf67", "sim.generator.weeks_later=2"),
              [6933, 6934]),
    "mtc_a": ("bench_stranger68", "mtc_a", ("mtc68", "conf68"), [6935, 6936]),
    "mtc_b": ("bench_stranger68", "mtc_b", ("mtc68", "conf68", "sim.generator.weeks_later=3"),
              [6935, 6936]),
}
GRINDS = {"grind_a": 0.0, "grind_b": 1.5}     # stable67's grinder (spindle_um), 14 runs
GRIND_RUNS, GRIND_OWN, GRIND_SEEDS = 14, {"grind_a": 6711, "grind_b": 6712}, [6937, 6938]
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
    "hmc": ("folder", "hmc", HMC_SEEDS),
    **{name: ("lab", name, seeds) for name, (_, _, _, seeds) in LABS.items()},
    **{name: ("grind", name, GRIND_SEEDS) for name in GRINDS},
}
OF = {**{n: "column" for n in ("col5791", "col1403", "col1514", "col6511", "col6512")},
      "swiss303": "swiss", "swiss5454": "swiss", "mill1514": "mill", "lab5401": "lab_mill",
      "year6511": "year", "year6512": "year", "year6_5411": "year6", "twin_lathe": "twin_lathe",
      "jig_grinder": "jig", "hmc": "hmc", **{n: n for n in (*LABS, *GRINDS)}}
OVERRIDES = {**remeasure.AUTO, **autorep.EXTRA,
             **{n: [f"hydra.searchpath=[file://{{root}}/labs/init-{n}/conf]", f"data={n}", LAB_CANDIDATES]
                for n in LABS},
             **{n: [f"data.path={{root}}/{n}"] for n in GRINDS}}
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
        elif kind == "hmc":
            import bench_new_machines59 as nm59
            nm59.write_hmc(folder, seed)
        else:
            import bench_new_machines60 as nm60
            nm60.write_jig_grinder(folder, seed)
    return io.read_dataset(folder, data_options(cfg))[0]


def _lab(name: str, seed: int, folder: Path, cfg):
    """A stranger's lab record drawn again: its bench's ``write`` (the lab's format) of one record
    simulated with ``seed`` and its variant's overrides, read with the record's init config."""
    import importlib

    import lab_matrix

    from thermocomp.core import io
    from thermocomp.shell.config.checks import data_options

    bench, written, (scenario, conf, *extra), _ = LABS[name]
    mod = importlib.import_module(bench)
    if not (folder / written).exists():
        shipped = mod.simulate, mod.SEEDS
        mod.simulate = lambda s, path: lab_matrix.simulate_scenario(scenario, conf, s, path, *extra)
        mod.SEEDS = {written: seed}
        try:
            mod.write(folder, mod.SEEDS) if bench == "bench_iso67" else mod.write(folder)
        finally:
            mod.simulate, mod.SEEDS = shipped
        if name == "tsc_a2":          # its run 5's cut-off last line deleted, as tsc_a2's (initialised)
            cut = folder / written / f"TC2_run{mod.CUT + 1:02d}.txt"
            text = cut.read_text(encoding="utf-8")
            cut.write_text(text[:text.rindex("\n") + 1], encoding="utf-8")
    path = mod.record_path(folder, written) if hasattr(mod, "record_path") else folder / written
    return io.read_dataset(path, data_options(cfg))[0]


def _grind(name: str, seed: int):
    """The grinder's 14 runs of ``seed``, dated 4 weeks later per seed drawn (its runs 3 -> 4
    and 7 -> 8 continue each other by their times: on the record's own calendar which draw a
    run continues would be ambiguous)."""
    import pandas as pd
    from stable67 import Stable67

    ds = Stable67(runs=GRIND_RUNS, spindle_um=GRINDS[name], seed=seed).generate()[0]
    weeks = 4 * (GRIND_SEEDS.index(seed) + 1)
    ds.manifest["start"] = [str(pd.Timestamp(t) + pd.Timedelta(weeks=weeks)) for t in ds.manifest["start"]]
    return ds


def write(root: Path) -> None:
    """The grinder's two records as bench_zerofew67 writes them (the last fifth of the runs test)."""
    import bench_zerofew67 as zerofew

    for name, spindle in GRINDS.items():
        if not (root / name).exists():
            zerofew.grind_record(root / name, GRIND_RUNS, spindle, GRIND_OWN[name])


def draws(machine: str, work: Path, cfg) -> list:
    """The new datasets of ``machine`` (cached as pickles under ``work/draws``)."""
    how, what, seeds = MACHINES[machine]
    out = []
    for seed in seeds:
        cache = work / "draws" / f"{machine}-{seed}.pkl"
        if not cache.exists():
            cache.parent.mkdir(parents=True, exist_ok=True)
            folder = work / "draws" / f"{machine}-{seed}"
            ds = (_simulated(what, seed) if how == "sim" else _written(what, seed, folder, cfg)
                  if how == "folder" else _lab(what, seed, folder, cfg) if how == "lab"
                  else _grind(what, seed))
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
    # the own campaigns' links kept; a new campaign continues at most one of its own draw
    assert {c: p for c, p in links.items() if c in ds.ids()} == predecessors(ds), name
    assert all(p.split("_")[0] == c.split("_")[0] for c, p in links.items() if c not in ds.ids()), name
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


def table(works: list[Path]) -> None:
    got = {r["record"]: r for w in works for r in remeasure._read(w / "automore.jsonl")}
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


def label(a, reference: str) -> np.ndarray:
    """The stored label (``y``: as measured) in the frame the squares were taken in: with
    ``first_sample`` each campaign less its first measured value (reproduces every stored SSE)."""
    y, c = a["y"].copy(), a["campaign"]
    if reference == "first_sample":
        for k in np.unique(c):
            rows = np.flatnonzero((c == k) & np.isfinite(y))
            y[c == k] -= y[rows[0]]
    return y


def halves(work: Path, names: list[str]) -> None:
    """Auto / MLR on the first and the second half of each new campaign (the record's mean over
    its targets of the pooled RMSE, from WORK/pred): the column's test cycle runs the unseen
    source Q3 in its second half."""
    got = {r["record"]: r for r in remeasure._read(work / "automore.jsonl")}
    for name in names:
        own, part = len(got[name]["own"]), {"first": [], "second": []}
        for t in got[name]["squares"]["auto"]:
            a = np.load(work / "pred" / f"{name}.{t}.npz")
            c, y = a["campaign"], label(a, got[name]["reference"])
            first = np.zeros(len(y), bool)
            for k in np.unique(c):
                rows = np.flatnonzero(c == k)
                first[rows[:len(rows) // 2]] = True
            for half, keep in (("first", first), ("second", ~first)):
                keep = keep & (c >= own) & np.isfinite(y)
                part[half].append([np.sqrt(np.mean((y[keep] - a[f"pred_{m}"][keep]) ** 2))
                                   for m in ("auto", "mlr")])
        print(name, "; ".join(f"{h} half: auto {np.mean(v, 0)[0]:.3g}, MLR {np.mean(v, 0)[1]:.3g} "
                              f"({np.mean(v, 0)[0] / np.mean(v, 0)[1]:.2f})" for h, v in part.items()))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "write": lambda root, *_: write(Path(root).resolve()),
        "rows": lambda root, work, *records: rows(Path(root).resolve(), Path(work).resolve(),
                                                  list(records) or list(OF)),
        "halves": lambda work, *records: halves(Path(work).resolve(), list(records)),
        "table": lambda *works: table([Path(w).resolve() for w in works]),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
