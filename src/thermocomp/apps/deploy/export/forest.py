"""The random forest of an ``arx_rf`` model as flat arrays the exported code walks (exportrest62).

:class:`~thermocomp.core.models.arx_rf.ARXRF` streams as its ARX (a linear law: :mod:`.laws`)
plus ``f(s(t))``, a forest on a machine state's switching signal: per time scale ``tau`` ``s =
expit(k (t - t0) / tau)``, ``t0`` the state's last change (``k`` +1 on, -1 off; the state itself
before its campaign's first change; a missing value holds it).  The code keeps, per state column
it tracks (``switch_input``), whether it is on and since when, computes each feature
(``switch_feature``: ``[switch, tau]``), and walks every tree of every forest in one table of
nodes (``node_feature``, ``node_threshold``, ``node_left``, ``node_right``, ``node_value``; a
leaf's ``left`` is -1), each tree from ``tree_root`` for at most ``tree_depth`` steps (a loop of
fixed length: a PLC's cycle time does not depend on the sample).  scikit-learn compares a
feature cast to float32 with the float64 threshold (``X.astype(float32) <= threshold``): so does
the code, or a feature on a threshold's float32 neighbour would take the other branch.  A
forest's value is the mean of its trees' leaves (``forest_trees``: forest ``f``'s trees are
``forest_trees[f]`` to ``forest_trees[f + 1] - 1``), added to its target's output times its
blend weight (``forest_target``, ``forest_weight``) and the factor of its ARX's law
(``forest_law``: an arx_rf within an ATI model, one per interval of the campaign's initial
ambient, counts in its interval only, exportati63; a forest that does not count is not walked),
in the measured channel only: the excess over the envelope does not reach it (the stream's
clamped copy reads the same state).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from dataclasses import fields as dataclass_fields

import numpy as np
from scipy.special import expit

NO_SWITCH = -1      # ARXRF state_column=None: the forest reads a constant 0


def is_forest(est) -> bool:
    """``est`` is an ``arx_rf`` model (its module is loaded when one was unpickled)."""
    module = sys.modules.get(__name__.split(".apps.")[0] + ".core.models.arx_rf")
    return module is not None and type(est) is module.ARXRF


@dataclass
class ForestArrays:
    """An arx_rf model's forests as fields of the exported system (module doc): declared once
    here, :class:`~.statespace.StateSpace` is made of them; all empty: none."""

    switch_input: list = field(default_factory=list)    # the states tracked (input; -1: none, 0)
    switch_feature: list = field(default_factory=list)  # [switch, tau] per feature
    switch_raw_time: bool = False     # the ramp's time: as read (else the stream's clock, now)
    forest_target: list = field(default_factory=list)
    forest_weight: list = field(default_factory=list)   # its blend weight
    # (n_forests,) the law whose factor the forest's value takes: its ARX's, whose factor is 1 in
    # its ATI interval of the campaign's initial ambient and 0 outside it (exportati63)
    forest_law: list = field(default_factory=list)
    forest_trees: list = field(default_factory=list)    # forest f: trees [f] .. [f + 1] - 1
    tree_root: list = field(default_factory=list)
    tree_depth: int = 0                                  # the longest walk, root to leaf
    node_feature: list = field(default_factory=list)
    node_threshold: list = field(default_factory=list)
    node_left: list = field(default_factory=list)       # -1: a leaf
    node_right: list = field(default_factory=list)
    node_value: list = field(default_factory=list)


def forest_arrays(ss) -> list[tuple[str, list, tuple, str]]:
    """The forests' constants of the exported code, ``(name, values, shape, kind)`` in the order
    both languages declare them (c.py, st.py: one list, each its own syntax); ``kind``: ``int``,
    ``index`` (a node or tree number: more than an ST INT counts) or ``real``."""
    nodes, nf, nt = len(ss.node_left), len(ss.switch_feature), len(ss.forest_target)
    trees = ss.forest_trees or [0]
    return [("SWITCH_INPUT", ss.switch_input, (len(ss.switch_input),), "int"),
            ("FEATURE_SWITCH", [f[0] for f in ss.switch_feature], (nf,), "int"),
            ("FEATURE_TAU", [f[1] for f in ss.switch_feature], (nf,), "real"),
            ("FOREST_TARGET", ss.forest_target, (nt,), "int"),
            ("FOREST_WEIGHT", ss.forest_weight, (len(ss.forest_weight),), "real"),
            ("FOREST_LAW", ss.forest_law or [0] * nt, (nt,), "int"),
            ("FOREST_TREES", trees, (len(trees),), "index"),
            ("TREE_ROOT", ss.tree_root, (len(ss.tree_root),), "index"),
            ("NODE_FEATURE", ss.node_feature, (nodes,), "int"),
            ("NODE_LEFT", ss.node_left, (nodes,), "index"),
            ("NODE_RIGHT", ss.node_right, (nodes,), "index"),
            ("NODE_THRESHOLD", ss.node_threshold, (nodes,), "real"),
            ("NODE_VALUE", ss.node_value, (nodes,), "real")]


class Forests(ForestArrays):
    """The forests of the exported code's targets, gathered as :func:`.laws.target_laws` meets
    them (module doc); :meth:`fields` are the :class:`~.statespace.StateSpace`'s."""

    def add(self, target: int, weight: float, est, inputs: list, law: int) -> None:
        """Forest of the fitted ARXRF ``est`` (weight ``weight`` in target ``target``'s blend),
        reading its state column among the code's ``inputs``, counting as law ``law`` does."""
        column = est.state_column
        switch = NO_SWITCH if column is None else inputs.index(column)
        if switch not in self.switch_input:
            self.switch_input.append(switch)
        s = self.switch_input.index(switch)
        taus = np.atleast_1d(np.asarray(est.tau_s, float)) if column is not None else [0.0]
        features = []
        for tau in taus:
            key = [s, float(tau)]
            if key not in self.switch_feature:
                self.switch_feature.append(key)
            features.append(self.switch_feature.index(key))
        if not self.forest_trees:
            self.forest_trees.append(0)
        for tree in (e.tree_ for e in est.forest_.estimators_):
            base = len(self.node_left)
            leaf = tree.children_left < 0
            self.tree_root.append(base)
            self.tree_depth = max(self.tree_depth, int(tree.max_depth))
            self.node_feature += [-1 if lf else features[f] for f, lf in zip(tree.feature, leaf)]
            self.node_threshold += [0.0 if lf else float(t) for t, lf in zip(tree.threshold, leaf)]
            self.node_left += [-1 if lf else base + int(c) for c, lf in zip(tree.children_left, leaf)]
            self.node_right += [-1 if lf else base + int(c) for c, lf in zip(tree.children_right, leaf)]
            self.node_value += [float(v) for v in tree.value[:, 0, 0]]
        self.forest_target.append(int(target))
        self.forest_weight.append(float(weight))
        self.forest_law.append(int(law))
        self.forest_trees.append(len(self.tree_root))

    def fields(self) -> dict:
        """The StateSpace's fields (none without a forest)."""
        if not self.forest_target:
            return {}
        return {f.name: getattr(self, f.name) for f in dataclass_fields(ForestArrays)}


class Switches:
    """The state columns' switching and the forests' values, in numpy (the :class:`Simulator`'s:
    the stream's :meth:`~thermocomp.core.models.arx_rf.ARXRF.stream_step`, all forests at once)."""

    def __init__(self, ss):
        self.ss = ss
        self.input = np.asarray(ss.switch_input, int)
        feature = np.asarray(ss.switch_feature, float).reshape(-1, 2)
        self.of, self.tau = feature[:, 0].astype(int), feature[:, 1]
        self.left, self.right = np.asarray(ss.node_left, int), np.asarray(ss.node_right, int)
        self.feature = np.asarray(ss.node_feature, int)
        self.threshold, self.value = (np.asarray(getattr(ss, k), float)
                                      for k in ("node_threshold", "node_value"))
        self.root = np.asarray(ss.tree_root, int)

    def step(self, v: np.ndarray, t: float, first: bool) -> np.ndarray:
        """Each forest's value at this sample (``v``: the inputs as the model reads them, a held
        state's missing value filled; ``t``: the time the model is given)."""
        on = np.where(self.input >= 0, v[np.maximum(self.input, 0)] > 0.5, False)
        if first:
            self.changed, self.t0 = np.zeros(len(on), bool), np.zeros(len(on))
        else:
            turned = on != self.on
            self.t0 = np.where(turned, t, self.t0)
            self.changed |= turned
        self.on = on
        k = np.where(on, 1.0, -1.0)[self.of]
        with np.errstate(divide="ignore", invalid="ignore"):     # (a tau of 0: no switch)
            ramp = expit(k * (t - self.t0[self.of]) / self.tau)
        s = self.features = np.where(self.changed[self.of], ramp, on[self.of].astype(float))
        s32 = s.astype(np.float32).astype(float)      # as scikit-learn's trees compare
        node = self.root.copy()
        for _ in range(self.ss.tree_depth):
            inner = self.left[node] >= 0
            go = s32[np.maximum(self.feature[node], 0)] <= self.threshold[node]
            node = np.where(inner, np.where(go, self.left[node], self.right[node]), node)
        leaves = self.value[node]
        bounds = self.ss.forest_trees
        return np.array([leaves[a:b].mean() for a, b in zip(bounds[:-1], bounds[1:])])
