"""One run's job: Hydra's ``run_job`` (``hydra.core.utils``, Hydra 1.3) for a run that thermocomp
composed itself, without the per-command work Hydra does there that a run does not need.

Hydra's ``run_job`` deep-copies the whole composed config for the task (its ``hydra`` node with
it, then deleted), deep-copies the Hydra config again for ``JobReturn.hydra_cfg``, and calls
``HydraConfig.set_config`` (a masked copy of the ``hydra`` node) twice.  Here the task runs on the
composed config itself, its ``hydra`` node taken out for the task's time and put back after it
(the config a run composes is its own: :func:`thermocomp.shell.cli._run_job` composes it for this
run alone); ``JobReturn.hydra_cfg`` is the Hydra config itself (read-only since ``set_config``),
and the run folder is set on the Hydra config in place of a second ``set_config``.  What differs
is seen by a job-end callback only: it gets the config as the task left it (Hydra's: as
composed), and ``JobReturn.cfg`` is that config with its ``hydra`` node.  thermocomp's callbacks
(:mod:`.callbacks`) read there only the ``hydra`` node, and ``promote.*`` under a search sweeper
(a sweep, which goes through Hydra's launchers).  Everything else is Hydra's, in
its order: callbacks, job logging, ``hydra.output_subdir``, ``hydra.job.chdir``,
``hydra.job.env_set``.  A sweep (``-m``) goes through Hydra's launchers as before.

bench_ci100c.py measures it (stop 100): on test_hostile's small commands the copies and the
second set_config were ~0.02-0.04 s of CPU of a 0.10-0.17 s command.
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

from omegaconf import DictConfig, OmegaConf, open_dict, read_write


@contextlib.contextmanager
def _hydra_node_out(config: DictConfig):
    """``config`` without its ``hydra`` node within the block (the config Hydra's copy-then-delete
    gives the task: the root's flags and type, the other keys in their order), the node back at
    its place after it."""
    content = config.__dict__["_content"]
    at = list(content).index("hydra")
    node = content.pop("hydra")
    try:
        yield config
    finally:
        rest = list(content.items())      # what the task left
        content.clear()
        content.update([*rest[:at], ("hydra", node), *rest[at:]])


def _set_output_dir(node: DictConfig, output_dir: str) -> None:
    with read_write(node.hydra.runtime), open_dict(node.hydra.runtime):
        node.hydra.runtime.output_dir = output_dir


def run_job(task_function, config: DictConfig, hydra_context):
    """Hydra's ``run_job(task_function, config, "hydra.run.dir", None, hydra_context)``."""
    from hydra.core.hydra_config import HydraConfig
    from hydra.core.utils import (
        JobReturn,
        JobRuntime,
        JobStatus,
        _flush_loggers,
        _save_config,
        configure_log,
        env_override,
    )

    callbacks = hydra_context.callbacks
    old_cwd = os.getcwd()
    hydra_config = HydraConfig.instance()
    orig_hydra_cfg = hydra_config.cfg
    hydra_config.set_config(config)       # the run folder's interpolations may read ${hydra:...}
    output_dir = os.path.abspath(str(OmegaConf.select(config, "hydra.run.dir")))
    _set_output_dir(config, output_dir)
    _set_output_dir(hydra_config.cfg, output_dir)    # as a second set_config would have it
    _chdir = None
    try:
        ret = JobReturn()
        ret.cfg = config       # Hydra's: a deep copy of it (see the module's docstring)
        hydra_cfg = hydra_config.cfg
        ret.hydra_cfg = hydra_cfg
        ret.overrides = OmegaConf.to_container(config.hydra.overrides.task)
        Path(output_dir).mkdir(parents=True, exist_ok=True)
        _chdir = hydra_cfg.hydra.job.chdir
        if _chdir is None:      # version_base 1.3: Hydra's default since 1.2
            _chdir = False
        if _chdir:
            os.chdir(output_dir)
            ret.working_dir = output_dir
        else:
            ret.working_dir = os.getcwd()
        configure_log(config.hydra.job_logging, config.hydra.verbose)
        if config.hydra.output_subdir is not None:
            hydra_output = Path(config.hydra.runtime.output_dir) / Path(config.hydra.output_subdir)
            task = config.hydra.overrides.task
            with _hydra_node_out(config) as task_cfg:
                _save_config(task_cfg, "config.yaml", hydra_output)
            _save_config(hydra_cfg, "hydra.yaml", hydra_output)
            _save_config(task, "overrides.yaml", hydra_output)
        with env_override(hydra_cfg.hydra.job.env_set):
            callbacks.on_job_start(config=config, task_function=task_function)
            try:
                with _hydra_node_out(config) as task_cfg:
                    ret.return_value = task_function(task_cfg)
                ret.status = JobStatus.COMPLETED
            except Exception as e:
                ret.return_value = e
                ret.status = JobStatus.FAILED
        ret.task_name = JobRuntime.instance().get("name")
        _flush_loggers()
        callbacks.on_job_end(config=config, job_return=ret)
        return ret
    finally:
        hydra_config.cfg = orig_hydra_cfg
        if _chdir:
            os.chdir(old_cwd)
