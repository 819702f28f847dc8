"""AmeriFlux's ``-9999`` (lab74): a numeric mark of ``data.missing_values`` matched by its
number however a cell writes it (``-9999``, ``-9999.0``, ``-9999.000``, ``-9999,0``), by the
file reader, a stream on stdin and a historian's long file; ``init`` proposes it for an
AmeriFlux table (``TIMESTAMP_START``) and only says it for another file.  Before, the mark was
refused ("must be a list of marks that are no number"), and a -9999 a temperature "below
absolute zero"."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import thermocomp
from test_historian60 import BEARING, CFG, samples, write
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.stdin import read_stream

FLUX = Path(__file__).parents[1] / "data" / "realexport73" / "21031_Statistics_AmeriFlux37_head.dat"
ROLES = {"error": ["T_1_9_1"], "state": ["NETRAD"],
         "ignore": ["ALB", "SW_*", "LW*", "PPFD_IN", "VWC*", "Ka*", "BulkEC*", "WS", "WD",
                    "T_CANOPY", "T_SI111_body", "T_1_3_1", "T_1_4_1", "T_1_6_1", "T_1_7_1",
                    "T__1_8_1"]}


def nines(path: Path) -> Path:
    """The flux table with -9999 written three ways: two rows of the soil's ``T_1_5_1`` (a gap
    of 2) and one of ``NETRAD`` (a state)."""
    lines = FLUX.read_text().splitlines()
    header = lines[0].split(",")
    soil, radiation = header.index('"T_1_5_1"'), header.index('"NETRAD"')
    for row, column, cell in ((6, soil, "-9999"), (7, soil, "-9999.000"), (10, radiation, "-9999.0")):
        cells = lines[row].split(",")
        cells[column] = cell
        lines[row] = ",".join(cells)
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_numeric_mark_reads_its_number_however_written_as_missing(tmp_path, caplog):
    """``data.missing_values=[-9999]`` (a YAML number, or its text): the three cells missing,
    repaired as gaps; the state's said (a state could read -9999)."""
    path = nines(tmp_path / "flux.dat")
    for given in ([-9999], ["-9999"]):
        ds, report = read_dataset(path, {"roles": ROLES, "missing_values": given,
                                         "max_gap_samples": 2}, missing="keep")
        df = ds.campaigns[ds.ids()[0]]
        assert df["T_1_5_1"].isna().to_numpy().nonzero()[0].tolist() == [5, 6]
        assert df["S_NETRAD"].isna().to_numpy().nonzero()[0].tolist() == [9]
    assert "column 'S_NETRAD': 1 cell(s) equal to a number of data.missing_values" in caplog.text
    ds, report = read_dataset(path, {"roles": ROLES, "missing_values": [-9999], "max_gap_samples": 2})
    assert report["campaigns"][ds.ids()[0]]["repairs"] == {"S_NETRAD": 1, "T_1_5_1": 2}


def test_a_number_that_is_a_reading_is_still_refused_as_a_mark():
    with pytest.raises(ContractError, match="below absolute zero .AmeriFlux's -9999."):
        ReadOptions.from_cfg({"missing_values": ["-99"]})


def test_init_proposes_minus_9999_for_an_ameriflux_table(tmp_path):
    path = nines(tmp_path / "flux.dat")
    roles = [f"data.roles.{k}=[{','.join(v)}]" for k, v in ROLES.items()]
    said = thermocomp("init", str(path), *roles, f"out={tmp_path / 'init'}").stdout
    assert ("'-9999' in 3 cells of number columns 'NETRAD', 'T_1_5_1': AmeriFlux's mark, in an "
            "AmeriFlux table (its TIMESTAMP_START): a mark for a value not measured") in said, said
    written = (tmp_path / "init" / "conf" / "data" / "flux.yaml").read_text()
    assert "missing_values:\n- '-9999'\nmax_gap_samples: 2\n" in written


def test_init_says_minus_9999_in_another_file_and_reads_it_as_written(tmp_path):
    """A lab's file (no TIMESTAMP_START): -9999 µm may be a reading, never dropped silently."""
    path = tmp_path / "lab.csv"
    rows = [f"{60 * i},{20 + 0.1 * i:.1f},{-9999 if i == 5 else 2 * i}" for i in range(30)]
    path.write_text("time [s],T1 [°C],dX [um]\n" + "\n".join(rows) + "\n")
    said = thermocomp("init", str(path), "data.roles.error=[dX]", f"out={tmp_path / 'init'}").stdout
    assert ("-9999 in 1 cell of 'dX [um]': AmeriFlux's mark for a value not measured? not "
            "written: the file is no AmeriFlux table") in said, said
    assert "missing_values" not in (tmp_path / "init" / "conf" / "data" / "lab.yaml").read_text()
    ds, _ = read_dataset(path, {"roles": {"error": ["dX"]}})
    assert ds.campaigns[ds.ids()[0]]["E_dX"].iloc[5] == -9999.0


def test_a_stream_on_stdin_reads_the_mark_as_the_file_does():
    """Decimal commas (``-9999,000``) and a point (``-9999.0``): missing, counted."""
    opts = ReadOptions.from_cfg({"missing_values": ["-9999"], "delimiter": ";", "decimal": ","})
    text = "time;T_a;E_x\n0;20,5;1,0\n60;-9999,000;2,0\n120;21,0;-9999\n180;21,5;3,0\n"
    df, missing = read_stream(text, ["T_a"], opts)
    assert missing == {"T_a": 1, "E_x": 1}
    assert df["T_a"].isna().tolist() == [False, True, False, False]
    dotted = "time,T_a,E_x\n0,20.5,1.0\n60,-9999.0,2.0\n120,21.0,-9999\n180,21.5,3.0\n"
    df = read_stream(dotted, ["T_a"], ReadOptions.from_cfg({"missing_values": [-9999]}))[0]
    assert df["T_a"].isna().tolist() == [False, True, False, False]


def test_a_historians_long_file_reads_the_mark_as_a_bad_sample(tmp_path):
    """``-9999,0`` as a tag's value: missing until the tag's next sample, as a Bad one is."""
    frame = samples()
    marked = frame.index[frame["TagName"] == BEARING][5]
    frame.loc[marked, "Value"] = -9999.0
    write(frame, tmp_path / "pi.csv")
    bad = samples()
    bad.loc[marked, "Quality"] = "Bad"
    write(bad, tmp_path / "bad.csv")
    cfg = {**CFG, "missing_values": [-9999]}
    read = [read_dataset(tmp_path / name, cfg, missing="keep")[0] for name in ("pi.csv", "bad.csv")]
    got, want = (pd.concat([ds.campaigns[c] for c in ds.ids()]) for ds in read)
    column = f"T_{BEARING}"
    assert got[column].isna().sum() > 0
    np.testing.assert_array_equal(got[column].to_numpy(), want[column].to_numpy())
