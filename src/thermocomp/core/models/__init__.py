"""Model families: scikit-learn estimators mapping temperatures (and states) to thermal error.

Every estimator follows the side-input and streaming protocol of
:mod:`thermocomp.core.context`: ``fit(X, y, context=None)``, ``predict(X, context=None)``,
``stream_init(context)`` and ``stream_step(x_row, state, context)``.  The
context's ``campaign`` marks campaign boundaries (dynamics never cross them);
its ``y_measured`` switches models with an autoregressive part to one-step-ahead
prediction (``eval.mode=one_step``).  Without it they run in simulation
(free-run) mode, as on a machine.
"""

from importlib import import_module

# family -> its module, imported on first use: a process pays only for the families it builds
# (arx_rf's forest loads sklearn.ensemble, arx SciPy's signal, lstm torch: seconds an MLR run
# does not need).  ``from thermocomp.core.models import ARX`` and Hydra's targets work as before.
_FAMILIES = {"MLR": "linear", "PCR": "pcr", "ARX": "arx", "ARXRF": "arx_rf", "LagBank": "lagbank",
             "Hammerstein": "hammerstein", "LSTM": "lstm"}

__all__ = list(_FAMILIES)


def __getattr__(name):
    if name in _FAMILIES:
        return getattr(import_module(f".{_FAMILIES[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted({*globals(), *_FAMILIES})
