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
