"""The four sensor faults the stranger benches (77, 78, 80, 81) plant in a machine's last run:
each bench names its sensors and rows, the faults themselves are written once."""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import numpy as np


def four_faults(n: int, period_s: float, frozen: tuple[str, int], jump: tuple[str, int],
                drift: tuple[str, int], dropout: tuple[str, int, int]
                ) -> dict[str, tuple[str, Callable[[np.ndarray], np.ndarray]]]:
    """``{kind: (sensor, change)}`` over a run of ``n`` samples ``period_s`` apart: ``frozen``
    (sensor, row): held at that row's reading from it on; ``jump``: +2 K from the row; ``drift``:
    +1 K/h from the row; ``dropout`` (sensor, first, last + 1): missing in between."""
    rows = np.arange(n)
    hours = np.clip(rows - drift[1], 0, None) * period_s / 3600.0
    (f_label, f_row), (j_label, j_row), (d_label, _), (o_label, o_from, o_to) = frozen, jump, drift, dropout
    return {"frozen": (f_label, lambda x: np.where(rows < f_row, x, x[f_row])),
            "jump": (j_label, lambda x: x + 2.0 * (rows >= j_row)),
            "drift": (d_label, lambda x: x + hours),
            "dropout": (o_label, lambda x: np.where((rows >= o_from) & (rows < o_to), np.nan, x))}


def fault_folders(root, seed, cases: dict, write_all: Callable) -> None:
    """Each case of ``cases`` (:func:`four_faults`) written by ``write_all(folder, fault)`` into
    ``ROOT/fault_<kind>_<SEED>/``: ``fault(name, values)`` alters the named sensor's values."""
    for kind, (label, change) in cases.items():
        def fault(name, x, label=label, change=change):
            return change(x) if name == label else x
        folder = Path(root) / f"fault_{kind}_{seed}"
        write_all(folder, fault)
        print(f"wrote {folder}")
