r"""Scenario ``climate_room``: many short lathe runs in a climate room, each at its own air level.

After the measured record of issue 34 ("a lathe with 43 test runs in a climate room held at
15-35 °C or ramped; targets X and Z"): ``n_runs`` runs of 8-10 h at 1 min, in calendar
order ``C01..``.  Before each run the room holds the run's level for ``soak_days`` with the
machine off, so the run starts soaked: every node (and every sensor) at the room
temperature, and the run's initial absolute temperatures say the level.  During the run
the room is held there or (share ``ramp_fraction``) ramped linearly by ``ramp_c`` over the
run, towards the middle of ``level_c``.  The spindle and the driven tools run segments of
0.5-2 h at random speeds, each segment on with the run's own duty cycle (drawn per run in
``duty``), idle otherwise (pumps and axes off).  The chronologically last
``test_fraction`` of the runs are ``test``, as the issue's record was cut.

The machine is the Swiss-type lathe of :mod:`~thermocomp.apps.sim.swiss_lathe` (nodes,
links, heat sources, the 12 sensors with ``T_amb``) with the errors of a lathe's X
(radial) and Z (axial) axes, :func:`thermoelastic_map`:
X = 1.6 tool_post + 2.5 tool_holder + 0.9 guide_bush - 0.5 headstock + 0.6 spindle
- 0.3 frame (the Swiss lathe's X, unchanged); Z = 2.3 spindle (~200 mm of shaft ahead
of its fixed front bearing, 11.5 µm/(m K)) + 1.7 headstock (~150 mm from the Z nut to that
bearing) - 1.1 frame (~100 mm from the Z screw's fixed bearing to the guide-bush plane)
- 0.4 guide_bush, µm/K of node rises.

Why the level matters (the material effect of the absolute temperature): the
sensitivities fall by :math:`\beta` per kelvin of the node's start level above 20 °C
(:class:`~thermocomp.apps.sim.thermoelastic.ThermoelasticMap` ``ambient_beta``,
:math:`\beta_X` = 0.015 /K, :math:`\beta_Z` = 0.02 /K, the values of the VMC): bearing
preload, the fits of the spindle cartridge and the bolted joints loosen as the whole
structure warms, so the same heat moves the tool less at 35 °C (-22 % in X, -30 % in Z)
than at 15 °C (+7.5 %, +10 %).  A model on the rises alone cannot see it; the run's
initial absolute temperatures (or ``ambient_c``) can.
"""

from __future__ import annotations

from thermocomp.apps.sim.ambient import DAY_S, HallClimate
from thermocomp.apps.sim.campaign import Machine, Programme
from thermocomp.apps.sim.network import ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan, Scenario
from thermocomp.apps.sim.sources import SPINDLE
from thermocomp.apps.sim.swiss_lathe import (
    AXES,
    LINKS,
    NODES,
    SWISS_LATHE_EFFECTS,
    TOOL,
    convection_rules,
    heat_sources,
    sensors,
)
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
from thermocomp.base.params import FRACTION, NON_NEGATIVE, POSITIVE, integer, number, numbers, span

SCENARIO = "climate_room"
RUN_EVERY_DAYS = 2.0          # one run every other day: the room soaks the machine in between
RAMP_STEP_S = 600.0           # the ramp's setpoint moves in 10-min steps (the room lag smooths them)


def thermoelastic_map() -> ThermoelasticMap:
    """The lathe's X and Z errors (µm/K of node rises), sensitivities falling with the level."""
    return ThermoelasticMap(
        linear={"E_X": {"tool_post": 1.6, "tool_holder": 2.5, "guide_bush": 0.9, "headstock": -0.5,
                        "spindle": 0.6, "frame": -0.3},
                "E_Z": {"spindle": 2.3, "headstock": 1.7, "frame": -1.1, "guide_bush": -0.4}},
        quadratic={"E_X": {"spindle": 0.02}},
        ambient_beta={"E_X": 0.015, "E_Z": 0.02},
        reference_c=20.0)


def climate_room_lathe() -> Machine:
    """The Swiss-type lathe with the X/Z map of :func:`thermoelastic_map`."""
    return Machine(ThermalNetwork(NODES, LINKS), heat_sources(), sensors(), thermoelastic_map(),
                   convection_rules())


# The Swiss lathe's effects, with its Y target read as this lathe's Z (no door is built in: the
# climate room's door stays shut); an ambient law switches in the middle of the room's range.
CLIMATE_ROOM_EFFECTS = {
    name: {**params, "targets": [("E_Z" if t == "E_Y" else t) for t in params["targets"]]}
    for name, params in SWISS_LATHE_EFFECTS.items()}
CLIMATE_ROOM_EFFECTS["ambient_law"]["threshold_c"] = 25.0


class ClimateRoom(Scenario):
    """Generator of the ``climate_room`` dataset: short lathe runs, each at its own air level.

    Parameters
    ----------
    n_runs : int
        Number of runs ``C01..`` in calendar order (one every other day).
    duration_h : (float, float)
        Range of run lengths (h), drawn uniformly, rounded to the sample period.
    sample_period_s : float
        Logger period of temperatures, speeds and both probes (s).
    level_c : (float, float)
        Range of the room levels (°C), one drawn uniformly per run.
    ramp_fraction : float
        Share of runs whose air is ramped by ``ramp_c`` over the run (the others held).
    ramp_c : float
        Size of a ramp (K), up or down, towards the middle of ``level_c`` where the other
        way would leave it.
    soak_days : float
        Days the room holds the run's level before it, the machine off.
    room_tau_h, room_drift_sd_c : float
        The room air's lag behind its setpoint (h) and the s.d. of its slow drift (°C).
    segment_h : (float, float)
        Range of the lengths of the spindle segments (h).
    duty : (float, float)
        Range of the runs' duty cycles: each segment runs with this probability, else idles.
    spindle_rpm, tool_rpm : sequence of float
        Speeds a running segment draws from.
    test_fraction : float
        The chronologically last share of the runs are ``test`` (at least one).
    temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um : float
    effects, effect_params, clean, seed
        See :class:`~thermocomp.apps.sim.scenario.Scenario`.
    """

    name = SCENARIO
    param_rules = {**Scenario.param_rules, "n_runs": integer(2, 1000), "duration_h": span(open_lo=True),
                   "sample_period_s": POSITIVE, "level_c": span(-40.0, 80.0), "ramp_fraction": FRACTION,
                   "ramp_c": NON_NEGATIVE, "soak_days": POSITIVE, "room_tau_h": POSITIVE,
                   "room_drift_sd_c": NON_NEGATIVE, "segment_h": span(open_lo=True),
                   "duty": span(0.0, 1.0), "spindle_rpm": numbers(0.0), "tool_rpm": numbers(0.0),
                   "test_fraction": number(0.0, 1.0, open_lo=True, open_hi=True)}

    def param_relations(self) -> list[tuple[str, str]]:
        if 3600.0 * float(self.duration_h[0]) < 2 * float(self.sample_period_s):
            return [("duration_h", "the shortest run must hold two samples of "
                                   f"sim.generator.sample_period_s={self.sample_period_s}")]
        return []

    def __init__(self, n_runs=43, duration_h=(8.0, 10.0), sample_period_s=60.0, level_c=(15.0, 35.0),
                 ramp_fraction=0.4, ramp_c=5.0, soak_days=2.0, room_tau_h=0.3, room_drift_sd_c=0.05,
                 segment_h=(0.5, 2.0), duty=(0.3, 1.0), spindle_rpm=(2000, 4000, 6000, 8000),
                 tool_rpm=(0, 1500, 3000, 4500, 6000), test_fraction=0.1, temp_noise_c=0.03,
                 temp_quantum_c=0.01, error_noise_um=0.2, error_quantum_um=0.1, effects=(),
                 effect_params=None, clean=False, seed=0):
        self.n_runs = n_runs
        self.duration_h = duration_h
        self.sample_period_s = sample_period_s
        self.level_c = level_c
        self.ramp_fraction = ramp_fraction
        self.ramp_c = ramp_c
        self.soak_days = soak_days
        self.room_tau_h = room_tau_h
        self.room_drift_sd_c = room_drift_sd_c
        self.segment_h = segment_h
        self.duty = duty
        self.spindle_rpm = spindle_rpm
        self.tool_rpm = tool_rpm
        self.test_fraction = test_fraction
        super().__init__(temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um, effects,
                         effect_params, clean, seed)

    def machine(self):
        return climate_room_lathe()

    def effect_defaults(self):
        return CLIMATE_ROOM_EFFECTS

    def _on_grid(self, t_s: float) -> float:
        return self.sample_period_s * max(1, round(t_s / self.sample_period_s))

    def _room(self, start_s: float, duration_s: float, level: float, ramp: float) -> HallClimate:
        """The room: ``level`` from the soak's start, then (``ramp`` != 0) a staircase of
        10-min setpoints from ``level`` to ``level + ramp`` over the run; always conditioned."""
        setpoints = [(start_s - float(self.soak_days) * DAY_S, level)]
        if ramp:
            steps = max(1, int(duration_s // RAMP_STEP_S))
            setpoints += [(start_s + k * duration_s / steps, level + ramp * k / steps)
                          for k in range(1, steps + 1)]
        return HallClimate(setpoints=tuple(setpoints), room_tau_h=float(self.room_tau_h),
                           hvac_hours=(0.0, 24.0), free_c=level, daily_amplitude_c=0.0,
                           drift_sd_c=float(self.room_drift_sd_c), drift_tau_h=2.0)

    def _ramp(self, rng, level: float) -> float:
        """0 (held) or +-ramp_c, turned towards the middle where the other way leaves level_c."""
        if rng.random() >= float(self.ramp_fraction) or not self.ramp_c:
            return 0.0
        ramp = float(self.ramp_c) * (1.0 if rng.random() < 0.5 else -1.0)
        lo, hi = (float(v) for v in self.level_c)
        return -ramp if not lo <= level + ramp <= hi else ramp

    def _programme(self, rng, duration_s: float, duty: float) -> tuple[Programme, Programme]:
        """Segments of random spindle / driven-tool speeds, each running with probability ``duty``."""
        lo, hi = (3600.0 * float(h) for h in self.segment_h)
        spindle, tool, t = [], [], 0.0
        while t < duration_s:
            running = rng.random() < duty
            spindle.append((t, float(rng.choice(self.spindle_rpm)) if running else 0.0))
            tool.append((t, float(rng.choice(self.tool_rpm)) if running else 0.0))
            t += self._on_grid(rng.uniform(lo, hi))
        return Programme(tuple(spindle)), Programme(tuple(tool))

    def plans(self, rng) -> list[CampaignPlan]:
        n = int(self.n_runs)
        n_test = min(n - 1, max(1, int(round(float(self.test_fraction) * n))))
        width = max(2, len(str(n)))
        lo, hi = (3600.0 * float(h) for h in self.duration_h)
        plans = []
        for k, child in enumerate(rng.spawn(n)):
            start = DAY_S * (10.0 + RUN_EVERY_DAYS * k) + 3600.0 * round(child.uniform(7.0, 9.0) * 12) / 12
            duration = self._on_grid(child.uniform(lo, hi))
            level = float(child.uniform(*self.level_c))
            ramp = self._ramp(child, level)
            duty = float(child.uniform(*self.duty))
            spindle, tool = self._programme(child, duration, duty)
            running = Programme(tuple((s, float(rpm > 0)) for s, rpm in spindle.steps))
            kind = f"ramped {ramp:+g} K" if ramp else "held"
            plans.append(CampaignPlan(
                cid=f"C{k + 1:0{width}d}", split="test" if k >= n - n_test else "train",
                start_s=start, duration_s=duration, rng=child,
                ambient=self._room(start, duration, level, ramp),
                programme=spindle, states={TOOL: tool.rpm_at, AXES: running.rpm_at},
                written=(SPINDLE, TOOL), sample_period_s=float(self.sample_period_s),
                cooldown_s=float(self.soak_days) * DAY_S,
                notes=f"room {level:.1f} °C {kind}, duty {duty:.2f}",
                manifest={"room_c": round(level, 2), "ramp_c": ramp, "duty": round(duty, 3),
                          "duration_h": duration / 3600.0},
                truth={"room_c": level, "ramp_c": ramp, "duty": duty,
                       "spindle_programme": [list(map(float, s)) for s in spindle.steps],
                       "tool_programme": [list(map(float, s)) for s in tool.steps]}))
        return plans


__all__ = ["ClimateRoom", "climate_room_lathe", "thermoelastic_map"]
