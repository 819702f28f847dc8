r"""Kinematic error model of a 3-axis machine (papers 000 and 001): TCP error from error parameters.

Each linear axis :math:`a` carries six error motions of its normalised position
:math:`\bar q = 2 (q - q_{min}) / (q_{max} - q_{min}) - 1`, each a sum of Legendre
polynomials,

.. math::

    E_{ka}(q) = \sum_n p_{ka n} L_n(\bar q), \qquad k \in \{X, Y, Z, A, B, C\},

named after ISO 230-1 with the order appended: ``E_XX1`` (positioning of X, order 1),
``E_ZX2`` (straightness of X in Z, order 2), ``E_AZ1`` (Z's rotation about X, order 1).
Translations are in µm, rotations in µm/m (µrad).  Orders: positioning 1..n, rotations
1..n, straightness 2..n; the three squareness errors are the order-1 straightness of the
axes after the first (``E_XY1``, ``E_XZ1``, ``E_ZY1``).  What is left out cannot be seen by
artefact distances: order 0 is a rigid offset, and the remaining order-1 straightness and
order-0 rotations are a rotation of the whole machine frame.  Optional column-ram cross
terms (paper 001, Eqs. 5-6) add ``E_YZ(y, z) = ȳ Σ b_n L_n(z̄)`` and
``E_AZ(y, z) = ȳ Σ c_n L_n(z̄)``, named ``E_YZY1``, ``E_YZY2``, ``E_AZY1``.

The chain is read tool to workpiece, ``tool-Y-Z-X-bed-workpiece`` (a moving column: X
carries Z carries Y carries the tool).  An axis on the tool side moves the tool by
:math:`+q`, one on the workpiece side moves the part by :math:`-q`, so the command is the
tool's position relative to the part either way.  Small-angle form (first order):

.. math::

    e = \sum_{a \in tool} (\delta_a + \varepsilon_a \times r_a)
      - \sum_{a \in part} (\delta_a + \varepsilon_a \times r'_a)

with :math:`r_a` the lever from axis :math:`a`'s carriage to the TCP (the positions of the
axes it carries plus the tool offset).  :meth:`KinematicModel.error` with ``form="htm"``
multiplies the full homogeneous transformation matrices instead (exact rotations); the two
differ by second-order terms only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre

AXES = "XYZ"
COMPONENTS = "XYZABC"          # three translations, three rotations (about X, Y, Z)
MICRO = 1e-3                   # µm/m (µrad) × mm -> µm
DEFAULT_CHAIN = "tool-Y-Z-X-bed-workpiece"
DEFAULT_RANGES = {"X": (0.0, 4000.0), "Y": (0.0, 1600.0), "Z": (0.0, 1600.0)}
# the kinds of parameter a design study perturbs (Parameter.kind, and the axes' squareness)
KINDS = ("positioning", "straightness", "squareness", "angular", "cross")
CROSS_TERMS = (("Y", "Z", "Y", (1, 2)), ("A", "Z", "Y", (1,)))   # paper 001: column-ram bending


@dataclass(frozen=True)
class Parameter:
    """One error parameter: ``component`` of ``axis``'s error motion, Legendre ``order``
    (in the axis' position, or in ``axis`` times ``by``'s position for a cross term)."""

    component: str
    axis: str
    order: int
    by: str = ""

    @property
    def name(self) -> str:
        return f"E_{self.component}{self.axis}{self.by}{self.order}"

    @property
    def angular(self) -> bool:
        return self.component in "ABC"

    @property
    def unit(self) -> str:
        return "µm/m" if self.angular else "µm"

    @property
    def kind(self) -> str:
        if self.by:
            return "cross"
        if self.angular:
            return "angular"
        return "positioning" if self.component == self.axis else "straightness"


def parse_chain(chain: str) -> tuple[list[str], list[str]]:
    """``(tool side, part side)``: the axes from the bed outwards on each side."""
    tokens = [t.strip() for t in str(chain).split("-")]
    if (len(tokens) != 6 or tokens[0] != "tool" or tokens[-1] != "workpiece" or "bed" not in tokens
            or sorted(t for t in tokens if t in AXES) != list(AXES)):
        raise ValueError(f"chain {chain!r}: expected tool-...-bed-...-workpiece with X, Y, Z once each "
                         f"(e.g. {DEFAULT_CHAIN!r})")
    bed = tokens.index("bed")
    return tokens[1:bed][::-1], tokens[bed + 1:-1]


def parameter_list(chain: str = DEFAULT_CHAIN, order: int = 2, cross_terms: bool = False) -> list[Parameter]:
    """The parameters of a model, in identification priority order (what is kept first when
    two parameters cannot be told apart)."""
    tool, part = parse_chain(chain)
    first = (tool + part)[0]       # the axis next to the bed defines the frame's x direction
    def motion(components):
        return [Parameter(c, a, n) for a in AXES for c in components
                for n in range(1 if c in "ABC" or c == a else 2, order + 1)]

    # squareness: order-1 straightness of the axes after the first, one per pair of axes; of
    # the four, the frame's rotation about the first axis removes one
    others = [a for a in AXES if a != first]
    square = [Parameter(c, a, 1) for a in others for c in AXES if c != a
              and not (a == others[1] and c == others[0])]
    # priority: translations, squareness, then rotations (a rotation the poses cannot tell from
    # a straightness or squareness is reported as the one not seen)
    out = motion("XYZ") + square + motion("ABC")
    if cross_terms:
        out += [Parameter(c, a, n, by) for c, a, by, orders in CROSS_TERMS for n in orders]
    return out


class KinematicModel:
    """TCP error of a 3-axis machine from its error parameters.

    Parameters
    ----------
    ranges : dict
        Axis -> (min, max) travel in mm (normalises the Legendre argument).
    chain : str
        Kinematic chain read tool to workpiece, e.g. ``tool-Y-Z-X-bed-workpiece``.
    tool : sequence of 3 floats
        Tool (probe) offset from the last tool-side carriage, mm.
    order : int
        Highest Legendre order of every error motion.
    cross_terms : bool
        Add the column-ram cross terms ``E_YZY*``, ``E_AZY*``.
    """

    def __init__(self, ranges=None, chain=DEFAULT_CHAIN, tool=(0.0, 0.0, -150.0), order=2,
                 cross_terms=False):
        self.ranges = {a: tuple(map(float, (ranges or DEFAULT_RANGES)[a])) for a in AXES}
        self.chain = chain
        self.tool = np.asarray(tool, float)
        self.order = int(order)
        self.cross_terms = bool(cross_terms)
        self.tool_side, self.part_side = parse_chain(chain)
        self.parameters = parameter_list(chain, self.order, self.cross_terms)
        self.names = [p.name for p in self.parameters]
        for a, (lo, hi) in self.ranges.items():
            if not hi > lo:
                raise ValueError(f"axis {a}: range {lo:g}..{hi:g} mm is empty")

    def to_dict(self) -> dict:
        return {"ranges": {a: list(r) for a, r in self.ranges.items()}, "chain": self.chain,
                "tool": self.tool.tolist(), "order": self.order, "cross_terms": self.cross_terms}

    @classmethod
    def from_dict(cls, d) -> KinematicModel:
        return cls(**{k: d[k] for k in ("ranges", "chain", "tool", "order", "cross_terms") if k in d})

    def normalised(self, positions) -> np.ndarray:
        """(n, 3) commanded positions (mm) -> Legendre arguments in [-1, 1] (beyond: extrapolated)."""
        q = np.asarray(positions, float)
        lo = np.array([self.ranges[a][0] for a in AXES])
        hi = np.array([self.ranges[a][1] for a in AXES])
        return 2.0 * (q - lo) / (hi - lo) - 1.0

    def motions(self, params, positions) -> np.ndarray:
        """Error motions ``(k, n, 3 axes, 6 components)`` of parameter rows ``params`` (k, p)."""
        p = np.atleast_2d(np.asarray(params, float))
        if p.shape[-1] != len(self.parameters):
            raise ValueError(f"expected {len(self.parameters)} parameters, got {p.shape[-1]}")
        qbar = self.normalised(positions)
        n = qbar.shape[0]
        vander = legendre.legvander(qbar, self.order + 1)           # (n, 3, order + 2)
        out = np.zeros((p.shape[0], n, 3, 6))
        for j, par in enumerate(self.parameters):
            ia, ic = AXES.index(par.axis), COMPONENTS.index(par.component)
            basis = vander[:, ia, par.order]
            if par.by:
                basis = basis * qbar[:, AXES.index(par.by)]
            out[:, :, ia, ic] += p[:, j, None] * basis[None, :]
        return out

    def _levers(self, positions):
        """Per axis, the lever (n, 3) from its carriage to the TCP, and its sign (+1 tool, -1 part)."""
        q = np.asarray(positions, float)
        unit = {a: np.eye(3)[AXES.index(a)] for a in AXES}
        levers = {}
        for i, a in enumerate(self.tool_side):
            carried = sum((q[:, [AXES.index(b)]] * unit[b] for b in self.tool_side[i + 1:]),
                          np.zeros_like(q))
            levers[a] = (carried + self.tool, 1.0)
        tool_point = sum((q[:, [AXES.index(b)]] * unit[b] for b in self.tool_side), np.zeros_like(q))
        tool_point = tool_point + self.tool
        for i, a in enumerate(self.part_side):
            # the part side carriage of `a` sits at -(q of the part axes up to and including a)
            carriage = -sum((q[:, [AXES.index(b)]] * unit[b] for b in self.part_side[:i + 1]),
                            np.zeros_like(q))
            levers[a] = (tool_point - carriage, -1.0)
        return levers

    def error(self, params, positions, form: str = "small") -> np.ndarray:
        """TCP error (µm): ``(n, 3)`` for one parameter vector, ``(k, n, 3)`` for rows (k, p).

        ``form="small"``: the first-order model (linear in the parameters); ``"htm"``: the full
        product of homogeneous transformation matrices.
        """
        single = np.asarray(params).ndim == 1
        m = self.motions(params, positions)
        if form == "htm":
            e = self._htm(m, np.asarray(positions, float))
        elif form == "small":
            e = np.zeros(m.shape[:2] + (3,))
            for a, (lever, sign) in self._levers(positions).items():
                ia = AXES.index(a)
                e += sign * (m[:, :, ia, :3] + MICRO * np.cross(m[:, :, ia, 3:], lever[None]))
        else:
            raise ValueError(f"form must be 'small' or 'htm', not {form!r}")
        return e[0] if single else e

    def basis(self, positions) -> np.ndarray:
        """``(n, 3, p)``: the small-angle model's TCP error per unit of each parameter."""
        eye = np.eye(len(self.parameters))
        return np.moveaxis(self.error(eye, positions), 0, -1)

    def _htm(self, m, q):
        """Exact transforms: tool point relative to the part, minus the command and the tool."""
        k, n = m.shape[:2]

        def transform(ia, sign):
            t = np.zeros((k, n, 4, 4))
            t[..., :3, :3] = _rotations(MICRO * 1e-3 * m[:, :, ia, 3:])   # µrad -> rad
            nominal = np.zeros((n, 3))
            nominal[:, ia] = sign * q[:, ia]
            t[..., :3, 3] = nominal[None] + 1e-3 * m[:, :, ia, :3]      # µm -> mm
            t[..., 3, 3] = 1.0
            return t

        tool = np.broadcast_to(np.eye(4), (k, n, 4, 4)).copy()
        for a in self.tool_side:
            tool = tool @ transform(AXES.index(a), 1.0)
        part = np.broadcast_to(np.eye(4), (k, n, 4, 4)).copy()
        for a in self.part_side:
            part = part @ transform(AXES.index(a), -1.0)
        point = tool @ np.append(self.tool, 1.0)
        relative = np.einsum("knij,knj->kni", np.linalg.inv(part), point)[..., :3]
        return 1e3 * (relative - q[None] - self.tool)                   # mm -> µm


def workspace_grid(model: KinematicModel, shape) -> np.ndarray:
    """``(n, 3)`` commands on a regular grid over the travel ranges, ``shape`` points along X, Y, Z."""
    axes = [np.linspace(*model.ranges[a], int(n)) for a, n in zip(AXES, shape)]
    return np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)


def _rotations(angles) -> np.ndarray:
    """``R = Rx(a) Ry(b) Rz(c)`` for angles ``(..., 3)`` in rad."""
    a, b, c = np.moveaxis(angles, -1, 0)
    ca, sa, cb, sb, cc, sc = np.cos(a), np.sin(a), np.cos(b), np.sin(b), np.cos(c), np.sin(c)
    r = np.empty(angles.shape[:-1] + (3, 3))
    r[..., 0, 0], r[..., 0, 1], r[..., 0, 2] = cb * cc, -cb * sc, sb
    r[..., 1, 0] = sa * sb * cc + ca * sc
    r[..., 1, 1] = -sa * sb * sc + ca * cc
    r[..., 1, 2] = -sa * cb
    r[..., 2, 0] = -ca * sb * cc + sa * sc
    r[..., 2, 1] = ca * sb * sc + sa * cc
    r[..., 2, 2] = ca * cb
    return r
