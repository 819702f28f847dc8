r"""Lumped-capacitance thermal network: the core of the digital twin.

The machine is a set of lumped masses (nodes) that exchange heat with each
other through conductances, with the workshop air through convection, and
receive heat from sources that depend on the machine state.  The same
equations serve every scenario; a scenario is data (nodes, links, sources,
convection rules, sensors, thermoelastic map).  This docstring collects them
with the parameter values of the v1 machine (:mod:`thermocomp.apps.sim.vmc`, a
3-axis VMC after Wei et al., Sensors 22:5085, 2022).

Node balance
------------
For node :math:`i` with heat capacity :math:`C_i` (J/K), conductances
:math:`G_{ij}` (W/K) to its neighbours, convection :math:`h_iA_i` (W/K) to the
air at :math:`T_a(t)` and heat input :math:`Q_i(t)` (W):

.. math::

    C_i \frac{dT_i}{dt} = \sum_j G_{ij}(T_j - T_i) + h_iA_i\,(T_a - T_i) + Q_i(t)

In matrix form :math:`C\dot T = -LT + g\,T_a + Q` with
:math:`L = \mathrm{Laplacian}(G) + \mathrm{diag}(hA)` and :math:`g = hA`, i.e.
:math:`\dot T = AT + Bu`, :math:`A = -C^{-1}L`,
:math:`B = C^{-1}[\,g \mid I\,]`, :math:`u = (T_a, Q_1, \dots, Q_n)`.
Because :math:`L\mathbf 1 = g`, the steady state is
:math:`T^* = T_a\mathbf 1 + L^{-1}Q`: the rise over ambient is linear in the
heat (twice the heat, twice the rise).  :math:`A` is similar to the symmetric
:math:`-C^{-1/2}LC^{-1/2}`, so its eigenvalues are real and negative and
:math:`-1/\lambda_k` are the modal time constants.

Integration
-----------
Inputs are held over an internal step :math:`\Delta` (the sample period cut
into equal steps of at most 30 s: 30 s for 5-min sampling; 10 min during the
cool-down), over which the solution is exact:

.. math::

    \exp\left(\begin{bmatrix} A & B \\ 0 & 0 \end{bmatrix}\Delta\right)
    = \begin{bmatrix} \Phi & \Gamma \\ 0 & I \end{bmatrix}, \qquad
    T_{k+1} = \Phi T_k + \Gamma u_k .

:math:`\Phi, \Gamma` are computed once per step size and convection vector
(:meth:`ThermalNetwork.propagator`), so the stiff network (3 min for a
bearing, 6 h for the bed) is stable and fast.  The air input of a step is the
mean of its end values.  Heat inputs are evaluated at the step start: the only
explicit part is the viscosity feedback of bearing friction, whose gain
(< 2 W/K) is small against the ~22 W/K that drain the bearing node.

Heat sources (:mod:`thermocomp.apps.sim.sources`), spindle speed :math:`n`
--------------------------------------------------------------------
* Spindle motor: :math:`Q_m = q_0 + a\,n_k + b\,n_k^2`, :math:`n_k = n/1000`
  (fixed magnetising/drive losses, iron and friction losses, windage and eddy
  losses); :math:`q_0` = 25 W, :math:`a` = 15 W/krpm, :math:`b` = 2 W/krpm²:
  63 / 117 / 187 W at 2000 / 4000 / 6000 rpm, 1-2 % of a 7.5-11 kW motor's
  rating at idle.  75 % heats the stator and housing, 25 % the rotor and,
  through the coupling, the spindle shaft.
* Bearing friction (Palmgren): viscous torque :math:`\propto (\nu n)^{2/3}`,
  so power :math:`\propto \nu^{2/3} n^{5/3}`, plus a load (preload) term
  :math:`\propto n`.  With :math:`\nu \propto e^{-0.03\,T}` (spindle oil),
  :math:`Q_b = P_v (n/n_{ref})^{5/3} e^{-0.02\,(T_b - 25)} + P_l\, n/n_{ref}`,
  :math:`n_{ref}` = 6000 rpm.  Front set: :math:`P_v` = 60 W, :math:`P_l` = 15 W
  (75 W at 6000 rpm, 15 W at 2000 rpm); rear bearing 25 W and 6 W.  80 % heats
  the outer ring and housing, 20 % the shaft.  A cold machine runs stiffer oil,
  makes more heat and grows more: one reason for the larger Z error at low
  ambient.
* Feed drives: the table reciprocates in X/Y during the ISO 230-3 test
  (1500 mm/min): 40 W while the spindle runs, 40 % table, 40 % bed, 20 % column
  front (ball screws, guideways, servo motors).

Totals: 124 W at 2000 rpm, 333 W at 6000 rpm; the hottest node then rises
6-17 K in 4-8 h, the 5.9-16.8 K reported for the Vcenter-55.

Nodes of the v1 machine (C = m·460 J/(kg K), hA = area × 5-10 W/(m² K))
-----------------------------------------------------------------------
=============  =======  ========  ==========================================
node           C (J/K)  hA (W/K)  why
=============  =======  ========  ==========================================
motor          2.0e4    6         ~45 kg, finned housing with its fan
spindle_shaft  1.15e4   1 (+)     ~25 kg steel shaft, little exposed surface
bearing_front  4.0e3    1 (+)     bearing set and inner housing, ~9 kg
bearing_rear   2.5e3    0.5       single rear bearing and housing, ~5 kg
headstock      1.4e5    12        ~300 kg cast iron, ~2 m²
column_front   3.2e5    8         front half of a ~1.4 t column, inside the
                                  enclosure (calm air)
column_back    3.2e5    25        back half, ribbed, open to the shop
bed            1.15e6   30        ~2.5 t, ~6 m²
table          1.4e5    6         ~300 kg, ~1 m²
=============  =======  ========  ==========================================

(+) A rotating shaft drags air: :math:`\Delta hA = g (n/1000)^{0.6}` with
:math:`g` = 1.5 W/K (shaft) and 0.5 W/K (front bearing, labyrinth), since
:math:`h \propto Re^{0.6}` (:class:`~thermocomp.apps.sim.sources.StateConvection`).
A campaign-wide factor scales all nominal :math:`hA` for the air movement of
the day (gates and fans in summer, draughts): see
:mod:`thermocomp.apps.sim.yearround`.

Links (W/K): motor-shaft 3 (coupling, rotor), motor-headstock 8 (flange),
shaft-bearing_front 6 and shaft-bearing_rear 4 (through rolling elements),
bearing_front-headstock 15 and bearing_rear-headstock 8 (press fits),
headstock-column_front 20 (Z guideways, slide and screw), column_front-column_back
20 (ribbed cast wall, k ≈ 50 W/(m K)), column-bed 10 each (bolted joint),
bed-table 5 (X/Y guideways).  Local time constants
:math:`C_i/(\sum_j G_{ij} + h_iA_i)`: bearings 3 min, shaft 14 min, motor
20 min, headstock 37 min, column 1.5 h, table 3.5 h, bed 6 h.

Ambient (:mod:`thermocomp.apps.sim.ambient`)
---------------------------------------
:math:`T_a = \bar T - A_y\cos(2\pi(d - d_{cold})/365) + A_d\cos(2\pi(h -
h_{peak})/24) + \delta(t)`: daily means from 5 °C (mid-January) to 32 °C
(mid-July), the paper's unheated hall (:math:`\bar T` = 18.5, :math:`A_y` =
13.5 °C); a ±3 °C day/night swing peaking at 15:00; :math:`\delta` an
Ornstein-Uhlenbeck drift (s.d. 0.4 °C, 12 h) for weather and neighbours.
Each campaign follows a 2-day rest in this air, so it starts near equilibrium
with the heavy castings lagging the daily swing.

Thermoelastic map (:mod:`thermocomp.apps.sim.thermoelastic`)
-------------------------------------------------------
Errors (µm) relative to the start from node rises :math:`\Delta_j = T_j -
T_j(0)` and start levels :math:`\theta_j = T_j(0) - 20` °C:

.. math::

    E_t = \sum_j s_{tj}\left[\Delta_j - \beta_t\left(\theta_j\Delta_j
          + \tfrac12\Delta_j^2\right)\right] + \sum_j q_{tj}\Delta_j^2

i.e. :math:`\int s_{tj}(1-\beta_t(T-20))\,dT`: sensitivities fall slowly as the
structure warms (fits and preloads loosen; :math:`\beta_Y` = 0.015,
:math:`\beta_Z` = 0.02 per K), so a cold machine shows more growth per kelvin
and the law changes with the ambient level, which a model of rises alone
cannot see.  Sensitivities are :math:`\alpha L` with α ≈ 11 µm/(m K):

* ``E_X``: motor +0.5 (off-centre motor), headstock -0.3, table +0.8 (X screw).
* ``E_Y``: headstock +3.5 (~320 mm from column face to spindle axis); column
  front -12, back +12 (bending of a 1.2 m column, 0.6 m deep:
  :math:`\alpha L^2/2d`); :math:`q` = 0.05 µm/K² on the headstock.
* ``E_Z``: shaft +2.0 (nose overhang ahead of the fixed front bearing),
  headstock +3.0 (~270 mm Z nut to front bearing), front bearing +0.8 (ring
  growth and preload), column front and back -3.0 each (column growth lifts
  the head), table +1.0 and bed +2.0 (lift the part); :math:`q` = 0.04 µm/K²
  on the front bearing (preload rises with temperature).

At 6000 rpm E_Z reaches 30-80 µm, E_Y 10-25 µm, E_X 5-10 µm.

Sensors (:mod:`thermocomp.apps.sim.sensors`)
---------------------------------------
A Pt100 glued or magnet-mounted on a housing sits between lumps and behind a
contact resistance: :math:`\tau_s\dot y_s = \sum_j w_{sj}T_j - y_s`
(:math:`\tau_s` = 8 min on housings, 2 min in air), reading
:math:`T_s = \mathrm{round}_q(y_s + o_s + \varepsilon)`,
:math:`\varepsilon \sim N(0, \sigma_T^2)`, :math:`\sigma_T` = 0.03 °C,
:math:`q` = 0.01 °C (0.1 °C in the paper), calibration offset
:math:`|o_s|` <= 0.1 °C.  Layout of the paper: five on the front-bearing area
(T1-T5), two on the motor, two on the spindle box, one on the frame for the
air.  Shaft, column, bed and table are unmeasured.  Errors get
:math:`N(0, \sigma_E^2)`, :math:`\sigma_E` = 0.4 µm, 0.1 µm quantum.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm


@dataclass(frozen=True)
class Node:
    """A lumped mass.

    Parameters
    ----------
    name : str
        Identifier used by links, sources, sensors and the thermoelastic map.
    capacity : float
        Heat capacity :math:`C = m c_p` in J/K.
    convection : float
        Heat transfer to the ambient air :math:`hA` in W/K.
    """

    name: str
    capacity: float
    convection: float = 0.0


@dataclass(frozen=True)
class Link:
    """A conductance ``conductance`` (W/K) between nodes ``a`` and ``b``."""

    a: str
    b: str
    conductance: float


@dataclass(frozen=True)
class Propagator:
    """Exact one-step map :math:`T_{k+1} = \\Phi T_k + \\gamma_a T_a + \\Gamma_Q Q`."""

    step_s: float
    phi: np.ndarray
    gamma_ambient: np.ndarray
    gamma_heat: np.ndarray

    def step(self, temperature: np.ndarray, ambient: float, heat: np.ndarray) -> np.ndarray:
        """Advance node temperatures (°C) by one step with constant inputs."""
        return self.phi @ temperature + self.gamma_ambient * ambient + self.gamma_heat @ heat


class ThermalNetwork:
    """Nodes, links and convection as a linear state-space model.

    Parameters
    ----------
    nodes : sequence of Node
    links : sequence of Link

    Notes
    -----
    See the module docstring for the equations.  Every node must be connected
    (directly or through links) to the ambient, otherwise :math:`L` is singular
    and the machine would have no steady state.
    """

    def __init__(self, nodes, links):
        self.nodes = tuple(nodes)
        self.links = tuple(links)
        self.names = tuple(n.name for n in self.nodes)
        if len(set(self.names)) != len(self.names):
            raise ValueError(f"duplicate node names in {self.names}")
        self.index = {name: i for i, name in enumerate(self.names)}
        for node in self.nodes:
            if node.capacity <= 0 or node.convection < 0:
                raise ValueError(f"node {node.name!r}: capacity must be > 0, convection >= 0")
        for link in self.links:
            if link.a not in self.index or link.b not in self.index or link.a == link.b:
                raise ValueError(f"link {link.a!r}-{link.b!r} must join two different known nodes")
            if link.conductance <= 0:
                raise ValueError(f"link {link.a!r}-{link.b!r}: conductance must be > 0")
        self.capacity = np.array([n.capacity for n in self.nodes], dtype=float)
        self.convection = np.array([n.convection for n in self.nodes], dtype=float)
        self.loss_matrix = self._loss_matrix()
        if np.linalg.matrix_rank(self.loss_matrix) < len(self.nodes):
            raise ValueError("some nodes have no heat path to the ambient")
        self._propagators: dict[tuple, Propagator] = {}

    @property
    def n_nodes(self) -> int:
        return len(self.nodes)

    def _loss_matrix(self, convection: np.ndarray | None = None) -> np.ndarray:
        """:math:`L = \\mathrm{Laplacian}(G) + \\mathrm{diag}(hA)` in W/K (``hA`` defaults to nominal)."""
        loss = np.diag(self.convection if convection is None else np.asarray(convection, dtype=float))
        for link in self.links:
            i, j = self.index[link.a], self.index[link.b]
            loss[i, i] += link.conductance
            loss[j, j] += link.conductance
            loss[i, j] -= link.conductance
            loss[j, i] -= link.conductance
        return loss

    def state_matrices(self, convection: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """:math:`A = -C^{-1}L` (1/s) and :math:`B = C^{-1}[hA \\mid I]` for :math:`u = (T_a, Q)`.

        ``convection`` replaces the nominal :math:`hA` vector (W/K), e.g. for a
        rotating spindle or an open door.
        """
        hA = self.convection if convection is None else np.asarray(convection, dtype=float)
        inv_c = 1.0 / self.capacity
        a = -inv_c[:, None] * self._loss_matrix(hA)
        b = np.column_stack([inv_c * hA, np.diag(inv_c)])
        return a, b

    def propagator(self, step_s: float, convection: np.ndarray | None = None) -> Propagator:
        """Exact discretisation for inputs held over ``step_s`` seconds.

        Cached per (step, convection vector): a machine visits few distinct
        states (a handful of speeds, door open/closed), so each ``expm`` runs once.
        """
        hA = self.convection if convection is None else np.asarray(convection, dtype=float)
        key = (float(step_s), hA.tobytes())
        if key not in self._propagators:
            step_s = float(step_s)
            a, b = self.state_matrices(hA)
            n, m = b.shape
            augmented = np.zeros((n + m, n + m))
            augmented[:n, :n] = a
            augmented[:n, n:] = b
            exp = expm(augmented * step_s)
            gamma = exp[:n, n:]
            self._propagators[key] = Propagator(step_s, exp[:n, :n], gamma[:, 0], gamma[:, 1:])
        return self._propagators[key]

    def heat_vector(self, heat: dict[str, float]) -> np.ndarray:
        """Node heat inputs (W) from a ``{node: watts}`` mapping."""
        q = np.zeros(self.n_nodes)
        for name, watts in heat.items():
            q[self.index[name]] += watts
        return q

    def steady_state(self, ambient: float, heat: np.ndarray) -> np.ndarray:
        """Steady node temperatures :math:`T_a + L^{-1}Q` (°C) for constant inputs."""
        return ambient + np.linalg.solve(self.loss_matrix, np.asarray(heat, dtype=float))

    def local_time_constants(self) -> dict[str, float]:
        """:math:`C_i / (\\sum_j G_{ij} + h_iA_i)` in s: how fast a node follows its surroundings."""
        drain = np.diag(self.loss_matrix)
        return {name: float(c / d) for name, c, d in zip(self.names, self.capacity, drain)}

    def modal_time_constants(self) -> np.ndarray:
        """Time constants :math:`-1/\\lambda_k` of the network's modes in s, ascending."""
        a, _ = self.state_matrices()
        return np.sort(-1.0 / np.linalg.eigvals(a).real)

    def to_dict(self) -> dict:
        """JSON-serialisable parameters (for the ground truth)."""
        return {
            "nodes": {n.name: {"capacity_J_per_K": n.capacity, "convection_hA_W_per_K": n.convection}
                      for n in self.nodes},
            "links": [{"a": link.a, "b": link.b, "conductance_W_per_K": link.conductance}
                      for link in self.links],
            "local_time_constants_s": self.local_time_constants(),
        }
