"""The replay report: stream campaigns row by row through a deployable compensator and check it
(pure core; a module of its own, not `replay`, which names the streaming function).

The deployed object is what ``promote`` registers inside the pyfunc model: a
:class:`~thermocomp.apps.deploy.StreamingCompensator`, or (default) an
:class:`~thermocomp.apps.deploy.AdaptiveCompensator` around one (sensor
surveillance, adaptive inputs, guarded correction).  Each campaign is streamed
from its start, one sample at a time, as a CNC loop calls it: from a reset, or,
for a campaign that continues others (``data.reference=none``), warmed on them
unscored (:func:`~.streaming.warm`).  Two streams per campaign:

* the **plain** stream (the streaming compensator alone, envelope off, no
  monitor), compared with the batch prediction of the same fitted
  :class:`~thermocomp.core.compensator.Compensator` (of the campaign joined to the
  ones it continues, as ``run`` scores it): any difference is the stream's
  (causality, state).  The comparison stops at a campaign's first missing value,
  which the plain stream refuses; the batch prediction's RMSE covers every row, the
  missing input cells interpolated as ``run``'s read repairs a gap (deploy88);
* the **deployed** stream (as registered), whose residual gives ``rmse`` and
  whose events and excluded sensors fill ``replay.json``.

The result is the ``replay.json`` layout of CLI.md.
"""

from __future__ import annotations

import time as clock
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ...base.errors import ContractError
from ...base.tables import name_width
from ...core.context import TIME
from ...core.guarded import summed
from ...core.metrics import RMSE
from ...core.timerule import stream_start
from .adapt import adapt_figures, finite_rms
from .adaptive import AdaptiveCompensator
from .guard import guard_changes
from .streaming import (
    OutOfEnvelopeError,
    StreamingCompensator,
    batch_prediction,
    on_campaign_clock,
    warm,
    warm_events,
)
from .surveillance import NEW_STATE


@dataclass
class Streamed:
    """One campaign streamed from its start."""

    y: np.ndarray                      # prediction per row and target (n, targets)
    clamped: np.ndarray                # inputs clamped to the envelope, per row
    seconds: float                     # time spent in the step loop
    events: list = field(default_factory=list)     # the adaptive compensator's, in order
    excluded: list = field(default_factory=list)   # sensors excluded after the last row
    guarded: np.ndarray | None = None  # rows per target whose correction the guard changed
    # the adaptive compensator's events while warmed on the campaigns it continues (deploy88)
    warm_events: list = field(default_factory=list)


def plain(deployed) -> StreamingCompensator:
    """The streaming compensator inside ``deployed`` (itself when it is one)."""
    return deployed.streaming if isinstance(deployed, AdaptiveCompensator) else deployed


def summary(deployed) -> dict:
    """``{"adaptive": bool, "pod": {...} | None}``: what ``promote.json`` and ``replay.json``
    say of the deployed object (the POD of its sensor monitor, when it has one)."""
    adaptive = isinstance(deployed, AdaptiveCompensator)
    mon = deployed.monitor if adaptive else None
    pod = None
    if mon is not None:
        p = mon.pod
        pod = {"n_sensors": len(mon.names), "n_modes": int(p.n_modes_),
               "captured_energy": float(p.energy_[p.n_modes_ - 1]), "sensors": list(mon.names)}
    return {"adaptive": adaptive, "pod": pod}


def streamed_hours(campaign: pd.DataFrame, period_s: float) -> float:
    """Hours a campaign covers: its known time span plus one period (rows × period without
    a time)."""
    t = campaign[TIME].to_numpy(float) if TIME in campaign.columns else np.empty(0)
    known = t[np.isfinite(t)]
    span = known[-1] - known[0] + period_s if len(known) > 1 else len(campaign) * period_s
    return float(span) / 3600


def alarm_rate(events: list[dict], hours: float) -> dict:
    """Sensor exclusions per 100 h streamed (on healthy campaigns: the false-alarm rate) and
    the re-admissions, beside the hours they are counted over (CLI.md, ``alarms``)."""
    excluded = [e for e in events if e.get("sensor") and e["to"] == "excluded"]
    per_sensor: dict[str, int] = {}
    for e in excluded:
        per_sensor[e["sensor"]] = per_sensor.get(e["sensor"], 0) + 1
    return {"hours": float(hours), "exclusions": len(excluded),
            "exclusions_per_100h": 100 * len(excluded) / hours if hours > 0 else None,
            "readmissions": sum(1 for e in events if e.get("sensor") and e["from"] == "excluded"),
            "exclusions_by_sensor": per_sensor,
            "new_thermal_states": sum(1 for e in events if e.get("to") == NEW_STATE)}


def campaign_start(campaign: pd.DataFrame, period_s: float) -> float:
    """Where the campaign starts on the clock of its ``time`` (0 without one): its first time, or,
    where that is missing, the first time read less a period per row before it, as the stream
    steps (:func:`thermocomp.core.timerule.stream_start`); times are written in seconds from it (CLI.md)."""
    return stream_start(campaign[TIME].to_numpy(float) if TIME in campaign.columns else [],
                        period_s)


def stream_rows(deployed, campaign: pd.DataFrame, cid: str = "", file=None,
                lead_in: pd.DataFrame | None = None) -> Streamed:
    """Stream one campaign from its start through ``_step`` (the body of ``step`` and ``predict``):
    from a reset, or warmed on ``lead_in``, the campaigns it continues (:func:`~.streaming.warm`).

    The adaptive compensator's events get ``campaign`` (``cid``) added, their ``time`` from the
    campaign's first row on the stream's clock (:mod:`thermocomp.core.timerule`).  A row the
    plain streaming compensator refuses (a missing value, an input outside the
    envelope with ``policy=refuse``) raises :class:`ContractError` naming the
    campaign, its ``file``, the column and the row (1-based).
    """
    X = campaign[deployed.columns_].to_numpy(float)
    t = campaign[TIME].to_numpy(float) if TIME in campaign.columns else np.full(len(campaign), np.nan)
    y = np.empty((len(X), len(deployed.targets_)))
    clamped = np.zeros(len(X), dtype=np.int64)
    adaptive = isinstance(deployed, AdaptiveCompensator)
    t0 = float("nan")      # the first row's time on the stream's clock: events count from it
    events: list[dict] = []
    try:
        warm(deployed, lead_in, campaign)
    except OutOfEnvelopeError as exc:
        raise ContractError(f"campaign {cid}: {exc}", file=file) from None
    warmed = guard_changes(deployed)
    # what the monitor did on the lead-in leaves the state the campaign starts from (deploy88)
    lead_events = warm_events(deployed, lead_in)
    step = deployed._step   # returns the clamp count too
    start = clock.perf_counter()
    i = 0
    try:
        for i in range(len(X)):
            y[i], clamped[i] = step(X[i], t[i])
            if adaptive and not i:
                t0 = deployed.clock_time_
            if adaptive and deployed.last_events_:
                events += on_campaign_clock(deployed.last_events_, t0, cid)
    except OutOfEnvelopeError as exc:
        deployed.reset()
        gap = np.flatnonzero(~np.isfinite(X[i]))
        if len(gap):
            raise ContractError(f"campaign {cid}: no finite value at {t[i] - t[0]:g} s from its "
                                "first row (sensor dropout?), which the plain "
                                "streaming compensator refuses (monitor.adaptive=true holds or "
                                "reconstructs it)", file=file, column=deployed.columns_[gap[0]],
                                row=i + 1) from None
        raise ContractError(f"campaign {cid}: {exc}", file=file, row=i + 1) from None
    seconds = clock.perf_counter() - start
    excluded = list(deployed.excluded_inputs) if adaptive else []
    guarded = None if warmed is None else guard_changes(deployed) - warmed
    deployed.reset()
    # their times, as the campaign's events', from its first row on the stream's clock (< 0)
    lead_events = on_campaign_clock(lead_events, t0, cid)
    return Streamed(y, clamped, seconds, events, excluded, guarded, lead_events)


def complete_rows(campaign: pd.DataFrame, columns) -> int:
    """Rows before the campaign's first missing value in ``columns``."""
    bad = ~np.isfinite(campaign[list(columns)].to_numpy(float)).all(axis=1)
    return int(np.argmax(bad)) if bad.any() else len(campaign)


def gaps_interpolated(campaign: pd.DataFrame, columns) -> pd.DataFrame:
    """``campaign`` with the missing cells of ``columns`` on the line between their two valid
    neighbours in time (its ``time``, else its rows), as ``run``'s read repairs a gap within
    ``data.max_gap_samples``; before a column's first or after its last valid value, that value
    held.  The batch prediction of every row, beside a stream that holds or reconstructs them."""
    filled = campaign.copy()
    t = campaign[TIME].to_numpy(float) if TIME in campaign.columns else np.arange(len(campaign), dtype=float)
    t = t if np.isfinite(t).all() else np.arange(len(campaign), dtype=float)
    for c in columns:
        v = campaign[c].to_numpy(float)
        ok = np.isfinite(v)
        if ok.any() and not ok.all():
            filled[c] = np.where(ok, v, np.interp(t, t[ok], v[ok]))
    return filled


def replay_report(deployed, campaigns: Mapping[str, pd.DataFrame],
                  files: Mapping[str, object] | None = None,
                  lead_ins: Mapping[str, pd.DataFrame] | None = None, adapt=None) -> dict:
    """Stream ``campaigns`` through ``deployed`` (see module doc); ``files`` (campaign -> file)
    only name the file of a refused row.  A campaign with a ``lead_ins`` entry continues the
    campaigns in it: both streams are warmed on it and the batch prediction is that of the
    campaign joined to it, as ``run`` scores it (like with like).

    Returns
    -------
    dict
        ``targets`` (per target: ``n_samples``; ``max_abs_stream_minus_batch``, the
        largest |plain stream − batch| over the complete rows, envelope off;
        ``rmse``, of the residual the deployed correction leaves (missing
        measurements skipped); ``rmse_batch``, the batch prediction's over every row,
        missing input cells interpolated (:func:`gaps_interpolated`); ``us_per_sample``;
        ``clamped_samples``; ``max_abs_correction`` and ``all_finite`` of the deployed
        stream; ``guarded_samples``, the samples whose correction the guard bounded,
        rate-limited or held (None without a guard);
        ``streamed_range`` [min, max] of it;
        ``bound``, the guard's [lo, hi] or null), ``excluded_inputs`` (sensors excluded
        at the end of any campaign, sorted) and ``events`` (every event with its
        ``campaign``), plus :func:`summary`'s ``adaptive`` and ``pod``, and for the adaptive
        compensator ``alarms`` (:func:`alarm_rate`).  With ``adapt``
        (an :class:`~.adapt.Adaptation`; the campaigns in their order, what is learned carried
        from one to the next) the deployed correction is the adapted one (``rmse``,
        ``max_abs_correction``, ...) and each target gets ``adapt``: ``rmse_frozen`` (the same
        stream unadapted), ``method``, ``gain``, ``bias_um`` (at the end), ``n_references``.
    """
    stream = plain(deployed)
    comp = stream.compensator
    lead_ins = lead_ins or {}
    measured = comp.measured(campaigns)
    targets = list(deployed.targets_)
    diffs, residuals, batch_residuals, outputs, frozen = [], [], [], [], []
    events, excluded, lead_events = [], set(), []
    clamps, seconds, n, hours = 0, 0.0, 0, 0.0
    guarded_each = []       # per campaign: rows per target the guard changed (None: no guard)
    from ...base.progress import bar

    rows = bar(total=sum(len(df) for df in campaigns.values()), desc="replay", unit="row")
    for cid, df in campaigns.items():
        m = measured[cid][targets].to_numpy(float)
        k, batch = complete_rows(df, stream.columns_), np.empty((0, len(targets)))
        lead = lead_ins.get(cid)
        if k:
            head = df.iloc[:k]
            batch = batch_prediction(comp, head, lead)[targets].to_numpy()
            with stream.envelope_off():   # the same inputs as batch: any difference is the stream's
                free = stream_rows(stream, head, cid, lead_in=lead).y
            diffs.append(np.abs(free - batch))
        if k < len(df):     # every row, gaps filled as run fills them: like with like (deploy88)
            batch = batch_prediction(comp, gaps_interpolated(df, stream.columns_), lead)[targets].to_numpy()
        batch_residuals.append(m - batch)
        run = stream_rows(deployed, df, cid, (files or {}).get(cid), lead_ins.get(cid))
        if adapt is not None:
            frozen.append(m - run.y)
            run.y = adapt.correct_recorded(run.y, df, m)
        residuals.append(m - run.y)
        outputs.append(run.y)
        events += run.events
        lead_events += run.warm_events
        excluded.update(run.excluded)
        clamps += int((run.clamped > 0).sum())
        guarded_each.append(run.guarded)
        seconds += run.seconds
        n += len(df)
        hours += streamed_hours(df, getattr(deployed, "period_s", 1.0))
        rows.update(len(df))
    rows.close()
    k_targets = len(targets)
    diff = np.concatenate(diffs) if diffs else np.empty((0, k_targets))
    resid = np.concatenate(residuals) if residuals else np.empty((0, k_targets))
    bres = np.concatenate(batch_residuals) if batch_residuals else np.empty((0, k_targets))
    out = np.concatenate(outputs) if outputs else np.empty((0, k_targets))
    guard = deployed.guard if isinstance(deployed, AdaptiveCompensator) else None
    guarded = summed(guarded_each, targets)
    us = 1e6 * seconds / max(n, 1)

    rms = finite_rms
    report = {t: {"n_samples": int(n),
                  "max_abs_stream_minus_batch": float(np.max(diff[:, j])) if len(diff) else 0.0,
                  RMSE: rms(resid[:, j]),
                  "us_per_sample": us,
                  "rmse_batch": rms(bres[:, j]),
                  "clamped_samples": clamps,
                  "guarded_samples": None if guard is None else guarded[t],
                  "max_abs_correction": float(np.max(np.abs(out[:, j]))) if n else 0.0,
                  "all_finite": bool(np.all(np.isfinite(out[:, j]))),
                  "streamed_range": [float(np.min(out[:, j])), float(np.max(out[:, j]))] if n else None,
                  "bound": None if guard is None else [float(guard.lo[j]), float(guard.hi[j])]}
              for j, t in enumerate(targets)}
    for j, t in enumerate(targets):     # a target measured now and then: scored where measured
        measured = int(np.count_nonzero(np.isfinite(resid[:, j])))
        if measured < n:
            report[t]["measured_rows"] = measured
    if adapt is not None:
        for t, figures in adapt_figures(adapt, frozen, targets).items():
            report[t]["adapt"] = figures
    result = {"targets": report, "excluded_inputs": sorted(excluded), "events": events,
              **summary(deployed)}
    if result["adaptive"]:
        result["alarms"] = alarm_rate(events, hours)
    if lead_events:
        result["lead_in_events"] = lead_events
    return result


def adapt_line(targets: Mapping, what: str, key: str) -> list[str]:
    """``adapt (<method>, <n> references): RMSE <what> <target> <frozen> -> <adapted>, ...``
    (``key``: the adapted RMSE's key), or nothing when no target was adapted."""
    adapted = [(t, r) for t, r in targets.items() if "adapt" in r]
    if not adapted:
        return []
    a = adapted[0][1]["adapt"]
    return [f"adapt ({a['method']}, {a['n_references']} references): RMSE {what} "
            + ", ".join(f"{t} {r['adapt']['rmse_frozen']:.3f} -> {r[key]:.3f}"
                        for t, r in adapted if r[key] is not None
                        and r["adapt"]["rmse_frozen"] is not None)]


def guarded_line(guarded: Mapping[str, int | None], n: int, figures: str) -> list[str]:
    """The line saying, per target, how many of the ``n`` streamed samples had their correction
    changed by the guard (``guarded``: :func:`~.guard.guard_changes` summed over the campaigns;
    None without a guard), and which figures are the guarded stream's (``figures``); none
    where it changed no row.  One wording for replay, monitor and promote (depl70, guard70)."""
    shown = {t: k for t, k in guarded.items() if k}
    if not shown:
        return []
    return ["guarded: " + ", ".join(f"{t} {k}" for t, k in shown.items())
            + f" of {n} samples had the correction bounded or rate-limited by the guard "
            f"(monitor.guard); {figures}"]


def clamped_line(clamped: int, n: int, policy: str, figures: str) -> list[str]:
    """The line saying how many of the ``n`` streamed samples had an input clamped to the
    training envelope (``policy``: promote.envelope.policy) and which figures are the clamped
    stream's (``figures``); none where none was.  One wording for replay and promote."""
    if not clamped:
        return []
    return [f"clamped: {clamped} of {n} samples had an input outside the training envelope "
            f"(promote.envelope.policy={policy}); {figures}"]


def first_exclusion(events: list[dict]) -> str:
    """``, first: <sensor> (<campaign>, <h> h)``: the first sensor excluded and when (hours
    from its campaign's start), or nothing; the end of the events line `replay` and `monitor`
    print."""
    excluded = [e for e in events if e.get("sensor") and e["to"] == "excluded"]
    if not excluded:
        return ""
    e = excluded[0]
    return f", first: {e['sensor']} ({e['campaign']}, {e['time'] / 3600:.2f} h)"


def new_states(events: list[dict]) -> str:
    """``; new thermal state: <n> (first <campaign>, <h> h: <sensors>)`` (the monitor's
    :data:`~.surveillance.NEW_STATE` events), or nothing; the end of the events line."""
    novel = [e for e in events if e.get("to") == NEW_STATE]
    if not novel:
        return ""
    e = novel[0]
    return (f"; new thermal state: {len(novel)} (first {e['campaign']}, {e['time'] / 3600:.2f} h: "
            f"{', '.join(e.get('sensors') or []) or '-'} out of band together, not excluded)")


def replay_json(deployed, result: dict, *, name: str, source: str, test_ids: list[str],
                missing: dict | None = None) -> dict:
    """``replay.json`` (CLI.md) of :func:`replay_report`'s ``result``."""
    stream = plain(deployed)
    report = {"model": name, "source": source, "targets": result["targets"],
              "excluded_inputs": result["excluded_inputs"], "events": result["events"],
              "adaptive": result["adaptive"], "pod": result["pod"],
              **({"alarms": result["alarms"]} if "alarms" in result else {}),
              "columns": list(deployed.columns_), "time_required": deployed.time_required_,
              "envelope": {"policy": stream.policy,
                           "margin": stream.envelope.margin if stream.envelope else None},
              "test_campaigns": test_ids}
    if missing:
        report["missing"] = missing     # missing cells per test campaign and column, streamed as NaN
    if result.get("lead_in_events"):
        report["lead_in_events"] = result["lead_in_events"]
    return report


def with_cold_start(report: dict, cold: dict, continuing: list[str]) -> dict:
    """``report`` (``replay.json``) with per target ``rmse_cold_start``, the deployed RMSE of
    ``cold`` (:func:`replay_report` of the same campaigns without lead-ins: each streamed from a
    reset at its first row, as a compensator restarted there), and ``cold_start_campaigns``, the
    test campaigns that continue others (``continuing``; none: the two figures are one).  The
    default figures stay the continued stream's: what ``run`` scores (deploy87)."""
    for t, r in report["targets"].items():
        r["rmse_cold_start"] = cold["targets"][t][RMSE]
    report["cold_start_campaigns"] = list(continuing)
    return report


def cold_start_line(report: dict) -> list[str]:
    """``cold start (...): RMSE <target> <cold> against <continued> continued, ...``, or nothing
    without ``replay.cold_start``."""
    if "cold_start_campaigns" not in report:
        return []
    return cold_line(report["cold_start_campaigns"],
                     [(t, r.get("rmse_cold_start"), r.get(RMSE)) for t, r in report["targets"].items()])


def cold_line(continuing: list[str], figures: list[tuple]) -> list[str]:
    """The line saying what a cold start costs: ``figures`` ``(name, cold, continued)`` RMSEs
    of the test campaigns ``continuing`` others (the stream warmed on them) and of each from a
    reset at its first row.  One wording for ``replay`` and ``promote`` (deploy87, deploy88)."""
    chains = ", ".join(continuing) or "none continues another"
    return [f"cold start (each test campaign from a reset at its first row; {chains}): RMSE "
            + ", ".join(f"{name} {cold:.3f} against {warm:.3f} continued"
                        for name, cold, warm in figures if cold is not None and warm is not None)]


def replay_lines(report: dict) -> list[str]:
    """The table and lines ``thermocomp replay`` prints.  RMSE batch: the fitted model's own
    prediction of the same rows (what ``run`` scores), so a deployment that streams
    differently (the adaptive monitor's exclusions) shows beside it."""
    targets = report["targets"]
    w = name_width(targets)
    lines = [f"{'target':<{w}} {'samples':>8} {'max|stream-batch|':>18} {'RMSE':>8} "
             f"{'RMSE batch':>11} {'µs/sample':>10}"]
    for t, r in targets.items():
        rmse, batch = ("-" if r.get(k) is None else f"{r[k]:.3f}" for k in (RMSE, "rmse_batch"))
        lines.append(f"{t:<{w}} {r['n_samples']:>8} {r['max_abs_stream_minus_batch']:>18.3g} "
                     f"{rmse:>8} {batch:>11} {r['us_per_sample']:>10.1f}")
    lines += adapt_line(targets, "frozen -> adapted", RMSE)
    lines += cold_start_line(report)
    clamped = max((r.get("clamped_samples") or 0 for r in targets.values()), default=0)
    if clamped:     # why RMSE leaves RMSE batch where no sensor was excluded
        lines += clamped_line(clamped, next(iter(targets.values()))["n_samples"],
                              (report.get("envelope") or {}).get("policy", "clamp"),
                              "RMSE is the clamped stream's, RMSE batch the model's own")
    # why RMSE leaves RMSE batch where no input was clamped (depl70)
    lines += guarded_line({t: r.get("guarded_samples") for t, r in targets.items()},
                          next(iter(targets.values()), {}).get("n_samples", 0),
                          "RMSE is the guarded stream's, RMSE batch the model's own")
    if report["adaptive"]:
        lines.append(f"events: {len(report['events'])}, excluded at a campaign's end: "
                     f"{', '.join(report['excluded_inputs']) or 'none'}"
                     + first_exclusion(report["events"]) + new_states(report["events"]))
    return lines + lead_in_line(report.get("lead_in_events") or [])


def lead_in_line(events: list[dict], unmonitored: str = "RMSE batch (run's)") -> list[str]:
    """The line saying the sensor monitor acted while the stream was warmed on the campaigns a
    test campaign continues (``replay.json``'s ``lead_in_events``): the test campaign starts
    from the state that left, where the figure named ``unmonitored`` (replay's and promote's
    RMSE batch, run's; monitor's RMSE fixed) streamed them unmonitored (deploy88, deploy89)."""
    if not events:
        return []
    e = events[0]
    return [f"warm-up: {len(events)} events of the sensor monitor on the campaigns the test "
            f"campaigns continue (first: {e.get('sensor') or '-'} {e.get('to', '')}, "
            f"{-e['time'] / 3600:.2f} h before {e['campaign']}); the test campaign starts from the "
            f"state they left, {unmonitored} saw them unmonitored"]
