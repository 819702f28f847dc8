"""What the stranger benches' own-machine scenarios share (``trunnion63``, ``portal64``, ``edm65``,
``tsc66``): the tail of their generators, once (benchdup66).

* :func:`merge` and :func:`held`: a programme's steps ``(start s, value)`` on the logger's grid,
  and a state signal that holds each value until the next step;
* :func:`weekday_shift`: the machine powered on weekdays within the shift's hours;
  :func:`working`: a run's working hours, 16 h from its start each day; :func:`either`: a state
  on while either of two is (tsc66, mtc68);
* :func:`day_runs`: the plans of a programme of independent day runs (mtc68, gpg69: each run
  from a day of a list at one hour, its own generator and clock, a rest before it), and
  :class:`DayRunsScenario`, its parameters declared once;
* :class:`LoggedStateEffect`: the base of a planted effect of a LOGGED state (its column, so
  declared) on the errors, with a node's rise from the campaign's first sample;
  :class:`TurnedGrowth`, a node's growth along an axis a logged angle turns (mtc68, keysight70);
* :class:`PlantedScenario`: a :class:`~thermocomp.apps.sim.scenario.DeclaredScenario` (its
  parameters declared once, as dataclass fields: leftovers67) with ONE planted
  effect the default model lacks (an :class:`~thermocomp.apps.sim.effects.UndeclaredEffect`
  whose column is logged): planted in every record, its figures in the truth under its name,
  and left out of the truth's ``undeclared_effects``.

Imported by the scenario modules themselves (``benchmarks/`` is on ``PYTHONPATH`` whenever they
are); ``THERMOCOMP_TARGETS`` still names only the scenario module.

Checked (benchdup66, no behaviour change): each stranger bench's ``write`` (its machine's
``thermocomp simulate`` at the committed settings and seeds, then the lab's files: tsc66 seeds
6601/6602, edm65 6501/6502, trunnion63 6301/6302, portal64 6401/6402 as one record and weekly)
run on the code before and after the move: the 77 files (records, ``campaigns.csv``, the
``*.truth.json``, the lab's exports) the same byte for byte; two runs of the old code agree alike.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime, timedelta
from typing import ClassVar

import numpy as np

from thermocomp.apps.sim.ambient import DAY_S
from thermocomp.apps.sim.effects import UndeclaredEffect
from thermocomp.apps.sim.scenario import CampaignPlan, DeclaredScenario


def merge(steps: list) -> list:
    """Steps on a grid; two on one grid point keep the later."""
    clean = []
    for start, value in steps:
        if clean and start <= clean[-1][0]:
            clean[-1] = (clean[-1][0], value)
        else:
            clean.append((start, value))
    return clean


def held(steps: list):
    """Steps ``(start s, value)`` -> campaign time -> the value of the last step started."""
    starts = np.array([s for s, _ in steps])
    values = np.array([v for _, v in steps])

    def at(t_rel):
        return values[np.searchsorted(starts, np.asarray(t_rel, float), side="right") - 1]
    return at


def weekday_shift(t_rel, shift_h: tuple) -> np.ndarray:
    """Campaign time -> 1 on weekdays from ``shift_h[0]`` to ``shift_h[1]`` h (every campaign
    starts on a Monday 00:00)."""
    hours = np.asarray(t_rel, float) / 3600.0
    day, hour = (hours // 24) % 7, hours % 24
    return ((day < 5) & (hour >= shift_h[0]) & (hour < shift_h[1])).astype(float)


def working(t_rel) -> np.ndarray:
    """Run time (from 06:00 of its first day) -> 1 from 06:00 to 22:00 each day."""
    hour = (np.asarray(t_rel, float) / 3600.0) % 24.0
    return (hour < 16.0).astype(float)


def either(a, b):
    """Two state signals -> one that is 1 while either is non-zero (a cut by either spindle)."""
    def at(t_rel):
        return ((a(t_rel) != 0) | (b(t_rel) != 0)).astype(float)
    return at


def day_runs(scenario, start: datetime, run_days: tuple, hall, programme, written: tuple,
             derived=None) -> list:
    """The plans of ``scenario.runs`` independent runs of ``scenario.run_h`` h at
    ``scenario.sample_period_s``: run k from ``start`` + its day of ``run_days`` (3 weeks later
    per round of the list, ``scenario.weeks_later`` more), its own generator ``[seed, k]`` (the
    ``written`` states' step lists drawn from it by ``programme(rng, period, duration)``, held;
    ``derived(states)``: more states, not written), after a 2-day rest in the ``hall``."""
    period = float(scenario.sample_period_s)
    duration = float(scenario.run_h) * 3600.0 - period
    plans = []
    for k in range(int(scenario.runs)):
        first_day = run_days[k % len(run_days)] + 21 * (k // len(run_days))
        at = start + timedelta(days=first_day, weeks=int(scenario.weeks_later))
        run_rng = np.random.default_rng([int(scenario.seed), k])
        states = dict(zip(written, (held(s) for s in programme(run_rng, period, duration))))
        states.update(derived(states) if derived else {})
        plans.append(CampaignPlan(
            cid=f"run{k + 1:02d}", split="train",
            start_s=(at - datetime(scenario.year, 1, 1)).total_seconds(), duration_s=duration,
            rng=run_rng, ambient=hall, programme=None, states=states, written=tuple(written),
            sample_period_s=period, error_period_s=None, cooldown_s=2 * DAY_S,
            notes=f"run {k + 1}, {scenario.run_h:g} h from {at:%a %Y-%m-%d %H:%M}", manifest={}))
    return plans


class LoggedStateEffect(UndeclaredEffect):
    """A planted effect of the logged state ``state`` (its column: declared) on the errors; the
    subclass's ``modify_errors`` says how (:meth:`logged`, :meth:`rise`)."""

    kind = "interaction"
    state: ClassVar[str] = ""

    @property
    def column(self):
        return self.state

    def logged(self, ctx) -> np.ndarray:
        """The state's values at the samples."""
        return np.asarray(ctx.states[self.state], float)

    @staticmethod
    def rise(ctx, node: str) -> np.ndarray:
        """``node``'s temperature rise from the campaign's first sample."""
        index = ctx.machine.network.index
        return ctx.node_temps[:, index[node]] - ctx.node_temps[0, index[node]]


class TurnedGrowth(LoggedStateEffect):
    """A node's growth (``gain`` µm/K of its rise) along an axis that the logged angle ``state``
    (degrees) turns: ``cos`` of it onto the target ``along_cos``, ``sin`` onto ``along_sin``
    (mtc68's tool spindle turned by B, keysight70's table by the tilt A)."""

    node: ClassVar[str] = ""
    along_cos: ClassVar[str] = ""
    along_sin: ClassVar[str] = ""

    def modify_errors(self, ctx, errors):
        errors = errors.copy()
        targets = ctx.machine.thermoelastic.targets
        angle = np.radians(self.logged(ctx))
        growth = float(self.params["gain"]) * self.rise(ctx, self.node)
        errors[:, targets.index(self.along_cos)] += growth * np.cos(angle)
        errors[:, targets.index(self.along_sin)] += growth * np.sin(angle)
        return errors


class PlantedScenario(DeclaredScenario):
    """A scenario with one planted effect, ``planted`` (its class), in every record.

    Subclasses set ``planted`` and say its figures in :meth:`planted_truth` (the truth's entry
    under ``planted.name``); the effect is not listed among the truth's ``undeclared_effects``
    (it is the machine's, not a requested one)."""

    planted: ClassVar[type]

    def planted_truth(self) -> dict:
        raise NotImplementedError

    def effects_list(self):
        return [*super().effects_list(), self.planted(int(self.seed))]

    def generate(self):
        dataset, truth = super().generate()
        truth[self.planted.name] = self.planted_truth()
        truth["undeclared_effects"] = [e for e in truth["undeclared_effects"]
                                       if e["name"] != self.planted.name]
        return dataset, truth


@dataclass(eq=False, repr=False, kw_only=True)
class DayRunsScenario(PlantedScenario):
    """A :class:`PlantedScenario` of ``runs`` independent runs of ``run_h`` h at
    ``sample_period_s`` (:func:`day_runs`), ``weeks_later`` weeks on (a record of the same
    machine later)."""

    runs: int = 8
    run_h: float = 24.0
    sample_period_s: float = 60.0
    weeks_later: int = 0


__all__ = ["DayRunsScenario", "LoggedStateEffect", "PlantedScenario", "TurnedGrowth", "day_runs",
           "either", "held", "merge", "weekday_shift", "working"]
