"""First-sample-frame predictions anchored at the campaign's first sample (issue 34; stop 66,
anchor66).

Usage::

    python benchmarks/bench_anchor66.py run ROOT rep [RECORD ...]    # bench_autorep65's 16 records
    python benchmarks/bench_anchor66.py run ROOT check [RECORD ...]  # bench_autocheck65's 12 records
    python benchmarks/bench_anchor66.py score ROOT rep|check         # rules S and A, the verdicts
    python benchmarks/bench_anchor66.py readme                       # |f(t0)| on make run's record

ROOT holds the records as bench_remeasure62's ``write`` / bench_autocheck65's ``write`` make them
(``rep``: lab5401, lag, nm59, nm60; ``check``: lab6539, lab6540).  ``run`` is bench_autorep65's /
bench_autocheck65's ``run`` (bench_remeasure62's ``auto_row``: ``bench_auto_rank.main`` with
``keep_oof``, auto fitted once on the train split, then each candidate alone; the campaign of each
out-of-fold row kept where auto's folds hold out whole campaigns, ``oof_group``), with one
addition: bench_auto_rank's test series also give the test campaign of each row, saved in the
record's arrays as ``test_group`` (an integer code per test campaign, in ``ds.ids('test')``'s
order; ``check``: bench_autocheck65's ``measured_test_only``, the measured rows only).  ``score``
reads the stored arrays only (no refit).  Nothing here reads the test split to choose.

Why
---
With ``data.reference=first_sample`` a campaign's label is exactly 0 at its first sample, but a
model's prediction there, f(t0), is not (intercepts, S_ columns kept raw, lags' start rules, state
features): whatever f(t0) is, it is a constant the label does not have.  The hypothesis: predict
the change since the campaign's first sample, ``yhat(t) = f(t) - f(t0)``.  (Not "a free intercept
per run": nothing is fitted; the model's own first prediction is subtracted.)

The rules (written and committed BEFORE anything was scored; not tuned afterwards)
---------------------------------------------------------------------------------
A campaign is *anchored* where its first scored row's label is exactly 0 (the first-sample frame,
the error measured at its first row): ``t0`` is that row, every prediction of the campaign has
``f(t0)`` subtracted.  Campaigns in the ``none`` frame (continued records: trunnion, portal) or
first measured later (their label already compares ``f(t) - f(m)``, core/first_probe.py) are not
anchored.  A record-target is *reached* where at least one test campaign (rule S) or one test or
held-out campaign (rule A) is anchored.

* rule S (single families): each family's test predictions anchored per test campaign; per family
  the test RMSE before / after on every reached record-target; also auto's kept blend (shipped
  weights) anchored on the test ("auto S").
* rule A (auto): every candidate's out-of-fold predictions (MLR's too: it is also the votes'
  baseline) anchored per held-out campaign (folds of whole campaigns, ``oof_group``; a held-out
  campaign whose first out-of-fold label is not 0, and the one-record folds (forward chaining over
  one campaign, whose held-out blocks do not start at a campaign's first sample), are left as they
  are), the votes recomputed by ``vote_weights`` as shipped (``min_folds=5``, MLR the base) on
  those, the blend of the candidates' anchored test predictions with the new weights.  Where auto
  kept one family (no votes) A is that family anchored on the test.

The bars (written before scoring)
---------------------------------
Per record the mean test RMSE over its targets.  MLR, the baseline of "better than MLR", is the
SHIPPED MLR (not anchored): the issue's baseline is what ``model=mlr`` ships today; anchored MLR
is scored as a family of rule S and reported beside it.

* A is adopted on a set if, over its reached records: the number of records where auto beats
  the shipped MLR does not fall, the geometric mean of auto A / auto shipped is <= 0.98, and no
  reached record is more than 10 % worse (A / shipped <= 1.10).
* S is adopted for a family on a set if, over the records it reaches: the geometric mean of
  anchored / shipped is <= 0.98 and no record is more than 10 % worse.  The src mechanism is one
  for every model (the compensator's prediction path), so it is proposed only if S passes for
  every family that is a ``model=`` choice scored here (mlr, pcr, arx, lagbank, hammerstein,
  lstm) and A passes (auto); a family's ATI wrapper (ati) is reported, not required.
* Passing on ``rep`` (bench_autorep65's 16 records) -> checked ONCE on ``check``
  (bench_autocheck65's 12 fresh records, seeds 6531-6542) with the same bars; src only if both pass.

Also reported (deciding nothing): ``|f(t0)|`` per family over the anchored test campaigns and
held-out campaigns (median, 90th percentile, max, µm), and on the README's default record (``make
run``: ``sim=yearround_spindle``, its default seed, MLR; ``readme``: the test RMSE before / after).

Measured 2026-12-01 (stop 66; main aab2fa8d, the shipped code; 2 shared cores, AMD EPYC; run once,
one thread, CPU user + sys: ``run rep`` 99.0 s, ``run check`` 52.5 s, ``score`` 0.6 s, ``readme``
0.8 s).  The fits equal stop 65's (MLR and shipped auto on every target; shipped votes recomputed
from the arrays = the kept weights, asserted).  Reached: ``rep`` 15 of 16 (fl9010's test continues
its train: ``reference`` none); the test anchored everywhere else (1 run; 2 for year6_5411, hmc,
jig_grinder; 8 for year6511/6512), the out-of-fold rows only on the 6 records with folds of whole
campaigns (year6_5411, lab5401, hmc, jig_grinder, year6511, year6512: 1-16 held-out runs);
``check`` 10 of 12 (trunnion6541, portal6542: ``none``).  Per record mean test RMSE (µm): MLR
shipped / anchored, auto shipped / S / A::

  rep    col5791 6.97 6.55  9.21 8.87 8.87 | col1403 7.40 7.38  9.43 9.26 9.26 | col1514 10.4 10.6
         10.8 10.9 10.9 | mill1514 2.09 3.62  2.11 3.68 3.68 | swiss303 1.37 2.34  0.766 2.10 2.10 |
         swiss5454 1.46 2.87  1.36 2.82 2.82 | year6_5411 1.61 1.93  1.09 1.21 1.16 | lab5401 2.01
         2.26  2.06 2.29 1.80 | hmc 0.596 0.702  0.965 1.39 0.652 | twin_lathe 0.376 0.465  0.361
         0.506 0.506 | jig_grinder 0.704 0.607  0.683 0.654 0.656 | col6511 7.71 7.59  8.12 7.95 7.95
         | col6512 9.15 9.18  9.31 9.31 9.31 | year6511 2.64 2.62  0.987 1.18 1.13 | year6512 2.37
         2.72  1.11 1.45 1.28 | fl9010 4.06 4.06  2.48 2.48 2.48 (not reached)
  rule A (15 reached): better than the shipped MLR 7 -> 5; geometric mean A / shipped 1.169; worst
         2.742 (swiss303) -> FAILS.  hmc E_Y, the motivating case: 1.58 -> 0.863 (MLR 0.78).
  rule S, geometric mean anchored / shipped (worst record): mlr 1.169 (1.96), pcr 1.217 (2.35), arx
         1.219 (3.00), lagbank 1.207 (2.79), hammerstein 1.209 (2.74), lstm 1.166 (1.99), ati 1.276
         (1.46), auto (shipped weights) 1.266 (2.74) -> every family FAILS.
  check  (context only: the rule had failed on rep) rule A 1.204, better than MLR 8 -> 8, worst
         1.534 (climate6538); S per family 0.987 (hammerstein, worst 1.198) to 1.219 (ati) -> FAILS.

|f(t0)| over the anchored test campaigns, median / p90 / max µm (rep): mlr 0.50 / 2.4 / 4.4, pcr
1.15 / 4.9 / 14.9, arx 0.40 / 1.4 / 5.6, lagbank 0.84 / 2.1 / 6.8, hammerstein 0.26 / 0.95 / 5.0,
lstm 0.41 / 2.4 / 2.8, ati 0.40 / 1.3 / 1.3; check alike (mlr 0.63 / 2.9).  Anchoring lowered a
campaign's squared error in 31-54 % of the campaign x target cases per family (f(t0) is one sample
of the model's error: a start transient as often as a constant offset).  README record (MLR, no S_
input: f(t0) is its intercept, the same in the 8 test runs): |f(t0)| E_X 0.309, E_Y 0.043, E_Z 2.75
µm; test RMSE 0.750 -> 0.748, 1.424 -> 1.429, 5.80 -> 5.68.  **Refused on both sets: no src
change.**
"""

from __future__ import annotations

import json
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

SETS = {"rep": (autorep.RECORDS, autorep.EXTRA), "check": (list(autocheck.RECORDS), autocheck.RECORDS)}
FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein", "lstm")     # required for src (model=)
BAR_GEO, BAR_WORST = 0.98, 1.10
_TEST_GROUP: dict[str, np.ndarray] = {}


def keep_test_groups(measured_only: bool) -> None:
    """bench_auto_rank's test series with the test campaign of each row kept (``_TEST_GROUP``);
    ``measured_only``: bench_autocheck65's ``measured_test_only`` (the measured rows only)."""
    import bench_auto_rank as rank

    shipped = rank._test

    def test(comp, ds):
        meas, pred = shipped(comp, ds)
        ids = ds.ids("test")
        group = np.concatenate([np.full(len(ds.campaigns[c]), i) for i, c in enumerate(ids)])
        out_m, out_p = {}, {}
        for t, m in meas.items():
            assert len(m) == len(group), (t, len(m), len(group))
            keep = np.isfinite(m) if measured_only else np.ones(len(m), bool)
            out_m[t], out_p[t], _TEST_GROUP[t] = m[keep], pred[t][keep], group[keep]
        return out_m, out_p

    rank._test = test


def record_row(root: Path, name: str) -> dict:
    """bench_remeasure62's ``auto_row``, the record's arrays given ``test_group``."""
    _TEST_GROUP.clear()
    row = remeasure.auto_row(root, name)
    for t in row["targets"]:
        path = root / "rank" / f"{name}.{t}.npz"
        with np.load(path, allow_pickle=False) as a:
            arrays = dict(a)
        assert len(arrays["test_y"]) == len(_TEST_GROUP[t])
        np.savez(path, **arrays, test_group=_TEST_GROUP[t])
    return row


def run(root: Path, which: str, names: list[str]) -> None:
    autorep.keep_groups()
    keep_test_groups(measured_only=which == "check")
    if which == "check":
        autocheck.write(root)
    remeasure.AUTO.update(SETS[which][1])
    remeasure.measure(root / "auto.jsonl", (("auto", record_row(root, n)) for n in names))


# --- the rules, on the stored arrays ---

def anchors(y: np.ndarray, group: np.ndarray | None, fold: np.ndarray | None = None
            ) -> list[np.ndarray]:
    """The rows of each anchored campaign (per fold where ``fold`` is given), its first row
    ``t0`` first: the campaigns whose first row's label is exactly 0."""
    if group is None:
        return []
    key = group.astype(np.int64) if fold is None else group.astype(np.int64) * 1_000_003 + fold
    out = []
    for k in np.unique(key):
        rows = np.flatnonzero(key == k)
        if y[rows[0]] == 0.0:
            out.append(rows)
    return out


def anchored(pred: np.ndarray, runs: list[np.ndarray]) -> np.ndarray:
    """``pred`` (rows x columns, or rows) with each run's first row's prediction subtracted."""
    out = np.array(pred, dtype=float, copy=True)
    for rows in runs:
        out[rows] = out[rows] - out[rows[0]]
    return out


def target_row(report: dict, a) -> dict:
    names = [k[5:] for k in a.files if k.startswith("test_") and k not in ("test_y", "test_group")]
    members = [n for n in names if n in report["validation"]]
    y, fold = a["oof_y"], a["oof_fold"]
    oof_group = a["oof_group"] if "oof_group" in a.files else None
    test_y = a["test_y"]
    test_runs = anchors(test_y, a["test_group"])
    oof_runs = anchors(y, oof_group, fold)
    tests = {n: a["test_" + n] for n in names}
    row = {"mlr": report["mlr"], "best_single": report["best_single"],
           "n_test_runs": len(np.unique(a["test_group"])), "test_anchored": len(test_runs),
           "oof_anchored": len(oof_runs),
           "f0_test": {n: [float(tests[n][r[0]]) for r in test_runs] for n in names},
           "f0_oof": {n: [float(a["oof_" + n][r[0]]) for r in oof_runs] for n in members},
           # per anchored test campaign: f(t0) and the campaign's mean residual (label - f)
           "offset": {n: [(float(tests[n][r[0]]), float(np.mean(test_y[r] - tests[n][r])))
                          for r in test_runs] for n in names},
           "S": {n: (rmse(test_y - tests[n]), rmse(test_y - anchored(tests[n], test_runs)))
                 for n in names}}
    kept = report["auto"]["weights"]
    test = np.column_stack([tests[n] for n in members])
    test_a = anchored(test, test_runs)
    if len(members) < 2 or BASELINE not in members:      # 'best' kept one: no votes
        w = np.array([kept.get(n, 0.0) for n in members])
        row.update(auto=rmse(test_y - test @ w), autoS=rmse(test_y - test_a @ w),
                   A=rmse(test_y - test_a @ w), w=kept, wA=kept, voted=False)
        assert abs(row["auto"] - report["auto"]["rmse"]) < 1e-6 * (1 + row["auto"])
        return row
    col = members.index(BASELINE)
    preds = np.column_stack([a["oof_" + n] for n in members])
    base = a["oof_" + BASELINE]
    shipped = vote_weights(preds, y, fold, base, base_column=col, min_folds=autorep.N_FOLDS)
    assert all(abs(shipped[i] - kept.get(n, 0.0)) < 1e-9 for i, n in enumerate(members)), (members, kept)
    wA = vote_weights(anchored(preds, oof_runs), y, fold, anchored(base, oof_runs), base_column=col,
                      min_folds=autorep.N_FOLDS)
    row.update(auto=rmse(test_y - test @ shipped), autoS=rmse(test_y - test_a @ shipped),
               A=rmse(test_y - test_a @ wA), voted=True,
               w={n: round(float(v), 2) for n, v in zip(members, shipped) if v >= 0.005},
               wA={n: round(float(v), 2) for n, v in zip(members, wA) if v >= 0.005})
    assert abs(row["auto"] - report["auto"]["rmse"]) < 1e-6 * (1 + row["auto"])
    return row


def score(root: Path, names: list[str]) -> list[tuple[str, dict]]:
    out = []
    for name in names:
        report = json.loads((root / "rank" / f"{name}.json").read_text())
        rows = {t: target_row(r, np.load(root / "rank" / f"{name}.{t}.npz", allow_pickle=False))
                for t, r in report["targets"].items()}
        out.append((name, rows))
    return out


def _geo(ratios) -> float:
    return float(np.exp(np.mean(np.log(ratios)))) if len(ratios) else float("nan")


def _w(weights: dict) -> str:
    return " ".join(f"{remeasure._ABBREVIATED.get(n, n)} {v:.2f}" for n, v in weights.items())


def verdict(scored) -> tuple[list[str], dict]:
    lines = [f"{'record':12s} {'target':6s} runs test/oof {'MLR':>6s} {'MLR S':>6s} {'auto':>6s} "
             f"{'auto S':>6s} {'A':>6s}  weights shipped | A"]
    recs, passed = [], {}
    for name, rows in scored:
        for t, r in rows.items():
            same = r["w"] == r["wA"]
            lines.append(f"{name:12s} {t[:6]:6s} {r['test_anchored']}/{r['n_test_runs']} "
                         f"{r['oof_anchored']:3d}  {r['mlr']:6.3g} {r['S']['mlr'][1]:6.3g} "
                         f"{r['auto']:6.3g} {r['autoS']:6.3g} {r['A']:6.3g}  {_w(r['w'])}"
                         + (" (both)" if same else f" | {_w(r['wA'])}"))
        fams = sorted({n for r in rows.values() for n in r["S"]})
        m = {k: float(np.mean([r[k] for r in rows.values()])) for k in ("mlr", "auto", "autoS", "A")}
        m["S"] = {n: tuple(float(np.mean([r["S"][n][i] for r in rows.values()])) for i in (0, 1))
                  for n in fams}
        m["reached_S"] = any(r["test_anchored"] for r in rows.values())
        m["reached_A"] = any(r["test_anchored"] or r["oof_anchored"] for r in rows.values())
        recs.append((name, m))
    lines += ["", "per record, mean over its targets: MLR shipped / anchored, auto shipped / S / A, "
              "A / shipped (*: reached)"]
    lines += [f"  {n:12s} {m['mlr']:6.4g} {m['S']['mlr'][1]:6.4g}  {m['auto']:6.4g} {m['autoS']:6.4g} "
              f"{m['A']:6.4g}  {m['A'] / m['auto']:.3f}{' *' if m['reached_A'] else ''}" for n, m in recs]
    hitA = [(n, m) for n, m in recs if m["reached_A"]]
    better = {k: sum(m[k] < m["mlr"] for _, m in hitA) for k in ("auto", "A")}
    ratios = [m["A"] / m["auto"] for _, m in hitA]
    geo, worst = _geo(ratios), max(ratios, default=float("nan"))
    passed["A"] = bool(hitA) and better["A"] >= better["auto"] and geo <= BAR_GEO and worst <= BAR_WORST
    lines += ["", f"rule A over {len(hitA)} reached records: better than the shipped MLR {better['auto']} -> "
              f"{better['A']}; geometric mean A / shipped {geo:.4f}; worst {worst:.3f} -> "
              + ("PASSES" if passed["A"] else "FAILS") + " the bar"]
    hitS = [(n, m) for n, m in recs if m["reached_S"]]
    lines.append(f"rule S over {len(hitS)} reached records, per family: geometric mean anchored / "
                 "shipped, worst record, record means before -> after")
    for fam in ["auto", *sorted({f for _, m in hitS for f in m["S"]})]:
        pairs = [(n, (m["auto"], m["autoS"]) if fam == "auto" else m["S"][fam]) for n, m in hitS
                 if fam == "auto" or fam in m["S"]]
        rs = [b / a for _, (a, b) in pairs]
        g, wst = _geo(rs), max(rs, default=float("nan"))
        passed["S:" + fam] = bool(rs) and g <= BAR_GEO and wst <= BAR_WORST
        lines.append(f"  {fam:11s} {g:.4f} {wst:.3f} {'passes' if passed['S:' + fam] else 'fails '}  "
                     + ", ".join(f"{n} {a:.3g}->{b:.3g}" for n, (a, b) in pairs))
    mech = all(passed.get("S:" + f, False) for f in FAMILIES) and passed["A"]
    lines.append("the one mechanism (S for " + ", ".join(FAMILIES) + " and A): "
                 + ("PASSES" if mech else "FAILS"))
    lines += ["", "|f(t0)| (µm) per family over the anchored campaigns, median / p90 / max (count): "
              "test | held-out (out-of-fold)"]
    fams = sorted({f for _, rows in scored for r in rows.values() for f in r["f0_test"]})
    for fam in fams:
        parts = []
        for key in ("f0_test", "f0_oof"):
            v = np.abs([x for _, rows in scored for r in rows.values() for x in r[key].get(fam, [])])
            parts.append(f"{np.median(v):.3g} / {np.percentile(v, 90):.3g} / {v.max():.3g} ({v.size})"
                         if v.size else "-")
        lines.append(f"  {fam:11s} " + " | ".join(parts))
    lines += ["", "why (deciding nothing): per family over the anchored test campaigns, c = -sum(f0 m) / "
              "sum(f0^2), m the campaign's mean residual (the share of f(t0) that is the campaign's "
              "constant offset; anchoring lowers a campaign's squared error iff f0 m < -f0^2 / 2, "
              "c > 0.5 for equal campaigns), and the campaigns anchoring improves"]
    for fam in fams:
        pairs = np.array([x for _, rows in scored for r in rows.values() for x in r["offset"].get(fam, [])])
        f0, m = pairs[:, 0], pairs[:, 1]
        c = -float(f0 @ m) / float(f0 @ f0)
        lines.append(f"  {fam:11s} c {c:+.2f}; improved {int(np.sum(f0 * m < -f0 ** 2 / 2))} of {len(f0)}")
    return lines, passed


def readme() -> list[str]:
    """``make run``'s record (``sim=yearround_spindle``, default seed, model=mlr): f(t0) per test
    campaign and the test RMSE before / after anchoring."""
    import bench_auto_rank as rank
    from hydra import compose, initialize_config_dir
    from hydra.utils import instantiate

    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import build_compensator
    from thermocomp.shell.source import resolve_reference

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=["track=false", "plots=none"])
    ds = instantiate(cfg.sim.generator).generate()[0]
    resolve_reference(cfg, ds)
    comp = build_compensator(cfg, ds=ds).fit({c: ds.campaigns[c] for c in ds.ids("train")})
    keep_test_groups(measured_only=True)
    meas, pred = rank._test(comp, ds)
    lines = [f"README record: reference {cfg.data.reference}, model {type(comp.estimator).__name__}, "
             f"{len(ds.ids('test'))} test campaigns"]
    for t in meas:
        runs = anchors(meas[t], _TEST_GROUP[t])
        f0 = np.abs([pred[t][r[0]] for r in runs])
        lines.append(f"  {t}: |f(t0)| median {np.median(f0):.3g} max {f0.max():.3g} µm over {len(runs)}"
                     f" anchored runs; test RMSE {rmse(meas[t] - pred[t]):.4g} -> "
                     f"{rmse(meas[t] - anchored(pred[t], runs)):.4g}")
    return lines


def main(argv: list[str]) -> int:
    def scored(root: str, which: str, *names: str) -> None:
        lines, passed = verdict(score(Path(root).resolve(), list(names) or list(SETS[which][0])))
        print(remeasure._wrapped(lines, 110))
        print(json.dumps(passed))

    return run_commands(__doc__, {
        "readme": lambda *_: print("\n".join(readme())),
        "run": lambda root, which, *names: run(Path(root).resolve(), which,
                                               list(names) or list(SETS[which][0])),
        "score": scored,
    }, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
