"""Model families: scikit-learn estimators mapping temperatures (and states) to thermal error.

Every estimator follows the side-input and streaming protocol of
:mod:`thermocomp.core.context`: ``fit(X, y, context=None)``, ``predict(X, context=None)``,
``stream_init(context)`` and ``stream_step(x_row, state, context)``.  The
context's ``campaign`` marks campaign boundaries (dynamics never cross them);
its ``y_measured`` switches models with an autoregressive part to one-step-ahead
prediction (``eval.mode=one_step``).  Without it they run in simulation
(free-run) mode, as on a machine.
"""

from .arx import ARX
from .arx_rf import ARXRF
from .hammerstein import Hammerstein
from .lagbank import LagBank
from .linear import MLR
from .pcr import PCR

__all__ = ["MLR", "PCR", "ARX", "ARXRF", "LagBank", "Hammerstein", "LSTM"]


def __getattr__(name):  # LSTM lazily: importing torch costs seconds the other models don't need
    if name == "LSTM":
        from .lstm import LSTM
        return LSTM
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
