"""``model=auto``'s no-correction rule (stable67) on few folds: a lab's first record of 3-5 short
train runs (issue 34; stop 67, zerofew67).

Usage::

    python benchmarks/bench_zerofew67.py write ROOT       # the data.path records (once)
    python benchmarks/bench_zerofew67.py run ROOT [RECORD ...]   # auto (uncompensated=keep) per record
    python benchmarks/bench_zerofew67.py score ROOT [ZEROCHECK_A ZEROCHECK_B]   # the verdict

The rule (stable67, ``model.estimator.uncompensated=zero``, the default): a target whose kept
model's pooled validation RMSE is NOT below no correction's (``none``, the RMS of the out-of-fold
labels) keeps a zero correction.  Known loss (tests/shell/test_export_auto57.py's spindle fixture,
4 short train runs, 2 folds): none validated 0.767 against Hammerstein's 0.974, the zero tested
1.697 µm against 0.639.  The question: with few folds, how often does the rule zero a target a
model would have corrected, how often does it save a stable axis?

The records (chosen and written here BEFORE anything was run or scored; seeds 6771-6790, on none
of which anything was tuned; each 3-5 train runs)
------------------------------------------------------------------------------------------------
* ``year3_6771..6773``: ``sim=yearround_spindle`` with ``sim.generator.n_campaigns=4`` (every
  third by date held out: 3 train campaigns, 1 test), seeds 6771-6773 (bench_autocheck65's
  year6_* cut to fewer campaigns);
* ``year5_6774..6776``: the same with ``n_campaigns=7`` (5 train, 2 test), seeds 6774-6776;
* ``grind5_6777``, ``grind5_6778``: stable67's grinder (``benchmarks/conf67``, ``sim=stable67``)
  with ``sim.generator.runs=5`` and ``data.test_fraction=0.2`` (4 train runs, 1 test), the
  machine as built (``spindle_um=0``); ``grind5_6779``, ``grind5_6780``: the same with the
  1.5 µm spindle growth on E_Z (``spindle_um=1.5``);
* ``lab6781``, ``lab6782``: bench_autocheck65's ``lab_record`` (``large_mill_week``, a 30 h week
  cut into three 10 h runs, a 12 h test run: 3 train runs, one fold);
* ``spindle6783..6786``: test_export_guard's ``_spindle_dataset`` (the export_auto57 fixture:
  6 campaigns of 120 one-minute samples, 4 train, 2 test) with its rng seeded 6783-6786
  instead of 3 (:func:`spindle_record`, the same lines with the seed a parameter);
* ``year4_6787..6790``: ``yearround_spindle`` with ``n_campaigns=6`` (4 train), seeds 6787-6790.

20 records.  Each is fitted once by bench_autocheck65's runner (bench_remeasure62's ``auto_row``:
bench_auto_rank fits auto on the train split with its out-of-fold predictions kept, then each
candidate alone) with ``model.estimator.uncompensated=keep`` appended, so the arrays hold what the
rule reads and the kept model's test predictions (as bench_zerocheck67).  Reported alone,
deciding nothing: ``spindle3`` (the export_auto57 fixture itself, seed 3, the known loss).

Per target (bench_zerocheck67's ``target_row``): ``before`` = the uncompensated error's test RMS,
``keep`` = the kept model's test RMSE, zeroed iff val kept >= none (the src's test); a zeroed
target tests ``before``.  **Wrong zero**: zeroed where ``keep < 0.9 * before`` (the kept model
tests better than no correction by more than 10 %).  **Saved**: zeroed where ``before < keep``.

The verdict rule (written before anything was scored)
-----------------------------------------------------
The rule STAYS as is if on the 20 records it makes no wrong zero.  Otherwise the ONE refinement R
(written now, before its scoring) is scored once on the same 20 records, the 28 records of
bench_zerocheck67 (its saved arrays, /tmp/zerocheck67-a and -b) and stable67's grinder
(``grind_a`` / ``grind_b``: ``sim=stable67`` seeds 6711 / 6712 (spindle_um 0 / 1.5), 14 runs,
``data.test_fraction=0.2``, fitted here as above):

  R: zero only where, beside the pooled test, no correction beats the kept model in MORE THAN
  HALF of the 500 bootstrap resamples auto's votes already draw (``blend._nested_resamples``,
  the same draws (rng 0), folds resampled and below ``n_folds`` each drawn fold by its blocks;
  squared errors [kept model's, none's] so each draw's ratio is kept / none's per fold averaged
  over the drawn folds; no correction wins a draw where that ratio >= 1).

R is adopted (src, a test failing on the old code, docs/models.md) only if all hold: (1) on the
20 records R makes fewer wrong zeros than the rule; (2) the geometric mean over all scored
records (20 + 28 + the grinder's 2) of R's mean test RMSE / the rule's is <= 1.0; (3) no record's
ratio R / rule is above 1.02; (4) on stable67's ``grind_a`` R zeroes every target the rule zeroes
(the grinder is what the rule was adopted for).  Else the bench and a docs paragraph only.
Nothing here chooses on the test split: it is only scored.

Two changes found when it first ran, neither choosing anything: the grinder through bench_auto_rank's
``sim=`` route had no test run (``data.test_fraction`` is not applied there), so the grinder
records are written as datasets (:func:`grind_record`, the last fifth of the runs ``test``; grind_a /
grind_b's files equal bench_stable67's simulated ones byte for byte); and grind_a / grind_b were
first counted among the few-run records by a slip in ``FEW`` (fixed; the figures below are the 20).

Measured 2026-12-01 (stop 67, base e3ed3bff; 2 shared cores; run once: ``run`` 76 s CPU user +
sys for the last 17 records, 0-12 s per record; ``score`` 1.3 s).  Folds: year3 3, year4 4, year5
5, grind5 2, lab 1, spindle 2.  grind_a here = stable67's table (keep 0.461 / 0.499 / 0.445, zero
0.451 / 0.499 / 0.448).

**20 records, 52 targets: the rule zeroes 9, wrong 0**; 8 saved (zero tests below keep:
grind5_6777 E_Z 0.816 / 0.881, grind5_6778 E_X 0.481 / 0.866 and E_Y 0.469 / 0.583, grind5_6779
E_Y 0.409 / 0.420, grind5_6780 E_X 0.676 / 0.713 and E_Y 0.414 / 0.511, spindle6783 1.10 / 1.42,
spindle6784 1.37 / 2.36), 1 lost within 10 % (grind5_6779 E_X 0.522 / 0.492, 1.061).  Not zeroed
where before < keep: 3 (grind5_6777 E_X 0.472 / 0.474, E_Y 0.404 / 0.752; grind5_6778 E_Z 0.400 /
0.479; val kept / none 0.918, 0.953, 0.934).  Every year / lab target keeps its model (val kept /
none <= 0.634), the grinder's 1.5 µm spindle growth too (0.412, 0.225; test 2.01 -> 0.451, 2.36 ->
0.403).  **Verdict: the rule STAYS as is.**  R (scored, deciding nothing) zeroes the same 9 (shares
0.78-1.00) and the same on grind_a / grind_b (0.85-0.97): R / rule 1.0000 on every record; on
zerocheck67's 28 it is the rule by construction (R zeroes a subset of the rule's; the rule zeroes 0
of 94).  ``spindle3`` (the export_auto57 fixture, every default candidate): val kept 0.833 / none
0.767, zeroed, test 1.697 against keep's 0.831 (a wrong zero), R's share 0.710: R zeroes it too.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import bench_autocheck65 as autocheck  # noqa: E402
import bench_autorep65 as autorep  # noqa: E402
import bench_remeasure62 as remeasure  # noqa: E402
import bench_zerocheck67 as zerocheck  # noqa: E402
from _cli import run_commands  # noqa: E402

from thermocomp.core.models.auto import BASELINE  # noqa: E402
from thermocomp.core.models.blend import N_RESAMPLES, _nested_resamples  # noqa: E402

KEEP = zerocheck.KEEP
WRONG, BAR_WORST = 0.9, 1.02
CONF67 = f"hydra.searchpath=[file://{HERE / 'conf67'}]"
LABS = {"lab6781": 6781, "lab6782": 6782}
# stable67's grinder, (runs, spindle_um, seed); the last fifth of its runs held out (data.test_fraction=0.2)
GRINDS = {**{f"grind5_{s}": (5, 0.0 if s < 6779 else 1.5, s) for s in (6777, 6778, 6779, 6780)},
          "grind_a": (14, 0.0, 6711), "grind_b": (14, 1.5, 6712)}
SPINDLES = {f"spindle{s}": s for s in (6783, 6784, 6785, 6786)}
FEW = {
    **{f"year3_{s}": ["sim=yearround_spindle", "sim.generator.n_campaigns=4", f"seed={s}"]
       for s in (6771, 6772, 6773)},
    **{f"year5_{s}": ["sim=yearround_spindle", "sim.generator.n_campaigns=7", f"seed={s}"]
       for s in (6774, 6775, 6776)},
    **{name: [f"data.path={{root}}/{name}"] for name in (*list(GRINDS)[:4], *LABS, *SPINDLES)},
    **{f"year4_{s}": ["sim=yearround_spindle", "sim.generator.n_campaigns=6", f"seed={s}"]
       for s in (6787, 6788, 6789, 6790)},
}
GRINDER = {name: [f"data.path={{root}}/{name}"] for name in ("grind_a", "grind_b")}
ALONE = {"spindle3": ["data.path={root}/spindle3"]}      # the known loss: reported, deciding nothing
RECORDS = {**FEW, **GRINDER, **ALONE}
os.environ["THERMOCOMP_TARGETS"] = ",".join(
    p for p in (os.environ.get("THERMOCOMP_TARGETS", "trunnion63.,portal64."), "stable67.") if p)


def spindle_record(root: Path, seed: int, rows: int = 120) -> Path:
    """test_export_guard's ``_spindle_dataset`` (the export_auto57 fixture) with its rng seeded
    ``seed``: six campaigns (four train, two test) of a spindle stepping between speeds, the
    hall's expansion plus a 30-min lag of friction heat growing as the speed's square."""
    sys.path[:0] = [str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
    from test_export_guard import _spindle_dataset

    return _spindle_dataset(root, rows, seed)


def grind_record(path: Path, runs: int, spindle_um: float, seed: int) -> Path:
    """stable67's grinder (``benchmarks/stable67.py``), ``runs`` runs, the last fifth of them held
    out (``data.test_fraction=0.2`` as bench_stable67's ``init``: 3 of 14, 1 of 5), as a dataset."""
    from stable67 import Stable67

    from thermocomp.core.io.contract import Dataset, write_dataset

    ds = Stable67(runs=runs, spindle_um=spindle_um, seed=seed).generate()[0]
    ids = list(ds.campaigns)
    n_test = round(0.2 * len(ids))
    manifest = ds.manifest.loc[ids].copy()
    manifest["split"] = ["train"] * (len(ids) - n_test) + ["test"] * n_test
    manifest["file"] = ""
    return write_dataset(Dataset(manifest, ds.campaigns, path.name), path)


def write(root: Path) -> None:
    root.mkdir(parents=True, exist_ok=True)
    for name, args in GRINDS.items():
        if not (root / name).exists():
            grind_record(root / name, *args)
    for name, seed in LABS.items():
        if not (root / name).exists():
            autocheck.lab_record(root / name, seed)
    for name, seed in {**SPINDLES, "spindle3": 3}.items():
        if not (root / name).exists():
            spindle_record(root / name, seed)


def run(root: Path, names: list[str]) -> None:
    autorep.keep_groups()
    autocheck.measured_test_only()
    remeasure.AUTO.update({n: [*o, KEEP] for n, o in RECORDS.items()})
    remeasure.measure(root / "auto.jsonl", (("auto", remeasure.auto_row(root, n)) for n in names))


def none_share(a, y: np.ndarray, fold: np.ndarray, preds: np.ndarray, w: np.ndarray) -> float:
    """R's figure: the share of auto's 500 resamples in which no correction beats the kept model
    (the mean over the drawn folds of kept / none's squared error >= 1)."""
    unit = np.unique(fold, return_inverse=True)[1]
    squared = np.column_stack([(y - preds @ w) ** 2, y ** 2])
    blocks = unit.max() + 1 < autorep.N_FOLDS
    ratio = _nested_resamples(squared, y, unit, a["oof_" + BASELINE], N_RESAMPLES, blocks)[:, 0]
    return float(np.mean(ratio >= 1.0))


def target_row(report: dict, a) -> dict:
    """bench_zerocheck67's row (the rule, asserted against the fit) and R's."""
    row = zerocheck.target_row(report, a)
    members, y, fold, _, _, preds, _, kept = autorep.stored(report, a)
    w = np.array([kept.get(n, 0.0) for n in members])
    share = none_share(a, y, fold, preds, w)
    zero_r = row["zeroed"] and share > 0.5
    return {**row, "share": share, "zeroed_R": zero_r, "R": row["before"] if zero_r else row["keep"],
            "n_folds": int(np.unique(fold).size), "rows": int(y.size),
            "wrong": row["zeroed"] and row["keep"] < WRONG * row["before"],
            "wrong_R": zero_r and row["keep"] < WRONG * row["before"],
            "saved": row["zeroed"] and row["before"] < row["keep"],
            "saved_R": zero_r and row["before"] < row["keep"]}


def _means(scored) -> dict:
    return {n: {k: float(np.mean([r[k] for r in s["targets"].values()]))
                for k in ("mlr", "keep", "zero", "R", "before")} for n, s in scored}


def verdict(root: Path, zero_a: Path | None, zero_b: Path | None) -> list[str]:
    few = autorep.score(root, list(FEW), target_row)
    grinder = autorep.score(root, list(GRINDER), target_row)
    alone = autorep.score(root, list(ALONE), target_row)
    cpu = {r["record"]: r["cpu_s"] for r in remeasure._read(root / "auto.jsonl")}
    lines = ["CPU s (user + sys) per record (auto fit + each candidate alone): "
             + ", ".join(f"{n} {cpu.get(n, float('nan')):.0f}" for n in RECORDS),
             "", "per target: folds (rows), test RMSE before / keep / MLR, val kept / none, R's share "
             "(none wins), Z: zeroed by the rule, r: by R; W: wrong zero, S: saved"]
    for group in (few, grinder, alone):
        for name, s in group:
            for t, r in s["targets"].items():
                flag = ("Z" if r["zeroed"] else "-") + ("r" if r["zeroed_R"] else "-") + (
                    " W" if r["wrong"] else "") + (" S" if r["saved"] else "")
                lines.append(f"  {name:12s} {t[:8]:8s} {r['n_folds']} ({r['rows']:5d}) before "
                             f"{r['before']:.3g} keep {r['keep']:.3g} MLR {r['mlr']:.3g}; val "
                             f"{r['val_kept']:.3g} / {r['val_none']:.3g} = "
                             f"{r['val_kept'] / r['val_none']:.3f}; share {r['share']:.3f}  {flag}")
    t_few = [r for _, s in few for r in s["targets"].values()]
    count = {k: sum(r[k] for r in t_few) for k in ("zeroed", "zeroed_R", "wrong", "wrong_R",
                                                    "saved", "saved_R")}
    lost = [r["before"] / r["keep"] for r in t_few if r["zeroed"] and r["keep"] < r["before"]]
    lines += ["", f"{len(few)} few-run records, {len(t_few)} targets: the rule zeroes {count['zeroed']} "
              f"(wrong {count['wrong']}, saved {count['saved']}, a loss within 10 %: {len(lost)}"
              + "".join(f" {q:.3f}" for q in lost) + f"; not zeroed where before < keep: "
              f"{sum(not r['zeroed'] and r['before'] < r['keep'] for r in t_few)}); "
              f"R zeroes {count['zeroed_R']} "
              f"(wrong {count['wrong_R']}, saved {count['saved_R']})"]
    m_few, m_grind = _means(few), _means(grinder)
    lines += ["", "per record, mean test RMSE: before, MLR, keep, the rule (zero), R, R / rule"]
    for m in (m_few, m_grind, _means(alone)):
        lines += [f"  {n:12s} {v['before']:7.4g} {v['mlr']:7.4g} {v['keep']:7.4g} {v['zero']:7.4g} "
                  f"{v['R']:7.4g}  {v['R'] / v['zero']:.4f}" for n, v in m.items()]
    if count["wrong"] == 0:
        lines.append("verdict: the rule STAYS as is (no wrong zero on the 20 few-run records); "
                     "R not needed (scored above, deciding nothing)")
        return lines
    ratios = {n: v["R"] / v["zero"] for n, v in {**m_few, **m_grind}.items()}
    n28 = 0
    for zroot, names in ((zero_a, autorep.RECORDS), (zero_b, list(autocheck.RECORDS))):
        if zroot is None:
            continue
        for n, v in _means(autorep.score(zroot, names, target_row)).items():
            ratios[f"zc:{n}"], n28 = v["R"] / v["zero"], n28 + 1
    geo = float(np.exp(np.mean(np.log(list(ratios.values())))))
    worst = max(ratios, key=ratios.get)
    ga = dict(grinder)["grind_a"]["targets"]
    kept_zero = all(r["zeroed_R"] for r in ga.values() if r["zeroed"])
    ok = (count["wrong_R"] < count["wrong"], geo <= 1.0, ratios[worst] <= BAR_WORST, kept_zero)
    lines.append(f"R over {len(ratios)} records ({len(m_few)} + zerocheck67's {n28} + grinder "
                 f"{len(m_grind)}): (1) wrong zeros {count['wrong']} -> {count['wrong_R']} "
                 f"{'met' if ok[0] else 'FAILED'}; (2) geometric mean R / rule {geo:.4f} "
                 f"{'met' if ok[1] else 'FAILED'}; (3) worst {ratios[worst]:.4f} ({worst}) "
                 f"{'met' if ok[2] else 'FAILED'}; (4) grind_a's zeros kept by R "
                 f"{'met' if ok[3] else 'FAILED'}")
    lines.append("verdict: " + ("R ADOPTED" if all(ok) else "R refused: the rule stays as is"))
    return lines


def main(argv: list[str]) -> int:
    def verdict_of(root: str, *zerochecks: str) -> None:
        zc = [Path(p).resolve() for p in zerochecks] + [None, None]
        print(remeasure._wrapped(verdict(Path(root).resolve(), zc[0], zc[1]), 106))

    return run_commands(__doc__, {
        "write": lambda root, *_: write(Path(root).resolve()),
        "run": lambda root, *names: run(Path(root).resolve(), list(names) or list(RECORDS)),
        "score": verdict_of,
    }, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
