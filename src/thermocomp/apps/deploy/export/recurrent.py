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
+ i g``, ``h <- o tanh(c)``; ``in`` is ``xs`` for layer 0 and the layer below's new ``h``
after it.  Layer 0's ``xs`` is over the model's own columns, each a feature the code computes
anyway (exportlstm64: :func:`net_reads`): ``lstm_in`` names its source in the code's ``[x,
lags]`` (an input, a diagnosed model's derived input or initial-state transient, the lag of one
or a low-pass copy of an input), read clamped (the first channel minus the excess channel:
the features of ``x - ex``, as the stream's model computes them), times the factor of the law
``lstm_in_law`` names (1; ``A0 - 20 °C`` for a diagnosed ambient law's block or an ATI
interval's interaction, ``[A0 > A_thr]`` for an ambient step's: the laws' own factors), then
standardised.  A plain lstm's columns are its inputs; an ATI interval's with the interaction
``[x, x (A0 - 20)]`` (exportati63); a diagnosed lstm's ``[x, features]`` in the effects' order,
as its skip law's are.  ``W_ih`` rows are ``lstm_width = max(inputs, H)`` wide (zeros beyond a
layer's own inputs; a narrower net's inputs padded with source -1, weight 0).  Every net of
the code has the same ``H`` and layer count (else refused, naming them).
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


def net_reads(est, cols, inputs: list, powers: dict, interacts: bool, derived, lo: float,
              hi: float) -> list[tuple]:
    """Per column of the inputs of the lstm ``est`` (an ATI interval's ``lo < A0 <= hi``), in
    the model's order, the feature of the code it is: ``(place, tau, law key)``, ``place`` in
    the code's ``[x, registered features]`` (``powers``, before :func:`.statespace._in_code_order`
    numbers them; ``cols`` its inputs), ``tau`` not None for the lag of that place (a diagnosed
    lag, a low-pass copy of an input), and the key (:attr:`.laws.Law.key`) of the law whose
    factor multiplies it: the net's skip law's own, an ambient law's ``A0 - 20``, an ambient
    step's ``[A0 > A_thr]``, an ATI interval's interaction times ``A0 - 20`` once more.  The
    columns are the skip law's (:func:`.laws._member_laws` lays them out the same way): the
    features the code computes for a linear base are what the network reads (exportlstm64)."""
    from .derived import derived_inputs

    if derived.factor is not None:     # (A0 - 20) x . w: one column, a sum of the code's features
        raise NotExportable("an lstm under a lean level law (the inputs' mean or fit x (A0 - 20)) "
                            "does not export: its network reads that one column, which is no "
                            "feature of the code; the served model runs it (thermocomp serve, connect)")
    extra = derived_inputs(derived, inputs, powers, cols)
    blocks = derived.blocks if derived.blocks is not None else [("ambient", None)] * interacts
    n, cols = len(inputs), [int(c) for c in cols]
    # [x, ambient blocks, derived inputs, low-pass blocks]: (place, tau, (lo, hi, power of A0 - 20))
    canonical = [(c, None, (lo, hi, 0)) for c in cols]
    for kind, threshold in blocks:
        key = (max(lo, threshold), hi, 0) if kind == "step" else (lo, hi, 1)
        canonical += [(c, None, key) for c in cols]
    canonical += [(n + f, tau, (lo, hi, 0)) for f, tau in extra]
    canonical += [(c, tau, (lo, hi, 0)) for tau in derived.lowpass for c in cols]
    if interacts and derived.blocks is not None:    # [Z, Z (A0 - 20)] (an ATI interval's)
        width = len(canonical)
        canonical += [(place, tau, (a, b, power + 1)) for place, tau, (a, b, power) in canonical]
        model = np.r_[derived.model_columns(width), width + derived.model_columns(width)]
    else:
        model = derived.model_columns(len(canonical))
    if len(canonical) != len(est.x_mean_):
        raise NotExportable(f"the lstm reads {len(est.x_mean_)} columns, its features are "
                            f"{len(canonical)}: a diagnosed model of another layout")
    where = np.argsort(model)           # a model column's canonical place
    return [canonical[p] for p in where]


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
    # (nets, inputs) per input of the first layer (the model's columns): its source in the code's
    # [x, lags] (< the width of x: x[source], else the lag source - width; -1: none, a narrower
    # net's padding) and the law whose factor multiplies it (exportlstm64)
    lstm_in: list = field(default_factory=list)
    lstm_in_law: list = field(default_factory=list)
    lstm_x_mean: list = field(default_factory=list)     # (nets, inputs)
    lstm_x_scale: list = field(default_factory=list)    # (nets, inputs)
    lstm_w_ih: list = field(default_factory=list)       # (nets, layers, 4 H, width)
    lstm_w_hh: list = field(default_factory=list)       # (nets, layers, 4 H, H)
    lstm_b_ih: list = field(default_factory=list)       # (nets, layers, 4 H)
    lstm_b_hh: list = field(default_factory=list)       # (nets, layers, 4 H)
    lstm_head: list = field(default_factory=list)       # (nets, H)
    lstm_head_bias: list = field(default_factory=list)  # (nets,)
    lstm_y_scale: list = field(default_factory=list)    # (nets,)


def net_inputs(ss) -> int:
    """The first layer's inputs (the widest net's columns)."""
    return len(ss.lstm_in[0]) if ss.lstm_in else 0


def net_arrays(ss) -> list[tuple[str, list, tuple, str]]:
    """The networks' constants of the exported code, ``(name, values, shape, kind)`` in the order
    both languages declare them (c.py, st.py: one list, each its own syntax); ``kind``: ``int``
    or ``real``."""
    k, L, H, W, n = (len(ss.lstm_target), ss.lstm_layers, ss.lstm_hidden, ss.lstm_width,
                     net_inputs(ss))
    return [("LSTM_TARGET", ss.lstm_target, (k,), "int"),
            ("LSTM_WEIGHT", ss.lstm_weight, (k,), "real"),
            ("LSTM_LAW", ss.lstm_law or [0] * k, (k,), "int"),
            ("LSTM_IN", ss.lstm_in, (k, n), "int"),
            ("LSTM_IN_LAW", ss.lstm_in_law, (k, n), "int"),
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
        # per net: its inputs [(place, tau, law)] before the code's numbering, their mean and
        # scale, its first layer's weights (4 H, its inputs) and its upper layers' (4 H, H)
        self._nets: list = []

    def add(self, target: int, weight: float, est, law: int, reads: list) -> None:
        """The network of the fitted LSTM ``est`` (weight ``weight`` in target ``target``'s
        blend), counting as law ``law`` does, its inputs ``reads`` (:func:`net_reads`, each key
        as the index of its law)."""
        cell, H, L = est.net_.lstm, int(est.hidden_size), int(est.num_layers)
        if self.lstm_target and (H, L) != (self.lstm_hidden, self.lstm_layers):
            raise NotExportable(f"the LSTMs of the targets have hidden_size, num_layers {H}, {L} "
                                f"and {self.lstm_hidden}, {self.lstm_layers}; the code steps one "
                                "shape of network")
        self._nets.append((list(reads), np.asarray(est.x_mean_, float), np.asarray(est.x_scale_, float),
                           _numpy(cell.weight_ih_l0),
                           [_numpy(getattr(cell, f"weight_ih_l{layer}")) for layer in range(1, L)]))
        self.lstm_target.append(int(target))
        self.lstm_weight.append(float(weight))
        self.lstm_law.append(int(law))
        self.lstm_hidden, self.lstm_layers = H, L
        for name, out in (("weight_hh", self.lstm_w_hh), ("bias_ih", self.lstm_b_ih),
                          ("bias_hh", self.lstm_b_hh)):
            out.append([_numpy(getattr(cell, f"{name}_l{layer}")).tolist() for layer in range(L)])
        self.lstm_head.append(_numpy(est.net_.head.weight).reshape(-1).tolist())
        self.lstm_head_bias.append(float(_numpy(est.net_.head.bias).reshape(-1)[0]))
        self.lstm_y_scale.append(float(est.y_scale_))

    def lags(self, place) -> set:
        """The lags the nets read, ``(tau, place of its input)`` in the code's numbering
        (``place``)."""
        return {(tau, int(place(p))) for reads, *_ in self._nets for p, tau, _ in reads
                if tau is not None}

    def fields(self, place, lag_at: dict, width: int) -> dict:
        """The StateSpace's fields (none without an LSTM): each input's source in ``[x, lags]``
        (``place`` numbers a feature as the code does, ``lag_at`` a lag's index by ``(tau,
        place of its input)``, ``width`` x's), the inputs of the nets padded to the widest's
        and the layers' input rows ``max(inputs, H)`` wide."""
        if not self.lstm_target:
            return {}
        n, H = max(len(net[0]) for net in self._nets), self.lstm_hidden
        self.lstm_width = W = max(n, H)
        w_ih = np.zeros((len(self._nets), self.lstm_layers, 4 * H, W))
        sources, laws, means, scales = [], [], [], []
        for k, (reads, mean, scale, first, upper) in enumerate(self._nets):
            w_ih[k, 0, :, :first.shape[1]] = first
            for layer, w in enumerate(upper, start=1):
                w_ih[k, layer, :, :H] = w
            pad = n - len(reads)
            sources.append([int(place(p)) if tau is None else width + lag_at[(tau, int(place(p)))]
                            for p, tau, _ in reads] + [-1] * pad)
            laws.append([int(law) for _, _, law in reads] + [0] * pad)
            means.append(mean.tolist() + [0.0] * pad)
            scales.append(scale.tolist() + [1.0] * pad)
        self.lstm_in, self.lstm_in_law, self.lstm_x_mean, self.lstm_x_scale = sources, laws, means, scales
        self.lstm_w_ih = w_ih.tolist()
        return {f.name: getattr(self, f.name) for f in dataclass_fields(NetArrays)}


def _sigmoid(a: np.ndarray) -> np.ndarray:
    return 1.0 / (1.0 + np.exp(-a))


class Cells:
    """The LSTMs stepped in numpy (the :class:`~.statespace.Simulator`'s), all nets at once."""

    def __init__(self, ss):
        k, L, H, W = len(ss.lstm_target), ss.lstm_layers, ss.lstm_hidden, ss.lstm_width
        self.source, self.law = (np.asarray(a, int).reshape(k, -1) for a in (ss.lstm_in, ss.lstm_in_law))
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

    def step(self, xs: np.ndarray, z: np.ndarray, factor: np.ndarray, first: bool) -> np.ndarray:
        """Each net's residual ``s_y (v . h_L + d)`` at the sample whose features are ``xs`` and
        lags ``z`` (both channels: the net reads the clamped ones, the first minus the second),
        each input times its law's ``factor`` in the campaign."""
        if first:
            self.h[:], self.c[:] = 0.0, 0.0
        clamped = np.concatenate([xs[0] - xs[1], z[0] - z[1]])
        x = np.where(self.source >= 0, clamped[np.maximum(self.source, 0)], 0.0) * factor[self.law]
        H = self.H
        for k in range(len(self.mean)):
            inp = np.zeros(self.W)
            inp[:x.shape[1]] = (x[k] - self.mean[k]) / self.scale[k]
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
