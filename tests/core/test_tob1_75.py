"""Campbell Scientific's binary table TOB1 (lab75), written here with ``struct.pack`` to the
format's description (five ASCII header lines as TOA5's, the fifth the data types; then
little-endian records, ``FP2`` big-endian: sign, 2-bit decimal exponent, 13-bit mantissa),
read as a TOA5 file is: ``SECONDS`` + ``NANOSECONDS`` from 1990-01-01 the time, ``RECORD`` left
out, FP2's infinity (``0x1FFF``, the logger's ``INF``) a missing value.  Before: every byte of
the file read as text, refused."""

from __future__ import annotations

import datetime as dt
import math
import struct
from pathlib import Path

import numpy as np
import pytest

from conftest import thermocomp
from thermocomp.core.io import ContractError, read_dataset

START = dt.datetime(2025, 3, 27, 23, 30)
HEAD = ['"TOB1","MZ_Halle3","CR1000X","12345","CR1000X.Std.05.02","CPU:thermo_mz.CR1X","26142",'
        '"Therm10min"',
        '"SECONDS","NANOSECONDS","RECORD","T_spindle_Avg","T_air_Avg","dX_Avg","dZ_Avg","BattV_Min"',
        '"SECONDS","NANOSECONDS","RN","Deg C","Deg C","um","mm","Volts"',
        '"","","","Avg","Avg","Avg","Avg","Min"',
        '"ULONG","ULONG","ULONG","IEEE4","IEEE8","FP2","IEEE4","FP2"']
INF_ROW = 9          # BattV_Min's FP2 infinity (a gap of 1)


def fp2(value: float, word: int | None = None) -> bytes:
    """``value`` in FP2, the most decimals its mantissa holds (``word``: that word as written)."""
    if word is None:
        for exponent in (3, 2, 1, 0):
            mantissa = round(abs(value) * 10 ** exponent)
            if mantissa <= 7999:
                word = (0x8000 if value < 0 else 0) | exponent << 13 | mantissa
                break
    return struct.pack(">H", word)


def spindle(i: int) -> tuple:
    return (20 + 3 * (1 - math.exp(-i / 8)), 20 + 0.02 * i, 4 * (1 - math.exp(-i / 6)) - 0.5,
            0.025 * (1 - math.exp(-i / 7)))


def tob1(path: Path, rows: int = 24, head=HEAD) -> Path:
    seconds = int((START - dt.datetime(1990, 1, 1)).total_seconds())
    body = b""
    for i in range(rows):
        t_spindle, t_air, dx, dz = spindle(i)
        body += struct.pack("<III", seconds + 600 * i, 500_000_000 * (i == 1), 1000 + i)
        body += struct.pack("<fd", t_spindle, t_air) + fp2(dx) + struct.pack("<f", dz)
        body += fp2(12.61, 0x1FFF if i == INF_ROW else None)
    path.write_bytes(("\r\n".join(head) + "\r\n").encode() + body)
    return path


def test_a_tob1_file_reads_as_its_toa5_would(tmp_path):
    ds, report = read_dataset(tob1(tmp_path / "therm.dat"),
                              {"roles": {"error": ["d*"]}, "max_gap_samples": 1})
    df = ds.campaigns[ds.ids()[0]]
    assert list(df.columns) == ["time", "T_spindle_Avg", "T_air_Avg", "E_dX_Avg", "E_dZ_Avg",
                                "S_BattV_Min"]
    assert report["campaigns"][ds.ids()[0]]["time_origin"] == "2025-03-27T23:30:00"
    assert df["time"].iloc[:3].tolist() == [0.0, 600.5, 1200.0]       # (row 2: its nanoseconds)
    want = np.array([spindle(i) for i in range(24)])
    assert df["T_spindle_Avg"].to_numpy() == pytest.approx(want[:, 0], abs=1e-5)   # IEEE4
    assert df["T_air_Avg"].to_numpy() == pytest.approx(want[:, 1], abs=1e-12)      # IEEE8
    assert df["E_dX_Avg"].to_numpy() == pytest.approx(want[:, 2], abs=5e-4)        # FP2, µm
    assert df["E_dX_Avg"].iloc[0] == -0.5
    assert df["E_dZ_Avg"].to_numpy() == pytest.approx(want[:, 3] * 1000, abs=1e-3)  # mm -> µm
    assert report["campaigns"][ds.ids()[0]]["repairs"] == {"S_BattV_Min": 1}      # FP2's INF
    assert df["S_BattV_Min"].iloc[INF_ROW] == pytest.approx(12.61)


def test_init_then_run_read_a_tob1_file(tmp_path):
    """No key given: the table named, the FP2 infinity's gap proposed; ``run model=mlr`` reads
    the config ``init`` wrote."""
    tob1(tmp_path / "therm.dat")
    said = thermocomp("init", str(tmp_path / "therm.dat"), f"out={tmp_path / 'init'}").stdout
    assert ("therm.dat: a Campbell Scientific TOB1 table 'Therm10min' of station 'MZ_Halle3' "
            "(CR1000X, serial 12345, program 'CPU:thermo_mz.CR1X')") in said, said
    assert "dX_Avg [um]            error        E_dX_Avg" in said
    written = (tmp_path / "init" / "conf" / "data" / "therm.yaml").read_text()
    assert "max_gap_samples: 1" in written
    assert "encoding" not in written          # (lab76: it wrote cp1252, a binary file's bytes)
    ran = thermocomp("run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]",
                     "data=therm", "model=mlr", "eval.validation=false", "track=false",
                     "plots=none", f"out={tmp_path / 'run'}").stdout
    assert "E_dZ_Avg" in ran


def test_a_tob1_file_cut_short_or_of_an_unread_type_is_refused(tmp_path):
    path = tob1(tmp_path / "cut.dat")
    path.write_bytes(path.read_bytes()[:-5])
    with pytest.raises(ContractError, match=r"cut.dat, data row 24: the binary records are 32 "
                                            r"bytes each .* the last 27 bytes make no whole"):
        read_dataset(path, {"roles": {"error": ["d*"]}})
    odd = tob1(tmp_path / "odd.dat", head=[*HEAD[:4], HEAD[4].replace('"IEEE8"', '"ASCII(8)"')])
    with pytest.raises(ContractError, match=r"column 'T_air_Avg'.*data type 'ASCII\(8\)'"):
        read_dataset(odd, {"roles": {"error": ["d*"]}})
