"""Checking an LSTM config imports no torch: a mistyped value is refused at once (torch's import
is ~4 s of a user's wait), and torch comes with the first fit or a pickled model."""

import subprocess
import sys

import pytest

CHECK = """
import sys
from thermocomp.base.errors import ConfigError
from thermocomp.core.models.lstm import LSTM
from thermocomp.shell.config.checks import check_component
try:
    check_component(LSTM(hidden_size=-3), "model.estimator")
except ConfigError as exc:
    print(exc)
print("torch imported:", "torch" in sys.modules)
"""


def test_a_refused_lstm_value_imports_no_torch():
    """(A valid value's check imports torch: ``LSTM.requires``; without torch it is refused
    naming the extra, tests/shell/test_extras.py.)"""
    out = subprocess.run([sys.executable, "-c", CHECK], capture_output=True, text=True, check=True).stdout
    assert out.splitlines() == ["model.estimator.hidden_size=-3: must be an integer >= 1, at most 4,096",
                                "torch imported: False"]


def test_a_model_pickled_with_the_network_at_its_old_place_loads(monkeypatch):
    """Pickles written before the network moved to ``_lstm_net`` name it ``lstm._Net``."""
    # here, not at the module's top: collection imported torch in every worker (~2 s of CPU)
    pytest.importorskip("torch")
    import pickle

    import numpy as np

    from thermocomp.core.models import _lstm_net, lstm

    model = lstm.LSTM(hidden_size=2, max_epochs=1, validation_fraction=0.0).fit(
        np.random.default_rng(0).normal(size=(40, 2)), np.arange(40.0))
    with monkeypatch.context() as m:          # pickled as before the move
        m.setattr(_lstm_net._Net, "__module__", "thermocomp.core.models.lstm")
        blob = pickle.dumps(model)
    assert b"_lstm_net" not in blob
    loaded = pickle.loads(blob)
    assert type(loaded.net_) is _lstm_net._Net
    np.testing.assert_array_equal(loaded.predict(np.ones((5, 2))), model.predict(np.ones((5, 2))))
