"""Figures (matplotlib, Agg backend, PNG)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def residual_plot(time_s, measured, predicted, target: str, campaign: str, path) -> Path:
    """Measured error, prediction and residual of one campaign against time (h)."""
    t = np.asarray(time_s, float) / 3600.0
    y, yhat = np.asarray(measured, float), np.asarray(predicted, float)
    fig, (ax, axr) = plt.subplots(2, 1, figsize=(7, 4.5), sharex=True,
                                  gridspec_kw={"height_ratios": [2, 1]})
    ax.plot(t, y, label=f"measured {target}", color="k", lw=1.2)
    ax.plot(t, yhat, label="model", color="tab:blue", lw=1.2, ls="--")
    ax.set_ylabel("error (µm)")
    ax.set_title(f"{campaign}: {target} before and after compensation")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    axr.plot(t, y - yhat, color="tab:red", lw=1.0)
    axr.axhline(0, color="grey", lw=0.8)
    axr.set_ylabel("residual (µm)")
    axr.set_xlabel("time since campaign start (h)")
    axr.grid(alpha=0.3)
    fig.tight_layout()
    return _save(fig, path)


def _save(fig, path) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.tmp.png")
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    tmp.replace(path)
    return path
