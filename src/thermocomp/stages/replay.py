"""`thermocomp replay`: stream the test campaigns through the deployable compensator.

The compensator is fitted on the train split of ``data.path`` with the
configured model (``replay.model=null``) or loaded (``replay.model=<model.pkl |
pyfunc folder | models:/name@alias>``), made deployable exactly as ``promote``
does (:meth:`StreamingCompensator.from_training` with ``promote.envelope``), and
every test campaign is streamed row by row from a reset.  Writes
``<out>/replay.json`` (CLI.md).
"""

from __future__ import annotations

from pathlib import Path

from omegaconf import DictConfig

from .. import io
from ..deploy import StreamingCompensator
from ..deploy.replay import replay_report
from ..errors import ConfigError
from ..evaluation import require_split
from ..paths import resolve
from ..tracking import connect, stage_run
from ..files import write_json
from .common import build_compensator, check_config, data_options, load_model, say


def _deployable(cfg: DictConfig, ds, train_ids) -> tuple[StreamingCompensator, str, str]:
    """``(streaming compensator, source, model name)``."""
    source = cfg.replay.get("model")
    env = cfg.promote.envelope
    train = {c: ds.campaigns[c] for c in train_ids}
    if source is None:
        say(f"fitting {cfg.model.name} on {len(train_ids)} train campaigns")
        comp, name, source = build_compensator(cfg).fit(train), str(cfg.model.name), "fitted"
    else:
        source = str(source)
        path = resolve(source) if not source.startswith("models:/") else None
        if path is None or (path / "MLmodel").is_file():
            import mlflow

            connect(cfg)
            try:
                model = mlflow.pyfunc.load_model(source if path is None else str(path))
            except Exception as exc:
                raise ConfigError(f"replay.model={source}: cannot load it "
                                  f"({' '.join(str(exc).split())[:200]})") from None
            streaming = model.unwrap_python_model().streaming
            return streaming, source, _name(streaming.compensator)
        comp = load_model(path)
        name = _name(comp)
    try:
        streaming = StreamingCompensator.from_training(comp, train, float(env.margin), str(env.policy))
    except ValueError as exc:
        raise ConfigError(f"the model cannot be deployed: {exc}") from None
    return streaming, source, name


def _name(comp) -> str:
    return ", ".join(sorted({type(e).__name__ for e in comp.estimators_.values()}))


def replay(cfg: DictConfig) -> dict:
    """Stream the test campaigns of ``data.path``; write ``<out>/replay.json``."""
    check_config(cfg)
    say(f"reading {resolve(cfg.data.path)}")
    ds, _ = io.read_dataset(resolve(cfg.data.path), data_options(cfg))
    train_ids, test_ids = require_split(ds, "train"), require_split(ds, "test")
    with stage_run(cfg, "replay") as tr:
        streaming, source, name = _deployable(cfg, ds, train_ids)
        missing = sorted({c for c in streaming.columns_ for i in test_ids
                          if c not in ds.campaigns[i].columns})
        if missing:
            raise io.ContractError("a test campaign lacks a column the deployed model reads",
                                   column=",".join(missing))
        say(f"streaming {len(test_ids)} test campaigns row by row ({', '.join(streaming.columns_)})")
        targets = replay_report(streaming, {c: ds.campaigns[c] for c in test_ids})
        report = {"model": name, "source": source, "targets": targets,
                  "excluded_inputs": [], "events": [],
                  "columns": list(streaming.columns_), "time_required": streaming.time_required_,
                  "envelope": {"policy": streaming.policy,
                               "margin": streaming.envelope.margin if streaming.envelope else None},
                  "test_campaigns": test_ids}
        path = write_json(Path(resolve(cfg.out)) / "replay.json", report)
        tr.log_metrics({"replay": targets})
        tr.log_artifact(path)
    print(f"{'target':<8} {'samples':>8} {'max|stream-batch|':>18} {'RMSE':>8} {'µs/sample':>10}")
    for t, r in targets.items():
        print(f"{t:<8} {r['n_samples']:>8} {r['max_abs_stream_minus_batch']:>18.3g} "
              f"{r['rmse']:>8.3f} {r['us_per_sample']:>10.1f}")
    say(f"replay: {path}")
    return report
