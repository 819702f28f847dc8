"""lstmbatch64: ``batch_size='auto'`` -- 16 pieces per Adam step unless an epoch would then have
fewer than 10 steps (one long record gives few pieces), never fewer than 4, the rate scaled from
16 pieces by the square root of the batch ratio; read from the training pieces only."""

import math
from unittest import mock

import torch
import yaml

from conftest import ctx
from test_lstm import lagged_data
from thermocomp.base.paths import conf_dir
from thermocomp.core.models import LSTM


def adam_steps(est, X, y, g):
    """Fit ``est``; the learning rate of every Adam step it took."""
    rates = []
    real = torch.optim.Adam.step

    def counted(self, *a, **kw):
        rates.append(self.param_groups[0]["lr"])
        return real(self, *a, **kw)

    with mock.patch.object(torch.optim.Adam, "step", counted):
        est.fit(X, y, context=ctx(g))
    return rates


def test_the_config_and_the_class_default_to_the_auto_batch():
    conf = yaml.safe_load((conf_dir() / "model" / "lstm.yaml").read_text())["estimator"]
    assert LSTM().batch_size == conf["batch_size"] == "auto"
    assert LSTM().learning_rate == conf["learning_rate"] == 6e-3


def test_one_long_record_gets_at_least_10_steps_an_epoch_at_a_rate_scaled_down():
    X, y, g = lagged_data(n_campaigns=1, n=60 * 32)          # one record: 60 pieces of 32
    est = LSTM(hidden_size=4, chunk=32, max_epochs=2, validation_fraction=0.0)
    rates = adam_steps(est, X, y, g)
    # 16 a step gave it 4 steps an epoch; 6 give it 10
    assert est.batch_size_ == 6 and len(rates) == 2 * 10
    assert set(rates) == {est.learning_rate_} == {6e-3 * math.sqrt(6 / 16)}


def test_many_pieces_keep_16_a_step_and_few_keep_4_at_the_rate_of_before():
    X, y, g = lagged_data(n_campaigns=40, n=4 * 16)             # 160 pieces of 16
    est = LSTM(hidden_size=4, chunk=16, max_epochs=1, validation_fraction=0.0)
    assert len(adam_steps(est, X, y, g)) == 10 and est.batch_size_ == 16
    assert est.learning_rate_ == 6e-3                           # the defaults of lstmspeed64 exactly
    X, y, g = lagged_data(n_campaigns=1, n=20 * 16)             # 20 pieces: 4 a step, 5 steps
    est = LSTM(hidden_size=4, chunk=16, max_epochs=1, validation_fraction=0.0)
    assert len(adam_steps(est, X, y, g)) == 5 and est.batch_size_ == 4
    assert est.learning_rate_ == 3e-3                           # the defaults before lstmspeed64


def test_the_held_out_tail_does_not_count_and_a_given_batch_is_kept():
    X, y, g = lagged_data(n_campaigns=1, n=100 * 16)            # 100 pieces, the last 20 held out
    est = LSTM(hidden_size=4, chunk=16, max_epochs=1, patience=5, validation_fraction=0.2)
    adam_steps(est, X, y, g)
    assert est.batch_size_ == 8                                 # 80 training pieces // 10
    given = LSTM(hidden_size=4, chunk=16, max_epochs=1, batch_size=16, learning_rate=1e-3)
    assert len(adam_steps(given, X, y, g)) == 5                 # ceil(80 / 16)
    assert (given.batch_size_, given.learning_rate_) == (16, 1e-3)
