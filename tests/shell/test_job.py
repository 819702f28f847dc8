"""thermocomp's job runner for a run (shell/job.py, ci100c) against Hydra's own ``run_job``: the
task gets the same config, the Hydra config says the same run folder, the job returns the same;
and a run's command deep-copies no composed config (Hydra's run_job copied it twice)."""

from __future__ import annotations

import copy

import pytest
from omegaconf import DictConfig, OmegaConf, open_dict

from conftest import thermocomp

TINY = ("track=false", "sim.generator.n_campaigns=3", "sim.generator.duration_h=[1.0,1.0]")


def _seen(job, tmp_path, out: str):
    """What a task sees and leaves under ``job`` (Hydra's run_job or ours) on a composed config."""
    from hydra.core.hydra_config import HydraConfig
    from hydra.core.utils import run_job as hydras
    from hydra.types import HydraContext, RunMode

    from thermocomp.shell.config import overrides

    config = overrides.compose([f"out={tmp_path / out}", "hydra.run.dir=${out}", *TINY], "simulate")
    config.hydra.mode = RunMode.RUN
    seen = {}

    def task(cfg):
        seen["config"] = OmegaConf.to_yaml(cfg).replace(out, "<out>")
        seen["keys"] = list(cfg)
        seen["struct"] = OmegaConf.is_struct(cfg)
        seen["output_dir"] = HydraConfig.get().runtime.output_dir.replace(out, "<out>")
        with open_dict(cfg):
            cfg.added = 1          # what a stage may do to its own config
        return "done"

    class Quiet:
        def on_job_start(self, **kwargs): ...
        def on_job_end(self, **kwargs): ...

    context = HydraContext(config_loader=None, callbacks=Quiet())
    if job is hydras:
        ret = hydras(task, config, "hydra.run.dir", None, context)
    else:
        ret = job(task, config, context)
    seen["return"] = (ret.return_value, ret.status, ret.working_dir, ret.overrides)
    seen["return"] = str(seen["return"]).replace(out, "<out>")
    seen["hydra_cfg"] = OmegaConf.to_yaml(ret.hydra_cfg).replace(out, "<out>")
    seen["after"] = (list(config)[-1] if "hydra" not in config else "hydra",
                     str(config.hydra.runtime.output_dir).replace(out, "<out>"))
    seen["initialized"] = HydraConfig.initialized()
    return seen


def test_the_task_sees_what_it_saw_under_hydras_run_job(tmp_path):
    from hydra.core.utils import run_job as hydras

    from thermocomp.shell.job import run_job

    theirs = _seen(hydras, tmp_path, "run-of-hydra")
    ours = _seen(run_job, tmp_path, "run-of-thermocomp")
    assert ours == theirs
    assert "hydra" not in ours["keys"] and ours["struct"]
    assert ours["output_dir"] == str(tmp_path / "<out>")


def test_a_run_deep_copies_no_composed_config(tmp_path, monkeypatch):
    """On 063630e6 Hydra's run_job deep-copied the composed config (and its Hydra config) once a
    run: ~0.01-0.03 s of CPU of a 0.05-0.17 s in-process command (bench_ci100c)."""
    copied = []
    original = DictConfig.__deepcopy__

    def counted(self, memo):
        content = self.__dict__["_content"]
        if self._get_parent() is None and isinstance(content, dict) and {"hydra", "seed"} <= set(content):
            copied.append(list(content))
        return original(self, memo)

    monkeypatch.setattr(DictConfig, "__deepcopy__", counted)
    proc = thermocomp("simulate", f"data.path={tmp_path / 'ds'}", *TINY, cwd=tmp_path)
    assert proc.returncode == 0 and (tmp_path / "ds" / "campaigns.csv").is_file()
    assert copied == []


@pytest.mark.parametrize("at", ["first", "middle", "last"])
def test_the_hydra_node_goes_back_where_it_was(at):
    from thermocomp.shell.job import _hydra_node_out

    keys = {"first": ["hydra", "a", "b"], "middle": ["a", "hydra", "b"], "last": ["a", "b", "hydra"]}[at]
    config = OmegaConf.create({k: {"x": 1} for k in keys})
    node = config._get_node("hydra")
    with _hydra_node_out(config) as task:
        assert list(task) == [k for k in keys if k != "hydra"]
        task.a.x = 2
    assert list(config) == keys and config._get_node("hydra") is node and config.a.x == 2
    assert copy.deepcopy(config) == config
