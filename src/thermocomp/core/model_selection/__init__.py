"""How models are chosen and validated: information criteria, greedy search, CV splitters.

Pure core (numpy, pandas, scipy, scikit-learn): the one home of

* :mod:`.criteria` -- AIC, AICc, BIC, BICc of a least-squares fit, one floor rule;
* :mod:`.greedy` -- the split greedy / forward search on a Gram matrix;
* :mod:`.splitters` -- campaign splitters usable with ``cross_val_score`` (imported at first
  use: scikit-learn costs a second that the config schema, reading :data:`CV_SCHEMES`, does not need).
"""

from .criteria import CRITERIA, ic_path, information_criteria, information_criterion
from .greedy import GreedyPath, greedy_path, scaled_gram
from .schemes import CV_SCHEMES

_SPLITTERS = ("BlockedForward", "CampaignHoldOut", "ForwardChaining", "LeaveBlockOut", "LeaveCampaignsOut",
              "LeaveOneCampaignOut", "TrainOnEachCampaign", "cv_scheme", "forward_gap", "unit_labels")

__all__ = ["CRITERIA", "GreedyPath", "greedy_path", "ic_path", "information_criteria",
           "information_criterion", "scaled_gram", "CV_SCHEMES", *_SPLITTERS]


def __getattr__(name):
    if name in _SPLITTERS:
        from . import splitters
        return getattr(splitters, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
