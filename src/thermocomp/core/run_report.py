"""A run's report: the numbers of ``metrics.json`` and the figures ``plots`` asks for.

What ``evaluate`` and ``run`` (and each fleet group) compute once a compensator is fitted: the
per-target scores, the validation compare and promote choose by (never the test split), ANOVA,
the ATI baselines and mutual prediction.  Figures are queued as soon as their numbers exist and
drawn by worker processes while the next numbers are computed.  Everything is written into a
staging folder (``metrics.json`` and ``headline/`` last); the shell moves it in.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import partial

from sklearn.base import clone

from ..base.files import atomic_write_text
from ..base.log import Clock, logger, say
from .compensator import Compensator, with_chosen_hyperparameters
from .continuation import carry_over
from .figures import run_figures as fig
from .metrics import E_P95, ISO_A3, VALIDATION, validation_block
from .scoring.evaluation import (
    MUTUAL_MAX_MODELS,
    VAL_FOLDS,
    ambient_by_campaign,
    anova,
    ati_report,
    mutual_prediction_report,
    predict_split,
    score,
    validation_reports,
)
from .scoring.headline import HEADLINE, write_headline
from .scoring.leaderboard import DEPLOYED_MODE
from .scoring.results import EvaluationResult
from .shared_fits import shared_fits


@dataclass(frozen=True)
class ReportSettings:
    """What a report computes and draws: the ``eval`` group, ``plots`` and the names it records."""

    model: str
    select: str
    ati: str = "none"
    denoise: str = "none"
    plots: str = "none"
    mode: str = "simulation"
    e_p95_statistic: str = "range"
    e_p95_max_points: int | None = 200
    iso_a3: bool = True
    validation: bool = True
    validation_folds: int = VAL_FOLDS
    validation_scheme: str = "auto"
    anova_alpha: float = 0.001
    ati_baselines: bool = True
    mutual_prediction: bool = True
    mutual_prediction_max_models: int | None = MUTUAL_MAX_MODELS

    @classmethod
    def from_eval(cls, ev: Mapping, **names) -> ReportSettings:
        """From the ``eval`` group (a mapping; absent keys keep their defaults) and ``names``
        (``model``, ``select``, ``ati``, ``denoise``, ``plots``)."""
        keys = ("mode", "validation", "validation_folds", "validation_scheme", "anova_alpha",
                "ati_baselines", "mutual_prediction", "mutual_prediction_max_models")
        e_p95 = ev.get(E_P95) or {}     # eval.e_p95: the settings of that figure
        given = {"e_p95_statistic": e_p95.get("statistic"),
                 "e_p95_max_points": e_p95.get("max_points", 200), "iso_a3": ev.get(ISO_A3),
                 **{k: ev.get(k) for k in keys}}
        nullable = ("e_p95_max_points", "mutual_prediction_max_models")  # None: no limit
        return cls(**{k: v for k, v in given.items() if v is not None or k in nullable}, **names)


@dataclass(frozen=True)
class Refits:
    """The unfitted compensators a report fits again: ``template`` (each validation fold) and
    ``single`` (the model without its ATI wrapper, each target's family as model=auto chose it:
    the ATI baselines and mutual prediction's single-campaign models)."""

    template: Compensator
    single: Compensator


def report_run(comp: Compensator, ds, s: ReportSettings, refits: Refits, stage, clock: Clock,
               extra: dict | None = None, choices: Callable | None = None) -> dict:
    """The metrics of ``comp`` fitted on ``ds``, written with the figures into ``stage``
    (``choices(comp, targets)``: what a model=auto compensator chose, into ``targets``)."""
    with fig.plots_folder(stage, s.plots) as (draw, folder):
        targets, predictions = score(comp, ds, s.mode, s.e_p95_statistic, s.e_p95_max_points,
                                     iso_a3=s.iso_a3)
        clock.lap("score")
        if choices is not None:
            choices(comp, targets)
        if s.validation:
            _add_validation(s, comp, ds, targets, refits.template)
            clock.lap("validation")
        metrics = {"model": s.model, "mode": s.mode, "targets": targets,
                   "select": s.select, "denoise": s.denoise, "dataset": ds.name,
                   "inputs": {t: comp.selected_[t] for t in comp.targets_},
                   "reference": comp.reference, "carry_over": carry_over(comp, ds)}
        metrics.update(extra or {})
        if s.plots != "none":
            fig.e_p95_figures(draw, folder, targets)
        if s.plots in ("test", "all"):
            fig.campaign_figures(draw, folder, comp, ds, predictions)
        if s.plots == "all":
            fig.campaign_figures(draw, folder, comp, ds, predict_split(comp, ds, "train", s.mode))
        clock.lap("figures")
        _model_reports(s, comp, ds, predictions, metrics, refits, (draw, folder), clock)
        result = EvaluationResult(metrics)
        atomic_write_text(stage / "metrics.json", result.to_json())
        write_headline(stage / HEADLINE, result.headline("dvc"))  # for `dvc metrics show`
        clock.lap("write")
    clock.lap("figures")  # drawing still under way once every number is written
    return metrics


def _model_reports(s: ReportSettings, comp: Compensator, ds, predictions: dict, metrics: dict,
                   refits: Refits, figures: tuple, clock: Clock) -> None:
    """ANOVA, the ATI baselines and mutual prediction into ``metrics`` (and their figures)."""
    metrics["anova"] = anova(comp, ds, float(s.anova_alpha), predictions)
    clock.lap("anova")
    with shared_fits():   # an ATI baseline's campaign is one of mutual prediction's: fitted once
        _single_campaign_reports(s, comp, ds, predictions, metrics, refits, figures, clock)


def _single_campaign_reports(s: ReportSettings, comp: Compensator, ds, predictions: dict,
                             metrics: dict, refits: Refits, figures: tuple, clock: Clock) -> None:
    """The ATI baselines and mutual prediction (models of single campaigns) into ``metrics``."""
    if s.ati_baselines:
        say("ATI report: cold/warm single-campaign baselines")
        # model=auto: each target's chosen family on the coldest / warmest campaign, not the
        # whole choice again on one campaign (93 s of a 125 s run on a lab's 4 runs)
        metrics["ati"] = ati_report(comp, ds, partial(clone, refits.single), s.mode, s.ati,
                                    predictions)
        clock.lap("ati")
    if s.plots != "none":
        fig.rsd_figures(*figures, metrics, ambient_by_campaign(ds, list(predictions)))
        clock.lap("figures")
    if s.mutual_prediction:
        n, cap = len(ds.ids()), s.mutual_prediction_max_models
        say(f"mutual prediction: {n} single-campaign models" if cap is None or n <= cap else
            f"mutual prediction: {cap} single-campaign models of {n} campaigns "
            f"(eval.mutual_prediction_max_models={cap}: on campaigns evenly spread over the "
            "ambient order; every campaign predicted)")
        # its single-campaign models keep the hyper-parameters the model chose on all train
        # campaigns: one CV per campaign cost 43 x 43 lag banks on a lathe record (model=auto:
        # each target's chosen family, not the whole choice again per campaign)
        make_single = partial(clone, with_chosen_hyperparameters(clone(refits.single), comp))
        metrics["mutual_prediction"] = mutual_prediction_report(make_single, ds, s.mode, cap)
        clock.lap("mutual_prediction")
        if s.plots in ("test", "all"):
            fig.mutual_figures(*figures, metrics["mutual_prediction"])
            clock.lap("figures")


def _add_validation(s: ReportSettings, comp: Compensator, ds, targets: dict, template) -> None:
    """``targets[t]["validation"]``: the score compare and promote choose by (never the test
    split).  ``template`` (the configured compensator, not the fitted one: its selection or
    denoiser may have been fitted on all train campaigns) is refitted per fold."""
    say("validation: " + ("the val split" if ds.ids("val") else "cross-validation on the train split"))
    asked, mode = int(s.validation_folds), str(s.mode)
    # the deployed mode too: compare and promote choose by it, whatever eval.mode scored the run
    both = validation_reports(partial(clone, template), ds, (mode, DEPLOYED_MODE), fitted=comp,
                              n_folds=asked, scheme=s.validation_scheme)
    val = both[mode]
    used = next(iter(val.values()), {}).get("n_folds", asked)
    if asked != VAL_FOLDS and used != asked:  # the default is clamped quietly: it is not a choice
        logger.warning("eval.validation_folds=%d: %d fold(s), %s", asked, used,
                       next(iter(val.values()))["method"])
    for t, entry in val.items():
        targets[t][VALIDATION] = entry
        if mode != DEPLOYED_MODE:
            targets[t][validation_block(DEPLOYED_MODE)] = both[DEPLOYED_MODE][t]
