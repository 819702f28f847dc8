r"""Scenario ``column_moving_source``: a machine column with a moving heat source.

After the FE case study of paper 002 (thermal mode shapes, POD monitoring):
a milling-machine column (k = 50 W/(m K), c = 500 J/(kg K)) with a fixed local
source Q1 (200 W steps, a motor or auxiliary unit), a source Q2 (250 W) that
moves with the vertical axis along the guideways (heat conducted from the
ram), a ±2 °C sinusoidal ambient of 24 h period, and -- in the test half only
-- a third local source Q3 that training never saw (for the monitoring of
issue 14's self-prediction error).  Temperatures and errors every 100 s.

As in the paper's FE model, the column has more deforming nodes than sensors:
10 levels of 0.25 m (2.5 m high) x 4 faces (front with the guideways, left,
right, back) + a base = 41 nodes, read by 19 structure sensors (+ the air), and
the thermoelastic map runs over every node, measured or not.  A face node is a
0.25 m strip of a 0.8 m wide, 0.1 m² wall: 100 kg, C = 5e4 J/K,
hA = 0.2 m² · 8 W/(m² K) = 1.6 W/K; vertical links k A / L = 50 · 0.1 / 0.25 =
20 W/K, corner links between neighbouring faces 50 · 0.03 / 0.4 = 3.75 W/K (front
and back face each other through the air: no link); each level-1 node sits on
the base (5e5 J/K, bed joint) through 15 W/K.

Sensors (unchanged names) keep their heights: ``T_<face>k`` is glued on the
upper node of the k-th 0.5 m band (level 2k, 0.5 k - 0.125 m), ``T_edgek`` between
the front and a side at that level; the odd levels, the whole back face and the
base are not measured.  Sensors read their node through a 1-min lag.
Q1 heats the left face over 0.5-1.0 m (levels 3-4); Q2 is shared by
:class:`~thermocomp.apps.sim.sources.MovingSource` between the two front nodes
around the axis position ``S_pos_Z`` (mm, written).  Q3 (200 W) is local: one
node, ``right_7`` (1.5-1.75 m), unmeasured, between the nodes of ``T_right3`` and
``T_right4`` (the truth's ``nearest_sensors``).  As in the paper, the sensors were
placed for the training field, so the new source sits near sensors, not on one
(on a 100 kg sensor node its 200 W would step the reading by 0.4 K in a sample).

Errors at the column top (µm/K of node rises, α = 11.5 µm/(m K), Δz = 0.25 m):
a level centred at height :math:`h` below the point :math:`P` tilts it by
:math:`\alpha\,\Delta z\,(P - h)/d` per kelvin of difference across the section:
E_Y front against back (depth d = 0.4 m), E_X left against right (width 0.8 m);
E_Z growth α Δz / 4 per face node, 6 µm/K for the base slab.  The same errors at the
guideways' mid-height (1.0 m, two levels below Q3's; paper 002 follows
several points of the column): ``E_X_mid``, ``E_Y_mid``, ``E_Z_mid``, moved by the
four levels below that point only.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse.csgraph import shortest_path

from thermocomp.apps.sim.ambient import DAY_S, SinusoidalAmbient
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.effects import intervals_signal
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan, Scenario
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning, MovingSource
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
from thermocomp.base.params import BOOLEAN, NON_NEGATIVE, POSITIVE, number, samples_in

SCENARIO = "column_moving_source"
FACES = ("front", "left", "right", "back")
RING = (("front", "left"), ("left", "back"), ("back", "right"), ("right", "front"))  # corner links
LEVELS = 10
LEVEL_M = 0.25
BANDS = 5                    # the sensors' 0.5 m bands: T_<face>k on level 2k
HEIGHT_M = LEVELS * LEVEL_M
DEPTH_M, WIDTH_M = 0.4, 0.8  # front-back, left-right
ALPHA = 11.5                 # µm/(m K)
POSITION = "S_pos_Z"
MID_M = 1.0   # height (m) of the second error point: guideways, top of level 4
Q1, Q2, Q3 = "_q1_on", "_q2_on", "_q3_on"
Q3_NODE = "right_7"


def node(face, level):
    return f"{face}_{level}"


def column_network() -> ThermalNetwork:
    nodes = [Node(node(f, k), 5.0e4, 1.6) for k in range(1, LEVELS + 1) for f in FACES]
    nodes.append(Node("base", 5.0e5, 10.0))
    links = []
    for k in range(1, LEVELS + 1):
        links += [Link(node(a, k), node(b, k), 3.75) for a, b in RING]
        if k < LEVELS:
            links += [Link(node(f, k), node(f, k + 1), 20.0) for f in FACES]
    links += [Link(node(f, 1), "base", 15.0) for f in FACES]
    return ThermalNetwork(nodes, links)


def thermoelastic_map() -> ThermoelasticMap:
    """Errors at the column top (``E_X``, ``E_Y``, ``E_Z``) and at the guideways' mid-height
    (``E_X_mid``, ``E_Y_mid``, ``E_Z_mid``, :data:`MID_M` above the base), over all nodes."""
    out, quadratic = {}, {}
    for suffix, point in (("", HEIGHT_M), ("_mid", MID_M)):
        ex, ey, ez = {}, {}, {"base": 6.0}   # the 0.5 m base slab lifts everything
        for k in range(1, LEVELS + 1):
            h = (k - 0.5) * LEVEL_M
            if h >= point:   # a level above the point does not move it
                continue
            tilt = ALPHA * LEVEL_M * (point - h)
            ey[node("front", k)], ey[node("back", k)] = tilt / DEPTH_M, -tilt / DEPTH_M
            ex[node("left", k)], ex[node("right", k)] = tilt / WIDTH_M, -tilt / WIDTH_M
            for f in FACES:
                ez[node(f, k)] = ALPHA * LEVEL_M / len(FACES)
        out.update({f"E_X{suffix}": ex, f"E_Y{suffix}": ey, f"E_Z{suffix}": ez})
        # the bed joint's nonlinearity tilts the column foot: its effect scales with the lever arm
        quadratic[f"E_Y{suffix}"] = {node("front", 1): 0.05 * (point - 0.5 * LEVEL_M)
                                     / (HEIGHT_M - 0.5 * LEVEL_M)}
    return ThermoelasticMap(out, quadratic=quadratic)


def heat_sources(q3_node=Q3_NODE):
    path = tuple(node("front", k) for k in range(1, LEVELS + 1))
    return [
        ConstantWhileRunning("Q1_fixed", {node("left", 3): 0.5, node("left", 4): 0.5}, power_W=200.0,
                             when=Q1),
        MovingSource("Q2_moving", {}, path=path,
                     positions_mm=tuple(1000.0 * (k - 0.5) * LEVEL_M for k in range(1, LEVELS + 1)),
                     signal=POSITION, when=Q2, power_W=250.0),
        ConstantWhileRunning("Q3_new", {q3_node: 1.0}, power_W=200.0, when=Q3),
    ]


def sensors():
    """One sensor per measured face and 0.5 m band (on level 2k), four between faces, one for the
    air (20); the odd levels, the back face and the base carry none."""
    rng = np.random.default_rng(2002)
    out = [TemperatureSensor(f"T_{f}{k}", {node(f, 2 * k): 1.0}, float(np.round(rng.uniform(-0.1, 0.1), 2)),
                             lag_s=60.0) for f in FACES[:3] for k in range(1, BANDS + 1)]
    for k in (1, 2, 4, 5):
        side = "right" if k % 2 else "left"
        out.append(TemperatureSensor(f"T_edge{k}", {node("front", 2 * k): 0.5, node(side, 2 * k): 0.5},
                                     float(np.round(rng.uniform(-0.1, 0.1), 2)), lag_s=60.0))
    out.append(TemperatureSensor("T_amb", {AMBIENT: 0.97, "base": 0.03}, 0.02, lag_s=120.0))
    return out


def nearest_sensors(target: str) -> list[str]:
    """The sensors whose node is fewest links away from node ``target`` (the first a local source
    there disturbs)."""
    network = column_network()
    adjacency = (network.loss_matrix != 0) & ~np.eye(network.n_nodes, dtype=bool)
    hops = shortest_path(adjacency.astype(float), unweighted=True, indices=network.index[target])
    measured = {x.column: hops[network.index[x.main_node]] for x in sensors() if x.main_node in network.index}
    return [c for c, h in measured.items() if h == min(measured.values())]


def machine_column() -> Machine:
    return Machine(column_network(), heat_sources(), sensors(), thermoelastic_map())


# The 0.5 m bands 2 and 3 of the former 5-level column are levels 3-6.
_MIDDLE = range(3, 7)
COLUMN_EFFECTS = {
    # A draught on the (unmeasured) base.
    "door": {"nodes": {"base": 40.0}, "air_offset_c": -8.0,
             "rate_per_h": 0.5, "duration_min": [10.0, 30.0], "targets": ["E_Z"]},
    "hidden_source": {"anchor": "base", "power_W": 400.0, "conductance_W_per_K": 10.0, "targets": ["E_Z"]},
    "lag_node": {"parent": node("front", 6), "capacity_J_per_K": 6.0e5, "conductance_W_per_K": 15.0,
                 "convection_W_per_K": 0.5, "sensitivity_um_per_K": {"E_Y": 10.0}, "targets": ["E_Y"]},
    "axis_position": {"axis": "Z", "travel_mm": [250.0, 2250.0], "home_mm": 1250.0,
                      "tilt_nodes": {**{node("left", k): 0.25 for k in _MIDDLE},
                                     **{node("right", k): -0.25 for k in _MIDDLE}},
                      "gain_um_per_K_per_m": 8.0, "targets": ["E_X"]},
    "sensor_drift": {"column": "T_front3", "rate_K_per_h": 0.1, "onset_fraction": 0.3, "splits": ["test"],
                     "targets": ["E_Y"]},
    "ambient_law": {"level_node": "ambient", "level_lag_h": 1.0, "threshold_c": 20.0, "gain": 0.5,
                    "targets": ["E_Y", "E_Z"]},
}


class ColumnMovingSource(Scenario):
    """Generator of the ``column_moving_source`` dataset: a training and a test load cycle.

    Parameters
    ----------
    train_hours, test_hours : float
    sample_period_s : float
        100 s, as the snapshots of paper 002.
    ambient_mean_c, ambient_amplitude_c : float
        Sinusoidal ambient (24 h); the test cycle shifts its phase and grows its amplitude by 25 %.
    q3 : bool
        Switch on the never-trained source Q3 in the second half of the test cycle.
    temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um : float
    effects, effect_params, clean, seed
        See :class:`~thermocomp.apps.sim.scenario.Scenario`.
    """

    name = SCENARIO
    param_rules = {**Scenario.param_rules, "train_hours": POSITIVE, "test_hours": POSITIVE,
                   "sample_period_s": POSITIVE, "ambient_mean_c": number(),
                   "ambient_amplitude_c": NON_NEGATIVE, "q3": BOOLEAN}

    def param_relations(self) -> list[tuple[str, str]]:
        return samples_in(self, ("train_hours", "test_hours"), "sample_period_s")

    def __init__(self, train_hours=40.0, test_hours=40.0, sample_period_s=100.0, ambient_mean_c=20.0,
                 ambient_amplitude_c=2.0, q3=True, temp_noise_c=0.02, temp_quantum_c=0.01,
                 error_noise_um=0.3, error_quantum_um=0.1, effects=(), effect_params=None, clean=False,
                 seed=0):
        self.train_hours = train_hours
        self.test_hours = test_hours
        self.sample_period_s = sample_period_s
        self.ambient_mean_c = ambient_mean_c
        self.ambient_amplitude_c = ambient_amplitude_c
        self.q3 = q3
        super().__init__(temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um, effects,
                         effect_params, clean, seed)

    def machine(self):
        return machine_column()

    def effect_defaults(self):
        return COLUMN_EFFECTS

    def _grid(self, t):
        return self.sample_period_s * round(t / self.sample_period_s)

    def _switching(self, rng, duration_s, on_h, off_h):
        out, t, on = [], self._grid(3600.0 * rng.uniform(0.5, 2.0)), True
        while t < duration_s:
            length = self._grid(3600.0 * rng.uniform(*(on_h if on else off_h)))
            if on:
                out.append((t, min(t + length, duration_s)))
            t, on = t + length, not on
        return out

    def _trajectory(self, rng, duration_s, speeds_mm_per_min):
        """Sweeps of the vertical axis between 250 and 2250 mm, speed changing per phase, dwells between."""
        t_grid = np.arange(0.0, duration_s + self.sample_period_s, self.sample_period_s)
        z = np.empty_like(t_grid)
        position, k, phase_end, speed, direction = 1250.0, 0, 0.0, speeds_mm_per_min[0], 1.0
        dwell = 0
        for i, t in enumerate(t_grid):
            if t >= phase_end:
                speed = float(speeds_mm_per_min[k % len(speeds_mm_per_min)])
                k += 1
                phase_end = t + 3600.0 * rng.uniform(2.0, 5.0)
            z[i] = position
            if dwell > 0:
                dwell -= 1
                continue
            position += direction * speed * self.sample_period_s / 60.0
            if not 250.0 <= position <= 2250.0:
                position = float(np.clip(position, 250.0, 2250.0))
                direction = -direction
                dwell = int(rng.integers(3, 20))
        return t_grid, np.round(z, 1)

    def plans(self, rng):
        plans = []
        for cid, split, child, hours, speeds, ambient in (
                ("train_cycle", "train", None, self.train_hours, (20.0, 60.0),
                 SinusoidalAmbient(self.ambient_mean_c, self.ambient_amplitude_c)),
                ("test_cycle", "test", None, self.test_hours, (10.0, 40.0, 90.0),
                 SinusoidalAmbient(self.ambient_mean_c + 0.5, 1.25 * self.ambient_amplitude_c,
                                   phase_rad=1.0))):
            child = rng.spawn(1)[0]
            duration = self._grid(3600.0 * float(hours))
            q1 = self._switching(child, duration, (2.0, 6.0), (2.0, 5.0))
            q2 = self._switching(child, duration, (3.0, 8.0), (1.0, 3.0))
            t_grid, z = self._trajectory(child, duration, speeds)
            q3 = ([(self._grid(0.5 * duration), self._grid(0.75 * duration))]
                  if (split == "test" and self.q3) else [])

            def position(t, t_grid=t_grid, z=z):
                k = np.searchsorted(t_grid, np.asarray(t) + 1e-6, side="right") - 1
                return z[np.clip(k, 0, len(z) - 1)]

            plans.append(CampaignPlan(
                cid=cid, split=split, start_s=DAY_S * 120 + 6 * 3600.0, duration_s=duration, rng=child,
                ambient=ambient, states={Q1: intervals_signal(q1), Q2: intervals_signal(q2),
                                         Q3: intervals_signal(q3), POSITION: position},
                written=(POSITION,), sample_period_s=float(self.sample_period_s), cooldown_s=3 * DAY_S,
                notes=f"{split} load cycle, {hours:g} h" + (", new source Q3 in the 2nd half" if q3 else ""),
                manifest={"duration_h": float(hours)},
                truth={"q1_on_s": [list(map(float, i)) for i in q1],
                       "q2_on_s": [list(map(float, i)) for i in q2],
                       "q3_on_s": [list(map(float, i)) for i in q3], "ambient_model": ambient.to_dict()}))
        return plans

    def truth_extra(self):
        if not self.q3:
            return {"novel_sources": []}
        return {"novel_sources": [{
            "name": "Q3_new", "split": "test", "node": Q3_NODE, "power_W": 200.0,
            "nearest_sensors": nearest_sensors(Q3_NODE),
            "description": "local source present only in the second half of the test cycle (never in "
                           "training): a monitoring target, not an undeclared effect a diagnosis can learn"}]}
