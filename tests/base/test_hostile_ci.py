"""CI cannot stay green on a broken team stack (issue 35 item 8): ``.ci/run`` stops when
``.ci/team-server start`` fails, and the PostgreSQL test fails instead of skipping there."""

from __future__ import annotations

import os
import shutil
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import ROOT

pytest_plugins = ("pytester",)   # the CI-required test runs in a session of its own

STUB = "#!/usr/bin/env bash\necho \"$(basename \"$0\") $*\" >> \"$CALLS\"\n"


def _stub(path: Path, body: str = STUB) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(body)
    path.chmod(path.stat().st_mode | stat.S_IEXEC)


def _ci_run(tmp_path: Path, failing: str) -> tuple[subprocess.CompletedProcess, list[str]]:
    """A scratch checkout: the real ``.ci/run``; ``make``, python, chromium and a team server
    whose ``failing`` subcommand fails are stubs that log their calls."""
    (tmp_path / ".ci").mkdir()
    shutil.copy2(ROOT / ".ci" / "run", tmp_path / ".ci" / "run")
    _stub(tmp_path / "bin" / "make")
    _stub(tmp_path / ".venv" / "bin" / "python")
    _stub(tmp_path / ".venv" / "bin" / "mkdocs")
    _stub(tmp_path / ".ci" / "chromium")
    _stub(tmp_path / ".ci" / "team-server",
          STUB + f'[ "$1" = {failing} ] && {{ echo "[team-server] {failing} failed" >&2; exit 1; }}'
          + '\nexit 0\n')
    calls = tmp_path / "calls"
    env = {**os.environ, "CALLS": str(calls), "PATH": f"{tmp_path / 'bin'}:{os.environ['PATH']}"}
    proc = subprocess.run([str(tmp_path / ".ci" / "run")], env=env, capture_output=True,
                          text=True, timeout=60, stdin=subprocess.DEVNULL)
    return proc, calls.read_text().splitlines()


def test_ci_run_stops_when_the_team_server_does_not_start(tmp_path):
    """As PostgreSQL failing to install does: no test runs, the trap still cleans up."""
    proc, log = _ci_run(tmp_path, "start")
    assert proc.returncode != 0, (proc.stdout, proc.stderr, log)
    assert "team-server start --background" in log and "team-server stop" in log
    assert not [c for c in log if c.startswith(("python", "make test"))], log


def test_ci_run_fails_when_the_background_start_never_came_up(tmp_path):
    """The stack comes up beside the tests: its failure fails CI after them, whatever the team
    test made of it (here ``make`` is a stub that passes)."""
    proc, log = _ci_run(tmp_path, "wait")
    assert proc.returncode != 0, (proc.stdout, proc.stderr, log)
    assert log.index("make test") < log.index("team-server wait") < log.index("team-server stop"), log


def test_ci_run_stops_when_the_packages_beside_the_install_fail(tmp_path):
    """The Debian packages install beside ``make install``: their failure stops CI after it,
    with their output, before any server or test."""
    proc, log = _ci_run(tmp_path, "packages")
    assert proc.returncode != 0, (proc.stdout, proc.stderr, log)
    assert "make install" in log and "team-server packages" in log
    assert "packages failed" in proc.stderr
    assert not [c for c in log if c.startswith(("team-server start", "chromium", "make test"))], log


class _KeepImports:
    """The library modules an in-process session imported, put back after it: pytester restores
    ``sys.modules`` as it was, and an extension module cannot load twice in one process (the
    next test file to import numpy.fft, through scipy, failed: "cannot load module more than
    once per process", 16 of tests/core/test_raw_exports44.py run after this file)."""

    def pytest_sessionfinish(self):
        self.modules = dict(sys.modules)


@pytest.fixture
def kept_imports():
    """Set up before ``pytester``, so torn down after it has restored ``sys.modules``."""
    keep = _KeepImports()
    yield keep
    for name, module in getattr(keep, "modules", {}).items():
        if not name.startswith("test_") and name != "conftest":   # the session's own
            sys.modules.setdefault(name, module)


def test_the_postgresql_test_fails_instead_of_skipping_when_ci_requires_the_server(
        kept_imports, pytester, monkeypatch):
    """A pytest session of its own, in this process (pytester): a child interpreter re-imported
    pytest, conftest, sklearn and MLflow (~3 s CPU) to see one test fail."""
    for name in ("THERMOCOMP_MLFLOW_SERVER", "CI"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("THERMOCOMP_REQUIRE_SERVER", "1")
    monkeypatch.delitem(sys.modules, "test_team", raising=False)   # it reads the server at import
    required = pytester.runpytest_inprocess(
        str(ROOT / "tests" / "shell" / "test_team.py"), "-k", "postgresql",
        "-p", "no:randomly", "-p", "no:cacheprovider", "-p", "no:xdist", plugins=[kept_imports])
    assert required.ret == 1 and required.parseoutcomes().get("failed") == 1, \
        "\n".join(required.outlines[-40:])


# -- the README test's reading of README.md (tests/test_readme.py runs the commands; this checks
# what it reads, without copying the venv) ----------------------------------------------------
def test_the_readme_test_accounts_for_every_block_and_directive():
    from test_readme import readme_blocks, unaccounted

    assert unaccounted((ROOT / "README.md").read_text()) == []
    ok = ("<!-- readme-test: expect E_Z -->\n```bash\nrun\n```\n"
          "<!-- readme-test: output -->\n```\nE_Z 1\n```\n")
    assert unaccounted(ok) == [] and [b["kind"] for b in readme_blocks(ok)] == ["expect", "output"]
    detached = "<!-- readme-test: skip — slow -->\n\n```bash\nmake test\n```\n"
    assert unaccounted(detached) == ["line 1: directive not on the line before a block"]
    for lang in ("sh", "console"):
        assert unaccounted(f"```{lang}\nthermocomp run\n```\n") == [
            f"line 1: a ```{lang} block is never run: write ```bash"]
    assert unaccounted("<!-- readme-test: output -->\n```\nE_Z 1\n```\n") == [
        "line 1: output goes on an unlabelled block after a command block"]


def test_the_readme_test_checks_every_row_of_a_printed_table():
    from test_readme import missing_lines

    table = "target  RMSE\nE_X     0.75\nE_Y     1.42\n"
    printed = "[thermocomp] reading\ntarget RMSE\nE_X   0.75\nE_Y   1.42\n[thermocomp] done\n"
    assert missing_lines(table, printed) == []
    assert missing_lines(table, printed.replace("1.42", "1.43")) == ["E_Y     1.42"]   # not row 1


def test_a_sigterm_swallowed_by_a_weakref_callback_is_raised_again():
    """A signal handler runs between any two bytecodes, also inside a weakref callback, where
    Python prints "Exception ignored" and drops the exception: the stage went on to its end
    (tests/shell/test_tracking.py's signalled run timed out so). signals_raise raises it again."""
    import gc
    import weakref

    from thermocomp.base.files import Terminated, signals_raise

    class Thing:
        pass

    def callback(_ref):             # the signal arrives while the callback runs
        os.kill(os.getpid(), signal.SIGTERM)
        for _ in range(1000):
            sum(range(10))

    reached_end = False
    with pytest.raises(Terminated):
        with signals_raise():
            thing = Thing()
            ref = weakref.ref(thing, callback)
            del thing                   # the callback runs here; its exception is ignored
            gc.collect()
            deadline = time.monotonic() + 5
            while time.monotonic() < deadline:
                sum(range(100))
            reached_end = ref is not None
    assert not reached_end
