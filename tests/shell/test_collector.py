"""The cyclic garbage collector's thresholds (thermocomp.base.lifetime.GC_THRESHOLDS): the console
command's process and a test process run at them, a library call of ``main`` leaves its caller's."""

from __future__ import annotations

import gc
import sys

import pytest

from thermocomp.base.lifetime import GC_THRESHOLDS
from thermocomp.shell import cli


@pytest.fixture
def python_thresholds(monkeypatch):
    """Python's own thresholds for the test, the process's put back after it; ``gc.freeze``
    (what the console's ``main`` ends with) a no-op: the test process's objects stay as they are."""
    before = gc.get_threshold()
    monkeypatch.setattr(gc, "freeze", lambda: None)
    gc.set_threshold(700, 10, 10)
    yield
    gc.set_threshold(*before)


def test_the_console_command_collects_at_the_projects_thresholds(python_thresholds, monkeypatch,
                                                                 capsys):
    monkeypatch.setattr(sys, "argv", ["thermocomp", "--version"])
    assert cli.main() == 0 and capsys.readouterr().out.startswith("thermocomp ")
    assert gc.get_threshold() == GC_THRESHOLDS
    assert GC_THRESHOLDS[0] > 700


def test_a_library_call_leaves_its_callers_thresholds(python_thresholds):
    assert cli.main(["--version"]) == 0
    assert gc.get_threshold() == (700, 10, 10)


def test_a_test_process_collects_at_the_commands_thresholds():
    # set by tests/conftest.py before the test modules import the stack
    assert gc.get_threshold() == GC_THRESHOLDS


@pytest.mark.parametrize("sweep_is, thresholds", [("parent", GC_THRESHOLDS),
                                                   ("this process", (700, 10, 10))])
def test_a_sweep_job_in_a_worker_of_the_sweep_collects_at_the_commands_thresholds(
        python_thresholds, monkeypatch, tmp_path, sweep_is, thresholds):
    """A joblib launcher's worker (a child of the sweep's process) is the sweep's own: it imports
    the stack at the command's thresholds; a job run in the sweep's process (the basic launcher,
    a library call of ``main``) leaves that process's."""
    import os

    from hydra.types import RunMode

    from thermocomp.base import lifetime
    from thermocomp.shell.callbacks import SWEEP_PID_ENV, MlflowSweepCallback
    from thermocomp.shell.config import overrides

    monkeypatch.setattr(lifetime, "watch_parent", lambda pid: None)    # no watch on pytest's parent
    monkeypatch.setenv(SWEEP_PID_ENV, str(os.getppid() if sweep_is == "parent" else os.getpid()))
    cfg = overrides.compose([f"out={tmp_path}", "track=false"], "run")
    cfg.hydra.mode = RunMode.RUN
    MlflowSweepCallback().on_job_start(config=cfg)
    assert gc.get_threshold() == thresholds
