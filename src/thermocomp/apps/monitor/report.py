"""The monitor report: campaigns streamed through the fixed and the adaptive compensator
(pure core: fitted compensators and frames in, the ``monitor.json`` dict out).

:func:`monitor_report` is what ``thermocomp monitor`` writes; :func:`summary_lines`
what it prints.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ...base.tables import name_width
from ...core.context import TIME
from ...core.guarded import summed
from ...core.metrics import unit
from ..deploy.adapt import Adaptation, adapt_figures
from ..deploy.adaptive import AdaptiveCompensator
from ..deploy.guard import guard_changes
from ..deploy.report import (
    adapt_line,
    alarm_rate,
    campaign_start,
    first_exclusion,
    guarded_line,
    lead_in_line,
    new_states,
    streamed_hours,
)
from ..deploy.streaming import on_campaign_clock, warm, warm_events
from ..deploy.surveillance import STATES
from .blind import undetected_offset_um
from .placement import covariance_sensors, qr_sensors


def stream_campaign(model, df: pd.DataFrame, lead_in: pd.DataFrame | None = None,
                    clamped: list | None = None, guarded: list | None = None,
                    warmed_events: list | None = None
                    ) -> tuple[np.ndarray, list[dict], tuple[list, list]]:
    """Stream one campaign from its start (a reset, or warmed on ``lead_in``, the campaigns it
    continues: :func:`~thermocomp.apps.deploy.streaming.warm`); a step of the fixed compensator
    that refuses its row holds the previous correction (the adaptive one gives one for every
    row: a failure there is a defect, raised, not a held correction whose row re-reported the
    previous row's events; their times from the campaign's first row on the stream's
    clock, :mod:`~thermocomp.core.timerule`).  ``clamped``: a list given gets each
    row's count of inputs clamped to the training envelope; ``guarded``: a list given gets, of a
    model with a correction guard, the campaign's rows per target whose correction it changed
    (:func:`~thermocomp.apps.deploy.guard.guard_changes`, the lead-in's not); ``warmed_events``:
    a list given gets the sensor monitor's events while the stream was warmed on ``lead_in``
    (:func:`~thermocomp.apps.deploy.streaming.warm_events`, their times from the campaign's first
    row: negative), as ``replay`` reports them (deploy89)."""
    X = df[model.columns_].to_numpy(float)
    t = df[TIME].to_numpy(float) if TIME in df.columns else np.arange(len(df), dtype=float)
    y = np.zeros((len(X), len(model.targets_)))
    events, states, errors = [], [], []
    warm(model, lead_in, df)
    warmed = guard_changes(model)
    # what the monitor did on the lead-in leaves the state the campaign starts from (deploy88)
    lead = warm_events(model, lead_in)
    t0 = 0.0
    for i in range(len(X)):
        n = 0
        try:
            y[i], n = model._step(X[i], t[i])
            if not i and isinstance(model, AdaptiveCompensator):
                t0 = model.clock_time_
                if warmed_events is not None:
                    warmed_events += on_campaign_clock(lead, t0)
        except ValueError:                   # the fixed compensator on a missing value
            if isinstance(model, AdaptiveCompensator):
                raise
            y[i] = y[i - 1] if i else np.nan
        if clamped is not None:
            clamped.append(n)
        mon = getattr(model, "monitor", None)
        if mon is not None:
            events += [{**e, "time": e["time"] - t0} for e in model.last_events_]
            states.append(mon.states)
            errors.append(mon.last_error_)
    if guarded is not None and warmed is not None:
        guarded.append(guard_changes(model) - warmed)
    model.reset()
    return y, events, (states, errors)


def _rmse(r: np.ndarray | None, k: int) -> float | None:
    """None: nothing to score (no errors, or no finite residual at all)."""
    if r is None or not np.isfinite(r[:, k]).any():
        return None
    return float(np.sqrt(np.nanmean(r[:, k] ** 2)))


def _stream_all(adaptive, fixed, comp, streamed: dict, leads: dict,
                adapt: Adaptation | None = None) -> dict:
    """Each campaign streamed through both compensators: events, state counts, traces; with
    ``adapt`` the adaptive correction learns from the reference measurements."""
    names = adaptive.monitor.names
    out = {"counts": np.zeros((len(names), len(STATES)), dtype=np.int64), "first_alarm": {},
           "events": [], "traces": {}, "res_f": [], "res_a": [], "res_frozen": [], "corr": [],
           "hours": 0.0, "clamped": 0, "samples": 0, "guarded": [], "lead_in_events": []}
    measured = comp.measured(streamed) if any(t in df.columns for df in streamed.values()
                                              for t in comp.targets_) else None
    for cid, df in streamed.items():
        clamped: list[int] = []
        y_fix, _, _ = stream_campaign(fixed, df, leads.get(cid), clamped)
        out["clamped"] += int(np.count_nonzero(clamped))
        out["samples"] += len(df)
        warmed: list[dict] = []
        y_ad, ev, (states, errors) = stream_campaign(adaptive, df, leads.get(cid),
                                                     guarded=out["guarded"], warmed_events=warmed)
        out["lead_in_events"] += [{"campaign": cid, **e} for e in warmed]
        start = campaign_start(df, adaptive.period_s)   # CLI.md: times in s from the campaign start
        t = (df[TIME].to_numpy(float) if TIME in df.columns else np.arange(len(df), dtype=float)) - start
        m = None if measured is None else measured[cid][adaptive.targets_].to_numpy()
        if adapt is not None:           # the deployed correction learns from the references
            if m is not None:
                out["res_frozen"].append(m - y_ad)
            adapt.start()
            y_ad = adapt.correct(y_ad, t, m)
        for e in ev:
            e = {"campaign": cid, **e}
            out["events"].append(e)
            if (e.get("sensor") in names and e["to"] in ("alarm", "excluded")
                    and e["sensor"] not in out["first_alarm"]):
                out["first_alarm"][e["sensor"]] = {"campaign": cid, "time": e["time"]}
        out["hours"] += streamed_hours(df, adaptive.period_s)
        S = np.asarray(states)
        for k in range(len(STATES)):
            out["counts"][:, k] += (S == k).sum(axis=0)
        out["traces"][cid] = {"time": t, "states": S, "errors": np.asarray(errors),
                              "fixed": y_fix, "adaptive": y_ad, "measured": m}
        out["corr"].append(y_ad)
        if m is not None:
            out["res_f"].append(m - y_fix)
            out["res_a"].append(m - y_ad)
    return out


def _targets(adaptive, run: dict) -> dict:
    C = np.vstack(run["corr"])
    guarded = summed(run["guarded"], adaptive.targets_)
    rf = np.vstack(run["res_f"]) if run["res_f"] else None
    ra = np.vstack(run["res_a"]) if run["res_a"] else None
    return {t: {"rmse_fixed": _rmse(rf, k), "rmse_adaptive": _rmse(ra, k),
                "max_abs_correction": float(np.max(np.abs(C[:, k]))) if len(C) else 0.0,
                "all_finite": bool(np.all(np.isfinite(C[:, k]))),
                "bound": [float(adaptive.guard.lo[k]), float(adaptive.guard.hi[k])],
                "clamped_samples": run["clamped"], "n_samples": run["samples"],
                "guarded_samples": None if guarded is None else guarded[t]}
            for k, t in enumerate(adaptive.targets_)}


def _pod(mon, placement: str) -> dict:
    names, pod = mon.names, mon.pod
    rank = qr_sensors(pod.phi_) if pod.n_modes_ <= len(names) else np.arange(len(names))
    cov = covariance_sensors(pod.phi_, pod.singular_values_, 1, None)
    return {"n_sensors": len(names), "n_modes": int(pod.n_modes_),
            "n_modes_energy": int(pod.n_modes_energy_),
            "captured_energy": float(pod.energy_[pod.n_modes_ - 1]),
            "train_self_prediction_c": float(pod.train_band_c_),
            "sensor_rank_qr": [names[i] for i in rank],
            "sensor_rank_covariance": [names[i] for i in cov],
            "placement": placement,
            "sensor_rank": [names[i] for i in (rank if placement == "qr" else cov)]}


def monitor_report(adaptive: AdaptiveCompensator, fixed, comp, streamed: dict, train: dict,
                   placement: str = "qr", leads: dict | None = None,
                   adapt: Adaptation | None = None) -> tuple[dict, dict]:
    """(the ``monitor.json`` report, per-campaign traces for the figures).

    ``streamed`` campaigns go through ``fixed`` and ``adaptive`` from their start
    (warmed on ``leads``); ``train`` prices an offset the exclusion band cannot see;
    ``adapt`` (:mod:`~thermocomp.apps.deploy.adapt`) adapts the adaptive correction to the
    reference measurements, each target's ``adapt`` giving the RMSE without it.
    """
    mon = adaptive.monitor
    run = _stream_all(adaptive, fixed, comp, streamed, leads or {}, adapt)
    sensors = {n: {"state_counts": dict(zip(STATES, map(int, run["counts"][j]))),
                   "first_alarm": run["first_alarm"].get(n),
                   "observable": bool(mon._observable[j]) if n not in mon.excluded else None}
               for j, n in enumerate(mon.names)}
    band = mon.warning_c if mon.exclude_at == "warning" else mon.alarm_c
    cost = undetected_offset_um(comp, train, dict(zip(mon.names, band.tolist())))
    for j, name in enumerate(mon.names):
        sensors[name]["undetected_offset_c"] = float(band[j])
        sensors[name]["undetected_offset_um"] = cost[name]
    report = {"sensors": sensors, "events": run["events"], "targets": _targets(adaptive, run),
              "pod": _pod(mon, placement),
              "bands": {"warning_c": mon.warning_c.tolist(), "alarm_c": mon.alarm_c.tolist(),
                        # (mon87) the bound within which a crossing may be the readings' rounding
                        "rounding_c": mon.rounding_c.tolist()},
              "alarms": alarm_rate(run["events"], run["hours"]),
              "campaigns": list(streamed)}
    if run["lead_in_events"]:           # (deploy89) as replay.json's, present when there is any
        report["lead_in_events"] = run["lead_in_events"]
    if adapt is not None:
        for t, figures in adapt_figures(adapt, run["res_frozen"], adaptive.targets_).items():
            report["targets"][t]["adapt"] = figures
    return report, run["traces"]


def summary_lines(report: dict) -> list[str]:
    """The table and lines ``thermocomp monitor`` prints."""
    w = name_width(report["targets"])
    lines = [f"{'target':<{w}} {'RMSE fixed':>11} {'RMSE adaptive':>14} {'max|corr|':>10} {'finite':>7}"]
    for t, r in report["targets"].items():
        f = "-" if r["rmse_fixed"] is None else f"{r['rmse_fixed']:.3f}"
        a = "-" if r["rmse_adaptive"] is None else f"{r['rmse_adaptive']:.3f}"
        lines.append(f"{t:<{w}} {f:>11} {a:>14} {r['max_abs_correction']:>10.3g} "
                     f"{str(r['all_finite']):>7}")
    first = next(iter(report["targets"].values()), {})
    if first.get("clamped_samples"):     # why RMSE fixed leaves what `run` scored
        lines.append(f"clamped: {first['clamped_samples']} of {first['n_samples']} samples had an "
                     "input outside the training envelope (promote.envelope.policy); both RMSEs "
                     "are the clamped streams'")
    lines += guarded_line({t: r.get("guarded_samples") for t, r in report["targets"].items()},
                          first.get("n_samples", 0), "RMSE adaptive is the guarded stream's")
    lines += _offset_lines(report["sensors"])
    lines += adapt_line(report["targets"], "adaptive without -> with", "rmse_adaptive")
    excl = [e for e in report["events"] if e["to"] == "excluded"]
    rate = (report.get("alarms") or {}).get("exclusions_per_100h")   # none in older reports
    lines.append(f"events: {len(report['events'])}, exclusions: {len(excl)}"
                 + ("" if rate is None else f" ({rate:.3g} per 100 h)")
                 + first_exclusion(report["events"]) + new_states(report["events"]))
    return lines + lead_in_line(report.get("lead_in_events") or [], "RMSE fixed")


def _offset_lines(sensors: dict) -> list[str]:
    """What an offset the monitor cannot see costs: the worst sensor whose band bounds it (the
    others predict it), and apart, per °C, those no other sensor predicts: no band bounds their
    drift (only their range, jump and freeze detectors judge them), so a band-sized figure would
    read as a bound it is not (a lathe's spindle motor: '60.5 °C inside the band')."""
    costs = {n: r for n, r in sensors.items()
             if any(v is not None for v in r.get("undetected_offset_um", {}).values())}

    def worst(r):
        return max(((v, t) for t, v in r["undetected_offset_um"].items() if v is not None))

    bounded = {n: r for n, r in costs.items() if r.get("observable") is not False}
    blind = {n: r for n, r in costs.items() if r.get("observable") is False}
    lines = []
    if bounded:
        name = max(bounded, key=lambda n: worst(bounded[n]))
        um, target = worst(bounded[name])
        lines.append(f"an offset inside the exclusion band costs up to {um:.3g} {unit(target)} "
                     f"({name} "
                     f"{bounded[name]['undetected_offset_c']:g} °C, {target}; per sensor in "
                     "monitor.json)")
    if blind:
        per_c = {n: (worst(r)[0] / r["undetected_offset_c"], worst(r)[1])
                 for n, r in blind.items() if r["undetected_offset_c"] > 0}
        slopes = ", ".join(f"{n} {v:.3g} {unit(t)}/°C" for n, (v, t) in sorted(
            per_c.items(), key=lambda kv: -kv[1][0]))   # (iso67: a tilt's in µm/m)
        lines.append(f"no other sensor predicts {', '.join(blind)}: no band bounds a drift of "
                     f"theirs (their range, jump and freeze detectors judge them){'; ' if slopes else ''}"
                     f"{slopes}")
    return lines
