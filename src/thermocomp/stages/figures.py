"""Figures of the denoise and select stages (matplotlib, Agg, PNG)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def _save(fig, path) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def raw_vs_denoised_plot(hours, raw, offline, causal, sensor: str, campaign: str, path,
                         applied: bool = True) -> Path:
    """Raw sensor, offline EMD and causal denoising, and what was removed (°C against h)."""
    fig, (ax, axr) = plt.subplots(2, 1, figsize=(7.5, 5), sharex=True,
                                  gridspec_kw={"height_ratios": [2, 1]})
    ax.plot(hours, raw, color="0.6", lw=1, label="raw")
    ax.plot(hours, offline, color="k", lw=1.3, label="offline EMD (IMF-1 removed)")
    ax.plot(hours, causal, color="tab:red", lw=1, ls="--", label="causal (deployed)")
    ax.set_ylabel(f"{sensor} (°C)")
    title = f"{sensor}, campaign {campaign}"
    ax.set_title(title if applied else title + " -- illustration, denoise=none")
    ax.legend(fontsize=8)
    axr.plot(hours, np.asarray(raw) - np.asarray(offline), color="k", lw=0.8, label="offline")
    axr.plot(hours, np.asarray(raw) - np.asarray(causal), color="tab:red", lw=0.8, ls="--",
             label="causal")
    axr.set_ylabel("removed (°C)")
    axr.set_xlabel("time (h)")
    axr.legend(fontsize=8)
    fig.tight_layout()
    return _save(fig, path)


def imf_plot(hours, raw, imfs, sensor: str, campaign: str, path) -> Path:
    """The signal, its IMFs and the residue stacked (each in °C, centred IMFs), as in paper 004 Fig. 6."""
    rows = [("signal", raw)] + [(f"IMF-{i + 1}", imf) for i, imf in enumerate(imfs[:-1])] + \
        [("residue", imfs[-1])]
    fig, axes = plt.subplots(len(rows), 1, figsize=(7.5, 1.3 * len(rows) + 0.6), sharex=True)
    for ax, (label, values) in zip(np.atleast_1d(axes), rows):
        ax.plot(hours, values, color="k", lw=0.9)
        ax.set_ylabel(f"{label}\n(°C)", fontsize=8)
        ax.tick_params(labelsize=7)
    np.atleast_1d(axes)[0].set_title(f"EMD of {sensor}, campaign {campaign}")
    np.atleast_1d(axes)[-1].set_xlabel("time (h)")
    fig.tight_layout()
    return _save(fig, path)


def selection_plot(scores: dict, selected: dict, score_names: dict, path) -> Path:
    """Per target: the score of every candidate sensor, selected ones highlighted."""
    targets = list(scores)
    fig, axes = plt.subplots(len(targets), 1, figsize=(7.5, 2.4 * len(targets) + 0.4), squeeze=False)
    for ax, t in zip(axes[:, 0], targets):
        names = list(scores[t])
        values = [scores[t][n] for n in names]
        colors = ["tab:red" if n in selected[t] else "0.7" for n in names]
        ax.bar(range(len(names)), values, color=colors)
        ax.set_xticks(range(len(names)), names, rotation=45, ha="right", fontsize=7)
        ax.set_ylabel(score_names[t], fontsize=8)
        ax.set_title(f"{t}: selected {', '.join(selected[t])}", fontsize=9)
    fig.tight_layout()
    return _save(fig, path)
