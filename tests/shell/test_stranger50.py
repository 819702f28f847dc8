"""A stranger's pass with a lab's folder of runs from a climate room (issue 34, items 1 and 2):
the served model reads every name the lab gave a column, a stdin stream takes the climate room's
set point for a model on the manifest's ``ambient_c``, and a lab's manifest without ``split``."""

from __future__ import annotations

import io
import json

import numpy as np
import pandas as pd
import pytest
from omegaconf import OmegaConf

from conftest import FAST, refused
from thermocomp.shell.cli import main


def _lab_folder(root, runs: int = 6):
    """Runs from two loggers: the first half write ``Zeit [s]``, the others ``Zeit`` (both in
    s); the error follows the heating through a lag, so a lag model reads the time."""
    root.mkdir()
    rng = np.random.default_rng(50)
    for k in range(runs):
        t = np.arange(60) * 60.0
        heat = 20 + (3 + k) * (1 - np.exp(-t / 1500)) + rng.normal(0, 0.02, t.size)
        other = 20 + 0.5 * np.sin(t / 900 + k) + rng.normal(0, 0.02, t.size)
        lagged = 20 + (3 + k) * (1 - np.exp(-t / 4000))
        error = 4 * (lagged - 20) + 0.5 * (heat - 20) + rng.normal(0, 0.05, t.size)
        pd.DataFrame({"Zeit [s]" if k < runs // 2 else "Zeit": t, "T0 [°C]": heat,
                      "T1 [°C]": other, "dX [µm]": error}).to_csv(
            root / f"Lauf_{k + 1:02d}.csv", sep=";", decimal=",", index=False)
    return root


def test_the_served_model_reads_the_time_under_each_name_the_labs_runs_gave_it(tmp_path):
    from thermocomp.apps.deploy import StreamingCompensator
    from thermocomp.apps.deploy.pyfunc import CompensatorModel
    from thermocomp.core.io import read_dataset
    from thermocomp.core.io.own_headers import lab_names
    from thermocomp.shell.model_store import load_model

    folder = _lab_folder(tmp_path / "lab")
    roles = ["data.roles.error=[dX]", "data.test_fraction=0.34"]
    assert main(["run", f"data.path={folder}", "model=lagbank", f"out={tmp_path / 'run'}",
                 *roles, *FAST]) == 0
    ds, _ = read_dataset(folder, {"roles": {"error": ["dX"]}, "test_fraction": 0.34})
    names = lab_names(OmegaConf.create({"data": {"columns": {}}}), ds)
    comp = load_model(tmp_path / "run" / "model.pkl")
    streaming = StreamingCompensator.from_training(comp, {c: ds.campaigns[c] for c in
                                                          ds.ids("train")}, policy="off")
    streaming.lab_names_ = names
    served = CompensatorModel(streaming)
    raw = pd.read_csv(folder / "Lauf_01.csv", sep=";", decimal=",")
    raw["Zeit [s]"] *= np.where(np.arange(len(raw)) > 20, 3.0, 1.0)   # a slower logger later
    contract = raw.rename(columns={"Zeit [s]": "time", "T0 [°C]": "T_T0", "T1 [°C]": "T_T1"})
    cols = ["time", "T_T0", "T_T1"]
    want = served.predict(None, contract[cols], params={"session": "contract"})["C_dX"]
    for header in ("Zeit [s]", "Zeit"):    # each logger's name of the time
        lab = raw[["Zeit [s]", "T0 [°C]", "T1 [°C]"]].rename(columns={"Zeit [s]": header})
        got = served.predict(None, lab, params={"session": header})["C_dX"]
        np.testing.assert_allclose(got, want, atol=1e-12)
    assert names["time"] == ["Zeit [s]", "Zeit"]
    # the two names of one column in one block are refused, as a lab name beside a contract one
    both = raw[["Zeit [s]", "T0 [°C]", "T1 [°C]"]].assign(Zeit=raw["Zeit [s]"])
    with pytest.raises(Exception, match="'Zeit \\[s\\]' and 'Zeit'"):
        served.predict(None, both, params={"session": "both"})


def _climate_room(root):
    """test_ambient_manifest's climate room (ambient from the manifest's ``ambient_c`` alone)
    with a third sensor, so that the monitor watches three."""
    from test_ambient_manifest import make_dataset

    ds = make_dataset(root)
    for f in ds.glob("R*.csv"):
        df = pd.read_csv(f)
        df.assign(T_column=0.5 * (df["T_spindle"] + df["T_air"]) + np.sin(df["time"] / 700)
                  ).to_csv(f, index=False)
    return ds


def test_a_stdin_stream_takes_the_climate_rooms_set_point_as_its_campaign_would(
        tmp_path, monkeypatch, capsys):
    ds = _climate_room(tmp_path / "ds")
    # R03 (18 °C) the one test campaign; its file streamed from data.path, then on stdin
    common = [f"data.path={ds}", "ati=cmeans", "data.split_overrides={R06: train}", *FAST]
    assert main(["monitor", f"out={tmp_path / 'file'}", *common]) == 0
    want = json.loads((tmp_path / "file" / "monitor.json").read_text())["targets"]["E_X"]
    stdin = (ds / "R03.csv").read_text()
    monkeypatch.setattr("sys.stdin", io.StringIO(stdin))
    assert main(["monitor", f"out={tmp_path / 'stdin'}", *common, "monitor.input=-",
                 "monitor.ambient_c=18.0"]) == 0
    got = json.loads((tmp_path / "stdin" / "monitor.json").read_text())["targets"]["E_X"]
    assert got["rmse_fixed"] == pytest.approx(want["rmse_fixed"], rel=1e-9)
    # another set point corrects otherwise: the value is what ATI reads
    monkeypatch.setattr("sys.stdin", io.StringIO(stdin))
    assert main(["monitor", f"out={tmp_path / 'warm'}", *common, "monitor.input=-",
                 "monitor.ambient_c=30.0"]) == 0
    other = json.loads((tmp_path / "warm" / "monitor.json").read_text())["targets"]["E_X"]
    assert other["rmse_fixed"] != pytest.approx(want["rmse_fixed"], rel=1e-3)
    # a campaign of data.path has its manifest's: the key is refused there, before any work
    refused(["monitor", f"out={tmp_path / 'no'}", *common, "monitor.ambient_c=18.0"], capsys,
            "monitor.ambient_c=18.0", "stdin")
    assert not (tmp_path / "no").exists()


def test_a_labs_manifest_without_split_is_read_by_init_and_its_lack_named_by_run(
        tmp_path, capsys):
    # the lab wrote its manifest as its runs: ';', decimal commas, the climate room's set point
    folder = _lab_folder(tmp_path / "lab")
    pd.DataFrame({"campaign": [f"L{k}" for k in range(1, 7)],
                  "file": [f"Lauf_{k:02d}.csv" for k in range(1, 7)],
                  "ambient_c": 15 + 2.5 * np.arange(6)}).to_csv(
        folder / "campaigns.csv", sep=";", decimal=",", index=False)
    assert main(["init", str(folder), f"out={tmp_path / 'init'}", "data.roles.error=[dX]"]) == 0
    config = (tmp_path / "init" / "conf" / "data" / "lab.yaml").read_text()
    assert "test_fraction: 0.1" in config
    assert "campaign L6: test" in capsys.readouterr().out
    # run without a fraction: the column it lacks is named, not 'campaign' (the header read
    # with ',' named none of them)
    refused(["run", f"data.path={folder}", f"out={tmp_path / 'run'}", "data.roles.error=[dX]",
             *FAST], capsys, "campaigns.csv", "column 'split'", "data.test_fraction")
    refused(["run", f"data.path={folder}", f"out={tmp_path / 'run'}", "data.roles.error=[dX]",
             "data.delimiter=;", *FAST], capsys, "column 'split'")
    assert not (tmp_path / "run").exists()


def test_a_manifest_saved_under_another_name_is_named_as_one_not_read_as_a_run(tmp_path, capsys):
    folder = _lab_folder(tmp_path / "lab")
    pd.DataFrame({"campaign": ["L1", "L2"], "file": ["Lauf_01.csv", "Lauf_02.csv"],
                  "ambient_c": [15.0, 17.5]}).to_csv(folder / "Versuchsplan.csv", sep=";",
                                                      decimal=",", index=False)
    refused(["run", f"data.path={folder}", f"out={tmp_path / 'run'}", "data.roles.error=[dX]",
             "data.test_fraction=0.34", *FAST], capsys, "Versuchsplan.csv",
            "rename it campaigns.csv")
    assert not (tmp_path / "run").exists()


def test_runs_joined_in_one_file_are_said_to_pause_where_they_were_joined(tmp_path, capsys):
    # the lab's other export: every run in one file, wall-clock times, days between runs
    runs = [pd.read_csv(f, sep=";", decimal=",") for f in sorted(_lab_folder(tmp_path / "lab")
                                                                  .glob("Lauf_*.csv"))]
    start = pd.Timestamp("2023-03-01 08:00")
    joined = pd.concat([pd.DataFrame({"Zeit": (start + pd.Timedelta(days=7 * k) + pd.to_timedelta(
        r.iloc[:, 0], unit="s")).dt.strftime("%d.%m.%Y %H:%M:%S")}).join(r.iloc[:, 1:])
        for k, r in enumerate(runs)])
    joined.to_csv(tmp_path / "alle.csv", sep=";", decimal=",", index=False)
    assert main(["run", f"data.path={tmp_path / 'alle.csv'}", "data.roles.error=[dX]",
                 "data.test_fraction=0.2", f"out={tmp_path / 'run'}", *FAST]) == 0
    err = capsys.readouterr().err
    assert "alle.csv: one record, yet it pauses 5 time(s)" in err
    assert "after data row 60)" in err and "One file per run in a folder" in err
    # a record sampled without such pauses is read without a word about them
    runs[0].to_csv(tmp_path / "eins.csv", sep=";", decimal=",", index=False)
    assert main(["run", f"data.path={tmp_path / 'eins.csv'}", "data.roles.error=[dX]",
                 "data.test_fraction=0.2", f"out={tmp_path / 'one'}", *FAST]) == 0
    assert "pauses" not in capsys.readouterr().err
