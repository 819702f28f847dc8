"""``model=auto``'s votes scored where new campaigns live: a fold holding out whole campaigns
scores its candidates on the held-out rows past the fit campaigns' range (issue 34; stop 85,
auto85b).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code and conf measured are that
tree's; a NEW tree needs the rule, ``git apply benchmarks/auto85b_rule.patch``: REFUSED, below)::

    python benchmarks/bench_auto85b.py trace ROOT RECORD ...          # rows outside, rank agreement
    python benchmarks/bench_auto85b.py rows ROOT WORK [RECORD ...]    # the 22 records' rows
    python benchmarks/bench_auto80.py fl WORK                         # fl_thermal -> WORK/fl.jsonl
    python benchmarks/bench_auto85b.py fresh ROOT WORK                # this stop's fresh records
    python benchmarks/bench_auto85b.py bar OLD NEW OLDFRESH NEWFRESH  # the verdict

``rows`` and ``fresh`` are bench_auto84's (its ``rows ... as_is``; ``fresh`` on its machines with
this stop's seeds, :data:`FRESH`).  ``trace``: per record (bench_automore69's overrides), auto
fitted on the train campaigns; per target, its folds, per fold the held-out rows with an input
past the fit rows' range (of all it scores), and the Spearman rank agreement over the validated
candidates between their validation RMSE (all out-of-fold rows; those outside only) and their
pooled RMSE on the record's new campaigns (bench_automore69's stored rows, /tmp/auto80/new:
read, not chosen by).

Why (bench_auto84 / 84b / 84c, REFUSED): where auto loses to MLR on new campaigns, these take the
inputs past the train range; the banks' CV and extrapolation folds built from the training rows
did not read which family extrapolates (84c: "rows at an end of the range still belong to a train
campaign whose other rows fit them"; left: whole campaigns held out, scored on their rows outside
the others' range).

Traced (2026-12-04, this tree = main 39d6305f's model code; ``trace`` on the 8 losing records,
swiss303 and tsc_a2; 1 min CPU each group)
------------------------------------------------------------------------------------------------
* One train campaign, so auto's folds forward-chain within one record and hold no campaign out:
  col5791, col1403, col1514, col6512 and swiss303 (and the fresh records of bench_auto84's
  ``fresh_set``: one train campaign each; ``fl_thermal``: one record at 90/10, a val split at
  60/20/20).  The rule cannot reach them: 4 of the 8 losses (col5791 1.258, col1403 1.311, col1514
  1.019, col6512 1.004 x MLR) are out of its scope.
* Campaign folds (blocked forward): iso_a (5 train campaigns, 2 folds: 2421 of 2527 and 2080 of
  3160 held-out rows outside), mtc_b (7, 3 folds: 47 / 390 / 0 of 1440), hmc (6, 3 folds: 40 of
  2003, 265 of 1193, 332 of 2310), lab5401 (3, 1 fold: 934 of 1200), tsc_a2 (5, 2 folds: 125 of
  2400, 0 of 2399).  Spearman (validation vs new campaigns), all rows -> outside rows: iso_a
  +0.29 -> +0.06, -0.89, +0.09, -0.43, +0.77 (unchanged: nearly every row is outside); mtc_b
  -0.10 -> 0.00, +0.40, -0.20 -> +0.60; hmc +0.61, +0.71 -> +0.75; lab5401 +0.40, +0.20, +0.80
  -> +0.60; tsc_a2 -0.12 -> +0.41, +0.81 -> +0.99, +0.84 -> +0.88, +0.70 -> +0.64.  Mean over
  these 17 targets +0.287 -> +0.358 (more agreement on 6, less on 3, equal on 8); the family
  best on the validation rows is the new campaigns' best on 2 of 17 targets with all rows
  (lab5401 E_Z lstm, tsc_a2 E_dZ1 hammerstein), on 3 with the outside rows (tsc_a2 E_dZ1 and
  E_dZ2 hammerstein, hmc E_CH16 lag bank).
What it says: a weak, mostly positive shift on the records it reaches; the mean agreement stays
low, and half the losses are out of reach.  Scored whole below (the bar decides, not the trace).

The rule (ONE rule, written and committed before anything below was scored)
---------------------------------------------------------------------------
``AutoRegressor(validation_rows="outside")``, the default of conf/model/auto.yaml: where auto's
folds hold out whole campaigns (blocked forward, leave-campaigns-out), the votes (bootstrap
shares, MLR's doubt) and the one-SE fallback score each candidate only on the held-out rows with
at least one declared input below the minimum or above the maximum of that fold's fit rows
(:func:`thermocomp.core.model_selection.extrapolation.outside_box`: per input, the box the fit
campaigns span -- the way a new campaign leaves the range, auto84's trace; a leverage ellipsoid
flags rows that only break the sensors' correlation inside the box, and ``in_range`` already
reads it); a fold with fewer than 20 such rows (``MIN_IN_RANGE_ROWS``, the ``in_range`` rule's)
is scored on all its rows; one record's folds are scored whole.  The zero rule is unchanged
(pooled over all rows).  metrics.json ``targets.<t>.auto.voting_rows`` says which rows scored.

The bar (before scoring; fails -> src and conf reverted, the rule kept as
``benchmarks/auto85b_rule.patch``, REFUSED here)
---------------------------------------------------------------------------------
Record figure = mean over targets of the pooled test RMSE on the new campaigns (bench_automore69's);
OLD = the shipped rows (/tmp/auto80/new), NEW = this tree's (``rows ROOT WORK``).

1. the 22 records: the count where auto is worse than MLR on the new campaigns falls below 8;
2. the count where auto is better than MLR there does not fall (13);
3. the geometric mean of auto / MLR over the 22 on the new campaigns not higher (0.826);
4. the count within 10 % of the best single family there does not fall (15);
5. no record's auto figure worse than shipped's by more than 2 %;
6. ``fl_thermal`` 90/10 auto mean test RMSE not worse than shipped (2.481 µm) by more than 1 %,
   and 60/20/20 auto's test MAE below the authors' GRU on >= 4 of 5 channels and on the mean;
7. fresh records of this stop's seeds (never looked at; bench_auto84's ``fresh_set(8866)``: the
   column 8866-8867, the Swiss lathe 8868-8869, the lab mill 8870, the mill week 8871, their new
   campaigns 8872-8874), shipped code (OLDFRESH: main's src and conf) against the rule (NEWFRESH):
   the count worse than MLR on their new campaigns not higher, and the geometric mean of auto /
   MLR there not higher.  (Said before: one train campaign each, so the rule cannot move them;
   item 7 checks that, item 6 likewise.)

Scored (2026-12-04; OLD = /tmp/auto80/new and main 39d6305f's src and conf on the fresh records,
NEW = this tree at 9fc11278 (the rule the conf default); 2 shared cores, load about 7, every record
once, ``OMP_NUM_THREADS=1``; CPU user + sys of the rows 147.8 s for the 22 (auto84c: 268 s),
fl_thermal 72.6 s, the fresh records 56.6 / 58.8 s OLD / NEW; ``bar /tmp/auto80/new
/tmp/auto85b/new /tmp/auto85b/fresh_old /tmp/auto85b/fresh_new``): **REFUSED** (item 5 fails;
src, conf and the test reverted, the rule and its test in ``benchmarks/auto85b_rule.patch``)
-------------------------------------------------------------------------------------------------
auto / MLR on the new campaigns, shipped -> rule (auto rule / shipped), the records the rule
moves (the 10 others equal, ratio 1.0000: the five columns, both Swiss lathes, mill1514,
twin_lathe, iso_b; grind_a 0.9999, grind_b 1.0014): lab5401 1.070 -> 1.148 (1.073), year6511 0.351 -> 0.355
(1.013), year6512 0.376 -> 0.380 (1.013), year6_5411 0.518 -> 0.517, jig_grinder 0.940 -> 0.944
(1.003), hmc 1.005 -> 0.914 (0.909), tsc_a2 0.376 -> 0.383 (1.018), iso_a 1.083 -> 1.028
(0.949), mtc_a 0.704 -> 0.683 (0.970), mtc_b 1.075 -> 1.017 (0.946).

1. holds: worse than MLR on the new campaigns 8 -> 7 (hmc turns into a win; left: col5791,
   col1403, col1514, col6512 -- one train campaign, out of the rule's reach -- lab5401, iso_a,
   mtc_b).
2. holds: better than MLR there 13 -> 14.
3. holds: geometric mean auto / MLR over the 22 0.8264 -> 0.8221.
4. holds: within 10 % of the best single family 15 -> 16.
5. FAILS: lab5401 7.3 % worse than shipped (1.070 -> 1.148 x MLR); tsc_a2 +1.8 %, year6511 /
   year6512 +1.3 % within the 2 %.
6. holds (unchanged, as said): ``fl_thermal`` 90/10 auto 2.4810 µm; 60/20/20 MAE 1.170 / 1.411 /
   4.078 / 1.399 / 2.529, mean 2.117, below the authors' on 4 of 5.
7. holds (unchanged, as said): the 6 fresh records worse than MLR on their new campaigns 1 -> 1
   (mill8871 1.025), geometric mean 0.7112 -> 0.7112.

Why (per target, from the stored rows after the verdict; new-campaign RMSE, shipped -> rule, MLR):
lab5401 has 3 train campaigns, so one fold (the third campaign held out, 934 of its 1200 rows
outside): on E_Z the votes moved arx 0.15 -> 0.33 (mlr 0.57 -> 0.48, lstm 0.28 -> 0.20) and E_Z
went 2.672 -> 3.244 µm (MLR 2.252), E_Y 2.968 -> 3.020: dropping the 266 inside rows of the one
fold handed arx votes the new campaigns do not back.  The gains are where several folds each hold
out a campaign: hmc E_CH15 0.906 -> 0.779 (MLR 0.837; hammerstein 0.60), iso_a E_Y1 0.378 ->
0.243 (MLR 0.371; lagbank 0.61), mtc_b E_dX 8.845 -> 8.007 (MLR 7.901), E_dY 0.373 -> 0.339.
So the trace's reading holds in part: on campaign folds the rows outside rank the families a
little more as the new campaigns do (hmc, iso_a, mtc_a, mtc_b 3-9 % better than shipped), but
with one fold the outside rows alone are too few campaigns' worth of evidence, and half the
losses (one train campaign) are beyond any campaign fold.

What remains: (a) the rule with a floor on the folds -- ``outside`` only where two or more folds
hold campaigns out (lab5401's one fold scored whole) -- is the narrowest change that would have
kept lab5401 as shipped; written after seeing lab5401, it needs its own fresh records WITH several
train campaigns (``fresh_set``'s machines have one each: they could not test this rule at all),
e.g. bench_automore69's ``year`` / ``hmc`` / lab machines drawn again on new seeds; (b) the one-
record losses (the column: col5791, col1403, col1514, col6512) need a fold inside one record that
leaves its range as the next campaign does, which auto84c's extrapolation folds did not find.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto84 as auto84  # noqa: E402
from _cli import run_commands  # noqa: E402

automore = auto84.automore
FRESH = auto84.fresh_set(8866)
FRESH_NEW = [8872, 8873, 8874]       # the new campaigns of each fresh record's machine
SHIPPED = Path("/tmp/auto80/new/automore.jsonl")
GEO_22, NEAR_22 = 0.826, 15          # shipped: geometric mean auto / MLR, within 10 % of the best


def fresh(root: Path, work: Path) -> None:
    """The fresh records of :data:`FRESH` through bench_auto84's ``fresh`` -> WORK."""
    auto84.FRESH, auto84.FRESH_NEW = FRESH, FRESH_NEW
    auto84.fresh(root, work)


def bar(old: Path, new: Path, oldf: Path, newf: Path) -> None:
    """bench_auto84's bar (its items 1-5: this bar's 1, 2, 5, 6, 7), then items 3 and 4."""
    import contextlib
    import io

    auto84.FRESH = FRESH
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        auto84.bar(old, new, oldf, newf)
    # auto84's items 3, 4, 5 are this bar's 5, 6, 7; its geometric mean / near line is items 3-4
    renumber = {"3 ": "5 ", "4 ": "6 ", "5 ": "7 "}
    lines = [renumber.get(w[:2], w[:2]) + w[2:] for w in out.getvalue().splitlines()
             if not w.startswith("(not in the bar)")]
    a, b = auto84._sums(old), auto84._sums(new)
    geo = [float(np.exp(np.mean([np.log(x["to_mlr"][1]) for x in s.values()]))) for s in (a, b)]
    near = [sum(x["to_best"][1] <= 1.1 for x in s.values()) for s in (a, b)]
    ok = [lines[-1].endswith("KEPT"), geo[1] <= GEO_22, near[1] >= NEAR_22]
    print("\n".join(lines[:-1]))
    print(f"3 geometric mean auto/MLR on the 22 {geo[0]:.4f} -> {geo[1]:.4f}: "
          f"{'holds' if ok[1] else 'FAILS'}\n4 within 10 % of the best single family {near[0]} -> "
          f"{near[1]}: {'holds' if ok[2] else 'FAILS'}\nVERDICT: {'KEPT' if all(ok) else 'REFUSED'}")


def trace(root: Path, names: list[str]) -> None:
    """Per target of ``names``: the held-out rows outside each fold's fit range, and the rank
    agreement of validation (all rows; outside only) with the new campaigns (stored rows)."""
    import bench_auto_rank as rank
    from scipy.stats import spearmanr

    from thermocomp.core.models import auto as auto_mod
    from thermocomp.shell.builders import build_compensator

    fit = auto_mod.AutoRegressor.fit

    def keeping_x(self, X, y, context=None):
        self.x_ = np.asarray(X, float)
        return fit(self, X, y, context)

    auto_mod.AutoRegressor.fit = keeping_x
    stored = {r["record"]: r for r in map(json.loads, SHIPPED.read_text().splitlines())}
    for name in names:
        overrides = [o.format(root=root) for o in automore.OVERRIDES[name]]
        sys.argv[2:] = overrides
        cfg, ds, train = rank.setup(overrides)
        comp = build_compensator(cfg, ds=ds).fit(train)
        row = stored[name]
        print(f"== {name}: {len(train)} train campaign(s)")
        for t, e in comp.estimators_.items():
            _, folds = e.oof_folds_
            outs = [((e.x_[s] < e.x_[f].min(0)) | (e.x_[s] > e.x_[f].max(0))).any(1) for f, s in folds]
            out = np.concatenate(outs)
            cands = [c for c in e.oof_ if c in row["squares"]]
            sq = [np.array([row["squares"][c][t][k] for k in row["new"]], float) for c in cands]
            new = np.array([np.sqrt(a[:, 1].sum() / a[:, 0].sum()) for a in sq])
            val = {w: np.array([np.sqrt(np.mean((e.oof_y_[m] - e.oof_[c][m]) ** 2)) for c in cands])
                   for w, m in (("all", np.ones_like(out)), ("out", out)) if m.sum() >= 2}
            said = ", ".join(f"{w} rho {spearmanr(v, new)[0]:+.2f} best {cands[int(np.argmin(v))]}"
                             for w, v in val.items())
            print(f"  {t}: {e.scheme_}; outside/held per fold "
                  f"{[f'{int(o.sum())}/{o.size}' for o in outs]}; new best {cands[int(np.argmin(new))]}; "
                  f"{said}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "trace": lambda root, *names: trace(Path(root).resolve(), list(names)),
        "rows": lambda root, work, *names: auto84.rows(Path(root).resolve(), Path(work).resolve(),
                                                       "as_is", list(names)),
        "fresh": lambda root, work: fresh(Path(root).resolve(), Path(work).resolve()),
        "bar": lambda old, new, oldf, newf: bar(Path(old), Path(new), Path(oldf), Path(newf)),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
