"""A simulated dataset as a probe cycle measures it: its errors kept on some rows only.

A lab often logs its temperatures every sample and measures the error now and then (a touch
probe on a reference sphere every N samples, the cells in between empty: ``data.sparse_targets``).
:func:`probe_cycle_copy` writes such a copy of a dataset the simulator wrote, so that the same
truth can be read dense and as a probe cycle.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pandas as pd


def probe_cycle_copy(dense: Path, dest: Path, keep: int | Callable[[np.ndarray], np.ndarray]) -> Path:
    """Copy the dataset folder ``dense`` to ``dest`` with each campaign's ``E_`` cells empty where
    the error was not measured: on every row but every ``keep``-th (from the first), or where
    ``keep(rows)`` (a boolean mask over the row numbers) is false.  Returns ``dest``."""
    def measured(rows: np.ndarray) -> np.ndarray:
        return rows % keep == 0 if isinstance(keep, int) else np.asarray(keep(rows), bool)

    dest = Path(dest)
    dest.mkdir(parents=True, exist_ok=True)
    for f in Path(dense).glob("*.csv"):
        df = pd.read_csv(f)
        if f.name != "campaigns.csv":
            errors = [c for c in df.columns if c.startswith("E_")]
            df.loc[~measured(np.arange(len(df))), errors] = np.nan
        df.to_csv(dest / f.name, index=False)
    return dest
