"""A thermocouple unplugged from a Keysight DAQ reads ``+9.90000000E+37`` (the unit's overload
mark): the reader named it another quantity (or a fault replay streams, which it refused), and
the compiled stream read it as a temperature and clamped it, without a word
(``benchmarks/bench_faults71.py``: keysight70's test run, the corrections up to 160 µm off)."""

from __future__ import annotations

import subprocess

import numpy as np
import pytest

from conftest import FAST
from test_deploy import campaigns
from test_export import needs_cc
from test_streamraw65 import _common, _mlr_stream, logger_file
from test_twolog70 import _folder
from thermocomp.apps.deploy import OutOfEnvelopeError, StreamingCompensator
from thermocomp.core.compensator import Compensator
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.models import MLR
from thermocomp.shell.cli import main

OVERLOAD = "+9.90000000E+37"


@pytest.mark.parametrize("unplugged", [range(3, 12), range(10, 12)])
def test_an_overload_mark_among_temperatures_is_named_as_one(tmp_path, unplugged):
    # before: "no temperature, in °C or kelvin (the column's median is 4.95e+37): another
    # quantity? give its column a role" (half the rows), or "a faulty reading ...: replay and
    # monitor stream a test campaign with it" (two rows), though replay refuses it as well
    folder = tmp_path / "ds"
    folder.mkdir()
    rows = [f"{k},{OVERLOAD if k in unplugged else 20 + 0.1 * k},{k}" for k in range(12)]
    (folder / "K01.csv").write_text("time,T_0,E_X\n" + "\n".join(rows) + "\n")
    (folder / "campaigns.csv").write_text("campaign,file,split\nK01,K01.csv,train\n")
    with pytest.raises(ContractError) as info:
        read_dataset(folder)
    said = str(info.value)
    assert info.value.column == "T_0" and info.value.row == unplugged[0] + 1
    assert "K01.csv" in said and "no sensor reads" in said and "data.missing_values" in said
    assert "another quantity" not in said and "stream a test campaign with it" not in said


def test_the_overload_mark_may_be_listed_as_a_missing_value_and_no_reading_number(tmp_path):
    # before: "data.missing_values must be a list of marks that are no number", the hint of the
    # refusal above unfollowable
    folder = tmp_path / "ds"
    folder.mkdir()
    rows = [f"{k},{OVERLOAD if k == 5 else 20 + 0.1 * k},{k}" for k in range(12)]
    (folder / "K01.csv").write_text("time,T_0,E_X\n" + "\n".join(rows) + "\n")
    (folder / "campaigns.csv").write_text("campaign,file,split\nK01,K01.csv,train\n")
    read = read_dataset(folder, {"missing_values": [OVERLOAD], "max_gap_samples": 1}
                        )[0].campaigns["K01"]
    assert read["T_0"].max() < 30 and read["T_0"].notna().all()      # interpolated, as a gap
    with pytest.raises(ContractError, match="beyond any reading"):
        read_dataset(folder, {"missing_values": ["20000"]})            # an rpm a spindle reads


@needs_cc
def test_the_compiled_stream_refuses_an_overload_mark_as_the_reader_does(tmp_path):
    # before: exit 0, the reading clamped at the envelope's edge, nothing said
    train = logger_file(tmp_path / "train.csv", False, "utf-8", None, mark=20)
    code = _mlr_stream(tmp_path, _common(train, "utf-8") + ["data.missing_values=['---']",
                                                            "data.max_gap_samples=1"])
    raw = train.read_bytes().replace(b";---;", b";+9,90000000E+37;")
    done = subprocess.run(["./stream"], cwd=code, input=raw, capture_output=True)
    said = done.stderr.decode()
    assert done.returncode == 2, said
    assert "line 22: input T_Ständer: 9.9e+37 degC is beyond 10000 degC" in said
    assert "data.missing_values" in said
    assert len(done.stdout.decode().splitlines()) == 1 + 20          # the rows before it


def test_a_dropout_in_a_two_logger_run_is_refused_naming_whose_rows_it_counts(tmp_path, capsys):
    # before: "file .../run03_temp.csv, column 'T_Bed', data row 13: ..." of a file whose
    # empty cell is on its line 71 (the rows counted were run03_disp.csv's samples)
    folder = _folder(tmp_path / "runs")
    data = [f"data.path={folder}", "data.roles.error=[dX]", "data.roles.state=[Door]",
            "data.test_fraction=0.34"]
    assert main(["run", *data, "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    temp = folder / "run03_temp.csv"
    lines = temp.read_text().splitlines()
    lines[70:] = [",".join(c if k != 2 else "" for k, c in enumerate(x.split(",")))
                  for x in lines[70:]]                        # 'Bed [°C]' unplugged
    temp.write_text("\n".join(lines) + "\n")
    capsys.readouterr()
    assert main(["replay", *data, f"replay.model={tmp_path / 'out' / 'model.pkl'}",
                 "monitor.adaptive=false", "track=false", f"out={tmp_path / 'replay'}"]) == 2
    said = capsys.readouterr().err
    assert "run03_temp.csv (its rows: run03_disp.csv's samples" in said, said
    assert ("column 'T_Bed', data row 13: campaign run03: no finite value at 720 s "
            "from its first row") in said


@pytest.mark.parametrize("policy", ["clamp", "off"])
def test_the_plain_stream_refuses_an_overload_mark_as_it_refuses_a_missing_value(policy):
    # before: read as a temperature (clamp: at the envelope's edge; a lag bank's served plain
    # stream on keysight70's test run gave 1.2e39 µm; off: as it came)
    camps = campaigns(0)
    train = {c: camps[c] for c in list(camps)[:4]}
    stream = StreamingCompensator.from_training(Compensator(MLR()).fit(train), train,
                                                policy=policy)
    bad = camps["K05"].copy()
    bad.loc[3:, "T_2"] = 9.9e37
    with pytest.raises(OutOfEnvelopeError, match=r"T_2 reads 9.9e\+37 at row 3, beyond 10000 °C"):
        stream.predict(bad)
    assert stream.n_samples_ == 0               # the refused block left no trace
    assert np.isfinite(stream.predict(bad.iloc[:3])["E_Z"]).all()
