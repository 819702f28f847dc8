"""A Campbell Scientific logger's ASCII tables (lab74): TOA5, LoggerNet's default for a CR1000X
(``tests/data/campbell74/therm10min_toa5.dat``, written here to Campbell's manual's "TOA5 file
format": an environment line, names, units, processing, CRLF rows, ``"NAN"``), and the older
TOACI1.  Before, the environment line (8 fields, the table's width) was taken for the header."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from conftest import thermocomp
from thermocomp.core.io import read_dataset
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.stdin import read_stream

TOA5 = Path(__file__).parents[1] / "data" / "campbell74" / "therm10min_toa5.dat"
ROLES = {"roles": {"error": ["d*"]}, "max_gap_samples": 1}


def test_init_reads_a_toa5_file_as_loggernet_wrote_it(tmp_path):
    """No key given: the station and table said, the names from line 2, the units from line 3
    (``Deg C``, ``mm``, ``um``, ``Volts``), ``RECORD`` left out, ``TIMESTAMP`` the time, and the
    ``NAN`` cell's gap proposed (before: every column "a mark for a value not measured",
    refused: "no column reads as a measured error")."""
    said = thermocomp("init", str(TOA5), f"out={tmp_path}").stdout
    assert ("therm10min_toa5.dat: a Campbell Scientific TOA5 table 'Therm10min' of station "
            "'MZ_Halle3' (CR1000X, serial 12345, program 'CPU:thermo_mz.CR1X'), delimiter ',', "
            "decimal '.', header on line 2 (1 line(s) above it left out), units from line 3; "
            "rows counted from line 5") in said, said
    assert "time: 'TIMESTAMP', timestamps from 2025-03-27T23:30:00" in said
    assert "sample period: 600 s, 24 rows" in said
    for line in ("RECORD                 DAQ's own    - (left out: no measurement)",
                 "T_column_Avg [Deg C]   temperature  T_column_Avg",
                 "dX_Avg [mm]            error        E_dX_Avg",
                 "dZ_Avg [um]            error        E_dZ_Avg",
                 "BattV_Min [V]          state        S_BattV_Min"):
        assert line in said, said
    assert "data.max_gap_samples=1" in said
    written = next((tmp_path / "conf" / "data").glob("*.yaml")).read_text()
    assert "max_gap_samples: 1" in written


def test_a_toa5_file_reads_its_values_in_the_contracts_units():
    """mm to µm, the ``NAN`` cell a gap interpolated, 600 s between rows."""
    ds, report = read_dataset(TOA5, ROLES)
    df = ds.campaigns[ds.ids()[0]]
    assert list(df.columns) == ["time", "T_spindle_Avg", "T_column_Avg", "T_air_Avg",
                                "E_dX_Avg", "E_dZ_Avg", "S_BattV_Min"]
    assert np.diff(df["time"]).tolist() == [600.0] * 23
    assert df["E_dX_Avg"].iloc[1] == pytest.approx(0.8)          # 0.0008 mm
    assert df["E_dZ_Avg"].iloc[1] == pytest.approx(3.02)         # um
    assert df["T_column_Avg"].iloc[7] == pytest.approx((20.442 + 20.567) / 2)    # "NAN"
    assert report["campaigns"][ds.ids()[0]]["repairs"] == {"T_column_Avg": 1}


def test_a_toaci1_file_is_read_by_its_two_header_lines(tmp_path):
    """TOACI1: ``"TOACI1","<station>","<table>"``, the names (``TMSTAMP``, ``RECNBR``), rows."""
    rows = TOA5.read_text().splitlines()[4:]
    old = tmp_path / "therm10min.dat"
    old.write_text('"TOACI1","MZ_Halle3","Therm10min"\n"TMSTAMP","RECNBR","T_spindle",'
                   '"T_column","T_air","dX","dZ","BattV"\n' + "\n".join(rows) + "\n")
    ds, _ = read_dataset(old, {"roles": {"error": ["d*"], "state": ["BattV"]},
                               "max_gap_samples": 1})
    df = ds.campaigns[ds.ids()[0]]
    assert list(df.columns) == ["time", "T_spindle", "T_column", "T_air", "E_dX", "E_dZ",
                                "S_BattV"]
    assert df["time"].iloc[-1] == 23 * 600.0
    assert df["E_dZ"].iloc[1] == pytest.approx(3.02)


def test_a_toa5_file_streamed_on_stdin_reads_as_the_file():
    """``monitor monitor.input=-``: the same values as the file reader (before: the
    environment line the header, the stream refused)."""
    opts = ReadOptions.from_cfg(ROLES)
    df, missing = read_stream(TOA5.read_text(), ["T_spindle_Avg", "E_dX_Avg"], opts)
    ds, _ = read_dataset(TOA5, ROLES)
    read = ds.campaigns[ds.ids()[0]]
    assert missing == {"T_column_Avg": 1}                       # "NAN", streamed as NaN
    assert np.allclose(df["E_dX_Avg"], read["E_dX_Avg"])
    assert np.allclose(df["time"], read["time"])
    assert "RECORD" not in df.columns
