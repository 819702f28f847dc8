"""A run's job (shell/job.py, ci102f) against Hydra's own ``run_job``: the task gets the same config,
the Hydra config says the same run folder, the callbacks and the job's return see the same; a run
deep-copies no composed config; a run that asks for ``.hydra/`` files gets Hydra's runner."""

from __future__ import annotations

import pytest
from omegaconf import DictConfig, OmegaConf, open_dict

from conftest import thermocomp

REFUSED = ("track=false", "eval.validation=maybe")     # refused in the task, by check_schema


def _seen(lean: bool, tmp_path, out: str) -> dict:
    """What a task, the callbacks and the job's return see under Hydra's run_job or ours."""
    from hydra.core.hydra_config import HydraConfig
    from hydra.core.utils import run_job
    from hydra.types import HydraContext, RunMode

    from thermocomp.shell import job
    from thermocomp.shell.config import overrides

    config = overrides.compose([f"out={tmp_path / out}", "hydra.run.dir=${out}", "track=false"], "run")
    config.hydra.mode = RunMode.RUN
    seen = {}

    def task(cfg):
        seen["task"] = (OmegaConf.to_yaml(cfg), list(cfg), OmegaConf.is_struct(cfg),
                        HydraConfig.get().runtime.output_dir)
        with open_dict(cfg):
            cfg.added = 1          # what a stage may do to its own config
        return "done"

    class Heard:
        def on_job_start(self, config, **kwargs):
            seen["start"] = (sorted(config), config.hydra.runtime.output_dir)

        def on_job_end(self, config, job_return, **kwargs):
            seen["end"] = (sorted(config), config.hydra.runtime.output_dir, job_return.return_value)

    if lean:
        ret = job.run_job(task, config, Heard())
    else:
        ret = run_job(task, config, "hydra.run.dir", None, HydraContext(None, Heard()))
    seen["return"] = (ret.status, ret.working_dir, ret.overrides, ret.task_name,
                      OmegaConf.to_yaml(ret.hydra_cfg), OmegaConf.is_readonly(ret.hydra_cfg.hydra))
    seen["after"] = (sorted(config), HydraConfig.initialized())
    return {k: str(v).replace(out, "<out>") for k, v in seen.items()}


def test_the_task_and_the_callbacks_see_what_they_saw_under_hydras_run_job(tmp_path):
    hydras, ours = _seen(False, tmp_path, "run-of-hydra"), _seen(True, tmp_path, "run-of-thermocomp")
    assert ours["task"] == hydras["task"]
    assert "'hydra'" not in ours["task"].split("], ")[0] and str(tmp_path / "<out>") in ours["task"]
    # the callbacks: the whole config; after the job, the stage's own change in it (Hydra's task
    # changed a copy) and the run's hydra node back
    assert ours["start"] == hydras["start"]
    for when in ("end", "after"):
        assert ours[when] == hydras[when].replace("['ati'", "['added', 'ati'")
    assert ours["return"] == hydras["return"]


def test_a_run_deep_copies_no_composed_config(tmp_path, monkeypatch):
    """On d85f1799 Hydra's run_job deep-copied the composed config and its Hydra config once a
    run (~0.02 s of CPU of a 0.06-0.14 s in-process command, bench_ci102f)."""
    copied = []
    original = DictConfig.__deepcopy__

    def counted(self, memo):
        content = self.__dict__["_content"]
        if isinstance(content, dict) and {"hydra", "seed"} <= set(content) and self._get_parent() is None:
            copied.append(list(content))
        return original(self, memo)

    monkeypatch.setattr(DictConfig, "__deepcopy__", counted)
    proc = thermocomp("run", f"out={tmp_path / 'o'}", *REFUSED, cwd=tmp_path, check=False)
    assert proc.returncode == 2 and "eval.validation='maybe'" in proc.stderr
    assert copied == []


@pytest.mark.parametrize("asks", ["hydra.output_subdir=.hydra", "hydra.job.chdir=true"])
def test_a_run_that_asks_for_hydras_files_or_folder_gets_hydras_runner(tmp_path, asks):
    from thermocomp.shell import job
    from thermocomp.shell.config import overrides

    assert job.lean(overrides.compose([], "run"))
    assert not job.lean(overrides.compose([asks], "run"))
    if asks.startswith("hydra.output_subdir"):
        proc = thermocomp("run", f"out={tmp_path / 'o'}", f"hydra.run.dir={tmp_path / 'o'}", asks,
                          *REFUSED, cwd=tmp_path, check=False)
        assert proc.returncode == 2
        assert sorted(p.name for p in (tmp_path / "o" / ".hydra").iterdir()) == [
            "config.yaml", "hydra.yaml", "overrides.yaml"]
