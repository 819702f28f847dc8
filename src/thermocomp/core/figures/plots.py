"""Figures (matplotlib, Agg backend, PNG), saved atomically by :func:`save_figure`.

Every figure of the pipeline is drawn here (the diagnosis' own in
:mod:`thermocomp.apps.diagnose.figures`, saved the same way); :class:`FigurePool`
draws them in worker processes while the caller goes on computing.
"""

from __future__ import annotations

import io
import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor
from functools import cache
from pathlib import Path

import numpy as np

from ...base.files import atomic_write_bytes
from ...base.lifetime import die_with_parent
from ..metrics import unit

DPI = 110


@cache
def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot

    return matplotlib.pyplot


class _Pyplot:
    """``matplotlib.pyplot`` on the Agg backend, imported on first use: a run whose figures
    are drawn by :class:`FigurePool` workers never pays that import (0.3 s) itself."""

    def __getattr__(self, name):
        return getattr(_pyplot(), name)


plt = _Pyplot()


def residual_plot(time_s, measured, predicted, target: str, campaign: str, path) -> Path:
    """Measured error, prediction and residual of one campaign against time (h)."""
    t = np.asarray(time_s, float) / 3600.0
    y, yhat = np.asarray(measured, float), np.asarray(predicted, float)
    fig, (ax, axr) = plt.subplots(2, 1, figsize=(7, 4.5), sharex=True,
                                  gridspec_kw={"height_ratios": [2, 1]})
    ax.plot(t, y, label=f"measured {target}", color="k", lw=1.2)
    ax.plot(t, yhat, label="model", color="tab:blue", lw=1.2, ls="--")
    ax.set_ylabel(f"error ({unit(target)})")
    ax.set_title(f"{campaign}: {target} before and after compensation")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    axr.plot(t, y - yhat, color="tab:red", lw=1.0, label="residual = measured − model")
    axr.axhline(0, color="grey", lw=0.8)
    axr.set_ylabel(f"residual ({unit(target)})")
    axr.set_xlabel("time since campaign start (h)")
    axr.legend(loc="best", fontsize=8)
    axr.grid(alpha=0.3)
    fig.tight_layout()
    return save_figure(fig, path)


BEFORE, AFTER = "#c0392b", "#1f5fa8"  # measured error / residual, in every figure


def e_p95_plot(window_s, before, after, target: str, statistic: str, path,
               max_before=None, max_after=None) -> Path:
    """E_P95 curves before/after compensation against window length (h, log axis), µm.

    With ``max_before``/``max_after`` the E_max curves (worst window) are drawn thin.
    """
    h = np.asarray(window_s, float) / 3600.0
    fig, ax = plt.subplots(figsize=(7, 4.2))
    label = "range" if statistic == "range" else "σ"
    ax.plot(h, _arr(before), color=BEFORE, lw=2, label=f"before: $E_{{P95}}$({label}), measured")
    ax.plot(h, _arr(after), color=AFTER, lw=2, label=f"after: $E_{{P95}}$({label}), residual")
    if max_before is not None and max_after is not None:
        ax.plot(h, _arr(max_before), color=BEFORE, lw=0.9, ls=":", label="$E_{max}$ before")
        ax.plot(h, _arr(max_after), color=AFTER, lw=0.9, ls=":", label="$E_{max}$ after")
    _hour_ticks(ax, h)
    ax.set_xlabel("window length Δt (h)")
    ax.set_ylabel(f"{target} error {label} in window ({unit(target)})")
    ax.set_title(f"{target}: in 95 % of windows of length Δt the error varies less than this")
    ax.title.set_fontsize(10)
    ax.grid(alpha=0.3, which="both")
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    return save_figure(fig, path)


def rsd_plot(per_campaign: dict, target: str, path, ambient: dict | None = None,
             baselines: dict | None = None, label: str = "model") -> Path:
    """Rsd of each test campaign (bars) with SM (line) and SM ± SD (band), µm.

    ``per_campaign``: campaign -> Rsd of the evaluated model; ``ambient``:
    campaign -> initial ambient (°C), shown in the tick labels and used for the
    order; ``baselines``: name -> {campaign -> Rsd} drawn as markers.
    """
    ids = list(per_campaign)
    if ambient and all(np.isfinite(ambient.get(c, np.nan)) for c in ids):
        ids.sort(key=lambda c: ambient[c])
        ticks = [f"{c}\n{ambient[c]:.1f} °C" for c in ids]
    else:
        ticks = ids
    v = np.array([per_campaign[c] for c in ids], float)
    sm = float(np.nanmean(v))
    sd = float(np.nanstd(v, ddof=1)) if np.isfinite(v).sum() > 1 else 0.0
    x = np.arange(len(ids))
    fig, ax = plt.subplots(figsize=(max(6, 0.65 * len(ids) + 2) + (3.2 if baselines else 0), 4.2))
    ax.bar(x, v, color=AFTER, alpha=0.8, width=0.6, label=label)
    ax.axhline(sm, color="k", lw=1.5, label=f"SM = {sm:.2f} {unit(target)}")
    ax.axhspan(sm - sd, sm + sd, color="grey", alpha=0.2, label=f"SM ± SD (SD = {sd:.2f} {unit(target)})")
    markers = iter("ov^sD")
    for name, values in (baselines or {}).items():
        b = np.array([values.get(c, np.nan) for c in ids], float)
        ax.plot(x, b, ls="none", marker=next(markers, "x"), mfc="none", ms=7,
                label=f"{name} (SM = {np.nanmean(b):.2f} {unit(target)})")
    ax.set_xticks(x, ticks, fontsize=8)
    ax.set_xlabel("test campaign (initial ambient)" if ticks is not ids else "test campaign")
    ax.set_ylabel(f"{target} residual Rsd ({unit(target)})")
    ax.set_title(f"{target}: Rsd per test campaign (accuracy SM, robustness SD)")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3, axis="y")
    if baselines:
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    else:
        ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    return save_figure(fig, path)


def mutual_prediction_plot(campaigns, rsd_matrix, target: str, path, ambient=None,
                           trained_on=None) -> Path:
    """Heat map of Rsd (µm, log colour scale): row = trained on (``trained_on``, default every
    campaign), column = predicted campaign."""
    from matplotlib.colors import LogNorm

    m = np.array([[np.nan if v is None else v for v in row] for row in rsd_matrix], float)
    labels = [f"{c} ({a:.0f} °C)" if a is not None and np.isfinite(a) else str(c)
              for c, a in zip(campaigns, ambient if ambient is not None else [None] * len(campaigns))]
    rows = list(campaigns) if trained_on is None else list(trained_on)
    n, k = len(campaigns), len(rows)
    size = min(11, 3 + 0.3 * n)
    fig, ax = plt.subplots(figsize=(size + 1.2, min(11, 3 + 0.3 * k) if k < n else size))
    pos = m[np.isfinite(m) & (m > 0)]
    norm = LogNorm(vmin=pos.min(), vmax=pos.max()) if pos.size and pos.max() > pos.min() else None
    im = ax.imshow(m, cmap="viridis_r", norm=norm, aspect="equal")
    ax.set_xticks(range(n), labels, rotation=90, fontsize=7)
    ax.set_yticks(range(k), [labels[list(campaigns).index(c)] for c in rows], fontsize=7)
    ax.set_xlabel("predicted campaign (initial ambient)")
    ax.set_ylabel("model trained on campaign (initial ambient)"
                  + (f"\n{k} of {n}: eval.mutual_prediction_max_models" if k < n else ""))
    ax.set_title(f"{target}: mutual prediction, Rsd ({unit(target)})")
    fig.colorbar(im, ax=ax, shrink=0.8, label=f"{target} Rsd ({unit(target)})")
    fig.tight_layout()
    return save_figure(fig, path)


def ati_intervals_plot(campaign_ambient: dict, boundaries, target: str, path,
                       test_ambient: dict | None = None, interval_campaigns=None) -> Path:
    """Campaigns' initial ambient (°C, x) and the ATI boundaries; one row per campaign.

    Campaigns are sorted by ambient; train campaigns are dots coloured by
    interval, test campaigns open diamonds; shaded bands are the intervals.
    """
    test = dict(test_ambient or {})
    rows = sorted({**campaign_ambient, **test}.items(), key=lambda kv: (kv[1], kv[0]))
    a_all = np.array([a for _, a in rows], float)
    lo, hi = np.nanmin(a_all) - 1.5, np.nanmax(a_all) + 1.5
    edges = [lo, *[float(b) for b in boundaries], hi]
    colours = plt.get_cmap("coolwarm")(np.linspace(0.05, 0.95, len(edges) - 1))
    fig, ax = plt.subplots(figsize=(8.5, max(3.5, 0.2 * len(rows) + 1.8)))
    for m in range(len(edges) - 1):
        ax.axvspan(edges[m], edges[m + 1], color=colours[m], alpha=0.15)
        n_camp = len(interval_campaigns[m]) if interval_campaigns is not None else None
        label = f"ATI {m + 1}" + (f"\n{n_camp} train" if n_camp is not None else "")
        ax.text((edges[m] + edges[m + 1]) / 2, len(rows) + 0.2, label, ha="center", va="bottom",
                fontsize=8)
    for b in boundaries:
        ax.axvline(b, color="k", lw=1, ls="--")
        ax.text(b, -1.0, f"{b:.1f} °C", ha="center", va="top", fontsize=8,
                bbox={"fc": "white", "ec": "none", "pad": 1})
    which = np.searchsorted(np.asarray(boundaries, float), a_all, side="left")
    for y, (c, a) in enumerate(rows):
        colour = colours[which[y]]
        if c in test:
            ax.plot(a, y, marker="D", ms=6, mfc="white", mec="k", ls="none")
        else:
            ax.plot(a, y, marker="o", ms=7, mfc=colour, mec="k", mew=0.5, ls="none")
    ax.plot([], [], "o", color="grey", label="train campaign")
    ax.plot([], [], "D", mfc="white", mec="k", label="test campaign")
    ax.set_yticks(range(len(rows)), [c for c, _ in rows], fontsize=7)
    ax.set_ylim(-2.0, len(rows) + 1.6)
    ax.set_xlim(lo, hi)
    ax.set_xlabel("initial ambient temperature of the campaign (°C)")
    ax.set_ylabel("campaign (sorted by ambient)")
    ax.set_title(f"{target}: ambient temperature intervals (one model each)")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    return save_figure(fig, path)


def elbow_plot(elbow: dict, target: str, path) -> Path:
    """Leave-one-campaign-out SM and SD (µm) against the number of ATIs; chosen one circled."""
    n = np.asarray(elbow["n_intervals"], int)
    sm, sd = _arr(elbow["sm"]), _arr(elbow["sd"])
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(n, sm, "o-", color=AFTER, label="SM (mean of Rsd): accuracy")
    ax.plot(n, sd, "s-", color="tab:orange", label="SD (s.d. of Rsd): robustness")
    single = elbow.get("single_model")
    if single and single.get("sm") is not None:
        ax.axhline(single["sm"], color=AFTER, ls=":", lw=1, label="SM, one model")
        if single.get("sd") is not None:
            ax.axhline(single["sd"], color="tab:orange", ls=":", lw=1, label="SD, one model")
    chosen = elbow.get("chosen")
    if chosen in n.tolist():
        i = n.tolist().index(chosen)
        ax.plot([chosen, chosen], [sm[i], sd[i]], "o", ms=16, mfc="none", mec="k",
                label=f"chosen: {chosen} intervals")
    ax.set_xticks(n)
    ax.set_xlabel("number of ambient temperature intervals")
    ax.set_ylabel(f"{target} held-out Rsd ({unit(target)})")
    ax.set_title(f"{target}: elbow (leave-one-campaign-out on train campaigns)")
    ax.title.set_fontsize(10)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save_figure(fig, path)


def iso_a3_plot(start_s, range_before, range_after, target: str, campaign: str, path) -> Path:
    """ISO 10791-10 A.3 virtual test: slot range (µm) against the test's start time (h)."""
    h = np.asarray(start_s, float) / 3600.0
    fig, ax = plt.subplots(figsize=(7, 3.8))
    ax.plot(h, range_before, color=BEFORE, lw=1.5, label="before (measured)")
    ax.plot(h, range_after, color=AFTER, lw=1.5, label="after (residual)")
    ax.set_xlabel("start of the 15 h A.3 test since campaign start (h)")
    ax.set_ylabel(f"{target} range of 16 slots ({unit(target)})")
    ax.set_title(f"{campaign}: ISO 10791-10 A.3 virtual test started at every sample")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save_figure(fig, path)


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
    return save_figure(fig, path)


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
    return save_figure(fig, path)


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
    return save_figure(fig, path)


def _hour_ticks(ax, hours) -> None:
    """Log time axis with plain-number ticks (0.1, 0.25 ... 168 h) inside the data range."""
    from matplotlib.ticker import FixedLocator, NullFormatter

    ax.set_xscale("log")
    h = np.asarray(hours, float)
    h = h[np.isfinite(h) & (h > 0)]
    if not h.size:
        return
    nice = [0.1, 0.25, 0.5, 1, 2, 4, 8, 15, 24, 48, 96, 168, 336, 720]
    ticks = [v for v in nice if h.min() * 0.999 <= v <= h.max() * 1.001]
    ax.xaxis.set_major_locator(FixedLocator(ticks))
    ax.set_xticks(ticks, [f"{v:g}" for v in ticks])
    ax.xaxis.set_minor_formatter(NullFormatter())


def _arr(values) -> np.ndarray:
    return np.array([np.nan if v is None else v for v in values], float)


def save_figure(fig, path) -> Path:
    """Write ``fig`` as PNG to ``path`` atomically and close it (the one figure saver).

    Rendered in memory, then :func:`~thermocomp.base.files.atomic_write_bytes` (temp
    file + rename, 0644): a reader never sees half a figure, and parallel
    workers never share a temp file.
    """
    png = io.BytesIO()
    try:
        fig.savefig(png, format="png", dpi=DPI)
    finally:
        plt.close(fig)
    return atomic_write_bytes(path, png.getvalue())


def _cpus() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


# A forked worker keeps every page the caller held when it was forked, also those the caller
# frees later: forked from a run holding a year's lag features (4.8 GB), the two workers held
# them on (scale58). Above this resident size figures are drawn in the caller instead (the same
# CPU, not beside the computing); a fork server would re-run an unguarded main script.
FORK_MAX_RSS = 1 << 30


def too_large_to_fork() -> bool:
    """This process holds more than ``FORK_MAX_RSS`` resident: :class:`FigurePool` draws here."""
    import psutil

    return psutil.Process().memory_info().rss > FORK_MAX_RSS


class FigurePool:
    """Draw figures in forked worker processes while the caller goes on computing.

    ``submit(plot, *args, **kwargs)`` queues ``plot(*args, **kwargs)``, a
    drawing function of this module (it returns the saved path); leaving the
    ``with`` block waits for every figure and re-raises the first error.
    Drawing is Python-bound (layout, ticks) and matplotlib is not thread-safe
    (a thread pool was slower and crashed in mathtext), hence processes;
    ``fork`` makes a worker cost a few ms instead of a fresh interpreter (a
    worker imports pyplot for its first figure, while the caller computes).  A worker dies
    with the caller, even a SIGKILLed one
    (:func:`~thermocomp.base.lifetime.die_with_parent`).

    Parameters
    ----------
    workers : int, optional
        Worker processes; default one per CPU this process may use.  ``0``
        (the default on one CPU, and above ``FORK_MAX_RSS`` resident: a worker would keep
        the memory this process frees later), or no ``fork`` (Windows, macOS default):
        figures are drawn in this process at submit time.

    Attributes
    ----------
    paths : list of Path
        The figures written, in submit order (complete after the ``with`` block).
    """

    def __init__(self, workers: int | None = None):
        if workers is None:
            workers = _cpus() if _cpus() > 1 and not too_large_to_fork() else 0
        fork = "fork" in multiprocessing.get_all_start_methods()
        self._pool = (ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork"),
                                          initializer=die_with_parent, initargs=(os.getpid(),))
                      if workers > 0 and fork else None)
        self._pending: list = []
        self.paths: list[Path] = []

    def submit(self, plot, *args, **kwargs) -> None:
        if self._pool is None:
            self.paths.append(plot(*args, **kwargs))
        else:
            self._pending.append(self._pool.submit(plot, *args, **kwargs))

    def __enter__(self) -> "FigurePool":
        return self

    def __exit__(self, exc_type, exc, tb) -> bool:
        if self._pool is not None:
            # wait even on error: no worker may still write once the caller cleans up
            self._pool.shutdown(wait=True, cancel_futures=exc_type is not None)
            if exc_type is None:
                self.paths += [f.result() for f in self._pending]
        return False
