"""LSTM on sliding windows of the inputs (PyTorch, CPU), with early stopping."""

from __future__ import annotations

import copy

import numpy as np
import torch
from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.utils.validation import check_is_fitted, validate_data
from torch import nn

from ..context import SideInputs, groups_of
from ..errors import ParameterError
from ..model_selection import CampaignHoldOut
from ._dynamics import window_index


class _Net(nn.Module):
    """LSTM over a window, linear read-out of the last hidden state."""

    def __init__(self, n_inputs: int, hidden_size: int, num_layers: int, dropout: float):
        super().__init__()
        self.lstm = nn.LSTM(n_inputs, hidden_size, num_layers=num_layers, batch_first=True,
                            dropout=dropout if num_layers > 1 else 0.0)
        self.head = nn.Linear(hidden_size, 1)

    def forward(self, x):
        out, _ = self.lstm(x)
        return self.head(out[:, -1, :]).squeeze(-1)


class _torch_threads:
    """Run a block with ``torch.set_num_threads(n)`` and restore the previous value."""

    def __init__(self, n: int):
        self.n = n

    def __enter__(self):
        self.previous = torch.get_num_threads()
        torch.set_num_threads(self.n)

    def __exit__(self, *exc):
        torch.set_num_threads(self.previous)


class LSTM(SideInputs, RegressorMixin, BaseEstimator):
    r"""Long short-term memory network on windows of the inputs.

    .. math:: \hat y(t) = w^\top h_t + c, \qquad
              h_t = \mathrm{LSTM}\big(x(t-L+1), \dots, x(t)\big)

    Inputs and target are standardised on the training data.  Windows of
    ``window`` samples never cross a campaign (``groups``): they are padded
    with the campaign's first sample.  Training minimises the mean squared
    error with Adam on shuffled mini-batches and stops early when the loss on a
    validation part of the training data has not improved for ``patience``
    epochs (the best weights are kept).  The validation part is a
    ``validation_fraction`` of the campaigns, or -- with a single campaign --
    its last contiguous ``validation_fraction`` of samples.

    Seeded and deterministic on CPU (``random_state``, a forked torch RNG, a
    fixed thread count); the global torch RNG and thread setting are left as
    they were.  Inference runs in float64, so batch ``predict`` and the
    streaming protocol agree to rounding.

    The network has no error feedback: ``simulation`` and ``one_step``
    predictions coincide.  Predictions depend on the preceding rows (the
    window), so scikit-learn's sample-order and subset invariance checks do not
    apply to it (documented exceptions of ``check_estimator``).

    Parameters
    ----------
    window : int, default 24
        Samples per input window (24 × 5 min = 2 h on the year-round data).
    hidden_size, num_layers : int, default 32, 1
    dropout : float, default 0.0
        Between stacked LSTM layers (``num_layers > 1``).
    learning_rate : float, default 3e-3
    weight_decay : float, default 0.0
    batch_size : int, default 64
    max_epochs : int, default 300
    patience : int, default 20
    validation_fraction : float, default 0.2
        0 trains ``max_epochs`` without early stopping.
    random_state : int, default 0
    n_threads : int, default 1
        ``torch.set_num_threads`` during fit and predict.

    Attributes
    ----------
    net_ : torch.nn.Module
        Trained network (float64, eval mode).
    x_mean_, x_scale_ : ndarray (n_features,)
    y_mean_, y_scale_ : float
    n_epochs_ : int
        Epochs run.
    best_epoch_ : int
        Epoch of the kept weights (1-based).
    loss_curve_, validation_curve_ : list of float
        Training and validation MSE (standardised units) per epoch.
    """

    def __init__(self, window: int = 24, hidden_size: int = 32, num_layers: int = 1,
                 dropout: float = 0.0, learning_rate: float = 3e-3, weight_decay: float = 0.0,
                 batch_size: int = 64, max_epochs: int = 300, patience: int = 20,
                 validation_fraction: float = 0.2, random_state: int = 0, n_threads: int = 1):
        self.window = window
        self.hidden_size = hidden_size
        self.num_layers = num_layers
        self.dropout = dropout
        self.learning_rate = learning_rate
        self.weight_decay = weight_decay
        self.batch_size = batch_size
        self.max_epochs = max_epochs
        self.patience = patience
        self.validation_fraction = validation_fraction
        self.random_state = random_state
        self.n_threads = n_threads

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.regressor_tags.poor_score = True     # few epochs in the generic checks
        tags.non_deterministic = False
        return tags

    def _check_params(self) -> None:
        positive = {"window": self.window, "hidden_size": self.hidden_size,
                    "num_layers": self.num_layers, "batch_size": self.batch_size,
                    "max_epochs": self.max_epochs, "patience": self.patience,
                    "n_threads": self.n_threads}
        for name, value in positive.items():
            if int(value) < 1:
                raise ParameterError(f"LSTM {name}={value!r} must be >= 1")
        if not 0 <= float(self.validation_fraction) < 1:
            raise ParameterError(f"LSTM validation_fraction={self.validation_fraction!r} must be in [0, 1)")

    def _validation_rows(self, groups, n: int) -> np.ndarray:
        """Boolean mask of validation rows: whole campaigns, or the tail of a single one."""
        holdout = CampaignHoldOut(self.validation_fraction, random_state=self.random_state)
        return holdout.test_mask(groups, np.empty((n, 0)))

    def _windows(self, X, groups) -> tuple[torch.Tensor, np.ndarray]:
        Xs = (np.asarray(X, dtype=float) - self.x_mean_) / self.x_scale_
        return torch.tensor(Xs, dtype=torch.float64), window_index(groups, len(Xs), int(self.window))

    def fit(self, X, y, context=None):
        self._check_params()
        groups = groups_of(context)
        X, y = validate_data(self, X, y, y_numeric=True)
        X, y = np.asarray(X, dtype=float), np.asarray(y, dtype=float)
        n = len(y)
        self.x_mean_ = X.mean(axis=0)
        self.x_scale_ = np.where(X.std(axis=0) > 0, X.std(axis=0), 1.0)
        self.y_mean_ = float(y.mean())
        self.y_scale_ = float(y.std()) if y.std() > 0 else 1.0
        xs, idx = self._windows(X, groups)
        xs = xs.float()
        ys = torch.tensor((y - self.y_mean_) / self.y_scale_, dtype=torch.float32)
        val = self._validation_rows(groups, n)
        train_rows, val_rows = np.flatnonzero(~val), np.flatnonzero(val)
        idx_t = torch.as_tensor(idx)
        with _torch_threads(int(self.n_threads)), torch.random.fork_rng(devices=[]):
            torch.manual_seed(int(self.random_state))
            gen = torch.Generator().manual_seed(int(self.random_state))
            net = _Net(X.shape[1], int(self.hidden_size), int(self.num_layers), float(self.dropout))
            opt = torch.optim.Adam(net.parameters(), lr=float(self.learning_rate),
                                   weight_decay=float(self.weight_decay))
            loss_fn = nn.MSELoss()
            train_t, val_t = torch.as_tensor(train_rows), torch.as_tensor(val_rows)
            best, best_state, best_epoch, waited = np.inf, None, 0, 0
            self.loss_curve_, self.validation_curve_ = [], []
            for epoch in range(1, int(self.max_epochs) + 1):
                net.train()
                perm = train_t[torch.randperm(len(train_t), generator=gen)]
                total = 0.0
                for batch in perm.split(int(self.batch_size)):
                    opt.zero_grad()
                    loss = loss_fn(net(xs[idx_t[batch]]), ys[batch])
                    loss.backward()
                    opt.step()
                    total += loss.item() * len(batch)
                self.loss_curve_.append(total / max(len(train_t), 1))
                if not len(val_t):
                    best_state, best_epoch = None, epoch
                    continue
                net.eval()
                with torch.no_grad():
                    val_loss = float(loss_fn(net(xs[idx_t[val_t]]), ys[val_t]))
                self.validation_curve_.append(val_loss)
                if val_loss < best:
                    best, best_state, best_epoch, waited = val_loss, copy.deepcopy(net.state_dict()), epoch, 0
                else:
                    waited += 1
                    if waited >= int(self.patience):
                        break
            if best_state is not None:
                net.load_state_dict(best_state)
        self.n_epochs_, self.best_epoch_ = epoch, best_epoch
        self.net_ = net.double().eval()
        self.context_columns_ = []
        return self

    def _run(self, windows: torch.Tensor) -> np.ndarray:
        with _torch_threads(int(self.n_threads)), torch.no_grad():
            out = torch.cat([self.net_(w) for w in windows.split(4096)]) if len(windows) \
                else torch.zeros(0, dtype=torch.float64)
        return out.numpy() * self.y_scale_ + self.y_mean_

    def predict(self, X, context=None):
        """Predicted error (the same in simulation and one-step mode)."""
        check_is_fitted(self)
        X = validate_data(self, X, reset=False)
        xs, idx = self._windows(X, groups_of(context))
        return self._run(xs[torch.as_tensor(idx)])

    # -- streaming (deployment) ---------------------------------------------------------
    def stream_init(self, context=None) -> dict:
        check_is_fitted(self)
        return {"history": None}

    def stream_step(self, x_row, state: dict, context=None) -> tuple[float, dict]:
        """One sample of ``predict``: the window of the last ``window`` samples."""
        x = (np.asarray(x_row, dtype=float).reshape(-1) - self.x_mean_) / self.x_scale_
        history = state["history"]
        history = np.tile(x, (int(self.window), 1)) if history is None \
            else np.vstack([history[1:], x[None, :]])
        y_hat = float(self._run(torch.tensor(history[None, :, :], dtype=torch.float64))[0])
        return y_hat, {"history": history}
