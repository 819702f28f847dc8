"""Thermoelastic map: node temperatures -> TCP displacement errors (µm).

For target :math:`t` (``E_X``, ``E_Y``, ``E_Z`` ...), node rises
:math:`\\Delta_j = T_j - T_j(0)` and start levels :math:`\\theta_j = T_j(0) - T_{ref}`:

.. math::

    E_t = \\sum_j s_{tj}\\Big[\\Delta_j - \\beta_t\\big(\\theta_j\\Delta_j
          + \\tfrac12\\Delta_j^2\\big)\\Big] + \\sum_j q_{tj}\\Delta_j^2

The bracket is :math:`\\int_{T_j(0)}^{T_j} (1 - \\beta_t (T - T_{ref}))\\,dT`: the
sensitivity :math:`s_{tj}` (µm/K) holds at :math:`T_{ref}` and falls by
:math:`\\beta_t` per kelvin of absolute temperature, so the law changes with the
ambient level.  :math:`q_{tj}` (µm/K²) are small nonlinear terms.  The error is
zero at the start by construction, as after zeroing the probes.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class ThermoelasticMap:
    """Sensitivities per target and node.

    Parameters
    ----------
    linear : dict
        Target -> {node: s (µm/K)} at ``reference_c``.
    quadratic : dict
        Target -> {node: q (µm/K²)}.
    ambient_beta : dict
        Target -> β (1/K), the relative fall of all its sensitivities per kelvin.
    reference_c : float
        Temperature (°C) at which ``linear`` holds.
    """

    linear: dict
    quadratic: dict = field(default_factory=dict)
    ambient_beta: dict = field(default_factory=dict)
    reference_c: float = 20.0

    @property
    def targets(self) -> list[str]:
        return list(self.linear)

    def _matrix(self, coefficients: dict, node_index: dict) -> np.ndarray:
        m = np.zeros((len(self.targets), len(node_index)))
        for row, target in enumerate(self.targets):
            for node, value in coefficients.get(target, {}).items():
                m[row, node_index[node]] = value
        return m

    def errors(self, node_temperatures: np.ndarray, node_index: dict) -> np.ndarray:
        """True errors (samples x targets, µm) for node temperatures (samples x nodes, °C)."""
        temps = np.asarray(node_temperatures, dtype=float)
        rise = temps - temps[0]
        level = temps[0] - self.reference_c
        s = self._matrix(self.linear, node_index)
        q = self._matrix(self.quadratic, node_index)
        beta = np.array([self.ambient_beta.get(t, 0.0) for t in self.targets])
        errors = rise @ s.T + (rise**2) @ q.T
        # The beta term per target: sum_j s_tj (theta_j rise_j + rise_j^2 / 2).
        errors -= beta * ((rise * level + 0.5 * rise**2) @ s.T)
        return errors

    def to_dict(self) -> dict:
        return {
            "reference_temperature_c": self.reference_c,
            "linear_um_per_K": self.linear,
            "quadratic_um_per_K2": self.quadratic,
            "ambient_beta_per_K": self.ambient_beta,
            "formula": "E_t = sum_j s_tj*(d_j - beta_t*(theta_j*d_j + d_j**2/2)) + sum_j q_tj*d_j**2; "
                       "d_j = T_j - T_j(0), theta_j = T_j(0) - reference",
        }
