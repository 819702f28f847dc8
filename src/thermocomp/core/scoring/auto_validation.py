"""``model=auto`` scored on a val split: each candidate fitted on the train split and scored in
free run on the val campaigns, as the run's validation scores a val split."""

from __future__ import annotations

import numpy as np
from sklearn.base import clone

from .. import continuation
from ..metrics import PERSISTENCE, RMS_BEFORE, RMSE, rmse
from ..models import MLR
from ..models.auto import BASELINE, NONE
from .evaluation import validation_report


def val_split_scores(comp, ds) -> dict:
    """``{target: {candidate: free-run RMSE on the val split}}`` of a model=auto compensator's
    candidates (and MLR, persistence, no correction: ``none``), each fitted on the train split
    as the run's validation scores a val split (:func:`~.evaluation.validation_report`); where a
    candidate cannot fit, the reason (a str, as the folds' path gives it).  The test split is not
    read."""
    candidates = {**comp.estimator.candidates}
    candidates.setdefault(BASELINE, MLR())
    scores: dict = {}
    fitted = None     # any candidate fitted on the train split: its frame gives the measured errors
    for name, candidate in candidates.items():
        one = clone(comp).set_params(estimator=clone(candidate))
        try:
            report = validation_report(lambda one=one: one, ds, "simulation")   # fits `one`
        except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
            scores.setdefault(None, {})[name] = f"cannot fit: {' '.join(str(exc).split())}"
            continue
        fitted = one
        for t, entry in report.items():
            scores.setdefault(t, {})[name] = entry[RMSE]
            scores[t][NONE] = entry[RMS_BEFORE]     # the same val rows for every candidate
    failed = scores.pop(None, {})
    val = ds.ids("val")
    measured = fitted.measured({c: ds.campaigns[c] for c in val}) if fitted is not None else {}
    # a val file that continues others starts from their last measured error, as the test's
    previous = continuation.persistence(fitted, ds, val) if fitted is not None else {}
    for t in scores:
        scores[t].update(failed)
        scores[t][PERSISTENCE] = rmse(np.concatenate(
            [measured[c][t].to_numpy(float) - previous[c][t].to_numpy(float) for c in val]))
    return scores
