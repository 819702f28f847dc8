"""``model=auto`` in the stages: its candidates built from their own configs, its table.

A candidate is named by its family's config (``conf/model/<name>.yaml``), so a new
family becomes a candidate by a config edit (``model.candidates=[...]``);
``ati`` / ``ati+<family>`` is the ATI wrapper (``conf/ati/cmeans.yaml``) of MLR /
that family.
"""

from __future__ import annotations

from omegaconf import DictConfig

from ...core.models.auto import BASELINE
from ..config.candidates import build_candidates, is_auto  # noqa: F401  (re-exported)


def auto_scheme(cfg: DictConfig, ds) -> dict:
    """``{"scheme": ...}``: validate as the test split of ``ds`` is held out, unless
    ``model.estimator.scheme`` names one (``{}`` without a dataset)."""
    if ds is None or cfg.model.estimator.get("scheme", "auto") != "auto":
        return {}
    from ...core.scoring.evaluation import holdout_scheme

    return {"scheme": holdout_scheme(ds)}


def val_split_scores(comp, ds) -> dict:
    """``{target: {candidate: free-run RMSE on the val split}}`` of a model=auto compensator's
    candidates (and MLR, persistence), each fitted on the train split as the run's validation
    scores a val split (:func:`~thermocomp.core.scoring.evaluation.validation_report`); None where a
    candidate cannot fit.  The test split is not read."""
    import numpy as np
    from sklearn.base import clone

    from ...core.metrics import PERSISTENCE, RMSE, rmse
    from ...core.models import MLR
    from ...core.models.one_step import persistence
    from ...core.scoring.evaluation import validation_report

    candidates = {**comp.estimator.candidates}
    candidates.setdefault(BASELINE, MLR())
    scores: dict = {}
    fitted = None     # any candidate fitted on the train split: its frame gives the measured errors
    for name, candidate in candidates.items():
        one = clone(comp).set_params(estimator=clone(candidate))
        try:
            report = validation_report(lambda one=one: one, ds, "simulation")   # fits `one`
        except (ValueError, ArithmeticError, np.linalg.LinAlgError):
            scores.setdefault(None, {})[name] = None
            continue
        fitted = one
        for t, entry in report.items():
            scores.setdefault(t, {})[name] = entry[RMSE]
    failed = scores.pop(None, {})
    val = {c: ds.campaigns[c] for c in ds.ids("val")}
    measured = fitted.measured(val) if fitted is not None else {}
    for t in scores:
        scores[t].update(failed)
        y = [measured[c][t].to_numpy(float) for c in val]
        scores[t][PERSISTENCE] = rmse(np.concatenate([v - persistence(v) for v in y]))
    return scores


def add_choices(comp, targets: dict) -> dict:
    """``targets[t]["auto"]``: each target's choice of a model=auto compensator, as
    ``metrics.json`` holds it (run's and each fleet group's); any other leaves ``targets`` as is."""
    for t, est in getattr(comp, "estimators_", {}).items():
        if hasattr(est, "family_"):
            targets[t]["auto"] = est.report()
    return targets


def as_chosen(template, fitted):
    """``template`` (an unfitted compensator) fitting, per target, the family ``fitted`` (a
    model=auto compensator) chose: what its validation refits (the choice itself is not
    re-validated: candidates x folds² fits).  Any other ``template`` as it is."""
    chosen = {t: getattr(est, "chosen_", getattr(est, "family_", None))
              for t, est in getattr(fitted, "estimators_", {}).items()}
    if not chosen or None in chosen.values() or "chosen" not in template.estimator.get_params(deep=False):
        return template
    return template.set_params(estimator__chosen=chosen)
