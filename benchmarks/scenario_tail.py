"""What the stranger benches' own-machine scenarios share (``trunnion63``, ``portal64``, ``edm65``,
``tsc66``): the tail of their generators, once (benchdup66).

* :func:`merge` and :func:`held`: a programme's steps ``(start s, value)`` on the logger's grid,
  and a state signal that holds each value until the next step;
* :func:`weekday_shift`: the machine powered on weekdays within the shift's hours;
  :func:`working`: a run's working hours, 16 h from its start each day; :func:`either`: a state
  on while either of two is (tsc66, mtc68);
* :class:`LoggedStateEffect`: the base of a planted effect of a LOGGED state (its column, so
  declared) on the errors, with a node's rise from the campaign's first sample;
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

from typing import ClassVar

import numpy as np

from thermocomp.apps.sim.effects import UndeclaredEffect
from thermocomp.apps.sim.scenario import DeclaredScenario


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


__all__ = ["LoggedStateEffect", "PlantedScenario", "either", "held", "merge", "weekday_shift",
           "working"]
