"""`thermocomp serve` SIGTERMed as it forks the server (connect68).

``run_server`` started the server (``subprocess.Popen``) before the ``try`` that stops it: a
SIGTERM raised inside ``Popen`` after the fork left the child running, no one to stop it (a
server whose parent ends before it arms its watch of the parent serves on).  The phase is
forced by patching ``Popen``, never by timing.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys

from mlflow.pyfunc.scoring_server import _SERVER_MODEL_PATH

from thermocomp.apps.deploy.server import run_server
from thermocomp.base.files import Terminated, signals_raise


def test_a_sigterm_as_the_server_is_forked_stops_it(tmp_path, monkeypatch):
    started = []
    real = subprocess.Popen

    class SignalledAtFork(real):
        """The child forked and running, then SIGTERM before Popen has returned it."""

        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            started.append(self)
            os.kill(os.getpid(), signal.SIGTERM)
            self.signalled = True     # the handler runs here, inside Popen, at the latest

    folder = tmp_path / "serve-model"
    (folder / "model").mkdir(parents=True)
    env = {**os.environ, _SERVER_MODEL_PATH: (folder / "model").as_uri()}
    monkeypatch.setattr(subprocess, "Popen", SignalledAtFork)
    with signals_raise():                  # as the console command runs a stage
        try:
            code = run_server([sys.executable, "-c", "import time; time.sleep(300)"], env)
        except Terminated:
            code = "terminated"
    (child,) = started
    left = child.poll() is None
    if left:                               # the test's own child: not left behind either way
        child.kill()
        child.wait()
    assert not left, "the server forked as SIGTERM came runs on"
    assert code == 0 and child.returncode == -signal.SIGTERM
    assert not folder.exists()
