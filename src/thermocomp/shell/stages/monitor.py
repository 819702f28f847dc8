"""`thermocomp monitor`: sensor surveillance and the fault-tolerant compensator, streamed.

The compensator is fitted on the train split of ``data.path`` (or loaded:
``monitor.model=<model.pkl>``), made deployable as ``promote`` does, and wrapped
in an :class:`~thermocomp.apps.deploy.AdaptiveCompensator` whose POD, detector
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

from ...apps.deploy import StreamingCompensator
from ...apps.deploy.adapt import from_config as adapt_from_config
from ...apps.monitor.report import monitor_report, summary_lines
from ...apps.monitor.report import stream_campaign as _stream  # noqa: F401  (tests stream through it)
from ...base.errors import ConfigError
from ...base.files import staged_outputs, write_json
from ...base.log import say
from ...base.paths import resolve
from ...core import io
from ...core.context import TIME
from ...core.continuation import carried_text, chain, lead_ins, preceding
from ...core.io.sniff import SNIFF_LINES, detected
from ...core.io.source import check_streamed_columns
from ..model_store import load_model
from ..source import check_volumetric_targets, read_streamed
from ..tracking import stage_run
from .builders import build_adaptive, build_compensator, deploy_stream, warn_stream_mode
from .common import check_config, data_options


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


def _stdin_lead_in(cfg: DictConfig, fixed: StreamingCompensator, ds, stream: pd.DataFrame) -> dict:
    """``{"stdin": lead-in}`` when ``monitor.continues`` names the campaign of ``data.path`` the
    stream continues: it is warmed on that campaign and those it continues, as ``replay`` warms
    a continuing test campaign (:func:`~thermocomp.core.continuation.preceding` its first row).  A
    model that reads the campaign's ambient from the manifest (no ambient sensor) has none for
    a stream of its own: refused."""
    campaign, comp = cfg.monitor.get("continues"), fixed.compensator
    if campaign is None:
        if fixed.ambient_given_:
            raise ConfigError("monitor.input=-: the model reads each campaign's ambient from the "
                              "manifest's ambient_c (no T_amb sensor), which a stream on stdin "
                              "lacks; record a T_amb sensor, or say the campaign it continues "
                              "(monitor.continues)")
        return {}
    campaign = str(campaign)
    if campaign not in ds.ids():
        raise ConfigError(f"monitor.continues={campaign}: no such campaign in {cfg.data.path} "
                          f"(campaigns: {', '.join(ds.ids())})")
    if comp.reference != "none":
        raise ConfigError(f"monitor.continues={campaign}: the model reads temperature changes "
                          f"from each campaign's first sample (data.reference={comp.reference}), "
                          "so no state carries over; fit it with data.reference=none")
    ids = chain(ds, campaign)
    say("stream warmed on the campaigns it continues (state carried over, unscored): "
        + carried_text({"stdin": [*ids, "stdin"]}))
    first = float(stream[TIME].iloc[0]) if TIME in stream.columns else 0.0
    return {"stdin": preceding(ds, ids, first)}


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
        leads = _stdin_lead_in(cfg, fixed, ds, streamed["stdin"]) if stdin else lead_ins(
            comp, ds, list(streamed))
        report, traces = monitor_report(adaptive, fixed, comp, streamed, train,
                                        str(cfg.monitor.pod.placement), leads,
                                        adapt_from_config(cfg.get("adapt"), len(comp.targets_)))
        if missing:
            report["missing"] = missing
        out = Path(resolve(cfg.out))
        with staged_outputs(out, last=("monitor.json",)) as stage:
            if cfg.plots != "none":
                from ...apps.monitor.figures import draw
                draw(stage / "monitor", adaptive, traces, report, cfg.monitor.get("map_time_h"))
            write_json(stage / "monitor.json", report)
        tr.log_metrics({"monitor": report["targets"]})
        tr.log_artifact(out / "monitor.json")
    print("\n".join(summary_lines(report)))
    say(f"monitor: {out / 'monitor.json'}")
    return report
