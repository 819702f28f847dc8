"""Scenario base class: a machine, a test calendar, undeclared effects -> dataset + truth.

A scenario (``conf/sim/<name>.yaml``, ``generator._target_`` one of the
subclasses) supplies :meth:`Scenario.machine` and :meth:`Scenario.plans` (one
:class:`CampaignPlan` per campaign); :meth:`Scenario.generate` runs every
campaign through :func:`~thermocomp.apps.sim.campaign.run_campaign` with the
effects of ``effects`` planted (:mod:`thermocomp.apps.sim.effects`) and returns a
:class:`~thermocomp.core.io.contract.Dataset` plus a JSON-serialisable ground truth.

``clean=True`` replaces the errors by an exactly linear function of the
measured sensor rises plus white probe noise (coefficients: least squares of
the physical errors on the rises over all campaigns): the "no missing effect"
control of the residual diagnosis.
"""

from __future__ import annotations

import contextlib
import copy
import zlib
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, is_dataclass
from datetime import datetime, timedelta
from typing import ClassVar

import numpy as np
import pandas as pd

from thermocomp.apps.sim.campaign import (
    CampaignContext,
    Measurement,
    Programme,
    hold_between_measurements,
    measured_rows,
    run_campaign,
)
from thermocomp.apps.sim.effects import build_effects
from thermocomp.apps.sim.sensors import quantise
from thermocomp.base.errors import ConfigError, ThermocompError
from thermocomp.base.params import BOOLEAN, NON_NEGATIVE, check_params
from thermocomp.core.io.contract import Dataset, write_dataset


def single_threaded_blas():
    """Context limiting BLAS to one thread (a no-op without ``threadpoolctl``)."""
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:  # pragma: no cover - threadpoolctl ships with scikit-learn
        return contextlib.nullcontext()
    return threadpool_limits(limits=1, user_api="blas")


def write_scenario(generator, path) -> tuple[dict, int, int]:
    """Write ``generator``'s dataset to ``path`` -> ``(truth, campaigns, rows)``.

    A generator with ``write(path)`` (a fleet) streams to disk, never whole in memory; others
    are generated, then written in their ``file_format`` (default CSV) with the extra files of
    their ``dataset_files()`` (``volumetric.json``).  The caller writes the truth.
    """
    if hasattr(generator, "write"):
        truth = generator.write(path)
        return truth, truth["campaigns"], truth["rows"]
    ds, truth = generator.generate()
    write_dataset(ds, path, getattr(generator, "file_format", "csv"),
                  generator.dataset_files() if hasattr(generator, "dataset_files") else None)
    return truth, len(ds.campaigns), int(sum(len(df) for df in ds.campaigns.values()))


def plain(value):
    """Hydra ListConfig/DictConfig/tuples -> JSON-friendly lists/dicts, numpy scalars -> Python."""
    if isinstance(value, str) or value is None:
        return value
    if isinstance(value, Mapping):
        return {str(k): plain(v) for k, v in value.items()}
    if hasattr(value, "__iter__"):
        return [plain(v) for v in value]
    return value.item() if hasattr(value, "item") else value


@dataclass
class CampaignPlan:
    """Everything one campaign needs; ``rng`` is its own generator (spawned from the seed)."""

    cid: str
    split: str
    start_s: float
    duration_s: float
    rng: np.random.Generator
    ambient: object                        # .sample(t_abs_s, rng) -> °C
    programme: Programme | None = None
    states: dict = field(default_factory=dict)
    written: tuple | None = None
    air_movement: float = 1.0
    sample_period_s: float = 300.0
    error_period_s: float | None = None
    cooldown_s: float = 2 * 86400.0
    notes: str = ""
    manifest: dict = field(default_factory=dict)
    truth: dict = field(default_factory=dict)


# Samples of a simulated dataset, all campaigns: 200x the largest scenario's default (a period
# of 1e-6 s or campaigns of 1e6 h are not refused by any one parameter's rule, and would simulate
# until memory ran out).  Counted from the plans, before anything is simulated.
MAX_SAMPLES = 10_000_000


def check_size(samples: float, campaigns: int) -> None:
    if not samples <= MAX_SAMPLES:
        raise ConfigError(f"sim.generator: {campaigns} campaigns of {samples:,.0f} samples in all, "
                          f"more than {MAX_SAMPLES:,}: shorten them or sample less often "
                          "(sample_period_s)")


class Scenario:
    """Base class of the generators (sklearn style: ``__init__`` only stores).

    Subclasses define :attr:`name`, :meth:`machine`, :meth:`plans`, and
    :meth:`effect_defaults` (where each effect attaches on this machine).
    Common parameters: ``effects`` (names), ``effect_params`` (name -> dict),
    ``clean`` (bool), ``seed`` and the measurement chain.
    """

    name: ClassVar[str] = ""
    builtin_effects: ClassVar[tuple] = ()
    year: int = 2023
    error_gaps: str = "hold"
    # what each parameter may be (thermocomp.base.params); subclasses add theirs
    param_rules: ClassVar[dict] = {"temp_noise_c": NON_NEGATIVE, "temp_quantum_c": NON_NEGATIVE,
                                   "error_noise_um": NON_NEGATIVE, "error_quantum_um": NON_NEGATIVE,
                                   "clean": BOOLEAN}

    def __init__(self, temp_noise_c, temp_quantum_c, error_noise_um, error_quantum_um, effects=(),
                 effect_params=None, clean=False, seed=0):
        """Store what every scenario takes: the measurement chain, the planted effects, the seed
        (a subclass names them in its own ``__init__`` too: :meth:`get_params` reads its
        signature; or it declares its parameters once, :class:`DeclaredScenario`)."""
        self.temp_noise_c = temp_noise_c
        self.temp_quantum_c = temp_quantum_c
        self.error_noise_um = error_noise_um
        self.error_quantum_um = error_quantum_um
        self.effects = effects
        self.effect_params = effect_params
        self.clean = clean
        self.seed = seed

    # --- to be provided by scenarios ------------------------------------------------------
    def machine(self):
        raise NotImplementedError

    def plans(self, rng: np.random.Generator) -> list[CampaignPlan]:
        raise NotImplementedError

    def effect_defaults(self) -> dict:
        return {}

    def truth_extra(self) -> dict:
        return {}

    # --- common -------------------------------------------------------------------------------
    def get_params(self) -> dict:
        """The constructor's parameters and their values, in its signature's order (a
        :class:`DeclaredScenario`'s: its own first, then the measurement chain's)."""
        if is_dataclass(self):
            names = [f.name for f in fields(self) if f.init]
            names = [n for n in names if n not in CHAIN] + [n for n in CHAIN if n in names]
        else:
            code = type(self).__init__.__code__
            names = list(code.co_varnames[1:code.co_argcount])
        return {name: plain(getattr(self, name)) for name in names}

    def measurement(self) -> Measurement:
        return Measurement(self.temp_noise_c, self.temp_quantum_c, self.error_noise_um, self.error_quantum_um)

    def effects_list(self):
        """The planted effects (built-in ones first), parameters merged over the scenario's defaults."""
        requested = [str(e) for e in (self.effects or [])]
        if self.clean and requested:
            raise ConfigError(f"sim.generator.clean=true plants no effect, but effects={requested}")
        names = list(self.builtin_effects) + [e for e in requested if e not in self.builtin_effects]
        if len(set(names)) != len(names):
            raise ConfigError(f"sim.generator.effects lists an effect twice: {requested}")
        return build_effects(names, plain(self.effect_params or {}), self.effect_defaults(),
                             int(self.seed))

    def generate(self) -> tuple[Dataset, dict]:
        """Simulate every campaign; returns ``(dataset, truth)``.

        Also sets ``node_temperatures_``: campaign id -> DataFrame of the true
        node temperatures (°C), the air (``ambient``) and every state signal at
        the samples (hidden ones too) -- the truth behind each column, for
        tests and benchmarks (too large for the JSON truth).

        BLAS is held to one thread: the matrices are 9-60 wide, where threads
        only add overhead (3x slower on a busy machine).
        """
        check_params(self)
        with single_threaded_blas():
            dataset, truth = self._generate()
        for effect in self.effects_:   # effects on the written files (sensor faults), after any cut
            dataset, truth = effect.modify_dataset(dataset, truth)
        return dataset, truth

    def _generate(self) -> tuple[Dataset, dict]:
        rng = np.random.default_rng(self.seed)
        self.effects_ = effects = self.effects_list()
        try:
            machine = self.machine()
        except ThermocompError:
            raise
        except ValueError as exc:   # a user's own machine (a sensor on no node...): exit 2, no traceback
            raise ConfigError(f"sim.generator._target_={type(self).__module__}."
                              f"{type(self).__name__}: its machine() is not valid: {exc}") from None
        for effect in effects:
            effect.check_targets(machine)
            machine = effect.modify_machine(machine)
        plans = self.plans(rng)
        check_size(sum(plan.duration_s / plan.sample_period_s for plan in plans), len(plans))
        measurement = self.measurement()
        simulated, frames, measured = [], {}, {}
        self.node_temperatures_ = {}
        from ...base.progress import bar

        for k, plan in enumerate(bar(plans, desc="simulate", unit="campaign")):
            ctx = CampaignContext(plan.cid, k, len(plans), plan.split, plan.start_s, plan.duration_s,
                                  plan.sample_period_s, machine)
            frame, info = run_campaign(
                machine, plan.ambient, plan.programme, plan.start_s, plan.duration_s, plan.rng,
                sample_period_s=plan.sample_period_s, measurement=measurement,
                air_movement=plan.air_movement, states=plan.states, written=plan.written,
                error_period_s=plan.error_period_s, error_gaps=self.error_gaps, effects=effects,
                context=ctx, cooldown_s=plan.cooldown_s)
            frames[plan.cid] = frame
            self.node_temperatures_[plan.cid] = pd.DataFrame(
                ctx.node_temps, columns=list(machine.network.names)).assign(
                ambient=ctx.ambient, **{k: v for k, v in ctx.states.items()})
            measured[plan.cid] = (measured_rows(frame["time"].to_numpy(), plan.error_period_s)
                                  if plan.error_period_s else np.ones(len(frame), dtype=bool))
            start = datetime(int(self.year), 1, 1) + timedelta(seconds=plan.start_s)
            simulated.append(campaign_entry(plan.cid, plan.split, start, plan.notes, frame, plan.manifest,
                                            {"duration_s": plan.duration_s, **plan.truth, **info}))
        clean = None
        if self.clean:
            clean = self._make_clean(frames, measured, machine)
        dataset, campaigns = assemble(self.name, {"scenario": self.name, "seed": self.seed}, simulated)
        truth = {
            "scenario": self.name,
            "seed": plain(self.seed),
            "params": self.get_params(),
            "clean": bool(self.clean),
            "noise": {"temperature_c": self.temp_noise_c, "temperature_quantum_c": self.temp_quantum_c,
                      "error_um": self.error_noise_um, "error_quantum_um": self.error_quantum_um},
            **machine.to_dict(),
            "sensor_nodes": {s.column: s.main_node for s in machine.sensors},
            "unmeasured_nodes": [n for n in machine.network.names
                                 if n not in {s.main_node for s in machine.sensors}],
            **self.truth_extra(),
            **campaigns,
            "undeclared_effects": [] if self.clean else [e.record() for e in effects],
        }
        if clean is not None:
            truth["clean_law"] = clean
        return dataset, plain(truth)

    def _make_clean(self, frames: dict, measured: dict, machine) -> dict:
        """Errors := measured sensor rises @ coefficients + white noise (in place)."""
        sensors = machine.sensor_array.columns
        targets = machine.thermoelastic.targets
        rises = {cid: (f[sensors] - f[sensors].iloc[0]).to_numpy() for cid, f in frames.items()}
        x = np.vstack([rises[cid][measured[cid]] for cid in frames])
        y = np.vstack([(f[targets] - f[targets].iloc[0]).to_numpy()[measured[cid]]
                       for cid, f in frames.items()])
        coef, *_ = np.linalg.lstsq(x, y, rcond=None)
        rng = np.random.default_rng([int(self.seed), zlib.crc32(b"clean")])
        for cid, frame in frames.items():
            errors = rises[cid] @ coef + self.error_noise_um * rng.standard_normal((len(frame), len(targets)))
            errors = quantise(errors, self.error_quantum_um)
            if not measured[cid].all():
                period = float(np.diff(frame["time"].to_numpy()[measured[cid]][:2])[0])
                errors = hold_between_measurements(errors, frame["time"].to_numpy(), period, self.error_gaps)
            frame[targets] = errors
        return {"formula": "E = (T - T(0)) @ coefficients + N(0, error_um^2), quantised",
                "coefficients_um_per_K": {t: dict(zip(sensors, map(float, coef[:, i])))
                                          for i, t in enumerate(targets)}}



# what every scenario takes (Scenario.__init__'s parameters), in its order
CHAIN = ("temp_noise_c", "temp_quantum_c", "error_noise_um", "error_quantum_um", "effects",
         "effect_params", "clean", "seed")


@dataclass(eq=False, repr=False, kw_only=True)
class DeclaredScenario(Scenario):
    """A scenario that declares its parameters once, as dataclass fields: its own, and a
    measurement chain's default it changes (``error_noise_um: float = 0.3``); the constructor,
    its signature (what ``sim.generator``'s keys are checked against) and :meth:`get_params`
    (its own first, then the chain's, as an ``__init__`` spelling them lists them) come from
    that one list (leftovers67: each bench scenario spelled an ``__init__`` of alike lines).
    Subclasses are ``@dataclass(eq=False, repr=False, kw_only=True)`` too: keywords only, the
    fields' order (the chain's first) being no order to call by."""

    temp_noise_c: float = 0.03
    temp_quantum_c: float = 0.01
    error_noise_um: float = 0.2
    error_quantum_um: float = 0.1
    effects: tuple = ()
    effect_params: dict | None = None
    clean: bool = False
    seed: int = 0


def campaign_entry(cid: str, split: str, start, notes: str, frame: pd.DataFrame, columns: Mapping,
                   truth: Mapping) -> tuple[dict, pd.DataFrame, dict]:
    """One simulated campaign as :func:`assemble` takes it: its manifest row (the contract's
    columns, then the scenario's ``columns``), its frame, its truth (``start``, ``split``, then
    ``truth``).  ``start``: a datetime."""
    row = {"campaign": cid, "file": f"{cid}.csv", "split": split,
           "start": start.isoformat(timespec="minutes"), "notes": notes,
           "ambient_c": round(initial_air(frame), 2), **columns}
    return row, frame, {"start": row["start"], "split": split, **truth}


def assemble(name: str, meta: dict, simulated: list[tuple[dict, pd.DataFrame, dict]]
             ) -> tuple[Dataset, dict]:
    """``(dataset, truth of its campaigns)`` of :func:`campaign_entry` results, in their order;
    the truth part holds ``initial_ambient_c`` and ``campaigns``."""
    manifest = pd.DataFrame([row for row, _, _ in simulated]).set_index("campaign")
    frames = {row["campaign"]: frame for row, frame, _ in simulated}
    campaigns = {row["campaign"]: truth for row, _, truth in simulated}
    return Dataset(manifest, frames, name=name, meta=meta), {
        "initial_ambient_c": {cid: c["ambient_start_c"] for cid, c in campaigns.items()},
        "campaigns": campaigns}


def initial_air(frame: pd.DataFrame) -> float:
    """First reading of the ambient sensor(s) ``T_amb``/``T_amb_*`` (mean), NaN if none."""
    amb = [c for c in frame.columns if c == "T_amb" or c.startswith("T_amb_")]
    return float(frame[amb].iloc[0].mean()) if amb else float("nan")


def copy_params(params: dict | None) -> dict:
    return copy.deepcopy(plain(params or {}))
