"""An independent check of ``model=auto``'s no-correction rule (stable67) on records it was not
tuned on (issue 34; stop 67, zerocheck67).

Usage::

    python benchmarks/bench_remeasure62.py write ROOT_A     # bench_autorep65's records (once)
    python benchmarks/bench_autocheck65.py write ROOT_B     # bench_autocheck65's (once)
    python benchmarks/bench_zerocheck67.py run16 ROOT_A     # auto (uncompensated=keep), 16 records
    python benchmarks/bench_zerocheck67.py run12 ROOT_B     # the same, 12 records
    python benchmarks/bench_zerocheck67.py score ROOT_A ROOT_B   # zero against keep, the verdict

The rule checked (stable67, 13671395): ``AutoRegressor`` validates no correction beside its
candidates (``validation_['none']``: the RMS of the out-of-fold labels, the rows every candidate is
scored on); where the kept model's pooled validation RMSE (the blend's ``rmse(oof_y - preds @ w)``,
or under ``combine=best`` the kept family's) is NOT below it, ``uncompensated=zero`` (the branch's
default) keeps a zero correction (the kept model weighted 0); ``keep`` keeps the model as before.
Its adoption bar covered only stable67's grinder, ``make run``'s record and ``fl_thermal``.

The records: bench_autorep65's 16 (``RECORDS``: bench_remeasure62's 11 auto records, fl9010,
col6511/6512, year6511/6512; the set bench_remeasure62 / autorep65 scored) and bench_autocheck65's
12 (``RECORDS``: seeds 6531-6542).  Their builders and runners are imported, not copied: ``run16``
is ``bench_autorep65.run``, ``run12`` is ``bench_autocheck65.run`` (bench_remeasure62's
``auto_row``: bench_auto_rank fits auto once on the train split, then each candidate alone; every
candidate's out-of-fold and test predictions saved per target), each record's overrides with
``model.estimator.uncompensated=keep`` appended: the fitted auto is the base's auto exactly (the
branch's ``keep``), and the arrays carry everything the rule reads.  ``score`` reads those arrays
(no refit): per target the kept weights ``w`` (re-derived by ``vote_weights`` where auto voted
and asserted equal to the kept ones, as bench_autorep65 asserts them), the kept model's pooled
validation ``kept = rmse(oof_y - oof @ w)``, no correction's ``none = rmse(oof_y)``; the target
is zeroed iff ``kept >= none`` (the src's test, ``not kept >= none`` keeps).  Its test RMSE under
``keep`` is the kept blend's (``rmse(test_y - test @ w)``, asserted = bench_auto_rank's auto);
under ``zero`` it is the uncompensated error's RMS on the test rows, ``rmse(test_y)`` (a zero
correction leaves the measured error: zero = before).  The test split is only scored: nothing here
chooses on it.

The verdict rule (written and committed before anything was scored)
-------------------------------------------------------------------
Per record the mean test RMSE over its targets (as bench_autorep65 / autocheck65), under ``zero``
and under ``keep``; over all 28 records (16 + 12) pooled.  The rule STAYS (default ``zero``) only
if all three hold:

1. the records where auto beats MLR (record mean below MLR's) are not fewer under ``zero`` than
   under ``keep``;
2. no record's mean test RMSE under ``zero`` is more than 2 % above ``keep``'s (ratio > 1.02);
3. the geometric mean over the 28 records of zero / keep is <= 1.0.

Otherwise it is turned OFF by default: ``conf/model/auto.yaml`` ``uncompensated: keep`` (the key
and the rule kept for a stable machine, asked for with ``model.estimator.uncompensated=zero``).
The rule itself is not changed here either way.  Reported, deciding nothing: the two sets apart,
the targets zeroed, each one's test RMSE under zero / keep / before and the validation figures
that zeroed it (kept, none, MLR's), CPU (user + sys).

Measured 2026-12-01 (stop 67; fix/stable67 74c977e3 with the bench, e28f1d7a; 2 shared cores under
load 7-10, AMD EPYC; run once, CPU user + sys: ``run16`` 216.6 s, ``run12`` 126.9 s, ``score``
0.6 s).  ``keep`` reproduced stop 65's shipped auto: the 60 targets of the 16 records equal
bench_autorep65's stored fits (/tmp/autorep65-root, main ba90b9e) exactly (largest relative
difference 0), the 12 records' means its docstring's "auto shipped" column.  Every voted target's
weights re-derived by ``vote_weights`` and its test RMSE equal the fit's (asserted).

**No target is zeroed: 0 of 94** (the 16 records' 60 targets, the 12's 34).  The kept model
validates below no correction everywhere; the closest, val kept / none: lab5401 E_X 0.812,
mill1514 E_X 0.644, year6_6534 E_X 0.391, lab6540 E_Y 0.308, fl9010 E_ch4 0.286.  So zero = keep
on every record (zero / keep 1.0000 for all 28): records better than MLR 18 -> 18 (16 records: 8,
12 records: 10), worst zero / keep 1.0000, geometric mean 1.0000.  **Verdict: the rule STAYS**
(default ``zero``): (1) 18 -> 18 met, (2) 1.0000 <= 1.02 met, (3) 1.0000 <= 1.0 met.  Refitted
end to end with the branch's default (``zero``; bench_auto_rank, nothing overridden) on the four
records nearest the line (lab5401, mill1514, year6_6534, lab6540): the same weights and test RMSE
as ``keep`` on all 12 targets, to the last digit (CPU 14.7 / 28.8 / 2.1 / 5.9 s).  ``fl_thermal``
60/20/20 (the val-split path, 97118f0c; deciding nothing): ``thermocomp run`` with ``zero`` and
``keep`` the same choice and test MAE 1.170 / 1.411 / 4.078 / 1.399 / 2.529 (no correction
validates 9.1-21.4 µm against the best candidate's 2.0-3.0; CPU 8.1 s each).

What this check does not reach: the rule never fires on these 28 records (all need
compensation), so it shows the rule costs nothing there, not that it is right where it fires.
Its known cost is where the folds are few (tests/shell/test_export_auto57.py's spindle fixture,
4 short train runs, 2 folds: none validated 0.767 against Hammerstein's 0.974, the zero tested
1.697 µm against 0.639).  Few folds are here too (one fold: lab5401 / 6539 / 6540, one held-out
10 h run of 1200 rows, trunnion6541, portal6542; 4 folds of 234-295 rows: the four year6_*;
3 folds: hmc, jig_grinder), but each record's errors are well above its noise: only lab5401
E_X came within 0.8 of none (0.812; its test: auto 2.639, MLR 2.64, before 5.14).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import bench_autocheck65 as autocheck  # noqa: E402
import bench_autorep65 as autorep  # noqa: E402
import bench_remeasure62 as remeasure  # noqa: E402
from _cli import run_commands  # noqa: E402

from thermocomp.core.metrics import rmse  # noqa: E402
from thermocomp.core.models.auto import BASELINE  # noqa: E402
from thermocomp.core.models.blend import vote_weights  # noqa: E402

KEEP = "model.estimator.uncompensated=keep"     # the base's auto, exactly
BAR_WORST, BAR_GEO = 1.02, 1.0


def _kept(overrides: dict) -> None:
    """Every record's overrides in ``overrides`` (a runner's dict, in place) fit the base's auto."""
    for name, o in overrides.items():
        if KEEP not in o:
            overrides[name] = [*o, KEEP]


def run16(root: Path, names: list[str]) -> None:
    _kept(remeasure.AUTO)
    _kept(autorep.EXTRA)
    autorep.run(root, names or autorep.RECORDS)


def run12(root: Path, names: list[str]) -> None:
    _kept(autocheck.RECORDS)
    autocheck.run(root, names or list(autocheck.RECORDS))


def target_row(report: dict, a) -> dict:
    """One target from the stored fit: MLR's test RMSE, keep's (the kept model), zero's
    (``rmse(test_y)``, = before), and the validation that decides (``kept`` against ``none``)."""
    members, y, fold, base, group, preds, test, kept = autorep.stored(report, a)
    w = np.array([kept.get(n, 0.0) for n in members])
    voted = len(members) > 1 and BASELINE in members
    if voted:                                        # auto voted (combine=vote, the default)
        shipped = vote_weights(preds, y, fold, base, base_column=members.index(BASELINE),
                               min_folds=autorep.N_FOLDS)
        assert np.allclose(shipped, w, atol=1e-9, rtol=0), (members, kept)
    else:                                            # one candidate kept whole ('best')
        assert abs(w.sum() - 1.0) < 1e-12, kept
    keep_test = rmse(a["test_y"] - test @ w)
    assert abs(keep_test - report["auto"]["rmse"]) < 1e-6 * (1 + keep_test)
    val_kept, val_none = rmse(y - preds @ w), rmse(y)
    zeroed = bool(val_kept >= val_none)
    before = rmse(a["test_y"])
    return {"mlr": report["mlr"], "best_single": report["best_single"], "keep": keep_test,
            "zero": before if zeroed else keep_test, "before": before, "zeroed": zeroed,
            "voted": voted, "val_kept": val_kept, "val_none": val_none,
            "val_mlr": report["validation"].get(BASELINE, float("nan")),
            "w": {n: round(float(v), 2) for n, v in kept.items() if v >= 0.005}}


def scored(root: Path, names: list[str]) -> list[tuple[str, dict]]:
    return autorep.score(root, names, target_row)


def _w(weights: dict) -> str:
    return " ".join(f"{remeasure._ABBREVIATED.get(n, n)} {v:.2f}" for n, v in weights.items())


def _counts(means: list) -> dict:
    n = len(means)
    ratio = [m["zero"] / m["keep"] for _, m in means]
    return {"n": n, "better_keep": sum(m["keep"] < m["mlr"] for _, m in means),
            "better_zero": sum(m["zero"] < m["mlr"] for _, m in means),
            "worst": max(ratio), "worst_record": means[int(np.argmax(ratio))][0],
            "geo": float(np.exp(np.mean(np.log(ratio))))}


def verdict(roots: dict) -> list[str]:
    lines, means, targets = [], [], []
    for label, (root, names) in roots.items():
        cpu = {r["record"]: r["cpu_s"] for r in remeasure._read(root / "auto.jsonl")}
        lines.append(f"{label}: CPU s (user + sys) per record (auto fit + each candidate alone): "
                     + ", ".join(f"{n} {cpu.get(n, float('nan')):.0f}" for n in names)
                     + f"; total {sum(cpu.get(n, 0.0) for n in names):.0f}")
        for name, s in scored(root, names):
            rows = s["targets"]
            targets += [(name, t, r) for t, r in rows.items()]
            m = {k: float(np.mean([r[k] for r in rows.values()])) for k in ("mlr", "keep", "zero")}
            means.append((name, m, label))
    zeroed = [(n, t, r) for n, t, r in targets if r["zeroed"]]
    lines += ["", f"targets zeroed: {len(zeroed)} of {len(targets)}; test RMSE zero (= before) / keep, "
              "MLR; validation kept / none (the decision), MLR; the kept weights"]
    lines += [f"  {n:12s} {t[:14]:14s} zero {r['zero']:.4g} keep {r['keep']:.4g} "
              f"({r['zero'] / r['keep']:.3f}), MLR {r['mlr']:.4g}; val kept {r['val_kept']:.4g} >= "
              f"none {r['val_none']:.4g}, MLR {r['val_mlr']:.4g}; {_w(r['w'])}" for n, t, r in zeroed]
    close = sorted(((r["val_kept"] / r["val_none"], n, t) for n, t, r in targets if not r["zeroed"]),
                   reverse=True)[:5]
    lines.append("not zeroed, the closest (val kept / none): " + ", ".join(
        f"{n} {t[:6]} {q:.3f}" for q, n, t in close))
    lines += ["", "per record, mean test RMSE over its targets: MLR, keep, zero, zero / keep "
              "(*: a target zeroed)"]
    hit = {n for n, _, _ in zeroed}
    lines += [f"  {n:12s} {m['mlr']:7.4g} {m['keep']:7.4g} {m['zero']:7.4g}  {m['zero'] / m['keep']:.4f}"
              f"{' *' if n in hit else ''}" for n, m, _ in means]
    for label in (*roots, "all"):
        sub = [(n, m) for n, m, lab in means if label in ("all", lab)]
        c = _counts(sub)
        lines.append(f"{label} ({c['n']} records): better than MLR keep {c['better_keep']} / zero "
                     f"{c['better_zero']}; worst zero / keep {c['worst']:.4f} ({c['worst_record']}); "
                     f"geometric mean zero / keep {c['geo']:.4f}")
    c = _counts([(n, m) for n, m, _ in means])
    ok = (c["better_zero"] >= c["better_keep"], c["worst"] <= BAR_WORST, c["geo"] <= BAR_GEO)
    lines.append("verdict: " + ("the rule STAYS (default zero)" if all(ok) else
                                "OFF by default (default keep; the key kept)")
                 + f" -- (1) records better than MLR {c['better_keep']} -> {c['better_zero']} "
                 f"{'met' if ok[0] else 'FAILED'}; (2) worst {c['worst']:.4f} {'<=' if ok[1] else '>'} "
                 f"{BAR_WORST} {'met' if ok[1] else 'FAILED'}; (3) geometric mean {c['geo']:.4f} "
                 f"{'<=' if ok[2] else '>'} {BAR_GEO} {'met' if ok[2] else 'FAILED'}")
    return lines


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "run16": lambda root, *names: run16(Path(root).resolve(), list(names)),
        "run12": lambda root, *names: run12(Path(root).resolve(), list(names)),
        "score": lambda root_a, root_b, *_: print(remeasure._wrapped(verdict({
            "autorep65 (16)": (Path(root_a).resolve(), autorep.RECORDS),
            "autocheck65 (12)": (Path(root_b).resolve(), list(autocheck.RECORDS))}), 106)),
    }, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
