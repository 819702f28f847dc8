"""The exported C stream reads the lab's own file (issue 34 item 1, "the deployed model accepts
the lab's own names", session 52): its headers, ';' and decimal commas, and its run-number column
starting each run, as replay streams the runs."""

from __future__ import annotations

import io
import json
import subprocess

import numpy as np
import pandas as pd
import pytest

import cbuild
from conftest import FAST
from test_export import _compose, needs_cc
from test_run_column52 import _long, _runs
from thermocomp.apps.deploy.streaming import replay
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import load_model
from thermocomp.shell.source import read_streamed

DATA = ("data.roles.error=[dX]", "data.roles.campaign=Lauf", "data.test_fraction=0.5")


def compiled(tmp_path, path):
    """``stream`` compiled from what a lagbank run on ``path`` exports (its lags read the time),
    in ``tmp_path / "code"`` (the run in ``tmp_path / "run"``)."""
    common = (f"data.path={path}", *DATA)
    assert main(["run", *common, "model=lagbank", *FAST, f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "monitor.adaptive=false", "export.format=c", "track=false",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    return cbuild.compiled(tmp_path / "code")


@needs_cc
def test_the_compiled_c_streams_the_labs_raw_long_file_as_replay(tmp_path):
    # before: stream.c split on ',' and knew contract names only ("the header lacks input
    # column T_T0"): the lab converted its file first, and started each run by a blank row
    path = _long(tmp_path / "alle.csv", _runs())
    common = (f"data.path={path}", *DATA)
    code = compiled(tmp_path, path).parent
    cfg = _compose(*common, "model=lagbank", "monitor.adaptive=false", "track=false")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    assert test_ids == ["Lauf_3", "Lauf_4"]
    stream = deploy_stream(cfg, load_model(tmp_path / "run" / "model.pkl"),
                           {c: ds.campaigns[c] for c in train_ids})
    want = np.vstack([-replay(stream, ds.campaigns[c])[stream.targets_].to_numpy(float)
                      for c in test_ids])
    lines = path.read_text(encoding="utf-8").splitlines()
    raw = "\n".join([lines[0], *(ln for ln in lines[1:] if ln.split(";")[0] in "34")]) + "\n"
    assert raw.startswith("Lauf;Zeit [s];T0 [°C]") and ",0" in raw   # the lab's own file
    run = subprocess.run([str(code / "stream")], input=raw.encode("utf-8"), capture_output=True,
                         check=True)
    got = pd.read_csv(io.BytesIO(run.stdout)).to_numpy(float)
    assert got.shape == want.shape == (60, 1)
    assert np.abs(got - want).max() <= 1e-9
    # the run column starts each run: streamed as one run, the second differs
    one = raw.replace("\n4;", "\n3;")
    joined = pd.read_csv(io.BytesIO(subprocess.run([str(code / "stream")], input=one.encode(),
                                                   capture_output=True, check=True).stdout))
    assert np.abs(joined.to_numpy(float)[30:] - want[30:]).max() > 1e-3
    # a time of day alone: refused with its row, not read as 8 s (a date and time reads,
    # test_lab_export53)
    clock = raw.replace("\n3;0,0;", "\n3;08:45:00;", 1)
    assert clock != raw
    bad = subprocess.run([str(code / "stream")], input=clock.encode(), capture_output=True)
    assert bad.returncode == 2 and b"line 2: the time is no number" in bad.stderr
    # (stranger74) a column the file lacks is said by the lab's header, not only T_T0
    lacking = subprocess.run([str(code / "stream")], input=raw.replace("T0 [°C]", "T9 [°C]", 1)
                             .encode(), capture_output=True)
    assert lacking.returncode == 2
    assert "lacks input column T_T0 (the lab's header 'T0 [°C]')".encode() in lacking.stderr


@pytest.mark.parametrize("text, want", [("T0 [°C]", '"T0 [\\302\\260C]"'),
                                        ('a"b\\c', '"a\\042b\\134c"'), ("µm1", '"\\302\\265m1"')])
def test_a_labs_header_is_an_ascii_c_string_of_its_bytes(text, want):
    from thermocomp.apps.deploy.export.c import c_string

    assert c_string(text) == want and c_string(text).isascii()


def test_the_served_model_reads_a_labs_wall_clock_times_as_replay_does(tmp_path):
    # before: "could not convert string to float: '01.03.2023 08:00:00'" (and MLflow's schema,
    # a double, refused the column): the lab converted its logger's clock to seconds first
    import mlflow
    from mlflow.exceptions import MlflowException

    from thermocomp.apps.deploy.pyfunc import save_compensator
    from thermocomp.core.io.own_headers import lab_names

    runs = _runs(3)
    for k, run in enumerate(runs):
        start = pd.Timestamp("2023-03-01 08:00") + pd.Timedelta(days=7 * k)
        run.insert(0, "Zeit", (start + pd.to_timedelta(run.pop("Zeit [s]"), unit="s"))
                   .dt.strftime("%d.%m.%Y %H:%M:%S"))
    path = _long(tmp_path / "alle.csv", runs)
    common = (f"data.path={path}", "data.roles.error=[dX]", "data.roles.campaign=Lauf",
              "data.test_fraction=0.34")
    assert main(["run", *common, "model=lagbank", *FAST, f"out={tmp_path / 'run'}"]) == 0
    cfg = _compose(*common, "model=lagbank", "monitor.adaptive=false", "track=false")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    stream = deploy_stream(cfg, load_model(tmp_path / "run" / "model.pkl"),
                           {c: ds.campaigns[c] for c in train_ids})
    assert "time" in stream.columns_ or stream.time_required_      # the lags read the clock
    stream.lab_names_ = lab_names(cfg, ds)
    served = mlflow.pyfunc.load_model(str(save_compensator(stream, tmp_path / "served")))
    want = -replay(stream, ds.campaigns["Lauf_3"])[stream.targets_].to_numpy(float)
    raw = pd.read_csv(path, sep=";", decimal=",")
    rows = raw[raw["Lauf"] == 3].drop(columns="Lauf")
    assert rows["Zeit"].iloc[0] == "15.03.2023 08:00:00"
    first = served.predict(rows.iloc[:12], params={"session": "m", "reset": True})
    rest = served.predict(rows.iloc[12:], params={"session": "m"})    # the campaign goes on
    got = pd.concat([first, rest])[["C_dX"]].to_numpy(float)
    assert np.abs(got - want).max() <= 1e-9
    # (data91) the time of day without its date, refused before, reads in its session as the
    # dated rows do (a day added where it would pass midnight, as a file's)
    clock = served.predict(rows.assign(Zeit=rows["Zeit"].str[-8:]), params={"session": "c",
                                                                           "reset": True})
    assert np.abs(clock[["C_dX"]].to_numpy(float) - want).max() <= 1e-9
    # (stranger74) a column the request lacks is named as the lab sends it, not only as T_T0
    with pytest.raises(MlflowException, match=r"lacks column\(s\) \['T0 \[°C\]' \(read as T_T0\)\]"):
        served.predict(rows.drop(columns="T0 [°C]"), params={"reset": True})


def test_the_served_model_starts_a_campaign_where_the_time_pauses_as_the_c_does(tmp_path):
    # audit106: a record read with data.runs_at_pauses (init writes it for a file that pauses):
    # the reader and stream.c (TC_PAUSE_S) start a campaign at each pause, a served session went
    # on as one campaign without a word (a lab's 3 h gap: 2.82 um off the C)
    from test_monitor_runs52 import _long as _days_apart
    from thermocomp.apps.deploy.pyfunc import CompensatorModel
    from thermocomp.shell.builders import deployable

    path = _days_apart(tmp_path / "alle.csv", clock=True)
    raw = pd.read_csv(path, sep=";", decimal=",")
    raw.drop(columns="Lauf").to_csv(path, sep=";", decimal=",", index=False)   # a day apart, no counter
    common = (f"data.path={path}", "data.roles.error=[dX]", "data.runs_at_pauses=true",
              "data.test_fraction=0.5")
    assert main(["run", *common, "model=mlr", *FAST, f"out={tmp_path / 'run'}"]) == 0
    cfg = _compose(*common, "model=mlr", "track=false")
    ds, train_ids, _, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    deployed = deployable(cfg, deploy_stream(cfg, load_model(tmp_path / "run" / "model.pkl"), train),
                          train, ds)
    assert deployed.pause_s_ == 100 * 60.0
    served = CompensatorModel(deployed)
    rows = raw[raw["Lauf"] >= 3].drop(columns=["Lauf", "dX [µm]"]).reset_index(drop=True)
    run3, run4 = rows.iloc[:30], rows.iloc[30:]
    want = pd.concat([served.predict(None, run3, {"session": "a", "reset": True}),
                      served.predict(None, run4, {"session": "b", "reset": True})], ignore_index=True)
    one = served.predict(None, rows, {"session": "one", "reset": True})          # within a block
    two = pd.concat([served.predict(None, run3, {"session": "two", "reset": True}),
                     served.predict(None, run4, {"session": "two"})], ignore_index=True)   # between
    for got in (one, two):
        assert np.abs(got[["C_dX"]].to_numpy(float) - want[["C_dX"]].to_numpy(float)).max() <= 1e-12
        said = json.loads(got["events"].iloc[30])
        assert said[0]["to"] == "new campaign" and "pauses 23.5 h" in said[0]["reason"]
    assert all(e == "[]" for e in one["events"].iloc[:30])
