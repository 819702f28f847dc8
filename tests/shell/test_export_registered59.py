"""The code of a promoted model names the dataset it was promoted on (deploy59).

docs/to-the-machine.md: "Every file starts with its provenance: the model family, the source,
the MLflow run, the dataset's SHA-256".  A ``model.pkl`` exported with ``data.path`` carried the
digest; the registry's champion (``export.model=models:/...@champion``, no data) carried
``dataset_hash: null``, though ``promote`` tags every version with it: the code a PLC runs could
not be traced to its data the way its run's could.
"""

from __future__ import annotations

import json

from conftest import LIGHT
from test_deploy import mlflow_store
from test_lab_promote57 import ROLES, lab_file
from thermocomp.base.files import folder_digest
from thermocomp.shell.cli import main


def test_the_champions_code_names_the_dataset_it_was_promoted_on(tmp_path, capsys):
    """(stranger78) ... and says it comes without a conformance pack, and how to get one (the
    champion's C had no ``check/``, unsaid)."""
    data = lab_file(tmp_path / "messung.csv", rows=120)
    uri = mlflow_store(tmp_path)
    common = [f"data.path={data}", *ROLES, f"tracking_uri={uri}"]
    assert main(["run", *common, *LIGHT, f"out={tmp_path / 'run'}"]) == 0
    assert main(["promote", *common, "promote.run_id=" + _last_run(uri),
                 f"out={tmp_path / 'promote'}"]) == 0
    out = tmp_path / "code"
    assert main(["export", "export.model=models:/thermocomp-compensator@champion",
                 "export.format=json", f"tracking_uri={uri}", f"out={out}"]) == 0
    assert ("no conformance pack (check/): a registered model is exported without reading data; "
            "export.check=true writes the pack") in capsys.readouterr().err
    assert not (out / "check").exists()
    provenance = json.loads((out / "compensator.json").read_text())["provenance"]
    assert provenance["dataset_hash"] == folder_digest(data)
    assert provenance["run_id"] == json.loads((tmp_path / "promote" / "promote.json").read_text())["run_id"]


def _last_run(uri: str) -> str:
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    exp = client.get_experiment_by_name("thermocomp").experiment_id
    return client.search_runs([exp], order_by=["attributes.start_time DESC"], max_results=1)[0].info.run_id
