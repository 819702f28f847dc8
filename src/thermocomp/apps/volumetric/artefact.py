"""A 1D ball array, its poses in the working volume, and the measurement set-up (``volumetric.json``).

The artefact (paper 001, Fig. 4): ``n_balls`` balls over ``length_mm``; with a misalignment
angle θ every other ball is set off the bar's axis by ``spacing · tan θ``, alternately
along the first and the second normal of the pose's frame (:meth:`Pose.frame`: balls
2, 6, 10, ... along v1, balls 4, 8, ... along v2; docs/data-format.md), so that the array
sees the volume's errors in more than one direction.  A pose places it: centre (mm,
commanded TCP coordinates) and a direction.  The position sets of paper 001: ``S1`` along
the three axes, ``S2`` the four volume diagonals, ``S3`` the six face diagonals, each
repeated at several X centres on a long X axis.

A distance column of a dataset is ``E_<pose>_B<i>_B<j>``: the measured minus the
calibrated distance between balls i and j (µm) in that pose.
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ...base.errors import closest
from ...base.params import (
    BOOLEAN,
    POSITIVE,
    Rule,
    check_values,
    integer,
    number,
    numbers,
    optional,
)
from .kinematics import AXES, KinematicModel

SETUP_FILE = "volumetric.json"
COLUMN = re.compile(r"^E_(?P<pose>[A-Za-z0-9]+)_B(?P<i>\d+)_B(?P<j>\d+)$")
POSITION_SETS = ("S1", "S2", "S3")


@dataclass
class BallArray:
    """Nominal ball centres of a 1D ball array in its own frame (bar along x), mm."""

    n_balls: int = 11
    length_mm: float = 1500.0
    misalignment_deg: float = 0.0

    def centres(self) -> np.ndarray:
        if self.n_balls < 2:
            raise ValueError(f"a ball array needs at least 2 balls, not {self.n_balls}")
        s = np.linspace(-self.length_mm / 2, self.length_mm / 2, self.n_balls)
        out = np.zeros((self.n_balls, 3))
        out[:, 0] = s
        offset = (s[1] - s[0]) * np.tan(np.radians(self.misalignment_deg))
        for k in range(1, self.n_balls, 2):          # every other ball, alternately across / up
            out[k, 1 + (k // 2) % 2] = offset
        return out


@dataclass
class Pose:
    """One placement of the artefact: centre (mm) and the bar's direction (any length)."""

    name: str
    centre: tuple
    direction: tuple

    def frame(self) -> np.ndarray:
        """Rows: the bar's unit direction u, ``v1 = u × e`` normalised (``e`` the machine axis of
        u's smallest component, the first on a tie) and ``v2 = u × v1``."""
        u = np.asarray(self.direction, float)
        u = u / np.linalg.norm(u)
        helper = np.eye(3)[np.argmin(np.abs(u))]
        v1 = np.cross(u, helper)
        v1 /= np.linalg.norm(v1)
        return np.vstack([u, v1, np.cross(u, v1)])

    def balls(self, array: BallArray) -> np.ndarray:
        """(n_balls, 3) nominal ball centres in machine coordinates (mm)."""
        return np.asarray(self.centre, float) + array.centres() @ self.frame()


def position_set(sets=POSITION_SETS, ranges=None, x_centres=(0.25, 0.75), tool=(0.0, 0.0, 0.0)) -> list[Pose]:
    """Poses of the sets ``S1`` (axes), ``S2`` (volume diagonals), ``S3`` (face diagonals) at each
    X centre (a fraction of the X travel), centred in Y and Z: in axis coordinates, where the
    kinematic model evaluates the errors (:func:`check_reach`), so a pose's centre, a tool point,
    is the axis position plus the ``tool`` offset (mm; the model's ``tool``)."""
    ranges = ranges or {a: (0.0, 1.0) for a in AXES}
    tool = np.broadcast_to(np.asarray(tool, float), (3,))
    directions = {
        "S1": [(1, 0, 0), (0, 1, 0), (0, 0, 1)],
        "S2": [(1, 1, 1), (1, 1, -1), (1, -1, 1), (1, -1, -1)],
        "S3": [(1, 1, 0), (1, -1, 0), (0, 1, 1), (0, 1, -1), (1, 0, 1), (1, 0, -1)],
    }
    unknown = [s for s in sets if s not in directions]
    if unknown:
        raise ValueError(f"unknown position set(s) {unknown}: use {list(directions)}")
    mid = {a: 0.5 * sum(ranges[a]) for a in AXES}
    poses = []
    for ix, fx in enumerate(x_centres):
        x = ranges["X"][0] + float(fx) * (ranges["X"][1] - ranges["X"][0])
        centre = tuple(float(c) for c in np.array([x, mid["Y"], mid["Z"]]) + tool)
        for s in sets:
            for k, d in enumerate(directions[s]):
                poses.append(Pose(f"{s}x{ix + 1}d{k + 1}", centre, d))
    return poses


def check_reach(model: KinematicModel, array: BallArray, poses: list[Pose],
                margin_mm: float = 1.0) -> None:
    """Every ball of every pose is reached within the machine's travel (a typed centre, or a bar
    longer than the volume, would be "measured" where no probe can go): a ValueError naming
    the pose, the ball and the axis.  The axes stand at the ball less the tool offset, where
    the kinematic model evaluates the errors (``identify.design``)."""
    lo = np.array([model.ranges[a][0] for a in AXES])
    hi = np.array([model.ranges[a][1] for a in AXES])
    for pose in poses:
        balls = pose.balls(array)
        axes = balls - model.tool
        out = (axes < lo - margin_mm) | (axes > hi + margin_mm)
        if out.any():
            k, a = np.argwhere(out)[0]
            # a ball hundreds of travels away is a unit, not a place: a lab's µm (or a bar in µm)
            far = abs(axes[k, a] - 0.5 * (lo[a] + hi[a])) > 100 * max(hi - lo)
            unit = (" (volumetric.json is in mm: the poses' centres, tool or artefact.length_mm "
                    "in µm? divide them by 1000)") if far else ""
            raise ValueError(f"pose {pose.name}: ball {k + 1} at {AXES[a]}={balls[k, a]:.6g} mm puts the "
                             f"{AXES[a]} axis at {axes[k, a]:.6g} mm (tool offset {model.tool[a]:g}), "
                             f"outside its travel {lo[a]:g}..{hi[a]:g} mm{unit}")


def pairs(n_balls: int) -> list[tuple[int, int]]:
    """Every ball pair (i < j), 1-based as in the column names."""
    return list(itertools.combinations(range(1, n_balls + 1), 2))


def column(pose: str, i: int, j: int) -> str:
    return f"E_{pose}_B{i:02d}_B{j:02d}"


@dataclass
class Setup:
    """What a volumetric dataset was measured with (``volumetric.json`` in the dataset folder).

    ``probing_um``: standard uncertainty of one probed ball centre per coordinate;
    ``ball_um``: of the artefact's calibrated ball centres per coordinate.
    """

    model: KinematicModel
    array: BallArray
    poses: list[Pose]
    probing_um: float = 0.5
    ball_um: float = 0.5

    def columns(self) -> list[str]:
        return [column(p.name, i, j) for p in self.poses for i, j in pairs(self.array.n_balls)]

    def to_dict(self) -> dict:
        return {"machine": self.model.to_dict(),
                "artefact": {"n_balls": self.array.n_balls, "length_mm": self.array.length_mm,
                             "misalignment_deg": self.array.misalignment_deg},
                "poses": [{"name": p.name, "centre": list(map(float, p.centre)),
                           "direction": list(map(float, p.direction))} for p in self.poses],
                "uncertainty_um": {"probing": self.probing_um, "ball": self.ball_um}}

    @classmethod
    def from_dict(cls, d: dict) -> Setup:
        """The set-up of ``volumetric.json`` (docs/data-format.md); a field outside its domain is
        a ``ValueError`` naming it (``artefact.n_balls='5': must be an integer >= 2``), and so is
        a key it does not know (a misspelt one would be read as its default)."""
        _check_setup(d)
        u = d.get("uncertainty_um", {})
        setup = cls(KinematicModel.from_dict(d["machine"]), BallArray(**d["artefact"]),
                    [Pose(p["name"], tuple(p["centre"]), tuple(p["direction"])) for p in d["poses"]],
                    float(u.get("probing", 0.5)), float(u.get("ball", 0.5)))
        check_reach(setup.model, setup.array, setup.poses)
        return setup


POINT = numbers(-math.inf, length=3)
UNCERTAINTY = number(0.0, 1000.0)    # µm: beyond a millimetre the distances say nothing
# The longest machine tools travel tens of metres: a travel of kilometres is a set-up written in
# µm, consistent within itself, so it passed and scaled every angular error by 1/1000 (µm/m)
MAX_TRAVEL_MM = 100_000.0
TRAVEL = Rule(lambda v: numbers(-math.inf, length=2)(v) and 0 < v[1] - v[0] <= MAX_TRAVEL_MM,
              f"a travel [min, max] in mm, min < max, at most {MAX_TRAVEL_MM:,.0f} mm apart (100 m: "
              "a set-up in µm? volumetric.json is in mm)")
# A 1D ball bar: n (n - 1) / 2 distances per pose are identified at once; 100 balls is already
# 4950 per pose (a typo of 10^9 balls exhausted the memory instead of being refused)
MAX_BALLS = 100
SETUP_RULES = {
    "machine": {"order": optional(integer(1, 10)), "tool": POINT,
                "cross_terms": optional(BOOLEAN)},
    "artefact": {"n_balls": integer(2, MAX_BALLS), "length_mm": POSITIVE,
                 "misalignment_deg": optional(number(-90.0, 90.0, open_lo=True, open_hi=True))},
    "uncertainty_um": {"probing": optional(UNCERTAINTY), "ball": optional(UNCERTAINTY)},
}
KEYS = {"": ("machine", "artefact", "poses", "uncertainty_um"),
        "machine": ("ranges", "chain", "tool", "order", "cross_terms"),
        "machine.ranges": AXES,
        "artefact": ("n_balls", "length_mm", "misalignment_deg"),
        "uncertainty_um": ("probing", "ball"),
        "poses": ("name", "centre", "direction")}
POSE_RULES = {"name": Rule(lambda v: isinstance(v, str) and re.fullmatch(r"[A-Za-z0-9]+", v),
                           "letters and digits"),
              "centre": POINT, "direction": numbers(-math.inf, length=3)}


def _check_keys(d: Mapping, part: str, where: str | None = None) -> None:
    """Refuse a key ``part`` does not have, naming the closest valid one: misspelt, it was
    ignored and its default used (``uncertainty`` for ``uncertainty_um``)."""
    valid = list(KEYS[part])
    for key in d:
        if key not in valid:
            close = closest(key, valid)
            hint = f"did you mean {close[0]!r}? " if close else ""
            path = f"{where or part}.{key}" if where or part else str(key)
            raise ValueError(f"{path}: unknown key; {hint}valid keys: {', '.join(valid)}")


def _check_geometry(machine: Mapping) -> None:
    """The travel and the probe offset have no default that could be right for a measured
    machine (a wrong travel rescales every Legendre argument): both must be given."""
    for key, what in (("ranges", "X, Y, Z travel [min, max] in mm"), ("tool", "probe offset, mm")):
        if key not in machine:
            raise ValueError(f"machine.{key}: missing (the {what})")
    ranges = machine["ranges"]
    if not isinstance(ranges, Mapping):
        raise ValueError("machine.ranges: must be an object of X, Y, Z travels")
    _check_keys(ranges, "machine.ranges")
    for axis in AXES:
        if axis not in ranges:
            raise ValueError(f"machine.ranges.{axis}: missing (a travel [min, max], mm)")
    check_values(ranges, dict.fromkeys(AXES, TRAVEL), "machine.ranges")


def _check_setup(d) -> None:
    """Each field of a set-up read from outside against its rule (the kinematic model checks
    its chain itself)."""
    if not isinstance(d, Mapping):
        raise ValueError(f"expected an object with {', '.join(SETUP_RULES)} and poses")
    _check_keys(d, "")
    for part, rules in SETUP_RULES.items():
        if part == "uncertainty_um" and part not in d:
            continue
        if not isinstance(d.get(part), Mapping):
            raise ValueError(f"{part}: missing or not an object")
        _check_keys(d[part], part)
        if part == "machine":
            _check_geometry(d[part])
        check_values(d[part], rules, part)
    poses = d.get("poses")
    if not isinstance(poses, list) or not poses:
        raise ValueError("poses: must be a non-empty list")
    names = set()
    for k, pose in enumerate(poses):
        where = f"poses[{k}]"
        if not isinstance(pose, Mapping):
            raise ValueError(f"{where}: not an object")
        _check_keys(pose, "poses", where)
        check_values(pose, POSE_RULES, where)
        if not np.linalg.norm(np.asarray(pose["direction"], float)) > 0:
            raise ValueError(f"{where} ({pose['name']}).direction={list(pose['direction'])}: "
                             "must not be zero")
        if pose["name"] in names:
            raise ValueError(f"{where}.name={pose['name']!r}: declared twice")
        names.add(pose["name"])
