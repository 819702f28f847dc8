"""lstmspeed64: the LSTM's training cost -- 16 pieces per Adam step, its least squares on one
BLAS thread, the training pieces cut once per fit with the state carried into each."""

import math
from unittest import mock

import numpy as np
import yaml
from threadpoolctl import threadpool_info

from conftest import ctx
from test_lstm import lagged_data
from thermocomp.base.paths import conf_dir
from thermocomp.core.models import LSTM
from thermocomp.core.models import lstm as lstm_module


def test_the_defaults_take_16_pieces_per_step_at_a_rate_scaled_with_the_batch():
    conf = yaml.safe_load((conf_dir() / "model" / "lstm.yaml").read_text())["estimator"]
    assert LSTM().batch_size == conf["batch_size"] == 16
    # Adam's rate scaled by the square root of the batch ratio (3e-3 at 4 pieces before)
    assert LSTM().learning_rate == conf["learning_rate"] == 3e-3 * math.sqrt(16 / 4)
    assert LSTM().patience == conf["patience"] == 10


def test_the_default_patience_runs_the_same_epochs_as_20_and_stops_sooner():
    X, y, g = lagged_data(n_campaigns=10, n=64)
    short, long = (LSTM(hidden_size=4, chunk=32, max_epochs=60, **kw).fit(X, y, context=ctx(g))
                   for kw in ({}, {"patience": 20}))
    assert short.n_epochs_ < long.n_epochs_
    assert short.validation_curve_ == long.validation_curve_[:len(short.validation_curve_)]
    # it stops 10 epochs after its best (here a plateau of 10 came before 20's later best)
    assert short.n_epochs_ == short.best_epoch_ + 10
    assert short.best_epoch_ == int(np.argmin(short.validation_curve_)) <= long.best_epoch_


def test_an_epoch_is_one_adam_step_per_16_training_pieces():
    import torch  # in the tests that use it: not imported at collection (~2 s of CPU per worker)

    X, y, g = lagged_data(n_campaigns=40, n=64)
    steps = []
    real = torch.optim.Adam.step

    def counted(self, *a, **kw):
        steps.append(1)
        return real(self, *a, **kw)

    with mock.patch.object(torch.optim.Adam, "step", counted):
        est = LSTM(hidden_size=4, chunk=32, max_epochs=2, validation_fraction=0.0).fit(
            X, y, context=ctx(g))
    pieces = 40 * 2                      # 40 campaigns of two 32-sample pieces, all trained on
    assert est.n_epochs_ == 2 and len(steps) == 2 * math.ceil(pieces / 16)


def test_the_least_squares_run_on_one_blas_thread():
    X, y, g = lagged_data(n_campaigns=4, n=40)
    threads = []
    real = np.linalg.lstsq

    def watched(*a, **kw):
        threads.append({i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"})
        return real(*a, **kw)

    with mock.patch.object(lstm_module.np.linalg, "lstsq", watched):
        LSTM(hidden_size=4, chunk=16, max_epochs=1).fit(X, y, context=ctx(g))
    # the skip path before training and its refit after: more threads only spin on a tall,
    # narrow matrix (8x the CPU on a lathe-sized set)
    assert len(threads) == 2 and all(t <= {1} for t in threads)


def test_a_piece_inside_a_campaign_starts_from_the_state_reached_there():
    import torch

    n_campaigns, length, chunk, layers, hidden = 3, 10, 4, 1, 2
    pieces = [(b, k) for b in range(n_campaigns) for k in range(0, length, chunk)]
    xs = torch.arange(n_campaigns * length * 1, dtype=torch.float32).reshape(n_campaigns, length, 1)
    ones = torch.ones(n_campaigns, length)
    data = lstm_module._Pieces(pieces, chunk, length, xs, ones, ones)
    # the inputs of a piece past the campaign's end are its last row, weighted 0
    last = pieces.index((0, 8))
    assert data.x[last, :, 0].tolist() == [8, 9, 9, 9] and data.w[last].tolist() == [1, 1, 0, 0]
    starts = [None] + [tuple(torch.full((layers, n_campaigns, hidden), 10.0 * c) + torch.arange(
        n_campaigns, dtype=torch.float32)[None, :, None] for _ in range(2)) for c in (1, 2)]
    h, c = data.states(starts)(torch.tensor([pieces.index((2, 4)), pieces.index((1, 0)),
                                             pieces.index((0, 8))]))
    assert h.shape == (layers, 3, hidden) and h.is_contiguous()
    assert h[0, :, 0].tolist() == [12.0, 0.0, 20.0] and torch.equal(h, c)
    assert data.carried.tolist() == [k > 0 for _, k in pieces]
