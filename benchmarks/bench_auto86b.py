"""Why model=auto on a fresh climate room does not keep its ATI candidate (stop 86, auto86b).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_auto86b.py trace ROOT [RECORD ...]   # the tables below

``trace``: in a scratch project root ROOT (made where missing,
what an earlier command wrote kept -- made anew until review96 --; the tree's ``conf/`` linked
in), per record of :data:`RECORDS` (``simulate``), ``run model=auto`` with the candidates of bench_audit86b
(``mlr, pcr, arx, lagbank, hammerstein, ati``) and ``keep_oof=true``, every fold model auto fits
recorded as it is fitted (``clone`` wrapped: nothing else changes).  Per target: each candidate's
pooled validation RMSE, the kept weights, then per validation fold (blocked forward: the train
campaigns it fits, the one it holds out, with their initial ambients) the free-run RMSE of MLR,
of the ATI candidate (``ati``: ATI of MLR, conf/ati/cmeans.yaml) and of the kept blend, and the
intervals the fold's ATI model chose.  Only train campaigns enter (auto sees nothing else); the
test RMSE is ``run``'s, printed after the choice, chose nothing.

The question, and the bar (written before tracing): a DEFECT is an ``ati`` candidate that applies
(train campaigns at >= 3 ambient levels) but is skipped, not fitted in every fold, scored on rows
other than its fold's held campaign(s), tied row for row with MLR (``validated_as``), or a crash
swallowed; only such a defect, with a test failing on main, would be mended.  A candidate that is
fitted and validated as it should, and loses on its folds, is the selection RULE's (votes over
per-fold MSE / MLR's, one-SE fallback): out of scope here, reported with numbers.

Traced (2026-12-04, branch fix/auto86b at 096856cd's src, ``trace /tmp/auto86b/t6``; 12-run
records: 9 train campaigns, 4 blocked forward folds, each holding one later train campaign out;
cr9012 43 runs, 39 train, 5 folds; "beyond K": how far the held campaign's ambient lies outside the
train ambients of the fold ATI interval that predicts it; "x": the interval's model takes the
ambient interaction; 162.5 s CPU for the whole command, 4 records, 2 cores shared by 6 helpers)
-----------------------------------------------------------------------------------------------------
cr9031 (test C10-C12 at 28.9 / 32.7 / 34.4 °C; train 14.9-33.6)::

  E_X  validation: mlr 1.86, pcr 1.22, arx 1.96, lagbank 1.85, hammerstein 1.87, ati 2.87
       kept mlr 0.27 + pcr 0.29 + lagbank 0.44 (ati 0), test 2.00
  fold held      fit: n, ambients   mlr    ati   kept  ati/mlr MSE  beyond K  fold ATI
  0    C06 24.4  5, 14.9-31.4      1.39  0.865    0.8       0.387       0.0  5 14.9-31.4x
  1    C07 33.6  6, 14.9-31.4     0.934   4.98  0.671        28.4       2.3  6 14.9-31.4x
  2    C08 17.3  7, 14.9-33.6      3.07  0.811   2.53      0.0698       0.0  7 14.9-33.6x
  3    C09 22.5  8, 14.9-33.6       1.4   3.02   1.23        4.66       1.2  4 14.9-21.3x | 4 24.4-33.6x
  E_Z  validation: mlr 2.99, pcr 5.08, arx 3.03, lagbank 3.86, hammerstein 3.69, ati 12.8
       kept mlr (votes mlr 0.93 + arx 0.07, then the one-SE rule: 1.004 +- 0.015), test 4.18
  0    C06 24.4  5, 14.9-31.4      2.51   1.01   2.51       0.164       0.0  5 14.9-31.4x
  1    C07 33.6  6, 14.9-31.4      1.99   9.28   1.99        21.6       2.3  6 14.9-31.4x
  2    C08 17.3  7, 14.9-33.6      5.09   2.39   5.09       0.221       0.0  7 14.9-33.6x
  3    C09 22.5  8, 14.9-33.6     0.994   22.8  0.994         525       1.2  4 14.9-21.3x | 4 24.4-33.6x

Why its ATI candidate is not kept: it applies (9 campaigns, >= 3 levels), is fitted in all 4
folds, scored on the held campaign's rows, no skip, no ``validated_as``, no crash: NO DEFECT.
It loses on 2 of 4 folds, both where the held campaign's ambient lies outside the fold ATI
interval's train ambients: fold 1 (C07 at 33.6 °C, the fold fits up to 31.4: 2.3 K of
extrapolation of the ambient interaction; MSE x28 / x22 over MLR's) and fold 3 (the fold's elbow
takes 2 intervals where the fit on all 9 campaigns takes 1; C09 at 22.5 °C falls in the cold one,
fit on 4 campaigns at 14.9-21.3 °C: 1.2 K beyond, MSE x4.7 / x525).  On the 2 folds inside their
interval's range it beats MLR by far (MSE x0.07-0.39).  The vote's per-fold mean ratio and the
pooled RMSE (2.87 / 12.8 against 1.86 / 2.99) are dominated by the 2 extrapolating folds.  The
model deployed under ``ati=cmeans`` is another: one interval over 14.9-33.65 °C (its elbow,
leave-one-campaign-out, SM 0.91 for 1 against 1.52 for 2), the test campaigns inside it or 0.8 K
beyond -- test 0.807 (mlr ati).  So the folds score a model extrapolating in ambient with 5-8
campaigns that the test (interpolation with 9) does not face.

cr9012 (where auto kept ATI, 0.457 / 0.666): 39 train campaigns, every fold's ATI one interval
over 20-35 campaigns spanning 15.9/17.4-34.7 °C, held campaigns at most 1.5 K beyond; ATI wins
every fold (MSE x0.050-0.212 over MLR's): kept alone (1.0) for both targets.

Fresh records (seeds 9076, 9077; the cr9031 settings; ati/mlr MSE per fold 0-3, "beyond K",
the fold ATI's intervals; the fit on all 9 train campaigns: 1 interval, cr9077 E_Z 3)::

  cr9076 (train 17.0-28.5 °C, test 30.4-33.3: every test campaign beyond the train ambients)
    E_X kept mlr 0.25 + arx 0.21 + ati 0.53 (ati validates 1.07, mlr 1.24), test 0.724
        1.79 (0.0 K, 2 intervals), 0.336, 0.434, 0.808 (each 0.0 K, 1 interval)
    E_Z kept arx 0.79 + mlr 0.18 + ati 0.04 (ati validates 1.97, mlr 2.31), test 3.45
        0.613, 1.46, 0.0708, 4.44 (each 0.0 K, 1 interval)
  cr9077 (train 18.7-34.6 °C, test all at 24.8 °C)
    E_X kept ati 0.82 + hammerstein 0.10 + mlr 0.05 + lagbank 0.03, test 0.529
        0.201 (3.8 K), 1.32 (1.6 K, 2 intervals), 0.0954 (0.0), 0.368 (1.2 K)
    E_Z kept ati 0.95 + arx 0.05, test 0.767
        0.511 (3.8 K, 2 intervals), 0.804 (1.6 K, 2 intervals), 0.0449, 0.224

So ambient extrapolation explains the size of cr9031's two losses but is no rule: cr9076 loses
folds with 0 K beyond, cr9077 wins folds 3.8 K beyond.  What the losing folds share more often:
over the 3 small records, a fold whose own elbow split 2 intervals (where the fit on every train
campaign takes 1, but cr9077 E_Z: 3) lost to MLR in 4 of 6 fold-targets; a fold of 1 interval
in 4 of 18.

Test RMSE (µm, mean over the 2 targets; scored after, chose nothing; "auto +2 ati": candidates
also ``ati+arx``, ``ati+lagbank``; "interleaved": leave-campaigns-out folds; "in_range":
``validation_rows=in_range``; "1 int": auto with conf/ati/cmeans.yaml at ``n_intervals: 1``,
in its folds and its fit alike)::

  record  auto   mlr    mlr ati  arx ati  lagbank ati  interleaved  in_range  +2 ati  1 int
  cr9031  3.09   3.18   0.807    0.613    1.03         2.95         3.09      1.75    3.01
  cr9076  2.09   2.50   1.14     1.22     1.52         2.38         2.46      1.48    2.00
  cr9077  0.648  0.956  0.758    0.93     0.661        0.907        0.648     0.742   0.777
  cr9012  0.562  1.99   0.562    0.684    0.469        0.562        0.562     0.468   0.562

Issue 34 on these: auto below MLR on all 4; within 10 % of the best single family compared here
on cr9077 only (0.648 against lagbank ati 0.661); cr9031 5.0x arx ati, cr9076 1.83x mlr ati, cr9012
1.20x lagbank ati.

Verdict
-------
NO DEFECT found: the ATI candidate is fitted and validated on the right rows on every record;
nothing mended, no src change.  It is not kept on cr9031 (and only partly on cr9076 E_Z) by the
RULE: 12-run records give 4 blocked forward folds of 5-8 campaigns; on cr9031 the 2 folds where
the held ambient lies outside the fold interval's (one of them a split the full fit does not make)
raise the ATI candidate's per-fold MSE over MLR's x4.7-x525, against the x2.6-x14 it gains on
the other 2; on cr9076 E_Z it loses 2 folds inside the range (x1.46, x4.44).

What I would try next (each a rule change, each to be barred on fresh seeds 9078-9085: these 4
records are looked at):

(1) the ATI candidate's folds at the interval count the fit on every train campaign takes (score
the deployed structure, not each fold's own elbow; 4 of the 8 losing fold-targets had split
intervals).  Its proxy "1 int" (ATI at one interval in folds and fit) is not enough: cr9031 3.09
-> 3.01 (ati validates 2.42 / 4.52 against MLR's 1.86 / 2.99: fold 1's 2.3 K extrapolation stays),
cr9076 2.09 -> 2.00, cr9077 0.648 -> 0.777 (its E_Z fit takes 3 intervals).
(2) votes robust to one fold's blow-up (the median of the per-fold ratios, or ratios capped),
measured against the one-SE fallback's record (bench_auto80).
(3) ``ati+arx`` / ``ati+lagbank`` as candidates: 3.09 -> 1.75, 2.09 -> 1.48, 0.562 -> 0.468
(cr9012), but 0.648 -> 0.742 on cr9077 (looked at here: a lead, not a verdict).
Leave-campaigns-out folds (interleaved) and ``validation_rows=in_range`` do not help (table).
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import shutil
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE)]
from _cli import project_root, run_commands  # noqa: E402

# cr9031: bench_audit86b's record; cr9012: bench_audit86's (auto kept mlr + ATI there);
# cr9076 / cr9077: this stop's fresh draws (seeds 9076-9085), the cr9031 settings
SMALL = ["sim.generator.n_runs=12", "sim.generator.duration_h=[3.0,4.0]", "sim.generator.test_fraction=0.25"]
RECORDS = {
    "cr9031": ["sim=climate_room", "seed=9031", *SMALL],
    "cr9012": ["sim=climate_room", "seed=9012"],
    "cr9076": ["sim=climate_room", "seed=9076", *SMALL],
    "cr9077": ["sim=climate_room", "seed=9077", *SMALL],
}
CANDIDATES = "model.candidates=[mlr,pcr,arx,lagbank,hammerstein,ati]"
# scored after the trace, for the comparison only (test RMSE, mean over targets): single families
# plain and under ati=cmeans, and auto with leave-campaigns-out folds (what to try next)
COMPARED = {"mlr": ["model=mlr"], "mlr ati": ["model=mlr", "ati=cmeans"],
            "arx ati": ["model=arx", "ati=cmeans"],
            "lagbank ati": ["model=lagbank", "ati=cmeans"],
            "auto interleaved": ["model=auto", CANDIDATES, "eval.validation_scheme=interleaved"],
            "auto in_range": ["model=auto", CANDIDATES, "model.estimator.validation_rows=in_range"],
            "auto +2 ati": ["model=auto",
                            "model.candidates=[mlr,pcr,arx,lagbank,hammerstein,ati,ati+arx,ati+lagbank]"]}


def stage(*args: str) -> int:
    """``thermocomp <args>`` in process, its output swallowed; its exit status."""
    from thermocomp.shell.cli import main

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        try:
            return int(main(list(args)) or 0)
        except SystemExit as exc:
            return int(exc.code or 0)


def fitted_folds(run) -> list:
    """Run ``run()`` with auto's ``clone`` wrapped; per AutoRegressor (one a target, in order of
    fit) the fold models of its ``ati`` candidate, in fold order."""
    from thermocomp.core.models import auto

    seen, plain, validate = {}, auto.clone, auto.AutoRegressor._validate
    now = [None]

    def recording(est, *a, **k):
        made = plain(est, *a, **k)
        if now[0] is not None:
            seen[now[0][0]].append(made)
        return made

    def validating(self, name, *a, **k):
        seen.setdefault(id(self), [])
        now[0] = (id(self), name) if name == "ati" else None
        try:
            return validate(self, name, *a, **k)
        finally:
            now[0] = None

    auto.clone, auto.AutoRegressor._validate = recording, validating
    try:
        run()
    finally:
        auto.clone, auto.AutoRegressor._validate = plain, validate
    return list(seen.values())


def trace(root: Path, chosen: list[str]) -> None:
    from thermocomp.shell.model_store import load_model

    project_root(str(root), REPO / "conf")      # kept: made anew until review96
    for record in [r for r in RECORDS if r in chosen] or list(RECORDS):
        data, out = root / "data" / record, root / "reports" / record
        assert stage("simulate", *RECORDS[record], f"data.path={data}") == 0
        manifest = pd.read_csv(data / "campaigns.csv").set_index("campaign")
        train = manifest.index[manifest["split"] == "train"]
        amb = manifest["ambient_c"]
        made = fitted_folds(lambda: stage("run", f"data.path={data}", f"out={out}", "plots=none",
                                          "model=auto", CANDIDATES, "model.estimator.keep_oof=true",
                                          "track=false"))
        metrics = json.loads((out / "metrics.json").read_text())
        comp = load_model(out / "model.pkl")
        test = ", ".join(f"{c} {amb[c]:.1f}" for c in manifest.index if c not in train)
        print(f"\n== {record}: {len(train)} train campaigns (ambient °C: "
              f"{', '.join(f'{c} {amb[c]:.1f}' for c in train)}); test {test}")
        for k, (target, est) in enumerate(comp.estimators_.items()):
            a = est
            rep = metrics["targets"][target]
            val = rep["auto"]["candidates"]
            print(f"-- {target}: test RMSE {rep['test']['rmse']:.3f}; kept {rep['auto']['weights']}; "
                  f"skipped {rep['auto']['skipped'] or '-'}; "
                  f"validated_as {rep['auto']['validated_as'] or '-'}")
            print("   validation: " + ", ".join(f"{n} {v:.3g}" for n, v in val.items()))
            w = np.array([a.weights_.get(n, 0.0) for n in a.candidates if n in a.oof_])
            blend = np.column_stack([a.oof_[n] for n in a.candidates if n in a.oof_]) @ w
            n_folds = int(a.oof_fold_.max()) + 1
            print(f"   {'fold':<5}{'held: ambient':<26}{'fit: n, ambients':<18}{'mlr':>7}{'ati':>7}"
                  f"{'kept':>7}{'ati/mlr MSE':>12}{'beyond K':>9}  "
                  "fold ATI: intervals n campaigns lo-hi °C, x interaction")
            train_names = np.array(sorted(train))
            for f in range(n_folds):
                rows = a.oof_fold_ == f
                y = a.oof_y_[rows]
                r = {n: float(np.sqrt(np.mean((y - p[rows]) ** 2))) for n, p in
                     (("mlr", a.oof_["mlr"]), ("ati", a.oof_.get("ati", np.full(rows.size, np.nan))),
                      ("kept", blend))}
                held = list(train_names[np.unique(a.oof_campaign_[rows])])
                ati = made[k][f] if k < len(made) and f < len(made[k]) else None
                fit_a = np.array(list(ati.campaign_ambient_.values())) if ati else np.array([np.nan])
                how = (" | ".join(f"{len(i['campaigns'])} {i['ambient_min']:.1f}-{i['ambient_max']:.1f}"
                                  f"{'x' if t else ''}" for i, t in zip(ati.intervals_, ati.interactions_))
                       if ati else "-")
                print(f"   {f:<5}{' '.join(f'{c} {amb[c]:.1f}' for c in held):<25} "
                      f"{f'{fit_a.size}, {fit_a.min():.1f}-{fit_a.max():.1f}':<18}"
                      f"{r['mlr']:>7.3g}{r['ati']:>7.3g}{r['kept']:>7.3g}"
                      f"{(r['ati'] / r['mlr']) ** 2:>12.3g}"
                      f"{_beyond(ati, [amb[c] for c in held]):>9.1f}  {how}")
        scored = {"auto": np.mean([t["test"]["rmse"] for t in metrics["targets"].values()])}
        for name, args in [*COMPARED.items(), ("auto ati 1 interval", ["model=auto", CANDIDATES])]:
            there = root / "reports" / f"{record}-{name.replace(' ', '-')}"
            # the last: conf/ati/cmeans.yaml with n_intervals 1 (a copy), in the folds and the fit
            os.environ["THERMOCOMP_ROOT"] = str(one_interval(root) if name.endswith("interval") else root)
            assert stage("run", f"data.path={data}", f"out={there}", "plots=none", "track=false", *args) == 0
            os.environ["THERMOCOMP_ROOT"] = str(root)
            got = json.loads((there / "metrics.json").read_text())["targets"]
            scored[name] = np.mean([t["test"]["rmse"] for t in got.values()])
        print("   test RMSE (mean over targets, scored after, chose nothing): "
              + ", ".join(f"{n} {v:.3g}" for n, v in scored.items()))


def one_interval(root: Path) -> Path:
    """A project root beside ``root`` whose ``conf/`` is the tree's with ATI at one interval."""
    other = root / "one_interval"
    if not other.exists():
        shutil.copytree(REPO / "conf", other / "conf")
        ati = other / "conf" / "ati" / "cmeans.yaml"
        text = ati.read_text()
        assert "n_intervals: elbow" in text
        ati.write_text(text.replace("n_intervals: elbow", "n_intervals: 1", 1))
    return other


def _beyond(ati, ambients: list) -> float:
    """How far (K) the held campaigns' ambients lie outside the train ambients of the fold ATI
    interval that predicts them (the largest; 0 inside)."""
    if ati is None:
        return float("nan")
    out = 0.0
    for a0 in ambients:
        i = int(np.searchsorted(ati.boundaries_, a0))
        lo, hi = ati.intervals_[i]["ambient_min"], ati.intervals_[i]["ambient_max"]
        out = max(out, lo - a0, a0 - hi)
    return out


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "trace": lambda root, *chosen: trace(Path(root).resolve(), list(chosen)),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
