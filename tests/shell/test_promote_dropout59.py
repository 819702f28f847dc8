"""``promote``'s "as deployed" test figures stream the test campaigns as recorded (deploy59).

``promote`` read ``data.path`` as a batch does: a test campaign's dropout (empty cells within
``data.max_gap_samples``) was filled from its neighbours, later samples included, before the
deployed compensator streamed it, so ``test_reported`` (and the version's ``metric.*`` tags),
documented as streamed as deployed, were ``run``'s batch figures (a year-round record with
5-sample dropouts, lag bank: 4.016 um against 4.060 from ``replay`` of the same model).  It now
reads the data as a stream sees it (train repaired as ``run`` fitted, test as recorded), as
``replay`` does.  The plain stream (``monitor.adaptive=false``) refuses such a row, so its
figures stay of the filled campaigns, said in a warning.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from conftest import LIGHT
from test_deploy import mlflow_store
from test_export import _make_dataset
from thermocomp.shell.cli import main


@pytest.fixture(scope="module")
def scored(tmp_path_factory):
    """``(common overrides, run id, run's test RMSE per target, replay's)``: a lag bank fitted
    on a record whose test campaign K05 has a 3-sample dropout of T_a."""
    root = tmp_path_factory.mktemp("dropout")
    data = _make_dataset(root / "data")
    k05 = pd.read_csv(data / "K05.csv")
    k05.loc[20:22, "T_a"] = np.nan
    k05.to_csv(data / "K05.csv", index=False)
    uri = mlflow_store(root)
    common = [f"data.path={data}", "data.max_gap_samples=3", f"tracking_uri={uri}"]
    assert main(["run", *common, "model=lagbank", *LIGHT, f"out={root / 'run'}"]) == 0
    metrics = json.loads((root / "run" / "metrics.json").read_text())["targets"]
    assert main(["replay", *common, f"replay.model={root / 'run' / 'model.pkl'}",
                 f"out={root / 'replay'}"]) == 0
    replayed = json.loads((root / "replay" / "replay.json").read_text())["targets"]
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    exp = client.get_experiment_by_name("thermocomp").experiment_id
    run_id = client.search_runs([exp], filter_string="tags.stage = 'run'")[0].info.run_id
    return (common, run_id, np.mean([m["test"]["rmse"] for m in metrics.values()]),
            np.mean([r["rmse"] for r in replayed.values()]))


def _reported(common, run_id, out, *extra) -> dict:
    assert main(["promote", *common, f"promote.run_id={run_id}", "promote.force=true", *extra,
                 f"out={out}"]) == 0
    return json.loads((out / "promote.json").read_text())["candidate"]["test_reported"]


def test_promote_reports_the_test_campaigns_as_the_deployed_model_streams_them(scored, tmp_path):
    common, run_id, by_run, deployed = scored
    assert abs(deployed - by_run) > 1e-6                     # the dropout matters here
    assert _reported(common, run_id, tmp_path)["rmse"] == pytest.approx(deployed, rel=1e-9)


def test_a_plain_streams_figures_are_of_the_filled_campaigns_said(scored, tmp_path, capsys):
    """(The stream read made it a traceback: MissingValueError at K05's row 20.)"""
    common, run_id, _, deployed = scored
    reported = _reported(common, run_id, tmp_path, "monitor.adaptive=false")
    assert np.isfinite(reported["rmse"]) and reported["rmse"] != pytest.approx(deployed)
    assert "K05 (3 cells) miss values, which the plain streaming compensator refuses" in \
        capsys.readouterr().err
