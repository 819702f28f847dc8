"""Figures of the volumetric validation (paper 000, Figs. 20-26): E_P95(σ) along the three
mid-range trajectories, the A.3 virtual test, the per-parameter reduction."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...core.figures.plots import AFTER, BEFORE, plt, save_figure
from ...core.metrics import RMS_AFTER, RMS_BEFORE


def trajectory_plot(axis: str, entry: dict, path) -> Path:
    """E_P95(σ) of the X, Y and Z error along one trajectory, before and after, per window."""
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.4), sharey=False)
    for ax, (direction, curve) in zip(axes, entry.items()):
        h = np.asarray(curve["window_s"], float) / 3600.0
        ax.plot(h, curve["before"], color=BEFORE, lw=1.5, label="before")
        ax.plot(h, curve["after"], color=AFTER, lw=1.5, label="after")
        ax.set_xscale("log")
        ax.set_xlabel("window Δt (h)")
        ax.set_title(f"{direction} along the {axis} trajectory", fontsize=9)
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("E_P95(σ) (µm)")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    return save_figure(fig, path)


def iso_a3_plot(curves: dict, path) -> Path:
    """Slot range of the 15 h A.3 test against its start, before/after, every test campaign."""
    fig, ax = plt.subplots(figsize=(7, 3.6))
    for k, (cid, mv) in enumerate(curves.items()):
        h = np.asarray(mv["start_s"], float) / 3600.0
        ax.plot(h, mv["range_before"], color=BEFORE, lw=1.2, label="before" if k == 0 else None)
        ax.plot(h, mv["range_after"], color=AFTER, lw=1.2, label="after" if k == 0 else None)
    ax.set_xlabel("start of the 15 h A.3 test (h)")
    ax.set_ylabel("Z slot range (µm)")
    ax.set_title("ISO 10791-10 A.3 virtual test, test piece on the table")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return save_figure(fig, path)


def parameter_plot(parameters: dict, path) -> Path:
    """RMS of each parameter's change before and after its thermal model."""
    names = list(parameters)
    x = np.arange(len(names))
    fig, ax = plt.subplots(figsize=(max(6.0, 0.35 * len(names)), 3.6))
    ax.bar(x - 0.2, [parameters[n][RMS_BEFORE] for n in names], 0.4, color=BEFORE, label="before")
    ax.bar(x + 0.2, [parameters[n][RMS_AFTER] for n in names], 0.4, color=AFTER, label="after")
    ax.set_xticks(x, names, rotation=90, fontsize=7)
    ax.set_ylabel("RMS (µm or µm/m)")
    ax.set_title("error parameters: change on the test split, before and after the thermal model")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save_figure(fig, path)


def draw_validation(folder, section: dict, curves: dict) -> Path:
    """Every volumetric figure into ``folder`` (created)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for axis, entry in section["trajectories"].items():
        trajectory_plot(axis, entry, folder / f"e_p95_sigma_{axis}_trajectory.png")
    if curves.get("iso_a3"):
        iso_a3_plot(curves["iso_a3"], folder / "iso10791_a3.png")
    parameter_plot(section["parameters"], folder / "parameters.png")
    return folder
