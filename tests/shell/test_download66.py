"""A registered model's load fetches only the files it reads (download66).

``replay``, ``serve``, ``export`` and ``connect`` of ``models:/<name>@<alias>`` downloaded the whole
model (270 files, 261 of them the package source of ``code_paths``) to read three: its
``MLmodel``, the signed pickle and its signature (serveflake66).  They now come one by one
(:class:`thermocomp.apps.deploy.pyfunc.ModelFiles`, the alias resolved once); the model loaded
is the one the whole download gave, and a file missing from the store is refused naming it.
"""

from __future__ import annotations

import contextlib
import json
from pathlib import Path

import pytest

from conftest import LIGHT
from test_deploy import mlflow_store, write_small_dataset
from thermocomp.shell.cli import main

NAME = "thermocomp-compensator"
MODEL = f"models:/{NAME}@champion"


@pytest.fixture(scope="module")
def promoted(tmp_path_factory):
    root = tmp_path_factory.mktemp("download66")
    data = write_small_dataset(root / "small")
    uri = mlflow_store(root)
    common = [f"data.path={data}", f"tracking_uri={uri}", *LIGHT]
    assert main(["run", *common, f"out={root / 'run'}"]) == 0
    import mlflow

    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    assert main(["promote", *common, f"promote.run_id={run_id}", f"out={root / 'p'}"]) == 0
    return data, uri


def _stored(uri: str) -> Path:
    """The champion's folder in the (local) store."""
    from mlflow import MlflowClient

    client = MlflowClient(uri, registry_uri=uri)
    version = client.get_model_version_by_alias(NAME, "champion").version
    return Path(client.get_model_version_download_uri(NAME, version).removeprefix("file://"))


def _replay(data, uri, model, out) -> list:
    return ["replay", f"data.path={data}", f"tracking_uri={uri}", "track=false", "plots=none",
            f"replay.model={model}", f"out={out}"]


def _replayed(out: Path) -> dict:
    """replay.json without its timing and its source's name: every number replayed."""
    found = json.loads((out / "replay.json").read_text())
    for row in found["targets"].values():
        row.pop("us_per_sample")
    found.pop("source")
    return found


def test_a_registered_load_copies_only_what_it_reads(promoted, tmp_path, monkeypatch):
    """Fails on the old code: it copied all 270 files of the model into its scratch folder."""
    import thermocomp.base.files as files
    from thermocomp.apps.deploy.pyfunc import load_deployed

    data, uri = promoted
    fetched: list[set] = []
    scratch = files.scratch_folder

    @contextlib.contextmanager
    def watched(prefix):
        with scratch(prefix) as folder:
            yield folder
            fetched.append({p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file()})

    monkeypatch.setattr(files, "scratch_folder", watched)
    import mlflow

    mlflow.set_tracking_uri(uri)      # the registry follows it (none set: it would outlive the test)
    deployed = load_deployed(MODEL)
    assert fetched == [{"MLmodel", "artifacts/compensator.pkl", "artifacts/compensator.pkl.sig"}]
    assert len([p for p in _stored(uri).rglob("*") if p.is_file()]) > 100   # what it skipped
    assert deployed.targets_ == ["E_X", "E_Z"]


def test_the_model_fetched_file_by_file_replays_as_the_whole_download(promoted, tmp_path):
    """A guard, not a change: it passes on the old code too (which downloaded the whole model)."""
    import mlflow

    data, uri = promoted
    whole = mlflow.artifacts.download_artifacts(artifact_uri=MODEL, dst_path=str(tmp_path / "whole"),
                                                tracking_uri=uri, registry_uri=uri)
    assert main(_replay(data, uri, MODEL, tmp_path / "registered")) == 0
    assert main(_replay(data, uri, whole, tmp_path / "folder")) == 0
    assert _replayed(tmp_path / "registered") == _replayed(tmp_path / "folder")


@pytest.mark.parametrize("missing", ["artifacts/compensator.pkl", "artifacts/compensator.pkl.sig"])
def test_a_file_missing_from_the_store_is_refused_naming_it(promoted, tmp_path, capsys, missing):
    """Fails on the old code: it named the scratch copy it had just removed, not the model
    (``file /tmp/thermocomp-model-.../artifacts/compensator.pkl: is not a regular file``; for the
    signature, ``...: not signed by this project``: the model was, its signature file is lost)."""
    data, uri = promoted
    gone = _stored(uri) / missing
    kept = gone.read_bytes()
    try:
        gone.unlink()
        capsys.readouterr()
        assert main(_replay(data, uri, MODEL, tmp_path / "r")) == 2
        err = capsys.readouterr().err
        assert f"file {MODEL}: the model has no readable {missing!r}" in err
        assert not (tmp_path / "r").exists()
    finally:
        gone.write_bytes(kept)


def test_an_artifact_named_outside_the_model_is_refused_before_it_is_read(promoted, tmp_path, capsys):
    """A guard, not a change (the old code refused it after the whole download): an edited MLmodel
    that names a file beyond the model's folder is never fetched, now file by file."""
    data, uri = promoted
    spec = _stored(uri) / "MLmodel"
    kept = spec.read_text()
    try:
        spec.write_text(kept.replace("path: artifacts/compensator.pkl\n",
                                     "path: ../../../../mlflow.db\n"))
        capsys.readouterr()
        assert main(_replay(data, uri, MODEL, tmp_path / "r")) == 2
        assert "outside the model folder" in capsys.readouterr().err
        assert not (tmp_path / "r").exists()
    finally:
        spec.write_text(kept)
