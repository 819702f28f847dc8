r"""Does validation choose among families as they are deployed, with ``adapt.method``? (adaptval64)

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_adaptval64.py prepare ROOT
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_adaptval64.py score ROOT [--every-s S]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_adaptval64.py table ROOT

``run``'s validation is frozen: compare, promote and ``model=auto`` choose by it, while
``adapt.method=bias`` can reorder the families (trunnion 6301, bench_stranger63: bias raised
mlr's test E_dZ 3.93 -> 4.35 and lowered lagbank's 2.19 -> 1.24).  For each record and family
(``thermocomp run``'s chain in process: ``fit_chain``, ``validation_template``, the folds of
``validation_reports``, each refitted on its rows) three figures per target:

* ``frozen_val``: the held-out blocks' RMSE as ``run``'s validation scores them;
* ``adapted_val``: each fold's held-out block streamed with the same
  :class:`~thermocomp.apps.deploy.adapt.Adaptation` as replay's (``adapt.*``), its
  references the fold's measured error (the label as the fold scores it) on replay's schedule
  (``every_s`` from each campaign's or block's first row), its state at a fold's start as replay's
  at the test split's: nothing learned; carried from one held-out unit of a fold to the next, as
  replay carries it from one test campaign to the next;
* ``adapted_test``: the test campaigns predicted as ``run`` scores them (state carried over
  where it applies, = replay's stream to 1e-13 µm, bench_stranger63) and adapted as replay
  adapts them (:meth:`Adaptation.correct_recorded`, in their order).

Records: trunnion (seed 6301, the lab's files through ``init``, bench_stranger63), the probe
grinder (seed 6131, bench_probe61 / bench_autocpu63), swiss_lathe_door (its default seed),
climate_room (43 short runs, its default seed), fl_thermal (the shipped spindle record, its
last 10 % the test).  Families mlr, pcr, arx, lagbank, hammerstein (lstm and arx_rf left out:
their fold fits cost minutes each on 2 shared cores).

The rule, written before any adapted figure was computed
--------------------------------------------------------
Cases: every (record, target) (``model=auto`` and ``promote.target=<E_ column>`` choose per
target) and each record's mean over its targets (``compare.target=mean``).  Per case the
frozen pick (lowest ``frozen_val``) and the adapted pick (lowest ``adapted_val``) are scored by
their ``adapted_test``; the regret of a pick is its ``adapted_test`` over the best family's,
minus 1.  ``adapt.method=bias`` (the recommended one) decides; ``rls`` is reported beside it.
The adapted validation is adopted only if BOTH

1. where the two picks differ, the adapted pick has the lower ``adapted_test`` in more cases
   than the frozen pick does, and
2. the mean regret over all cases is lower with the adapted pick than with the frozen one.

Otherwise it is refused and these numbers go to docs/sweeps.md.  Spearman's rho of each
validation against ``adapted_test`` over the families is reported, not used to decide.

Measured (2026-12-01, 2 shared cores; 85 s of CPU over the 55 record x family cells)
-------------------------------------------------------------------------------------
Checked first: ``frozen_val`` = ``validation_report``'s RMSE exactly (0.0 in all 55 cells), and
trunnion's mlr ``adapted_test`` = bench_stranger63's replay (bias 0.27 / 0.28 / 4.35, rls 0.29 /
0.31 / 4.73).  Verdict: REFUSED, the choice stays the frozen validation::

    method (every_s)  records        cases differ better/worse  regret frozen->adapted  rho (Spearman)
    bias (7200, rule) the rule's 5     20     5      2 / 3       0.045 -> 0.084     +0.72 -> +0.76
    bias (7200)       6 added after    25     9      5 / 4       0.141 -> 0.168     +0.56 -> +0.64
    rls  (7200)       the rule's 5     20     3      2 / 1       0.068 -> 0.102     +0.70 -> +0.78
    bias (1800)       the rule's 5     20     3      2 / 1       0.036 -> 0.026     +0.73 -> +0.74
    bias (1800)       6 added after    25    10      6 / 4       0.161 -> 0.193     +0.57 -> +0.69
    rls  (1800)       all 11           45    27     10 / 17      0.613 -> 0.713     +0.52 -> +0.47

("differ": the cases where the two picks differ; "better/worse": the adapted pick's adapted test
against the frozen pick's there.)

Added after the rule decided (``extra_records``, deciding nothing): trunnion_b, grinder_b,
yearround_spindle, long_record, large_mill_week, column_moving_source.  Adaptation changed the
test's best family in 5 of the rule's 20 cases (bias, 7200 s).  The adapted pick's worst misses:
fl_thermal ch5 mlr 2.93 um against the lag bank's 1.41 (7200 s), column_moving_source Y lagbank
17.3 against mlr's 7.58 (1800 s: its test half holds a heat source never trained on; its 4
cases are all the added records' losses at 1800 s); its best hits: swiss_lathe_door X
hammerstein 0.94 against the lag bank's 1.47, grinder's mean lagbank 0.61 against arx's 0.71.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
FAMILIES = ("mlr", "pcr", "arx", "lagbank", "hammerstein")
METHODS = ("bias", "rls")
DECIDING = "bias"


def records(root: Path) -> dict[str, list[str]]:
    """Record -> the data overrides ``thermocomp run`` is given for it."""
    return {
        "trunnion": [f"hydra.searchpath=[file://{root}/init-trunnion/conf]", "data=trunnion"],
        "grinder": [f"hydra.searchpath=[file://{root}/init-grinder/conf]", "data=grinder"],
        "swiss_lathe_door": [f"data.path={root}/swiss_lathe_door"],
        "climate_room": [f"data.path={root}/climate_room"],
        "fl_thermal": ["data=fl_thermal"],
    }


SIMULATED = ("yearround_spindle", "long_record", "large_mill_week", "column_moving_source")


def extra_records(root: Path) -> dict[str, list[str]]:
    """Records added AFTER the rule decided on :func:`records` (reported, deciding nothing): the
    second draws of the two lab machines and four more simulated ones."""
    return {"trunnion_b": [f"hydra.searchpath=[file://{root}/init-trunnion_b/conf]",
                           "data=trunnion_b"],
            "grinder_b": [f"hydra.searchpath=[file://{root}/init-grinder_b/conf]",
                          "data=grinder_b_joined"],
            **{sim: [f"data.path={root / sim}"] for sim in SIMULATED}}


def prepare(root: Path) -> None:
    """The records' files: the lab's through ``init`` (trunnion, grinder), the simulated ones."""
    env = dict(os.environ, PYTHONPATH=str(REPO / "src"))
    py = [sys.executable]
    steps = [[*py, str(REPO / "benchmarks" / "bench_stranger63.py"), "write", str(root)],
             [*py, "-m", "thermocomp", "init", str(root / "trunnion"), f"out={root}/init-trunnion"],
             [*py, str(REPO / "benchmarks" / "bench_probe61.py"), "write", str(root)],
             [*py, "-m", "thermocomp", "init", str(root / "grinder"), "data.test_fraction=0.34",
              f"out={root}/init-grinder"]]
    steps += [[*py, "-m", "thermocomp", "init", str(root / "trunnion_b"), "data.sample_period_s=60",
               f"out={root}/init-trunnion_b"],
              [*py, str(REPO / "benchmarks" / "bench_probe61.py"), "join", str(root)],
              [*py, "-m", "thermocomp", "init", str(root / "grinder_b_joined"),
               "data.test_fraction=0.34", f"out={root}/init-grinder_b"]]
    for sim in ("swiss_lathe_door", "climate_room", *SIMULATED):
        if not (root / sim).exists():
            steps.append([*py, "-m", "thermocomp", "simulate", f"sim={sim}",
                          f"data.path={root / sim}", "track=false"])
    root.mkdir(parents=True, exist_ok=True)
    for step in steps:
        subprocess.run(step, cwd=root, env=env, check=True)


def rms(values) -> float | None:
    r = np.concatenate([np.ravel(v) for v in values]) if values else np.empty(0)
    ok = np.isfinite(r)
    return float(np.sqrt(np.mean(r[ok] ** 2))) if ok.any() else None


def fold_units(template, ds):
    """``(campaigns as fitted, folds, method)``: the folds ``validation_reports`` scores."""
    from thermocomp.core import continuation
    from thermocomp.core.scoring import evaluation as ev

    train = ev.require_split(ds, "train")
    camps = continuation.fit_campaigns(ds, ds.campaigns, train,
                                       getattr(template, "reference", "first_sample"))
    if len(camps) >= 2 and ev.holdout_scheme(ds) == "forward":
        return camps, ev._campaign_folds(camps, ev.VAL_FOLDS, blocked=True), "blocked forward"
    if len(camps) >= 2:
        return camps, ev._campaign_folds(camps, ev.VAL_FOLDS), "leave-campaigns-out"
    return camps, ev._forward_folds(camps, ev.VAL_FOLDS), "forward chaining"


def validation(template, ds, adapt_cfg) -> dict:
    """Per target: frozen and adapted (per method) validation RMSE over the held-out blocks."""
    from omegaconf import OmegaConf
    from sklearn.base import clone

    from thermocomp.apps.deploy.adapt import from_config
    from thermocomp.core.context import TIME

    camps, folds, method = fold_units(template, ds)
    frozen, adapted = {}, {m: {} for m in METHODS}
    targets = None
    for fit_rows, pred_rows, units, _ in folds:
        comp = clone(template).fit({c: camps[c].iloc[:n] for c, n in fit_rows.items()})
        targets = list(comp.targets_)
        part = {c: camps[c].iloc[:n] for c, n in pred_rows.items()}
        pred = comp.predict(part, mode="simulation")
        meas = comp.measured(part, predicted=pred)
        adapters = {m: from_config(OmegaConf.merge(adapt_cfg, {"method": m}), len(targets))
                    for m in METHODS}
        for unit, (c, a, b) in units.items():
            y = meas[c][targets].to_numpy(float)[a:b]
            p = pred[c][targets].to_numpy(float)[a:b]
            times = part[c][TIME].to_numpy(float)[a:b]
            for t_j, t in enumerate(targets):
                frozen.setdefault(t, []).append(y[:, t_j] - p[:, t_j])
            for m, adapt in adapters.items():
                adapt.start()          # a held-out unit: the schedule from its first row
                q = adapt.correct(p, times, y)
                for t_j, t in enumerate(targets):
                    adapted[m].setdefault(t, []).append(y[:, t_j] - q[:, t_j])
    return {"method": f"{method} ({len(folds)} folds)",
            "targets": {t: {"frozen_val": rms(frozen[t]),
                            **{f"adapted_val_{m}": rms(adapted[m][t]) for m in METHODS}}
                        for t in targets}}


def test_figures(comp, ds, adapt_cfg) -> dict:
    """Per target: frozen and adapted (per method) test RMSE, as run scores / replay adapts."""
    from omegaconf import OmegaConf

    from thermocomp.apps.deploy.adapt import from_config
    from thermocomp.core import continuation

    ids = ds.ids("test")
    targets = list(comp.targets_)
    pred, meas = continuation.predict(comp, ds, ids, "simulation", continuation.carry_over(comp, ds))
    out = {t: {"frozen_test": rms([meas[c][t].to_numpy(float) - pred[c][t].to_numpy(float)
                                   for c in ids])} for t in targets}
    for m in METHODS:
        adapt = from_config(OmegaConf.merge(adapt_cfg, {"method": m}), len(targets))
        res = []
        for c in ids:
            y = meas[c][targets].to_numpy(float)
            res.append(y - adapt.correct_recorded(pred[c][targets].to_numpy(float),
                                                  ds.campaigns[c], y))
        for j, t in enumerate(targets):
            out[t][f"adapted_test_{m}"] = rms([r[:, j] for r in res])
    return out


def score_one(root: Path, record: str, family: str, every_s: float | None = None) -> dict:
    """One record x family: ``run``'s fit, then the validation and test figures above
    (``every_s``: another ``adapt.every_s`` than the default)."""
    from thermocomp.shell.builders import validation_template
    from thermocomp.shell.chain import fit_chain
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.source import open_source

    data = {**records(root), **extra_records(root)}[record]
    every = [f"adapt.every_s={every_s}"] if every_s else []
    cfg = compose([*data, f"model={family}", "track=false", "plots=none", "adapt.method=bias", *every])
    ds = open_source(cfg)
    t0 = time.process_time()
    comp = fit_chain(cfg, ds)
    val = validation(validation_template(cfg, comp, ds), ds, cfg.adapt)
    test = test_figures(comp, ds, cfg.adapt)
    return {"record": record, "family": family, "validation_method": val["method"],
            "cpu_s": round(time.process_time() - t0, 1),
            "targets": {t: {**f, **test[t]} for t, f in val["targets"].items()}}


def results(root: Path, every_s: float | None = None) -> Path:
    return root / (f"adaptval64-every{every_s:g}.json" if every_s else "adaptval64.json")


def score(root: Path, names, every_s: float | None = None) -> None:
    path = results(root, every_s)
    rows = json.loads(path.read_text()) if path.exists() else []
    done = {(r["record"], r["family"]) for r in rows}
    os.chdir(REPO)        # data=fl_thermal's path is relative to the project root
    for record in names:
        for family in FAMILIES:
            if (record, family) in done:
                continue
            rows.append(score_one(root, record, family, every_s))
            print(json.dumps(rows[-1]), flush=True)
            path.write_text(json.dumps(rows, indent=1))


# -- the rule -----------------------------------------------------------------------------


def cases(rows: list[dict], method: str) -> list[dict]:
    """Per (record, target) and (record, mean): each family's three figures."""
    out = []
    for record in dict.fromkeys(r["record"] for r in rows):
        fam = {r["family"]: r["targets"] for r in rows if r["record"] == record}
        targets = list(next(iter(fam.values())))
        keys = {"frozen": "frozen_val", "adapted": f"adapted_val_{method}",
                "test": f"adapted_test_{method}", "frozen_test": "frozen_test"}
        for t in [*targets, "mean"]:
            figs = {f: {k: (float(np.mean([v[x][key] for x in targets])) if t == "mean"
                            else v[t][key]) for k, key in keys.items()} for f, v in fam.items()}
            out.append({"record": record, "target": t, "families": figs})
    return out


def judge(case: dict) -> dict:
    from scipy.stats import spearmanr

    figs = case["families"]
    best = min(f["test"] for f in figs.values())
    pick = {k: min(figs, key=lambda f: figs[f][k]) for k in ("frozen", "adapted")}
    test = [figs[f]["test"] for f in figs]
    return {**{f"{k}_pick": p for k, p in pick.items()},
            **{f"{k}_test": figs[p]["test"] for k, p in pick.items()},
            **{f"{k}_regret": figs[p]["test"] / best - 1 for k, p in pick.items()},
            "best_test": best, "best_family": min(figs, key=lambda f: figs[f]["test"]),
            "best_frozen_test": min(figs, key=lambda f: figs[f]["frozen_test"]),
            **{f"rho_{k}": float(spearmanr([figs[f][k] for f in figs], test)[0])
               for k in ("frozen", "adapted")}}


def summary(judged: list) -> tuple[str, bool]:
    """One line of the rule's numbers over ``judged`` ((case, judge) pairs), and its verdict."""
    changed = [j for _, j in judged if j["frozen_pick"] != j["adapted_pick"]]
    wins = sum(j["adapted_test"] < j["frozen_test"] for j in changed)
    losses = sum(j["adapted_test"] > j["frozen_test"] for j in changed)
    regret = {k: float(np.mean([j[f"{k}_regret"] for _, j in judged])) for k in ("frozen", "adapted")}
    rho = {k: float(np.nanmean([j[f"rho_{k}"] for _, j in judged])) for k in ("frozen", "adapted")}
    reordered = sum(j["best_frozen_test"] != j["best_family"] for _, j in judged)
    adopted = wins > losses and regret["adapted"] < regret["frozen"]
    return (f"{len(judged)} cases (adaptation changes the test's best family in {reordered}); picks "
            f"differ in {len(changed)}: adapted better in {wins}, worse in {losses}; mean regret "
            f"frozen {regret['frozen']:.3f}, adapted {regret['adapted']:.3f}; mean rho frozen "
            f"{rho['frozen']:+.2f}, adapted {rho['adapted']:+.2f}"), adopted


def table(root: Path, every_s: float | None = None) -> str:
    rows = json.loads(results(root, every_s).read_text())
    deciding = set(records(root))
    lines = []
    for method in METHODS:
        judged = [(c, judge(c)) for c in cases(rows, method)]
        lines.append(f"adapt.method={method}: record target | frozen pick (val) adapted test | "
                     "adapted pick (val) adapted test | best | rho frozen / adapted")
        for c, j in judged:
            lines.append(f"  {c['record']:20s} {c['target']:11s} | {j['frozen_pick']:11s} "
                         f"{j['frozen_test']:7.3f} | {j['adapted_pick']:11s} {j['adapted_test']:7.3f}"
                         f" | {j['best_test']:7.3f} | {j['rho_frozen']:+.2f} / {j['rho_adapted']:+.2f}")
        first = [(c, j) for c, j in judged if c["record"] in deciding]
        line, adopted = summary(first)
        deciding_here = method == DECIDING and every_s is None
        lines.append(f"  the rule's records: {line}; rule: {'ADOPT' if adopted else 'refuse'}"
                     + (" (deciding)" if deciding_here else " (reported)"))
        later = [(c, j) for c, j in judged if c["record"] not in deciding]
        if later:
            lines.append(f"  records added after the rule decided: {summary(later)[0]}")
            lines.append(f"  all records: {summary(judged)[0]}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", choices=("prepare", "score", "table"))
    parser.add_argument("root")
    parser.add_argument("--records", nargs="+", default=None)
    parser.add_argument("--every-s", type=float, default=None,
                        help="adapt.every_s (default: the config's); reported, deciding nothing")
    args = parser.parse_args(argv)
    root = Path(args.root).resolve()
    if args.what == "prepare":
        prepare(root)
        return 0
    if args.what == "score":
        score(root, args.records or [*records(root), *extra_records(root)], args.every_s)
    print(table(root, args.every_s))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
