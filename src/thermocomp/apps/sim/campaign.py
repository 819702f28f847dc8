"""One thermal test campaign on a machine: cool-down, spindle programme, sampling.

The machine rests (no heat) for ``cooldown_s`` in the workshop air, starting
from equilibrium with it, so a campaign starts near equilibrium but with the
small lags of the heavy castings behind the daily swing, as on a real shop
floor.  Then the programme runs and the sensors and the error probes are
sampled every ``sample_period_s``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from thermocomp.apps.sim.network import ThermalNetwork
from thermocomp.apps.sim.sensors import SensorArray, TemperatureSensor, quantise
from thermocomp.apps.sim.sources import SPINDLE, HeatInjector, HeatSource, StateConvection
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap


@dataclass(frozen=True)
class Programme:
    """Spindle speed as a step function: ``steps`` = ((start s, rpm), ...) from t = 0."""

    steps: tuple

    def __post_init__(self):
        starts = [s for s, _ in self.steps]
        if not starts or starts[0] != 0 or any(b <= a for a, b in zip(starts, starts[1:])):
            raise ValueError(f"programme steps must start at 0 and increase: {self.steps}")

    def rpm_at(self, t_s) -> np.ndarray:
        """Commanded speed (rpm) at campaign times ``t_s`` (s)."""
        starts = np.array([s for s, _ in self.steps], dtype=float)
        speeds = np.array([r for _, r in self.steps], dtype=float)
        return speeds[np.searchsorted(starts, np.asarray(t_s, dtype=float), side="right") - 1]

    def describe(self) -> str:
        return ", ".join(f"{rpm:g} rpm from {int(start // 3600)}:{int(start % 3600 // 60):02d}"
                         for start, rpm in self.steps)


@dataclass
class Machine:
    """A digital twin: thermal network, heat sources, sensors and thermoelastic map."""

    network: ThermalNetwork
    sources: list[HeatSource]
    sensors: list[TemperatureSensor]
    thermoelastic: ThermoelasticMap
    convection_rules: list[StateConvection] = field(default_factory=list)
    injector: HeatInjector = field(init=False, repr=False)
    sensor_array: SensorArray = field(init=False, repr=False)

    def __post_init__(self):
        self.injector = HeatInjector(self.network, self.sources)
        self.sensor_array = SensorArray(self.sensors, self.network.names)
        unknown = {n for coefs in self.thermoelastic.linear.values() for n in coefs} - set(self.network.index)
        if unknown:
            raise ValueError(f"thermoelastic map uses unknown nodes {sorted(unknown)}")

    def to_dict(self) -> dict:
        return {
            "network": self.network.to_dict(),
            "heat_sources": [s.to_dict() for s in self.sources],
            "convection_rules": [r.to_dict() for r in self.convection_rules],
            "sensors": self.sensor_array.to_dict(),
            "thermoelastic": self.thermoelastic.to_dict(),
        }


@dataclass(frozen=True)
class Measurement:
    """Noise and resolution of the measurement chain."""

    temp_noise_c: float = 0.03
    temp_quantum_c: float = 0.01
    error_noise_um: float = 0.4
    error_quantum_um: float = 0.1


def integrate(machine: Machine, temperature0: np.ndarray, times_s: np.ndarray,
              ambient: np.ndarray, states: dict[str, np.ndarray],
              air_movement: float = 1.0) -> np.ndarray:
    """Node temperatures (len(times) x nodes) on a uniform grid.

    ``ambient`` and every state signal in ``states`` (``{"S_spindle_rpm":
    array}``, later doors, axis positions) are given at ``times_s``; over step
    k the air is the mean of its ends and the state is its value at k
    (zero-order hold).  ``air_movement`` scales the nominal convection
    (draughts, fans, open gates).  The record is walked in runs of constant
    state: within a run the propagator and the state-only heat are fixed, and
    only the temperature-dependent sources are re-evaluated, at the start of
    each step.
    """
    step = float(times_s[1] - times_s[0])
    network, injector = machine.network, machine.injector
    index = network.index
    temps = np.empty((len(times_s), network.n_nodes))
    temps[0] = temperature0
    air = 0.5 * (ambient[:-1] + ambient[1:])
    n_steps = len(times_s) - 1
    signals = np.column_stack([np.asarray(v, dtype=float) for v in states.values()])[:n_steps]
    changes = np.flatnonzero(np.any(np.diff(signals, axis=0) != 0, axis=1)) + 1
    bounds = [0, *changes.tolist(), n_steps]
    for first, stop in zip(bounds[:-1], bounds[1:]):
        state = {name: float(value) for name, value in zip(states, signals[first])}
        hA = injector.convection(state, machine.convection_rules, air_movement)
        propagator = network.propagator(step, hA)
        phi, to_air, to_heat = propagator.phi, propagator.gamma_ambient, propagator.gamma_heat
        static, thermal = injector.parts(state)
        drive = to_heat @ static
        feedback = [(source, to_heat @ column) for source, column in thermal]
        current = temps[first]

        def temperature_of(node: str) -> float:
            return current[index[node]]

        for k in range(first, stop):
            nxt = phi @ current + to_air * air[k] + drive
            for source, response in feedback:
                nxt += source.power(state, temperature_of) * response
            temps[k + 1] = current = nxt
    return temps


@dataclass
class CampaignContext:
    """What an undeclared effect (:mod:`thermocomp.apps.sim.effects`) sees of one campaign.

    Filled in step by step by :func:`run_campaign`: the plan first (id, index,
    times), then the simulated node temperatures, states and air at the samples.
    ``truth`` collects per-campaign facts the effects want in the ground truth.
    """

    cid: str
    index: int
    n_campaigns: int
    split: str
    start_s: float
    duration_s: float
    sample_period_s: float
    machine: "Machine"
    times_s: np.ndarray | None = None       # sample times (s since campaign start)
    node_temps: np.ndarray | None = None    # samples x nodes (°C)
    states: dict | None = None              # state signals at the samples
    ambient: np.ndarray | None = None       # air at the samples (°C)
    truth: dict = field(default_factory=dict)


def _state_arrays(states: dict, t_rel: np.ndarray) -> dict[str, np.ndarray]:
    """Evaluate state signals (callables of campaign time, or arrays) on ``t_rel``."""
    out = {}
    for name, signal in states.items():
        values = signal(t_rel) if callable(signal) else np.asarray(signal, dtype=float)
        out[name] = np.broadcast_to(np.asarray(values, dtype=float), t_rel.shape).copy()
    return out


def run_campaign(machine: Machine, ambient_model, programme: Programme | None,
                 start_s: float, duration_s: float, rng: np.random.Generator, *,
                 sample_period_s: float = 300.0, max_step_s: float = 30.0,
                 cooldown_s: float = 2 * 86400.0, cooldown_step_s: float = 600.0,
                 measurement: Measurement = Measurement(),
                 air_movement: float = 1.0, states: dict | None = None,
                 written: tuple | None = None, error_period_s: float | None = None,
                 error_gaps: str = "hold", effects=(), context: CampaignContext | None = None
                 ) -> tuple[pd.DataFrame, dict]:
    """Simulate one campaign.

    Parameters
    ----------
    machine : Machine
    ambient_model : object with ``sample(t_abs_s, rng) -> °C``
        E.g. :class:`~thermocomp.apps.sim.ambient.AmbientModel`.
    programme : Programme or None
        Spindle speed over the campaign (``S_spindle_rpm``); None: no spindle.
    start_s : float
        Start time in s since 1 January 00:00 (sets season and time of day).
    duration_s : float
        Length of the record; samples at 0, ``sample_period_s``, ... <= duration.
    rng : numpy.random.Generator
        The only source of randomness of the base data (ambient drift, sensor
        and probe noise).  Effects draw from their own generators, so a dataset
        with an effect planted is paired sample by sample with the one without.
    sample_period_s, max_step_s : float
        Logger period; the integration step is the period cut into equal steps
        of at most ``max_step_s``.
    cooldown_s, cooldown_step_s : float
        Rest before the campaign (no heat, every state 0), integrated with a
        coarser step.
    measurement : Measurement
    air_movement : float
        Factor on the nominal convection of every node for this campaign.
    states : dict, optional
        More state signals ``{"S_...": callable(t_rel_s) or array}`` held
        constant over each integration step (heaters, door, axis position).
    written : tuple of str, optional
        State signals written as columns (default: the spindle speed, if any).
    error_period_s : float, optional
        The probes measure every ``error_period_s`` (a multiple of the sample
        period); between two measurements ``error_gaps='hold'`` repeats the last
        reading (what a logger polling the probes at the sample rate records),
        ``'nan'`` leaves the cells empty.
    effects : sequence of UndeclaredEffect
        Hooks that add states, change readings or errors (see
        :mod:`thermocomp.apps.sim.effects`); ``context`` carries the campaign to them.

    Returns
    -------
    frame : DataFrame
        ``time``, ``T_`` (°C), ``E_`` (µm, relative to the start), written ``S_``.
    info : dict
        JSON-serialisable truths: air and node temperatures at the start, the
        largest node rises and the noise-free final errors.
    """
    substeps = math.ceil(sample_period_s / max_step_s - 1e-9)
    step_s = sample_period_s / substeps
    n_samples = int(math.floor(duration_s / sample_period_s + 1e-9)) + 1
    n_cool = int(round(cooldown_s / cooldown_step_s))
    cool_times = start_s - cooldown_s + cooldown_step_s * np.arange(n_cool + 1)
    run_times = start_s + step_s * np.arange((n_samples - 1) * substeps + 1)
    # One ambient path through cool-down and run keeps the drift continuous.
    ambient = ambient_model.sample(np.concatenate([cool_times, run_times[1:]]), rng)
    ambient_cool, ambient_run = ambient[:n_cool + 1], ambient[n_cool:]
    t_rel = run_times - start_s

    signals = dict(states or {})
    if programme is not None:
        signals = {SPINDLE: programme.rpm_at, **signals}
    written = list(written if written is not None else ([SPINDLE] if programme is not None else []))
    fine = _state_arrays(signals, t_rel)
    for effect in effects:
        added = effect.campaign_states(context, t_rel, fine)
        fine.update(added)
        written += [name for name in effect.written_states(context) if name not in written]
    if not fine:
        fine = {SPINDLE: np.zeros_like(t_rel)}

    network = machine.network
    at_rest = {name: np.zeros(n_cool + 1) for name in fine}
    cooled = integrate(machine, np.full(network.n_nodes, ambient_cool[0]), cool_times,
                       ambient_cool, at_rest, air_movement)[-1]
    temps = integrate(machine, cooled, run_times, ambient_run, fine, air_movement)

    sampled = slice(None, None, substeps)
    node_temps, air = temps[sampled], ambient_run[sampled]
    time = sample_period_s * np.arange(n_samples)
    if context is not None:
        context.times_s, context.node_temps, context.ambient = time, node_temps, air
        context.states = {name: values[sampled] for name, values in fine.items()}
    # Sensor lags act on the fine grid, then the logger samples.
    true_readings = machine.sensor_array.true_readings(temps, ambient_run, step_s)[sampled]
    for effect in effects:
        true_readings = effect.modify_readings(context, true_readings)
    readings = machine.sensor_array.measure(true_readings, rng, measurement.temp_noise_c,
                                            measurement.temp_quantum_c)
    true_errors = machine.thermoelastic.errors(node_temps, network.index)
    for effect in effects:
        true_errors = effect.modify_errors(context, true_errors)
    errors = quantise(true_errors + measurement.error_noise_um * rng.standard_normal(true_errors.shape),
                      measurement.error_quantum_um)
    if error_period_s is not None and error_period_s != sample_period_s:
        errors = hold_between_measurements(errors, time, error_period_s, error_gaps)

    columns = {"time": time}
    columns.update(zip(machine.sensor_array.columns, readings.T))
    columns.update(zip(machine.thermoelastic.targets, errors.T))
    for effect in effects:
        columns.update(effect.extra_columns(context))
    for name in written:
        columns[name] = fine[name][sampled]
    frame = pd.DataFrame(columns)
    info = {
        "ambient_start_c": float(air[0]),
        "node_start_c": dict(zip(network.names, map(float, node_temps[0]))),
        "node_max_rise_c": dict(zip(network.names, map(float, (node_temps - node_temps[0]).max(0)))),
        "true_error_final_um": dict(zip(machine.thermoelastic.targets, map(float, true_errors[-1]))),
    }
    if context is not None and context.truth:
        info["effects"] = context.truth
    return frame.astype("float64"), info


ERROR_GAPS = ("hold", "nan")


def measured_rows(time_s: np.ndarray, error_period_s: float) -> np.ndarray:
    """Boolean mask of the samples at which the probes measure (every ``error_period_s``)."""
    phase = np.mod(np.asarray(time_s, dtype=float) + 1e-6, error_period_s)
    return phase < 1e-3


def hold_between_measurements(errors: np.ndarray, time_s: np.ndarray, error_period_s: float,
                              gaps: str = "hold") -> np.ndarray:
    """Errors (samples x targets) measured only every ``error_period_s``.

    ``gaps='hold'``: the last measurement is repeated until the next one;
    ``'nan'``: the cells in between are empty (needs ``data.max_gap_samples``
    of at least period/sample - 1 to be read).
    """
    if gaps not in ERROR_GAPS:
        raise ValueError(f"error_gaps must be one of {ERROR_GAPS}, got {gaps!r}")
    measured = measured_rows(time_s, error_period_s)
    if gaps == "nan":
        out = errors.copy()
        out[~measured] = np.nan
        return out
    last = np.maximum.accumulate(np.where(measured, np.arange(len(errors)), 0))
    return errors[last]
