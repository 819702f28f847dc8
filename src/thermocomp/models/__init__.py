"""Model families: scikit-learn estimators mapping temperatures (and states) to thermal error.

Every estimator takes ``fit(X, y, groups=None)`` and
``predict(X, groups=None, y_measured=None)``; ``groups`` marks campaign
boundaries (dynamics never cross them), ``y_measured`` switches models with an
autoregressive part to one-step-ahead prediction (``eval.mode=one_step``).
Without it they run in simulation (free-run) mode, as on a machine.
"""

from .linear import MLR

__all__ = ["MLR"]
