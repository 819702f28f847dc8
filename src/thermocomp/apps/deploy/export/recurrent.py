"""An ``lstm`` model's network as arrays the exported code steps per sample (lstmexport62).

:class:`~thermocomp.core.models.lstm.LSTM` predicts ``y = mu_y + s_y (w . xs + c + v . h_L +
d)``, ``xs = (x - mu_x) / s_x`` its standardised inputs, ``h_L`` the last layer's hidden state
of a torch LSTM run from ``(h, c) = 0`` at the campaign's first sample, in float64.  The linear
skip path ``w . xs + c`` is a law of the code like an MLR's (:func:`skip_law`, in the model's
units); the residual ``s_y (v . h_L + d)`` is added beside the laws, times the member's blend
weight and the factor of its skip law (``lstm_law``: an lstm within an ATI model, one per
interval of the campaign's initial ambient ``A0``, counts in its interval only, exportati63; a
net that does not count is not stepped), in the measured channel (as an arx_rf's forest:
:mod:`.forest`).  An LSTM has no step
gain, so the stream runs it on the clamped inputs ``x - ex`` alone: the code takes the skip
law's response to the excess out outright (``clamp_outright``) and steps the cell on ``x - ex``.

Per net ``k`` and layer ``l`` (torch's gate order i, f, g, o over rows of ``4 H``): ``a = W_ih
in + b_ih + W_hh h + b_hh``, ``i, f, o = sigmoid(a_i, a_f, a_o)``, ``g = tanh(a_g)``, ``c <- f c
+ i g``, ``h <- o tanh(c)``; ``in`` is ``xs`` (over the code's inputs: a column the net does not
read has weight 0, mean 0, scale 1) for layer 0 and the layer below's new ``h`` after it.  An
ATI interval's model with the ambient interaction reads ``[x, x (A0 - 20 °C)]``, and so does
the base of a diagnosed model whose only effect is the ambient law (diaglstm63): where a net
does (``lstm_ambient``), layer 0's ``in`` is ``xs`` over ``[x, x (A0 - ambient_centre)]``, 2
n_inputs wide (the second half weight 0 for a net without it).  ``W_ih`` rows are
``lstm_width = max(n_inputs [x 2], H)`` wide (zeros beyond a layer's own inputs).  Every net
of the code has the same ``H`` and layer count (else refused, naming them).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from dataclasses import fields as dataclass_fields

import numpy as np

from .errors import NotExportable


def is_lstm(est) -> bool:
    """``est`` is an ``lstm`` model (its module is loaded when one was unpickled)."""
    module = sys.modules.get(__name__.split(".apps.")[0] + ".core.models.lstm")
    return module is not None and type(est) is module.LSTM


def skip_law(est):
    """An :class:`~thermocomp.core.models.MLR` equal to ``est``'s skip path in the model's units:
    ``mu_y + s_y (w . (x - mu_x) / s_x + c)`` (the residual is :class:`Nets`')."""
    from ....core.models import MLR

    w = est.net_.skip.weight.detach().numpy().reshape(-1).astype(float)
    c = float(est.net_.skip.bias.detach().numpy().reshape(-1)[0])
    law = MLR()
    law.coef_ = est.y_scale_ * w / est.x_scale_
    law.intercept_ = est.y_mean_ + est.y_scale_ * (c - float(np.sum(w * est.x_mean_ / est.x_scale_)))
    return law


def _numpy(t) -> np.ndarray:
    return t.detach().numpy().astype(float)


@dataclass
class NetArrays:
    """An lstm model's networks as fields of the exported system (module doc): declared once
    here, :class:`~.statespace.StateSpace` is made of them; all empty: none."""

    lstm_target: list = field(default_factory=list)
    lstm_weight: list = field(default_factory=list)     # its blend weight
    # (nets,) the law whose factor the net's residual takes: its skip path's, 1 in its ATI
    # interval of the campaign's initial ambient and 0 outside it (exportati63)
    lstm_law: list = field(default_factory=list)
    lstm_hidden: int = 0
    lstm_layers: int = 0
    lstm_width: int = 0
    # the nets read [x, x (A0 - ambient_centre)] (an ATI interval's model with the ambient
    # interaction, exportati63): lstm_x_mean and lstm_x_scale are 2 n_inputs wide
    lstm_ambient: bool = False
    lstm_x_mean: list = field(default_factory=list)     # (nets, n_inputs [x 2: lstm_ambient])
    lstm_x_scale: list = field(default_factory=list)    # (nets, n_inputs [x 2: lstm_ambient])
    lstm_w_ih: list = field(default_factory=list)       # (nets, layers, 4 H, width)
    lstm_w_hh: list = field(default_factory=list)       # (nets, layers, 4 H, H)
    lstm_b_ih: list = field(default_factory=list)       # (nets, layers, 4 H)
    lstm_b_hh: list = field(default_factory=list)       # (nets, layers, 4 H)
    lstm_head: list = field(default_factory=list)       # (nets, H)
    lstm_head_bias: list = field(default_factory=list)  # (nets,)
    lstm_y_scale: list = field(default_factory=list)    # (nets,)


def net_inputs(ss) -> int:
    """The first layer's inputs: the code's inputs, twice with the ambient interaction."""
    return len(ss.inputs) * (1 + ss.lstm_ambient)


def net_arrays(ss) -> list[tuple[str, list, tuple, str]]:
    """The networks' constants of the exported code, ``(name, values, shape, kind)`` in the order
    both languages declare them (c.py, st.py: one list, each its own syntax); ``kind``: ``int``
    or ``real``."""
    k, L, H, W, n = (len(ss.lstm_target), ss.lstm_layers, ss.lstm_hidden, ss.lstm_width,
                     net_inputs(ss))
    return [("LSTM_TARGET", ss.lstm_target, (k,), "int"),
            ("LSTM_WEIGHT", ss.lstm_weight, (k,), "real"),
            ("LSTM_LAW", ss.lstm_law or [0] * k, (k,), "int"),
            ("LSTM_X_MEAN", ss.lstm_x_mean, (k, n), "real"),
            ("LSTM_X_SCALE", ss.lstm_x_scale, (k, n), "real"),
            ("LSTM_W_IH", ss.lstm_w_ih, (k, L, 4 * H, W), "real"),
            ("LSTM_W_HH", ss.lstm_w_hh, (k, L, 4 * H, H), "real"),
            ("LSTM_B_IH", ss.lstm_b_ih, (k, L, 4 * H), "real"),
            ("LSTM_B_HH", ss.lstm_b_hh, (k, L, 4 * H), "real"),
            ("LSTM_HEAD", ss.lstm_head, (k, H), "real"),
            ("LSTM_HEAD_BIAS", ss.lstm_head_bias, (k,), "real"),
            ("LSTM_Y_SCALE", ss.lstm_y_scale, (k,), "real")]


class Nets(NetArrays):
    """The LSTMs of the exported code's targets, gathered as :func:`.laws.target_laws` meets
    them (module doc); :meth:`fields` are the :class:`~.statespace.StateSpace`'s."""

    def __init__(self):
        super().__init__()
        # per net: its input standardisation and first layer's weights over [x, x (A0 -
        # centre)] (2 n), its upper layers' (H wide): spread to the code's width in fields()
        self._inputs: list = []
        self._n = 0

    def add(self, target: int, weight: float, est, cols, n: int, law: int,
            ambient: bool = False) -> None:
        """The network of the fitted LSTM ``est`` (weight ``weight`` in target ``target``'s
        blend) reading the code's inputs ``cols`` of ``n`` (``ambient``: and them times ``A0 -
        ambient_centre``, an ATI interval's interaction), counting as law ``law`` does."""
        cell, H, L = est.net_.lstm, int(est.hidden_size), int(est.num_layers)
        if self.lstm_target and (H, L) != (self.lstm_hidden, self.lstm_layers):
            raise NotExportable(f"the LSTMs of the targets have hidden_size, num_layers {H}, {L} "
                                f"and {self.lstm_hidden}, {self.lstm_layers}; the code steps one "
                                "shape of network")
        cols = np.asarray(cols, int)
        reads = np.r_[cols, n + cols] if ambient else cols     # among [x, x (A0 - centre)]
        mean, scale, first = np.zeros(2 * n), np.ones(2 * n), np.zeros((4 * H, 2 * n))
        mean[reads], scale[reads] = est.x_mean_, est.x_scale_
        first[:, reads] = _numpy(cell.weight_ih_l0)
        upper = [_numpy(getattr(cell, f"weight_ih_l{layer}")) for layer in range(1, L)]
        self._inputs.append((mean, scale, first, upper))
        self._n = n
        self.lstm_target.append(int(target))
        self.lstm_weight.append(float(weight))
        self.lstm_law.append(int(law))
        self.lstm_hidden, self.lstm_layers = H, L
        self.lstm_ambient = self.lstm_ambient or bool(ambient)
        for name, out in (("weight_hh", self.lstm_w_hh), ("bias_ih", self.lstm_b_ih),
                          ("bias_hh", self.lstm_b_hh)):
            out.append([_numpy(getattr(cell, f"{name}_l{layer}")).tolist() for layer in range(L)])
        self.lstm_head.append(_numpy(est.net_.head.weight).reshape(-1).tolist())
        self.lstm_head_bias.append(float(_numpy(est.net_.head.bias).reshape(-1)[0]))
        self.lstm_y_scale.append(float(est.y_scale_))

    def fields(self) -> dict:
        """The StateSpace's fields (none without an LSTM): the layers' input rows ``max(n_inputs,
        H)`` wide (``2 n_inputs`` where a net reads the ambient interaction: ``lstm_ambient``)."""
        if not self.lstm_target:
            return {}
        own = self._n * (1 + self.lstm_ambient)     # the first layer's inputs
        H = self.lstm_hidden
        self.lstm_width = max(own, H)
        w_ih = np.zeros((len(self._inputs), self.lstm_layers, 4 * H, self.lstm_width))
        for k, (mean, scale, first, upper) in enumerate(self._inputs):
            w_ih[k, 0, :, :own] = first[:, :own]
            for layer, w in enumerate(upper, start=1):
                w_ih[k, layer, :, :H] = w
        self.lstm_w_ih = w_ih.tolist()
        self.lstm_x_mean = [mean[:own].tolist() for mean, _, _, _ in self._inputs]
        self.lstm_x_scale = [scale[:own].tolist() for _, scale, _, _ in self._inputs]
        return {f.name: getattr(self, f.name) for f in dataclass_fields(NetArrays)}


def _sigmoid(a: np.ndarray) -> np.ndarray:
    return 1.0 / (1.0 + np.exp(-a))


class Cells:
    """The LSTMs stepped in numpy (the :class:`~.statespace.Simulator`'s), all nets at once."""

    def __init__(self, ss):
        k, L, H, W = len(ss.lstm_target), ss.lstm_layers, ss.lstm_hidden, ss.lstm_width
        self.mean, self.scale = (np.asarray(a, float).reshape(k, -1)
                                 for a in (ss.lstm_x_mean, ss.lstm_x_scale))
        self.w_ih = np.asarray(ss.lstm_w_ih, float).reshape(k, L, 4 * H, W)
        self.w_hh = np.asarray(ss.lstm_w_hh, float).reshape(k, L, 4 * H, H)
        self.b = (np.asarray(ss.lstm_b_ih, float).reshape(k, L, 4 * H),
                  np.asarray(ss.lstm_b_hh, float).reshape(k, L, 4 * H))
        self.head = np.asarray(ss.lstm_head, float).reshape(k, H)
        self.head_bias, self.y_scale = (np.asarray(a, float) for a in (ss.lstm_head_bias, ss.lstm_y_scale))
        self.h, self.c = np.zeros((k, L, H)), np.zeros((k, L, H))
        self.H, self.W = H, W
        self.ambient, self.centre = bool(ss.lstm_ambient), float(ss.ambient_centre)

    def step(self, x: np.ndarray, first: bool, a0: float = 0.0) -> np.ndarray:
        """Each net's residual ``s_y (v . h_L + d)`` at the sample of (clamped) inputs ``x`` in a
        campaign of initial ambient ``a0`` (read where the nets read ``x (A0 - centre)``)."""
        if first:
            self.h[:], self.c[:] = 0.0, 0.0
        if self.ambient:
            x = np.r_[x, x * (a0 - self.centre)]
        H = self.H
        for k in range(len(self.mean)):
            inp = np.zeros(self.W)
            inp[:len(x)] = (x - self.mean[k]) / self.scale[k]
            for layer in range(self.h.shape[1]):
                a = (self.w_ih[k, layer] @ inp + self.b[0][k, layer]
                     + self.w_hh[k, layer] @ self.h[k, layer] + self.b[1][k, layer])
                i, f = _sigmoid(a[:H]), _sigmoid(a[H:2 * H])
                g, o = np.tanh(a[2 * H:3 * H]), _sigmoid(a[3 * H:])
                self.c[k, layer] = f * self.c[k, layer] + i * g
                self.h[k, layer] = o * np.tanh(self.c[k, layer])
                inp = np.zeros(self.W)
                inp[:H] = self.h[k, layer]
        return self.y_scale * (np.einsum("kh,kh->k", self.head, self.h[:, -1]) + self.head_bias)
