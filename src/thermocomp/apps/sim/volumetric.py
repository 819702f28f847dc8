r"""Scenario ``large_mill_volumetric``: the ``large_mill_week`` tests measured with a ball array.

The machine, its sensors and the heater and hall-climate programmes are those of
:mod:`thermocomp.apps.sim.large_mill` (paper 000); what is measured is no longer the drift of
one point but the artefact calibration of paper 000 (sections 2-3) repeated every
``cycle_min``: a 1D ball array (:class:`~thermocomp.apps.volumetric.BallArray`) probed in every
pose of a position set, each cycle giving the distance deviation of every ball pair.

Ground truth: every error parameter :math:`p_k` of the kinematic model
(:class:`~thermocomp.apps.volumetric.KinematicModel`, all of them, seen by the poses or not) is

.. math::

    p_k(t) = p_k^{cold} + g \sum_j s_{kj} \, (T_j(t) - 20\,°C)

with :math:`p^{cold}` a constant cold geometry drawn from the seed (scaled so that its
volumetric error -- RMS of :math:`|e|` over a 5×5×5 grid of the volume -- is
``cold_ve_um``), :math:`T_j` the true node temperatures of the thermal network and
:math:`s_{kj}` the sensitivities of :data:`SENSITIVITY` (µm or µm/m per K, scaled by
``thermal_gain``): the X scale follows the bed, the Z scale the column front, the Y scale
the ram; the column leans in X when its side (heater H1) is warmer than its front and back
(squareness and straightness of Z in X, its pitch), forward when its back (H2) is warmer
(Y-Z squareness ``E_ZY1``, ``E_YZ2``, its roll); a bed warmer in the middle bows (Z
straightness of X) and pitches the column carriage; a ram warmer at the rear droops.

A distance is simulated through the full HTM model (``form="htm"``): the machine reads
a ball at the command that puts the actual TCP on it, so its reading is the ball's true
centre minus the TCP error there, evaluated at the nominal command (the error of that
shortcut, gradient × error, is ~0.003 µm); each reading is off by ``probing_um`` per
coordinate, and the artefact's balls are off their calibrated centres by ``ball_um`` per
coordinate, the same error for the whole dataset (one artefact).  The artefact itself
is taken at its calibration temperature (invar, or compensated).

A row of a campaign file is one measurement cycle: ``time``, every ``T_`` sensor at that
instant and the distance deviations ``E_<pose>_B<i>_B<j>`` (µm, measured − calibrated,
absolute); ``volumetric.json`` (:meth:`~thermocomp.apps.volumetric.Setup.to_dict`) goes in the
dataset folder, the parameter series of every campaign in the truth (``parameters``).
"""

from __future__ import annotations

import json
import zlib

import numpy as np
import pandas as pd

from thermocomp.apps.sim.large_mill import LargeMillWeek, moving_column_mill
from thermocomp.apps.sim.scenario import Scenario, plain, single_threaded_blas
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
from thermocomp.apps.volumetric import SETUP_FILE, BallArray, KinematicModel, Setup, position_set
from thermocomp.apps.volumetric.artefact import MAX_BALLS, POSITION_SETS
from thermocomp.apps.volumetric.measure import artefact_distances
from thermocomp.base.params import (
    BOOLEAN,
    NON_NEGATIVE,
    POSITIVE,
    check_params,
    integer,
    number,
    numbers,
    samples_in,
    subset,
)

SCENARIO = "large_mill_volumetric"
REFERENCE_C = 20.0
# parameter -> {node: sensitivity per K above 20 °C} (µm/K, angular µm/(m K)); a parameter the
# model does not have (order, cross terms) is skipped.  Legendre order 1 is half the change over
# the travel: a 4 m bed 3 µm/(m K) longer than its scale gives 6 µm/K of E_XX1.
SENSITIVITY = {
    # scales: steel against the glass scales
    "E_XX1": {"bed_left": 2.0, "bed_mid": 2.0, "bed_right": 2.0},
    "E_XX2": {"bed_mid": 4.0, "bed_left": -2.0, "bed_right": -2.0},
    "E_YY1": {"ram_front": 1.2, "ram_rear": 1.2},
    "E_YY2": {"ram_rear": 4.0, "ram_front": -4.0},
    "E_ZZ1": {"column_front_low": 1.2, "column_upper_front": 1.2},
    "E_ZZ2": {"column_upper_front": 5.0, "column_front_low": -5.0},
    # column side warmer (H1): the column leans in X (a·L²/2d over 1.6 m of Z on a 1.2 m column)
    "E_XZ1": {"column_side_low": 6.0, "column_front_low": -3.0, "column_back_low": -3.0},
    "E_XZ2": {"column_side_low": 4.0, "column_upper_front": -2.0, "column_upper_back": -2.0},
    "E_BZ1": {"column_side_low": 4.0, "column_front_low": -2.0, "column_back_low": -2.0},
    # column back warmer (H2): it leans forward, in Y
    "E_ZY1": {"column_back_low": 5.0, "column_front_low": -5.0, "column_upper_back": 2.0,
              "column_upper_front": -2.0},
    "E_YZ2": {"column_back_low": 5.0, "column_front_low": -5.0},
    "E_AZ1": {"column_back_low": 5.0, "column_front_low": -5.0},
    "E_CZ1": {"column_side_low": 3.0, "column_back_low": -3.0},
    # X-Y squareness: the upper column's front/back gradient turns the ram's guideways
    "E_XY1": {"column_upper_front": 8.0, "column_upper_back": -8.0},
    # ram warmer at the rear: droop and pitch
    "E_ZY2": {"ram_rear": 3.0, "ram_front": -3.0, "head": -1.5},
    "E_AY1": {"ram_front": 6.0, "ram_rear": -6.0},
    # bed warmer in the middle: it bows (Z straightness of X, a·L²/8h ~ 40 µm/K of gradient over
    # its depth) and pitches the column carriage (the bow's slope)
    "E_ZX2": {"bed_mid": 8.0, "bed_left": -4.0, "bed_right": -4.0},
    "E_BX1": {"bed_mid": 10.0, "bed_left": -5.0, "bed_right": -5.0},
    "E_CX1": {"column_side_low": 3.0, "column_back_low": -3.0},
    # column-ram cross terms (cross_terms=true): the upper column's gradient bends the ram's support
    "E_YZY1": {"column_upper_front": 2.0, "column_upper_back": -2.0},
    "E_AZY1": {"column_upper_front": 4.0, "column_upper_back": -4.0},
}
COLD_SD = {"translation": 5.0, "angular": 4.0}      # relative spread of the cold draw before scaling


def volume_grid(model: KinematicModel, n: int = 5) -> np.ndarray:
    """``(n³, 3)`` commands on a regular grid over the axes' travel (mm)."""
    axes = [np.linspace(*model.ranges[a], n) for a in "XYZ"]
    return np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)


def volumetric_error(model: KinematicModel, params, grid=None) -> np.ndarray:
    """VE (µm): RMS over the grid of the TCP error's length, per parameter row."""
    grid = volume_grid(model) if grid is None else grid
    e = model.error(np.atleast_2d(params), grid)
    return np.sqrt(np.mean(np.sum(e ** 2, axis=-1), axis=-1))


def simulate_distances(setup: Setup, params: np.ndarray, rng: np.random.Generator,
                       ball_error_um: np.ndarray) -> np.ndarray:
    """Distance deviations ``(n_cycles, n_columns)`` (µm) in ``setup.columns()`` order.

    ``params`` (n_cycles, p): the full parameter vector of each cycle; ``ball_error_um``
    (n_balls, 3): the artefact's ball centres off their calibrated ones (its own frame).
    """
    params = np.atleast_2d(params)
    noise = setup.probing_um * rng.standard_normal((len(params), len(setup.poses),
                                                    setup.array.n_balls, 3))
    return artefact_distances(setup.model, setup, params, ball_error_um, noise)


class LargeMillVolumetric(LargeMillWeek):
    """Generator of the ``large_mill_volumetric`` dataset (module docstring).

    Parameters
    ----------
    train_hours, test_hours : float
        Lengths of the training (March) and validation (June) tests.
    cycle_min : float
        Minutes between two measurement cycles (one row each).
    heater_power_W, temp_noise_c, temp_quantum_c : float
        As in :class:`~thermocomp.apps.sim.large_mill.LargeMillWeek`.
    probing_um, ball_um : float
        Standard uncertainty (per coordinate) of a probed ball centre and of the artefact's
        calibrated ball centres.
    cold_ve_um : float
        Volumetric error of the drawn cold geometry.
    thermal_gain : float
        Factor on every sensitivity of :data:`SENSITIVITY`.
    order, cross_terms : int, bool
        Of the kinematic model (:class:`~thermocomp.apps.volumetric.KinematicModel`).
    n_balls, length_mm, misalignment_deg : int, float, float
        The ball array (:class:`~thermocomp.apps.volumetric.BallArray`).
    sets, x_centres : sequence
        The poses (:func:`~thermocomp.apps.volumetric.position_set`).
    seed : int
    """

    name = SCENARIO
    param_rules = {"train_hours": POSITIVE, "test_hours": POSITIVE, "cycle_min": POSITIVE,
                   "heater_power_W": NON_NEGATIVE, "temp_noise_c": NON_NEGATIVE,
                   "temp_quantum_c": NON_NEGATIVE, "probing_um": NON_NEGATIVE, "ball_um": NON_NEGATIVE,
                   "cold_ve_um": NON_NEGATIVE, "thermal_gain": NON_NEGATIVE, "order": integer(1, 10),
                   "cross_terms": BOOLEAN, "n_balls": integer(2, MAX_BALLS), "length_mm": POSITIVE,
                   "misalignment_deg": number(0.0, 90.0, open_hi=True),
                   "sets": subset(POSITION_SETS), "x_centres": numbers(0.0, 1.0)}

    def param_relations(self) -> list[tuple[str, str]]:
        return samples_in(self, ("train_hours", "test_hours"), "cycle_min", 60.0)

    def __init__(self, train_hours=234.0, test_hours=169.0, cycle_min=20.0, heater_power_W=450.0,
                 temp_noise_c=0.05, temp_quantum_c=0.01, probing_um=0.5, ball_um=0.5, cold_ve_um=12.0,
                 thermal_gain=1.0, order=2, cross_terms=False, n_balls=11, length_mm=1500.0,
                 misalignment_deg=0.0, sets=("S1", "S2", "S3"), x_centres=(0.25, 0.75), seed=0):
        self.train_hours = train_hours
        self.test_hours = test_hours
        self.cycle_min = cycle_min
        self.heater_power_W = heater_power_W
        self.probing_um = probing_um
        self.ball_um = ball_um
        self.cold_ve_um = cold_ve_um
        self.thermal_gain = thermal_gain
        self.order = order
        self.cross_terms = cross_terms
        self.n_balls = n_balls
        self.length_mm = length_mm
        self.misalignment_deg = misalignment_deg
        self.sets = sets
        self.x_centres = x_centres
        # what the thermal twin of large_mill_week needs: the row is the cycle, no planted effect,
        # no TCP probe (the parameters are computed from the node temperatures)
        Scenario.__init__(self, temp_noise_c, temp_quantum_c, 0.0, 0.0, seed=seed)

    @property
    def sample_period_s(self) -> float:
        return 60.0 * float(self.cycle_min)

    def setup(self) -> Setup:
        """The measurement set-up (``volumetric.json``)."""
        model = KinematicModel(order=int(self.order), cross_terms=bool(self.cross_terms))
        array = BallArray(int(self.n_balls), float(self.length_mm), float(self.misalignment_deg))
        poses = position_set(list(plain(self.sets)), model.ranges, list(plain(self.x_centres)),
                             model.tool)
        return Setup(model, array, poses, float(self.probing_um), float(self.ball_um))

    def sensitivities(self, model: KinematicModel) -> dict:
        return {n: {node: float(self.thermal_gain) * s for node, s in SENSITIVITY[n].items()}
                for n in model.names if n in SENSITIVITY}

    def machine(self):
        machine = super().machine()
        # the parameters as the twin's targets: the truth records their sensitivities
        machine.thermoelastic = ThermoelasticMap(linear=self.sensitivities(self.setup().model),
                                                 reference_c=REFERENCE_C)
        return machine

    def cold_geometry(self, model: KinematicModel, rng: np.random.Generator) -> np.ndarray:
        """A cold parameter vector whose VE is ``cold_ve_um``."""
        sd = np.array([COLD_SD["angular" if p.angular else "translation"] for p in model.parameters])
        p = sd * rng.standard_normal(len(sd))
        return p * float(self.cold_ve_um) / volumetric_error(model, p)[0]

    def generate(self):
        """``(dataset, truth)``: the thermal twin's campaigns with the distances as targets.

        Also sets ``setup_`` (the :class:`~thermocomp.apps.volumetric.Setup`) and ``parameters_``
        (campaign id -> DataFrame of the true parameters per cycle).
        """
        check_params(self)
        setup = self.setup_ = self.setup()
        model = setup.model
        ds, truth = super().generate()
        with single_threaded_blas():
            return self._measure(ds, truth, setup, model)

    def _measure(self, ds, truth, setup, model):
        rng = np.random.default_rng([int(self.seed), zlib.crc32(SCENARIO.encode())])
        cold_rng, ball_rng, probe_rng = rng.spawn(3)
        cold = self.cold_geometry(model, cold_rng)
        ball_error = float(self.ball_um) * ball_rng.standard_normal((int(self.n_balls), 3))
        sens = self.sensitivities(model)
        nodes = list(moving_column_mill().network.names)
        S = np.array([[sens.get(n, {}).get(node, 0.0) for node in nodes] for n in model.names])
        columns = setup.columns()
        self.parameters_ = {}
        for cid, frame in list(ds.campaigns.items()):
            temps = self.node_temperatures_[cid][nodes].to_numpy()
            P = cold + (temps - REFERENCE_C) @ S.T
            D = simulate_distances(setup, P, probe_rng, ball_error)
            keep = frame[[c for c in frame.columns if not c.startswith("E_")]]
            ds.campaigns[cid] = pd.concat([keep, pd.DataFrame(D, columns=columns, index=frame.index)],
                                          axis=1)
            self.parameters_[cid] = pd.DataFrame(P, columns=model.names, index=frame.index)
            tc = truth["campaigns"][cid]
            tc.pop("true_error_final_um", None)
            tc["parameters"] = {n: P[:, k].tolist() for k, n in enumerate(model.names)}
            tc["parameter_p2p"] = dict(zip(model.names, np.ptp(P, axis=0).tolist()))
        truth["volumetric"] = {
            "setup": setup.to_dict(),
            "reference_c": REFERENCE_C,
            "cold_parameters": dict(zip(model.names, cold.tolist())),
            "cold_ve_um": float(volumetric_error(model, cold)[0]),
            "ball_error_um": ball_error.tolist(),
            "sensitivity_per_K": sens,
            "formula": "p_k(t) = cold_k + sum_j sensitivity_kj * (T_node_j(t) - reference_c); "
                       "distance = |reading_j - reading_i| - calibrated, reading = ball - e_htm(ball - tool) "
                       "+ N(0, probing^2); ball = nominal + ball_error",
        }
        truth["noise"] = {"temperature_c": self.temp_noise_c, "temperature_quantum_c": self.temp_quantum_c,
                          "probing_um": self.probing_um, "ball_um": self.ball_um}
        ds.meta["volumetric"] = setup.to_dict()
        return ds, plain(truth)

    def dataset_files(self) -> dict:
        """Files written inside the dataset folder, next to the campaign files."""
        return {SETUP_FILE: json.dumps(self.setup_.to_dict(), indent=2) + "\n"}

    file_format = "parquet"
