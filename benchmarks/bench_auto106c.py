"""``model=auto``'s hedge toward MLR on a record whose folds are ONE held-out campaign, by at most 8
of that fold's blocks and the fold's POOLED squared error (issue 34; stop 106, auto106c).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the vote and hedge code is that tree's)::

    python benchmarks/bench_auto106c.py seen STORE22 STOREONE [STORE ...]   # stored rows, replayed
    python benchmarks/bench_auto106c.py fl STORE                             # fl_thermal 90/10, replayed
    python benchmarks/bench_auto106c.py authors OUT     # fl_thermal 60/20/20 run (bench_auto105b's)
    python benchmarks/bench_auto106c.py fresh OUT       # seeds 10095-10099, fitted and scored ONCE
    python benchmarks/bench_auto106c.py cost ROWS       # the hedge's CPU on a white one-fold residual
    python benchmarks/bench_auto106c.py trace STORE RECORD   # per target: blocks, lam, per-block errors

The rule is REFUSED and its src is ``benchmarks/auto106c_rule.patch``: ``git apply`` it first (every
command but ``authors`` calls its ``one_fold_weight`` / ``fold_blocks``).

STORE22 / STOREONE / STORE: as bench_auto106b's (``/tmp/auto105b/main``, ``/tmp/auto105b/one``,
``/tmp/auto105b/fresh``) and auto106b's fresh main-key fits of seeds 10069-10073 (seen now; a store
with ``train_campaigns.json``, 3 each).  main = the stored W with auto105b's hedge replayed.

The rule (``hedge='campaigns_or_fold'``, the new default; ``AutoRegressor._hedged``,
:func:`thermocomp.core.models.hedge.one_fold_weight`): auto105b's nested weight where the folds are
>= 3 whole campaigns, unchanged.  Where the folds are ONE held-out campaign (blocked forward on 2-3
train campaigns), auto106b's idea with its two defects removed:
- the units: the fold cut into contiguous blocks at least one decorrelation length of MLR's residual
  long (about one independent look each, as auto106b) and AT MOST 8 (``MAX_FOLD_BLOCKS``): block
  length ``max(decorrelation length, ceil(rows / 8))``.  Why 8: the labs' folds had 3-8 such blocks
  (lab5401 4-6, lab10032 6-7), so they keep theirs, and the nested choice costs at most 8 votes,
  whatever the fold's length (auto106b: one vote per block, 63 one-row blocks on year4_10073, 108 s
  CPU per target on a 2,000-row white fold).
- the measure: ``lam`` least in the fold's pooled squared error of ``lam * A + (1 - lam) * MLR``
  (A: the choice made without each block predicts it), ``<e, d> / <d, d>`` clipped to [0, 1], not a
  mean of per-block error ratios (ruled by blocks where MLR is near right: auto106b's lam ~0 against
  a candidate at 0.81 of MLR's MSE).  Fewer than 2 blocks: lam 1.
How it differs from refused rules: auto106b (REFUSED: blocks unbounded, per-block ratio mean) as
said; auto93d (REFUSED) a per-member threshold on block resamples, not a continuous mix; auto105
(REFUSED) hedged any >= 2 folds incl. one record's time blocks: those stay untouched here.

BAR (written and committed before ``seen``, ``fl``, ``authors``, ``cost`` ran on this rule and before
seeds 10095-10099 were simulated; KEPT only if all hold):
(1) SEEN 22: losers (auto / MLR > 1) at most main's 6, geo auto / MLR at most 0.8192.
(2) SEEN, every record of the 22, the 10 one-campaign, auto105b's 5 fresh and auto106b's 5 fresh
    (10069-10073, main-key fits): rule / main <= 1.01.
(3) The 10 one-campaign records unchanged: lam 1 on every target.
(4) fl_thermal: 90/10 mean RMSE >= 25 % under MLR's (main 38.9 %); the authors' 60/20/20 split
    re-run with this tree's src: test MAE below the GRU on >= 4 of 5 and the mean (main: 4 of 5).
(5) FRESH 10095-10099, one-fold records named before drawing (:data:`FRESH`, auto106b's kinds):
    lab10095, lab10096, lab10097 (bench_auto_losses56's ``lab_record``: 3 train runs, one fold) and
    year4_10098, year4_10099 (``yearround_spindle``, 4 campaigns, the last held out, 3 train
    forward).  Each fitted twice, main's key (``hedge=campaigns``) and the rule's (the default),
    scored once on its own test: no new loser (main / MLR <= 1 < rule / MLR), geo rule / MLR <=
    geo main / MLR over the five, AND no fresh record rule / main > 1.05.
(6) Cost (``cost 500``, ``cost 2000``: fold_blocks + one_fold_weight, CPU per target): at most 8
    blocks, and at most 10 x one vote (``vote_weights`` on the same rows, timed there too).

Measured (2026-12-07, the rule's src (now ``benchmarks/auto106c_rule.patch``); ``OMP_NUM_THREADS=1``,
2 shared cores, load ~9-12; CPU user + sys by ``/usr/bin/time``: ``seen`` 4.3 s, ``fl`` 1.5 s).
REFUSED: (2) fails.
(1) SEEN 22 (``seen /tmp/auto105b/main /tmp/auto105b/one /tmp/auto105b/fresh /tmp/auto106c/fresh106b``):
    lab5401 keeps lam 1; losers 6, geo 0.8192, as main: met.
(2) worst seen rule / main 1.0183 over 42 records (lab10032 1.227 -> 1.250 x MLR): NOT met.  The
    others moved: lab10069 1.204 -> 1.169, lab10070 1.500 -> 1.510, lab10071 1.386 -> 1.335,
    year4_10073 0.553 -> 0.546 (year4_10072 unchanged, 0.616).
(3) the 10 one-campaign records: no target hedged, geo 0.7654 both: met.
(4) fl_thermal 90/10 (one train record, 5 time-block folds: not hedged) 2.481, 38.9 % under MLR's
    4.060: met.  The authors' 60/20/20 (a val split, auto keeps one family: the rule cannot act) not
    re-run after (2) failed.
(5) FRESH 10095-10099 NOT drawn: the verdict was fixed by (2), and the seeds stay fresh for a next rule.
(6) ``cost 500``: 7 blocks, lam 0.576, hedge 0.08 s CPU = 5.2 x one vote; ``cost 2000``: 8 blocks,
    lam 0.556, 0.39 s = 6.7 x one vote (auto106b: 108 s, lam ~0): met.  lam ~0.55 is the right mix
    there (independent errors of variance 1 and 0.81: 1 / 1.81).
Why (2) fails (``trace /tmp/auto105b/fresh lab10032``, after the verdict): the pooled measure is
ruled by the blocks where MLR's error is LARGEST, the mirror of auto106b's defect.  E_Z (W 1.793 x
MLR on the test): 7 blocks of 171 rows; W (arx 0.84) loses 4 of 7 blocks (A / MLR 1.30-2.00 where
MLR's MSE is 2.5-4.4) but wins the two heavy ones (MSE 30 and 51: A / MLR 0.57, 0.42), so the
pooled lam is 1 and the loss the test shows is left.  E_Y (W 0.891 on the test): one block holds
most of the fold's squared error (MLR MSE 214 of the six blocks' 347 summed) and there A ~ MLR; A
loses blocks 0, 1, 2, 5, so lam 0.537 and the test goes 0.891 -> 0.939.  Neither measure (mean of
per-block ratios: ruled by small-error blocks; pooled: by large-error ones) picks the test's side
here; a next rule could give each block one equal say (a rank or sign measure over <= 8 blocks),
on its own seeds.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto87b as b87  # noqa: E402
import bench_auto105 as a105  # noqa: E402
import bench_auto105b as a105b  # noqa: E402
import bench_auto106 as a106  # noqa: E402
import bench_auto106b as a106b  # noqa: E402
from _cli import run_commands  # noqa: E402

MAIN_GEO, MAIN_LOSERS = 0.8192, 6
MAIN_KEY = "model.estimator.hedge=campaigns"      # main's rule (auto105b), for the fresh fits
TRAIN_CAMPAIGNS = 3           # every fresh record's train part, by construction
YEAR4 = ["sim=yearround_spindle", "sim.generator.n_campaigns=4", "sim.generator.test_every=4"]
FRESH = {"lab10095": ["data.path={out}/lab10095"], "lab10096": ["data.path={out}/lab10096"],
         "lab10097": ["data.path={out}/lab10097"],
         "year4_10098": [*YEAR4, "seed=10098"], "year4_10099": [*YEAR4, "seed=10099"]}


def rule_weight(a: dict, kept: dict, campaigns: int) -> float:
    """lam of the rule on stored rows: auto105b's where it acts (>= 3 campaign folds); on ONE
    campaign fold the src's pooled hedge over at most 8 blocks; else 1."""
    from thermocomp.core.models.hedge import one_fold_weight

    if campaigns < 2 or np.unique(a["oof_fold"]).size != 1:
        return a105b.gated_weight(a, kept, campaigns)
    if "oof_mlr" not in a or sum(kept.values()) <= 0 or b87._nonzero(kept) == {"mlr": 1.0}:
        return 1.0
    names = [n for n in b87.ORDER if f"oof_{n}" in a]
    preds = np.column_stack([a[f"oof_{n}"] for n in names])
    return one_fold_weight(preds, a["oof_y"], names.index("mlr"), a105.N_FOLDS)


def seen(store22: str, store_one: str, *more: str) -> None:
    a106b.rule_weight = rule_weight        # bench_auto106b's tables, this rule's lam
    a106b.seen(store22, store_one, *more)


def fl(store: str) -> None:
    a106b.rule_weight = rule_weight
    a106b.fl(store)


def fresh(out: str) -> None:
    """Seeds 10095-10099 (:data:`FRESH`), each fitted with main's key and with the rule's, scored ONCE."""
    from bench_auto_losses56 import lab_record

    out_p = Path(out).resolve()
    rows = []
    for name, ov in FRESH.items():
        if name.startswith("lab") and not (out_p / name).exists():
            lab_record(out_p / name, seed=int(name[3:]))
        got = {}
        for key, extra in (("main", [MAIN_KEY]), ("rule", [])):
            sub = out_p / key
            sub.mkdir(parents=True, exist_ok=True)
            if not (sub / f"{name}.json").exists():
                a105._rank(sub, name, [o.format(out=out_p) for o in ov] + extra)
            got[key] = a106b._score(sub, name)
        main, rule = got["main"], got["rule"]
        for t, (folds, a, w) in main["info"].items():
            lam = rule_weight(a, w, TRAIN_CAMPAIGNS)
            built = {n: round(v, 3) for n, v in rule["info"][t][2].items()}
            print(f"  {name} {t}: folds {folds}, main W {dict((n, round(v, 3)) for n, v in w.items())}, "
                  f"replayed lam {lam:.3f}, built rule W {built}")
        rows.append({"record": name, "main": main["auto"] / main["mlr"], "rule": rule["auto"] / rule["mlr"]})
        print(f"{name:12s} main / MLR {rows[-1]['main']:.3f}  rule / MLR {rows[-1]['rule']:.3f}  "
              f"(MLR {main['mlr']:.4f} / {rule['mlr']:.4f})", flush=True)
    new = [r["record"] for r in rows if r["main"] <= 1 < r["rule"]]
    worse = [r["record"] for r in rows if r["rule"] > 1.05 * r["main"]]
    g_main, g_rule = a106._geo(r["main"] for r in rows), a106._geo(r["rule"] for r in rows)
    print(f"fresh geo main / MLR {g_main:.4f} rule / MLR {g_rule:.4f}; new losers {new or 'none'}; "
          f"> 5 % worse than main {worse or 'none'}: BAR (5) "
          f"{'met' if not new and not worse and g_rule <= g_main else 'NOT met'}")


def cost(rows: str) -> None:
    """The one-fold hedge on ROWS rows of a white residual (bench_auto106b's ``cost`` data): MLR, a
    candidate with 0.9 of its noise s.d., one with 1.1; blocks, lam, CPU of the hedge and of one vote."""
    from thermocomp.core.models.blend import vote_weights
    from thermocomp.core.models.hedge import fold_blocks, one_fold_weight

    n, rng = int(rows), np.random.default_rng(1)
    y = rng.normal(0.0, 5.0, n)
    preds = np.column_stack([y + rng.normal(0.0, s, n) for s in (1.0, 0.9, 1.1)])
    t0 = time.process_time()
    vote_weights(preds, y, np.zeros(n, int), preds[:, 0], base_column=0, min_folds=a105.N_FOLDS)
    t1 = time.process_time()
    blocks = np.unique(fold_blocks(y, preds[:, 0])).size
    lam = one_fold_weight(preds, y, 0, a105.N_FOLDS)
    t2 = time.process_time()
    print(f"{n} rows: {blocks} blocks, lam {lam:.3f}, hedge {t2 - t1:.2f} s CPU, one vote {t1 - t0:.2f} s "
          f"({(t2 - t1) / max(t1 - t0, 1e-9):.1f} x): BAR (6) "
          f"{'met' if blocks <= 8 and t2 - t1 <= 10 * (t1 - t0) else 'NOT met'}")


def trace(store: str, record: str) -> None:
    """Per target of RECORD in STORE: the fold's blocks, the rule's lam, and per block MLR's MSE with
    A's (the choice made without the block) and the kept W's over it; the test at lam 1 and the rule's."""
    from thermocomp.core.models.hedge import fold_blocks, nested_prediction, one_fold_weight

    rep = json.loads((Path(store) / f"{record}.json").read_text())
    for t, r in rep["targets"].items():
        with np.load(Path(store) / f"{record}.{t}.npz", allow_pickle=True) as z:
            a = {k: z[k] for k in z.files}
        w = {n: float(v) for n, v in r["auto"]["weights"].items()}
        names = [n for n in b87.ORDER if f"oof_{n}" in a]
        preds, y = np.column_stack([a[f"oof_{n}"] for n in names]), a["oof_y"]
        base, one = names.index("mlr"), np.zeros(len(a["oof_y"]), int)
        units = fold_blocks(y, preds[:, base])
        lam = one_fold_weight(preds, y, base, a105.N_FOLDS)
        e = y - preds[:, base]
        nested = nested_prediction(preds, y, one, base, a105.N_FOLDS, units)
        kept = sum(v * a[f"oof_{n}"] for n, v in w.items())
        print(f"{t}: {len(y)} rows, {np.unique(units).size} blocks, lam {lam:.3f}, kept W "
              f"{ {n: round(v, 2) for n, v in w.items()} }")
        for j in np.unique(units):
            on, ee = units == j, float(np.mean(e[units == j] ** 2))
            a_, w_ = np.mean((y[on] - nested[on]) ** 2) / ee, np.mean((y[on] - kept[on]) ** 2) / ee
            print(f"   block {j}: {on.sum()} rows, MLR MSE {ee:.3g}, A / MLR {a_:.3f}, W / MLR {w_:.3f}")
        test = sum(v * a[f"test_{n}"] for n, v in w.items())
        for lam_ in (1.0, lam):
            mix = lam_ * test + (1 - lam_) * a["test_mlr"]
            print(f"   test RMSE / MLR at lam {lam_:.3f}: "
                  f"{b87._rmse(a['test_y'] - mix) / b87._rmse(a['test_y'] - a['test_mlr']):.3f}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": seen, "fl": lambda s: fl(s),
                                  "authors": lambda out: a105b.authors(out),
                                  "fresh": lambda out: fresh(out), "cost": lambda n: cost(n),
                                  "trace": trace},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
