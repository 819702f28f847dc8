"""Why ``model=auto``'s ATI candidate wins validation and loses the test (``trunnion`` E_Y, stop 58).

Usage::

    python benchmarks/bench_auto_ati58.py folds NAME [OVERRIDE ...]   # ATI per validation fold
    python benchmarks/bench_auto_ati58.py runs NAME [OVERRIDE ...]    # MLR / ATI per test run
    OUT=DIR python benchmarks/bench_auto_ati58.py after NAME [OVERRIDE ...]
        # bench_auto_rank.py with the rule below patched in (before: bench_auto_rank.py itself)

The rule, written down before any record was scored with it (after steps 1 and the test runs'
ambients on trunnion only): **the ambient interaction is not extrapolated in ambient**: an
interval's model takes ``X (clip(A0, a_lo, a_hi) - 20 °C)``, ``[a_lo, a_hi]`` the initial
ambients of the campaigns it was fitted on (the fit itself unchanged: its rows are inside).
The records, chosen before scoring (every one where the ATI candidate applies and that costs
under a minute of CPU): ``trunnion``, ``laser`` (bench_new_machines58), ``year6_5411``,
``year6_5412`` (``sim=yearround_spindle sim.generator.n_campaigns=6``), ``year5791``,
``year5792`` (``sim=yearround_spindle``), ``climate5501`` (``sim=climate_room``).  Acceptance:
no record's auto mean test RMSE worse by more than 1 %, and trunnion E_Y better.

FINDINGS
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from sklearn.base import clone

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_auto_rank import _test, setup  # noqa: E402

from thermocomp.core.context import AMBIENT_C0, groups_of, subset  # noqa: E402
from thermocomp.core.metrics import rmse  # noqa: E402
from thermocomp.core.models import auto as auto_module  # noqa: E402
from thermocomp.shell.builders import build_compensator  # noqa: E402

SEEN: dict = {}   # id(AutoRegressor) -> (X, y, context) it was fitted on


def _stash(fit):
    def wrapped(self, X, y, context=None):
        SEEN[id(self)] = (np.asarray(X, float), np.asarray(y, float), context)
        return fit(self, X, y, context)
    return wrapped


def campaign_a0(context, rows) -> dict:
    """``{campaign: initial ambient}`` of the rows ``rows``."""
    groups, a0 = groups_of(context)[rows], np.asarray(context[AMBIENT_C0], float)[rows]
    return {str(g): float(a0[np.flatnonzero(groups == g)[0]]) for g in dict.fromkeys(groups)}


def ati_fold(ati, X, y, context, fit, pred, score, variants: dict) -> dict:
    """The ATI candidate refitted on one fold: its intervals and the held-out runs' A0; the fold
    RMSE of ``variants`` (name -> params set on the candidate)."""
    model = clone(ati).fit(X[fit], y[fit], context=subset(context, fit))
    a0_fit, a0_held = campaign_a0(context, fit), campaign_a0(context, score)
    out = {"n": model.n_intervals_, "edges": [round(b, 2) for b in model.boundaries_],
           "campaigns": [len(iv["campaigns"]) for iv in model.intervals_],
           "interaction": list(model.interactions_),
           "elbow": None if model.elbow_ is None else {
               "chosen": model.elbow_["chosen"],
               "sm+sd": [round(a + b, 3) for a, b in zip(model.elbow_["sm"], model.elbow_["sd"])]},
           "fit_a0": [round(min(a0_fit.values()), 2), round(max(a0_fit.values()), 2)],
           "held_a0": {k: round(v, 2) for k, v in a0_held.items()}, "rmse": {}}
    for name, params in variants.items():
        m = clone(ati).set_params(**params).fit(X[fit], y[fit], context=subset(context, fit))
        yhat = np.asarray(m.predict(X[pred], context=subset(context, pred)), float)[score[pred]]
        out["rmse"][name] = rmse(y[score] - yhat)
    return out


VARIANTS = {"ati": {}, "ati_no_interaction": {"ambient_interaction": False},
            "one_interval_interaction": {"n_intervals": 1}}


def folds(name: str, overrides: list[str]) -> dict:
    """Step 1: per target, per fold, the ATI candidate's intervals and its RMSE against MLR's."""
    auto_module.AutoRegressor.fit = _stash(auto_module.AutoRegressor.fit)
    cfg, ds, train = setup([*overrides, "model.candidates=[mlr,ati]"])
    comp = build_compensator(cfg, ds=ds).fit(train)
    meas, _ = _test(comp, ds)
    report = {}
    for t, est in comp.estimators_.items():
        X, y, context = SEEN[id(est)]
        rows = {"validation": {k: round(v, 4) for k, v in est.validation_.items()}, "folds": []}
        for f, (fit, pred, score) in enumerate(est._folds(groups_of(context), len(y))):
            info = ati_fold(est.candidates["ati"], X, y, context, fit, pred, score, VARIANTS)
            k = est.oof_fold_ == f
            info["oof"] = {c: rmse(est.oof_y_[k] - est.oof_[c][k]) for c in est.oof_}
            assert np.isclose(info["rmse"]["ati"], info["oof"]["ati"]), (info["rmse"], info["oof"])
            rows["folds"].append(info)
            print(f"{name} {t} fold {f}: {info}", flush=True)
        report[t] = rows
    return report


def clip_interaction() -> None:
    """Patch the rule in: each interval's interaction takes its campaign's A0 clipped to the
    initial ambients of the campaigns the interval's model was fitted on."""
    from thermocomp.core.models.ati import AMBIENT_CENTRE_C, ATIRegressor

    fit_base = ATIRegressor._fit_base

    def _fit_base(self, X, y, rows, context):
        est, interacts = fit_base(self, X, y, rows, context)
        if interacts:
            a0 = np.asarray(subset(context, rows)[AMBIENT_C0], float)
            interacts = (float(a0.min()), float(a0.max()))
        return est, interacts

    def _design(X, context, interacts):
        if not interacts:
            return X
        a0 = np.asarray(context[AMBIENT_C0], float)
        if isinstance(interacts, tuple):
            a0 = np.clip(a0, *interacts)
        return np.hstack([X, X * (a0 - AMBIENT_CENTRE_C)[:, None]])

    ATIRegressor._fit_base = _fit_base
    ATIRegressor._design = staticmethod(_design)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[0] == "folds":
        folds(argv[1], argv[2:])
    elif argv[0] == "after":
        from bench_auto_rank import main as rank

        clip_interaction()
        rank(argv[1], argv[2:])
    elif argv[0] == "runs":
        per_run(argv[1], argv[2:])
    return 0



def per_run(name: str, overrides: list[str], families=("mlr", "ati")) -> dict:
    """Each test run's initial ambient and RMSE of ``families`` alone (fitted on the train split)."""
    from thermocomp.core.frame import initial_ambient
    from thermocomp.core.scoring.evaluation import split_residuals

    cfg, ds, train = setup([*overrides, f"model.candidates=[{','.join(families)}]"])
    auto = build_compensator(cfg, ds=ds)
    ids = ds.ids("test")
    out = {}
    for f in families:
        comp = clone(auto).set_params(estimator=clone(auto.estimator.candidates[f]))
        comp.fit(train)
        _, _, series = split_residuals(comp, ds, ids, "simulation")
        for t, (_, r) in series.items():
            out.setdefault(t, {})[f] = {c: round(rmse(r[c]), 3) for c in ids}
        if f.startswith("ati"):
            for t, est in comp.estimators_.items():
                out[t]["intervals"] = [(iv["low"], iv["high"], len(iv["campaigns"])) for iv in est.intervals_]
                out[t]["interaction"] = list(est.interactions_)
                out[t]["train_a0"] = {k: round(v, 2) for k, v in est.campaign_ambient_.items()}
    a0 = {c: round(initial_ambient(ds.campaigns[c]), 2) for c in ids}
    for t, row in out.items():
        row["test_a0"] = a0
        print(f"{name} {t}: {row}", flush=True)
    return out


if __name__ == "__main__":
    raise SystemExit(main())
