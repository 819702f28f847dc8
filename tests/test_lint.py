"""The code stays as ruff's configuration in pyproject.toml wants it (pyflakes, pycodestyle,
import order): a finding fails the suite with the file, line and rule."""

from __future__ import annotations

import subprocess
import sys

from conftest import ROOT


def test_ruff_finds_nothing():
    done = subprocess.run([sys.executable, "-m", "ruff", "check", "--output-format", "concise",
                           "src", "tests", "benchmarks", "pipelines"],
                          cwd=ROOT, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
