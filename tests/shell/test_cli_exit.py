"""How a command-line process ends: its objects frozen out of the garbage collector before the
interpreter's last collections, which walked every imported module's objects (~0.6 s of CPU of
every `thermocomp` process, a fifth of a small run); the status, the output and the atexit
handlers as before.  In-process callers (tests, a notebook) keep their collector as it was."""

from __future__ import annotations

import gc
import os
import subprocess
import sys
from pathlib import Path

import pytest

import thermocomp
from thermocomp.shell.cli import main

SRC = Path(thermocomp.__file__).resolve().parents[1]
# what the console script does, plus an atexit handler registered first (so run last) that
# says whether the collector was frozen when the process ended
PROBE = ("import atexit, gc, sys\n"
         "atexit.register(lambda: print('frozen at exit:', gc.get_freeze_count() > 0))\n"
         "from thermocomp.shell.cli import main\n"
         "sys.exit(main())\n")


@pytest.mark.parametrize("args, code, says", [(["--version"], 0, "thermocomp "),
                                              (["nosuchstage"], 2, "")])
def test_a_command_line_ends_with_its_objects_frozen_and_its_status(args, code, says):
    proc = subprocess.run([sys.executable, "-c", PROBE, *args], capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(SRC)}, timeout=120)
    assert proc.returncode == code, proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[-1] == "frozen at exit: True"
    assert lines[0].startswith(says)
    if code:
        assert "unknown stage 'nosuchstage'" in proc.stderr


def test_a_command_in_this_process_leaves_the_collector_as_it_was(capsys):
    before = gc.get_freeze_count()
    assert main(["--version"]) == 0
    # nothing more frozen (conftest froze what collection imported: one of those objects may
    # be freed meanwhile, the count then drops)
    assert gc.get_freeze_count() <= before
    assert capsys.readouterr().out.startswith("thermocomp ")


# A command a signal ends: the threads it leaves do not keep the process (base.lifetime.
# end_left_threads).  Driven, not timed: SIGTERM is sent on return from Thread.start() (inside it,
# where the signal came while start() waited for the new thread) of an executor's first worker;
# or a thread that never ends.  The stage's function is replaced (stages.stage) by one that does so.
LEFT = """
import atexit, os, signal, sys, threading, time
from concurrent.futures import ThreadPoolExecutor
import thermocomp.shell.stages as stages
from thermocomp.base import lifetime
lifetime.LEFT_THREADS_GRACE_S = 1.0
atexit.register(lambda: print("atexit handlers ran", flush=True))
kept = []

def pool_worker_started(cfg):
    start = threading.Thread.start
    def started(thread):
        start(thread)
        threading.Thread.start = start
        os.kill(os.getpid(), signal.SIGTERM)
    threading.Thread.start = started
    kept.append(ThreadPoolExecutor(2))      # held, as MLflow's artifact repository holds its pool
    kept[-1].submit(int)
    time.sleep(60)

def thread_stuck(cfg):
    threading.Thread(target=threading.Event().wait, name="stuck66").start()
    os.kill(os.getpid(), signal.SIGTERM)
    time.sleep(60)

stages.stage = lambda name, fn=globals()[sys.argv.pop()]: fn     # the last argument names it
from thermocomp.shell.cli import main
sys.exit(main())
"""


@pytest.mark.parametrize("left", ["pool_worker_started", "thread_stuck"])
def test_a_command_a_sigterm_ended_ends_its_process_whatever_threads_it_left(tmp_path, left):
    """SIGTERM on return from a ThreadPoolExecutor's first Thread.start() left a worker the
    interpreter joined for ever at exit (`thermocomp serve` as MLflow downloads the model: CI,
    stop 65); a thread that never ends is waited for a while, then ends with the process."""
    proc = subprocess.run([sys.executable, "-c", LEFT, "simulate", f"out={tmp_path / 'out'}",
                           "track=false", left], capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(SRC)}, timeout=60)
    assert proc.returncode == 1, proc.stderr
    assert "simulate terminated (SIGTERM)" in proc.stderr
    assert proc.stdout.splitlines()[-1] == "atexit handlers ran"
    # the executor's worker ends as the interpreter ends them; a stuck thread is named
    assert ("stuck66" in proc.stderr) == (left == "thread_stuck"), proc.stderr
