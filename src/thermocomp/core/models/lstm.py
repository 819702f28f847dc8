"""LSTM residual on a linear skip path, run over whole campaigns (PyTorch, CPU)."""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING

import numpy as np
from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.utils.validation import check_is_fitted, validate_data

from ...base.params import NON_NEGATIVE, check_estimator, integer, number
from ..context import SideInputs, groups_of
from ..model_selection import CampaignHoldOut
from ._dynamics import segment_bounds
from .base import measured_rows

if TYPE_CHECKING:
    import torch


def __getattr__(name: str):
    # pickles written before the network moved to _lstm_net name it lstm._Net
    if name == "_Net":
        from ._lstm_net import _Net
        return _Net
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _like_lengths(bounds, width: int, cells: int = 4_000_000) -> list[list[tuple[int, int]]]:
    """``bounds`` (campaigns' ``(start, stop)``) in batches of like length, shortest first, each
    batch padded to at most ``cells`` values (``width`` per row) unless one campaign alone is more."""
    batches, batch = [], []
    for start, stop in sorted(bounds, key=lambda b: b[1] - b[0]):
        if batch and (len(batch) + 1) * (stop - start) * width > cells:
            batches.append(batch)
            batch = []
        batch.append((start, stop))
    return batches + [batch] if batch else batches


class _Pieces:
    """The training pieces ``(campaign, start)`` of ``chunk`` samples, cut once per fit: their
    inputs ``x``, targets ``y`` and loss weights ``w`` (0 past a campaign's end or on rows not
    trained on), and which of them start inside a campaign (``carried``) with the state the
    network reaches there."""

    def __init__(self, pieces, chunk: int, length: int, xs, yp, fit_w):
        from ._lstm_net import torch

        self.pieces, self.chunk = pieces, chunk
        steps = torch.stack([torch.arange(k, k + chunk) for _, k in pieces])
        rows = torch.tensor([b for b, _ in pieces])[:, None]
        window = steps.clamp(max=length - 1)
        self.x, self.y = xs[rows, window], yp[rows, window]
        self.w = fit_w[rows, window] * (steps < length).float()
        self.campaign = rows[:, 0]
        self.piece = torch.tensor([k // chunk for _, k in pieces])
        self.carried = self.piece > 0

    def states(self, starts):
        """``batch -> (h, c)`` of its pieces from the states at every piece start (``starts``:
        per piece index, ``(h, c)`` of shape (layers, campaigns, hidden), ``None`` first)."""
        from ._lstm_net import torch

        if len(starts) < 2:
            return None
        # zeros for a campaign's first piece, as a state at rest
        h, c = (torch.cat([torch.zeros_like(starts[1][i])[None],
                           torch.stack([s[i] for s in starts[1:]])])
                [self.piece, :, self.campaign] for i in (0, 1))

        def of(batch):
            return h[batch].transpose(0, 1).contiguous(), c[batch].transpose(0, 1).contiguous()
        return of


class LSTM(SideInputs, RegressorMixin, BaseEstimator):
    r"""Linear model plus an LSTM residual, the state carried through each campaign.

    .. math:: \hat y(t) = \mu_y + \sigma_y\big(w^\top \tilde x(t) + c
              + v^\top h_t + d\big), \qquad
              (h_t, c_t) = \mathrm{LSTM}\big(\tilde x(t), (h_{t-1}, c_{t-1})\big),
              \quad (h, c) = 0 \text{ before the campaign's first sample}

    with :math:`\tilde x = (x - \mu_x)/\sigma_x` and :math:`\mu, \sigma` the
    mean and standard deviation of the training rows.  The inputs are the
    declared inputs in the reference frame (temperature changes since the
    campaign start with the default reference), so the recurrent state, like
    the machine's thermal state, starts every campaign from rest.

    The linear skip path :math:`w, c` is the least-squares fit on the rows
    the network trains on and stays fixed during training; the read-out
    :math:`v, d` starts at zero, so the network learns only what the static
    law leaves over.  Training minimises the mean squared
    error with Adam by truncated back-propagation through time: every
    campaign is cut into pieces of ``chunk`` samples, each piece starting from
    the (detached) state the network reaches there when run from the campaign
    start (recomputed every epoch), ``batch_size`` pieces per step.  Early
    stopping on the held-out part of the training rows
    (:class:`~thermocomp.core.model_selection.CampaignHoldOut`: whole campaigns, or
    the tail of a single campaign, whose state is then carried in from the
    training part) keeps the best epoch, the linear model (epoch 0) included:
    a network that does not beat the static law on held-out rows is dropped.
    Finally :math:`w, c` are refitted by least squares on all training rows
    with the learned residual held fixed, so without a network the model is
    ordinary least squares on the training data.

    Seeded and deterministic on CPU (``random_state``, a forked torch RNG, a
    fixed thread count); the global torch RNG and thread setting are left as
    they were.  Inference runs in float64, so batch ``predict`` and the
    streaming protocol (one LSTM step per sample, carrying ``(h, c)``) agree to
    rounding.

    The network has no error feedback: ``simulation`` and ``one_step``
    predictions coincide.  Predictions depend on the preceding rows of the
    campaign, so scikit-learn's sample-order and subset invariance checks do
    not apply to it (documented exceptions of ``check_estimator``).

    Parameters
    ----------
    hidden_size, num_layers : int, default 16, 1
    dropout : float, default 0.0
        Between stacked LSTM layers (``num_layers > 1``).
    chunk : int, default 128
        Samples per truncated back-propagation piece.
    learning_rate : float, default 6e-3
    weight_decay : float, default 0.0
    batch_size : int, default 16
        Pieces per Adam step.  A step costs nearly the same for 4 pieces as for 16 (the
        recurrence is sequential in time; the batch is the cheap dimension), so few large
        batches are cheap; 16 at 6e-3 (4 at 3e-3 before lstmspeed64: the rate scaled by the
        square root of the batch ratio) reached the same held-out MSE on a lathe-sized set's
        fits at under half the CPU (docs/measured/models.md).
    max_epochs : int, default 100
    patience : int, default 10
        Epochs without a better validation loss before stopping.  A shorter patience runs the
        same epochs and stops sooner: it keeps another epoch only where a longer plateau came
        before the best (3 of a lathe-sized set's 60 fits at 20: 0.3-3.3 % higher held-out MSE).
    validation_fraction : float, default 0.2
        0 trains ``max_epochs`` without early stopping.
    random_state : int, default 0
    n_threads : int, default 1
        ``torch.set_num_threads`` during fit and predict.

    Attributes
    ----------
    net_ : torch.nn.Module
        Trained network (float64, eval mode); ``net_.skip`` is the linear path.
    x_mean_, x_scale_ : ndarray (n_features,)
    y_mean_, y_scale_ : float
    n_epochs_ : int
        Epochs run.
    best_epoch_ : int
        Epoch of the kept weights (0: the linear model, the network added nothing).
    loss_curve_ : list of float
        Training MSE (standardised units) per epoch.
    validation_curve_ : list of float
        Validation MSE before training (epoch 0) and after every epoch.
    """

    # no analytic step gain (a recurrent net): the deploy guard reads one off the model by held
    # steps, as of any model without one (apps.deploy.held_gains.stepped_gain, guard111b); the
    # envelope clamp still has none

    def __init__(self, hidden_size: int = 16, num_layers: int = 1, dropout: float = 0.0,
                 chunk: int = 128, learning_rate: float = 6e-3, weight_decay: float = 0.0,
                 batch_size: int = 16, max_epochs: int = 100, patience: int = 10,
                 validation_fraction: float = 0.2, random_state: int = 0, n_threads: int = 1):
        self.hidden_size = hidden_size
        self.num_layers = num_layers
        self.dropout = dropout
        self.chunk = chunk
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

    requires = ("torch",)      # checked with the config (shell.config.checks), imported at fit
    # the weights grow as hidden_size² x num_layers: 4096 x 64 is ~17 GB of them already
    param_rules = {**{name: integer(1) for name in ("chunk", "batch_size", "max_epochs", "patience")},
                   "hidden_size": integer(1, at_most=4096), "num_layers": integer(1, at_most=64),
                   "n_threads": integer(1, at_most=1024),
                   "dropout": number(0.0, 1.0, open_hi=True), "learning_rate": NON_NEGATIVE,
                   "weight_decay": NON_NEGATIVE,
                   "validation_fraction": number(0.0, 1.0, open_hi=True),
                   "random_state": integer(0, 2 ** 32 - 1)}

    def _validation_rows(self, groups, n: int) -> np.ndarray:
        """Boolean mask of validation rows: whole campaigns, or the tail of a single one."""
        holdout = CampaignHoldOut(self.validation_fraction, random_state=self.random_state)
        return holdout.test_mask(groups, np.empty((n, 0)))

    # -- training ------------------------------------------------------------------------
    def _states(self, net, xs: torch.Tensor) -> tuple[torch.Tensor, list]:
        """Outputs over whole campaigns and the state at the start of every piece (no grad)."""
        from ._lstm_net import torch

        chunk, outs, starts, state = int(self.chunk), [], [], None
        with torch.no_grad():
            for k in range(0, xs.shape[1], chunk):
                starts.append(state)
                y, _, state = net(xs[:, k:k + chunk], state)
                outs.append(y)
        return torch.cat(outs, dim=1), starts

    def fit(self, X, y, context=None):
        from ._lstm_net import _Net, _padded, _torch_threads, torch

        check_estimator(self)
        groups = groups_of(context)
        # a target measured now and then (data.sparse_targets): the network runs over every
        # row, its loss (training and validation) is masked to the measured ones
        X, y, measured = measured_rows(self, X, y)
        X = np.asarray(X, dtype=float)
        n, p = X.shape
        self.x_mean_ = X.mean(axis=0)
        self.x_scale_ = np.where(X.std(axis=0) > 0, X.std(axis=0), 1.0)
        self.y_mean_ = float(y[measured].mean())
        self.y_scale_ = float(y[measured].std()) if y[measured].std() > 0 else 1.0
        Xs = (X - self.x_mean_) / self.x_scale_
        ys = np.where(measured, (y - self.y_mean_) / self.y_scale_, 0.0)   # (0: weight 0 below)
        split = self._validation_rows(groups, n)
        val, train = split & measured, ~split & measured
        bounds = segment_bounds(groups, n)
        length = max(stop - start for start, stop in bounds)
        chunk = int(self.chunk)
        xs = _padded(Xs, bounds, length, torch.float32)
        yp = _padded(ys, bounds, length, torch.float32)
        fit_w = _padded(train.astype(float), bounds, length, torch.float32)
        val_w = _padded(val.astype(float), bounds, length, torch.float32)
        # pieces (campaign, start) holding training rows; pieces of a held-out tail are skipped
        pieces = [(b, k) for b, (start, stop) in enumerate(bounds)
                  for k in range(0, stop - start, chunk) if fit_w[b, k:k + chunk].sum() > 0]
        data = _Pieces(pieces, chunk, length, xs, yp, fit_w)
        with _torch_threads(int(self.n_threads)), torch.random.fork_rng(devices=[]):
            torch.manual_seed(int(self.random_state))
            gen = torch.Generator().manual_seed(int(self.random_state))
            net = _Net(p, int(self.hidden_size), int(self.num_layers), float(self.dropout))
            # the static law first, fitted on the rows the network trains on and held fixed: the
            # network learns only what it leaves over, and epoch 0 (no network) is judged on
            # held-out rows like every other epoch
            self._least_squares(net, Xs[train], ys[train])
            net.skip.requires_grad_(False)
            opt = torch.optim.Adam([q for q in net.parameters() if q.requires_grad],
                                   lr=float(self.learning_rate),
                                   weight_decay=float(self.weight_decay), foreach=True)
            best, best_state, best_epoch, waited = np.inf, None, 0, 0
            self.loss_curve_, self.validation_curve_ = [], []
            epoch = 0
            from ...base.progress import bar
            epochs = bar(total=int(self.max_epochs), desc="LSTM epochs", unit="epoch")
            while True:
                net.eval()
                out, starts = self._states(net, xs)
                if val.any():
                    val_loss = float((val_w * (out - yp) ** 2).sum() / val_w.sum())
                    self.validation_curve_.append(val_loss)
                    if val_loss < best:
                        best, best_epoch, waited = val_loss, epoch, 0
                        best_state = copy.deepcopy(net.state_dict())
                    else:
                        waited += 1
                if epoch >= int(self.max_epochs) or (val.any() and waited >= int(self.patience)):
                    epochs.close()
                    break
                epoch += 1
                epochs.update()
                net.train()
                self.loss_curve_.append(self._epoch(net, opt, data, data.states(starts), gen))
            if best_state is not None:
                net.load_state_dict(best_state)
        self.n_epochs_, self.best_epoch_ = epoch, best_epoch if val.any() else epoch
        self.net_ = net.double().eval()
        # the linear law refitted on every training row, the learned residual held fixed
        self._least_squares(self.net_, Xs[measured],
                            (ys - self._outputs(Xs, groups, residual=True))[measured])
        self.context_columns_ = []
        return self

    def _epoch(self, net, opt, data: _Pieces, states, gen) -> float:
        """One pass over the training pieces in random order, ``batch_size`` per Adam step;
        the training MSE (standardised) of the epoch."""
        from ._lstm_net import nn, torch

        total, weight = 0.0, 0.0
        order = torch.randperm(len(data.pieces), generator=gen)
        for i in range(0, len(order), int(self.batch_size)):
            batch = order[i:i + int(self.batch_size)]
            # a batch of campaign starts runs from rest (no state given, as zeros)
            state = None if not data.carried[batch].any() else states(batch)
            xb, yb, wb = data.x[batch], data.y[batch], data.w[batch]
            opt.zero_grad()
            pred, _, _ = net(xb, state)
            counted = wb.sum()
            loss = (wb * (pred - yb) ** 2).sum() / counted.clamp(min=1.0)
            loss.backward()
            nn.utils.clip_grad_norm_(net.parameters(), 1.0)
            opt.step()
            total, weight = total + loss.item() * float(counted), weight + float(counted)
        return total / max(weight, 1.0)

    @staticmethod
    def _least_squares(net, Xs, ys) -> None:
        """Set the skip path to the least-squares fit of ``ys`` on ``Xs``."""
        from threadpoolctl import threadpool_limits

        from ._lstm_net import torch

        # one BLAS thread: on a narrow tall matrix more threads only spin (a lathe-sized set's
        # lstsq cost 8x the CPU with two of them, for nothing)
        with threadpool_limits(limits=1, user_api="blas"):
            coef = np.linalg.lstsq(np.c_[Xs, np.ones(len(Xs))], ys, rcond=None)[0]
        with torch.no_grad():
            net.skip.weight.copy_(torch.as_tensor(coef[None, :-1]))
            net.skip.bias.fill_(float(coef[-1]))

    # -- inference -----------------------------------------------------------------------
    def _outputs(self, Xs: np.ndarray, groups, residual: bool = False) -> np.ndarray:
        """Prediction (or only the network's residual) of the net, standardised, per row."""
        from ._lstm_net import _padded, _torch_threads, torch

        out = np.zeros(len(Xs))
        with _torch_threads(int(self.n_threads)), torch.no_grad():
            # campaigns of like length in one padded batch: one pass of the recurrence for all
            # (a campaign at a time, 43 of them, was half of a lathe's mutual prediction); the
            # LSTM is causal, so a campaign's outputs do not see the zeros after its end
            for batch in _like_lengths(segment_bounds(groups, len(Xs)), Xs.shape[1]):
                length = max(stop - start for start, stop in batch)
                y = self.net_(_padded(Xs, batch, length, torch.float64))[1 if residual else 0].numpy()
                for b, (start, stop) in enumerate(batch):
                    out[start:stop] = y[b, :stop - start]
        return out

    def predict(self, X, context=None):
        """Predicted error (the same in simulation and one-step mode)."""
        check_is_fitted(self)
        X = validate_data(self, X, reset=False)
        Xs = (np.asarray(X, dtype=float) - self.x_mean_) / self.x_scale_
        return self._outputs(Xs, groups_of(context)) * self.y_scale_ + self.y_mean_

    # -- streaming (deployment) ---------------------------------------------------------
    def stream_init(self, context=None) -> dict:
        """The network at rest: ``(h, c) = 0`` before a campaign's first sample."""
        check_is_fitted(self)
        return {"hc": None}

    def stream_step(self, x_row, state: dict, context=None) -> tuple[float, dict]:
        """One LSTM step from the carried ``(h, c)``."""
        y, hc = self._from_state(np.asarray(x_row, dtype=float).reshape(1, 1, -1), state["hc"])
        return float(y[0, 0]), {"hc": hc}

    def stream_steps(self, X, state: dict, context=None) -> tuple[np.ndarray, dict]:
        """A block of rows from the carried ``(h, c)`` in one pass of the recurrence
        (:func:`thermocomp.core.context.stream_steps`)."""
        y, hc = self._from_state(np.asarray(X, dtype=float)[None], state["hc"])
        return y[0], {"hc": hc}

    def stream_branches(self, blocks, state: dict, context=None) -> np.ndarray:
        """Blocks (b, n, p) each from the same ``(h, c)``, as one batch of sequences
        (:func:`thermocomp.core.context.stream_branches`)."""
        blocks = np.asarray(blocks, dtype=float)
        hc = None if state["hc"] is None else tuple(s.repeat(1, len(blocks), 1) for s in state["hc"])
        return self._from_state(blocks, hc)[0]

    def _from_state(self, blocks: np.ndarray, hc) -> tuple[np.ndarray, tuple]:
        """Predictions (b, n) of ``blocks`` (b, n, p) from ``hc`` (None: at rest), and the state after."""
        from ._lstm_net import _torch_threads, torch

        xs = (blocks - self.x_mean_) / self.x_scale_
        with _torch_threads(int(self.n_threads)), torch.no_grad():
            y, _, hc = self.net_(torch.tensor(xs, dtype=torch.float64), hc)
        return y.numpy() * self.y_scale_ + self.y_mean_, hc
