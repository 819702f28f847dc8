"""A run's job (thermocomp.shell.job) is Hydra's ``run_job`` without its copies of the config: the
task, the callbacks, HydraConfig during the job, the ``.hydra/`` files and the job's return the
same as Hydra's own runner gives, and the task's config a copy of its own."""

from __future__ import annotations

import hashlib
import inspect
import os

from hydra._internal.callbacks import Callbacks
from hydra.core import utils as hydra_utils
from hydra.core.hydra_config import HydraConfig
from hydra.types import HydraContext, RunMode
from omegaconf import OmegaConf, open_dict

from thermocomp.shell.config import overrides
from thermocomp.shell.job import run_job

# hydra.core.utils.run_job of hydra-core 1.3.8 (pyproject pins it), the code shell/job.py follows
RUN_JOB_SHA256 = "398b33286c017043f1461d40578429260e9130f35fb9a30ae94be718c1c14b63"


def test_hydras_run_job_is_the_one_the_job_follows():
    source = inspect.getsource(hydra_utils.run_job)
    assert hashlib.sha256(source.encode()).hexdigest() == RUN_JOB_SHA256, (
        "Hydra's run_job changed: bring thermocomp.shell.job in line with it, then this digest")


class _Seen:
    """A callback and a task that note what they get (the task also changes its config)."""

    def __init__(self):
        self.notes = []

    def on_job_start(self, config, **kwargs):
        self.notes.append(("start", OmegaConf.to_yaml(config)))

    def on_job_end(self, config, job_return, **kwargs):
        self.notes.append(("end", OmegaConf.to_yaml(config), job_return.status))

    def task(self, cfg):
        self.notes.append(("task", OmegaConf.to_yaml(cfg), "hydra" in cfg,
                           cfg._get_flag("struct"), os.getcwd(), str(HydraConfig.get().runtime.output_dir),
                           OmegaConf.to_yaml(HydraConfig.instance().cfg)))
        with open_dict(cfg):
            cfg.out = "changed by the task"
            cfg.added = 1
        return "done"


def _ran(runner, folder) -> tuple:
    cfg = overrides.compose_checked([f"hydra.run.dir={folder}", "hydra.output_subdir=.hydra",
                                     "+hydra.job.env_set.THERMOCOMP_JOB_TEST=x", "seed=3"], "run")
    cfg.hydra.mode = RunMode.RUN
    seen, callbacks = _Seen(), Callbacks()
    callbacks.callbacks = [seen]
    before = HydraConfig.instance().cfg
    ret = runner(seen.task, cfg, callbacks)
    files = {p.name: p.read_text() for p in sorted((folder / ".hydra").iterdir())}
    return (seen.notes, files, HydraConfig.instance().cfg is before, OmegaConf.to_yaml(cfg),
            ret.status, ret.return_value, ret.overrides, ret.working_dir, ret.task_name,
            OmegaConf.to_yaml(ret.cfg), OmegaConf.to_yaml(ret.hydra_cfg))


def test_a_job_is_what_hydras_run_job_makes_of_it(tmp_path):
    def hydras(task, cfg, callbacks):
        return hydra_utils.run_job(task_function=task, config=cfg, job_dir_key="hydra.run.dir",
                                   job_subdir_key=None,
                                   hydra_context=HydraContext(config_loader=None, callbacks=callbacks))

    theirs = _ran(hydras, tmp_path / "job")
    ours = _ran(run_job, tmp_path / "job")       # the same folder: output_dir in the texts
    assert ours == theirs
    task = theirs[0][1]
    assert task[2:4] == (False, True)                               # no hydra node, struct
    assert "changed by the task" not in theirs[3]                   # the task's own copy
    assert theirs[4].name == "COMPLETED" and theirs[5] == "done"
