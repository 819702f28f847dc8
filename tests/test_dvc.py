"""`dvc repro` of the default study in a scratch copy of the project, the venv not on PATH."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT

pytestmark = pytest.mark.slow
STAGES = ("simulate", "ingest", "denoise", "select", "train", "evaluate", "diagnose")


def _dvc(*args, cwd, env):
    proc = subprocess.run([str(Path(sys.executable).parent / "dvc"), *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return proc.stdout + proc.stderr


def _ran(log: str) -> set[str]:
    return {s for s in STAGES if f"Running stage '{s}'" in log}


def copy_project(dest: Path) -> tuple[Path, dict]:
    """A scratch copy of the project (its `.venv` a link to this one) and an environment whose
    PATH does NOT hold the venv: `dvc repro` must work as a new user types it."""
    dest.mkdir()
    for item in ("conf", "src", "dvc.yaml", ".dvc", "pipelines"):
        src = ROOT / item
        if src.is_dir():
            shutil.copytree(src, dest / item, ignore=shutil.ignore_patterns("__pycache__", "tmp"))
        else:
            shutil.copy2(src, dest / item)
    os.symlink(Path(sys.executable).parent.parent, dest / ".venv")
    git = dict(GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@t", GIT_COMMITTER_NAME="t",
               GIT_COMMITTER_EMAIL="t@t")
    venv_bin = str(Path(sys.executable).parent)
    path = os.pathsep.join(p for p in os.environ["PATH"].split(os.pathsep)
                           if p and Path(p).resolve() != Path(venv_bin).resolve())
    env = {**os.environ, **git, "THERMOCOMP_ROOT": str(dest), "PATH": path}
    env.pop("VIRTUAL_ENV", None)
    # The study as committed, minus the report extras that refit one model per campaign:
    # this test is about what DVC reruns, not about the report (tested elsewhere).
    eval_conf = dest / "conf/eval/default.yaml"
    eval_conf.write_text(eval_conf.read_text().replace("mutual_prediction: true",
                                                       "mutual_prediction: false"))
    subprocess.run(["git", "init", "-q"], cwd=dest, check=True)
    return dest, env


@pytest.fixture()
def project(tmp_path):
    return copy_project(tmp_path / "proj")


def test_repro_twice_runs_nothing_then_model_param_reruns_train_and_evaluate(project):
    dest, env = project
    first = _dvc("repro", cwd=dest, env=env)
    assert _ran(first) == set(STAGES), first
    assert (dest / "reports/default/metrics.json").is_file()
    assert (dest / "mlruns/mlflow.db").is_file()

    second = _dvc("repro", cwd=dest, env=env)
    assert _ran(second) == set(), second

    model_conf = dest / "conf/model/mlr.yaml"
    model_conf.write_text(model_conf.read_text().replace("fit_intercept: true",
                                                         "fit_intercept: false"))
    third = _dvc("repro", cwd=dest, env=env)
    assert _ran(third) == {"train", "evaluate", "diagnose"}, third

    shown = _dvc("metrics", "show", cwd=dest, env=env)
    assert "reports/default/headline/E_Z.json" in shown and "test_rmse" in shown
