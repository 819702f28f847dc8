"""An en-GB LabVIEW record end to end (data86b): ``.lvm`` files whose dates with slashes are
day first (one run on the 13th says so), read by ``init`` into ``data.dayfirst: true``, ``run``
and ``promote`` by its config, and the registered model served a block of the held-out run's
rows timed by the lab's clock in that order, as the same rows timed in seconds; the held-out
run's ``.lvm`` piped into ``monitor`` of the registered model (``monitor.input=-``) read as the
file is, and a run whose dates say no order read in the record's."""

from __future__ import annotations

import datetime as dt
import io
import json
import re

import numpy as np
import pandas as pd
import pytest

from conftest import LIGHT
from test_deploy import mlflow_store
from test_stranger69 import NAMES, ROWS, UNITS, _lvm, _values
from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.lvm import lvm_as_csv
from thermocomp.shell.cli import main

STARTS = (dt.datetime(2027, 9, 6, 6), dt.datetime(2027, 9, 8, 6), dt.datetime(2027, 9, 13, 6))


def _gb_folder(root):
    """Three runs as an en-GB LabVIEW writes them: ``Date 06/09/2027`` (its segments' too)."""
    root.mkdir()
    for run, start in enumerate(STARTS, start=1):
        path = _lvm(root / f"ZP1200_Lauf_{run:02d}.lvm", start, _values(run))
        text = path.read_bytes().decode("cp1252")
        path.write_bytes(re.sub(r"(\d{4})/(\d\d)/(\d\d)", r"\3/\2/\1", text).encode("cp1252"))
    return root


def test_an_en_gb_labview_record_init_run_promote_served_in_the_order_it_settled(tmp_path,
                                                                                 capsys,
                                                                                 monkeypatch):
    import mlflow

    folder = _gb_folder(tmp_path / "runs")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0
    assert "ZP1200_Lauf_03.lvm's '13/09/2027'" in capsys.readouterr().out
    assert "dayfirst: true" in (tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text(
        encoding="utf-8")
    uri = mlflow_store(tmp_path)
    common = [f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=runs",
              "model=lagbank", *LIGHT, f"tracking_uri={uri}"]
    assert main(["run", *common, f"out={tmp_path / 'run'}"]) == 0
    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    assert main(["promote", *common, f"promote.run_id={run_id}",
                 f"out={tmp_path / 'promote'}"]) == 0
    model_uri = json.loads((tmp_path / "promote" / "promote.json").read_text())["model_uri"]
    model = mlflow.pyfunc.load_model(model_uri)
    # the held-out run's rows under the lab's names, timed by its clock (13/09 06:00, a minute
    # apart) and in seconds: the model reads the first as the second
    values = _values(3)
    inputs = {f"{n} [{u}]": values[:, k] for k, (n, u) in enumerate(zip(NAMES, UNITS))
              if u == "Deg C" or n.startswith("X")}
    stamps = pd.Timestamp(STARTS[2]) + pd.to_timedelta(np.arange(ROWS), unit="min")
    block = pd.DataFrame({"time": stamps.strftime("%d/%m/%Y %H:%M:%S"), **inputs})
    served, timed = (model.predict(b, params={"reset": True})
                     for b in (block, block.assign(time=np.arange(ROWS) * 60.0)))
    np.testing.assert_array_equal(served["C_dX"], timed["C_dX"])
    assert np.abs(timed["C_dX"]).max() > 0
    # the held-out run's file piped into monitor of the registered model: read day first, as
    # on the file
    scored = {}
    for where in ("file", "stdin"):
        if where == "stdin":
            monkeypatch.setattr("sys.stdin", io.StringIO(
                (folder / "ZP1200_Lauf_03.lvm").read_bytes().decode("cp1252")))
        out = tmp_path / f"monitor-{where}"
        assert main(["monitor", *common, f"monitor.model={model_uri}", f"out={out}",
                     *(["monitor.input=-"] if where == "stdin" else [])]) == 0
        scored[where] = json.loads((out / "monitor.json").read_text())["targets"]["E_dX"]
    assert scored["stdin"]["rmse_fixed"] == scored["file"]["rmse_fixed"]
    # the 6th's file, its dates saying no order: read in the one its record settled, every row
    monkeypatch.setattr("sys.stdin", io.StringIO(
        (folder / "ZP1200_Lauf_01.lvm").read_bytes().decode("cp1252")))
    assert main(["monitor", *common, f"monitor.model={model_uri}", "monitor.input=-",
                 f"out={tmp_path / 'monitor-6th'}"]) == 0
    said = json.loads((tmp_path / "monitor-6th" / "monitor.json").read_text())["targets"]
    assert said["E_dX"]["n_samples"] == ROWS


def test_a_streamed_labview_file_of_two_sessions_is_refused(tmp_path):
    """Where a stream is one campaign, a file two VI runs appended to (a run each) is refused;
    ``monitor`` streams each as a campaign (test_data87), ``connect.warm`` warms on the last
    (test_data88)."""
    one = _lvm(tmp_path / "Lauf.lvm", STARTS[0], _values(1)).read_bytes().decode("cp1252")
    assert lvm_as_csv(one, "<stdin>").startswith("time,Luft [Deg C],")
    with pytest.raises(ContractError, match="holds 2 sessions .* stream one run"):
        lvm_as_csv(one + "\r\n" + one, "<stdin>")
