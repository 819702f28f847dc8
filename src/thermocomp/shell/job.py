"""A run's job: Hydra's ``run_job`` (``hydra.core.utils``, Hydra 1.3) for the config a run composed
for itself, without its copies of that config.

Hydra's ``run_job`` deep-copies the composed config for the task (and deletes the copy's ``hydra``
node), deep-copies the Hydra config again for ``JobReturn.hydra_cfg`` and calls
``HydraConfig.set_config`` (a masked deep copy of the ``hydra`` node) twice: ~0.03 s of CPU of each
command (bench_ci102f.py), where a run's config is its own (:func:`.cli._run_job` composes it for
this run alone) and the Hydra config is read-only once set.  Here the task gets the composed config
itself, its ``hydra`` node taken out for the task's time (what :func:`.cli._compose` gives a library
caller), ``HydraConfig`` holds the node (one ``set_config``; the run folder set on it as Hydra's
second call would), and the callbacks see the whole config, as under Hydra.  The rest is Hydra's
own helpers in its order: callbacks, job logging, ``hydra.job.env_set``.  A run that asks for what
is left out here, ``hydra.output_subdir`` (the ``.hydra/`` files) or ``hydra.job.chdir=true``,
goes through Hydra's ``run_job`` (:func:`lean`: False); so does every sweep job (its launcher).
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

from omegaconf import DictConfig, OmegaConf, flag_override, open_dict, read_write


def lean(config: DictConfig) -> bool:
    """Whether :func:`run_job` runs ``config``'s job as Hydra's would (no ``.hydra/`` files, no
    change of the working folder)."""
    return config.hydra.output_subdir is None and not config.hydra.job.chdir


@contextlib.contextmanager
def _without_hydra(config: DictConfig):
    """``config`` with no ``hydra`` node within the block (the task's config under Hydra: the
    other keys in their order, the root's flags); the node back after it, not copied."""
    node = config.hydra
    with open_dict(config):
        del config["hydra"]
    try:
        yield config
    finally:
        node._set_parent(None)   # OmegaConf copies a node put back under its own root
        with open_dict(config), flag_override(config, "no_deepcopy_set_nodes", True):
            config["hydra"] = node


def run_job(task_function, config: DictConfig, callbacks):
    """Hydra's ``run_job(task_function, config, "hydra.run.dir", None, HydraContext(None,
    callbacks))`` for a :func:`lean` config; its ``JobReturn``."""
    from hydra.core.hydra_config import HydraConfig
    from hydra.core.utils import JobReturn, JobRuntime, JobStatus, _flush_loggers, configure_log, env_override

    hydra = HydraConfig.instance()
    before = hydra.cfg
    hydra.set_config(config)          # the run folder may read ${hydra:...}
    output_dir = os.path.abspath(str(OmegaConf.select(config, "hydra.run.dir")))
    for node in (config.hydra.runtime, hydra.cfg.hydra.runtime):
        with read_write(node), open_dict(node):
            node.output_dir = output_dir
    try:
        ret = JobReturn()
        ret.hydra_cfg = hydra.cfg      # Hydra's: a deep copy of this read-only config
        ret.overrides = OmegaConf.to_container(config.hydra.overrides.task)
        Path(output_dir).mkdir(parents=True, exist_ok=True)
        ret.working_dir = os.getcwd()
        configure_log(config.hydra.job_logging, config.hydra.verbose)
        with env_override(hydra.cfg.hydra.job.env_set):
            callbacks.on_job_start(config=config, task_function=task_function)
            with _without_hydra(config) as task_cfg:
                ret.cfg = task_cfg     # Hydra's: the task's copy; here its hydra node is back after
                try:
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
        hydra.cfg = before
