"""Sweeps on other engines: a local Ray cluster (``hydra/launcher=ray``) and submitit's local
executor (the SLURM launcher's code path, ``hydra/launcher=submitit_local``).  Every job is one
MLflow child run under the sweep's parent run in a fresh SQLite store.

In ``make test``: what thermocomp contributes to a Ray sweep, in this process (Ray's calls
faked: a job's arguments go through cloudpickle as Ray ships them, and the job sees the runtime
environment's variables, not this process's); and the launcher configs composing.  A real
local Ray cluster and a real submitit process (~60 s of CPU for the two: Ray's daemons, a
process importing the stack) are ``full``."""

from __future__ import annotations

import json
import os
import sqlite3

import pytest

from conftest import thermocomp
from test_deploy import LIGHT_EVAL, mlflow_store, write_small_dataset
from thermocomp.shell.tracking import PARENT_ENV, SWEEP_TAG


@pytest.fixture(scope="session")
def dataset(tmp_path_factory):
    return write_small_dataset(tmp_path_factory.mktemp("launchers") / "small")


def _runs(uri: str):
    import mlflow

    mlflow.set_tracking_uri(uri)
    runs = mlflow.search_runs(experiment_names=["thermocomp"])
    return runs[runs[f"tags.{SWEEP_TAG}"] == "parent"], runs[runs["tags.mlflow.parentRunId"].notna()]


def _sweep(tmp_path, dataset, *overrides: str, subprocess: bool = True):
    uri = mlflow_store(tmp_path)
    sweep_dir = tmp_path / "sweep"
    proc = thermocomp("run", "-m", f"data.path={dataset}", f"tracking_uri={uri}", *LIGHT_EVAL,
                      f"hydra.sweep.dir={sweep_dir}", *overrides, subprocess=subprocess)
    return (uri, sweep_dir, proc, *_runs(uri))


class RayInProcess:
    """The calls Hydra's Ray launcher makes (``init``, ``remote``, ``get``), run in this process:
    each job's arguments are cloudpickled and loaded again, as Ray ships them to a worker, and
    the job runs with the variables of ``init``'s runtime environment as a worker has them
    (this process's own ``THERMOCOMP_PARENT_RUN_ID`` hidden)."""

    def __init__(self):
        self.init_kwargs = None
        self.remote_options = None
        self.jobs = 0

    def is_initialized(self) -> bool:
        return self.init_kwargs is not None

    def init(self, **kwargs):
        self.init_kwargs = kwargs

    def get(self, result):
        return result

    def remote(self, *function, **options):
        def wrap(job):
            return _Remote(self, job)
        if function:                       # ray.remote(fn), no options
            return wrap(function[0])
        self.remote_options = options
        return wrap


class _Remote:
    def __init__(self, ray, job):
        self.ray, self.job = ray, job

    def remote(self, **kwargs):
        import cloudpickle
        from hydra.core.plugins import Plugins
        from hydra.core.singleton import Singleton

        shipped = cloudpickle.loads(cloudpickle.dumps(kwargs))
        # A worker installs the shipped Hydra state, and Hydra then scans its plugins afresh,
        # which executes their modules again (load_module): in a worker process the first time,
        # here a second time, leaving this process's plugin classes stale (the next joblib sweep
        # of the process could not pickle a job: "not the same object as
        # hydra_plugins.thermocomp_conf.conf_source.parsed"). This process's scan stands in.
        shipped["singleton_state"]["instances"][Plugins] = Plugins.instance()
        worker_env = self.ray.init_kwargs["runtime_env"]["env_vars"]
        here, hydra_here = dict(os.environ), Singleton.get_state()
        os.environ.pop(PARENT_ENV, None)
        os.environ.update(worker_env)
        try:
            self.ray.jobs += 1
            return self.job(**shipped)
        finally:
            os.environ.clear()
            os.environ.update(here)
            hydra_here["instances"][Plugins] = Plugins.instance()
            Singleton.set_state(hydra_here)      # the worker's state stays in the worker

def test_a_ray_sweep_hands_its_jobs_the_parent_run_through_the_runtime_environment(
        tmp_path, dataset, monkeypatch):
    """What thermocomp adds to Ray's launcher: its init settings, a task that survives
    cloudpickle, and the parent run id a worker on any node gets from the runtime environment
    (resolved after the sweep's callback made the parent run).  The real local cluster:
    test_ray_sweep_on_a_local_cluster_makes_four_children_under_one_parent (full)."""
    import ray

    fake = RayInProcess()
    for name in ("init", "is_initialized", "remote", "get"):
        monkeypatch.setattr(ray, name, getattr(fake, name))
    uri, sweep_dir, proc, parents, children = _sweep(
        tmp_path, dataset, "model=mlr,pcr", "hydra/launcher=ray",
        "hydra.launcher.ray.init.num_cpus=2", subprocess=False)
    init = fake.init_kwargs
    assert init["address"] is None and init["num_cpus"] == 2 and init["include_dashboard"] is False
    assert fake.remote_options == {"num_cpus": 1, "max_retries": 0} and fake.jobs == 2
    assert len(parents) == 1 and len(children) == 2
    parent_id = parents["run_id"].iloc[0]
    assert init["runtime_env"]["env_vars"][PARENT_ENV] == parent_id
    assert parents["tags.launcher"].iloc[0] == "RayLauncher"
    assert (children["tags.mlflow.parentRunId"] == parent_id).all()
    assert (children["status"] == "FINISHED").all() and parents["status"].iloc[0] == "FINISHED"
    assert sorted(children["params.model.name"]) == ["mlr", "pcr"]
    assert parents["metrics.sweep.jobs"].iloc[0] == 2
    assert json.loads((sweep_dir / "sweep.json").read_text())["parent_run_id"] == parent_id
    assert all((sweep_dir / str(job) / "metrics.json").is_file() for job in range(2))


@pytest.mark.slow
@pytest.mark.full(reason="a real local Ray cluster (~40 s of CPU); in make test: "
                         "test_a_ray_sweep_hands_its_jobs_the_parent_run_through_the_runtime_environment "
                         "(the launcher's calls in process) and test_sweep's joblib workers")
def test_ray_sweep_on_a_local_cluster_makes_four_children_under_one_parent(tmp_path, dataset):
    """Four jobs (was six) on a two-CPU cluster: more jobs than CPUs, so Ray queues some, and two
    at a time write to the one SQLite store."""
    uri, sweep_dir, proc, parents, children = _sweep(
        tmp_path, dataset, "model=mlr,pcr", "seed=1,2", "hydra/launcher=ray",
        "hydra.launcher.ray.init.num_cpus=2")
    assert "Started a local Ray instance" in proc.stderr + proc.stdout   # no address: ray.init()
    assert "(_run_job pid=" in proc.stderr + proc.stdout                 # jobs ran in Ray workers
    assert len(parents) == 1 and len(children) == 4
    parent_id = parents["run_id"].iloc[0]
    assert parents["tags.launcher"].iloc[0] == "RayLauncher"
    assert (children["tags.mlflow.parentRunId"] == parent_id).all()
    assert (children["status"] == "FINISHED").all() and parents["status"].iloc[0] == "FINISHED"
    assert sorted(zip(children["params.model.name"], children["params.seed"].astype(int))) == [
        (m, s) for m in ("mlr", "pcr") for s in (1, 2)]
    assert children["metrics.E_Z.val.rmse"].notna().all()
    assert parents["metrics.sweep.jobs"].iloc[0] == 4
    assert json.loads((sweep_dir / "sweep.json").read_text())["parent_run_id"] == parent_id
    for job in range(4):
        assert (sweep_dir / str(job) / "metrics.json").is_file()
    assert "database is locked" not in proc.stderr
    with sqlite3.connect(uri[len("sqlite:///"):]) as con:
        assert con.execute("PRAGMA integrity_check").fetchone()[0] == "ok"


@pytest.mark.slow
@pytest.mark.full(reason="a process of its own importing the stack (~15 s of CPU); in make test: "
                         "test_a_ray_sweep_hands_its_jobs_the_parent_run_through_the_runtime_environment "
                         "(a job through cloudpickle, as submitit ships it) and test_sweep's "
                         "joblib workers (jobs in processes of their own, children of the parent)")
def test_submitit_local_executor_runs_a_sweep_job_in_a_process_of_its_own(tmp_path, dataset):
    """One job (was two, ~7 s of CPU each: a process importing the stack): what the launcher
    does with several, one child run per job under one parent, is the Ray test's above."""
    uri, sweep_dir, proc, parents, children = _sweep(
        tmp_path, dataset, "model=pcr", "hydra/launcher=submitit_local")
    assert len(parents) == 1 and len(children) == 1
    assert parents["tags.launcher"].iloc[0] == "LocalLauncher"
    assert (children["tags.mlflow.parentRunId"] == parents["run_id"].iloc[0]).all()
    assert (children["status"] == "FINISHED").all() and parents["status"].iloc[0] == "FINISHED"
    assert list(children["params.model.name"]) == ["pcr"]
    # submitit ran the job as its own process and kept its log beside the sweep
    logs = list((sweep_dir / ".submitit").rglob("*_log.out"))
    assert len(logs) == 1 and "pcr" in logs[0].read_text()


def test_launcher_and_sweeper_configs_compose():
    from hydra import compose, initialize_config_dir

    from thermocomp.base.paths import conf_dir

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        ray = compose("config", ["hydra/launcher=ray"], return_hydra_config=True)
        local = compose("config", ["hydra/launcher=submitit_local"], return_hydra_config=True)
        optuna = compose("config", ["hydra/sweeper=optuna_arx"], return_hydra_config=True)
    assert ray.hydra.launcher._target_.endswith("RayLauncher")
    assert ray.hydra.launcher.ray.init.address is None          # local cluster unless configured
    env = ray.hydra.launcher.ray.init.runtime_env.env_vars
    assert "THERMOCOMP_PARENT_RUN_ID" in env                     # the parent run reaches any node
    assert local.hydra.launcher._target_.endswith("LocalLauncher")
    assert optuna.hydra.sweeper._target_.endswith("OptunaSweeper")
    sweeper = optuna.hydra.sweeper
    assert sweeper.params.model == "arx" and str(sweeper.direction).endswith("minimize")

