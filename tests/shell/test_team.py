"""Team scale: the same commands against an MLflow tracking server on PostgreSQL; DVC remote storage.

The server test runs when ``THERMOCOMP_MLFLOW_SERVER`` names a running server
(``eval "$(.ci/team-server start)"`` starts PostgreSQL + MLflow on loopback;
``.ci/run`` does it in CI, in the background beside the first tests (the test waits for it), with
``THERMOCOMP_REQUIRE_SERVER=1``: there a missing server fails the test instead of skipping it).
``THERMOCOMP_PG_URI``, when set, lets the test look into the PostgreSQL database itself.
"""

from __future__ import annotations

import filecmp
import json
import os
import shutil
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

from conftest import ROOT, thermocomp
from test_deploy import LIGHT_EVAL, write_small_dataset
from thermocomp.shell.cli import main

pytestmark = pytest.mark.slow
SERVER = os.environ.get("THERMOCOMP_MLFLOW_SERVER")
PG_URI = os.environ.get("THERMOCOMP_PG_URI")


def test_sweep_compare_promote_against_a_postgresql_backed_server(tmp_path):
    if not SERVER:
        if os.environ.get("THERMOCOMP_REQUIRE_SERVER"):   # .ci/run: a skip would leave CI green
            pytest.fail("THERMOCOMP_MLFLOW_SERVER unset: .ci/team-server start did not run or failed")
        pytest.skip('no MLflow server: eval "$(.ci/team-server start)" first')
    _wait_for_background_start()
    from mlflow import MlflowClient

    data = write_small_dataset(tmp_path / "small")
    tag = uuid.uuid4().hex[:8]                       # the server outlives this test: own names
    experiment, model_name = f"team-{tag}", f"team-compensator-{tag}"
    common = [f"data.path={data}", f"tracking_uri={SERVER}", f"experiment_name={experiment}",
              *LIGHT_EVAL]
    sweep_dir = tmp_path / "sweep"
    thermocomp("run", "-m", *common, "model.estimator.fit_intercept=true,false",
               "hydra/launcher=joblib", "hydra.launcher.n_jobs=2", f"hydra.sweep.dir={sweep_dir}")

    client = MlflowClient(SERVER)
    exp = client.get_experiment_by_name(experiment)
    runs = client.search_runs([exp.experiment_id])
    parents = [r for r in runs if r.data.tags.get("thermocomp.sweep") == "parent"]
    children = [r for r in runs if "mlflow.parentRunId" in r.data.tags]
    assert len(parents) == 1 and len(children) == 2
    assert all(r.info.status == "FINISHED" and "E_Z.test.rmse" in r.data.metrics
               for r in children)
    assert {a.path for a in client.list_artifacts(parents[0].info.run_id, "compare")} >= {
        "compare/compare.csv"}

    assert main(["compare", *common, f"compare.out={tmp_path / 'cmp'}"]) == 0
    assert (tmp_path / "cmp" / "compare.csv").read_text().count("\n") == 3  # header + 2 runs
    # out beside the dataset: one holding data.path is refused (no stage writes into it)
    assert main(["promote", *common, f"promote.model_name={model_name}", f"out={tmp_path / 'p'}"]) == 0
    report = json.loads((tmp_path / "p" / "promote.json").read_text())
    assert report["moved"] and report["run_id"] in {r.info.run_id for r in children}
    import pandas as pd

    table = pd.read_csv(tmp_path / "cmp" / "compare.csv")    # best by validation, not by test
    assert table["val_rmse"].is_monotonic_increasing and report["run_id"] == table["run_id"].iloc[0]
    assert str(client.get_model_version_by_alias(model_name, "champion").version) == report["version"]

    if PG_URI:                                        # the runs really are in PostgreSQL
        import psycopg2

        with psycopg2.connect(PG_URI.replace("+psycopg2", "")) as con, con.cursor() as cur:
            cur.execute("SELECT count(*) FROM runs r JOIN experiments e "
                        "ON r.experiment_id = e.experiment_id WHERE e.name = %s", (experiment,))
            assert cur.fetchone()[0] == 3
            cur.execute("SELECT count(*) FROM model_versions WHERE name = %s", (model_name,))
            assert cur.fetchone()[0] == 1


def _wait_for_background_start(timeout_s: float = 300) -> None:
    """``.ci/team-server start --background`` (CI) brings the stack up beside the first tests:
    ``THERMOCOMP_TEAM_STATUS`` names the file where it says ``ready`` or ``failed``,
    ``THERMOCOMP_TEAM_LOG`` the start's log (shown when it failed)."""
    status = os.environ.get("THERMOCOMP_TEAM_STATUS")
    if not status:
        return
    status = Path(status)
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline and not (status.is_file() and status.read_text().strip()):
        time.sleep(0.5)
    said = status.read_text().strip() if status.is_file() else f"no word in {timeout_s:.0f} s"
    if said != "ready":
        log = Path(os.environ.get("THERMOCOMP_TEAM_LOG", os.devnull))
        pytest.fail(f"the team stack did not come up ({said}):\n"
                    + (log.read_text()[-3000:] if log.is_file() else ""))


def _run(*args, cwd, env):
    proc = subprocess.run(list(args), cwd=cwd, env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return proc.stdout


def test_dvc_local_folder_remote_push_then_pull_restores_data(tmp_path):
    proj = tmp_path / "proj"
    proj.mkdir()
    for item in (".dvc/config", ".dvcignore", "dvc.yaml"):
        (proj / item).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / item, proj / item)
    dvc = str(Path(sys.executable).parent / "dvc")
    env = {**os.environ, "GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t",
           "GIT_COMMITTER_NAME": "t", "GIT_COMMITTER_EMAIL": "t@t"}
    _run("git", "init", "-q", cwd=proj, env=env)
    data = write_small_dataset(proj / "data" / "raw" / "small")
    model = proj / "models" / "release" / "model.pkl"
    model.parent.mkdir(parents=True)
    model.write_bytes(os.urandom(4096))
    remote = tmp_path / "remote"
    _run(dvc, "remote", "add", "-d", "storage", str(remote), cwd=proj, env=env)
    _run(dvc, "add", "data/raw/small", "models/release/model.pkl", cwd=proj, env=env)
    _run(dvc, "push", cwd=proj, env=env)
    assert any(p.is_file() for p in remote.rglob("*"))

    keep = tmp_path / "keep"
    shutil.copytree(data, keep / "small")
    shutil.copy2(model, keep / "model.pkl")
    shutil.rmtree(data)
    model.unlink()
    shutil.rmtree(proj / ".dvc" / "cache")           # only the remote has the bytes now
    _run(dvc, "pull", "data/raw/small.dvc", "models/release/model.pkl.dvc", cwd=proj, env=env)
    assert not filecmp.dircmp(data, keep / "small").diff_files
    assert sorted(p.name for p in data.iterdir()) == sorted(p.name for p in (keep / "small").iterdir())
    assert filecmp.cmp(model, keep / "model.pkl", shallow=False)
