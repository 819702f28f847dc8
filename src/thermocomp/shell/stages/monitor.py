"""`thermocomp monitor`: sensor surveillance and the fault-tolerant compensator, streamed.

The compensator, fitted on the train split of ``data.path`` (or ``monitor.model=<model.pkl>``),
is made deployable as ``promote`` does (a registered model's, a pyfunc folder or ``models:/...``,
streams as registered, its status words read by its declaration: data86b) and wrapped in an
adaptive compensator fitted on the same split.  Each test campaign (as recorded: missing cells
stay NaN) or the CSV rows of stdin (``monitor.input=-``) is streamed from its start, or warmed
on the campaigns it continues, through both (:func:`thermocomp.apps.monitor.report.monitor_report`).  Writes
``<out>/monitor.json`` (CLI.md) and figures in ``<out>/monitor/``.
"""

from __future__ import annotations

import sys
from pathlib import Path

from omegaconf import DictConfig

from ...apps.deploy.adapt import from_config as adapt_from_config
from ...apps.deploy.report import plain
from ...apps.monitor.report import monitor_report, summary_lines
from ...apps.monitor.stdin import (
    check_continued,
    said_if_cold_continuation,
    said_if_mid_campaign,
    said_if_other_period,
    said_if_unknown,
    stdin_chain,
    stdin_lead_in,
)
from ...base.errors import ConfigError
from ...base.files import staged_outputs, write_json
from ...base.log import say
from ...base.paths import resolve
from ...core import io
from ...core.context import TIME
from ...core.continuation import fit_joined, lead_ins, said_warmed
from ...core.io.contract import AMBIENT_C
from ...core.io.own_headers import lab_names
from ...core.io.source import check_streamed_columns
from ...core.io.stdin import TIME_ORIGIN, stdin_text, stream_campaigns
from ..builders import (
    build_adaptive,
    build_compensator,
    deploy_stream,
    loaded_stream,
    registered_first,
    warn_stream_mode,
)
from ..config.checks import check_config, data_options
from ..model_store import load_model, model_family
from ..source import check_volumetric_targets, read_streamed, slashed_time
from ..tracking import name_given_model, stage_run


def _stdin_lead_in(cfg: DictConfig, fixed, ds, streamed: dict, train_ids: list[str]) -> dict:
    """``{first campaign: lead-in}`` when ``monitor.continues`` names the campaign the stream
    continues (its first run, with ``data.roles.campaign``: each later run starts from a reset);
    without it, a first row that looks like the middle of a campaign is said."""
    cid, stream = next(iter(streamed.items()))
    # (a model that reads the ambient only where it is known starts without: stranger66)
    given = fixed.ambient_given_ and not fixed.ambient_optional_
    ids = stdin_chain(ds, cfg.monitor.get("continues"), ambient_given=given,
                      reference=fixed.compensator.reference, data_path=cfg.data.path,
                      ambient_c=cfg.monitor.get("ambient_c"))
    leads = stdin_lead_in(ds, ids, cid, stream[TIME] if TIME in stream.columns else None,
                          stream.attrs.get(TIME_ORIGIN))
    if ids:
        said_warmed({cid: [*ids, cid]}, leads)
        check_continued(leads[cid], stream, ids[-1])
    else:
        said_if_mid_campaign(ds, train_ids, stream, cid)
        said_if_cold_continuation(ds, fixed, cid)
    return leads


def _fitted(cfg: DictConfig, ds, train: dict, registered):
    """``(compensator, its plain stream)``: fitted on ``train``, or ``monitor.model``'s (a
    registered one's stream as registered: what is monitored is what was deployed)."""
    path = cfg.monitor.get("model")
    # one plain stream serves both: the fixed run and the adaptive one are each streamed from a
    # reset, one after the other
    if registered is not None:
        comp, stream = plain(registered).compensator, plain(registered)
    elif path is None:
        # fitted as run fits it: train files that continue one another joined (their state
        # carried over)
        comp = fit_joined(build_compensator(cfg, ds=ds), ds, list(train), train)
        stream = deploy_stream(cfg, comp, train)
    else:       # a model.pkl, checked as replay checks it (names97: another record's said first)
        comp = load_model(resolve(str(path)))
        stream = loaded_stream(cfg, ds, train, comp, f"monitor.model={path}")
    check_volumetric_targets(cfg, ds, comp.targets_, f"monitor.model={path}")
    return comp, stream


def monitor(cfg: DictConfig) -> dict:
    """Stream the test campaigns (or stdin) through the fixed and the adaptive compensator."""
    check_config(cfg, inputs=("monitor.model",))
    warn_stream_mode(cfg, "monitor")
    model = cfg.monitor.get("model")
    if model is not None and not str(model).strip():     # resolved, '' is the project root
        raise ConfigError("monitor.model is empty: a model.pkl, a pyfunc folder or "
                          "models:/<name>@<alias>")
    # a registered model, loaded before the record is read: its status words decoded as it
    # declares them (data86b, as replay's)
    cfg, loaded = registered_first(cfg, model, "monitor.model")
    registered = loaded[0] if loaded else None
    stdin = cfg.monitor.get("input") == "-"
    ds, train_ids, test_ids, missing = read_streamed(cfg, test=not stdin)
    streamed, train = {c: ds.campaigns[c] for c in test_ids}, {c: ds.campaigns[c] for c in train_ids}
    with stage_run(cfg, "monitor", given_model=model is not None) as tr:
        comp, fixed = _fitted(cfg, ds, train, registered)
        if model is not None:
            name_given_model(tr, "monitor", str(model), model_family(comp))
        adaptive = build_adaptive(cfg, fixed, train, ds)
        if adaptive.monitor is None:
            raise ConfigError("monitor needs at least 3 temperature inputs (T_ columns) in the "
                              f"model, got {[c for c in adaptive.columns_ if c.startswith('T_')]}")
        if stdin:
            opts = io.ReadOptions.from_cfg(data_options(cfg))
            # (code71) dates with slashes in the order the training record decided: a stream
            # cannot see the future, its first row alone read 10/03 into 11/03 month first
            streamed, missing = stream_campaigns(stdin_text(sys.stdin, opts.encoding),
                                                 adaptive.columns_, opts, slashed_time(cfg, ds),
                                                 lab_names(cfg, ds))
            said_if_unknown(streamed, ds)
            if cfg.monitor.get("ambient_c") is not None:   # as the manifest's ambient_c is carried
                for df in streamed.values():
                    df.attrs[AMBIENT_C] = float(cfg.monitor.ambient_c)
        else:
            check_streamed_columns(ds, list(streamed), adaptive.columns_, "the model")
        said_if_other_period(streamed, train)
        say(f"streaming {len(streamed)} campaign(s) through the fixed and the adaptive compensator")
        leads = _stdin_lead_in(cfg, fixed, ds, streamed, train_ids) if stdin else lead_ins(
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
