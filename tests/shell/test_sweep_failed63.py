"""A sweep with a failed job, compared and promoted later (journey63): the table and the choice
say the grid is not whole, where they had said only the runs that finished."""

from __future__ import annotations

import json

import pytest

from conftest import thermocomp
from test_deploy import LIGHT_EVAL, mlflow_store, write_small_dataset


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    """The small dataset both tests sweep (read only: each moves no file of it)."""
    return write_small_dataset(tmp_path_factory.mktemp("failed63") / "small")


def test_compare_and_promote_say_the_jobs_a_sweep_lost(tmp_path, dataset):
    """Half of a sweep's jobs refused on their data (no child run): `compare` said '1 runs'
    and `promote` ranked '1 finished run(s)', nothing of the job that never ran."""
    uri, sweep = mlflow_store(tmp_path), tmp_path / "sweep"
    proc = thermocomp("run", "-m", f"data.path={dataset},{tmp_path / 'moved'}", f"tracking_uri={uri}",
                      *LIGHT_EVAL, f"hydra.sweep.dir={sweep}", check=False)
    assert proc.returncode == 2
    shown = thermocomp("compare", f"tracking_uri={uri}", f"compare.sweep={sweep}")
    assert "1 runs (1 of its 2 jobs failed: why in each one's folder, failed.json)" in shown.stdout
    # (audit99) the refused job's reason kept in its folder: "the sweep's log" was kept nowhere
    note = json.loads((sweep / "1" / "failed.json").read_text())
    assert note["exit"] == 2 and note["said"].startswith("thermocomp: error: ")
    assert str(tmp_path / "moved") in note["said"] and not (sweep / "0" / "failed.json").exists()
    table = json.loads((sweep / "compare.json").read_text())
    assert (table["n_runs"], table["failed_jobs"], table["jobs"]) == (1, 1, 2)
    chosen = thermocomp("promote", f"data.path={dataset}", f"tracking_uri={uri}",
                        f"compare.sweep={sweep}", f"out={tmp_path / 'promoted'}")
    assert "1 of its 2 jobs failed; the candidate is the best of the runs that finished" in chosen.stderr


def test_a_sweep_whose_every_job_failed_is_refused_saying_so(tmp_path, dataset):
    """Every job refused on its data: 'sweep ... has no child runs' (compare) and 'no finished
    child run to promote' (promote), exit 2, without saying the jobs had failed."""
    uri, sweep = mlflow_store(tmp_path), tmp_path / "sweep"
    thermocomp("run", "-m", f"data.path={tmp_path / 'moved'}", "model=mlr,arx", f"tracking_uri={uri}",
               *LIGHT_EVAL, f"hydra.sweep.dir={sweep}", check=False)
    shown = thermocomp("compare", f"tracking_uri={uri}", f"compare.sweep={sweep}", check=False)
    assert shown.returncode == 2 and "no child runs (2 of its 2 jobs failed" in shown.stderr
    chosen = thermocomp("promote", f"data.path={dataset}", f"tracking_uri={uri}",
                        f"compare.sweep={sweep}", f"out={tmp_path / 'promoted'}", check=False)
    assert chosen.returncode == 2 and "to promote (2 of its 2 jobs failed)" in chosen.stderr
    assert not (tmp_path / "promoted").exists()

