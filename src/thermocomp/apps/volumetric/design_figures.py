"""Figures of the calibration design study (paper 001, Figs. 6, 8 and 9), drawn through :mod:`plots`."""

from __future__ import annotations

from pathlib import Path

from ...core.figures.plots import plt, save_figure

WHAT_IF_LABEL = "what-if: a ball outside the travel"


def _what_ifs(ax, x, rows) -> None:
    """Ring the strategies no bar can be measured in (``reachable: false``)."""
    out = [(xi, r["median"]) for xi, r in zip(x, rows) if not r.get("reachable", True)]
    if out:
        ax.scatter(*zip(*out), s=160, facecolors="none", edgecolors="red", linewidths=1.5,
                   zorder=5, label=WHAT_IF_LABEL)


def _band(ax, x, rows, label):
    med = [r["median"] for r in rows]
    ax.fill_between(x, [r["p5"] for r in rows], [r["p95"] for r in rows], alpha=0.2)
    ax.plot(x, med, "o-", label=f"{label} (median, 5-95 %)")
    _what_ifs(ax, x, rows)


def draw(folder, result: dict) -> list[Path]:
    """``balls.png`` (VCE vs balls), ``misalignment.png`` (VCE vs θ per set, with the VCE of
    the noise-free distances and of the noise alone) and
    ``position_sets.png`` (VCE per set vs probed points), each with VE as a reference and the
    strategies beyond the travel ringed as what-ifs."""
    folder = Path(folder)
    rows, ve = result["strategies"], result["ve"]
    written = []

    def study(name):
        return [r for r in rows if name in r["studies"]]

    balls = sorted(study("balls"), key=lambda r: r["n_balls"])
    if balls:
        fig, ax = plt.subplots(figsize=(6, 4))
        for s in dict.fromkeys(r["position_set"] for r in balls):
            rs = [r for r in balls if r["position_set"] == s]
            _band(ax, [r["n_balls"] for r in rs], rs, f"VCE {s}, θ={rs[0]['misalignment_deg']:g}°")
        ax.axhline(ve["median"], color="k", ls="--", label="VE (median)")
        ax.set(xlabel="number of balls", ylabel="µm", title="VCE vs number of balls", ylim=(0, None))
        ax.legend(fontsize=8)
        written.append(save_figure(fig, folder / "balls.png"))
    mis = study("misalignment")
    if mis:
        sets = list(dict.fromkeys(r["position_set"] for r in mis))
        fig, axes = plt.subplots(1, len(sets), figsize=(5 * len(sets), 4), sharey=True, squeeze=False)
        for ax, s in zip(axes[0], sets):
            rs = sorted((r for r in mis if r["position_set"] == s), key=lambda r: r["misalignment_deg"])
            theta = [r["misalignment_deg"] for r in rs]
            _band(ax, theta, rs, "VCE")
            # why: the VCE of the noise-free distances and of the noise alone (the identified
            # error is the sum of the two errors, not of their RMS)
            ax.plot(theta, [r["noise_free_median"] for r in rs], "s:", ms=3, lw=1,
                    label="noise-free distances (median)")
            ax.plot(theta, [r["noise_only_median"] for r in rs], "^:", ms=3, lw=1,
                    label="probing and ball noise alone (median)")
            ax.axhline(ve["median"], color="k", ls="--", label="VE (median)")
            ax.set(xlabel="misalignment θ (°)", ylabel="µm", title=f"{s}, {rs[0]['n_balls']} balls",
                   ylim=(0, None))
            ax.legend(fontsize=8)
        written.append(save_figure(fig, folder / "misalignment.png"))
    sets = study("position_sets")
    if sets:
        fig, ax = plt.subplots(figsize=(6, 4))
        for r in sets:
            spread = [[r["median"] - r["p5"]], [r["p95"] - r["median"]]]
            ax.errorbar(r["n_probings"], r["median"], yerr=spread, fmt="o", capsize=3)
            ax.annotate(r["position_set"] + ("" if r.get("reachable", True) else " (what-if)"),
                        (r["n_probings"], r["median"]), textcoords="offset points",
                        xytext=(4, 4), fontsize=8)
        _what_ifs(ax, [r["n_probings"] for r in sets], sets)
        ax.axhline(ve["median"], color="k", ls="--", label="VE (median)")
        ax.set(xlabel="probed points (poses × balls)", ylabel="VCE (µm)",
               title="VCE per position set (median, 5-95 %)", ylim=(0, None))
        ax.legend(fontsize=8)
        written.append(save_figure(fig, folder / "position_sets.png"))
    return written
