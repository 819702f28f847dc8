"""A TDM/TDX pair written by LabVIEW's storage VIs rather than DIAdem: its time a LabVIEW
timestamp (``eTimeUsi``: a 2^-64 s fraction, then seconds since 1904-01-01 UTC) and a local
column's ``flags`` block marking values not valid (0), the numbers stored under them zeros.
Before: the timestamp block refused ("value type 'eTimeUsi' is not read"), and flags were not
read: a flagged value entered the record as the 0 °C stored under it."""

from __future__ import annotations

import datetime as dt

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError

ROWS = 90
START = dt.datetime(2027, 4, 5, 6, 0, 0, 250000, tzinfo=dt.timezone.utc)   # a quarter second in
LABVIEW_1970 = 2082844800        # s from 1904-01-01 to 1970-01-01 (LabVIEW's epoch)


def _channels(day: int):
    t = np.arange(ROWS)
    return {"Halle": 20 + 0.01 * t + day, "Spindel": 25 + 0.03 * t, "dX": 0.5 * t + 0.1 * day}


def _labview_pair(folder, day: int, invalid=slice(0, 0)):
    """``run<day>.tdm`` + ``.tdx``: ``Time`` as eTimeUsi stamps, 60 s apart; the channels float64;
    ``Spindel``'s ``invalid`` rows stored as 0 and flagged 0 in a byte block."""
    folder.mkdir(parents=True, exist_ok=True)
    start = START + dt.timedelta(days=day - 1)
    whole, part = divmod(start.timestamp() + 60.0 * np.arange(ROWS), 1.0)
    stamps = np.zeros(ROWS, dtype=[("fraction", "<u8"), ("seconds", "<i8")])
    stamps["seconds"] = whole.astype("int64") + LABVIEW_1970
    stamps["fraction"] = np.round(part * 2.0 ** 64).astype("uint64")
    values = _channels(day)
    values["Spindel"][invalid] = 0.0
    flags = np.ones(ROWS, "u1")
    flags[invalid] = 0
    arrays = [("Time", "s", "DT_DATE", stamps, "eTimeUsi")] + [
        (n, "°C" if n != "dX" else "µm", "DT_DOUBLE", v, "eFloat64Usi") for n, v in values.items()]
    blocks, body, offset = [], [], 0
    with open(folder / f"run{day}.tdx", "wb") as f:
        for k, (_, _, _, v, vtype) in enumerate([*arrays, ("", "", "", flags, "eUInt8Usi")]):
            f.write(v.tobytes())
            blocks.append(f'<block byteOffset="{offset}" id="inc{k}" length="{ROWS}" '
                          f'valueType="{vtype}"/>')
            offset += v.nbytes
    for k, (name, unit, dtype, _, _) in enumerate(arrays):
        flagged = '<flags external="inc4"/>' if name == "Spindel" else ""
        body.append(f'<tdm_channel id="c{k}"><name>{name}</name><unit_string>{unit}</unit_string>'
                    f'<datatype>{dtype}</datatype><local_columns>#xpointer(id("l{k}"))'
                    f'</local_columns></tdm_channel><localcolumn id="l{k}"><global_flag>15'
                    f'</global_flag>{flagged}<sequence_representation>explicit'
                    f'</sequence_representation><values>#xpointer(id("s{k}"))</values></localcolumn>'
                    f'<double_sequence id="s{k}"><values external="inc{k}"/></double_sequence>')
    ids = " ".join(f'id("c{k}")' for k in range(len(arrays)))
    (folder / f"run{day}.tdm").write_text(
        '<?xml version="1.0" encoding="UTF-8"?><usi:tdm xmlns:usi="http://www.ni.com/Schemas/'
        f'USI/1_0" version="1.0"><usi:include><file byteOrder="littleEndian" url="run{day}.tdx">'
        + "".join(blocks) + f'</file></usi:include><usi:data><tdm_channelgroup id="g"><name>Log'
        f'</name><channels>#xpointer({ids})</channels></tdm_channelgroup>' + "".join(body)
        + "</usi:data></usi:tdm>", encoding="utf-8")
    return folder / f"run{day}.tdm"


def test_labview_timestamps_are_utc_to_the_fraction_of_a_second(tmp_path):
    for day in (1, 2):
        _labview_pair(tmp_path / "lv", day)
    ds, _ = read_dataset(tmp_path / "lv", {"roles": {"error": ["dX"]}, "test_fraction": 0.5})
    assert list(ds.campaigns) == ["run1", "run2"]
    # (no data.timezone: a LabVIEW stamp is UTC, to the quarter second it was written at)
    assert ds.manifest["start"].iloc[1] == pd.Timestamp(START + dt.timedelta(days=1))
    np.testing.assert_allclose(ds.campaigns["run2"]["time"], 60.0 * np.arange(ROWS), atol=1e-5)
    np.testing.assert_allclose(ds.campaigns["run2"]["T_Spindel"], _channels(2)["Spindel"])


def test_flagged_values_are_missing_not_the_zeros_stored_under_them(tmp_path):
    _labview_pair(tmp_path / "lv", 1, invalid=slice(40, 44))
    _labview_pair(tmp_path / "lv", 2)
    with pytest.raises(ContractError, match="gap of 4 missing values"):
        read_dataset(tmp_path / "lv", {"roles": {"error": ["dX"]}, "test_fraction": 0.5})
    ds, _ = read_dataset(tmp_path / "lv", {"roles": {"error": ["dX"]}, "test_fraction": 0.5,
                                           "max_gap_samples": 4})
    # the gap bridged from its neighbours: the spindle's ramp, not 0 °C
    np.testing.assert_allclose(ds.campaigns["run1"]["T_Spindel"], _channels(1)["Spindel"])


def test_a_channel_shorter_than_its_groups_time_ends_in_empty_rows(tmp_path, caplog):
    """DIAdem's channels of one group may end apart (tdm_loader's DIAdem test file: forces of
    11314 values beside a time of 11316); before: refused, "one length a group"."""
    path = _labview_pair(tmp_path / "lv", 1)
    _labview_pair(tmp_path / "lv", 2)
    header = path.read_text(encoding="utf-8")
    path.write_text(header.replace(f'id="inc1" length="{ROWS}"', f'id="inc1" length="{ROWS - 2}"'),
                    encoding="utf-8")
    from thermocomp.core.io.tdm import tdm_records

    (record,) = tdm_records(path)
    hall = next(c for c in record.channels if c.header.startswith("Halle"))
    assert hall.values.size == ROWS and np.isnan(hall.values[-2:]).all()
    np.testing.assert_array_equal(hall.values[:-2], _channels(1)["Halle"][:-2])
    assert "'Halle' 88" in caplog.text and "their last rows empty" in caplog.text


def _inline_header(path, groups: dict) -> None:
    """A TDM header with every value inline (no TDX): ``groups`` name -> [(channel, datatype,
    values)]."""
    body, refs, k = [], [], 0
    for gid, (group, channels) in enumerate(groups.items()):
        ids = []
        for name, dtype, values in channels:
            cells = "".join(f"<A>{float(v)!r}</A>" for v in values)
            body.append(f'<tdm_channel id="c{k}"><name>{name}</name><datatype>{dtype}</datatype>'
                        f'<local_columns>#xpointer(id("l{k}"))</local_columns></tdm_channel>'
                        f'<localcolumn id="l{k}"><values>#xpointer(id("s{k}"))</values>'
                        f'</localcolumn><double_sequence id="s{k}"><values>{cells}</values>'
                        "</double_sequence>")
            ids.append(f'id("c{k}")')
            k += 1
        refs.append(f'<tdm_channelgroup id="g{gid}"><name>{group}</name><channels>'
                    f'#xpointer({" ".join(ids)})</channels></tdm_channelgroup>')
    path.write_text('<?xml version="1.0" encoding="UTF-8"?><usi:tdm xmlns:usi="http://www.ni.com/'
                    'Schemas/USI/1_0" version="1.0"><usi:data>' + "".join(refs + body)
                    + "</usi:data></usi:tdm>", encoding="utf-8")


def test_an_evaluation_group_without_time_reads_on_the_raw_groups_rows(tmp_path, caplog):
    """DIAdem's evaluation group (tdm_loader's DIAdem file: ``Auswertung``, no time, beside the
    raw group and its dates); before: "no grid reads them together"."""
    from thermocomp.core.io.tdm import DIADEM_EPOCH_S, tdm_records

    dates = DIADEM_EPOCH_S + 1.8e9 + 60.0 * np.arange(6)
    _inline_header(path := tmp_path / "eval.tdm", {
        "Rohwerte": [("Zeit", "DT_DATE", dates), ("T1", "DT_DOUBLE", np.arange(6.0))],
        "Auswertung": [("T1_Offset", "DT_DOUBLE", np.arange(5.0) - 0.5)]})
    (record,) = tdm_records(path)
    offset = next(c for c in record.channels if c.header == "T1_Offset")
    np.testing.assert_array_equal(offset.time, record.channels[0].time)
    np.testing.assert_array_equal(offset.values[:5], np.arange(5.0) - 0.5)
    assert np.isnan(offset.values[5])
    assert "group 'Auswertung' has no time of its own: read on group 'Rohwerte''s" in caplog.text
