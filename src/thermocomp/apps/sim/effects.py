r"""Undeclared effects: physics a compensation model was never told about.

Each effect is planted on any scenario with one override,
``thermocomp simulate sim=<scenario> "sim.generator.effects=[door,lag_node]"``,
parameters in ``sim.generator.effect_params.<name>.<key>``, and recorded in the
ground truth's ``undeclared_effects`` as ``{"name", "kind", "column",
"targets", "description", "params"}``; ``kind`` and ``column`` are what a
correct residual diagnosis (``diagnosis.json`` of CLI.md) must report.

Every effect acts through the thermal network or the structure, never as noise
added to an error column, and draws its randomness (schedules, trajectories)
from its own generator seeded by ``(seed, effect, campaign)``: the dataset with
an effect is paired sample by sample with the one without it.

========================  ==============  =====================================================
effect                    kind            mechanism
========================  ==============  =====================================================
``door``                  signal          door openings (``S_door``, 0/1): extra convection
                                          :math:`\Delta hA` on the work-area nodes while open
``hidden_source``         signal          a unit (hydraulic power pack) bolted to a structure
                                          node, switched on and off by its own duty cycle;
                                          only the controller's oil temperature
                                          (``S_hydraulic_temp_C``) sees it
``lag_node``              dynamics        an unmeasured mass between a heated node and the
                                          structure, :math:`C\dot T_l = G(T_p - T_l) +
                                          hA(T_a - T_l)`, with its own sensitivity
``axis_position``         interaction     an axis dwells at positions :math:`p(t)`
                                          (``S_pos_<axis>``, mm); a thermal tilt
                                          :math:`\varphi = \sum_j w_j\Delta_j` acts through the
                                          lever :math:`p - p(0)`:
                                          :math:`\Delta E = g\,\varphi\,(p - p(0))`
``sensor_drift``          sensor_fault    one declared sensor drifts by :math:`r\,(t - t_0)^+`
                                          (or freezes) partway through the campaigns
``ambient_law``           ambient_interval the sensitivities of the targets grow by a factor
                                          :math:`1 + \gamma\,\sigma((T_{lev} - T_{thr})/w)`
                                          once the structure's level passes a threshold
``ageing``                dynamics        the machine ages after training: in the campaigns of
                                          ``splits`` the targets' sensitivities grow by a factor
                                          :math:`1 + g\,(k + 1)/K` (campaign :math:`k` of
                                          :math:`K`); *extension*, issue 36 item 6
``sensor_faults``         sensor_fault    one sensor's *reading* fails in the written test
                                          campaigns: freeze, jump, dropout (empty cells), drift,
                                          or a spike on the reference (first) sample
========================  ==============  =====================================================

``axis_position``: with ``p(0)`` the home position of every campaign, the term
is a product of the referenced position and a temperature rise, so a correct
diagnosis reports ``kind = "interaction"`` with ``column = "S_pos_<axis>"``.
``hidden_source``: the oil temperature is a controller signal, written as an
``S_`` column so that no ``T_*`` glob declares it; set
``effect_params.hidden_source.column=T_<name>`` to write it as a declared
sensor instead (then only a selection that drops it leaves the effect unseen).
``sensor_faults`` is the one effect that does not act through the physics: it
rewrites the written campaign files (:meth:`UndeclaredEffect.modify_dataset`,
after the measurement chain and, for ``long_record``, after the cut), so the
thermal network and the errors are untouched and every healthy sample is the
one of the dataset without it.
"""

from __future__ import annotations

import copy
import math
import zlib
from typing import ClassVar

import numpy as np

from thermocomp.apps.sim.campaign import CampaignContext, Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.sensors import first_order_lag, quantise
from thermocomp.apps.sim.sources import ConstantWhileRunning, StateConvection
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap
from thermocomp.base.errors import ConfigError
from thermocomp.base.params import (
    FRACTION,
    NON_NEGATIVE,
    POSITIVE,
    check_params,
    choice,
    integer,
    number,
    number_map,
    optional,
    span,
    subset,
)

KINDS = ("signal", "dynamics", "ambient_interval", "interaction", "nonlinear", "sensor_fault")


def extend_machine(machine: Machine, *, nodes=(), links=(), sources=(), rules=(),
                   linear: dict | None = None) -> Machine:
    """A new machine with extra nodes, links, sources, convection rules and sensitivities."""
    network = ThermalNetwork(list(machine.network.nodes) + list(nodes),
                             list(machine.network.links) + list(links))
    te = machine.thermoelastic
    coefficients = copy.deepcopy(te.linear)
    for target, extra in (linear or {}).items():
        if target not in coefficients:
            raise ConfigError(f"effect sensitivity names unknown target {target!r} "
                              f"(have {list(coefficients)})")
        for node, value in extra.items():
            coefficients[target][node] = coefficients[target].get(node, 0.0) + float(value)
    thermoelastic = ThermoelasticMap(coefficients, copy.deepcopy(te.quadratic),
                                     dict(te.ambient_beta), te.reference_c)
    return Machine(network, list(machine.sources) + list(sources), list(machine.sensors),
                   thermoelastic, list(machine.convection_rules) + list(rules))


def intervals_signal(intervals) -> callable:
    """0/1 signal of campaign time: 1 inside any ``[start, end)`` interval."""
    starts = np.array([a for a, _ in intervals], dtype=float)
    ends = np.array([b for _, b in intervals], dtype=float)

    def signal(t):
        t = np.asarray(t, dtype=float)[..., None]
        return np.any((t >= starts - 1e-6) & (t < ends - 1e-6), axis=-1).astype(float)
    return signal


def _on_grid(t_s: float, grid_s: float) -> float:
    return grid_s * max(1, round(t_s / grid_s))


class UndeclaredEffect:
    """Base class: hooks called by :func:`~thermocomp.apps.sim.campaign.run_campaign`.

    Parameters
    ----------
    seed : int
        Scenario seed; the effect's generator per campaign is
        ``default_rng([seed, crc32(name), campaign index])``.
    **params
        Overrides of :attr:`defaults` (unknown keys are a ConfigError).
    """

    name: ClassVar[str] = ""
    kind: ClassVar[str] = ""
    defaults: ClassVar[dict] = {}
    param_rules: ClassVar[dict] = {}     # what each parameter may be (thermocomp.base.params)

    def __init__(self, seed: int = 0, **params):
        unknown = set(params) - set(self.defaults)
        if unknown:
            raise ConfigError(f"sim.generator.effect_params.{self.name}: unknown key(s) "
                              f"{sorted(unknown)} (known: {sorted(self.defaults)})")
        self.seed = int(seed)
        self.params = {**copy.deepcopy(self.defaults), **params}
        check_params(self, f"sim.generator.effect_params.{self.name}", self.params)

    # --- hooks (no-ops by default) -------------------------------------------------------
    def modify_machine(self, machine: Machine) -> Machine:
        return machine

    def campaign_states(self, ctx: CampaignContext, t_rel: np.ndarray, fine: dict) -> dict:
        return {}

    def written_states(self, ctx: CampaignContext) -> list[str]:
        return []

    def modify_readings(self, ctx: CampaignContext, readings: np.ndarray) -> np.ndarray:
        return readings

    def modify_errors(self, ctx: CampaignContext, errors: np.ndarray) -> np.ndarray:
        return errors

    def extra_columns(self, ctx: CampaignContext) -> dict:
        return {}

    def modify_dataset(self, dataset, truth: dict) -> tuple:
        """Change the written campaigns (after the measurement chain and any cut of the
        record) and their truth; returns ``(dataset, truth)``."""
        return dataset, truth

    # --- bookkeeping ----------------------------------------------------------------------
    @property
    def column(self) -> str | None:
        return None

    @property
    def targets(self) -> list[str]:
        return list(self.params.get("targets", []))

    def description(self) -> str:
        return (self.__doc__ or "").strip().splitlines()[0]

    def rng(self, ctx: CampaignContext) -> np.random.Generator:
        return np.random.default_rng([self.seed, zlib.crc32(self.name.encode()), ctx.index])

    def record(self) -> dict:
        return {"name": self.name, "kind": self.kind, "column": self.column,
                "targets": self.targets, "description": self.description(),
                "params": copy.deepcopy(self.params)}

    def check_targets(self, machine: Machine) -> None:
        """Every target named in ``targets`` an error of ``machine``: the truth records them as
        what a correct diagnosis must find, so a target the data has no column of (``E_Q``) was
        a truth no diagnosis could meet, written without a word."""
        self._target_rows(machine)

    def _target_rows(self, machine: Machine) -> list[int]:
        self._check_targets(machine, self.targets, "targets")
        return [machine.thermoelastic.targets.index(t) for t in self.targets]

    def _check_targets(self, machine: Machine, targets, key: str) -> None:
        known = machine.thermoelastic.targets
        missing = [t for t in targets if t not in known]
        if missing:
            raise ConfigError(f"sim.generator.effect_params.{self.name}.{key}: unknown "
                              f"target(s) {missing} (have {known})")

    def _check_nodes(self, machine: Machine, nodes, key: str) -> None:
        unknown = [n for n in nodes if n not in machine.network.index]
        if unknown:
            raise ConfigError(f"sim.generator.effect_params.{self.name}.{key}: unknown node(s) "
                              f"{unknown} (have {list(machine.network.names)})")


class Door(UndeclaredEffect):
    """Door openings: shop air sweeps the work area while the door is open (S_door = 1)."""

    name, kind = "door", "signal"
    param_rules = {"nodes": number_map(0.0), "air_offset_c": number(), "rate_per_h": NON_NEGATIVE,
                   "duration_min": span(open_lo=True)}
    defaults = {
        "column": "S_door",
        "nodes": {},                 # node -> extra convection hA (W/K) while open
        "air_offset_c": 0.0,         # the draught's temperature minus the ambient sensor's
        "rate_per_h": 0.5,           # mean number of openings per hour of campaign
        "duration_min": [5.0, 20.0],  # uniform range of one opening (rounded to the samples)
        "targets": [],
    }

    @property
    def column(self):
        return self.params["column"]

    def description(self):
        nodes = ", ".join(f"{n} +{g:g} W/K" for n, g in self.params["nodes"].items())
        return (f"door openings ({self.column} 0/1, ~{self.params['rate_per_h']:g}/h, "
                f"{self.params['duration_min'][0]:g}-{self.params['duration_min'][1]:g} min): "
                f"shop air {self.params['air_offset_c']:+g} K from the ambient sensor sweeps the "
                f"work area, extra convection on {nodes}")

    def modify_machine(self, machine):
        nodes = dict(self.params["nodes"])
        if not nodes:
            raise ConfigError("sim.generator.effect_params.door.nodes is empty: say which nodes the "
                              "open door exposes")
        self._check_nodes(machine, nodes, "nodes")
        rules = [StateConvection(node, float(g), signal=self.column, scale=1.0, exponent=0.0)
                 for node, g in nodes.items()]
        # Convection g to air at T_a + offset = convection g to T_a plus a heat g * offset.
        offset = float(self.params["air_offset_c"])
        draughts = [ConstantWhileRunning(f"door_draught_{node}", {node: 1.0}, power_W=float(g) * offset,
                                         when=self.column) for node, g in nodes.items() if offset]
        return extend_machine(machine, rules=rules, sources=draughts)

    def openings(self, rng, duration_s: float, grid_s: float) -> list[tuple[float, float]]:
        """Poisson openings (mean gap 1/rate), each ``duration_min`` long, on the sample grid."""
        rate = float(self.params["rate_per_h"]) / 3600.0
        lo, hi = (60.0 * float(m) for m in self.params["duration_min"])
        out, t = [], 0.0
        if rate <= 0:
            return out
        while True:
            t = _on_grid(t + rng.exponential(1.0 / rate), grid_s)
            length = _on_grid(rng.uniform(lo, hi), grid_s)
            if t + length >= duration_s:
                return out
            out.append((t, t + length))
            t += length

    def campaign_states(self, ctx, t_rel, fine):
        if self.column in fine:   # the scenario's own door programme (the lathe)
            return {}
        intervals = self.openings(self.rng(ctx), ctx.duration_s, ctx.sample_period_s)
        ctx.truth.setdefault(self.name, {})["openings_s"] = [list(map(float, i)) for i in intervals]
        return {self.column: intervals_signal(intervals)(t_rel)}

    def written_states(self, ctx):
        return [self.column]


class HiddenSource(UndeclaredEffect):
    """A hydraulic power unit bolted to the structure, switched by its own duty cycle."""

    name, kind = "hidden_source", "signal"
    param_rules = {"power_W": NON_NEGATIVE, "capacity_J_per_K": POSITIVE,
                   "convection_W_per_K": NON_NEGATIVE, "conductance_W_per_K": POSITIVE,
                   "on_min": span(open_lo=True), "off_min": span(open_lo=True),
                   "noise_c": NON_NEGATIVE, "quantum_c": NON_NEGATIVE}
    defaults = {
        "column": "S_hydraulic_temp_C",  # the controller's oil temperature, the only witness
        "anchor": "",                    # structure node the unit is bolted to
        "power_W": 250.0,                # pump and valve losses while running
        "capacity_J_per_K": 4.0e4,       # ~20 l of oil and a steel tank
        "convection_W_per_K": 4.0,
        "conductance_W_per_K": 12.0,     # bolted flange to the structure
        "on_min": [40.0, 120.0],         # duty cycle: on and off spells (uniform ranges)
        "off_min": [40.0, 120.0],
        "noise_c": 0.05,                 # NC temperature channel
        "quantum_c": 0.1,
        "targets": [],
    }
    NODE = "hydraulic_unit"
    STATE = "_hydraulic_on"   # internal: not written (the '_' prefix is no contract column)

    @property
    def column(self):
        return self.params["column"]

    def description(self):
        p = self.params
        return (f"hydraulic unit ({p['power_W']:g} W while on, on {p['on_min'][0]:g}-{p['on_min'][1]:g}"
                f" min / off {p['off_min'][0]:g}-{p['off_min'][1]:g} min) bolted to {p['anchor']}; "
                f"only {self.column} (its oil temperature) sees it")

    def modify_machine(self, machine):
        p = self.params
        if not self.column.startswith(("S_", "T_")):
            raise ConfigError(f"sim.generator.effect_params.hidden_source.column must start with "
                              f"S_ or T_, got {self.column!r}")
        self._check_nodes(machine, [p["anchor"]], "anchor")
        return extend_machine(
            machine,
            nodes=[Node(self.NODE, float(p["capacity_J_per_K"]), float(p["convection_W_per_K"]))],
            links=[Link(self.NODE, p["anchor"], float(p["conductance_W_per_K"]))],
            sources=[ConstantWhileRunning("hidden_hydraulic_unit", {self.NODE: 1.0},
                                          power_W=float(p["power_W"]), when=self.STATE)])

    def campaign_states(self, ctx, t_rel, fine):
        rng = self.rng(ctx)
        grid = ctx.sample_period_s
        on = [60.0 * float(m) for m in self.params["on_min"]]
        off = [60.0 * float(m) for m in self.params["off_min"]]
        running, t, intervals = bool(rng.random() < 0.5), 0.0, []
        while t < ctx.duration_s:
            length = _on_grid(rng.uniform(*(on if running else off)), grid)
            if running:
                intervals.append((t, min(t + length, ctx.duration_s + grid)))
            t += length
            running = not running
        ctx.truth.setdefault(self.name, {})["on_s"] = [list(map(float, i)) for i in intervals]
        return {self.STATE: intervals_signal(intervals)(t_rel)}

    def extra_columns(self, ctx):
        rng = np.random.default_rng([self.seed, zlib.crc32(b"hidden_source/noise"), ctx.index])
        node = ctx.node_temps[:, ctx.machine.network.index[self.NODE]]
        value = quantise(node + float(self.params["noise_c"]) * rng.standard_normal(len(node)),
                         float(self.params["quantum_c"]))
        return {self.column: value}


class LagNode(UndeclaredEffect):
    """An unmeasured internal mass that follows a heated node with a long lag and moves the TCP."""

    name, kind = "lag_node", "dynamics"
    param_rules = {"capacity_J_per_K": POSITIVE, "conductance_W_per_K": POSITIVE,
                   "convection_W_per_K": NON_NEGATIVE, "sensitivity_um_per_K": number_map()}
    defaults = {
        "parent": "",                    # the heated node it hangs on
        "capacity_J_per_K": 2.0e5,
        "conductance_W_per_K": 30.0,
        "convection_W_per_K": 1.0,
        "sensitivity_um_per_K": {},      # target -> µm/K of the lag mass
        "targets": [],
    }
    NODE = "lag_mass"

    def time_constant_s(self) -> float:
        p = self.params
        drain = float(p["conductance_W_per_K"]) + float(p["convection_W_per_K"])
        return float(p["capacity_J_per_K"]) / drain

    def description(self):
        return (f"unmeasured internal mass on {self.params['parent']} (time constant "
                f"{self.time_constant_s() / 3600:.1f} h) moving "
                + ", ".join(f"{t} {s:g} µm/K" for t, s in self.params["sensitivity_um_per_K"].items()))

    def record(self):
        out = super().record()
        out["params"]["time_constant_s"] = self.time_constant_s()
        return out

    def modify_machine(self, machine):
        p = self.params
        self._check_nodes(machine, [p["parent"]], "parent")
        # the key named: extend_machine's message said only "effect sensitivity"
        self._check_targets(machine, p["sensitivity_um_per_K"], "sensitivity_um_per_K")
        return extend_machine(
            machine,
            nodes=[Node(self.NODE, float(p["capacity_J_per_K"]), float(p["convection_W_per_K"]))],
            links=[Link(self.NODE, p["parent"], float(p["conductance_W_per_K"]))],
            linear={t: {self.NODE: float(s)} for t, s in p["sensitivity_um_per_K"].items()})


class AxisPosition(UndeclaredEffect):
    """An axis dwells at varying positions; a thermal tilt acts on the TCP through its lever."""

    name, kind = "axis_position", "interaction"
    param_rules = {"travel_mm": span(-math.inf), "home_mm": number(),
                   "dwell_min": span(open_lo=True), "tilt_nodes": number_map(),
                   "gain_um_per_K_per_m": number()}
    defaults = {
        "axis": "Z",
        "travel_mm": [0.0, 500.0],
        "home_mm": 250.0,                # every campaign starts here (the lever's zero)
        "dwell_min": [15.0, 60.0],       # time at one position (uniform range)
        "tilt_nodes": {},                # node -> weight; tilt = sum w_j * rise_j (K)
        "gain_um_per_K_per_m": 20.0,     # alpha / depth of the tilting structure
        "targets": [],
    }

    @property
    def column(self):
        return f"S_pos_{self.params['axis']}"

    def description(self):
        tilt = " ".join(f"{w:+g}*{n}" for n, w in self.params["tilt_nodes"].items())
        return (f"{self.column} (mm) dwells over {self.params['travel_mm']}; the thermal tilt "
                f"({tilt}) acts through the lever p - p(0): {self.params['gain_um_per_K_per_m']:g} "
                f"µm/(K m) on {', '.join(self.targets)}; a product of the position and a rise")

    def modify_machine(self, machine):
        self._check_nodes(machine, self.params["tilt_nodes"], "tilt_nodes")
        self._target_rows(machine)
        return machine

    def trajectory(self, rng, duration_s: float, grid_s: float) -> list[tuple[float, float]]:
        """(start s, position mm) steps from the home position."""
        lo, hi = (float(v) for v in self.params["travel_mm"])
        dwell = [60.0 * float(m) for m in self.params["dwell_min"]]
        steps, t = [(0.0, float(self.params["home_mm"]))], 0.0
        while True:
            t = t + _on_grid(rng.uniform(*dwell), grid_s)
            if t >= duration_s:
                return steps
            steps.append((t, float(np.round(rng.uniform(lo, hi), 1))))

    def campaign_states(self, ctx, t_rel, fine):
        if self.column in fine:   # the scenario moves this axis itself
            return {}
        steps = self.trajectory(self.rng(ctx), ctx.duration_s, ctx.sample_period_s)
        starts = np.array([s for s, _ in steps])
        values = np.array([v for _, v in steps])
        return {self.column: values[np.searchsorted(starts, t_rel + 1e-6, side="right") - 1]}

    def written_states(self, ctx):
        return [self.column]

    def tilt(self, ctx) -> np.ndarray:
        index = ctx.machine.network.index
        rise = ctx.node_temps - ctx.node_temps[0]
        return sum(float(w) * rise[:, index[n]] for n, w in self.params["tilt_nodes"].items())

    def modify_errors(self, ctx, errors):
        position = ctx.states[self.column]
        lever_m = (position - position[0]) / 1000.0
        extra = float(self.params["gain_um_per_K_per_m"]) * self.tilt(ctx) * lever_m
        errors = errors.copy()
        for row in self._target_rows(ctx.machine):
            errors[:, row] += extra
        return errors


class SensorDrift(UndeclaredEffect):
    """One declared temperature sensor drifts (or freezes) partway through the campaigns."""

    name, kind = "sensor_drift", "sensor_fault"
    param_rules = {"mode": choice("drift", "stuck"), "rate_K_per_h": number(),
                   "onset_fraction": FRACTION, "from_fraction": FRACTION,
                   "splits": subset(("train", "val", "test"))}
    defaults = {
        "column": "",
        "mode": "drift",                 # drift: + rate*(t - t0); stuck: frozen from t0
        "rate_K_per_h": 0.5,
        "onset_fraction": 0.3,           # t0 as a fraction of each affected campaign
        "from_fraction": 0.0,            # campaigns from this fraction of the calendar on
        "splits": ["train", "test"],     # splits whose campaigns (from then on) are affected
        "targets": [],
    }

    @property
    def column(self):
        return self.params["column"]

    def description(self):
        p = self.params
        what = (f"drifts by {p['rate_K_per_h']:g} K/h" if p["mode"] == "drift" else "freezes")
        return (f"sensor {self.column} {what} from {p['onset_fraction']:.0%} of each campaign on "
                f"({'/'.join(p['splits'])} campaigns from {p['from_fraction']:.0%} of the calendar on): "
                f"a degrading contact")

    def modify_machine(self, machine):
        if self.column not in machine.sensor_array.columns:
            raise ConfigError(f"sim.generator.effect_params.sensor_drift.column: {self.column!r} is "
                              f"no sensor (have {machine.sensor_array.columns})")
        if self.params["mode"] not in ("drift", "stuck"):
            raise ConfigError("sim.generator.effect_params.sensor_drift.mode must be drift or stuck")
        return machine

    def affected(self, ctx) -> bool:
        return (ctx.split in self.params["splits"]
                and ctx.index >= float(self.params["from_fraction"]) * ctx.n_campaigns)

    def fault(self, ctx, true_reading: np.ndarray) -> np.ndarray:
        """Faulty reading (°C) from the healthy one at the samples."""
        if not self.affected(ctx):
            return true_reading
        t0 = float(self.params["onset_fraction"]) * ctx.duration_s
        after = ctx.times_s >= t0
        out = true_reading.copy()
        if self.params["mode"] == "drift":
            out += float(self.params["rate_K_per_h"]) * np.clip(ctx.times_s - t0, 0, None) / 3600.0
        elif after.any():
            out[after] = true_reading[np.argmax(after)]
        ctx.truth.setdefault(self.name, {})["onset_s"] = t0
        return out

    def modify_readings(self, ctx, readings):
        j = ctx.machine.sensor_array.columns.index(self.column)
        readings = readings.copy()
        readings[:, j] = self.fault(ctx, readings[:, j])
        return readings


class AmbientLaw(UndeclaredEffect):
    """The thermoelastic law changes with the ambient level (an unmodelled ambient interval)."""

    name, kind = "ambient_law", "ambient_interval"
    param_rules = {"level_lag_h": NON_NEGATIVE, "threshold_c": number(), "width_c": POSITIVE,
                   "gain": number()}
    defaults = {
        "level_node": "",                # node (or "ambient": the air) whose level sets the interval
        "level_lag_h": 0.0,              # the level is that temperature through a first-order lag
        "threshold_c": 20.0,
        "width_c": 0.3,                  # logistic transition width
        "gain": 0.5,                     # relative growth of the targets' sensitivities above
        "targets": [],
    }

    def description(self):
        p = self.params
        lag = f" (lagged {p['level_lag_h']:g} h)" if p["level_lag_h"] else ""
        return (f"above {p['threshold_c']:g} °C of {p['level_node']}{lag} the sensitivities of "
                f"{', '.join(self.targets)} grow by {p['gain']:.0%} (a joint that clamps "
                f"differently once the structure is warm)")

    def modify_machine(self, machine):
        if self.params["level_node"] != "ambient":
            self._check_nodes(machine, [self.params["level_node"]], "level_node")
        self._target_rows(machine)
        return machine

    def factor(self, level_c: np.ndarray) -> np.ndarray:
        """Relative change :math:`\\gamma\\,\\sigma((T_{lev} - T_{thr})/w)` of the sensitivities."""
        p = self.params
        z = (np.asarray(level_c, dtype=float) - float(p["threshold_c"])) / float(p["width_c"])
        return float(p["gain"]) / (1.0 + np.exp(-np.clip(z, -50, 50)))

    def level(self, node_temps: np.ndarray, ambient: np.ndarray, times_s: np.ndarray,
              index: dict) -> np.ndarray:
        """Level temperature (°C) at the samples."""
        name = self.params["level_node"]
        raw = np.asarray(ambient if name == "ambient" else node_temps[:, index[name]], dtype=float)
        tau = 3600.0 * float(self.params["level_lag_h"])
        if tau > 0 and len(raw) > 1:
            return first_order_lag(raw[:, None], [tau], float(times_s[1] - times_s[0]))[:, 0]
        return raw

    def modify_errors(self, ctx, errors):
        machine = ctx.machine
        index = machine.network.index
        rise = ctx.node_temps - ctx.node_temps[0]
        gain = self.factor(self.level(ctx.node_temps, ctx.ambient, ctx.times_s, index))
        share = float(np.mean(gain > 0.5 * float(self.params["gain"])))
        ctx.truth.setdefault(self.name, {})["share_above"] = share
        errors = errors.copy()
        for row in self._target_rows(machine):
            target = machine.thermoelastic.targets[row]
            coefficients = machine.thermoelastic.linear[target]
            linear = sum(float(v) * rise[:, index[n]] for n, v in coefficients.items())
            errors[:, row] += gain * linear
        return errors


class Ageing(UndeclaredEffect):
    """The machine ages after training: the thermoelastic law of the later campaigns drifts."""

    name, kind = "ageing", "dynamics"
    param_rules = {"gain": number(), "splits": subset(("train", "val", "test"))}
    defaults = {
        "gain": 0.4,                     # relative growth of the sensitivities at the last campaign
        "splits": ["test"],              # the campaigns recorded after the model was trained
        "targets": [],                   # [] = every target
    }

    @property
    def targets(self):
        return list(self.params["targets"]) or list(getattr(self, "_all", []))

    def description(self):
        p = self.params
        return (f"in the {'/'.join(p['splits'])} campaigns the sensitivities of "
                f"{', '.join(self.targets) or 'every target'} grow by up to {p['gain']:.0%} "
                "over the series (a machine that ages: wear, preload, a settling joint)")

    def modify_machine(self, machine):
        self._all = list(machine.thermoelastic.targets)
        self._target_rows(machine)
        return machine

    def factor(self, ctx) -> float:
        r"""Relative change :math:`g\,(k + 1)/K` of the sensitivities in campaign ``ctx``."""
        if ctx.split not in self.params["splits"]:
            return 0.0
        return float(self.params["gain"]) * (ctx.index + 1) / max(ctx.n_campaigns, 1)

    def modify_errors(self, ctx, errors):
        machine = ctx.machine
        index = machine.network.index
        rise = ctx.node_temps - ctx.node_temps[0]
        factor = self.factor(ctx)
        ctx.truth.setdefault(self.name, {})["factor"] = factor
        errors = errors.copy()
        for row in self._target_rows(machine):
            coefficients = machine.thermoelastic.linear[machine.thermoelastic.targets[row]]
            errors[:, row] += factor * sum(float(v) * rise[:, index[n]] for n, v in coefficients.items())
        return errors


FAULT_KINDS = ("freeze", "jump", "dropout", "drift", "spike_ref")


def is_ambient(column: str) -> bool:
    """``T_amb`` or ``T_amb_<name>``: an air sensor (DATA_FORMAT.md)."""
    return column == "T_amb" or column.startswith("T_amb_")


class SensorFaults(UndeclaredEffect):
    """One temperature sensor's reading fails partway through the affected campaigns.

    Acts on the written files only (:meth:`modify_dataset`): the thermal
    network and the errors are untouched, and every sample outside the fault
    is the one of the dataset without it (same seed).  ``kind``:

    ``freeze``
        from the onset on the reading keeps the value it had at the onset,
        exactly (no noise);
    ``jump``
        ``+magnitude_c`` from the onset on (a step offset);
    ``dropout``
        empty cells from the onset for ``duration_samples`` (null: to the end);
    ``drift``
        ``+rate_K_per_h * (t - t_onset)`` from the onset on;
    ``spike_ref``
        the campaign's first sample (the reference sample) reads
        ``+magnitude_c``; the others are healthy.

    The onset is ``onset_fraction`` of each affected campaign's duration,
    snapped to the nearest sample; faulty values are quantised like the
    logger's.  ``column=""`` draws a non-ambient sensor with the effect's own
    generator (``default_rng([seed, crc32(name)])``).  The truth records, per
    affected campaign, ``kind``, ``column``, ``onset_s``, ``onset_index`` (row of
    the written file), ``end_index`` (first row after the fault) and the size
    (``magnitude_c``, ``rate_K_per_h``, ``held_c`` or ``duration_samples``).
    """

    name, kind = "sensor_faults", "sensor_fault"
    param_rules = {"kind": choice(*FAULT_KINDS), "magnitude_c": number(), "rate_K_per_h": number(),
                   "onset_fraction": FRACTION, "duration_samples": optional(integer(1)),
                   "splits": subset(("train", "val", "test"))}
    defaults = {
        "kind": "jump",                  # one of FAULT_KINDS
        "column": "",                    # "" = drawn among the non-ambient sensors
        "magnitude_c": 3.0,              # jump, spike_ref
        "rate_K_per_h": 1.0,             # drift
        "onset_fraction": 0.5,           # onset as a fraction of each affected campaign
        "duration_samples": None,        # dropout length; None = to the end of the campaign
        "splits": ["test"],              # splits whose campaigns are affected
        "campaigns": None,               # campaign ids to restrict to (None = all of `splits`)
        "targets": [],
    }

    def __init__(self, seed: int = 0, **params):
        super().__init__(seed, **params)
        p = self.params
        self.column_ = p["column"] or None

    @property
    def column(self):
        return self.column_

    def description(self):
        p = self.params
        size = {"jump": f"+{p['magnitude_c']:g} °C step", "spike_ref": f"+{p['magnitude_c']:g} °C "
                "on the reference (first) sample", "drift": f"drift of {p['rate_K_per_h']:g} K/h",
                "freeze": "frozen reading", "dropout": "dropout (empty cells)"}[p["kind"]]
        where = "" if p["kind"] == "spike_ref" else f" from {p['onset_fraction']:.0%} of each campaign on"
        return (f"sensor {self.column or '(drawn)'} fails: {size}{where} "
                f"({'/'.join(p['splits'])} campaigns); the physics and the errors are untouched")

    def modify_machine(self, machine):
        sensors = list(machine.sensor_array.columns)
        if self.params["column"]:
            if self.params["column"] not in sensors:
                raise ConfigError(f"sim.generator.effect_params.{self.name}.column: "
                                  f"{self.params['column']!r} is no sensor (have {sensors})")
        else:
            candidates = [c for c in sensors if not is_ambient(c)]
            rng = np.random.default_rng([self.seed, zlib.crc32(self.name.encode())])
            self.column_ = str(candidates[int(rng.integers(len(candidates)))])
        return machine

    def affected(self, dataset) -> list[str]:
        """Ids of the campaigns the fault hits (``splits``, restricted to ``campaigns``)."""
        key = f"sim.generator.effect_params.{self.name}"
        ids = [c for c in dataset.ids() if dataset.manifest.loc[c, "split"] in self.params["splits"]]
        wanted = self.params["campaigns"]
        if wanted is not None:
            wanted = [str(c) for c in ([wanted] if isinstance(wanted, str) else wanted)]
            unknown = [c for c in wanted if c not in dataset.ids()]
            if unknown:
                raise ConfigError(f"{key}.campaigns: unknown {unknown} (have {dataset.ids()})")
            ids = [c for c in ids if c in wanted]
        if not ids:
            raise ConfigError(f"{key} hits no campaign (splits={list(self.params['splits'])}, "
                              f"campaigns={wanted}; have {dict(dataset.manifest['split'])})")
        return ids

    def fault(self, time_s: np.ndarray, reading: np.ndarray, quantum_c: float = 0.0
              ) -> tuple[np.ndarray, dict]:
        """The faulty reading of one campaign from its healthy one, and its truth."""
        p = self.params
        kind, n = p["kind"], len(time_s)
        onset = 0
        if kind != "spike_ref":
            t0 = time_s[0] + float(p["onset_fraction"]) * (time_s[-1] - time_s[0])
            onset = int(np.argmin(np.abs(time_s - t0)))
        out, end = reading.astype(float).copy(), n
        truth = {"kind": kind, "column": self.column, "onset_index": onset,
                 "onset_s": float(time_s[onset])}
        if kind == "freeze":
            out[onset:] = reading[onset]
            truth["held_c"] = float(reading[onset])
        elif kind == "jump":
            out[onset:] = quantise(reading[onset:] + float(p["magnitude_c"]), quantum_c)
            truth["magnitude_c"] = float(p["magnitude_c"])
        elif kind == "drift":
            hours = (time_s[onset:] - time_s[onset]) / 3600.0
            out[onset:] = quantise(reading[onset:] + float(p["rate_K_per_h"]) * hours, quantum_c)
            truth["rate_K_per_h"] = float(p["rate_K_per_h"])
        elif kind == "dropout":
            if p["duration_samples"] is not None:
                end = min(n, onset + int(p["duration_samples"]))
            out[onset:end] = np.nan
            truth["duration_samples"] = end - onset
        else:  # spike_ref: the reference sample only
            end = 1
            out[0] = quantise(reading[:1] + float(p["magnitude_c"]), quantum_c)[0]
            truth["magnitude_c"] = float(p["magnitude_c"])
        truth["end_index"] = end
        return out, truth

    def modify_dataset(self, dataset, truth):
        quantum = float(truth.get("noise", {}).get("temperature_quantum_c") or 0.0)
        faults = {}
        for cid in self.affected(dataset):
            frame = dataset.campaigns[cid]
            values, faults[cid] = self.fault(frame["time"].to_numpy(), frame[self.column].to_numpy(),
                                             quantum)
            dataset.campaigns[cid] = frame.assign(**{self.column: values})
            truth["campaigns"][cid].setdefault("effects", {})[self.name] = faults[cid]
        for record in truth["undeclared_effects"]:
            if record["name"] == self.name:
                record["campaigns"] = faults
        return dataset, truth


EFFECTS = {cls.name: cls for cls in (Door, HiddenSource, LagNode, AxisPosition, SensorDrift, AmbientLaw,
                                      Ageing, SensorFaults)}


def build_effects(names, params: dict | None, defaults: dict, seed: int) -> list[UndeclaredEffect]:
    """Effects ``names`` with parameters ``defaults[name]`` updated by ``params[name]``."""
    params = params or {}
    out = []
    for name in names:
        if name not in EFFECTS:
            raise ConfigError(f"sim.generator.effects: unknown effect {name!r} "
                              f"(known: {', '.join(EFFECTS)})")
        merged = {**copy.deepcopy(defaults.get(name, {})), **dict(params.get(name) or {})}
        out.append(EFFECTS[name](seed, **merged))
    return out
