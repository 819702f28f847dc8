"""How models are chosen and validated: information criteria, greedy search, CV splitters.

Pure core (numpy, pandas, scipy, scikit-learn): the one home of

* :mod:`.criteria` -- AIC, AICc, BIC, BICc of a least-squares fit, one floor rule;
* :mod:`.greedy` -- the split greedy / forward search on a Gram matrix;
"""

from .criteria import CRITERIA, ic_path, information_criteria, information_criterion
from .greedy import GreedyPath, greedy_path, scaled_gram

__all__ = ["CRITERIA", "GreedyPath", "greedy_path", "ic_path", "information_criteria",
           "information_criterion", "scaled_gram"]
