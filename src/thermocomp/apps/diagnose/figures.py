"""Figures of a diagnosis (matplotlib, PNG): residual vs the accepted effect, E_P95 before/after."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...core.figures.plots import AFTER, BEFORE, _arr, _hour_ticks, plt, save_figure


def residual_vs_effect(residual, signal, units, label: str, target: str, path, time_s=None) -> Path:
    """The CV residual before an effect against the part of it the effect's features explain.

    Left: scatter over all train samples, one colour per campaign (or CV block),
    named in the legend, with the identity line (an effect that explained the
    residual completely would put every point on it).  Right: both against
    time (h since the campaign's start; sample index when ``time_s`` is None)
    for the campaign where the effect explains most.
    """
    r, s = np.asarray(residual, float), np.asarray(signal, float)
    units = np.asarray(units, dtype=object)
    ids = list(dict.fromkeys(units))
    hours = None if time_s is None else np.asarray(time_s, float) / 3600.0
    fig, (ax, axt) = plt.subplots(1, 2, figsize=(11, 4.8), gridspec_kw={"width_ratios": [1, 1.4]},
                                  layout="constrained")
    cmap = plt.get_cmap("viridis", max(len(ids), 2))
    for i, u in enumerate(ids):
        rows = units == u
        ax.plot(s[rows], r[rows], ".", ms=3, color=cmap(i), alpha=0.7, label=str(u))
    lim = np.nanmax(np.abs(np.r_[r, s])) if r.size else 1.0
    ax.plot([-lim, lim], [-lim, lim], color="k", lw=0.8, ls="--", label="residual = effect")
    ax.set_xlabel("effect signal: the residual part its features explain (µm)")
    ax.set_ylabel(f"{target} CV residual before (µm)")
    ax.set_title(label, fontsize=9)
    ax.grid(alpha=0.3)
    # one entry per campaign: below the axes, in columns, so many campaigns stay readable
    ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=min(6, len(ids) + 1),
              markerscale=3, title="train campaign (CV unit)", title_fontsize=7, frameon=False)
    best = max(ids, key=lambda u: float(np.sum(s[units == u] ** 2))) if ids else None
    if best is not None:
        rows = np.flatnonzero(units == best)
        x = hours[rows] if hours is not None else np.arange(rows.size)
        axt.plot(x, r[rows], color=BEFORE, lw=1.2, label="CV residual before")
        axt.plot(x, s[rows], color=AFTER, lw=1.2, ls="--", label="effect signal")
        axt.plot(x, r[rows] - s[rows], color="grey", lw=0.9, label="what is left")
        axt.set_xlabel("time since campaign start (h)" if hours is not None else f"sample of {best}")
        axt.set_ylabel(f"{target} (µm)")
        axt.set_title(f"{best}: the campaign the effect explains most", fontsize=9)
        axt.grid(alpha=0.3)
        axt.legend(fontsize=8)
    return save_figure(fig, path)


def e_p95_before_after(window_s, measured, before, after, target: str, statistic: str,
                       model: str, path) -> Path:
    """E_P95 curves on the test split: measured error, residual before and after the diagnosis."""
    h = np.asarray(window_s, float) / 3600.0
    name = "range" if statistic == "range" else "σ"
    fig, ax = plt.subplots(figsize=(7, 4.2))
    ax.plot(h, _arr(measured), color="grey", lw=1.5, ls=":", label="measured error (no compensation)")
    ax.plot(h, _arr(before), color=BEFORE, lw=2, label=f"residual, {model}")
    ax.plot(h, _arr(after), color=AFTER, lw=2, label=f"residual, {model} + diagnosed effects")
    _hour_ticks(ax, h)
    ax.set_xlabel("window length Δt (h)")
    ax.set_ylabel(f"{target} $E_{{P95}}$({name}) (µm)")
    ax.set_title(f"{target}, test campaigns: before and after the diagnosis", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    return save_figure(fig, path)


def diagnosis_figures(diagnosis, folder) -> dict[str, list[Path]]:
    """Every figure of a :class:`~thermocomp.apps.diagnose.Diagnosis`, per target, under ``folder``."""
    folder = Path(folder)
    out: dict[str, list[Path]] = {}
    for t, d in diagnosis.targets.items():
        paths = []
        j = diagnosis.to_json(t)["test_e_p95"]
        paths.append(e_p95_before_after(j["window_s"], j["measured"], j["before"], j["after"], t,
                                        j["statistic"], diagnosis.model, folder / f"e_p95_{t}.png"))
        for k, rnd in enumerate(r for r in d.search.rounds if r.accepted is not None):
            data = rnd.figure_data or {}
            if data.get("signal") is None:
                continue    # a removed sensor has no signal of its own
            e = rnd.accepted.effect
            label = f"step {k + 1}: {e.kind} {e.column or ''} {e.label}".replace("  ", " ")
            paths.append(residual_vs_effect(data["residual"], data["signal"], data["units"], label, t,
                                            folder / f"residual_vs_effect_{t}_{k + 1}.png",
                                            data.get("time_s")))
        out[t] = paths
    return out
