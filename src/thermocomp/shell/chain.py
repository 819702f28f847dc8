"""What the ``denoise``, ``select`` and ``train`` stages compute, one function each: a stage
opens its source, calls its function and writes the result; ``run`` chains the same functions
in memory (:func:`fit_chain`), so the two paths are one.  ``train`` passes the outputs of
``denoise``/``select`` where their fingerprint matches (``stages/artifacts.py``) instead of
computing them again.
"""

from __future__ import annotations

from dataclasses import dataclass

from omegaconf import DictConfig
from sklearn.frozen import FrozenEstimator

from ..base.errors import ConfigError
from ..core.compensator import Compensator
from ..core.continuation import fit_campaigns
from ..core.denoise import fit_denoiser
from ..core.denoise.split import denoise_split
from ..core.scoring.evaluation import require_split
from ..core.select.per_target import select_on_campaigns
from .build import build
from .builders import build_compensator, build_denoiser
from .source import declared_columns, reference


@dataclass(frozen=True)
class Denoised:
    """The denoise step: the fitted denoiser (None: ``denoise=none``), the inputs it denoises,
    the campaigns denoised offline (the train split, or every campaign) and its report."""

    fitted: object | None
    inputs: list
    campaigns: dict
    report: dict


def denoise_step(cfg: DictConfig, ds, every: bool = False) -> Denoised:
    """The configured denoiser fitted on the train split of ``ds``, the train campaigns denoised
    offline; ``every``: every campaign, and the report (the ``denoise`` stage's output)."""
    ids = require_split(ds, "train")
    inputs, _ = declared_columns(cfg, ds)
    if every:
        fitted, out, report = denoise_split(build_denoiser(cfg), ds.campaigns, ids, inputs)
        return Denoised(fitted, inputs, out, report)
    fitted, out = fit_denoiser(build_denoiser(cfg), {c: ds.campaigns[c] for c in ids}, inputs)
    return Denoised(fitted, inputs, out, {})


def handed_denoised(cfg: DictConfig, ds, processed) -> Denoised:
    """The denoise step with the denoiser the ``denoise`` stage fitted (``processed``: its
    ``(dataset, fitted denoiser)``): the train campaigns of ``ds`` denoised by it, as read (the
    frames keep what the reader gave them)."""
    inputs, ids = declared_columns(cfg, ds)[0], require_split(ds, "train")
    fitted = processed[1]
    frozen = None if fitted is None else FrozenEstimator(fitted)
    return Denoised(fitted, inputs, fit_denoiser(frozen, {c: ds.campaigns[c] for c in ids}, inputs)[1],
                    {})


def select_step(cfg: DictConfig, ds, denoised: Denoised) -> tuple[dict, dict, dict]:
    """The configured selector fitted per target on the denoised train campaigns, in the
    reference frame: ``(entry per target, scores, their labels)`` (``selection.json``)."""
    selector = build(cfg.select.selector, "select.selector")
    try:
        if hasattr(selector, "check_params"):
            selector.check_params()
    except ValueError as exc:
        raise ConfigError(f"select.selector: {exc}") from exc
    ids = require_split(ds, "train")
    _, targets = declared_columns(cfg, ds)
    return select_on_campaigns(selector, {c: denoised.campaigns[c] for c in ids},
                               denoised.inputs, targets, reference(cfg), str(cfg.select.name))


def train_step(cfg: DictConfig, ds, denoised: Denoised, selection: dict) -> Compensator:
    """The configured compensator fitted on the ``denoised`` train split of ``ds`` with its
    fitted denoiser (used as fitted) and the ``selection`` (inputs per target)."""
    comp = build_compensator(cfg, ds=ds)
    den = denoised.fitted
    comp.set_params(denoiser=None if den is None else FrozenEstimator(den), selection=selection)
    # campaigns that continue one another fitted joined, as they are predicted (state carried over)
    train = fit_campaigns(ds, denoised.campaigns, require_split(ds, "train"), reference(cfg))
    return comp.fit(train, denoised=True)


def fit_chain(cfg: DictConfig, ds, denoised: Denoised | None = None,
              selection: dict | None = None) -> Compensator:
    """denoise -> select -> train on ``ds`` in memory; ``denoised``/``selection``: a step's
    result already at hand (``train``: the stages' outputs that match), not computed again."""
    denoised = denoised or denoise_step(cfg, ds)
    if selection is None:
        selection = {t: e["selected"] for t, e in select_step(cfg, ds, denoised)[0].items()}
    return train_step(cfg, ds, denoised, selection)
