"""Scoring a fitted compensator on the train and test splits (pure core).

:func:`score` gives the ``targets`` part of ``metrics.json``; :func:`anova`,
:func:`mutual_prediction_report` and :func:`ati_report` the ``anova``,
``mutual_prediction`` and ``ati`` parts.  Models are built through a
``make_compensator`` callable, so this module knows no config.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from contextlib import contextmanager

import numpy as np

from ...base.errors import FallbackWarning, TooFewSamples
from ...base.jsonsafe import json_safe
from .. import continuation
from ..compensator import MODES, Compensator
from ..frame import initial_ambient
from ..io.contract import TIME, ContractError, Dataset, ambient_source
from ..io.instants import START, start_instants
from ..metrics import (
    ISO_A3,
    PERSISTENCE,
    RMS_BEFORE,
    RMSE,
    RSD,
    RSD_MEAN,
    RSD_SD,
    reduction_pct,
    rsd,
    rsd_summary,
    split_scores,
    test_block,
    validation_scores,
)
from ..timerule import median_step
from .iso10791 import a3_report
from .stats import anova_oneway, mutual_prediction

BEFORE = "before"    # the fold residuals' key of the measured error itself (no correction)


def sample_period(ds: Dataset, ids) -> float:
    """The sample period (s) of the campaigns ``ids`` (:func:`~thermocomp.core.timerule.median_step`;
    NaN without a step)."""
    return median_step([ds.campaigns[c][TIME].to_numpy(float) for c in ids]) or float("nan")


def require_split(ds: Dataset, split: str) -> list[str]:
    ids = ds.ids(split)
    if not ids:
        root = ds.meta.get("path")
        manifest = ds.meta.get("manifest", f"{root}/campaigns.csv" if root else "campaigns.csv")
        fraction = f"data.{split}_fraction=0.1 (the last share held out) or " if split != "train" else ""
        if manifest is None:      # a record or a folder of runs: no manifest to set it in
            raise ContractError(f"the dataset has no {split!r} campaign and no manifest: set "
                                f"{fraction}data.split_overrides", file=root)
        raise ContractError(f"the dataset has no {split!r} campaign (set `split` in the manifest, "
                            f"{fraction}data.split_overrides)", column="split", file=manifest)
    return ids


def score(comp: Compensator, ds: Dataset, mode: str = "simulation",
          e_p95_statistic: str = "range", e_p95_points: int | None = 200,
          iso_a3: bool = True) -> tuple[dict, dict]:
    """Per-target train/test figures in the layout of ``metrics.json`` (``targets`` key).

    The test split also gets ``iso10791_a3``, the ISO 10791-10 A.3 virtual
    test of :mod:`thermocomp.core.scoring.iso10791` (``summary`` null with a reason when no
    test campaign lasts the test's 15 h).  Beside the figures of ``mode``,
    each target gets the test figures (``rmse``, ``rsd_mean``, ``rsd_sd``) of
    the other mode (``test_one_step`` or ``test_simulation``) and of the
    persistence baseline (``persistence``: the previous measured error as the
    prediction).  A campaign that continues another one is predicted with the
    model's state carried over (:mod:`thermocomp.core.continuation`).

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
        pred, meas, series = split_residuals(comp, ds, ids, mode, carried)
        dt = sample_period(ds, ids)
        for t, (y, r) in series.items():
            out[t][split] = split_scores(y, r, dt, e_p95_statistic, e_p95_points,
                                         with_before_after=(split == "test"))
            if split == "test" and iso_a3:
                times = {c: ds.campaigns[c][TIME].to_numpy(float) for c in ids}
                out[t][split][ISO_A3] = a3_report(times, y, r)
        if split == "test":
            predictions = {c: (meas[c], pred[c]) for c in ids}
    ids = require_split(ds, "test")
    other = next(m for m in MODES if m != mode)
    baselines = {PERSISTENCE: continuation.persistence(comp, ds, ids, carried)}
    baselines[test_block(other)] = continuation.predict(comp, ds, ids, other, carried)[0]
    for key, pred in baselines.items():
        for t in comp.targets_:
            y = {c: predictions[c][0][t].to_numpy() for c in ids}
            out[t][key] = split_scores(y, {c: y[c] - pred[c][t].to_numpy() for c in ids}, 1.0,
                                       with_before_after=False)
    one_step = test_block(other) if other == "one_step" else "test"
    for t in comp.targets_:     # a reference, not a compensator: a probe must be on the machine
        out[t][PERSISTENCE]["needs_measured_error_online"] = True
    for t, rows in probe_cycles(comp).items():
        # measured now and then: "one step" is from the last probe reading, a cycle ahead
        for key in (PERSISTENCE, one_step):
            out[t][key]["ahead_of_last_measured_rows"] = rows
    return out, predictions


def probe_cycles(comp: Compensator) -> dict[str, int]:
    """``{target: rows between two measurements}`` of the targets ``comp`` was trained on
    measured now and then (``data.sparse_targets``): their one-step laws span a probe cycle."""
    laws = getattr(comp, "one_step_", None) or {}
    return {t: law.every_ for t, law in laws.items() if getattr(law, "every_", 1) > 1}


def split_residuals(comp: Compensator, ds: Dataset, ids, mode: str, carried=None
                    ) -> tuple[dict, dict, dict]:
    """``(predicted, measured, {target: (measured, residual)})`` of the campaigns ``ids``, state
    carried over where it applies; the last per target as ``{campaign: array}`` maps, what
    :func:`~thermocomp.core.metrics.split_scores` scores."""
    pred, meas = continuation.predict(comp, ds, ids, mode, carried)
    series = {}
    for t in comp.targets_:
        y = {c: meas[c][t].to_numpy() for c in ids}
        series[t] = (y, {c: y[c] - pred[c][t].to_numpy() for c in ids})
    return pred, meas, series


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


def _test_rsd(comp: Compensator, ds: Dataset, mode: str, predictions: dict | None = None
              ) -> dict[str, dict[str, float]]:
    """Per target, the Rsd of each test campaign (``predictions``: :func:`score`'s
    ``{campaign: (measured, predicted)}`` of ``comp`` in ``mode``, else predicted here)."""
    ids = require_split(ds, "test")
    if predictions is None:
        pred, meas = continuation.predict(comp, ds, ids, mode)
    else:
        meas, pred = ({c: predictions[c][k] for c in ids} for k in (0, 1))
    return {t: {c: rsd(meas[c][t].to_numpy() - pred[c][t].to_numpy()) for c in ids}
            for t in comp.targets_}


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


MUTUAL_MAX_MODELS = 24  # eval.mutual_prediction_max_models: the default data's 24 campaigns all get one


def mutual_prediction_report(make_compensator: Callable[[], Compensator], ds: Dataset,
                             mode: str = "simulation", max_models: int | None = None) -> dict:
    """Mutual prediction matrices over all campaigns, ordered by initial ambient.

    ``{target: {"campaigns": [...], "ambient_c0": [...], "trained_on": [...], "rsd": [[...]],
    "max_models": ...}}``: row ``i`` trained on campaign ``trained_on[i]`` alone, column ``j``
    predicted (paper 003, Fig. 6).  ``max_models`` (None: no limit): at most that many
    single-campaign models, on :func:`spread_campaigns` of the ambient order; every campaign
    is still predicted.
    """
    amb = ambient_by_campaign(ds)
    ids = sorted(ds.ids(), key=lambda c: (np.nan_to_num(amb[c], nan=np.inf), c))
    rows = spread_campaigns(ids, max_models)
    mats = mutual_prediction({c: ds.campaigns[c] for c in ids}, make_compensator, mode, rows)
    return {t: {"campaigns": ids, "ambient_c0": json_safe([amb[c] for c in ids]),
                "trained_on": rows, RSD: json_safe(m.to_numpy()), "max_models": max_models}
            for t, m in mats.items()}


def spread_campaigns(ids: list, at_most: int | None) -> list:
    """``ids`` when there are no more than ``at_most`` (or None), else ``at_most`` of them evenly
    spread over their order, the first and the last included: by position alone (no score)."""
    if at_most is None or len(ids) <= at_most:
        return list(ids)
    # the step is >= 1 when at_most <= len(ids): the rounded positions are distinct
    return [ids[i] for i in np.round(np.linspace(0, len(ids) - 1, at_most)).astype(int)]


def ati_report(comp: Compensator, ds: Dataset, make_base: Callable[[], Compensator],
               mode: str = "simulation", name: str = "none", predictions: dict | None = None
               ) -> dict:
    """ATI intervals, elbow and the paper-003 comparison on the test split.

    Per target: the fitted intervals and elbow curve (when the model is an ATI
    model), and the test SM/SD of the evaluated model next to one model trained
    on the coldest train campaign alone and one on the warmest (paper 003,
    Sect. 4.3), plus -- for an ATI model -- one model on all train campaigns.
    ``predictions``: :func:`score`'s test predictions of ``comp`` in ``mode`` when the caller
    has them (else predicted here: model=auto's blend over the joined record again).
    """
    train = require_split(ds, "train")
    amb = ambient_by_campaign(ds, train)
    out: dict = {"name": name,      # T_amb (sensors) or ambient_c (the manifest), per campaign
                 "ambient_source": sorted({str(ambient_source(ds.campaigns[c])) for c in train})}
    models = {"model": comp}
    if all(np.isfinite(v) for v in amb.values()):
        cold, warm = min(amb, key=amb.get), max(amb, key=amb.get)
        out["baseline_campaigns"] = {"coldest": {"campaign": cold, "ambient_c0": amb[cold]},
                                     "warmest": {"campaign": warm, "ambient_c0": amb[warm]}}
        # one campaign per model by design (as mutual prediction's; a file, not the run of files
        # it may continue: the paper's baseline is one campaign's fit): a member's fallback on one
        # campaign (model=auto blending ATI: "1 training campaign(s)") is no news of the run's
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", FallbackWarning)
            models["coldest"] = make_base().fit({cold: ds.campaigns[cold]})
            # one train campaign (a record cut in two) is both: fitted once (model=auto: every
            # candidate again, 13 min of a 41 min run on large_mill_week)
            models["warmest"] = (models["coldest"] if warm == cold
                                 else make_base().fit({warm: ds.campaigns[warm]}))
    else:
        out["reason"] = ("no initial ambient temperature (T_amb*, or the manifest's ambient_c) "
                         "in the train campaigns: no cold/warm baselines")
    out["ati_model"] = any(hasattr(e, "intervals_") for e in comp.estimators_.values())
    if out["ati_model"]:
        models["single_model"] = continuation.fit_joined(make_base(), ds, train)
    test = {k: _test_rsd(m, ds, mode, predictions if m is comp else None)
            for k, m in models.items()}
    out["targets"] = {}
    for t in comp.targets_:
        est = comp.estimators_[t]
        entry = {"n_intervals": int(getattr(est, "n_intervals_", 1))}
        if hasattr(est, "intervals_"):
            entry.update(boundaries_c=[float(b) for b in est.boundaries_],
                         intervals=est.intervals_, elbow=json_safe(est.elbow_),
                         campaign_ambient_c0=est.campaign_ambient_)
        entry["test"] = {k: rsd_summary(v[t], skip_nan=False) for k, v in test.items()}
        model = entry["test"]["model"]
        entry["improvement_pct"] = {
            f"{stat}_vs_{base}": reduction_pct(entry["test"][base][key], model[key])
            for base in ("coldest", "warmest", "single_model") if base in entry["test"]
            for stat, key in (("sm", RSD_MEAN), ("sd", RSD_SD))}
        out["targets"][t] = entry
    return out


# -- validation: the score that chooses (compare, promote); the test split only reports --------
VAL_FOLDS = 5
MIN_TRAIN_FRACTION = 0.5   # forward chaining validates a single record on its second half


SCHEMES = ("forward", "interleaved")


def holdout_scheme(ds: Dataset) -> str:
    """How the test split is held out of the campaigns, so that validation does the same:
    ``'forward'`` when every test campaign comes after every train campaign (by the manifest's
    ``start`` when it has one for each, else in the manifest's order; one record cut in time
    too), else ``'interleaved'`` (test campaigns among the train ones, e.g. every third by
    date).  Only the split's layout is read, never a test value."""
    order = ds.ids()
    if START in ds.manifest.columns:
        starts = start_instants(ds.manifest[START])   # (with and without an offset: in UTC)
        if starts.notna().all():
            order = list(starts.sort_values(kind="stable").index)
    train, test = set(ds.ids("train")), set(ds.ids("test"))
    where = {c: i for i, c in enumerate(order)}
    if len(train) < 2 or not test or min(where[c] for c in test) > max(where[c] for c in train):
        return "forward"
    return "interleaved"


def validation_report(make_compensator: Callable[[], Compensator], ds: Dataset,
                      mode: str = "simulation", fitted: Compensator | None = None,
                      n_folds: int = VAL_FOLDS, scheme: str = "auto") -> dict:
    r"""Per-target validation figures, computed without the test split.

    * ``val`` campaigns in the manifest: the model fitted on the train split
      (``fitted``, else a new one) predicts them (``method = "val split"``).
    * otherwise cross-validation on the train campaigns, holding them out as the
      test split is held out (``scheme``; ``auto``: :func:`holdout_scheme`):
      several campaigns, ``interleaved`` ->
      :class:`~thermocomp.core.model_selection.LeaveCampaignsOut` with
      ``min(n_folds, n_campaigns)`` folds, ``forward`` ->
      :class:`~thermocomp.core.model_selection.BlockedForward` (the later half of the
      campaigns in blocks, each predicted by a fit on the campaigns before it);
      a single long record ->
      :class:`~thermocomp.core.model_selection.ForwardChaining` on its second half
      (expanding window, a gap of half a validation block).  Each fold refits
      the whole configured compensator (``make_compensator()``: selection,
      denoiser, ATI elbow, everything) on its training rows and predicts its
      held-out rows in ``mode`` (simulation: inputs only).  A forward-chaining
      fold predicts the record from its start, so the model's state carries
      over the gap as on the machine, and is scored on the held-out block.

    With ``R_u`` the residual of held-out unit ``u`` (a campaign, or a block of
    the record) and :math:`R_{sd}` of paper 003 (Eq. 17):

    .. math:: \mathrm{rmse} = \sqrt{\frac{\sum_u \sum_j R_{u,j}^2}{\sum_u n_u}},\quad
              \mathrm{rsd\_mean},\ \mathrm{rsd\_sd} = \mathrm{SM}, \mathrm{SD}
              \text{ of } \{R_{sd}(R_u)\}_u

    Returns
    -------
    dict target -> ``{"rmse", "rsd_mean", "rsd_sd", "method", "n_folds", "per_unit"}``
    """
    return validation_reports(make_compensator, ds, (mode,), fitted, n_folds, scheme)[mode]


def validation_reports(make_compensator: Callable[[], Compensator], ds: Dataset,
                       modes=("simulation",), fitted: Compensator | None = None,
                       n_folds: int = VAL_FOLDS, scheme: str = "auto") -> dict:
    """:func:`validation_report` in each of ``modes`` from the same fits (a fold's model is
    fitted once and predicts in every mode): ``{mode: {target: entry}}``."""
    modes = tuple(dict.fromkeys(modes))
    val_ids = ds.ids("val")
    train = require_split(ds, "train")
    if val_ids:
        comp = fitted if fitted is not None else continuation.fit_joined(make_compensator(), ds, train)
        carried = continuation.carry_over(comp, ds)
        out = {}
        for mode in modes:
            # a val file that continues others predicted with their state, as run's test split
            pred, meas = continuation.predict(comp, ds, val_ids, mode, carried)
            residual = {t: {c: meas[c][t].to_numpy() - pred[c][t].to_numpy() for c in val_ids}
                        for t in comp.targets_}
            before = {t: {c: meas[c][t].to_numpy() for c in val_ids} for t in comp.targets_}
            out[mode] = _validation_entries(residual, "val split", 1, before)
        return out
    template = make_compensator()
    # the folds of the train split in the frame the run fits and predicts it in: a run of files
    # that continue one another is one campaign (one fold unit; alone: forward chaining over it,
    # every fold's prediction carried from the record's start, as its fit's)
    camps = continuation.fit_campaigns(ds, ds.campaigns, train,
                                       getattr(template, "reference", "first_sample"))
    if scheme not in ("auto", *SCHEMES):
        raise ValueError(f"scheme must be auto or one of {SCHEMES}, got {scheme!r}")
    if len(camps) >= 2 and (holdout_scheme(ds) if scheme == "auto" else scheme) == "forward":
        folds = _campaign_folds(camps, n_folds, blocked=True)
        method = f"blocked forward ({len(folds)} folds)"
    elif len(camps) >= 2:
        folds = _campaign_folds(camps, n_folds)
        method = f"leave-campaigns-out ({len(folds)} folds)"
    else:
        folds = _forward_folds(camps, n_folds)
        method = "forward chaining"
    residuals = _stored_residuals(fitted, template, camps, folds, modes)
    said = method
    if residuals is not None:
        said += "; model=auto: its members' out-of-fold predictions, weights fixed, not refitted"
    elif template.denoiser is None:
        residuals = _fold_residuals_stacked(template, camps, folds, modes)
    else:
        residuals = _fold_residuals(template, camps, folds, modes)
    out = {}
    for mode in modes:
        out[mode] = _validation_entries(residuals[mode], said, len(folds), residuals[BEFORE])
        if method == "forward chaining":
            for entry in out[mode].values():
                entry["gap_samples"] = folds[0][3] if folds else 0
    return out


def _campaign_folds(camps: dict, n_folds: int, blocked: bool = False) -> list[tuple]:
    """``(fit rows, predict rows, {unit: score rows}, gap)`` as ``{campaign: row count}`` maps:
    leave-campaigns-out, or (``blocked``) :class:`~thermocomp.core.model_selection.BlockedForward`,
    the later campaigns in blocks, each fold fitted on the campaigns before its block."""
    from ..model_selection import BlockedForward, LeaveCampaignsOut

    ids = list(camps)
    lengths = {c: len(camps[c]) for c in ids}
    if blocked:
        splits = [(np.flatnonzero(fit), np.flatnonzero(held)) for fit, _, held in
                  BlockedForward(n_folds, MIN_TRAIN_FRACTION).folds(np.array(ids, dtype=object))]
    else:
        splits = LeaveCampaignsOut(n_folds=n_folds).split(ids, groups=ids)
    folds = []
    for fit, held in splits:
        fit_ids, held_ids = [ids[i] for i in fit], [ids[i] for i in held]
        folds.append(({c: lengths[c] for c in fit_ids}, {c: lengths[c] for c in held_ids},
                      {c: (c, 0, lengths[c]) for c in held_ids}, 0))
    return folds


def _forward_folds(camps: dict, n_folds: int) -> list[tuple]:
    """Forward-chaining folds of the single record: fit on a prefix, predict up to the block's end."""
    from ..model_selection import ForwardChaining
    from ..model_selection.splitters import forward_block

    (cid, df), = camps.items()
    n = len(df)
    k = max(1, min(int(n_folds), n - 1))
    gap = forward_block(n, k, MIN_TRAIN_FRACTION) // 2
    folds = []
    for j, (fit, held) in enumerate(ForwardChaining(k, gap=gap, min_train_fraction=MIN_TRAIN_FRACTION)
                                    .split(np.zeros((n, 1)))):
        a, b = int(held[0]), int(held[-1]) + 1
        folds.append(({cid: int(fit[-1]) + 1}, {cid: b}, {f"{cid}#{j + 1}": (cid, a, b)}, gap))
    return folds


def _fold_residuals_stacked(template: Compensator, camps: dict, folds, modes) -> dict:
    """``{mode: residuals}`` of every fold from one stack of the train campaigns (no denoiser
    to refit)."""
    from sklearn.base import clone

    from ..frame import resolve_columns, stack

    columns = list(dict.fromkeys(c for df in camps.values() for c in df.columns))
    inputs, targets = resolve_columns(columns, template.inputs, template.targets)
    m = stack(camps, inputs, targets, template.reference)
    start = dict(zip(camps, np.cumsum([0] + [len(df) for df in camps.values()])))
    residual: dict = {mode: {t: {} for t in targets} for mode in (*modes, BEFORE)}
    for fit_rows, pred_rows, units, _ in folds:
        comp = clone(template)
        comp.inputs_, comp.targets_, comp.denoiser_ = inputs, targets, None
        with _fold_named(fit_rows):
            comp.fit_stacked(_rows(m, _mask(start, fit_rows, len(m.X))))
        sub = _rows(m, _mask(start, pred_rows, len(m.X)))
        order = [c for c in camps if c in pred_rows]      # the stack's order
        offsets = dict(zip(order, np.cumsum([0] + [pred_rows[c] for c in order])))
        preds = {mode: comp.predict_stacked(sub, mode) for mode in modes}
        # the label as every scorer reads it (Compensator.measured): a late first probe's
        # completed by the fold model's simulation there (else each held-out campaign's residual
        # carried the unmeasured E(m) - E(0): hobbing bench E_dZ validation 8.85 um, test 0.56)
        label = comp.scored_label(sub.Y.to_numpy(float), sub.groups, preds.get("simulation")
                                  if "simulation" in preds else lambda: comp.predict_stacked(sub))
        for mode in (*modes, BEFORE):
            pred = preds.get(mode, np.zeros_like(label))        # BEFORE: no correction
            for unit, (c, a, b) in units.items():
                rows = slice(offsets[c] + a, offsets[c] + b)
                for k, t in enumerate(targets):
                    residual[mode][t][unit] = label[rows, k] - pred[rows, k]
    return residual


def _stored_residuals(fitted: Compensator | None, template: Compensator, camps: dict, folds,
                      modes) -> dict | None:
    """``{mode: residuals}`` from ``fitted``'s own out-of-fold free-run predictions (model=auto:
    ``out_of_fold()`` of every target's estimator) where a refit per fold would repeat them: the
    same folds of the same rows, simulation only, nothing else fitted per fold (no denoiser, no
    selection, no label completed by the fold model, :mod:`thermocomp.core.first_probe`).  A
    target measured now and then is scored by both on its measured rows only: the stored folds
    hold those, a refit's residual is NaN on the others.  None otherwise: the folds are refitted.
    """
    from ..first_probe import late_starts
    from ..frame import stack
    from ..select import AllInputs

    if (fitted is None or set(modes) != {"simulation"} or template.denoiser is not None
            or not isinstance(template.selector, (AllInputs, type(None)))
            or template.selection is not None
            or any(fitted.selected_[t] != fitted.inputs_ for t in fitted.targets_)):
        return None
    stored = {t: getattr(e, "out_of_fold", lambda: None)()
              for t, e in getattr(fitted, "estimators_", {}).items()}
    if not stored or any(s is None for s in stored.values()):
        return None
    # the labels a refit would score, in the frame it reads them (a late first probe's would be
    # completed by each fold model's own simulation: refitted)
    labels = stack(camps, [], list(stored), template.reference)
    Y = labels.Y.to_numpy(float)
    if template.reference == "first_sample" and late_starts(Y, labels.groups):
        return None
    lengths = [len(df) for df in camps.values()]
    start, n = dict(zip(camps, np.cumsum([0] + lengths))), sum(lengths)
    wanted = [(np.flatnonzero(_mask(start, fit_rows, n)),
               np.sort(np.concatenate([np.arange(start[c] + a, start[c] + b) for c, a, b in units.values()])))
              for fit_rows, _, units, _ in folds]
    residual: dict = {"simulation": {}, BEFORE: {}}
    for k, (t, (rows, theirs, y, pred)) in enumerate(stored.items()):
        measured = np.isfinite(Y[:, k])
        mine = [(fit, score[measured[score]]) for fit, score in wanted]
        if rows != n or len(theirs) != len(mine) or not all(
                np.array_equal(a, b) for own, other in zip(mine, theirs) for a, b in zip(own, other)):
            return None
        scored = np.concatenate([score for _, score in theirs])
        if not np.array_equal(y, Y[scored, k]):     # fitted on other labels than these
            return None
        for mode, error in (("simulation", y - pred), (BEFORE, y)):
            rows_of = np.full(n, np.nan)
            rows_of[scored] = error
            residual[mode][t] = {unit: rows_of[start[c] + a:start[c] + b]
                                 for *_, units, _ in folds for unit, (c, a, b) in units.items()}
    return residual


def _fold_residuals(template: Compensator, camps: dict, folds, modes) -> dict:
    """``{mode: residuals}`` of every fold, refitting the whole compensator (denoiser included)
    on campaigns."""
    from sklearn.base import clone

    residual: dict = {mode: {} for mode in (*modes, BEFORE)}
    for fit_rows, pred_rows, units, _ in folds:
        # (a run of files joined, :func:`continuation.fit_campaigns`, is denoised here as one
        # campaign, not file by file as run's final fit: a fold ends inside the run)
        with _fold_named(fit_rows):
            comp = clone(template).fit({c: camps[c].iloc[:n] for c, n in fit_rows.items()})
        part = {c: camps[c].iloc[:n] for c, n in pred_rows.items()}
        preds = {mode: comp.predict(part, mode=mode) for mode in modes}
        meas = comp.measured(part, predicted=preds.get("simulation"))
        for mode in (*modes, BEFORE):
            for unit, (c, a, b) in units.items():
                for t in comp.targets_:
                    pred = 0.0 if mode == BEFORE else preds[mode][c][t].to_numpy()[a:b]
                    residual[mode].setdefault(t, {})[unit] = meas[c][t].to_numpy()[a:b] - pred
    return residual


@contextmanager
def _fold_named(fit_rows: dict):
    """A fold too short for the model's fit refused naming the fold's rows (a short record's
    first forward fold fits a few rows: the model's own message alone read as a bug)."""
    try:
        yield
    except TooFewSamples as error:
        rows = ", ".join(f"the first {n} row{'s' * (n != 1)} of {c}" for c, n in fit_rows.items())
        raise TooFewSamples(f"validation: a fold fits on {rows}, too few: {error.reason}; give "
                            "the train part more rows or set eval.validation=false") from None


def _mask(start: dict, rows: dict, n: int) -> np.ndarray:
    """Rows of the stack: the first ``rows[c]`` rows of each campaign ``c``."""
    mask = np.zeros(n, dtype=bool)
    for c, k in rows.items():
        mask[start[c]:start[c] + k] = True
    return mask


def _rows(m, mask: np.ndarray):
    """The stacked matrices restricted to ``mask`` (rows stay in campaign, then time order)."""
    from ..frame import Matrices

    context = None if m.context is None else m.context[mask].reset_index(drop=True)
    return Matrices(m.X[mask].reset_index(drop=True), m.Y[mask].reset_index(drop=True),
                    m.groups[mask], m.time[mask], context)


def _validation_entries(residual: dict, method: str, n_folds: int, before: dict) -> dict:
    """Each target's validation figures, with ``rms_before``: the measured error's RMS on the
    rows scored (``before``: no correction), what a compensator must beat to be worth deploying."""
    out = {}
    for t, per in residual.items():
        out[t] = validation_scores(per, method, n_folds)
        out[t][RMS_BEFORE] = validation_scores(before[t], method, n_folds)[RMSE]
    return out
