"""`thermocomp replay`: stream the test campaigns through the deployable compensator.

The compensator is fitted on the train split of ``data.path`` (``replay.model=null``) or
loaded (``replay.model=<model.pkl | pyfunc folder | models:/name@alias>``), made deployable
exactly as ``promote`` does (a pyfunc model is replayed as it is), and every test campaign
(missing values kept) is streamed row by row from its start, or warmed on the campaigns it
continues (:func:`thermocomp.apps.deploy.report.replay_report`).  Writes ``<out>/replay.json``;
with ``replay.cold_start=true`` also the deployed RMSE of each test campaign streamed from a reset
(:func:`~thermocomp.apps.deploy.report.with_cold_start`).
"""

from __future__ import annotations

from pathlib import Path

from omegaconf import DictConfig

from ...apps.deploy.adapt import from_config as adapt_from_config
from ...apps.deploy.report import plain, replay_json, replay_lines, replay_report, with_cold_start
from ...base.errors import ConfigError
from ...base.files import write_json
from ...base.log import say
from ...base.paths import resolve
from ...core.continuation import lead_ins
from ...core.io.source import check_streamed_columns
from ..builders import deployable_model, registered_first, warn_stream_mode
from ..config.checks import check_config
from ..source import check_volumetric_targets, read_streamed
from ..tracking import name_given_model, stage_run


def replay(cfg: DictConfig) -> dict:
    """Stream the test campaigns of ``data.path``; write ``<out>/replay.json``."""
    check_config(cfg, inputs=("replay.model",))
    warn_stream_mode(cfg, "replay")
    model = cfg.replay.get("model")
    if model is not None and not str(model).strip():     # resolved, '' is the project root
        raise ConfigError("replay.model is empty: a model.pkl, a pyfunc folder or models:/<name>@<alias>")
    # a registered model, loaded before the record is read: its status words decoded as it
    # declares them (data86)
    cfg, loaded = registered_first(cfg, model, "replay.model")
    ds, train_ids, test_ids, gaps = read_streamed(cfg)
    with stage_run(cfg, "replay", given_model=model is not None) as tr:
        deployed, source, name = loaded or deployable_model(cfg, ds, train_ids, model,
                                                            "replay.model")
        if model is not None:
            name_given_model(tr, "replay", source, name)
        check_volumetric_targets(cfg, ds, deployed.targets_, f"replay.model={source}")
        check_streamed_columns(ds, test_ids, deployed.columns_, "the deployed model",
                               getattr(deployed, "bits_", None))
        kind = "adaptive" if deployed is not plain(deployed) else "streaming"
        say(f"streaming {len(test_ids)} test campaigns row by row through the {kind} compensator "
            f"({', '.join(deployed.columns_)})")
        tests = {c: ds.campaigns[c] for c in test_ids}
        files = {c: ds.rows_named(c) for c in test_ids}
        leads = lead_ins(plain(deployed).compensator, ds, test_ids)
        result = replay_report(deployed, tests, files, leads,
                               adapt_from_config(cfg.get("adapt"), len(deployed.targets_)))
        report = replay_json(deployed, result, name=name, source=source, test_ids=test_ids,
                             missing=gaps)
        if cfg.replay.get("cold_start"):    # what a restart of the compensator costs (deploy87)
            say("cold start: streaming the test campaigns again, each from a reset at its first row")
            cold = replay_report(deployed, tests, files, None,
                                 adapt_from_config(cfg.get("adapt"), len(deployed.targets_)))
            with_cold_start(report, cold, [c for c in test_ids if c in leads])
        path = write_json(Path(resolve(cfg.out)) / "replay.json", report)
        tr.log_metrics({"replay": report["targets"]})
        tr.log_artifact(path)
    print("\n".join(replay_lines(report)))
    say(f"replay: {path}")
    return report
