"""The compiled ``stream.c`` reads a lab's file in the lab's own units (streamunits60): a column
the reader converted (°F, K -> °C, mm -> µm, min -> s) is converted cell by cell as the reader
did, so that the lab's file, not a converted copy, streams as replay streams the dataset."""

from __future__ import annotations

import io
import json
import subprocess

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from conftest import FAST, refused
from test_export import _compose, needs_cc
from test_run_column52 import _long, _runs
from thermocomp.apps.deploy.streaming import replay
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import load_model
from thermocomp.shell.source import read_streamed

DATA = ("data.roles.error=[dX]", "data.roles.campaign=Lauf", "data.test_fraction=0.5")


def _in_lab_units(runs: list[pd.DataFrame]) -> list[pd.DataFrame]:
    """The runs as a lab in °F, K, mm and minutes writes them."""
    return [pd.DataFrame({"Zeit [min]": r["Zeit [s]"] / 60, "T0 [°F]": r["T0 [°C]"] * 9 / 5 + 32,
                          "T1 [K]": r["T1 [°C]"] + 273.15, "dX [mm]": r["dX [µm]"] / 1e3})
            for r in runs]


def _exported(tmp_path, path, *extra) -> tuple[list, int]:
    common = (f"data.path={path}", *DATA, *extra)
    assert main(["run", *common, "model=lagbank", *FAST, f"out={tmp_path / 'run'}"]) == 0
    return common, main(["export", *common, "monitor.adaptive=false", "export.format=c",
                         "track=false", f"export.model={tmp_path / 'run' / 'model.pkl'}",
                         f"out={tmp_path / 'code'}"])


def _stream(binary, text: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(binary)], input=text.encode("utf-8"), capture_output=True)


@needs_cc
def test_the_compiled_c_streams_a_labs_file_in_degf_k_mm_and_minutes_as_replay(tmp_path):
    # before: "the header ... lacks input column T_T0" (a converted column was left out of the
    # lab's names, its unit unknown to stream.c): the lab had to convert its file first
    path = _long(tmp_path / "alle.csv", _in_lab_units(_runs()))
    common, code = _exported(tmp_path, path)
    assert code == 0
    folder = tmp_path / "code"
    compiled(folder)
    cfg = _compose(*common, "model=lagbank", "monitor.adaptive=false", "track=false")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    assert test_ids == ["Lauf_3", "Lauf_4"]
    stream = deploy_stream(cfg, load_model(tmp_path / "run" / "model.pkl"),
                           {c: ds.campaigns[c] for c in train_ids})
    assert "time" in stream.columns_ or stream.time_required_      # the minutes matter
    want = np.vstack([-replay(stream, ds.campaigns[c])[stream.targets_].to_numpy(float)
                      for c in test_ids])
    lines = path.read_text(encoding="utf-8").splitlines()
    raw = "\n".join([lines[0], *(ln for ln in lines[1:] if ln.split(";")[0] in "34")]) + "\n"
    assert raw.startswith("Lauf;Zeit [min];T0 [°F];T1 [K];dX [mm]")    # the lab's own file
    run = _stream(folder / "stream", raw)
    assert run.returncode == 0, run.stderr
    got = pd.read_csv(io.BytesIO(run.stdout)).to_numpy(float)
    assert got.shape == want.shape == (60, 1)
    assert np.abs(got - want).max() <= 1e-9
    units = json.loads((folder / "compensator.json").read_text())["provenance"]["lab_units"]
    assert units["T0 [°F]"][0] == "T_T0" and units["T1 [K]"][1:] == [1.0, -273.15]
    # the same rows under contract names are in the contract's units: read as they are
    contract = raw.replace("Zeit [min]", "time", 1).replace("T0 [°F]", "T_T0", 1)
    moved = _stream(folder / "stream", contract)
    assert moved.returncode == 0, moved.stderr
    assert np.abs(pd.read_csv(io.BytesIO(moved.stdout)).to_numpy(float) - want).max() > 1.0
    # a reference measurement in mm (adapt.method=bias learns from each row's dX): learned as
    # the same error in µm under its contract name
    assert main(["export", *common, "monitor.adaptive=false", "adapt.method=bias",
                 "export.format=c", "track=false", f"export.model={tmp_path / 'run' / 'model.pkl'}",
                 f"out={tmp_path / 'adapt'}"]) == 0
    compiled(tmp_path / "adapt")
    learned = _stream(tmp_path / "adapt" / "stream", raw)
    frame = pd.read_csv(io.StringIO(raw), sep=";", decimal=",")
    frame["dX [mm]"] *= 1e3
    in_um = frame.rename(columns={"dX [mm]": "E_dX"}).to_csv(sep=";", decimal=",", index=False)
    as_um = _stream(tmp_path / "adapt" / "stream", in_um)
    assert learned.returncode == as_um.returncode == 0, learned.stderr + as_um.stderr
    learned, as_um = (pd.read_csv(io.BytesIO(r.stdout)).to_numpy(float) for r in (learned, as_um))
    assert np.abs(learned - got).max() > 0.1          # the references moved the corrections
    assert np.abs(learned - as_um).max() <= 1e-9
    # JSON Lines: refused saying what to do
    jsonl = "\n".join(json.dumps({"Zeit [min]": 0.0, "T0 [°F]": 68.0}) for _ in range(2)) + "\n"
    bad = _stream(folder / "stream", jsonl)
    assert bad.returncode == 2 and b"convert the file to CSV" in bad.stderr, bad.stderr



def dated_runs() -> list[pd.DataFrame]:
    """test_run_column52's runs, a week apart, timed by a date and a time of day in two columns
    (``Datum``, ``Uhrzeit``: a lab's export) in place of their seconds."""
    runs = _runs()
    for k, r in enumerate(runs):
        start = pd.Timestamp("2023-03-01 08:00") + pd.Timedelta(days=7 * k)
        stamps = start + pd.to_timedelta(r.pop("Zeit [s]"), unit="s")
        r.insert(0, "Uhrzeit", stamps.dt.strftime("%H:%M:%S"))
        r.insert(0, "Datum", stamps.dt.strftime("%d.%m.%Y"))
    return runs


# (keysight70: '%m/%d/%Y %H:%M:%S', this test's form before, is read by stream.c now, TC_SLASHED)
@pytest.mark.parametrize("form, extra, says", [
    ("%d-%b-%Y %H:%M:%S", ("data.time='%d-%b-%Y %H:%M:%S'",),
     ("'Zeit'", "data.time=%d-%b-%Y %H:%M:%S"))])
def test_a_time_stream_c_cannot_read_is_refused_at_export_naming_its_column(tmp_path, capsys,
                                                                            form, extra, says):
    # before: exported, and the compiled stream refused every row ("the time is no number", a
    # date alone)
    runs = _runs()
    for k, r in enumerate(runs):
        start = pd.Timestamp("2023-03-01 08:00") + pd.Timedelta(days=7 * k)
        stamps = (start + pd.to_timedelta(r.pop("Zeit [s]"), unit="s")).dt.strftime(form)
        if ";" in form:        # the date and its time of day in two columns
            r.insert(0, "Uhrzeit", stamps.str.split(";").str[1])
            r.insert(0, "Datum", stamps.str.split(";").str[0])
        else:
            r.insert(0, "Zeit", stamps)
    path = _long(tmp_path / "alle.csv", runs)
    common = (f"data.path={path}", *DATA, *extra)
    assert main(["run", *common, "model=lagbank", *FAST, f"out={tmp_path / 'run'}"]) == 0
    refused(["export", *common, "monitor.adaptive=false", "export.format=c", "track=false",
             f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"],
            capsys, "export.format=c", *says)
    assert not (tmp_path / "code").exists()


@needs_cc
def test_a_date_and_its_time_of_day_in_two_columns_are_joined_by_the_compiled_stream(tmp_path):
    # stranger65: refused at export ("a date ('Datum') and a time of day ('Uhrzeit') in two
    # columns, which stream.c does not join"); stream.c joins them now, as the reader does
    from test_export import checked_pack

    runs = dated_runs()
    path = _long(tmp_path / "alle.csv", runs)
    common = (f"data.path={path}", *DATA, "data.roles.time=[Datum,Uhrzeit]")
    assert main(["run", *common, "model=lagbank", *FAST, f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "monitor.adaptive=false", "export.format=c", "track=false",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    checked_pack(tmp_path / "code")
    done = _stream(tmp_path / "code" / "stream", path.read_text(encoding="utf-8"))
    assert done.returncode == 0, done.stderr
    assert len(done.stdout.splitlines()) == sum(len(r) for r in runs) + 1
