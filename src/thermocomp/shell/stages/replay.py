"""`thermocomp replay`: stream the test campaigns through the deployable compensator.

The compensator is fitted on the train split of ``data.path`` with the
configured model (``replay.model=null``) or loaded (``replay.model=<model.pkl |
pyfunc folder | models:/name@alias>``), made deployable exactly as ``promote``
does (:meth:`StreamingCompensator.from_training` with ``promote.envelope``,
wrapped in the adaptive compensator of the ``monitor`` group when
``monitor.adaptive``, the default), and every test campaign is streamed row by
row from its start: from a reset, or, when it continues other campaigns
(``data.reference=none``), warmed on them unscored, as ``run`` scores it.  A
pyfunc model is replayed as it is (what it holds).

The test campaigns are read with their missing values kept (a sensor dropout
streams through the adaptive compensator as the machine would see it); the
train split as ``run`` reads it (:func:`~.common.read_streamed`).  Writes
``<out>/replay.json`` (CLI.md).
"""

from __future__ import annotations

from pathlib import Path

from omegaconf import DictConfig

from ...apps.deploy.adapt import from_config as adapt_from_config
from ...apps.deploy.report import plain, replay_report
from ...base.errors import ConfigError
from ...base.files import write_json
from ...base.log import say
from ...base.paths import resolve
from ...core.continuation import lead_ins
from ...core.io.source import check_streamed_columns
from ...core.metrics import RMSE
from ..source import check_volumetric_targets, read_streamed
from ..tracking import stage_run
from .builders import deployable_model, warn_stream_mode
from .common import check_config


def replay(cfg: DictConfig) -> dict:
    """Stream the test campaigns of ``data.path``; write ``<out>/replay.json``."""
    check_config(cfg, inputs=("replay.model",))
    warn_stream_mode(cfg, "replay")
    model = cfg.replay.get("model")
    if model is not None and not str(model).strip():     # resolved, '' is the project root
        raise ConfigError("replay.model is empty: a model.pkl, a pyfunc folder or models:/<name>@<alias>")
    ds, train_ids, test_ids, gaps = read_streamed(cfg)
    root = resolve(cfg.data.path)
    with stage_run(cfg, "replay") as tr:
        deployed, source, name = deployable_model(cfg, ds, train_ids, cfg.replay.get("model"),
                                                  "replay.model")
        check_volumetric_targets(cfg, ds, deployed.targets_, f"replay.model={source}")
        check_streamed_columns(ds, test_ids, deployed.columns_, "the deployed model")
        kind = "adaptive" if deployed is not plain(deployed) else "streaming"
        say(f"streaming {len(test_ids)} test campaigns row by row through the {kind} compensator "
            f"({', '.join(deployed.columns_)})")
        result = replay_report(deployed, {c: ds.campaigns[c] for c in test_ids},
                               {c: root / str(ds.manifest.loc[c, "file"]) for c in test_ids},
                               lead_ins(plain(deployed).compensator, ds, test_ids),
                               adapt_from_config(cfg.get("adapt"), len(deployed.targets_)))
        targets = result["targets"]
        stream = plain(deployed)
        report = {"model": name, "source": source, "targets": targets,
                  "excluded_inputs": result["excluded_inputs"], "events": result["events"],
                  "adaptive": result["adaptive"], "pod": result["pod"],
                  **({"alarms": result["alarms"]} if "alarms" in result else {}),
                  "columns": list(deployed.columns_), "time_required": deployed.time_required_,
                  "envelope": {"policy": stream.policy,
                               "margin": stream.envelope.margin if stream.envelope else None},
                  "test_campaigns": test_ids}
        if gaps:
            report["missing"] = gaps      # missing cells per test campaign and column, streamed as NaN
        path = write_json(Path(resolve(cfg.out)) / "replay.json", report)
        tr.log_metrics({"replay": targets})
        tr.log_artifact(path)
    # RMSE batch: the fitted model's own prediction of the same rows (what `run` scores), so a
    # deployment that streams differently (the adaptive monitor's exclusions) shows beside it
    print(f"{'target':<8} {'samples':>8} {'max|stream-batch|':>18} {'RMSE':>8} {'RMSE batch':>11} "
          f"{'µs/sample':>10}")
    for t, r in targets.items():
        rmse, batch = ("-" if r.get(k) is None else f"{r[k]:.3f}" for k in (RMSE, "rmse_batch"))
        print(f"{t:<8} {r['n_samples']:>8} {r['max_abs_stream_minus_batch']:>18.3g} "
              f"{rmse:>8} {batch:>11} {r['us_per_sample']:>10.1f}")
    adapted = {t: r["adapt"] for t, r in targets.items() if "adapt" in r}
    if adapted:
        a = next(iter(adapted.values()))
        print(f"adapt ({a['method']}, {a['n_references']} references): RMSE frozen -> adapted "
              + ", ".join(f"{t} {r['adapt']['rmse_frozen']:.3f} -> {r[RMSE]:.3f}"
                          for t, r in targets.items() if "adapt" in r and r[RMSE] is not None
                          and r["adapt"]["rmse_frozen"] is not None))
    if report["adaptive"]:
        print(f"events: {len(report['events'])}, excluded at a campaign's end: "
              f"{', '.join(report['excluded_inputs']) or 'none'}")
    say(f"replay: {path}")
    return report
