"""A run's job: Hydra's job runner (``hydra.core.utils.run_job`` of hydra-core 1.3.8, pinned) step
by step, without the copies of the composed config that nothing reads.

Hydra's ``run_job`` sets HydraConfig twice (a masked copy of the ``hydra`` node each time),
deep-copies the whole config for the task and HydraConfig's config again for the job's return:
~30 ms of CPU of an in-process command's ~70 ms of config handling (bench_ci109a), paid by every
command.  Here HydraConfig is set once (its run folder written into its copy as the second
``set_config`` would), the task's copy is pickled (the same nodes, flags, values and parents,
2-3x faster than OmegaConf's node-by-node deepcopy) and the job's ``hydra_cfg`` is HydraConfig's
own, put back after the job as Hydra puts it back.  The rest -- run folder, ``chdir``, job
logging, ``.hydra/`` files, ``env_set``, callbacks, the job's return -- is Hydra's, in its order.
tests/shell/test_job.py holds it to Hydra's ``run_job`` (its source and what a task gets).
"""

from __future__ import annotations

import copy
import os
import pickle
from pathlib import Path
from textwrap import dedent

from omegaconf import DictConfig, OmegaConf, open_dict, read_write


def task_config(config: DictConfig) -> DictConfig:
    """A copy of ``config`` without its ``hydra`` node, as Hydra's ``run_job`` hands its task:
    pickled (a root config has no parent to drag along), deep-copied if it does not pickle (a
    structured node whose class pickle cannot import)."""
    try:
        out = pickle.loads(pickle.dumps(config, pickle.HIGHEST_PROTOCOL))
    except (pickle.PicklingError, AttributeError, TypeError):
        out = copy.deepcopy(config)
    with read_write(out), open_dict(out):
        del out["hydra"]
    return out


def run_job(task_function, config: DictConfig, callbacks):
    """Hydra's ``run_job(task_function, config, "hydra.run.dir", None, HydraContext(None,
    callbacks))``: its :class:`~hydra.core.utils.JobReturn`."""
    from hydra import version
    from hydra._internal.deprecation_warning import deprecation_warning
    from hydra.core import utils as hydra_utils
    from hydra.core.hydra_config import HydraConfig
    from hydra.core.utils import JobReturn, JobRuntime, JobStatus, configure_log, env_override

    old_cwd = os.getcwd()
    orig_hydra_cfg = HydraConfig.instance().cfg
    HydraConfig.instance().set_config(config)     # the run folder may read it (${hydra:...})
    hydra_cfg = HydraConfig.instance().cfg
    output_dir = str(OmegaConf.select(config, "hydra.run.dir"))
    for runtime in (config.hydra.runtime, hydra_cfg.hydra.runtime):
        with read_write(runtime), open_dict(runtime):
            runtime.output_dir = os.path.abspath(output_dir)
    _chdir = None
    try:
        ret = JobReturn()
        task_cfg = task_config(config)
        ret.cfg = task_cfg
        ret.hydra_cfg = hydra_cfg
        ret.overrides = OmegaConf.to_container(config.hydra.overrides.task)
        Path(output_dir).mkdir(parents=True, exist_ok=True)
        _chdir = hydra_cfg.hydra.job.chdir
        if _chdir is None and version.base_at_least("1.2"):
            _chdir = False
        if _chdir is None:
            url = "https://hydra.cc/docs/1.2/upgrades/1.1_to_1.2/changes_to_job_working_dir/"
            deprecation_warning(message=dedent(f"""\
                Future Hydra versions will no longer change working directory at job runtime by default.
                See {url} for more information."""), stacklevel=2)
            _chdir = True
        if _chdir:
            os.chdir(output_dir)
            ret.working_dir = output_dir
        else:
            ret.working_dir = os.getcwd()
        configure_log(config.hydra.job_logging, config.hydra.verbose)
        if config.hydra.output_subdir is not None:
            hydra_output = Path(config.hydra.runtime.output_dir) / Path(config.hydra.output_subdir)
            hydra_utils._save_config(task_cfg, "config.yaml", hydra_output)
            hydra_utils._save_config(hydra_cfg, "hydra.yaml", hydra_output)
            hydra_utils._save_config(config.hydra.overrides.task, "overrides.yaml", hydra_output)
        with env_override(hydra_cfg.hydra.job.env_set):
            callbacks.on_job_start(config=config, task_function=task_function)
            try:
                ret.return_value = task_function(task_cfg)
                ret.status = JobStatus.COMPLETED
            except Exception as e:
                ret.return_value = e
                ret.status = JobStatus.FAILED
        ret.task_name = JobRuntime.instance().get("name")
        hydra_utils._flush_loggers()
        callbacks.on_job_end(config=config, job_return=ret)
        return ret
    finally:
        HydraConfig.instance().cfg = orig_hydra_cfg
        if _chdir:
            os.chdir(old_cwd)
