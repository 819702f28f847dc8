"""Model families: scikit-learn estimators mapping temperatures (and states) to thermal error.

Every estimator takes ``fit(X, y, groups=None)`` and
``predict(X, groups=None, y_measured=None)``; ``groups`` marks campaign
boundaries (dynamics never cross them), ``y_measured`` switches models with an
autoregressive part to one-step-ahead prediction (``eval.mode=one_step``).
Without it they run in simulation (free-run) mode, as on a machine.
"""

from .arx import ARX
from .arx_rf import ARXRF
from .linear import MLR
from .pcr import PCR

__all__ = ["MLR", "PCR", "ARX", "ARXRF", "LSTM"]


def __getattr__(name):  # LSTM lazily: importing torch costs seconds the other models don't need
    if name == "LSTM":
        from .lstm import LSTM
        return LSTM
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
