"""The v1 machine: a 3-axis vertical machining centre (spindle test of ISO 230-3).

Modelled on the Vcenter-55 of Wei et al. (2022): 10 Pt sensors, five on the
front bearing area, two on the spindle motor, two on the spindle box and one on
the frame for the air.  The column, bed and table carry no sensor.  Why each
value is plausible: :mod:`thermocomp.apps.sim.network`.
"""

from __future__ import annotations

from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.sources import (
    BearingFriction,
    ConstantWhileRunning,
    SpindleMotorLosses,
    StateConvection,
)
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap

# C = m * 460 J/(kg K); hA = area * 5-10 W/(m² K).
NODES = (
    Node("motor", 2.0e4, 6.0),
    Node("spindle_shaft", 1.15e4, 1.0),
    Node("bearing_front", 4.0e3, 1.0),
    Node("bearing_rear", 2.5e3, 0.5),
    Node("headstock", 1.4e5, 12.0),
    Node("column_front", 3.2e5, 8.0),   # inside the enclosure: calmer air
    Node("column_back", 3.2e5, 25.0),    # ribbed and open to the shop
    Node("bed", 1.15e6, 30.0),
    Node("table", 1.4e5, 6.0),
)

LINKS = (
    Link("motor", "spindle_shaft", 3.0),        # air gap and rotor
    Link("motor", "headstock", 8.0),            # mounting flange
    Link("spindle_shaft", "bearing_front", 6.0),  # through the rolling elements
    Link("spindle_shaft", "bearing_rear", 4.0),
    Link("bearing_front", "headstock", 15.0),   # press fit in the housing
    Link("bearing_rear", "headstock", 8.0),
    Link("headstock", "column_front", 20.0),    # Z guideways and slide
    Link("column_front", "column_back", 20.0),  # ribbed cast wall
    Link("column_front", "bed", 10.0),          # bolted joint
    Link("column_back", "bed", 10.0),
    Link("bed", "table", 5.0),                  # X/Y guideways
)


def heat_sources():
    """Spindle motor, front and rear bearings, feed drives (see :mod:`~thermocomp.apps.sim.sources`)."""
    return [
        SpindleMotorLosses("spindle_motor", {"motor": 0.75, "spindle_shaft": 0.25},
                           idle_W=25.0, linear_W_per_krpm=15.0, quadratic_W_per_krpm2=2.0),
        BearingFriction("front_bearings", {"bearing_front": 0.8, "spindle_shaft": 0.2},
                        viscous_W=60.0, load_W=15.0, bearing_node="bearing_front"),
        BearingFriction("rear_bearing", {"bearing_rear": 0.8, "spindle_shaft": 0.2},
                        viscous_W=25.0, load_W=6.0, bearing_node="bearing_rear"),
        ConstantWhileRunning("feed_drives", {"table": 0.4, "bed": 0.4, "column_front": 0.2},
                             power_W=40.0),
    ]


def convection_rules():
    """The rotating shaft and nose are cooled by the air they drag: h ~ n^0.6."""
    return [StateConvection("spindle_shaft", 1.5, exponent=0.6),
            StateConvection("bearing_front", 0.5, exponent=0.6)]


def sensors():
    """The paper's layout: T1-T5 bearing area, T7/T8 motor, T6/T9 box, T10 frame (air)."""
    return [
        TemperatureSensor("T_bearing_f1", {"bearing_front": 0.85, "headstock": 0.15}, 0.05, lag_s=480.0),
        TemperatureSensor("T_bearing_f2", {"bearing_front": 0.7, "headstock": 0.3}, -0.04, lag_s=480.0),
        TemperatureSensor("T_bearing_f3", {"bearing_front": 0.55, "headstock": 0.45}, 0.02, lag_s=480.0),
        TemperatureSensor("T_nose", {"bearing_front": 0.4, "headstock": 0.6}, -0.08, lag_s=480.0),
        TemperatureSensor("T_bearing_r", {"bearing_rear": 0.8, "headstock": 0.2}, 0.06, lag_s=480.0),
        TemperatureSensor("T_motor1", {"motor": 0.9, "headstock": 0.1}, 0.03, lag_s=480.0),
        TemperatureSensor("T_motor2", {"motor": 0.7, "headstock": 0.3}, -0.02, lag_s=480.0),
        TemperatureSensor("T_box1", {"headstock": 1.0}, 0.0, lag_s=480.0),
        TemperatureSensor("T_box2", {"headstock": 0.9, "motor": 0.1}, 0.07, lag_s=480.0),
        TemperatureSensor("T_amb", {AMBIENT: 0.95, "column_back": 0.05}, -0.05, lag_s=120.0),
    ]


def thermoelastic_map():
    """TCP errors: sensitivities s = alpha * L (alpha ≈ 11 µm/(m K)), µm/K per node rise."""
    return ThermoelasticMap(
        linear={
            # X: the motor sits off-centre on the headstock (asymmetric growth),
            # the X ball screw warms the table.
            "E_X": {"motor": 0.5, "headstock": -0.3, "table": 0.8},
            # Y: the headstock pushes the spindle away from the column (~330 mm),
            # the warmer column front bends the column backwards (alpha L^2 / 2d).
            "E_Y": {"headstock": 3.5, "column_front": -12.0, "column_back": 12.0},
            # Z: nose overhang of the shaft, headstock from Z nut to front bearing,
            # bearing ring growth; column growth lifts the head; bed/table lift the part.
            "E_Z": {"spindle_shaft": 2.0, "headstock": 3.0, "bearing_front": 0.8,
                    "column_front": -3.0, "column_back": -3.0, "table": 1.0, "bed": 2.0},
        },
        # Preload rises with the bearing temperature: axial shift grows faster than linear.
        quadratic={"E_Z": {"bearing_front": 0.04}, "E_Y": {"headstock": 0.05}},
        # Fits and preload loosen as the structure warms (Wei et al. 2022: more Z at low ambient).
        ambient_beta={"E_Y": 0.015, "E_Z": 0.02},
        reference_c=20.0,
    )


def vertical_machining_centre() -> Machine:
    """Assemble the v1 twin."""
    return Machine(ThermalNetwork(NODES, LINKS), heat_sources(), sensors(), thermoelastic_map(),
                   convection_rules())


# Where each undeclared effect (thermocomp.apps.sim.effects) attaches on this machine, and its
# default size: each leaves an MLR on the ten sensors a test residual dominated by it
# (measured in benchmarks/bench_sim.py).
VMC_EFFECTS = {
    # The open door lets the colder shop-floor air sweep the front of the column and the
    # headstock inside the enclosure (forced convection, h ~ 15-25 W/(m² K) on ~2 m²).
    "door": {"nodes": {"column_front": 60.0},
             "air_offset_c": -8.0, "rate_per_h": 1.0, "duration_min": [5.0, 20.0],
             "targets": ["E_Y"]},
    # A hydraulic power pack bolted to the back of the column: it heats the column back,
    # which bends the column (E_Y) -- the column carries no sensor.
    "hidden_source": {"anchor": "column_back", "power_W": 300.0, "targets": ["E_Y"]},
    # A thick motor bracket: ~3 h behind the motor, it yaws the head (E_X).
    "lag_node": {"parent": "headstock", "capacity_J_per_K": 3.0e5, "conductance_W_per_K": 20.0,
                 "convection_W_per_K": 0.5, "sensitivity_um_per_K": {"E_X": 7.0}, "targets": ["E_X"]},
    # The head dwells at heights over the Z travel; the column's front/back gradient tilts it,
    # and the tilt reaches the TCP through the head's height.
    "axis_position": {"axis": "Z", "travel_mm": [0.0, 600.0], "home_mm": 300.0,
                      "tilt_nodes": {"column_back": 1.0, "column_front": -1.0},
                      "gain_um_per_K_per_m": 50.0, "targets": ["E_Y"]},
    # The box sensor's contact degrades in the second half of the year: the held-out campaigns
    # there drift, the training campaigns stay healthy (a fault seen in training is absorbed by
    # the collinear sensors and leaves no residual).
    "sensor_drift": {"column": "T_box1", "mode": "drift", "rate_K_per_h": 0.8, "from_fraction": 0.5,
                     "splits": ["train", "test"], "targets": ["E_X", "E_Z"]},
    "ambient_law": {"level_node": "bed", "threshold_c": 18.5, "gain": 0.8, "targets": ["E_X", "E_Y"]},
}
