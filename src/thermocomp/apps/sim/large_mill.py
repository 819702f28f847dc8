r"""Scenario ``large_mill_week``: week-long tests of a moving-column milling machine.

After Iñigo et al. (Sensors 24:6196, 2024, paper 000): a medium/large
moving-column mill with a fixed workpiece table, 52 thermocouples (table 10,
X bed 10, column 16, ram 12, ambient 4) logged every 30 s, a ~234 h training
test in March and a ~169 h validation test in June (warmer hall, HVAC on by
day and off from 18:00, nights up to 27 °C), two hot-air heaters on the lower
column (H1 side, H2 back) switched on and off, and forced heating/cooling of
the hall.  Targets: thermal drift of the TCP in X (along the bed), Y (ram),
Z (vertical).

The machine (C = m · 460 J/(kg K), hA = area · 6-8 W/(m² K))
-----------------------------------------------------------
==================  ========  ======  ==============================================
node                C (J/K)   hA      what
==================  ========  ======  ==============================================
table_top           9.2e5     30      2 t fixed table, top plate with the part
table_base          9.2e5     12      2 t, on the foundation
bed_left/mid/right  1.4e6     25      9 t X bed in three sections
column_*_low        5.5e5     12-20   lower column: side (H1), back (H2), front
column_upper_*      5.5e5     12-18   upper column, front (Z guideways) and back
ram_front/rear      3.5e5     10      1.5 t Y ram, two halves
head                3.7e5     8       spindle head at the ram nose (unmeasured)
==================  ========  ======  ==============================================

Heat: the volumetric calibration keeps the axes moving (X 80 W on the bed
and the lower column front, Y 60 W ram, Z 40 W column front), no cutting;
the heaters deliver ~450 W each into the lower column (of ~2 kW blown).
Errors (µm/K of node rises): the column bends in X when its side warms
(:math:`\alpha L^2/2d` of a 3 m column, 1.2 m wide, shared between the lower
and upper halves), in Y when its back warms; its growth lifts the head in Z
(3 m · 11.5 µm/(m K)); the ram grows in Y; the table lifts the part.  The
hall's forced ±4 °C swing moves Z by 50-100 µm, as in the paper's ranges.
"""

from __future__ import annotations

import numpy as np

from thermocomp.apps.sim.ambient import DAY_S, HallClimate
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan, Scenario
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import ConstantWhileRunning
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
from thermocomp.base.params import NON_NEGATIVE, POSITIVE, samples_in

SCENARIO = "large_mill_week"
HEATER_SIDE, HEATER_BACK, AXES = "_heater_side", "_heater_back", "_axes_moving"

NODES = (
    Node("table_top", 9.2e5, 30.0), Node("table_base", 9.2e5, 12.0),
    Node("bed_left", 1.4e6, 25.0), Node("bed_mid", 1.4e6, 25.0), Node("bed_right", 1.4e6, 25.0),
    Node("column_side_low", 5.5e5, 20.0), Node("column_back_low", 5.5e5, 20.0),
    Node("column_front_low", 5.5e5, 12.0),
    Node("column_upper_front", 5.5e5, 12.0), Node("column_upper_back", 5.5e5, 18.0),
    Node("ram_front", 3.5e5, 10.0), Node("ram_rear", 3.5e5, 10.0), Node("head", 3.7e5, 8.0),
)
LINKS = (
    Link("table_top", "table_base", 150.0),
    Link("bed_left", "bed_mid", 80.0), Link("bed_mid", "bed_right", 80.0),
    Link("column_front_low", "bed_mid", 40.0), Link("column_back_low", "bed_mid", 30.0),
    Link("column_side_low", "bed_mid", 30.0),
    Link("column_side_low", "column_front_low", 60.0), Link("column_side_low", "column_back_low", 60.0),
    Link("column_front_low", "column_back_low", 60.0),
    Link("column_front_low", "column_upper_front", 60.0), Link("column_back_low", "column_upper_back", 60.0),
    Link("column_side_low", "column_upper_back", 30.0), Link("column_side_low", "column_upper_front", 30.0),
    Link("column_upper_front", "column_upper_back", 60.0),
    Link("ram_rear", "column_upper_front", 30.0), Link("ram_front", "ram_rear", 50.0),
    Link("head", "ram_front", 40.0),
)


def heat_sources():
    return [
        ConstantWhileRunning("heater_H1_side", {"column_side_low": 0.85, "bed_mid": 0.15}, 450.0,
                             HEATER_SIDE),
        ConstantWhileRunning("heater_H2_back", {"column_back_low": 0.85, "bed_mid": 0.15}, 450.0,
                             HEATER_BACK),
        ConstantWhileRunning("x_drive", {"bed_mid": 0.5, "column_front_low": 0.5}, 80.0, AXES),
        ConstantWhileRunning("y_drive", {"ram_rear": 0.7, "column_upper_front": 0.3}, 60.0, AXES),
        ConstantWhileRunning("z_drive", {"column_upper_front": 1.0}, 40.0, AXES),
    ]


def thermoelastic_map():
    return ThermoelasticMap(
        linear={
            "E_X": {"column_side_low": 14.0, "column_front_low": -7.0, "column_back_low": -7.0,
                    "column_upper_back": 3.0, "column_upper_front": -3.0,
                    "bed_left": -2.0, "bed_right": 2.0, "table_top": 3.0},
            "E_Y": {"column_back_low": 12.0, "column_front_low": -12.0, "column_upper_back": 8.0,
                    "column_upper_front": -8.0, "ram_front": 7.0, "ram_rear": 5.0, "head": 6.0,
                    "table_top": -3.0},
            "E_Z": {"column_side_low": 5.0, "column_back_low": 5.0, "column_front_low": 5.0,
                    "column_upper_front": 6.0, "column_upper_back": 6.0, "head": 5.0, "bed_mid": 2.0,
                    "table_top": -6.0, "table_base": -6.0},
        },
        quadratic={"E_X": {"column_side_low": 0.3}, "E_Z": {"column_upper_front": 0.1}},
        ambient_beta={"E_X": 0.004, "E_Y": 0.004, "E_Z": 0.004},
        reference_c=20.0,
    )


def sensors():
    """52 thermocouples at fixed positions (the same machine for every seed)."""
    rng = np.random.default_rng(20240930)
    out = []

    def add(prefix, count, nodes, lag_s, air=0.0):
        for i in range(count):
            w = rng.dirichlet(np.full(len(nodes), 0.6)) if len(nodes) > 1 else np.ones(1)
            weights = {n: float(x) * (1 - air) for n, x in zip(nodes, w)}
            if air:
                weights[AMBIENT] = air
            total = sum(weights.values())
            weights = {n: v / total for n, v in weights.items()}
            out.append(TemperatureSensor(f"{prefix}_{i + 1:02d}", weights,
                                         float(np.round(rng.uniform(-0.4, 0.4), 2)), lag_s=lag_s))

    add("T_table", 10, ["table_top", "table_base"], 600.0, air=0.03)
    bed_nodes = ["bed_left", "bed_mid", "bed_right"]
    for i in range(10):  # along X: left to right
        x = i / 9 * 2
        k = min(int(x), 1)
        w = x - k
        weights = {bed_nodes[k]: 1 - w, bed_nodes[k + 1]: w} if w > 0 else {bed_nodes[k]: 1.0}
        out.append(TemperatureSensor(f"T_bed_{i + 1:02d}", weights,
                                     float(np.round(rng.uniform(-0.4, 0.4), 2)), lag_s=600.0))
    add("T_col", 16, ["column_side_low", "column_back_low", "column_front_low", "column_upper_front",
                      "column_upper_back"], 600.0)
    add("T_ram", 12, ["ram_front", "ram_rear"], 600.0, air=0.02)
    for name, node in (("T_amb_left", "table_top"), ("T_amb_right", "table_top"),
                       ("T_amb_back1", "column_back_low"), ("T_amb_back2", "column_upper_back")):
        out.append(TemperatureSensor(name, {AMBIENT: 0.97, node: 0.03},
                                     float(np.round(rng.uniform(-0.3, 0.3), 2)), lag_s=120.0))
    return out


def moving_column_mill() -> Machine:
    return Machine(ThermalNetwork(NODES, LINKS), heat_sources(), sensors(), thermoelastic_map())


LARGE_MILL_EFFECTS = {
    "door": {"nodes": {"table_top": 80.0, "column_front_low": 80.0}, "air_offset_c": -8.0,
             "rate_per_h": 0.5, "duration_min": [15.0, 45.0], "targets": ["E_Y"]},
    "hidden_source": {"anchor": "head", "power_W": 400.0, "conductance_W_per_K": 15.0,
                      "on_min": [60.0, 240.0], "off_min": [60.0, 240.0], "targets": ["E_Y"]},
    "lag_node": {"parent": "column_back_low", "capacity_J_per_K": 1.5e6, "conductance_W_per_K": 50.0,
                 "convection_W_per_K": 1.0, "sensitivity_um_per_K": {"E_Y": 20.0}, "targets": ["E_Y"]},
    "axis_position": {"axis": "Z", "travel_mm": [0.0, 1500.0], "home_mm": 750.0, "dwell_min": [20.0, 90.0],
                      "tilt_nodes": {"column_side_low": 1.0, "column_front_low": -0.5,
                                     "column_back_low": -0.5},
                      "gain_um_per_K_per_m": 20.0, "targets": ["E_X"]},
    "sensor_drift": {"column": "T_col_03", "rate_K_per_h": 0.05, "onset_fraction": 0.3,
                     "splits": ["test"], "targets": ["E_X", "E_Y", "E_Z"]},
    "ambient_law": {"level_node": "ambient", "level_lag_h": 2.0, "threshold_c": 23.0, "gain": 0.2,
                    "targets": ["E_Z"]},
}


def _h(hours):
    return 3600.0 * float(hours)


class LargeMillWeek(Scenario):
    """Generator of the ``large_mill_week`` dataset: one training and one validation test.

    Parameters
    ----------
    train_hours, test_hours : float
        Lengths of the training (March) and validation (June) tests.
    sample_period_s : float
        Logger period (30 s in the paper).
    heater_power_W : float
        Heat each hot-air heater delivers into the lower column.
    temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um : float
        Measurement chain (thermocouple noise after averaging, probe noise).
    effects, effect_params, clean, seed
        See :class:`~thermocomp.apps.sim.scenario.Scenario`.

    Notes
    -----
    The test programmes are written as fractions of the test length, so a short
    test (``train_hours=24``) keeps every phase.  Heaters and HVAC are not
    columns: the paper logs them as test conditions (ground truth ``programme``).
    """

    name = SCENARIO
    param_rules = {**Scenario.param_rules, "train_hours": POSITIVE, "test_hours": POSITIVE,
                   "sample_period_s": POSITIVE, "heater_power_W": NON_NEGATIVE}

    def param_relations(self) -> list[tuple[str, str]]:
        return samples_in(self, ("train_hours", "test_hours"), "sample_period_s")

    def __init__(self, train_hours=234.0, test_hours=169.0, sample_period_s=30.0, heater_power_W=450.0,
                 temp_noise_c=0.05, temp_quantum_c=0.01, error_noise_um=0.5, error_quantum_um=0.1,
                 effects=(), effect_params=None, clean=False, seed=0):
        self.train_hours = train_hours
        self.test_hours = test_hours
        self.sample_period_s = sample_period_s
        self.heater_power_W = heater_power_W
        super().__init__(temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um, effects,
                         effect_params, clean, seed)

    def machine(self):
        machine = moving_column_mill()
        for source in machine.sources:
            if source.name.startswith("heater"):
                source.power_W = float(self.heater_power_W)
        return machine

    def effect_defaults(self):
        return LARGE_MILL_EFFECTS

    def _grid(self, t):
        return self.sample_period_s * round(t / self.sample_period_s)

    def _programme(self, start_s, hours, heater_phases, forced, hvac_hours, base_c, free_c):
        """Heater intervals and the hall's setpoints from phases given as fractions of the test."""
        duration = _h(hours)
        heaters = {HEATER_SIDE: [], HEATER_BACK: []}
        for a, b, which in heater_phases:
            for name in which:
                heaters[name].append((self._grid(a * duration), self._grid(b * duration)))
        setpoints = [(start_s - 5 * DAY_S, base_c)]
        for a, level in forced:
            setpoints.append((start_s + a * duration, level))
        climate = HallClimate(setpoints=tuple(setpoints), hvac_hours=hvac_hours, free_c=free_c,
                              daily_amplitude_c=1.0 if hvac_hours != (0.0, 24.0) else 0.3)
        return heaters, climate

    def plans(self, rng):
        from thermocomp.apps.sim.effects import intervals_signal
        train, test = rng.spawn(2)
        # Training, 24 March: 30 % quiet, heaters H1, H2, both, then forced cool/heat of the hall.
        tr_heat, tr_climate = self._programme(
            _h(24 * 82 + 8), self.train_hours,
            [(0.30, 0.40, [HEATER_SIDE]), (0.47, 0.57, [HEATER_BACK]),
             (0.64, 0.73, [HEATER_SIDE, HEATER_BACK])],
            [(0.80, 18.0), (0.86, 18.0), (0.89, 26.0), (0.96, 22.0)], (0.0, 24.0), 22.0, 22.0)
        # Validation, 8 June: HVAC 06-18 h at 24 °C, nights free up to ~27 °C, heaters recombined.
        te_heat, te_climate = self._programme(
            _h(24 * 159 + 8), self.test_hours,
            [(0.12, 0.19, [HEATER_BACK]), (0.26, 0.36, [HEATER_SIDE]),
             (0.47, 0.54, [HEATER_SIDE, HEATER_BACK]), (0.65, 0.70, [HEATER_SIDE])],
            [(0.77, 26.5), (0.87, 24.0)], (6.0, 18.0), 24.0, 26.0)
        plans = []
        for cid, split, child, start, hours, heat, climate in (
                ("train_week", "train", train, _h(24 * 82 + 8), self.train_hours, tr_heat, tr_climate),
                ("validation_week", "test", test, _h(24 * 159 + 8), self.test_hours, te_heat, te_climate)):
            states = {name: intervals_signal(iv) for name, iv in heat.items()}
            states[AXES] = np.ones_like
            plans.append(CampaignPlan(
                cid=cid, split=split, start_s=start, duration_s=self._grid(_h(hours)), rng=child,
                ambient=climate, states=states, written=(), sample_period_s=float(self.sample_period_s),
                cooldown_s=3 * DAY_S, notes=f"{split}: heaters H1/H2 and forced hall climate, {hours:g} h",
                manifest={"duration_h": float(hours)},
                truth={"heaters_s": {k.strip("_"): [list(map(float, i)) for i in v] for k, v in heat.items()},
                       "climate": climate.to_dict()}))
        return plans
