"""Scoring a fitted compensator on the train and test splits (pure core).

:func:`score` gives the ``targets`` part of ``metrics.json``; :func:`anova`,
:func:`mutual_prediction_report` and :func:`ati_report` the ``anova``,
``mutual_prediction`` and ``ati`` parts.  Models are built through a
``make_compensator`` callable, so this module knows no config.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from . import continuation
from .compensator import MODES, Compensator
from .frame import initial_ambient
from .io.contract import TIME, ContractError, Dataset
from .iso10791 import a3_report
from .jsonsafe import json_safe
from .metrics import reduction_pct, rsd, sm_sd, split_scores
from .stats import anova_oneway, mutual_prediction


def sample_period(ds: Dataset, ids) -> float:
    """Median sampling step (s) over the campaigns ``ids``."""
    steps = [np.diff(ds.campaigns[c][TIME].to_numpy(float)) for c in ids]
    steps = np.concatenate([s for s in steps if s.size]) if steps else np.empty(0)
    return float(np.median(steps)) if steps.size else float("nan")


def require_split(ds: Dataset, split: str) -> list[str]:
    ids = ds.ids(split)
    if not ids:
        raise ContractError(f"the dataset has no {split!r} campaign (set `split` in the manifest "
                            f"or data.split_overrides)", file="campaigns.csv", column="split")
    return ids


def score(comp: Compensator, ds: Dataset, mode: str = "simulation",
          e_p95_statistic: str = "range", e_p95_points: int | None = 200,
          iso_a3: bool = True) -> tuple[dict, dict]:
    """Per-target train/test figures in the layout of ``metrics.json`` (``targets`` key).

    The test split also gets ``iso10791_a3``, the ISO 10791-10 A.3 virtual
    test of :mod:`thermocomp.iso10791` (``summary`` null with a reason when no
    test campaign lasts the test's 15 h).  Beside the figures of ``mode``,
    each target gets the test figures (``rmse``, ``rsd_mean``, ``rsd_sd``) of
    the other mode (``test_one_step`` or ``test_simulation``) and of the
    persistence baseline (``persistence``: the previous measured error as the
    prediction).  A campaign that continues another one is predicted with the
    model's state carried over (:mod:`thermocomp.continuation`).

    Returns
    -------
    targets : dict
        ``{target: {"train": {...}, "test": {...}, "test_<other mode>": {...},
        "persistence": {...}}}``.
    predictions : dict
        ``{campaign: (measured DataFrame, predicted DataFrame)}`` for test campaigns.
    """
    out = {t: {} for t in comp.targets_}
    predictions = {}
    carried = continuation.carry_over(comp, ds)
    for split in ("train", "test"):
        ids = require_split(ds, split)
        pred, meas = continuation.predict(comp, ds, ids, mode, carried)
        dt = sample_period(ds, ids)
        for t in comp.targets_:
            y = {c: meas[c][t].to_numpy() for c in ids}
            r = {c: y[c] - pred[c][t].to_numpy() for c in ids}
            out[t][split] = split_scores(y, r, dt, e_p95_statistic, e_p95_points,
                                         with_before_after=(split == "test"))
            if split == "test" and iso_a3:
                times = {c: ds.campaigns[c][TIME].to_numpy(float) for c in ids}
                out[t][split]["iso10791_a3"] = a3_report(times, y, r)
        if split == "test":
            predictions = {c: (meas[c], pred[c]) for c in ids}
    ids = require_split(ds, "test")
    other = next(m for m in MODES if m != mode)
    baselines = {f"test_{other}": continuation.predict(comp, ds, ids, other, carried)[0],
                 "persistence": continuation.persistence(comp, ds, ids, carried)}
    for key, pred in baselines.items():
        for t in comp.targets_:
            y = {c: predictions[c][0][t].to_numpy() for c in ids}
            out[t][key] = split_scores(y, {c: y[c] - pred[c][t].to_numpy() for c in ids}, 1.0,
                                       with_before_after=False)
    return out, predictions


def predict_split(comp: Compensator, ds: Dataset, split: str, mode: str = "simulation"
                  ) -> dict:
    """``{campaign: (measured, predicted)}`` of a split, state carried over where it applies
    (what :func:`score` scores; for ``diagnose``'s test scoring and ``replay``)."""
    ids = require_split(ds, split)
    pred, meas = continuation.predict(comp, ds, ids, mode)
    return {c: (meas[c], pred[c]) for c in ids}


def ambient_by_campaign(ds: Dataset, ids=None) -> dict[str, float]:
    """Initial absolute ambient temperature (°C) of each campaign (NaN without ``T_amb*``)."""
    return {c: initial_ambient(ds.campaigns[c]) for c in (ds.ids() if ids is None else ids)}


def _test_rsd(comp: Compensator, ds: Dataset, mode: str) -> dict[str, dict[str, float]]:
    """Per target, the Rsd of each test campaign."""
    ids = require_split(ds, "test")
    pred, meas = continuation.predict(comp, ds, ids, mode)
    return {t: {c: rsd(meas[c][t].to_numpy() - pred[c][t].to_numpy()) for c in ids}
            for t in comp.targets_}


def _sm_sd_entry(per_campaign: dict[str, float]) -> dict:
    sm, sd = sm_sd(list(per_campaign.values()))
    return {"rsd_mean": sm, "rsd_sd": sd,
            "per_campaign": {c: (float(v) if np.isfinite(v) else None) for c, v in per_campaign.items()}}


def anova(comp: Compensator, ds: Dataset, alpha: float = 0.001,
          predictions: dict | None = None) -> dict:
    """One-way ANOVA across campaigns per target (paper 003, Sect. 3.3).

    ``error``: the measured error of every campaign of the dataset, in the
    reference frame (does the error law differ between campaigns?);
    ``residual_test``: the residual of the test campaigns, when ``predictions``
    (from :func:`score`) are given (does the model leave campaign-specific error?).
    """
    camps = {c: ds.campaigns[c] for c in ds.ids()}
    meas = comp.measured(camps)
    out = {}
    for t in comp.targets_:
        entry = {"error": anova_oneway({c: meas[c][t].to_numpy() for c in camps}, alpha)}
        if predictions:
            entry["residual_test"] = anova_oneway(
                {c: (m[t] - p[t]).to_numpy() for c, (m, p) in predictions.items()}, alpha)
        out[t] = entry
    return out


def mutual_prediction_report(make_compensator: Callable[[], Compensator], ds: Dataset,
                             mode: str = "simulation") -> dict:
    """Mutual prediction matrices over all campaigns, ordered by initial ambient.

    ``{target: {"campaigns": [...], "ambient_c0": [...], "rsd": [[...]]}}``, row
    ``i`` trained on campaign ``i`` alone, column ``j`` predicted (paper 003, Fig. 6).
    """
    amb = ambient_by_campaign(ds)
    ids = sorted(ds.ids(), key=lambda c: (np.nan_to_num(amb[c], nan=np.inf), c))
    mats = mutual_prediction({c: ds.campaigns[c] for c in ids}, make_compensator, mode)
    return {t: {"campaigns": ids, "ambient_c0": json_safe([amb[c] for c in ids]),
                "rsd": json_safe(m.to_numpy())}
            for t, m in mats.items()}


def ati_report(comp: Compensator, ds: Dataset, make_base: Callable[[], Compensator],
               mode: str = "simulation", name: str = "none") -> dict:
    """ATI intervals, elbow and the paper-003 comparison on the test split.

    Per target: the fitted intervals and elbow curve (when the model is an ATI
    model), and the test SM/SD of the evaluated model next to one model trained
    on the coldest train campaign alone and one on the warmest (paper 003,
    Sect. 4.3), plus -- for an ATI model -- one model on all train campaigns.
    """
    train = require_split(ds, "train")
    amb = ambient_by_campaign(ds, train)
    out: dict = {"name": name}
    models = {"model": comp}
    if all(np.isfinite(v) for v in amb.values()):
        cold, warm = min(amb, key=amb.get), max(amb, key=amb.get)
        out["baseline_campaigns"] = {"coldest": {"campaign": cold, "ambient_c0": amb[cold]},
                                     "warmest": {"campaign": warm, "ambient_c0": amb[warm]}}
        models["coldest"] = make_base().fit({cold: ds.campaigns[cold]})
        models["warmest"] = make_base().fit({warm: ds.campaigns[warm]})
    else:
        out["reason"] = ("no initial ambient temperature (T_amb*) in the train campaigns: "
                         "no cold/warm baselines")
    out["ati_model"] = any(hasattr(e, "intervals_") for e in comp.estimators_.values())
    if out["ati_model"]:
        models["single_model"] = make_base().fit({c: ds.campaigns[c] for c in train})
    test = {k: _test_rsd(m, ds, mode) for k, m in models.items()}
    out["targets"] = {}
    for t in comp.targets_:
        est = comp.estimators_[t]
        entry = {"n_intervals": int(getattr(est, "n_intervals_", 1))}
        if hasattr(est, "intervals_"):
            entry.update(boundaries_c=[float(b) for b in est.boundaries_],
                         intervals=est.intervals_, elbow=json_safe(est.elbow_),
                         campaign_ambient_c0=est.campaign_ambient_)
        entry["test"] = {k: _sm_sd_entry(v[t]) for k, v in test.items()}
        model = entry["test"]["model"]
        entry["improvement_pct"] = {
            f"{stat}_vs_{base}": reduction_pct(entry["test"][base][key], model[key])
            for base in ("coldest", "warmest", "single_model") if base in entry["test"]
            for stat, key in (("sm", "rsd_mean"), ("sd", "rsd_sd"))}
        out["targets"][t] = entry
    return out
