"""Figures of `thermocomp monitor`, after paper 002 (figs. 8–11)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...base.log import logger
from ...core.figures.plots import plt, save_figure
from ..deploy.surveillance import STATES

COLOURS = {"ok": "#2ca02c", "warning": "#ffbf00", "alarm": "#d62728", "excluded": "#7f7f7f"}


def _campaign(traces: dict, report: dict) -> str:
    """The campaign of the first exclusion or alarm, else the first one."""
    for e in report["events"]:
        if e["to"] in ("alarm", "excluded") and e.get("sensor") in report["sensors"]:
            return e["campaign"]
    return next(iter(traces))


def draw(folder: Path, adaptive, traces: dict, report: dict, map_time_h=None) -> list[Path]:
    folder.mkdir(parents=True, exist_ok=True)
    cid = _campaign(traces, report)
    tr = traces[cid]
    hours = (tr["time"] - tr["time"][0]) / 3600.0
    mon = adaptive.monitor
    out = []

    # 1. self-prediction error per sensor with the bands (excluded samples dotted)
    fig, ax = plt.subplots(figsize=(10, 5))
    E, S = tr["errors"], tr["states"]
    # the bands of the sensors with an error to show: one no other predicts has none, and its
    # band (from its loose training spread: ±54 °C on a lathe's spindle motor) set the scale,
    # every other error a flat line at 0
    shown = np.isfinite(E).any(axis=0)
    if not shown.any():
        shown = np.ones(len(mon.names), dtype=bool)
    warning_c, alarm_c = mon.warning_c[shown].max(), mon.alarm_c[shown].max()
    for j, name in enumerate(mon.names):
        e = E[:, j]
        if not np.isfinite(e).any():
            continue
        line, = ax.plot(hours, np.where(S[:, j] != 3, e, np.nan), lw=1, label=name)
        ax.plot(hours, np.where(S[:, j] == 3, e, np.nan), ls=":", color=line.get_color(), lw=1)
    for band, c in ((warning_c, COLOURS["warning"]), (alarm_c, COLOURS["alarm"])):
        ax.axhline(band, color=c, ls="--", lw=1)
        ax.axhline(-band, color=c, ls="--", lw=1)
    ax.set(xlabel="time (h)", ylabel="self-prediction error E_s (°C)",
           title=f"{cid}: self-prediction error per sensor (dotted: excluded)")
    ax.legend(fontsize=6, ncol=4, loc="upper left")
    out.append(save_figure(fig, folder / "self_prediction.png"))

    # 2. sensor map state at an instant
    if map_time_h is not None and float(map_time_h) > hours[-1]:
        logger.warning(f"monitor.map_time_h={float(map_time_h):g} is after the end of campaign {cid} "
                       f"({hours[-1]:.4g} h): the sensor map shows its last sample")
    if map_time_h is None:
        first = [e for e in report["events"] if e["campaign"] == cid and e["to"] in ("alarm", "excluded")
                 and e.get("sensor") in report["sensors"]]
        map_time_h = (first[0]["time"] - tr["time"][0]) / 3600.0 if first else hours[-1]
    i = int(np.clip(np.searchsorted(hours, float(map_time_h)), 0, len(hours) - 1))
    fig, ax = plt.subplots(figsize=(10, 1.2 + 0.25 * len(mon.names)))
    y = np.arange(len(mon.names))
    vals = np.nan_to_num(E[i])
    ax.barh(y, vals, color=[COLOURS[STATES[s]] for s in S[i]])
    ax.set_yticks(y, mon.names, fontsize=7)
    for band in (warning_c, alarm_c):
        ax.axvline(band, color="k", ls=":", lw=0.8)
        ax.axvline(-band, color="k", ls=":", lw=0.8)
    ax.set(xlabel="self-prediction error (°C)",
           title=f"{cid} at {hours[i]:.2f} h: sensor states "
                 "(green ok, yellow warning, red alarm, grey excluded)")
    out.append(save_figure(fig, folder / "sensor_map.png"))

    # 3. compensation error, fixed vs adaptive
    if tr["measured"] is not None:
        k = len(adaptive.targets_)
        fig, axes = plt.subplots(k, 1, figsize=(10, 2.4 * k), sharex=True, squeeze=False)
        for n, (ax, t) in enumerate(zip(axes[:, 0], adaptive.targets_)):
            m = tr["measured"][:, n]
            ax.plot(hours, m, color="0.6", lw=1, label="measured error")
            ax.plot(hours, m - tr["fixed"][:, n], lw=1, label="residual, fixed model")
            ax.plot(hours, m - tr["adaptive"][:, n], lw=1, label="residual, adaptive model")
            ax.set_ylabel(f"{t} (µm)")
        axes[0, 0].legend(fontsize=7)
        axes[-1, 0].set_xlabel("time (h)")
        axes[0, 0].set_title(f"{cid}: compensation error, fixed and adaptive")
        out.append(save_figure(fig, folder / "compensation.png"))
    return out
