"""``thermocomp <stage> [overrides]`` (see ``shared/spec/CLI.md``).

Hydra is the one source of configuration.  A single run composes ``conf/``
with the compose API (so bad config maps to exit status 2 cleanly); ``-m`` /
``--multirun`` and Hydra's own flags (``--cfg job`` ...) go through
``hydra.main`` so sweeps, launchers and callbacks work unchanged.

Exit status: 0 success, 2 bad input or bad config (one line on stderr), 1 otherwise.
"""

from __future__ import annotations

import sys
import traceback

USAGE = """usage: thermocomp <stage> [key=value ...] [-m]

stages:
  simulate   write a dataset from the built-in digital twin (sim=<scenario>)
  ingest     validate data.path, write Parquet + report to data.interim
  denoise    denoise the declared inputs (denoise=none|emd) -> data.processed + figures
  select     choose the inputs per target (select=...) -> models/<name>/selection.json
  train      fit the configured model on the train split
  evaluate   score it on train/test, write <out>/metrics.json and figures
  diagnose   closed loop: CV residual -> missing effect -> refit -> before/after (<out>/diagnosis.json)
  run        ingest .. evaluate in one process; -m for a sweep (one MLflow parent run)
  compare    table of a sweep's child runs, best first (compare.sweep=, compare.sort_by=)
  promote    register the best run's compensator; move @champion only if it is better
  replay     stream the test campaigns row by row through the deployable compensator (replay.json)

overrides: data.path=<dir> data.inputs=[T_*] data.targets=[E_Z] model=mlr select=all denoise=none
           eval.mode=simulation|one_step out=<dir> tracking_uri=<uri> seed=<int>
Relative paths are resolved against the project root."""


def _config_errors() -> tuple[type, ...]:
    from hydra.errors import HydraException
    from omegaconf.errors import OmegaConfBaseException

    from .errors import ThermocompError

    return (ThermocompError, HydraException, OmegaConfBaseException)


def _guarded(fn, *args):
    """Call ``fn``; bad input/config -> one line on stderr and exit 2."""
    try:
        return fn(*args)
    except _config_errors() as exc:
        msg = " ".join(str(exc).split())
        print(f"thermocomp: error: {msg}", file=sys.stderr)
        sys.exit(2)


def _check_seed(cfg) -> None:
    """``seed`` steers every random choice of every stage: an integer, checked before any."""
    from .errors import ConfigError

    seed = cfg.get("seed")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ConfigError(f"seed={seed!r} is not an integer >= 0")


def _compose(overrides: list[str]):
    from hydra import compose, initialize_config_dir

    from .paths import conf_dir

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3",
                               job_name="thermocomp"):
        return compose(config_name="config", overrides=overrides)


def _per_job(cfg):
    """In a multirun every job writes under its own Hydra output folder."""
    from hydra.core.hydra_config import HydraConfig
    from hydra.types import RunMode
    from omegaconf import open_dict

    if HydraConfig.initialized() and HydraConfig.get().mode == RunMode.MULTIRUN:
        out = HydraConfig.get().runtime.output_dir
        with open_dict(cfg):
            cfg.out = out
            cfg.model_path = f"{out}/model.pkl"
    return cfg


def _hydra_main(stage: str, args: list[str]) -> None:
    import hydra

    from .paths import conf_dir
    from .stages import stage as lookup

    fn = lookup(stage)

    @hydra.main(config_path=str(conf_dir()), config_name="config", version_base="1.3")
    def task(cfg):
        _guarded(_check_seed, cfg)
        return _guarded(fn, _per_job(cfg))

    sys.argv = [f"thermocomp-{stage}", *args]
    task()


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] in ("-h", "--help", "help"):
        print(USAGE)
        return 0 if argv else 2
    stage, args = argv[0], argv[1:]
    from .stages import STAGES, stage as lookup

    if stage not in STAGES:
        print(f"thermocomp: error: unknown or not yet available stage {stage!r} "
              f"(available: {', '.join(STAGES)})", file=sys.stderr)
        return 2
    try:
        if any(a.startswith("-") for a in args):
            _hydra_main(stage, args)
        else:
            cfg = _guarded(_compose, args)
            _guarded(_check_seed, cfg)
            _guarded(lookup(stage), cfg)
    except SystemExit as exc:
        return exc.code if isinstance(exc.code, int) else 1
    except KeyboardInterrupt:
        return 130
    except Exception:  # anything else is a bug or an environment failure: status 1
        traceback.print_exc()
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
