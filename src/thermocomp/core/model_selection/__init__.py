"""How models are chosen and validated: information criteria, greedy search, CV splitters.

Pure core (numpy, pandas, scipy, scikit-learn): the one home of

* :mod:`.criteria` -- AIC, AICc, BIC, BICc of a least-squares fit, one floor rule;
* :mod:`.greedy` -- the split greedy / forward search on a Gram matrix;
* :mod:`.splitters` -- campaign splitters usable with ``cross_val_score``.
"""

from .criteria import CRITERIA, ic_path, information_criteria, information_criterion
from .greedy import GreedyPath, greedy_path, scaled_gram
from .splitters import (
    CV_SCHEMES,
    BlockedForward,
    CampaignHoldOut,
    ForwardChaining,
    LeaveCampaignsOut,
    LeaveOneCampaignOut,
    TrainOnEachCampaign,
    cv_scheme,
    forward_gap,
    unit_labels,
)

__all__ = ["BlockedForward", "CRITERIA", "CampaignHoldOut",
           "ForwardChaining", "GreedyPath", "LeaveCampaignsOut",
           "LeaveOneCampaignOut", "TrainOnEachCampaign", "greedy_path", "ic_path",
           "information_criteria", "information_criterion", "scaled_gram", "unit_labels",
           "cv_scheme", "forward_gap", "CV_SCHEMES"]
