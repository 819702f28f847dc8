"""A thermocouple unplugged from a Keysight DAQ reads ``+9.90000000E+37`` (the unit's overload
mark): the reader named it another quantity (or a fault replay streams, which it refused), and
the compiled stream read it as a temperature and clamped it, without a word
(``benchmarks/bench_faults71.py``: keysight70's test run, the corrections up to 160 µm off)."""

from __future__ import annotations

import subprocess

import pytest

from test_export import needs_cc
from test_streamraw65 import _common, _mlr_stream, logger_file
from thermocomp.core.io import ContractError, read_dataset

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
