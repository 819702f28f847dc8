"""Closing the loop: find what a compensation model misses, trace it to an effect, fix, prove it.

Pure core (no Hydra, MLflow or paths).  :func:`diagnose` takes a dataset and
a configured :class:`~thermocomp.core.compensator.Compensator`, cross-validates its
residual on the train campaigns, searches the candidate effects
(:mod:`.candidates`) and returns a :class:`Diagnosis` whose ``to_json`` is
``diagnosis.json`` (CLI.md).  The diagnosed model is a Compensator around
:class:`AugmentedRegressor`, which any model family can sit in.
"""

from .augmented import AugmentedRegressor
from .candidates import CONTROL, CandidateOptions
from .diagnosis import Diagnosis, TargetDiagnosis, augment, diagnose, search_train
from .features import KINDS, Effect, effect_features, first_order_lag
from .search import SearchOptions

__all__ = ["diagnose", "Diagnosis", "TargetDiagnosis", "AugmentedRegressor", "augment", "Effect",
           "effect_features", "first_order_lag", "SearchOptions", "CandidateOptions", "KINDS",
           "CONTROL", "search_train"]
