"""Every stage command of every DVC pipeline as committed (`dvc.yaml`, `pipelines/*/dvc.yaml`)
names a stage, and its config (each job of a sweep) composes and passes the checks a stage runs
before it reads anything: in a second, without DVC or a process.  DVC runs them end to end in
test_dvc_metrics (the default study and the sweep) and test_dvc_volumetric (marked ``full``:
`make test-all` only)."""

from __future__ import annotations

import itertools
import shlex

import pytest
import yaml
from omegaconf import OmegaConf

from conftest import ROOT
from thermocomp.shell.build import build, check_targets
from thermocomp.shell.config.checks import COMPONENTS, check_component
from thermocomp.shell.config.overrides import compose_checked, parse
from thermocomp.shell.config.rules import check_schema
from thermocomp.shell.stages import STAGES

LAUNCHER = "pipelines/thermocomp"
PIPELINES = [ROOT / "dvc.yaml", *sorted((ROOT / "pipelines").glob("*/dvc.yaml"))]


def _commands():
    for path in PIPELINES:
        for name, stage in yaml.safe_load(path.read_text())["stages"].items():
            yield pytest.param(shlex.split(stage["cmd"]), id=f"{path.relative_to(ROOT)}:{name}")


def _jobs(args: list[str]) -> list[list[str]]:
    """The overrides of each job: one per combination of the swept values (a run: one job)."""
    choices = []
    for arg in args:
        o = parse(arg)
        if o is not None and o.is_sweep_override():
            choices.append([f"{o.get_key_element()}={v}" for v in o.sweep_string_iterator()])
        elif not arg.startswith("-"):
            choices.append([arg])
    return [list(job) for job in itertools.product(*choices)]


@pytest.mark.parametrize("argv", list(_commands()))
def test_every_pipeline_command_composes_and_passes_the_stage_checks(argv):
    assert argv[0] == LAUNCHER and argv[1] in STAGES, argv
    stage, args = argv[1], argv[2:]
    jobs = _jobs(args)
    assert ("-m" in args) == (len(jobs) > 1), args       # a sweep sweeps, a run does not
    for job in jobs:
        cfg = compose_checked(job, stage)
        check_targets(cfg)
        check_schema(cfg)
        for key in COMPONENTS:
            node = OmegaConf.select(cfg, key)
            if node is not None:
                check_component(build(node, key), key)
