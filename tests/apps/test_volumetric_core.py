"""The volumetric core: kinematics (small-angle vs HTM, chains, linearity), artefact
calibration round trip and identifiability by name."""

from __future__ import annotations

import numpy as np
import pytest

from thermocomp.apps.volumetric import (
    ArtefactCalibration,
    BallArray,
    KinematicModel,
    Pose,
    Setup,
    position_set,
)
from thermocomp.apps.volumetric.artefact import pairs
from thermocomp.apps.volumetric.identify import design
from thermocomp.apps.volumetric.kinematics import workspace_grid


@pytest.fixture(scope="session")
def model():
    return KinematicModel(order=3, cross_terms=True)


@pytest.fixture(scope="session")
def points(model):
    rng = np.random.default_rng(0)
    lo = np.array([model.ranges[a][0] for a in "XYZ"])
    hi = np.array([model.ranges[a][1] for a in "XYZ"])
    return lo + rng.random((300, 3)) * (hi - lo)


def test_small_angle_and_htm_differ_by_second_order_terms_only(model, points):
    p = np.random.default_rng(1).uniform(-20, 20, len(model.names))
    diff = [np.abs(model.error(s * p, points, "htm") - model.error(s * p, points, "small")).max()
            for s in (1.0, 10.0)]
    size = np.abs(model.error(p, points, "small")).max()
    assert diff[0] < 1e-3 * size                 # agree within second-order terms
    assert diff[1] / diff[0] == pytest.approx(100, rel=0.05)   # params × 10 -> difference × 100


def test_small_angle_form_is_linear_in_the_parameters(model, points):
    rng = np.random.default_rng(2)
    p, q = rng.normal(size=(2, len(model.names)))
    e = model.error(np.vstack([p, q, 2 * p - 3 * q]), points)
    np.testing.assert_allclose(e[2], 2 * e[0] - 3 * e[1], atol=1e-9)
    np.testing.assert_allclose(np.einsum("nip,p->ni", model.basis(points), p), e[0], atol=1e-9)


@pytest.mark.parametrize("chain", ["tool-Y-Z-bed-workpiece", "Y-Z-X-bed-workpiece",
                                   "tool-Y-Y-X-bed-workpiece", "tool-Y-Z-X-workpiece", "tool-Y-Z-X-bed"])
def test_a_bad_chain_is_refused_with_the_expected_form(chain):
    with pytest.raises(ValueError, match="tool-...-bed-...-workpiece"):
        KinematicModel(chain=chain)


def test_the_part_side_moves_the_part_the_other_way():
    """A positioning error of X gives the same TCP error whether X carries the tool or the part."""
    tool = KinematicModel(chain="tool-Y-Z-X-bed-workpiece")
    part = KinematicModel(chain="tool-Y-Z-bed-X-workpiece")
    q = np.array([[1000.0, 800.0, 400.0], [3000.0, 200.0, 1200.0]])
    p = np.zeros(len(tool.names))
    p[tool.names.index("E_XX1")] = 5.0
    pp = np.zeros(len(part.names))
    pp[part.names.index("E_XX1")] = 5.0
    np.testing.assert_allclose(tool.error(p, q), -part.error(pp, q), atol=1e-12)
    assert abs(tool.error(p, q)[1, 0]) == pytest.approx(5.0 * 0.5)       # L1(0.5) = 0.5


def _setup(sets=("S1", "S2", "S3"), misalignment=0.0, tool=(0.0, 0.0, -150.0)):
    m = KinematicModel(tool=tool)
    return Setup(m, BallArray(11, 1500.0, misalignment), position_set(sets, m.ranges, tool=m.tool))


def test_identification_round_trip_within_two_uncertainties():
    setup = _setup(("S1", "S3"))
    cal = ArtefactCalibration(setup).fit()
    d = design(setup)
    rng = np.random.default_rng(3)
    truth = rng.uniform(-10, 10, (20, len(setup.model.names)))
    noise = rng.standard_normal((20, len(d.A))) @ np.linalg.cholesky(d.cov).T   # correlated, as d.cov
    noisy = truth @ d.A.T + noise
    est, flagged = cal.identify(noisy)
    from thermocomp.apps.volumetric import equivalent_truth
    z = (est - equivalent_truth(cal, truth)) / cal.uncertainty_
    assert not flagged
    assert np.mean(np.abs(z) <= 2) >= 0.9
    assert np.abs(z).max() < 5


def test_unseen_parameters_are_named():
    """With the probe along Z, a rotation of Y about Z moves nothing: named as not seen at all;
    its rotation about X equals its positioning error, named with it."""
    cal = ArtefactCalibration(_setup()).fit()
    assert cal.unidentifiable_["E_CY1"] == [] and cal.unidentifiable_["E_CY2"] == []
    assert cal.unidentifiable_["E_AY1"] == ["E_YY1"]
    assert not set(cal.unidentifiable_) & set(cal.names_)
    assert len(cal.names_) + len(cal.unidentifiable_) == len(cal.setup.model.names)
    # a probe set off along X gives the rotation about Z a lever along Y: it now moves the
    # TCP as the positioning error of Y does, and is named with it
    offset = ArtefactCalibration(_setup(tool=(100.0, 0.0, -150.0))).fit()
    assert offset.unidentifiable_["E_CY1"] == ["E_YY1"]


def test_a_misaligned_array_sees_more_parameters():
    aligned = ArtefactCalibration(_setup(("S2",))).fit()
    tilted = ArtefactCalibration(_setup(("S2",), misalignment=15.0)).fit()
    assert len(tilted.names_) > len(aligned.names_)
    assert set(aligned.names_) < set(tilted.names_)


# --- another machine's physics: an independent forward model ----------------------------------

def _other_machine_error(coeffs, q, ranges, tool, ref):
    """TCP error (µm) of a table-moving-X machine (tool-Z-Y-bed-X-workpiece) written apart from
    thermocomp: error motions are power series of the position in m (not Legendre), each
    carriage rotates about its own reference point ``ref`` (not the origin), and the rotations
    are exact (scipy rotation vectors)."""
    from scipy.spatial.transform import Rotation

    def frame(axis, sign):
        i = "XYZ".index(axis)
        s = (q[:, i] - 0.5 * sum(ranges[axis])) / 1000.0
        m = sum(coeffs[i, :, k][None] * s[:, None] ** k for k in range(coeffs.shape[2]))
        rot = Rotation.from_rotvec(1e-6 * m[:, 3:]).as_matrix()
        t = np.tile(np.eye(4), (len(q), 1, 1))
        t[:, :3, :3] = rot
        t[:, :3, 3] = ref[axis] - rot @ ref[axis] + 1e-3 * m[:, :3]
        t[:, i, 3] += sign * q[:, i]
        return t

    carried = frame("Y", 1) @ frame("Z", 1) @ np.append(tool, 1.0)
    relative = np.einsum("nij,nj->ni", np.linalg.inv(frame("X", -1)), carried)[:, :3]
    return 1e3 * (relative - q - tool)


def _without_rigid_motion(e, points):
    """What is left of a field (n, 3) once the best-fitting small rigid motion is taken out (a
    rigid motion of the whole machine changes no distance)."""
    p = points / 1000.0
    cols = [np.tile(np.eye(3)[k], (len(p), 1)) for k in range(3)]
    cols += [np.cross(np.eye(3)[k], p) for k in range(3)]
    A = np.stack([c.reshape(-1) for c in cols], 1)
    coef = np.linalg.lstsq(A, e.reshape(-1), rcond=None)[0]
    return (e.reshape(-1) - A @ coef).reshape(-1, 3)


def test_a_machine_written_apart_is_recovered_from_its_distances_up_to_a_rigid_motion():
    """Distances of an independently written machine (part-side X, rotations about carriage
    points off the origin, power series) are fitted to noise level, and the identified model
    predicts its TCP error over the volume up to a rigid motion, which no distance sees."""
    ranges = {"X": (0.0, 2500.0), "Y": (0.0, 1000.0), "Z": (0.0, 800.0)}
    tool = np.array([0.0, 0.0, -200.0])
    ref = {"X": np.array([1250.0, -400.0, -300.0]), "Y": np.array([0.0, 500.0, 900.0]),
           "Z": np.array([0.0, 0.0, 400.0])}
    rng = np.random.default_rng(7)
    coeffs = rng.normal(0, 1, (3, 6, 4)) * np.array([0, 6, 4, 2])          # µm, µrad per m^k
    model = KinematicModel(ranges=ranges, chain="tool-Z-Y-bed-X-workpiece", tool=tool, order=3)
    array = BallArray(9, 1200.0, 8.0)
    poses = position_set(("S1", "S2", "S3"), ranges, (0.3, 0.7))
    setup = Setup(model, array, poses)
    cal = ArtefactCalibration(setup).fit()
    d = []
    for pose in poses:
        balls = pose.balls(array)
        q = balls - tool                          # the command whose actual TCP is on each ball
        for _ in range(3):
            q = balls - tool - 1e-3 * _other_machine_error(coeffs, q, ranges, tool, ref)
        read = q + tool
        d += [1e3 * (np.linalg.norm(read[j - 1] - read[i - 1]) - np.linalg.norm(balls[j - 1] - balls[i - 1]))
              for i, j in pairs(array.n_balls)]
    d = np.array(d)
    est, flagged = cal.identify(d[None])
    assert not flagged
    assert np.sqrt(np.mean((d - cal.predict(est)[0]) ** 2)) < 1e-3 * np.sqrt(np.mean(d ** 2))
    grid = workspace_grid(model, (7, 7, 7))
    truth = _other_machine_error(coeffs, grid, ranges, tool, ref)
    gap = _without_rigid_motion(truth - model.error(cal.full(est)[0], grid), grid)
    ve = np.sqrt(np.mean(np.sum(_without_rigid_motion(truth, grid) ** 2, 1)))
    assert ve > 5.0                                             # a machine with errors to find
    assert np.sqrt(np.mean(np.sum(gap ** 2, 1))) < 1e-3 * ve


def test_the_misalignment_offsets_are_where_data_format_md_says(model):
    # a user describing a real misaligned bar needs the normal each ball is set off along
    from test_docs import DATA_FORMAT

    rule = ("balls 2, 6, 10, … (1-based) along v1 = u × e / \\|u × e\\|, e the machine axis on which u "
            "has its smallest component (X before Y before Z on a tie), balls 4, 8, … along v2 = u × v1")
    assert rule in DATA_FORMAT
    for example in ("Along +X: v1 = +Z, v2 = −Y", "along +Y: v1 = −Z, v2 = −X", "along +Z: v1 = +Y, v2 = −X"):
        assert example in DATA_FORMAT
    array = BallArray(n_balls=11, length_mm=1000.0, misalignment_deg=10.0)
    offset = 100.0 * np.tan(np.radians(10.0))
    for direction in [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, -1, 1), (0, 2, -1), (-1, 0, 0)]:
        u = np.asarray(direction, float) / np.linalg.norm(direction)
        e = np.eye(3)[np.argmin(np.abs(u))]
        v1 = np.cross(u, e) / np.linalg.norm(np.cross(u, e))
        v2 = np.cross(u, v1)
        centre = np.array([100.0, 200.0, 300.0])
        along = np.linspace(-500, 500, 11)
        expected = centre + along[:, None] * u
        expected[1::4] += offset * v1           # balls 2, 6, 10
        expected[3::4] += offset * v2           # balls 4, 8
        balls = Pose("p", tuple(centre), direction).balls(array)
        assert np.allclose(balls, expected), direction
    axes = {"X": (1, 0, 0), "Y": (0, 1, 0), "Z": (0, 0, 1)}
    for axis, v1, v2 in (("X", (0, 0, 1), (0, -1, 0)), ("Y", (0, 0, -1), (-1, 0, 0)),
                         ("Z", (0, 1, 0), (-1, 0, 0))):
        assert np.allclose(Pose("p", (0, 0, 0), axes[axis]).frame()[1:], [v1, v2])


def test_the_reach_check_uses_the_axis_positions_the_model_evaluates():
    model = KinematicModel(ranges={"X": (0, 800), "Y": (-300, 300), "Z": (0, 700)}, tool=(0, 0, -120))
    array = BallArray(n_balls=7, length_mm=420.0)
    low = Pose("low", (200.0, -150.0, 150.0), (0, 0, 1))      # tool points down to Z -60, axes 60..480
    Setup.from_dict({**Setup(model, array, [low]).to_dict()})
    high = Pose("high", (200.0, -150.0, 470.0), (0, 0, 1))    # ball 6 at Z 610: its axis at 730
    with pytest.raises(ValueError, match="pose high: ball 6 at Z=610 mm puts the Z axis at 730 mm"):
        Setup.from_dict(Setup(model, array, [high]).to_dict())


def test_the_poses_are_centred_in_the_reachable_volume_in_axis_coordinates():
    # the default scenario: a 1500 mm bar along Z on a 0..1600 travel, tool at Z -150
    model = KinematicModel()
    poses = position_set(("S1", "S2", "S3"), model.ranges, (0.25, 0.75), model.tool)
    for pose in poses:
        axes = pose.balls(BallArray()) - model.tool
        mid = [0.5 * sum(model.ranges[a]) for a in "YZ"]
        assert np.allclose(0.5 * (axes.min(0) + axes.max(0))[1:], mid), pose.name
    Setup.from_dict(Setup(model, BallArray(), poses).to_dict())      # every ball reached
    assert poses[2].centre == (1000.0, 800.0, 650.0)                 # S1x1d3: axes Z 50..1550
    with pytest.raises(ValueError, match="pose S1x1d3: ball 11 at Z=1550 mm puts the Z axis at 1700 mm"):
        Setup.from_dict(Setup(model, BallArray(), position_set(("S1",), model.ranges)).to_dict())
    odd = KinematicModel(ranges={"X": (-500, 900), "Y": (100, 1300), "Z": (-200, 1500)}, tool=(30, -40, -260))
    poses = position_set(("S1", "S2", "S3"), odd.ranges, (0.5,), odd.tool)
    assert {p.centre for p in poses} == {(230.0, 660.0, 390.0)}
    Setup.from_dict(Setup(odd, BallArray(11, 1100.0, 10.0), poses).to_dict())
