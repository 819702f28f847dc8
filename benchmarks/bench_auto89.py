"""``model=auto`` never worse than MLR by choice: a signal outside the fold ratios -- the later
part of every train campaign held out (issue 34; stop 89, auto89).  TRACED (no rule kept)

Usage (from the repository root; ``PYTHONPATH=<tree>/src``; ``seen`` and ``one`` need the trace
instrument: ``git apply benchmarks/auto89_rule.patch``, the rule as tried, below)::

    python benchmarks/bench_auto89.py seen DATA WORK VARIANT RECORD ...  # -> WORK/VARIANT.jsonl
    python benchmarks/bench_auto89.py table WORK VARIANT                 # the check against the test
    python benchmarks/bench_auto89.py one WORK RECORD                    # one-record records (column)

``seen``: bench_auto88's ``auto`` runner (``run model=auto``, this tree's src and conf) on climate
rooms of bench_auto88b's :data:`RECORDS` (simulated into DATA where absent); with the patch each
target's ``metrics.json`` ``targets.<t>.auto.late_parts`` holds the check's figures (per train
campaign, the kept blend's MSE over MLR's on its later half, both fitted on the earlier halves;
the blend's validation fold ratios beside).  ``table``: per target whose blend is not MLR alone,
main's test RMSE over MLR's (stored OLD rows of main's code: /tmp/auto88/seen, /tmp/auto88/fresh,
/tmp/auto88b/fresh: :data:`STORES`) beside the late parts' mean / median / geometric mean and
the validation folds' mean; then, exactly from those rows, each decision statistic as a rule
(``>= 1`` sends the target to MLR, whose test RMSE is the MLR row's): records changed, geometric
mean new / main, worst record, records worse than MLR.  ``one``: a one-record record
(bench_remeasure62's ``AUTO`` overrides, simulated into WORK/data) run with the check allowed on
one record's forward folds (it is off there in the patch: the later half of one record is what
those folds already validate), to see what it would say on the column.

The rule tried (``benchmarks/auto89_rule.patch``: ``LatePartsOut`` in model_selection/splitters.py,
``AutoRegressor.late_check='late_parts'``)
-------------------------------------------------------------------------------------------------
Where auto's folds hold out whole campaigns and the kept blend (after the one-SE rule) is not MLR
alone: every member and MLR fitted once more on the first half of each train campaign's rows,
every train campaign predicted in free run from its own start, scored on its second half; per
campaign the blend's summed squared error over MLR's; mean >= 1 keeps MLR alone.  Cost: one fit
per member and MLR (CPU cr9031 7.2 -> 7.1 s, cr9012 9.9 -> 12.1 s, within x1.5).

Trace (2026-12-05; main a0d62dea + the patch, ``git archive`` copy; 2 shared cores, load 2-4,
``OMP_NUM_THREADS=1``; seen records only: ``seen /tmp/auto89/data /tmp/auto89/seen2 late <the 31
rooms below>``, ``table /tmp/auto89/seen2 late``, the same with ``extremes``, ``one /tmp/auto89/one
col1403``; the patch as committed reproduces cr9245's / cr9088's figures of both to the bit)
------------------------------------------------------------------------------------------------
* cr9245 (auto88b's fresh; main auto 2.482 against MLR 1.922): E_X keeps ``ati`` 1.00 (its folds
  over MLR 0.27 0.31 0.90 0.07; validation RMSE 1.70 against MLR 5.98; test 0.919 against MLR
  1.150: a WIN); E_Z keeps ati 0.52 / mlr 0.39 / hammerstein 0.09 (ati validates 1.67 against MLR
  7.74; the blend's folds 1.25 0.72 0.80 0.23, mean + SE 0.96: passes the one-SE rule by 0.04;
  test 4.045 against MLR 2.693: the LOSS, x1.50).  Its test campaigns: C10 at 20.2 °C ramped
  -5 K (to ~15 °C, below every train campaign's 23.4-31.5 °C), C11 at duty 0.96 (train <= 0.93):
  ATI meets an ambient no train campaign had.  Late parts (per train campaign, blend / MLR): E_Z
  0.84 0.77 0.37 4.52 4.59 1.62 0.36 0.68 0.55 (mean 1.59, median 0.77, geo 1.01; ati alone 4.36,
  hammerstein 41.4) -> MLR, right; E_X 0.46 0.75 0.22 1.42 2.16 6.58 0.35 3.51 25.2 (mean 4.52)
  -> MLR, wrong (the win lost).  Record 2.482 -> 1.922 (= MLR).
* cr9088 (main 1.117 x MLR): E_X lagbank 0.53 / mlr 0.33 (folds 1.00 0.50 0.42 0.47; late mean
  1.73, median 0.83; lagbank alone 5.27) -> MLR; E_Z lagbank 0.64 (folds 0.45 0.75 0.08 0.71;
  late mean 0.90) passes: 1.339 -> 1.302 (MLR 1.199).
* col1403 (one train campaign; the loss is on new campaigns, 1.311 x MLR): its forward folds
  already are "the later part of the train record"; forced on it (``one``), the late half says
  the losing blends are far better than MLR: E_Y (lagbank 0.84) 0.11, E_Y_mid (hammerstein 0.64,
  lagbank 0.36) 0.04, E_Z_mid 0.59, E_Z 0.98 -- the column's losses are to a new test cycle
  (shifted ambient, an unseen source), auto86's ground; no signal here (13.4 s CPU).
* The 60 seen climate-room targets whose blend is not MLR alone (31 rooms: auto87's, auto88's,
  auto88b's; 7 lost to MLR on test), ``table``: Spearman of the late parts with main / MLR on
  test +0.51 (mean), +0.53 (median), +0.61 (geo), the validation folds' mean +0.57 -- as
  informative as the folds, not beside them: the side of 1 agrees with the test on 0.73 / 0.80 /
  0.83 of the targets, where "always below MLR" agrees on 0.88.  Strong wins fail it (cr9244 E_X
  0.44 x MLR on test: late mean 5.13, median 2.96; cr9183 E_Z 0.70: 5.57 / 3.80; cr9076 E_X 0.42:
  1.58 / 1.71); losses pass it (cr9089 E_Z 1.22 x MLR: 0.52 / 0.32; cr9083 E_X 1.11: median 0.48;
  cr9088 E_Z 1.16: 0.90).  A climate room's later half is the same room a warmer machine later
  (held or ramped), not the new ambient level its test loses on.
* Each statistic as the rule (exact from the rows; the real fits of ``mean`` equal it on all 31
  records): mean >= 1 flags 17 (4 of 7 losses, 13 wins): geo new / main 1.115, 11 records > 2 %
  worse (cr9079 0.850 -> 3.115, cr9182 1.268 -> 1.836, cr9076 2.085 -> 2.595, cr9244 0.869 ->
  1.200 ...), worse than MLR 2 -> 2 (cr9245 mended, cr9076 now); median >= 1: geo 1.029, 5 > 2 %,
  2 -> 3; geo >= 1: geo 1.019, 4 > 2 % (cr9244 x1.38, cr9076 x1.24, cr9183 x1.31), 2 -> 2.
* Probe after the rule failed (seen only, no rule taken from it): ``late_check=ambient_extremes``,
  the two train campaigns of the lowest and highest initial ambient held out (the fit on the
  others), aimed at cr9245's cause.  cr9245 right on both targets (E_X 1.46 0.47, mean 0.96: kept;
  E_Z 1.13 2.02: MLR; record 2.482 -> 1.806, below MLR's 1.922), but over the 60 targets Spearman
  +0.30 (mean) / +0.41 (geo), below the folds' +0.57: ATI's big wins fail it (cr9181 E_Z 0.17 x
  MLR on test: 1.14; cr9081 E_Z 0.50: 29.3), a loss passes (cr9089 E_Z geo 0.94).  As a rule
  (mean >= 1): geo x main 1.142, 8 records > 2 % worse (cr9181 0.655 -> 2.754, cr9079 0.850 ->
  3.115, cr9081 0.686 -> 1.456), worse than MLR 2 -> 1; geo >= 1: 1.025, 4 > 2 % worse.  Whether
  a test campaign's ambient lies outside the train span does not mark the losses either (cr9248:
  all three above the span, 0.28 / 0.30 x MLR; cr9083 E_X lost with all three inside).
* CPU of ``run model=auto`` with the check (not alternated with main: indicative): cr9031 7.1 s
  (main 7.2 in auto88), cr9012 11.2-12.1 s (main 9.9): one fit per member and MLR.

Verdict: the rule (mean >= 1, and the median / geo forms) makes the SEEN rooms worse, as does
the extremes probe, so neither was taken to fresh seeds: **TRACED**, src as on main (the
instrument in auto89_rule.patch).  Seeds 9271-9280 NOT drawn (left for the next rule).  The
brief's bar (fresh 9271-9280 as bench_auto88b's climate rooms: geo auto / MLR not worse than
main's and none > 2 % worse; the 22: fewer than 8 worse than MLR, none > 2 % worse; CPU x1.5 on
cr9031 / cr9012; auto tests) was not scored.
Left: the seen losses are small but for cr9245 E_Z (x1.50) and cr9089 E_Z (x1.22); no train-side
signal tried (fold spreads and votes auto87b-d, restarted blocks auto86, later halves and ambient
extremes here) separates them from the wins.  A lead, one record, not a finding: cr9245's train
ambient span (23.4-31.5 °C, 8.1 K) is the narrowest of the 31 rooms (the others 11.3-19.8 K).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto88b as auto88b  # noqa: E402
from _cli import run_commands  # noqa: E402

STORES = {"main": ["/tmp/auto88/seen/main.jsonl", "/tmp/auto88/fresh/old/main.jsonl",
                   "/tmp/auto88b/fresh/old/main.jsonl"],
          "mlr": ["/tmp/auto88/seen/mlr.jsonl", "/tmp/auto88/fresh/mlr/mlr.jsonl",
                  "/tmp/auto88b/fresh/mlr/mlr.jsonl"]}
# the checks (auto89_rule.patch's ``late_check``): late halves of every train campaign (the rule
# tried), the two ambient-extreme train campaigns held out (a probe)
auto88b.auto88.VARIANTS.update({"late": [], "extremes": ["+model.estimator.late_check=ambient_extremes"]})
STATISTICS = {"mean": np.mean, "median": np.median, "geo": lambda r: float(np.exp(np.mean(np.log(r))))}


def _rows(paths: list[str]) -> dict:
    out = {}
    for path in paths:
        out.update(auto88b.auto88._rows(Path(path)))
    return out


def late_rows(work: Path, variant: str) -> list[dict]:
    """Per target of WORK's runs with late-part figures: record, target, main's and MLR's test
    RMSE (the stored rows), the late parts' per-campaign ratios and the validation folds'."""
    main, mlr = _rows(STORES["main"]), _rows(STORES["mlr"])
    out = []
    for path in sorted((work / "root" / "reports").glob(f"*-{variant}/metrics.json")):
        record = path.parent.name.rsplit("-", 1)[0]
        if record not in main or record not in mlr:
            continue
        for target, v in json.loads(path.read_text())["targets"].items():
            late = v.get("auto", {}).get("late_parts")
            if late:
                out.append({"record": record, "target": target, "main": main[record]["rmse"][target],
                            "mlr": mlr[record]["rmse"][target], "late": np.asarray(late["ratios"]),
                            "folds": np.asarray(late.get("folds") or [np.nan]),
                            "weights": main[record]["weights"][target]})
    return out


def rule_effect(rows: list[dict], statistic) -> dict:
    """Exactly from the rows: targets where ``statistic`` of the late parts >= 1 take MLR's test
    RMSE; per record the mean over its targets (targets without figures: main's, as kept)."""
    main, mlr = _rows(STORES["main"]), _rows(STORES["mlr"])
    sent = {(r["record"], r["target"]) for r in rows if statistic(r["late"]) >= 1.0}
    records = sorted({r["record"] for r in rows})
    out = {}
    for record in records:
        old = main[record]["rmse"]
        new = {t: mlr[record]["rmse"][t] if (record, t) in sent else v for t, v in old.items()}
        out[record] = (float(np.mean(list(old.values()))), float(np.mean(list(new.values()))),
                       float(np.mean(list(mlr[record]["rmse"].values()))))
    return out


def table(work: str, variant: str) -> None:
    rows = late_rows(Path(work), variant)
    print("record  target  main/MLR | late parts mean  median  geo | folds mean   main's kept blend")
    for r in sorted(rows, key=lambda r: r["main"] / r["mlr"]):
        stats = "  ".join(f"{f(r['late']):6.3f}" for f in STATISTICS.values())
        print(f"{r['record']:7s} {r['target']:6s} {r['main'] / r['mlr']:6.3f}   |  {stats} | "
              f"{np.mean(r['folds']):6.3f}   {r['weights']}")
    lost = np.array([r["main"] > r["mlr"] for r in rows])
    print(f"\n{len(rows)} targets, {lost.sum()} lost to MLR on test")
    for name, f in STATISTICS.items():
        flagged = np.array([f(r["late"]) >= 1.0 for r in rows])
        effect = rule_effect(rows, f)
        ratio = np.array([n / o for o, n, _ in effect.values()])
        worse_mlr = [(o > m * (1 + 1e-9), n > m * (1 + 1e-9)) for o, n, m in effect.values()]
        print(f"rule '{name} >= 1': flags {flagged.sum()} ({(flagged & lost).sum()} of the {lost.sum()} "
              f"losses, {(flagged & ~lost).sum()} wins); records {len(effect)}: geo new/main "
              f"{np.exp(np.mean(np.log(ratio))):.4f}, worst {max(ratio):.3f} "
              f"({max(effect, key=lambda k: effect[k][1] / effect[k][0])}), > 2 % worse "
              f"{int((ratio > 1.02).sum())}, worse than MLR {sum(w[0] for w in worse_mlr)} -> "
              f"{sum(w[1] for w in worse_mlr)}")
        changed = [f"{k} {o:.3f} -> {n:.3f}" for k, (o, n, _) in effect.items() if abs(n / o - 1) > 1e-9]
        print("   " + ", ".join(changed))
    from scipy.stats import spearmanr

    test = [r["main"] / r["mlr"] for r in rows]
    print("Spearman with main's test RMSE over MLR's: " + ", ".join(
        f"late {n} {spearmanr([f(r['late']) for r in rows], test)[0]:+.2f}" for n, f in STATISTICS.items())
        + f", validation folds' mean {spearmanr([np.mean(r['folds']) for r in rows], test)[0]:+.2f}")
    side = np.array([[f(r["late"]) < 1 for f in STATISTICS.values()] for r in rows])
    print("side agreement with test (statistic < 1 where main beat MLR): "
          + ", ".join(f"{n} {np.mean(side[:, k] == ~lost):.2f}" for k, n in enumerate(STATISTICS))
          + f"; a constant 'below MLR' {np.mean(~lost):.2f}")


def seen(data: str, work: str, variant: str, *records: str) -> None:
    auto88b.auto88.auto(Path(data).resolve(), Path(work).resolve(), variant, list(records))


def one(work: str, record: str) -> None:
    """``record`` (bench_remeasure62's AUTO overrides) with the check allowed on one record."""
    import bench_auto87 as auto87
    import bench_remeasure62 as remeasure

    from thermocomp.core.models import auto

    auto.CAMPAIGN_FOLDS = (*auto.CAMPAIGN_FOLDS, auto.FORWARD_ONE)
    work_path = Path(work).resolve()
    data = work_path / "data" / record
    if not (data / "campaigns.csv").exists():
        assert auto87.stage("simulate", *remeasure.AUTO[record], f"data.path={data}") == 0, record
    root = auto87._root(work_path)
    targets, cpu = auto87._scored(data, root / "reports" / f"{record}-one", "model=auto")
    for t, v in targets.items():
        late = v["auto"].get("late_parts")
        print(f"{record} {t} test {v['test']['rmse']:.4f} kept {v['auto']['weights']} late {late}")
    print(f"CPU {cpu:.1f} s")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": seen, "table": table, "one": one}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
