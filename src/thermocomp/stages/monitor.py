"""`thermocomp monitor`: sensor surveillance and the fault-tolerant compensator, streamed.

The compensator is fitted on the train split of ``data.path`` (or loaded:
``monitor.model=<model.pkl>``), made deployable as ``promote`` does, and wrapped
in an :class:`~thermocomp.deploy.AdaptiveCompensator` whose POD, detector
limits and correction guard are fitted on the same train split.  Each test
campaign (or the CSV rows of stdin, ``monitor.input=-``) is streamed twice from
its start -- a reset, or, for a campaign that continues others
(``data.reference=none``), warmed on them unscored -- through the fixed
compensator and the adaptive one.  Test campaigns
are read as recorded (missing cells stay NaN, counted in ``missing``); train
campaigns must be complete, or repaired within the ``data`` limits.  Writes
``<out>/monitor.json`` (CLI.md) and figures in ``<out>/monitor/``.
"""

from __future__ import annotations

import sys
from io import StringIO
from pathlib import Path

import numpy as np
import pandas as pd
from omegaconf import DictConfig

from .. import io
from ..context import TIME
from ..deploy import StreamingCompensator
from ..deploy.report import campaign_start
from ..deploy.streaming import warm
from ..errors import ConfigError
from ..files import staged_outputs, write_json
from ..io.sniff import SNIFF_LINES, detected
from ..monitor import (
    STATES,
    AdaptiveCompensator,
    covariance_sensors,
    qr_sensors,
    undetected_offset_um,
)
from ..paths import resolve
from ..tracking import stage_run
from .common import (
    build_adaptive,
    build_compensator,
    check_config,
    check_streamed_columns,
    check_volumetric_targets,
    data_options,
    deploy_stream,
    lead_ins,
    load_model,
    read_streamed,
    say,
    warn_stream_mode,
)


def _stdin_campaign(columns: list[str], opts: io.ReadOptions) -> tuple[dict, dict]:
    """``({"stdin": frame}, missing cells)`` from CSV rows on stdin (header first), read as a
    campaign file is (``data.delimiter``, ``data.decimal``, ``data.columns``: a lab's logger
    rows stream as they are written); empty cells stay NaN, a non-numeric one is refused with
    its row.  ``time`` in seconds or as ISO 8601 timestamps (``data.time``; ``auto``: as the
    first row reads, like a campaign file)."""
    text = sys.stdin.read().lstrip("\ufeff")
    opts = detected(text.splitlines()[:SNIFF_LINES], opts, "<stdin>")   # data.delimiter=auto ...
    try:
        df = pd.read_csv(StringIO(text), sep=opts.delimiter, decimal=opts.decimal,
                         thousands=opts.thousands)
    except Exception as exc:    # pandas raises several kinds for a bad stream
        raise io.ContractError(f"stdin is not a CSV table with a header, data.delimiter="
                               f"{opts.delimiter!r} ({' '.join(str(exc).split())})",
                               file="<stdin>") from None
    df = df.rename(columns={k: v for k, v in opts.columns.items() if k in df.columns})
    time_format = opts.time
    absent = [c for c in columns if c not in df.columns]
    if not absent and df.empty:
        raise io.ContractError("stdin has a header but no data row", file="<stdin>")
    if absent:
        raise io.ContractError("stdin lacks a column the compensator reads", file="<stdin>",
                               column=",".join(absent))
    if TIME in df.columns:
        df[TIME] = _stdin_seconds(df[TIME], time_format)
    # every data column is numeric (the contract's T_, E_, S_ and time), not only those the
    # model reads: the measured errors and the context are read from the same frame
    numeric = list(dict.fromkeys([*columns, *(c for c in df.columns
                                              if c == TIME or str(c)[:2] in ("T_", "E_", "S_"))]))
    for c in numeric:
        bad = pd.to_numeric(df[c], errors="coerce").isna() & df[c].notna()
        if bad.any():
            raise io.ContractError("non-numeric value", file="<stdin>", column=c,
                                   row=int(np.flatnonzero(bad)[0]) + 1)
        df[c] = pd.to_numeric(df[c], errors="coerce")
    counts = {c: int(n) for c, n in df[numeric].isna().sum().items() if n}
    return {"stdin": df}, ({"stdin": counts} if counts else {})


def _stdin_seconds(time: pd.Series, time_format: str) -> pd.Series:
    """The stream's ``time`` in seconds since its first row when it holds ISO 8601 timestamps
    (as given otherwise: the numeric check refuses what is no number).  A time that goes back
    is no refusal here: the stream's guard judges it, as on the machine."""
    first = time.iloc[0]
    iso = time_format == "iso8601" or (time_format == "auto" and isinstance(first, str)
                                       and pd.isna(pd.to_numeric(first, errors="coerce")))
    if not iso:
        return time
    stamps = pd.to_datetime(time.astype(str).where(time.notna()), format="ISO8601", utc=True,
                            errors="coerce")
    bad = stamps.isna() & time.notna()
    if bad.any() or pd.isna(stamps.iloc[0]):
        row = int(np.flatnonzero(bad)[0]) + 1 if bad.any() else 1
        raise io.ContractError(f"not an ISO 8601 time (data.time={time_format}: the stream's first "
                               "row is a timestamp)", file="<stdin>", column=TIME, row=row)
    return (stamps - stamps.iloc[0]).dt.total_seconds()


def _stream(model, df: pd.DataFrame, lead_in: pd.DataFrame | None = None
            ) -> tuple[np.ndarray, list[dict], list[np.ndarray]]:
    """Stream one campaign from its start (a reset, or warmed on ``lead_in``, the campaigns it
    continues: :func:`~thermocomp.deploy.streaming.warm`); a step of the fixed compensator
    that refuses its row holds the previous correction (the adaptive one gives one for every
    row: a failure there is a defect, raised, not a held correction whose row re-reported the
    previous row's events)."""
    X = df[model.columns_].to_numpy(float)
    t = df[TIME].to_numpy(float) if TIME in df.columns else np.arange(len(df), dtype=float)
    y = np.zeros((len(X), len(model.targets_)))
    events, states, errors = [], [], []
    warm(model, lead_in)
    for i in range(len(X)):
        try:
            y[i] = model._step(X[i], t[i])[0]
        except ValueError:                   # the fixed compensator on a missing value
            if isinstance(model, AdaptiveCompensator):
                raise
            y[i] = y[i - 1] if i else np.nan
        mon = getattr(model, "monitor", None)
        if mon is not None:
            events += model.last_events_
            states.append(mon.states)
            errors.append(mon.last_error_)
    model.reset()
    return y, events, (states, errors)


def monitor(cfg: DictConfig) -> dict:
    """Stream the test campaigns (or stdin) through the fixed and the adaptive compensator."""
    check_config(cfg, inputs=("monitor.model",))
    warn_stream_mode(cfg, "monitor")
    model = cfg.monitor.get("model")
    if model is not None and (not str(model).strip() or str(model).startswith("models:/")):
        raise ConfigError(f"monitor.model={model}: a model.pkl file (run's or train's); a "
                          "registered model replays through replay.model=models:/<name>@<alias>")
    stdin = cfg.monitor.get("input") == "-"
    ds, train_ids, test_ids, missing = read_streamed(cfg, test=not stdin)
    streamed = {c: ds.campaigns[c] for c in test_ids}
    train = {c: ds.campaigns[c] for c in train_ids}
    with stage_run(cfg, "monitor") as tr:
        path = cfg.monitor.get("model")
        comp = build_compensator(cfg, ds=ds).fit(train) if path is None else load_model(resolve(str(path)))
        check_volumetric_targets(cfg, ds, comp.targets_, f"monitor.model={path}")
        # one plain stream serves both: the fixed run and the adaptive one are each streamed
        # from a reset, one after the other
        fixed = deploy_stream(cfg, comp, train)
        adaptive = build_adaptive(cfg, fixed, train)
        if adaptive.monitor is None:
            raise ConfigError("monitor needs at least 3 temperature inputs (T_ columns) in the "
                              f"model, got {[c for c in adaptive.columns_ if c.startswith('T_')]}")
        if stdin:
            streamed, missing = _stdin_campaign(adaptive.columns_,
                                                io.ReadOptions.from_cfg(data_options(cfg)))
        else:
            check_streamed_columns(ds, list(streamed), adaptive.columns_, "the model")
        say(f"streaming {len(streamed)} campaign(s) through the fixed and the adaptive compensator")
        leads = {} if stdin else lead_ins(comp, ds, list(streamed))
        report, traces = _report(adaptive, fixed, comp, streamed, str(cfg.monitor.pod.placement),
                                 leads)
        mon = adaptive.monitor
        band = mon.warning_c if mon.exclude_at == "warning" else mon.alarm_c
        cost = undetected_offset_um(comp, train, dict(zip(mon.names, band.tolist())))
        for j, name in enumerate(mon.names):
            report["sensors"][name]["undetected_offset_c"] = float(band[j])
            report["sensors"][name]["undetected_offset_um"] = cost[name]
        if missing:
            report["missing"] = missing
        out = Path(resolve(cfg.out))
        with staged_outputs(out, last=("monitor.json",)) as stage:
            if cfg.plots != "none":
                from ..monitor.figures import draw
                draw(stage / "monitor", adaptive, traces, report, cfg.monitor.get("map_time_h"))
            write_json(stage / "monitor.json", report)
        tr.log_metrics({"monitor": report["targets"]})
        tr.log_artifact(out / "monitor.json")
    _print(report)
    say(f"monitor: {out / 'monitor.json'}")
    return report


def _report(adaptive: AdaptiveCompensator, fixed: StreamingCompensator, comp, streamed,
            placement: str = "qr", leads: dict | None = None) -> tuple[dict, dict]:
    mon = adaptive.monitor
    names = mon.names
    counts = np.zeros((len(names), len(STATES)), dtype=np.int64)
    first_alarm: dict = {}
    events, traces = [], {}
    measured = comp.measured(streamed) if any(t in df.columns for df in streamed.values()
                                              for t in comp.targets_) else None
    res_f, res_a, corr = [], [], []
    for cid, df in streamed.items():
        lead = (leads or {}).get(cid)
        y_fix, _, _ = _stream(fixed, df, lead)
        y_ad, ev, (states, errors) = _stream(adaptive, df, lead)
        start = campaign_start(df)      # CLI.md: event times in seconds from the campaign start
        t = (df[TIME].to_numpy(float) if TIME in df.columns else np.arange(len(df), dtype=float)) - start
        for e in ev:
            e = {"campaign": cid, **e, "time": e["time"] - start}
            events.append(e)
            if (e.get("sensor") in names and e["to"] in ("alarm", "excluded")
                    and e["sensor"] not in first_alarm):
                first_alarm[e["sensor"]] = {"campaign": cid, "time": e["time"]}
        S = np.asarray(states)
        for k in range(len(STATES)):
            counts[:, k] += (S == k).sum(axis=0)
        traces[cid] = {"time": t, "states": S, "errors": np.asarray(errors), "fixed": y_fix,
                       "adaptive": y_ad,
                       "measured": None if measured is None else measured[cid][adaptive.targets_].to_numpy()}
        corr.append(y_ad)
        if measured is not None:
            m = measured[cid][adaptive.targets_].to_numpy()
            res_f.append(m - y_fix)
            res_a.append(m - y_ad)
    C = np.vstack(corr)
    rf = np.vstack(res_f) if res_f else None
    ra = np.vstack(res_a) if res_a else None

    def rmse(r, k):     # None: nothing to score (no errors, or no finite residual at all)
        if r is None or not np.isfinite(r[:, k]).any():
            return None
        return float(np.sqrt(np.nanmean(r[:, k] ** 2)))

    pod = mon.pod
    rank = qr_sensors(pod.phi_) if pod.n_modes_ <= len(names) else np.arange(len(names))
    cov = covariance_sensors(pod.phi_, pod.singular_values_, 1, None)
    report = {
        "sensors": {n: {"state_counts": dict(zip(STATES, map(int, counts[j]))),
                        "first_alarm": first_alarm.get(n),
                        "observable": bool(mon._observable[j]) if n not in mon.excluded else None}
                    for j, n in enumerate(names)},
        "events": events,
        "targets": {t: {"rmse_fixed": rmse(rf, k), "rmse_adaptive": rmse(ra, k),
                        "max_abs_correction": float(np.max(np.abs(C[:, k]))) if len(C) else 0.0,
                        "all_finite": bool(np.all(np.isfinite(C[:, k]))),
                        "bound": [float(adaptive.guard.lo[k]), float(adaptive.guard.hi[k])]}
                    for k, t in enumerate(adaptive.targets_)},
        "pod": {"n_sensors": len(names), "n_modes": int(pod.n_modes_),
                "n_modes_energy": int(pod.n_modes_energy_),
                "captured_energy": float(pod.energy_[pod.n_modes_ - 1]),
                "train_self_prediction_c": float(pod.train_band_c_),
                "sensor_rank_qr": [names[i] for i in rank],
                "sensor_rank_covariance": [names[i] for i in cov],
                "placement": placement,
                "sensor_rank": [names[i] for i in (rank if placement == "qr" else cov)]},
        "bands": {"warning_c": mon.warning_c.tolist(), "alarm_c": mon.alarm_c.tolist()},
        "campaigns": list(streamed),
    }
    return report, traces


def _print(report: dict) -> None:
    print(f"{'target':<8} {'RMSE fixed':>11} {'RMSE adaptive':>14} {'max|corr|':>10} {'finite':>7}")
    for t, r in report["targets"].items():
        f = "-" if r["rmse_fixed"] is None else f"{r['rmse_fixed']:.3f}"
        a = "-" if r["rmse_adaptive"] is None else f"{r['rmse_adaptive']:.3f}"
        print(f"{t:<8} {f:>11} {a:>14} {r['max_abs_correction']:>10.3g} {str(r['all_finite']):>7}")
    costs = [(max(v for v in r["undetected_offset_um"].values() if v is not None), n, r)
             for n, r in report["sensors"].items()
             if any(v is not None for v in r.get("undetected_offset_um", {}).values())]
    if costs:
        worst, name, r = max(costs, key=lambda c: c[0])
        target = max((t for t, v in r["undetected_offset_um"].items() if v is not None),
                     key=r["undetected_offset_um"].get)
        print(f"an offset inside the exclusion band costs up to {worst:.3g} µm ({name} "
              f"{r['undetected_offset_c']:g} °C, {target}; per sensor in monitor.json)")
    excl = [e for e in report["events"] if e["to"] == "excluded"]
    print(f"events: {len(report['events'])}, exclusions: {len(excl)}"
          + (f", first: {excl[0]['sensor']} ({excl[0]['campaign']}, {excl[0]['time'] / 3600:.2f} h)"
             if excl else ""))
