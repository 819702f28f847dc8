"""What a run records in MLflow, and that it is recorded at all.

Run names from the overrides, a handful of params and headline metrics (the
full ``metrics.json`` is the artifact), ``simulate`` untracked by default, a
fresh SQLite store created once under a file lock (2 parallel runs: 2 runs
recorded), and runs ended KILLED on SIGTERM/SIGINT, FAILED on errors.
"""

from __future__ import annotations

import json
import os
import signal
import sqlite3
import subprocess
import time

import pytest

from conftest import BIN, TEST_PATH
from test_deploy import LIGHT_EVAL, mlflow_store, write_small_dataset
from thermocomp.base.files import folder_digest
from thermocomp.core.models import MLR
from thermocomp.core.scoring.results import EvaluationResult
from thermocomp.shell.cli import _compose, main
from thermocomp.shell.tracking import (
    PARAM_KEYS,
    config_container,
    run_name,
    run_params,
    sweep_name,
    task_overrides,
)


class Sleepy(MLR):
    """MLR whose fit takes a minute: a run that is surely still RUNNING when it is signalled."""

    def fit(self, X, y, context=None):
        # in short slices, as a computation runs bytecode: a signal the kernel hands to another
        # thread of the process (a store's, say) reaches the main thread's handler only when it
        # runs bytecode again, not inside one 60 s sleep (the run then outlived the test's wait)
        end = time.monotonic() + 60
        while time.monotonic() < end:
            time.sleep(0.1)
        return super().fit(X, y, context)


class Interrupted(MLR):
    """MLR whose fit is interrupted by Ctrl-C: SIGINT to this thread, its handler run before
    ``fit`` returns (as test_hostile's killed runs), while the run is RUNNING."""

    def fit(self, X, y, context=None):
        signal.raise_signal(signal.SIGINT)
        raise AssertionError("not reached")


@pytest.fixture(scope="session")
def dataset(tmp_path_factory):
    return write_small_dataset(tmp_path_factory.mktemp("tracking") / "small")


def _named(*overrides: str) -> str:
    cfg = _compose(list(overrides))
    return run_name(cfg, task_overrides())


def test_run_name_says_what_differs_from_the_defaults():
    assert _named() == "mlr"
    assert _named("select=pearson", "seed=1") == "mlr-pearson-seed1"
    assert _named("seed=1", "model=arx", "select=pearson") == "arx-pearson-seed1"   # stable order
    # where things go and how much is reported do not name a run
    assert _named("ati=cmeans", "eval.mode=one_step", "data.path=/x/y", "out=/o", "plots=none",
                  "tracking_uri=sqlite:////t/m.db", "eval.validation=false") == "mlr-cmeans-one_step"
    assert (_named("data.inputs=[T_1,T_2]", "model.estimator.fit_intercept=false")
            == "mlr-inputs=T_1,T_2-fit_intercept=false")
    assert _named("name=weak", "denoise=emd") == "weak/mlr-emd"


def test_a_sweep_is_named_from_what_it_sweeps():
    assert (sweep_name(["data.path=/x", "model=mlr,pcr", "seed=range(0,3)", "plots=none"])
            == "sweep/model=mlr,pcr-seed=range0,3")
    assert sweep_name(["data.path=/x"], "study") == "sweep/study"


def test_params_are_the_meaningful_leaves_plus_what_was_overridden():
    overrides = ["ati=cmeans", "model.estimator.fit_intercept=false", "data.path=/x/y"]
    cfg = _compose(overrides)
    params = run_params(config_container(cfg), task_overrides())
    everything = run_params.__globals__["_flat_params"](config_container(cfg))
    assert len(everything) > 100 and len(params) < 25
    assert set(PARAM_KEYS) <= set(params)
    assert params["ati.name"] == "cmeans" and params["model.estimator.fit_intercept"] == "False"
    assert params["data.path"] == "/x/y"
    assert not any(k.startswith("ati.estimator") or k.endswith("_target_") for k in params)


def test_a_run_records_its_name_stage_dataset_headline_metrics_and_signed_model(tmp_path, dataset):
    uri = mlflow_store(tmp_path)
    out = tmp_path / "out"
    assert main(["run", f"data.path={dataset}", f"tracking_uri={uri}", f"out={out}", "seed=1",
                 "select=pearson", *LIGHT_EVAL]) == 0
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    [run] = client.search_runs([client.get_experiment_by_name("thermocomp").experiment_id])
    assert run.info.run_name == "mlr-pearson-seed1" and run.info.status == "FINISHED"
    assert run.data.tags["stage"] == "run"
    assert run.data.tags["dataset_hash"] == folder_digest(dataset)
    m = json.loads((out / "metrics.json").read_text())
    assert run.data.metrics == pytest.approx({**EvaluationResult(m).headline("mlflow"),
                                              "fit_time_s": m["fit_time_s"]})
    for t, tm in m["targets"].items():
        mine = [k for k in run.data.metrics if k.startswith(f"{t}.")]
        assert 8 <= len(mine) <= 12
        assert run.data.metrics[f"{t}.test.rmse"] == pytest.approx(tm["test"]["rmse"])
        assert run.data.metrics[f"{t}.val.rmse"] == pytest.approx(tm["validation"]["rmse"])
        assert run.data.metrics[f"{t}.persistence.rmse"] == pytest.approx(tm["persistence"]["rmse"])
    logged = {a.path for a in client.list_artifacts(run.info.run_id)}
    assert {"metrics.json", "config.yaml", "model.pkl", "model.pkl.sig"} <= logged
    # the run names its id (what promote.run_id takes) in its log
    assert f"MLflow run {run.info.run_id} (experiment 'thermocomp'" in (
        out / "thermocomp.log").read_text()


def test_simulate_is_not_tracked_unless_asked(tmp_path):
    uri = mlflow_store(tmp_path)
    small = ["sim.generator.n_campaigns=3", "sim.generator.test_every=3", f"tracking_uri={uri}"]
    assert main(["simulate", f"data.path={tmp_path / 'a'}", *small]) == 0
    with sqlite3.connect(uri[len("sqlite:///"):]) as con:
        assert con.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 0
    assert main(["simulate", f"data.path={tmp_path / 'b'}", "track=true", *small]) == 0
    with sqlite3.connect(uri[len("sqlite:///"):]) as con:
        assert con.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 1


def test_a_failing_run_ends_failed(tmp_path, dataset):
    uri = mlflow_store(tmp_path)
    assert main(["run", f"data.path={dataset}", f"tracking_uri={uri}", f"out={tmp_path / 'o'}",
                 "data.inputs=[X_*]", *LIGHT_EVAL]) == 2
    assert _statuses(uri) == ["FAILED"]


def _statuses(uri: str) -> list[str]:
    with sqlite3.connect(uri[len("sqlite:///"):]) as con:
        return [r[0] for r in con.execute("SELECT status FROM runs")]


N_PARALLEL = 2


@pytest.mark.slow
def test_parallel_runs_on_a_fresh_store_are_all_recorded(tmp_path, dataset):
    """Two, not four nor eight: without the store's file lock four runs failed in 3 of 3 tries,
    two in 2 of 2, and 3 of 3 again in session 50 (the creators race as soon as two start
    together: a disk I/O error in the migrations); each run costs ~7 s of CPU."""
    db = tmp_path / "fresh" / "mlflow.db"                  # no file yet: every process may migrate
    light = [*LIGHT_EVAL, "eval.validation=false"]
    procs = [subprocess.Popen([str(BIN / "thermocomp"), "run", f"data.path={dataset}",
                               f"tracking_uri=sqlite:///{db}", f"out={tmp_path / str(i)}",
                               f"seed={i}", *light], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True) for i in range(N_PARALLEL)]
    results = [p.communicate(timeout=600) for p in procs]
    for p, (_, err) in zip(procs, results):
        assert p.returncode == 0, err[-2000:]
    with sqlite3.connect(db) as con:
        rows = con.execute("SELECT name, status FROM runs").fetchall()
        assert con.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    assert sorted(rows) == sorted((f"mlr-seed{i}", "FINISHED") for i in range(N_PARALLEL))


@pytest.mark.slow
@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, 1)], ids=["SIGTERM"])
def test_a_signalled_run_ends_killed(tmp_path, dataset, sig, code):
    """SIGTERM from outside, as a scheduler stops a job, to a fresh process (Ctrl-C: the next
    test, in this process)."""
    uri = mlflow_store(tmp_path)
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([TEST_PATH, os.environ.get("PYTHONPATH", "")])}
    proc = subprocess.Popen([str(BIN / "thermocomp"), "run", f"data.path={dataset}",
                             f"tracking_uri={uri}", f"out={tmp_path / 'o'}", *LIGHT_EVAL,
                             "model.estimator._target_=test_tracking.Sleepy"],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        while _statuses(uri) != ["RUNNING"]:
            assert proc.poll() is None and time.monotonic() < deadline, proc.stderr.read()
            time.sleep(0.2)
        proc.send_signal(sig)
        proc.wait(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == code
    assert _statuses(uri) == ["KILLED"]
    assert not (tmp_path / "o" / "metrics.json").exists()


def test_a_run_interrupted_by_ctrl_c_ends_killed(tmp_path, dataset):
    uri = mlflow_store(tmp_path)
    # Ctrl-C as in a terminal: an earlier test or library in this worker may have left SIGINT
    # ignored or handled otherwise
    interrupt = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        assert main(["run", f"data.path={dataset}", f"tracking_uri={uri}", f"out={tmp_path / 'o'}",
                     *LIGHT_EVAL, "model.estimator._target_=test_tracking.Interrupted"]) == 1
    finally:
        signal.signal(signal.SIGINT, interrupt)
    assert _statuses(uri) == ["KILLED"]
    assert not (tmp_path / "o" / "metrics.json").exists()


def test_a_locked_store_while_a_run_ends_still_ends_it(tmp_path, dataset, monkeypatch):
    """The store is locked (another process reading it) on the first attempt to write the end
    status: the retry writes it (a retried `mlflow.end_run` had popped the run and ended nothing)."""
    from mlflow import MlflowClient

    real = MlflowClient.set_terminated
    calls = []

    def locked_once(self, run_id, status=None, end_time=None):
        calls.append(status)
        if len(calls) == 1:
            raise sqlite3.OperationalError("database is locked")
        return real(self, run_id, status, end_time)

    monkeypatch.setattr(MlflowClient, "set_terminated", locked_once)
    uri = mlflow_store(tmp_path)
    assert main(["run", f"data.path={dataset}", f"tracking_uri={uri}", f"out={tmp_path / 'o'}",
                 *LIGHT_EVAL]) == 0
    assert calls[:2] == ["FINISHED", "FINISHED"] and _statuses(uri) == ["FINISHED"]


def test_a_lab_column_name_with_units_is_tracked(tmp_path, dataset):
    """A lab's headers carry units ('dX [µm]', 'Spindle [°C]'); mapped through a data config
    they became param names MLflow refuses, and the run ended with a traceback, exit 1."""
    import pandas as pd

    lab = tmp_path / "lab"
    lab.mkdir()
    names = {}
    for f in dataset.iterdir():
        if f.name == "campaigns.csv" or f.suffix != ".csv":
            (lab / f.name).write_bytes(f.read_bytes())
            continue
        df = pd.read_csv(f)
        names = {c: f"{c[2:]} [{'µm' if c.startswith('E_') else '°C'}]" for c in df.columns
                 if c.startswith(("T_", "E_"))}
        df.rename(columns=names).to_csv(lab / f.name, index=False)
    conf = tmp_path / "myconf" / "data"
    conf.mkdir(parents=True)
    mapping = "\n".join(f'  "{lab_name}": {contract}' for contract, lab_name in names.items())
    (conf / "lab.yaml").write_text(f"defaults:\n  - default\ncolumns:\n{mapping}\n")
    uri = mlflow_store(tmp_path)
    assert main(["run", f"hydra.searchpath=[file://{tmp_path / 'myconf'}]", "data=lab",
                 f"data.path={lab}", f"tracking_uri={uri}", f"out={tmp_path / 'out'}",
                 *LIGHT_EVAL]) == 0
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    [run] = client.search_runs([client.get_experiment_by_name("thermocomp").experiment_id])
    assert run.info.status == "FINISHED"
    logged = [k for k in run.data.params if k.startswith("data.columns.")]
    assert logged and all("[" not in k and "µ" not in k and "°" not in k for k in logged)


def _schema(db) -> dict:
    """Each table's columns and constraints (their order aside: Alembic's batch migrations
    write a table's CHECK constraints in an order of their own), and the schema version."""
    with sqlite3.connect(db) as con:
        tables = {name: sorted(line.strip().rstrip(",") for line in sql.splitlines())
                  for name, sql in con.execute("SELECT name, sql FROM sqlite_master "
                                               "WHERE sql IS NOT NULL")}
        return {**tables, "version": con.execute("SELECT * FROM alembic_version").fetchall()}


def test_a_new_store_is_the_migrated_template_copied_with_its_own_default_experiment(
        tmp_path, monkeypatch):
    """Every new store ran MLflow's ~70 Alembic migrations (1.6-2 s of CPU, per test store and
    per first run of a project); they run once per MLflow version, for the template."""
    import mlflow.store.db.utils as db_utils
    from mlflow.store.tracking.sqlalchemy_store import SqlAlchemyStore

    from thermocomp.shell import store

    monkeypatch.setattr(store, "template_folder", lambda: tmp_path / "templates", raising=False)
    (tmp_path / "first").mkdir()
    # what creators killed outright (SIGKILL) leave, of a store and of the template
    import mlflow

    (tmp_path / "templates").mkdir()
    killed = [tmp_path / "first" / ".mlflow.db.x1.creating",
              tmp_path / "templates" / f".store-{mlflow.__version__}.db.x2.creating-journal"]
    for stale in killed:
        stale.write_bytes(b"half")
    store.create_store(tmp_path / "first" / "mlflow.db")           # makes the template
    assert not [p for p in killed if p.exists()]
    migrated = tmp_path / "migrated" / "mlflow.db"        # as MLflow creates a store itself
    migrated.parent.mkdir()
    SqlAlchemyStore(f"sqlite:///{migrated}", migrated.parent.as_uri()).engine.dispose()

    def no_migrations(engine):
        raise AssertionError("a store with the template at hand ran the migrations")

    monkeypatch.setattr(db_utils, "_upgrade_db", no_migrations)
    db = tmp_path / "second" / "mlflow.db"
    db.parent.mkdir()
    store.create_store(db)
    assert _schema(db) == _schema(migrated)
    with sqlite3.connect(db) as con:
        assert con.execute("SELECT experiment_id, name, artifact_location FROM experiments"
                           ).fetchall() == [(0, "Default", (db.parent / "0").as_uri())]
    assert sorted(p.name for p in db.parent.iterdir()) == ["mlflow.db"]   # no temp file left


def test_a_store_another_run_holds_locked_a_moment_is_read_not_refused(tmp_path, monkeypatch):
    """Another run writing the store locks it longer than SQLite's wait (5 s; here 0.05 s, the
    lock 0.3 s); the schema check read that as damage ("not an SQLite database (database is
    locked)": a fresh-clone CI's two parallel runs on a fresh store, lead71)."""
    import threading
    from contextlib import closing

    from mlflow.store.tracking.dbmodels import models  # noqa: F401  (imported before the lock)

    from thermocomp.shell import store

    connect = sqlite3.connect
    monkeypatch.setattr(store.sqlite3, "connect", lambda *a, **k: connect(*a, **{**k, "timeout": 0.05}))

    db = tmp_path / "mlflow.db"
    with closing(sqlite3.connect(db)) as con:
        con.execute("CREATE TABLE t (x)")
    writer = sqlite3.connect(db, check_same_thread=False, isolation_level=None)
    writer.execute("BEGIN EXCLUSIVE")
    release = threading.Timer(0.3, lambda: writer.execute("COMMIT"))
    release.start()
    try:
        store.check_schema(f"sqlite:///{db}", db)    # no alembic_version: nothing else to check
    finally:
        release.join()
        writer.close()
