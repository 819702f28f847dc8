"""Process faults against the MLflow store and the figure workers (hostile matrix).

Two ``promote``s at once, a ``promote`` or a ``run`` killed outright (SIGKILL), a store whose
creation is cut short, tracking URIs MLflow would retry or fail on for minutes: the champion
is the best run, no run is left RUNNING by a dead process, no worker outlives its parent,
no half-created store, one line and exit 2.
"""

from __future__ import annotations

import json
import os
import signal
import sqlite3
import subprocess
import sys
import textwrap
import time
from contextlib import closing
from pathlib import Path

import psutil
import pytest

import thermocomp
from conftest import LIGHT, refused
from conftest import thermocomp as tc
from test_deploy import mlflow_store
from test_hostile import FAST, make_dataset, snapshot
from thermocomp.shell import store as store_module
from thermocomp.shell.cli import main

SRC = Path(thermocomp.__file__).resolve().parents[1]
UNTRACKED = [a for a in FAST if not a.startswith("track=")]


def _client(uri):
    from mlflow import MlflowClient

    return MlflowClient(uri)


def _wait_for(condition, procs, limit_s: float = 300.0) -> None:
    """Poll ``condition`` until true or one of ``procs`` has exited (a bound, not a timing)."""
    deadline = time.monotonic() + limit_s
    while not condition():
        if any(p.poll() is not None for p in procs) or time.monotonic() > deadline:
            return
        time.sleep(0.02)


# -- promote: one decision at a time, no run status touched ----------------------------------


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    """A store with a two-run sweep on a small dataset; the runs' validation RMSE differ."""
    root = tmp_path_factory.mktemp("promote_race")
    ds = make_dataset(root / "ds", rows=60)
    uri = mlflow_store(root)               # a copy of a migrated store: its creation is not the point
    tc("run", "-m", f"data.path={ds}", f"tracking_uri={uri}", *LIGHT, f"out={root / 'out'}",
       "data.inputs=[T_0],[T_0,T_amb]", f"hydra.sweep.dir={root / 'sweep'}", cwd=root)
    client = _client(uri)
    runs = [r for r in client.search_runs([client.get_experiment_by_name("thermocomp")
                                           .experiment_id])
            if r.data.tags.get("thermocomp.sweep") != "parent"]
    scores = {r.info.run_id: r.data.metrics["E_X.val.rmse"] for r in runs}
    assert len(scores) == 2 and len(set(scores.values())) == 2
    best = min(scores, key=scores.get)
    return {"root": root, "uri": uri, "runs": list(scores), "best": best,
            "args": [f"data.path={ds}", f"tracking_uri={uri}", f"compare.sweep={root / 'sweep'}"]}


# A promote whose registration can be held (pause) or cut (kill): files in PROBE_DIR say where
# it is.
PROBE = textwrap.dedent("""
    import os, signal, sys, time
    from pathlib import Path

    import thermocomp.apps.deploy.pyfunc as pyfunc
    from thermocomp.shell.cli import main

    mode, here = os.environ["PROBE_MODE"], Path(os.environ["PROBE_DIR"])
    register = pyfunc.log_compensator

    def log_compensator(*args, **kwargs):
        if mode == "kill":
            os.kill(os.getpid(), signal.SIGKILL)
        if mode == "pause":
            (here / "registering").touch()
            while not (here / "go").exists():
                time.sleep(0.02)
        return register(*args, **kwargs)

    pyfunc.log_compensator = log_compensator
    sys.exit(main(sys.argv[1:]))
""")


def _promote(sweep, tmp_path, mode: str, tag: str, model_name: str) -> subprocess.Popen:
    probe = tmp_path / "probe.py"
    probe.write_text(PROBE)
    env = {**os.environ, "PROBE_MODE": mode, "PROBE_DIR": str(tmp_path),
           "PYTHONPATH": os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")])}
    return subprocess.Popen([sys.executable, str(probe), "promote", *sweep["args"],
                             f"promote.model_name={model_name}", f"out={tmp_path / tag}"],
                            cwd=sweep["root"], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def _statuses(sweep) -> dict:
    client = _client(sweep["uri"])
    return {r: client.get_run(r).info.status for r in sweep["runs"]}


@pytest.mark.slow
def test_two_promotes_at_once_leave_the_best_run_champion_and_decide_once(sweep, tmp_path,
                                                                          monkeypatch):
    """The first in a process of its own, held inside its registration (so inside the registry
    lock); the second in this process (a second interpreter importing the stack cost ~7 s of
    CPU), made to wait for that lock while the first holds it: the lock is the OS's between
    two processes either way."""
    from contextlib import contextmanager
    from threading import Event, Thread

    import thermocomp.shell.stages.promote as stage

    name = "race"
    first = _promote(sweep, tmp_path, "pause", "first", name)     # held inside its registration
    _wait_for(lambda: (tmp_path / "registering").exists(), [first])
    assert (tmp_path / "registering").exists(), first.communicate()[1][-3000:]
    lock = stage.registry_lock

    @contextmanager
    def visible_lock(uri):
        (tmp_path / "waiting").touch()
        with lock(uri):
            yield
    monkeypatch.setattr(stage, "registry_lock", visible_lock)

    second_ended = Event()

    def release_the_first_once_the_second_waits():   # (or has ended without waiting)
        _wait_for(lambda: (tmp_path / "waiting").exists() or second_ended.is_set(), [first])
        (tmp_path / "go").touch()
    releaser = Thread(target=release_the_first_once_the_second_waits, daemon=True)
    releaser.start()
    try:
        second = tc("promote", *sweep["args"], f"promote.model_name={name}",
                    f"out={tmp_path / 'second'}", cwd=sweep["root"], check=False)
    finally:
        second_ended.set()
        releaser.join(timeout=60)
    out = first.communicate(timeout=600)
    assert [first.returncode, second.returncode] == [0, 0], out[1][-2000:] + second.stderr[-2000:]
    assert (tmp_path / "waiting").exists() and (tmp_path / "go").exists()
    reports = [json.loads((tmp_path / t / "promote.json").read_text()) for t in ("first", "second")]
    # the second chose while the first registered: the best run is still FINISHED, so both
    # chose it, and the second compared against the first's decision
    assert [r["run_id"] for r in reports] == [sweep["best"]] * 2
    assert [r["reason"] for r in reports].count("no champion yet") == 1
    champion = _client(sweep["uri"]).get_model_version_by_alias(name, "champion")
    assert champion.tags["source_run_id"] == sweep["best"]
    assert set(_statuses(sweep).values()) == {"FINISHED"}


@pytest.mark.slow
def test_a_promote_killed_while_registering_changes_no_run_and_the_next_picks_the_best(
        sweep, tmp_path):
    name = "killed"
    killed = _promote(sweep, tmp_path, "kill", "killed", name)
    killed.communicate(timeout=600)
    assert killed.returncode == -signal.SIGKILL
    assert set(_statuses(sweep).values()) == {"FINISHED"}
    # the next promote in this process: the killed one's process boundary is the point, not its
    tc("promote", *sweep["args"], f"promote.model_name={name}", f"out={tmp_path / 'again'}",
       cwd=sweep["root"])                                 # exit 0 (checked)
    report = json.loads((tmp_path / "again" / "promote.json").read_text())
    assert report["run_id"] == sweep["best"] and report["moved"]
    champion = _client(sweep["uri"]).get_model_version_by_alias(name, "champion")
    assert champion.tags["source_run_id"] == sweep["best"]


# -- a run killed outright: no worker left, the run marked KILLED by the next command ----------

WORKERS = textwrap.dedent("""
    import sys, time
    from thermocomp.core.figures.plots import FigurePool

    with FigurePool(workers=2) as pool:
        for _ in range(4):
            pool.submit(time.sleep, 0.01)
        print("ready", flush=True)
        time.sleep(600)
""")


def _orphans_after_kill(proc: subprocess.Popen, workers: list) -> list[str]:
    """SIGKILL ``proc``; the ``workers`` still alive (not zombies) 30 s later, killed then."""
    proc.kill()
    proc.wait()
    _, alive = psutil.wait_procs(workers, timeout=30)
    left = []
    for w in alive:
        try:
            if w.status() != psutil.STATUS_ZOMBIE:
                left.append(f"{w.pid} {w.status()} {' '.join(w.cmdline())[:100]}")
                w.kill()          # do not leave them to the next test
        except psutil.NoSuchProcess:
            pass
    return left


def test_figure_workers_die_with_a_sigkilled_parent():
    proc = subprocess.Popen([sys.executable, "-c", WORKERS], stdout=subprocess.PIPE, text=True,
                            env={**os.environ, "PYTHONPATH": str(SRC)})
    assert proc.stdout.readline().strip() == "ready"
    workers = psutil.Process(proc.pid).children()
    assert len(workers) == 2
    assert _orphans_after_kill(proc, workers) == []


@pytest.mark.skipif(len(os.sched_getaffinity(0)) < 2, reason="figures are drawn in workers on 2+ CPUs")
def test_a_run_sigkilled_during_its_figures_leaves_no_worker_and_ends_killed(tmp_path):
    ds = make_dataset(tmp_path / "ds", rows=60)
    uri = mlflow_store(tmp_path)           # migrated already: the child spends its time drawing
    common = [f"data.path={ds}", f"tracking_uri={uri}", "eval.mutual_prediction=false",
              "eval.ati_baselines=false", "eval.validation=false"]   # the figures sooner
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    run = subprocess.Popen([sys.executable, "-m", "thermocomp", "run", *common, "plots=all",
                            f"out={tmp_path / 'killed'}", "name=killed"], cwd=tmp_path, env=env,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    parent = psutil.Process(run.pid)

    client = _client(uri)

    def forked():          # children with the run's own command line
        try:
            return [c for c in parent.children() if c.cmdline() == parent.cmdline()]
        except psutil.Error:
            return []

    def tracked():         # the run's row, committed before any figure is drawn
        exp = client.get_experiment_by_name("thermocomp")
        return exp and client.search_runs([exp.experiment_id], "tags.run_name = 'killed'")

    # Such a child is a figure worker only once the run is in the store: MLflow's git helper,
    # spawned inside start_run, shows the parent's command line until it execs git (under load
    # the kill once landed in that window, before the run existed).
    _wait_for(lambda: forked() and tracked(), [run])
    workers = forked()
    assert workers and tracked(), "the run ended before drawing its figures"
    assert _orphans_after_kill(run, workers) == []
    killed = tracked()[0]
    assert killed.info.status == "RUNNING", "the run ended before the kill"  # SIGKILL: no word
    assert main(["run", *common, "plots=none", f"out={tmp_path / 'next'}", "name=next"]) == 0
    assert client.get_run(killed.info.run_id).info.status == "KILLED"
    statuses = {r.data.tags["run_name"]: r.info.status for r in client.search_runs(
        [killed.info.experiment_id])}
    assert statuses == {"killed": "KILLED", "next": "FINISHED"}


def _children_when(proc: subprocess.Popen, ready) -> list:
    """``proc``'s child processes once ``ready(children)`` holds (or ``proc`` has ended)."""
    parent = psutil.Process(proc.pid)

    def children():
        try:
            return parent.children(recursive=True)
        except psutil.Error:
            return []
    _wait_for(lambda: ready(children()), [proc])
    return children()


def _loky(children) -> list:
    return [c for c in children if "loky" in " ".join(c.cmdline())]


# joblib.Parallel as the stages make it (design, the fleet's groups and simulator), its tasks
# outliving any test
PARALLEL = textwrap.dedent("""
    import time
    from joblib import delayed
    from thermocomp.base.lifetime import parallel

    parallel(2)(delayed(time.sleep)(600) for _ in range(4))
""")


def test_joblib_workers_of_a_sigkilled_process_die_with_it():
    """lifetime.parallel's workers, in a process that imports nothing else (the stage itself,
    its imports and its own workers' ~5 s of CPU: the next test, full)."""
    proc = subprocess.Popen([sys.executable, "-c", PARALLEL], env={**os.environ, "PYTHONPATH": str(SRC)},
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    children = _children_when(proc, lambda c: len(_loky(c)) >= 2)
    assert len(_loky(children)) >= 2, "the process ended before starting its workers"
    assert _orphans_after_kill(proc, children) == []


@pytest.mark.slow
@pytest.mark.full(reason="a stage's process and its workers importing the stack; in make test: "
                         "test_joblib_workers_of_a_sigkilled_process_die_with_it (the stages' "
                         "lifetime.parallel)")
def test_joblib_workers_of_a_sigkilled_stage_die_with_it(tmp_path):
    design = subprocess.Popen([sys.executable, "-m", "thermocomp", "design", "design.n_machines=2000",
                               "design.n_jobs=2", "track=false", "plots=none",
                               f"out={tmp_path / 'design'}"], cwd=tmp_path,
                              env={**os.environ, "PYTHONPATH": str(SRC)},
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    children = _children_when(design, lambda c: len(_loky(c)) >= 2)
    assert len(_loky(children)) >= 2, "design ended before starting its workers"
    assert _orphans_after_kill(design, children) == []


@pytest.mark.slow
def test_joblib_sweep_jobs_die_with_a_sigkilled_sweep(tmp_path):
    ds = make_dataset(tmp_path / "ds")
    sweep_dir = tmp_path / "sweep"
    sweep = subprocess.Popen([sys.executable, "-m", "thermocomp", "run", "-m", "hydra/launcher=joblib",
                              "hydra.launcher.n_jobs=2", f"data.path={ds}", *FAST, "seed=0,1,2,3",
                              f"hydra.sweep.dir={sweep_dir}", f"out={tmp_path / 'out'}"],
                             cwd=tmp_path, env={**os.environ, "PYTHONPATH": str(SRC)},
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    started = lambda _: len(list(sweep_dir.glob("*/.hydra/overrides.yaml"))) >= 2  # noqa: E731
    children = _children_when(sweep, started)
    assert started(None) and _loky(children), "the sweep ended before its jobs started"
    assert _orphans_after_kill(sweep, children) == []


def test_a_run_of_a_live_process_is_not_marked_killed(tmp_path):
    from thermocomp.shell.store import mark_orphan_runs, process_tags

    uri = mlflow_store(tmp_path)
    client = _client(uri)
    exp = client.create_experiment("e", artifact_location=(tmp_path / "e").as_uri())
    mine = client.create_run(exp, tags=process_tags()).info.run_id
    reused = client.create_run(exp, tags={**process_tags(), "thermocomp.process_start": "1.0"})
    assert mark_orphan_runs(uri) == [reused.info.run_id]   # same pid, another start: pid reused
    assert client.get_run(mine).info.status == "RUNNING"


# -- the store is created whole or not at all ----------------------------------------------


def test_a_store_creation_cut_short_leaves_no_store_and_the_next_run_creates_it(
        tmp_path, monkeypatch, capsys):
    import mlflow.store.db.utils as db_utils

    ds = make_dataset(tmp_path / "ds")
    store = tmp_path / "mlruns"
    args = [f"data.path={ds}", f"tracking_uri=sqlite:///{store / 'mlflow.db'}", *UNTRACKED]

    def disk_full(engine):       # the initial tables are there, the migrations fail
        raise sqlite3.OperationalError("database or disk is full")

    templates = tmp_path / "templates"        # no migrated template yet: the migrations run
    monkeypatch.setattr(store_module, "template_folder", lambda: templates)
    monkeypatch.setattr(db_utils, "_upgrade_db", disk_full)
    assert main(["run", *args, f"out={tmp_path / 'first'}"]) != 0
    assert sorted(p.name for p in store.iterdir() if not p.name.endswith(".lock")) == []
    assert not list(templates.glob("*.db"))        # nor a template cut short
    monkeypatch.undo()
    capsys.readouterr()
    assert main(["run", *args, f"out={tmp_path / 'second'}"]) == 0
    client = _client(f"sqlite:///{store / 'mlflow.db'}")
    exp = client.get_experiment_by_name("thermocomp")
    assert [r.info.status for r in client.search_runs([exp.experiment_id])] == ["FINISHED"]


def _old_schema(db: Path) -> None:
    with closing(sqlite3.connect(db)) as con:
        con.execute("UPDATE alembic_version SET version_num = 'c8d9e0f1a2b3'")
        con.commit()


def _half_migrated(db: Path) -> None:       # as a migration cut short leaves it
    _old_schema(db)
    with closing(sqlite3.connect(db)) as con:
        con.execute("DROP TABLE latest_metrics")
        con.commit()


def _not_a_database(db: Path) -> None:
    db.write_bytes(b"\x7fELF" + bytes(range(256)) * 8)


@pytest.mark.parametrize("damage, says", [(_old_schema, "not a complete store"),
                                          (_half_migrated, "not a complete store"),
                                          (_not_a_database, "not an SQLite database")],
                         ids=["old-schema", "half-migrated", "not-a-database"])
def test_a_damaged_store_is_said_in_one_line_and_left_as_it_is(tmp_path, capsys, damage, says):
    from test_deploy import mlflow_store

    uri = mlflow_store(tmp_path)
    db = Path(uri[len("sqlite:///"):])
    damage(db)
    ds = make_dataset(tmp_path / "ds")
    before = db.read_bytes()
    refused(["run", f"data.path={ds}", f"tracking_uri={uri}", f"out={tmp_path / 'out'}",
             *UNTRACKED], capsys, f"tracking_uri={uri}", says)
    assert db.read_bytes() == before and not (tmp_path / "out").exists()


# -- tracking URIs MLflow would retry or fail on at length: one line, exit 2, nothing written -


@pytest.mark.parametrize("uri, says", [
    ("sqlite:///", "needs a file path"),
    ("sqlite://", "needs a file path"),
    ("sqlite:///:memory:", "needs a file path"),
    ("sqlite:///{tmp}/mlruns/", "needs a file path"),
    ("databricks", "no Databricks credentials"),
    ("databricks://nobody", "no Databricks credentials"),
    ("postgresql://user:secret@127.0.0.1:{port}/mlflow", "no database server answers"),
], ids=["sqlite-no-path", "sqlite-memory", "sqlite-memory-named", "sqlite-folder",
        "databricks", "databricks-profile", "postgresql-closed-port"])
def test_a_tracking_uri_mlflow_cannot_use_is_refused_in_one_line(tmp_path, capsys, monkeypatch,
                                                                 uri, says):
    from conftest import free_port

    for var in [v for v in os.environ if v.startswith("DATABRICKS_")]:
        monkeypatch.delenv(var)
    monkeypatch.setenv("HOME", str(tmp_path))            # no ~/.databrickscfg
    ds = make_dataset(tmp_path / "ds")
    out = tmp_path / "out"
    uri = uri.format(tmp=tmp_path, port=free_port())
    before = snapshot(out, tmp_path / "mlruns")
    line = refused(["run", f"data.path={ds}", f"out={out}", f"tracking_uri={uri}", *UNTRACKED],
                   capsys, "tracking_uri=", says)
    assert "secret" not in line
    assert snapshot(out, tmp_path / "mlruns") == before
