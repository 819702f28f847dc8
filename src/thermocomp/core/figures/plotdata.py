"""Data behind the figures, as CSV files that ``dvc plots show`` draws (``dvc.yaml``, ``plots:``).

Written next to the PNGs, one folder per kind so that each gets its own axes
in ``dvc.yaml``:

- ``<out>/plots/e_p95/<target>.csv``: ``window_h, before, after`` (E_P95 of the test split);
- ``<out>/plots/residuals/<campaign>_<target>.csv``: ``hours, measured, model, residual``
  (``plots=test|all``; the folder exists, empty, otherwise, so DVC finds it);
- ``<compare.out>/compare_plot.csv``: ``rank, run, val_rmse, test_rmse`` of a sweep.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from ...base.files import atomic_write_text
from ..metrics import E_P95, RMSE
from ..scoring.results import TEST_RMSE, VAL_RMSE, TargetResult

E_P95_DIR, RESIDUALS_DIR = E_P95, "residuals"   # the curves' folder is named as the figure


def _write(path: Path, frame: pd.DataFrame) -> Path:
    return atomic_write_text(path, frame.to_csv(index=False, float_format="%.6g"))


def write_e_p95(folder, targets: dict) -> None:
    """``e_p95/<target>.csv`` for every target of ``metrics["targets"]``; creates ``residuals/``."""
    folder = Path(folder)
    (folder / RESIDUALS_DIR).mkdir(parents=True, exist_ok=True)
    for t, m in targets.items():
        e = TargetResult(m).test.e_p95
        _write(folder / E_P95_DIR / f"{t}.csv",
               pd.DataFrame({"window_h": np.asarray(e["window_s"], float) / 3600.0,
                             "before": e["before"], "after": e["after"]}))


def write_residual(folder, time_s, measured, model, target: str, campaign: str) -> Path:
    """``residuals/<campaign>_<target>.csv``: time in hours from the campaign start."""
    time_s = np.asarray(time_s, float)
    measured, model = np.asarray(measured, float), np.asarray(model, float)
    return _write(Path(folder) / RESIDUALS_DIR / f"{campaign}_{target}.csv",
                  pd.DataFrame({"hours": (time_s - time_s[0]) / 3600.0, "measured": measured,
                                "model": model, "residual": measured - model}))


def write_compare(out, table: pd.DataFrame) -> Path:
    """``compare_plot.csv``: the ranked runs of a sweep (best first), validation and test RMSE."""
    label = table[[c for c in ("model", "select") if c in table.columns]].astype(str).agg("/".join, axis=1)
    frame = pd.DataFrame({"rank": np.arange(1, len(table) + 1),
                          "run": label + " " + table["run_id"].astype(str).str[:8],
                          VAL_RMSE: table.get(VAL_RMSE), TEST_RMSE: table.get(RMSE)})
    return _write(Path(out) / "compare_plot.csv", frame)
