"""A unit changed inside a file: a step that no sensor makes and that a unit conversion undoes.

A logger set to °F (or a probe to mm) part way through a campaign leaves a file whose values
are all plausible on their own: the whole-file checks (``data.fahrenheit_threshold_c``,
``data.kelvin_threshold_c``, the other campaigns' error ranges) cannot see it, and a model is
fitted on it.  A generic step test cannot tell it from a physical step either (a door opens:
the ambient sensor jumps a few K in one coarse sample; a fault offsets one sensor).  So a step
is refused only when three things hold, each against the column's own history:

1. it is a step the column does not make: larger than ``data.max_step_ratio`` times its robust
   sample-to-sample scale (1.4826 x the MAD of its differences, the column taken as if the unit
   had been kept, so that the rows in the other unit do not set the scale);
2. a unit conversion accounts for it: the value after is the value before converted (°C -> °F:
   1.8 x + 32, µm -> mm: x / 1000, ...) within a fifth of the step, and converted back it is
   within a step the column makes of the value before (a fault offset lands near a conversion
   only as far as a fifth of its size); so the level jumps by the factor the unit makes, which
   a physical step matches only by chance (a door's 3 K at 20 °C would have to be 48 K), and
   the value before is far enough from zero for x1000 to say so;
3. it persists: the next samples, converted back, move less than a fifth of the step (a spike
   steps back; a re-zeroed probe goes on at the new level in the old unit's steps, which
   converted back are 1000x the noise).

Unit-aware rather than a generic step test: doors and faults make steps as large, so a generic
test could only warn, on every such event; none of them lands where a conversion puts the value,
so this one can refuse.  A step that fits a unit while another sensor of the same kind steps at
the same row without fitting one is ambiguous (an event that moved several sensors): it is
warned about, not refused.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from ...base.log import logger
from .contract import ContractError, role
from .lines import Lines, at
from .tables import _values

FIT = 0.2         # a conversion must leave at most this share of the step, there and after
PERSIST = 3       # samples after the step that must continue in the old unit, converted back
MIN_SAMPLES = 6   # fewer finite values: no history to judge a step against
CANDIDATES = 8    # steps a unit explains that are judged against the history, per unit

# role -> (what the rows from the step on read as, the conversion from the rows before to
# them, and back); E_ columns are µm, T_ columns °C (or °F before a change to °C)
UNITS = {
    "T": (("°F of the °C before", lambda x: 1.8 * x + 32, lambda y: (y - 32) / 1.8),
          ("°C of the °F before", lambda x: (x - 32) / 1.8, lambda y: 1.8 * y + 32)),
    "E": (("mm of the µm before", lambda x: x / 1000, lambda y: y * 1000),
          ("1000x the rows before (nm after µm, or µm after mm)", lambda x: x * 1000,
           lambda y: y / 1000)),
}


def robust_step_scale(values: np.ndarray) -> float:
    """1.4826 x the MAD of the sample-to-sample differences (the smallest non-zero
    difference when most are zero: a quantised, mostly constant reading)."""
    steps = np.diff(values)
    scale = 1.4826 * float(np.median(np.abs(steps - np.median(steps))))
    if scale > 0:
        return scale
    moved = np.abs(steps[steps != 0])
    return float(moved.min()) if moved.size else 0.0


def unit_change(x: np.ndarray, ratio: float, units) -> tuple[int, int]:
    """``(k, i)``: the first step of the finite values ``x`` (``x[k]`` to ``x[k+1]``) that is
    a change to ``units[i]`` (see the module docstring); ``(-1, -1)`` when there is none."""
    steps = np.diff(x)
    tolerance = FIT * np.abs(steps)
    found = []
    for i, (_, forward, back) in enumerate(units):
        fits, undone = _fitting(x, forward, back)
        for k in np.flatnonzero(fits)[:CANDIDATES]:
            # the column as if the unit had been kept: its history judges the step
            scale = robust_step_scale(np.concatenate((x[:k + 1], undone[k + 1:])))
            # x1000 of a value within the noise of zero predicts nothing: the conversion of
            # the value before must be sharper than the fit it is held to
            spread = abs(forward(x[k] + scale) - forward(x[k]))
            # converted back, the step is one the column makes: no larger than its step limit
            # or its largest other step (plus the resolution the new unit is written at). A
            # fault offset of 50 K at 14 °C lands within a fifth of the step of 1.8 x + 32
            # (64.4 for 57.7), but 3.7 K off where the column never steps 0.5 K
            kept = np.abs(np.diff(np.concatenate((x[:k + 1], undone[k + 1:]))))
            moved = np.abs(np.diff(x[k + 1:]))
            quantum = float(moved[moved > 0].min()) if (moved > 0).any() else 0.0
            ordinary = (max(ratio * scale, float(np.delete(kept, k).max(initial=0.0)))
                        + abs(back(x[k + 1] + quantum) - back(x[k + 1])))
            if (abs(steps[k]) > ratio * scale and spread <= tolerance[k]
                    and abs(undone[k + 1] - x[k]) <= ordinary):
                found.append((int(k), i))
                break
    return min(found, default=(-1, -1))


def _fitting(x: np.ndarray, forward, back) -> tuple[np.ndarray, np.ndarray]:
    """Where a step of ``x`` (along axis 0: a column, or columns side by side) fits a change of
    unit (``forward``, ``back``: the conversion and its inverse): explained by the conversion,
    converted back within a fifth of the step, and persisting; and ``x`` converted back."""
    steps = np.diff(x, axis=0)
    tolerance = FIT * np.abs(steps)
    with np.errstate(over="ignore", invalid="ignore"):
        explained = (np.abs(x[1:] - forward(x[:-1])) <= tolerance) & (steps != 0)
        undone = back(x)
        # step k with the rows after it converted back, and the PERSIST steps after it
        at = np.abs(undone[1:] - x[:-1])
        moves = np.concatenate((np.abs(np.diff(undone, axis=0)), np.full((PERSIST,) + x.shape[1:], -np.inf)))
        after = sliding_window_view(moves[1:], PERSIST, axis=0).max(axis=-1)
        return explained & (at <= tolerance) & (after > -np.inf) & (after <= tolerance), undone


def _suspects(values: dict[str, tuple[np.ndarray, np.ndarray]], units) -> list[str]:
    """The columns (name -> rows, finite values) with a step that fits a change of unit, which
    :func:`unit_change` then judges against the column's history: the columns measured in every
    row are screened side by side (a volumetric dataset's 1430 distances one by one: 60 ms)."""
    n = max((rows.size for rows, _ in values.values()), default=0)
    full = [name for name, (rows, _) in values.items() if rows.size == n]
    if n < MIN_SAMPLES or not full:
        return list(values)
    X = np.column_stack([values[name][1] for name in full])
    hit = np.zeros(len(full), bool)
    for _, forward, back in units:
        hit |= _fitting(X, forward, back)[0].any(axis=0)
    cleared = {name for name, h in zip(full, hit) if not h}
    return [name for name in values if name not in cleared]


def _finite(column) -> tuple[np.ndarray, np.ndarray]:
    """The rows of ``column`` that hold a value, and those values."""
    v = _values(column)
    rows = np.flatnonzero(np.isfinite(v))
    return rows, v[rows]


def _steps_without_a_unit(columns: dict, names: list[str], row: int, ratio: float,
                          units) -> bool:
    """Whether one of ``names`` steps into ``row`` by more than ``ratio`` times its typical
    step with no unit change there (an event that moved several sensors)."""
    for name in names:
        rows, x = _finite(columns[name])
        k = int(np.searchsorted(rows, row))
        if rows.size < MIN_SAMPLES or not 0 < k < rows.size or rows[k] != row:
            continue
        change, _ = unit_change(x, ratio, units)
        if abs(x[k] - x[k - 1]) > ratio * robust_step_scale(x) and change != k - 1:
            return True
    return False


def check_unit_steps(columns: dict, path: Path, ratio: float | None, offset: int,
                     lines: Lines | None = None) -> None:
    """Refuse a ``T_`` or ``E_`` column whose unit changes inside the file (see the module
    docstring), naming the first row in the new unit (1-based data row of the source file:
    ``offset`` rows were trimmed before ``columns``' first; ``lines``: its line, in a warning)."""
    if ratio is None:
        return
    for kind, units in UNITS.items():
        names = [n for n in columns if role(n) == kind]
        values = {name: _finite(columns[name]) for name in names}
        found = []
        for name in _suspects(values, units):
            rows, x = values[name]
            k, unit = unit_change(x, ratio, units) if rows.size >= MIN_SAMPLES else (-1, -1)
            if k >= 0:
                found.append((int(rows[k + 1]), name, x[k], x[k + 1], units[unit][0]))
        for row, name, before, after, what in sorted(found, key=lambda f: f[0]):
            says = (f"steps from {before:g} to {after:g} in one sample and the rows from here on "
                    f"read as {what}: the unit changes inside the file, convert it "
                    f"(data.max_step_ratio={ratio:g})")
            others = [n for n in names if n != name]
            if _steps_without_a_unit(columns, others, row, ratio, units):
                logger.warning(f"{path}, column '{name}', {at(lines)(row + offset + 1)}: {says}; other "
                               "sensors step at the same row, so it may be a real event")
                continue
            raise ContractError(says, file=path, column=name, row=row + offset + 1)
