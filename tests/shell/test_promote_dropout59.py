"""``promote``'s "as deployed" test figures stream the test campaigns as recorded (deploy59).

``promote`` read ``data.path`` as a batch does: a test campaign's dropout (empty cells within
``data.max_gap_samples``) was filled from its neighbours, later samples included, before the
deployed compensator streamed it, so ``test_reported`` (and the version's ``metric.*`` tags),
documented as streamed as deployed, were ``run``'s batch figures (a year-round record with
5-sample dropouts, lag bank: 4.016 um against 4.060 from ``replay`` of the same model).  It now
reads the data as a stream sees it (train repaired as ``run`` fitted, test as recorded), as
``replay`` does.
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


def test_promote_reports_the_test_campaigns_as_the_deployed_model_streams_them(tmp_path):
    data = _make_dataset(tmp_path / "data")
    k05 = pd.read_csv(data / "K05.csv")
    k05.loc[20:22, "T_a"] = np.nan                         # a logger's dropout of 3 samples
    k05.to_csv(data / "K05.csv", index=False)
    uri = mlflow_store(tmp_path)
    common = [f"data.path={data}", "data.max_gap_samples=3", f"tracking_uri={uri}"]
    assert main(["run", *common, "model=lagbank", *LIGHT, f"out={tmp_path / 'run'}"]) == 0
    metrics = json.loads((tmp_path / "run" / "metrics.json").read_text())["targets"]
    assert main(["replay", *common, f"replay.model={tmp_path / 'run' / 'model.pkl'}",
                 f"out={tmp_path / 'replay'}"]) == 0
    replayed = json.loads((tmp_path / "replay" / "replay.json").read_text())["targets"]
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    exp = client.get_experiment_by_name("thermocomp").experiment_id
    run_id = client.search_runs([exp], filter_string="tags.stage = 'run'")[0].info.run_id
    assert main(["promote", *common, f"promote.run_id={run_id}", f"out={tmp_path / 'promote'}"]) == 0
    reported = json.loads((tmp_path / "promote" / "promote.json").read_text())["candidate"]["test_reported"]
    deployed = np.mean([r["rmse"] for r in replayed.values()])
    scored = np.mean([m["test"]["rmse"] for m in metrics.values()])
    assert abs(deployed - scored) > 1e-6                    # the dropout matters here
    assert reported["rmse"] == pytest.approx(deployed, rel=1e-9)
