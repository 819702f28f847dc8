"""Sweeps: `thermocomp run -m` with the joblib launcher -> one MLflow parent run, one child per job,
a comparison table.  (Parallel runs on one fresh SQLite store: test_tracking.)"""

from __future__ import annotations

import json
import shutil
import sqlite3

import pandas as pd
import pytest

from conftest import copy_project, thermocomp
from test_deploy import LIGHT_EVAL, mlflow_store, write_small_dataset
from thermocomp.base.files import folder_digest
from thermocomp.shell.cli import main
from thermocomp.shell.tracking import SWEEP_TAG, _is_locked, retry_locked


@pytest.fixture(scope="session")
def dataset(tmp_path_factory):
    return write_small_dataset(tmp_path_factory.mktemp("sweep") / "small")


def _sweep(tmp_path, dataset, n_jobs: int, *overrides: str):
    uri = mlflow_store(tmp_path)
    sweep_dir = tmp_path / "sweep"
    proc = thermocomp("run", "-m", f"data.path={dataset}", f"tracking_uri={uri}", *LIGHT_EVAL,
                      "hydra/launcher=joblib", f"hydra.launcher.n_jobs={n_jobs}",
                      f"hydra.sweep.dir={sweep_dir}", *overrides)
    import mlflow

    mlflow.set_tracking_uri(uri)
    runs = mlflow.search_runs(experiment_names=["thermocomp"])
    parents = runs[runs[f"tags.{SWEEP_TAG}"] == "parent"]
    children = runs[runs["tags.mlflow.parentRunId"].notna()]
    return uri, sweep_dir, proc, parents, children


@pytest.fixture(scope="module")
def four_jobs(tmp_path_factory, dataset):
    """A four-job joblib sweep on two workers (what the module's last test runs a second sweep
    after, in this process): ``(folder, _sweep's results)``."""
    root = tmp_path_factory.mktemp("four_jobs")
    return root, _sweep(root, dataset, 2, "model.estimator.fit_intercept=true,false",
                        "data.inputs=[T_*],[T_1]")


@pytest.mark.slow
def test_four_job_joblib_sweep_makes_one_parent_four_children_and_a_table(four_jobs, dataset, capsys):
    tmp_path, (uri, sweep_dir, proc, parents, children) = four_jobs
    assert len(parents) == 1 and len(children) == 4
    parent_id = parents["run_id"].iloc[0]
    assert (children["tags.mlflow.parentRunId"] == parent_id).all()
    assert (children["status"] == "FINISHED").all() and parents["status"].iloc[0] == "FINISHED"
    assert children["metrics.E_Z.test.rmse"].notna().all()
    assert children["metrics.fit_time_s"].notna().all()
    combos = set(zip(children["params.model.estimator.fit_intercept"], children["params.data.inputs"]))
    assert len(combos) == 4                                     # every combination ran once
    # each child is named from its own overrides, each job folder says what ran
    assert sorted(children["tags.mlflow.runName"]) == sorted(
        f"mlr-fit_intercept={b}-inputs={i}" for b in ("true", "false") for i in ("T_*", "T_1"))
    for job in range(4):
        said = (sweep_dir / str(job) / ".hydra" / "overrides.yaml").read_text().lower()
        run = children[children["params.out"] == str(sweep_dir / str(job))]
        intercept = run["params.model.estimator.fit_intercept"].iloc[0].lower()
        assert len(run) == 1 and f"model.estimator.fit_intercept={intercept}" in said
    assert parents["metrics.sweep.jobs"].iloc[0] == 4
    assert json.loads((sweep_dir / "sweep.json").read_text())["parent_run_id"] == parent_id

    # The table printed and saved when the sweep ends: best (lowest validation RMSE) first,
    # the test figures beside it, labelled as reported only.
    assert "val_rmse" in proc.stdout and "test:rsd_mean" in proc.stdout and "test:e_p95_1h" in proc.stdout
    assert "reported, not used to choose" in proc.stdout
    table = pd.read_csv(sweep_dir / "compare.csv")
    assert sorted(table["run_id"]) == sorted(children["run_id"])
    assert table["val_rmse"].is_monotonic_increasing and table["rsd_mean"].notna().all()
    assert (table["val_method"] == "blocked forward (2 folds)").all()   # test last: the later 2 of 4
    assert table["e_p95_1h"].notna().all() and table["e_p95_8h"].isna().all()  # 2 h campaigns
    assert "['T_1']" in table["settings"].iloc[-1]      # one sensor cannot explain E_X: worst
    summary = json.loads((sweep_dir / "compare.json").read_text())
    assert summary["best"]["run_id"] == table["run_id"].iloc[0] and summary["ranked_by_validation"]
    assert "rsd_mean" in summary["reported_not_used_to_choose"]
    # persistence does not depend on the model: one baseline row below the ranked runs, not ranked
    assert [b["model"] for b in summary["baselines"]] == ["persistence (baseline)"]
    md = (sweep_dir / "compare.md").read_text().strip().splitlines()
    assert "persistence (baseline)" in md[-1] and "persistence" not in "".join(table["model"].astype(str))
    from mlflow import MlflowClient

    logged = {a.path for a in MlflowClient(uri).list_artifacts(parent_id, "compare")}
    assert logged == {"compare/compare.csv", "compare/compare.md", "compare/compare.json"}

    # `thermocomp compare` on the same sweep, another criterion, its own folder.
    out = tmp_path / "cmp"
    assert main(["compare", f"tracking_uri={uri}", f"compare.sweep={sweep_dir}",
                 "compare.sort_by=rms_reduction_pct", "compare.target=E_X", f"compare.out={out}"]) == 0
    again = pd.read_csv(out / "compare.csv")
    assert again["rms_reduction_pct"].is_monotonic_decreasing and len(again) == 4
    assert (out / "compare.md").read_text().startswith("| status")
    assert main(["compare", f"tracking_uri={uri}", "compare.sort_by=nope"]) == 2
    capsys.readouterr()
    assert main(["compare", f"tracking_uri={uri}", "compare.descending=maybe"]) == 2  # was: truthy
    assert "compare.descending='maybe': must be null or true or false" in capsys.readouterr().err
    # tracebacks before: the sweep read through another store, a file in compare.out's place
    other_store = mlflow_store(tmp_path / "other_store")   # empty, migrated: not this sweep's
    assert main(["compare", f"tracking_uri={other_store}", f"compare.sweep={sweep_dir}"]) == 2
    assert "tracked in another store" in capsys.readouterr().err
    afile = tmp_path / "afile"
    afile.write_text("")
    assert main(["compare", f"tracking_uri={uri}", f"compare.sweep={sweep_dir}",
                 f"compare.out={afile}"]) == 2
    assert "exists and is not a folder" in capsys.readouterr().err

    # promote the sweep's best: only with the dataset its runs were scored on, and only once
    other = write_small_dataset(tmp_path / "other", seed=1)
    promote = ["promote", f"tracking_uri={uri}", f"compare.sweep={sweep_dir}", f"out={tmp_path / 'p'}"]
    assert main([*promote, f"data.path={other}"]) == 2
    err = capsys.readouterr().err
    assert f"data.path={other}" in err and "was not scored by any run of sweep" in err
    assert folder_digest(other)[:12] in err and folder_digest(dataset)[:12] in err
    assert main([*promote, f"data.path={dataset}"]) == 0
    first = json.loads((tmp_path / "p" / "promote.json").read_text())
    assert first["run_id"] == table["run_id"].iloc[0] and first["moved"]
    capsys.readouterr()
    assert main([*promote, f"data.path={dataset}"]) == 0
    assert f"already champion: version {first['version']}" in capsys.readouterr().out
    again = json.loads((tmp_path / "p" / "promote.json").read_text())
    assert not again["registered"] and again["version"] == first["version"]
    assert len(MlflowClient(uri).search_model_versions("name='thermocomp-compensator'")) == 1


@pytest.fixture(scope="module")
def second_sweep(tmp_path_factory, four_jobs, dataset):
    """A second two-job joblib sweep on two workers in this process, after four_jobs', its table
    sent to ``compare.out`` and an ``out=`` given: ``(folder, _sweep's results)``.  Two tests
    read it (ci104e: the compare.out test ran a two-job sweep of its own, one worker)."""
    root = tmp_path_factory.mktemp("second_sweep")
    return root, _sweep(root, dataset, 2, "model.estimator.fit_intercept=true,false",
                        f"compare.out={root / 'table'}", f"out={root / 'ignored'}")


@pytest.mark.slow
def test_a_sweep_writes_its_table_where_compare_out_says_and_says_out_is_per_job(second_sweep):
    # both were silently ignored: the table went to the sweep folder, out= nowhere
    tmp_path, (_, sweep_dir, proc, _, children) = second_sweep
    table = tmp_path / "table"
    assert len(children) == 2 and (table / "compare.csv").is_file()
    assert not (sweep_dir / "compare.csv").exists() and not (tmp_path / "ignored").exists()
    assert "out= is not used" in proc.stderr


@pytest.mark.slow
def test_a_failing_job_does_not_stop_the_sweep_and_the_parent_run_says_so(tmp_path, dataset):
    """The first job's config is bad (exit 2, its message on stderr): the second still runs,
    the sweep ends with the worst job's status and a summary naming the failed job."""
    uri = mlflow_store(tmp_path)
    proc = thermocomp("run", "-m", f"data.path={dataset}", f"tracking_uri={uri}", *LIGHT_EVAL,
                      "data.inputs=[X_*],[T_*]", f"hydra.sweep.dir={tmp_path / 'sweep'}", check=False)
    assert proc.returncode == 2 and "X_*" in proc.stderr
    assert "1 sweep job(s) failed: 0 (" in proc.stderr and "data.inputs=[X_*]): exit 2" in proc.stderr
    assert "2/2 jobs done (#1 ok" in proc.stderr and "1/2 jobs done (#0 FAILED" in proc.stderr
    assert (tmp_path / "sweep" / "1" / "metrics.json").is_file()
    assert not (tmp_path / "sweep" / "0" / "metrics.json").exists()
    import mlflow

    mlflow.set_tracking_uri(uri)
    runs = mlflow.search_runs(experiment_names=["thermocomp"])
    parent = runs[runs[f"tags.{SWEEP_TAG}"] == "parent"]
    assert list(parent["status"]) == ["FAILED"]               # not left RUNNING, not FINISHED
    assert list(parent["metrics.sweep.failed_jobs"]) == [1] and list(parent["metrics.sweep.jobs"]) == [2]
    children = runs[runs["tags.mlflow.parentRunId"].notna()]
    assert sorted(children["status"]) == ["FAILED", "FINISHED"]


@pytest.mark.slow
def test_a_job_failing_on_its_data_before_its_run_starts_is_counted_by_the_parent(tmp_path, dataset):
    # a job refused on reading its data (exit 2) never starts its child run: the parent was
    # FINISHED with sweep.jobs=1, sweep.failed_jobs=0 (0 and 0 when every job failed so)
    bad = tmp_path / "bad"
    shutil.copytree(dataset, bad)
    first = sorted(bad.glob("*.parquet")) or sorted(p for p in bad.glob("*.csv") if p.name != "campaigns.csv")
    df = pd.read_parquet(first[0]) if first[0].suffix == ".parquet" else pd.read_csv(first[0])
    df = df.astype({"T_1": object})
    df.loc[3, "T_1"] = "abc"
    csv = first[0].with_suffix(".csv")
    first[0].unlink()
    df.to_csv(csv, index=False)
    manifest = pd.read_csv(bad / "campaigns.csv")
    manifest["file"] = manifest["file"].replace(first[0].name, csv.name)
    manifest.to_csv(bad / "campaigns.csv", index=False)
    uri = mlflow_store(tmp_path)
    proc = thermocomp("run", "-m", f"data.path={dataset},{bad}", f"tracking_uri={uri}", *LIGHT_EVAL,
                      f"hydra.sweep.dir={tmp_path / 'sweep'}", check=False)
    assert proc.returncode == 2 and "column 'T_1', line 5 (data row 4)" in proc.stderr, proc.stderr
    import mlflow

    mlflow.set_tracking_uri(uri)
    runs = mlflow.search_runs(experiment_names=["thermocomp"])
    parent = runs[runs[f"tags.{SWEEP_TAG}"] == "parent"]
    assert list(parent["status"]) == ["FAILED"]
    assert list(parent["metrics.sweep.jobs"]) == [2] and list(parent["metrics.sweep.failed_jobs"]) == [1]


@pytest.mark.slow
def test_a_sweep_started_elsewhere_writes_every_job_under_the_project_root(tmp_path, dataset):
    # Hydra made the job folders relative to the current directory, sweep.json went to the root
    dest, env = copy_project(tmp_path / "proj")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    for sweep_dir in ([], ["hydra.sweep.dir=reports/mine"]):
        thermocomp("run", "-m", "model=mlr,pcr", f"data.path={dataset}", "track=false",
                   *LIGHT_EVAL, *sweep_dir, cwd=elsewhere, env=env)
        assert list(elsewhere.iterdir()) == []
    jobs = sorted(p.relative_to(dest / "reports") for p in (dest / "reports").rglob("metrics.json"))
    assert len(jobs) == 4 and [j.parts[0] for j in jobs].count("mine") == 2, jobs
    assert all(j.parts[0] in ("multirun", "mine") for j in jobs), jobs


def test_retry_on_database_is_locked_then_give_up_on_other_errors():
    calls = []

    def flaky():
        calls.append(1)
        if len(calls) < 3:
            try:
                raise sqlite3.OperationalError("database is locked")
            except sqlite3.OperationalError as exc:
                raise RuntimeError("(sqlite3.OperationalError) wrapped by MLflow") from exc
        return "ok"

    assert retry_locked(flaky, base_delay=0.001) == "ok" and len(calls) == 3
    assert _is_locked(RuntimeError("x")) is False

    def broken():
        calls.append(1)
        raise ValueError("no such table")

    calls.clear()
    with pytest.raises(ValueError):
        retry_locked(broken, base_delay=0.001)
    assert len(calls) == 1


def test_launcher_configs_compose_slurm_documented_not_run():
    from hydra import compose, initialize_config_dir

    from thermocomp.base.paths import conf_dir

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        slurm = compose("config", ["hydra/launcher=slurm"], return_hydra_config=True)
        joblib = compose("config", ["hydra/launcher=joblib"], return_hydra_config=True)
    assert slurm.hydra.launcher._target_.endswith("SlurmLauncher")
    assert slurm.hydra.launcher.cpus_per_task == 2
    assert joblib.hydra.launcher._target_.endswith("JoblibLauncher")
    callback = slurm.hydra.callbacks.mlflow_sweep
    assert callback._target_ == "thermocomp.shell.callbacks.MlflowSweepCallback"


@pytest.mark.slow
def test_a_second_joblib_sweep_in_one_process_attaches_its_jobs_to_its_own_parent(four_jobs, second_sweep):
    # joblib's (loky) workers outlive a sweep and are reused by the next one with the environment
    # of their start: the second sweep's jobs took the FIRST sweep's parent run id (a run of
    # another store: "Run ... not found", no child; CI, two in-process sweeps on one pytest worker).
    # The first: four_jobs' (two workers, as the second; its own parent and children checked above).
    _, (_, _, _, first, _) = four_jobs
    _, (_, sweep_dir, _, parents, children) = second_sweep
    assert len(parents) == 1 and len(children) == 2
    parent_id = parents["run_id"].iloc[0]
    assert parent_id != first["run_id"].iloc[0]
    assert (children["tags.mlflow.parentRunId"] == parent_id).all()
    assert (children["status"] == "FINISHED").all()
