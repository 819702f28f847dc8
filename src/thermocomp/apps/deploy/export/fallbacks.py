"""(cmon83) The served fallback models in the code: the correction fitted without a sensor no
other predicts (:mod:`thermocomp.apps.deploy.fallback`), served while that sensor is out.

Each fallback is the model's family refitted without the sensor, streamed beside the model from
the campaign's start on the same inputs; the served correction is its (before the guard) while
its sensor is out and the monitor rebuilds the field (``AdaptiveCompensator._fallen_back``).  Its
laws go into the code's system after the model's, ``law_set`` naming whose each is (0 the
model's, ``s`` the fallback of set ``s``): every law steps on every sample (its history, lags,
feedback and clamp bound its own), and the output sums the laws of the set being served (the
monitor's ``fallback_set``: per monitored sensor its set, 0 none in the code); its lstm networks
(of the model's shape) step beside the model's too, and other static powers are appended; an
arx_rf fallback's forest (cmon91) joins the model's forests, counting by its ARX's law (its
``forest_law``), so it adds only while its set is served (the code's forest walk, as its laws).
A fallback the system cannot hold beside the model (another denoiser, envelope, inputs or
derived inputs, a cascade of lags, a state times the inputs' rises, a forest ramping on another
clock, an lstm network of another shape) is left out: its exclusion stays flagged ``FALLBACK``
(:mod:`.watch`).  An export before a fallback's laws were merged has none in its
``fallback_set`` (0): it flags as it did.  (st103b) The ST block holds them too
(:func:`.left_out.with_st_fallbacks`), served while it holds their sensor out by ``BLIND_OUT`` or
(st103c) by its ``JUMP``.
"""

from __future__ import annotations

import numpy as np

from .errors import NotExportable

# what a fallback's system must share with the model's to step beside it in one system
SHARED = ("inputs", "targets", "fir", "referenced", "clamp", "lo", "hi", "derived",
          "derived_clamped", "derived_over", "initial", "held", "input_limit", "clamp_outright",
          "pattern", "pattern_mean", "pattern_scale", "pattern_basis", "pattern_tol",
          "ambient_inputs", "ambient_given", "ambient_optional", "ambient_centre", "period",
          "grid_period")


def with_fallbacks(ss, deployed, system) -> None:
    """Add to ``ss`` (with a monitor) the laws of each of ``deployed``'s fallbacks it can hold,
    in the monitor's order, and the monitor's ``fallback_set``; ``system``: a fallback's stream
    -> its :class:`~.statespace.StateSpace` (as the model's was made)."""
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    sets = [0] * len(names)
    falls = getattr(deployed, "fallbacks_", {}) or {}
    for k, sensor in enumerate(names):
        if sensor not in falls:
            continue
        try:
            fb = system(falls[sensor])
        except NotExportable:
            continue
        if _holds(ss, fb):
            sets[k] = max(ss.law_set or [0]) + 1
            _merge(ss, fb, sets[k])
    ss.monitor["fallback_set"] = sets


def _holds(ss, fb) -> bool:
    """Whether ``fb``'s laws can step beside ``ss``'s in one system."""
    lone = not (ss.clamp_states or fb.clamp_states or fb.lag_of)
    # (cmon91) forests ramp their states over one clock: the stream's, or the time as read
    clock = not (ss.forest_target and fb.forest_target) or ss.switch_raw_time == fb.switch_raw_time
    # other static powers (a Hammerstein model refitted may keep another degree): appended,
    # where no derived input's column (nor a network's lag) follows them
    nets = ss.lstm_target or fb.lstm_target
    powers = ss.powers == fb.powers or not (ss.derived or ss.initial or nets)
    # networks (an lstm, a model=auto blend's member): the code steps one shape of them
    shape = not (ss.lstm_target and fb.lstm_target) or (
        (ss.lstm_hidden, ss.lstm_layers) == (fb.lstm_hidden, fb.lstm_layers))
    return lone and clock and powers and shape and all(getattr(ss, k) == getattr(fb, k) for k in SHARED)


def _merge(ss, fb, s: int) -> None:
    """``fb``'s laws appended to ``ss``'s as set ``s``: its powers and lags mapped onto the
    model's (one of its own appended where none is), its input history to the deeper of the
    two."""
    laws, lags, n = len(ss.laws), len(ss.taus), len(ss.inputs)
    wide, powers = n + len(ss.powers) + len(ss.derived) + len(ss.initial), len(ss.powers)
    # fb's columns [x, powers, derived, initial] in the system's (other powers: no derived
    # column after them, _holds)
    col = np.arange(n + len(fb.powers) + len(fb.derived) + len(fb.initial))
    for k, p in enumerate(fb.powers):
        if p not in ss.powers:
            ss.powers.append(p)
        col[n + k] = n + ss.powers.index(p)
    b0 = np.zeros((laws + len(fb.laws), wide + len(ss.powers) - powers))
    b0[:laws, :wide] = np.asarray(ss.b0, float).reshape(laws, wide)
    b0[laws:, col] = np.asarray(fb.b0, float).reshape(len(fb.laws), len(col))
    plain = {(tau, j): k for k, (tau, j, of) in enumerate(
        zip(ss.taus, ss.lag_input, ss.lag_of or [-1] * len(ss.taus))) if of < 0}
    rest = list(ss.lag_rest) or [0] * len(ss.taus)
    where = []
    for k, (tau, j) in enumerate(zip(fb.taus, (int(col[j]) for j in fb.lag_input))):
        if (tau, j) not in plain:
            plain[(tau, j)] = len(ss.taus)
            ss.taus.append(tau)
            ss.lag_input.append(j)
            ss.lag_decay.append(fb.lag_decay[k])
            rest.append((fb.lag_rest or [0] * len(fb.taus))[k])
            if ss.lag_of:
                ss.lag_of.append(-1)
        where.append(plain[(tau, j)])
    ss.lag_rest = rest if any(rest) else []
    g = np.zeros((laws + len(fb.laws), len(ss.taus)))
    g[:laws, :lags] = np.asarray(ss.g, float).reshape(laws, lags)
    g[laws:, where] = np.asarray(fb.g, float).reshape(len(fb.laws), len(fb.taus))
    depth = max(ss.depth, fb.depth)
    bd = np.zeros((laws + len(fb.laws), depth, n))
    bd[:laws, :ss.depth] = np.asarray(ss.bd, float).reshape(laws, ss.depth, n)
    bd[laws:, :fb.depth] = np.asarray(fb.bd, float).reshape(len(fb.laws), fb.depth, n)
    ss.law_set = (list(ss.law_set) or [0] * laws) + [s] * len(fb.laws)
    ss.law_target = ss.laws + fb.laws
    for k in ("intercept", "ar", "law_lo", "law_hi", "law_ambient"):
        setattr(ss, k, list(getattr(ss, k)) + list(getattr(fb, k)))
    if ss.clamp_gain is not None:
        ss.clamp_gain = list(ss.clamp_gain) + list(fb.clamp_gain)
    ss.b0, ss.g, ss.bd, ss.depth = b0.tolist(), g.tolist(), bd.tolist(), depth
    ss.uses_time = ss.uses_time or fb.uses_time
    if fb.lstm_target:
        _merge_nets(ss, fb, laws, col, where)
    if fb.forest_target:
        _merge_forests(ss, fb, laws)


def _merge_forests(ss, fb, laws: int) -> None:
    """(cmon91) ``fb``'s forests appended to ``ss``'s: its states and features mapped onto the
    system's (one of its own appended where none is), its trees' nodes and roots shifted past the
    system's, each forest counting by its ARX's law among ``fb``'s (after the ``laws`` before)."""
    if not ss.forest_target:
        ss.switch_raw_time = fb.switch_raw_time
    switch = []
    for j in fb.switch_input:
        if j not in ss.switch_input:
            ss.switch_input.append(j)
        switch.append(ss.switch_input.index(j))
    feature = []
    for s, tau in fb.switch_feature:
        key = [switch[int(s)], float(tau)]
        if key not in ss.switch_feature:
            ss.switch_feature.append(key)
        feature.append(ss.switch_feature.index(key))
    nodes, trees = len(ss.node_left), len(ss.tree_root)
    ss.tree_root = list(ss.tree_root) + [nodes + int(r) for r in fb.tree_root]
    ss.node_feature = list(ss.node_feature) + [-1 if f < 0 else feature[f] for f in fb.node_feature]
    for k in ("node_left", "node_right"):
        setattr(ss, k, list(getattr(ss, k)) + [-1 if c < 0 else nodes + int(c)
                                                for c in getattr(fb, k)])
    ss.node_threshold = list(ss.node_threshold) + list(fb.node_threshold)
    ss.node_value = list(ss.node_value) + list(fb.node_value)
    ss.forest_trees = (list(ss.forest_trees) or [0]) + [trees + int(b) for b in fb.forest_trees[1:]]
    ss.forest_law = (list(ss.forest_law) or [0] * len(ss.forest_target)) + [
        laws + int(r) for r in fb.forest_law or [0] * len(fb.forest_target)]
    ss.forest_target = list(ss.forest_target) + list(fb.forest_target)
    ss.forest_weight = list(ss.forest_weight) + list(fb.forest_weight)
    ss.tree_depth = max(ss.tree_depth, fb.tree_depth)


def _merge_nets(ss, fb, laws: int, col, where: list) -> None:
    """``fb``'s networks appended to ``ss``'s, their inputs' sources and laws mapped onto the
    system's (its lags ``where``), every net's inputs and layer rows padded to the widest."""
    width = len(col)        # x's columns (the same in both: _holds)
    sources = [[-1 if q < 0 else int(col[q]) if q < width else width + where[q - width]
                for q in row] for row in fb.lstm_in]
    n = max(len(r) for r in [*ss.lstm_in, *sources])
    W = max(ss.lstm_width, fb.lstm_width)

    def padded(rows, value):
        return [list(r) + [value] * (n - len(r)) for r in rows]

    def wide(w_ih):
        w = np.asarray(w_ih, float)
        return np.pad(w, [(0, 0)] * (w.ndim - 1) + [(0, W - w.shape[-1])]).tolist() if len(w) else []

    ss.lstm_in = padded(ss.lstm_in, -1) + padded(sources, -1)
    ss.lstm_in_law = padded(ss.lstm_in_law, 0) + padded([[q + laws for q in r]
                                                         for r in fb.lstm_in_law], 0)
    ss.lstm_x_mean = padded(ss.lstm_x_mean, 0.0) + padded(fb.lstm_x_mean, 0.0)
    ss.lstm_x_scale = padded(ss.lstm_x_scale, 1.0) + padded(fb.lstm_x_scale, 1.0)
    ss.lstm_w_ih = wide(ss.lstm_w_ih) + wide(fb.lstm_w_ih)
    ss.lstm_law = list(ss.lstm_law) + [q + laws for q in fb.lstm_law]
    for k in ("lstm_target", "lstm_weight", "lstm_w_hh", "lstm_b_ih", "lstm_b_hh", "lstm_head",
              "lstm_head_bias", "lstm_y_scale"):
        setattr(ss, k, list(getattr(ss, k)) + list(getattr(fb, k)))
    ss.lstm_hidden, ss.lstm_layers, ss.lstm_width = fb.lstm_hidden, fb.lstm_layers, W
