"""Heat sources and state-dependent convection.

A source computes one power from the machine state (a dict of ``S_`` values,
e.g. ``{"S_spindle_rpm": 6000.0}``) and the node temperatures, and spreads it
over nodes with fixed fractions.  A source whose split depends on the state (a
heat source that moves with an axis) overrides :meth:`HeatSource.distribution`.
A :class:`StateConvection` adds convection to a node as a function of a state
signal (a rotating shaft, an open door).  Equations and values:
:mod:`thermocomp.apps.sim.network`.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Callable, ClassVar, Mapping

import numpy as np

SPINDLE = "S_spindle_rpm"

TemperatureOf = Callable[[str], float]


@dataclass
class HeatSource:
    """Base class: ``power(state, temperature_of)`` W spread as ``split``.

    Parameters
    ----------
    name : str
    split : dict
        Node -> fraction of the power (fractions sum to 1).
    """

    name: str
    split: dict[str, float] = field(default_factory=dict)
    # Sources whose power depends on temperatures are re-evaluated every step;
    # the others only when the state changes.
    depends_on_temperature: ClassVar[bool] = False

    def power(self, state: Mapping[str, float], temperature_of: TemperatureOf) -> float:
        raise NotImplementedError

    def distribution(self, state: Mapping[str, float]) -> Mapping[str, float]:
        """Fractions of the power per node; constant here, state-dependent in subclasses."""
        return self.split

    def to_dict(self) -> dict:
        return {"kind": type(self).__name__, **asdict(self)}


@dataclass
class SpindleMotorLosses(HeatSource):
    """:math:`Q = q_0 + a\\,n_k + b\\,n_k^2` while running, :math:`n_k = n/1000` rpm.

    ``idle_W`` (fixed magnetising and drive losses), ``linear_W_per_krpm`` (iron
    and friction losses), ``quadratic_W_per_krpm2`` (windage, eddy currents).
    """

    idle_W: float = 25.0
    linear_W_per_krpm: float = 15.0
    quadratic_W_per_krpm2: float = 2.0

    def power(self, state, temperature_of):
        return _speed_losses(self, state.get(SPINDLE, 0.0))


def _speed_losses(motor, rpm: float) -> float:
    """:math:`q_0 + a\\,n_k + b\\,n_k^2` W of ``motor``'s coefficients (``idle_W``,
    ``linear_W_per_krpm``, ``quadratic_W_per_krpm2``) at ``rpm``, :math:`n_k = |n|/1000`; none at
    a standstill: the law of :class:`SpindleMotorLosses` and :class:`SpeedLosses`."""
    n_k = abs(rpm) / 1000.0
    if n_k == 0.0:
        return 0.0
    return motor.idle_W + motor.linear_W_per_krpm * n_k + motor.quadratic_W_per_krpm2 * n_k**2


@dataclass
class BearingFriction(HeatSource):
    """Palmgren friction power of a bearing set.

    .. math::

        Q = P_v\\,(n/n_{ref})^{5/3}\\,e^{-\\kappa (T_b - T_{ref})} + P_l\\,n/n_{ref}

    The viscous term scales as :math:`(\\nu n)^{2/3}\\cdot n`; with
    :math:`\\nu \\propto e^{-k_\\nu T}` the temperature factor has
    :math:`\\kappa = \\tfrac23 k_\\nu`.  ``bearing_node`` is the node whose
    temperature sets the oil viscosity.
    """

    depends_on_temperature: ClassVar[bool] = True

    viscous_W: float = 60.0
    load_W: float = 15.0
    reference_rpm: float = 6000.0
    speed_exponent: float = 5.0 / 3.0
    viscosity_coefficient_per_K: float = 0.02
    reference_temperature_c: float = 25.0
    bearing_node: str = "bearing_front"

    def power(self, state, temperature_of):
        ratio = abs(state.get(SPINDLE, 0.0)) / self.reference_rpm
        if ratio == 0.0:
            return 0.0
        stiffness = np.exp(-self.viscosity_coefficient_per_K
                           * (temperature_of(self.bearing_node) - self.reference_temperature_c))
        return float(self.viscous_W * ratio**self.speed_exponent * stiffness + self.load_W * ratio)


@dataclass
class ConstantWhileRunning(HeatSource):
    """``power_W`` while the state signal ``when`` is non-zero (feed drives during a test)."""

    power_W: float = 40.0
    when: str = SPINDLE

    def power(self, state, temperature_of):
        return self.power_W if state.get(self.when, 0.0) != 0.0 else 0.0


@dataclass
class StateConvection:
    """Extra convection :math:`\\Delta hA = g\\,(|s|/s_0)^p` (W/K) on ``node`` from state signal ``signal``.

    A rotating shaft is cooled by forced convection, :math:`h \\propto Re^{0.6}
    \\propto n^{0.6}`; an open door is ``p = 0`` with ``s`` in {0, 1}.
    """

    node: str
    gain_W_per_K: float
    signal: str = SPINDLE
    scale: float = 1000.0
    exponent: float = 0.6

    def extra(self, state: Mapping[str, float]) -> float:
        value = abs(state.get(self.signal, 0.0)) / self.scale
        return self.gain_W_per_K * value**self.exponent if value > 0 else 0.0

    def to_dict(self) -> dict:
        return {"kind": type(self).__name__, **asdict(self)}


class HeatInjector:
    """Sources bound to a network: node heat vector :math:`Q` (W) for a state.

    Parameters
    ----------
    network : ThermalNetwork
    sources : sequence of HeatSource
    """

    def __init__(self, network, sources):
        self.network = network
        self.sources = tuple(sources)
        for source in self.sources:
            unknown = set(source.split) - set(network.index)
            if unknown:
                raise ValueError(f"source {source.name!r} heats unknown nodes {sorted(unknown)}")
            if source.split and not np.isclose(sum(source.split.values()), 1.0):
                raise ValueError(f"source {source.name!r}: split fractions must sum to 1")
        self._thermal = [s for s in self.sources if s.depends_on_temperature]
        # Node columns of the fixed splits, so the per-step loop builds no arrays.
        self._fixed = {id(s): self._column(s.split) for s in self.sources
                       if type(s).distribution is HeatSource.distribution}
        self._cache: dict[tuple, np.ndarray] = {}

    def _column(self, fractions: Mapping[str, float]) -> np.ndarray:
        column = np.zeros(self.network.n_nodes)
        for node, fraction in fractions.items():
            column[self.network.index[node]] += fraction
        return column

    def powers(self, state: Mapping[str, float], temperature: np.ndarray) -> np.ndarray:
        """Power of each source (W), in the order of ``sources``."""
        return np.array([s.power(state, self._reader(temperature)) for s in self.sources])

    def _reader(self, temperature: np.ndarray) -> TemperatureOf:
        index = self.network.index
        return lambda node: temperature[index[node]]

    def _state_part(self, state: Mapping[str, float]) -> np.ndarray:
        """Heat of the temperature-independent sources (W per node), cached per state."""
        key = tuple(sorted(state.items()))
        if key not in self._cache:
            if len(self._cache) > 256:  # continuous states (axis positions) would grow it forever
                self._cache.clear()
            q = np.zeros(self.network.n_nodes)
            for source in self.sources:
                if not source.depends_on_temperature:
                    watts = source.power(state, None)
                    if watts:
                        q += watts * self._column(source.distribution(state))
            self._cache[key] = q
        return self._cache[key]

    def convection(self, state: Mapping[str, float], rules, air_movement: float = 1.0) -> np.ndarray:
        """Node convection :math:`hA` (W/K): nominal times ``air_movement`` plus the ``rules``' extra."""
        hA = air_movement * self.network.convection
        for rule in rules:
            hA[self.network.index[rule.node]] += rule.extra(state)
        return hA

    def parts(self, state: Mapping[str, float]) -> tuple[np.ndarray, list]:
        """Split the heat for a fixed ``state``: the temperature-independent node
        vector (W), and ``(source, node column)`` for the sources that must be
        re-evaluated at every step."""
        thermal = [(source, self._fixed.get(id(source), None)) for source in self._thermal]
        thermal = [(source, column if column is not None else self._column(source.distribution(state)))
                   for source, column in thermal]
        return self._state_part(state).copy(), thermal

    def heat(self, state: Mapping[str, float], temperature: np.ndarray) -> np.ndarray:
        """Node heat vector (W) for ``state`` and node temperatures (°C)."""
        q = self._state_part(state).copy()
        if self._thermal:
            read = self._reader(temperature)
            for source in self._thermal:
                watts = source.power(state, read)
                if watts:
                    column = self._fixed.get(id(source))
                    q += watts * (column if column is not None else self._column(source.distribution(state)))
        return q


@dataclass
class SpeedLosses(HeatSource):
    """:math:`Q = q_0 + a\\,n_k + b\\,n_k^2` of a motor on state ``signal`` (rpm) while it runs.

    :class:`SpindleMotorLosses` for any motor, e.g. the driven tools of a lathe.
    """

    signal: str = SPINDLE
    idle_W: float = 15.0
    linear_W_per_krpm: float = 8.0
    quadratic_W_per_krpm2: float = 1.0

    def power(self, state, temperature_of):
        return _speed_losses(self, state.get(self.signal, 0.0))


@dataclass
class MovingSource(HeatSource):
    """``power_W`` while ``when`` is on, deposited where an axis stands (paper 002's Q2).

    The path is a chain of nodes at positions ``positions_mm``; at position
    :math:`p` (state ``signal``) the power is shared linearly between the two
    nodes around it, so the heat moves smoothly along the guideway.
    """

    path: tuple = ()
    positions_mm: tuple = ()
    signal: str = "S_pos_Z"
    when: str = ""
    power_W: float = 250.0

    def power(self, state, temperature_of):
        return self.power_W if (not self.when or state.get(self.when, 0.0) != 0.0) else 0.0

    def distribution(self, state):
        p = float(np.clip(state.get(self.signal, self.positions_mm[0]), self.positions_mm[0],
                          self.positions_mm[-1]))
        k = int(np.clip(np.searchsorted(self.positions_mm, p, side="right") - 1, 0, len(self.path) - 2))
        w = (p - self.positions_mm[k]) / (self.positions_mm[k + 1] - self.positions_mm[k])
        return {self.path[k]: 1.0 - w, self.path[k + 1]: w}
