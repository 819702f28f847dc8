"""`thermocomp promote` creates a new model version with its tags in one registry write.

A version is recognised by its tags (``find_registered``: the same deployment on the same
dataset, from the same run or model bytes), so a version that existed without them -- a promote
cut between the creation and the tags -- would be registered again by the next promote.  And
each tag set afterwards was one registry commit (~30 per version).
"""

from __future__ import annotations

import json

import pytest
from mlflow import MlflowClient

from test_promote import project  # noqa: F401  (the session's store with a weak and a strong run)
from thermocomp.shell.cli import main

pytestmark = pytest.mark.slow


def test_a_new_version_carries_its_tags_from_its_creation(project, capsys, monkeypatch):  # noqa: F811
    root, common, uri, weak, _ = project
    name, out = "one-write", root / "one-write"

    def after_creation(*args, **kwargs):
        raise AssertionError(f"a tag written after the version was created: {args[1:]}")

    monkeypatch.setattr(MlflowClient, "set_model_version_tag", after_creation)
    code = main(["promote", *common, f"promote.run_id={weak}", f"promote.model_name={name}",
                 f"out={out}"])
    assert code == 0, capsys.readouterr().err
    report = json.loads((out / "promote.json").read_text())
    assert report["registered"] and report["moved"] and report["reason"] == "no champion yet"

    tags = MlflowClient(uri).get_model_version(name, report["version"]).tags
    assert tags["source_run_id"] == weak and tags["promoted"] == "True"
    assert tags["decision"] == report["reason"] and len(tags["model_digest"]) == 64
    assert float(tags["metric.val_rmse"]) == pytest.approx(report["candidate"]["score"], rel=1e-5)
