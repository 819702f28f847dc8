"""Two more shapes of a lab's raw export: a Windows (cp1252 / Latin-1) file, and the date and the
time of day in two columns.  Each is read to the values it holds, or refused in one line naming
the file, the row and the setting that reads it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from conftest import refused
from test_raw_exports44 import _record
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.shell.cli import main


def _windows(path: Path, encoding: str = "cp1252", header=("Zeit [s]", "T1 [°C]", "dX [µm]"),
             cells: dict | None = None) -> Path:
    """A Windows export: ``;``-separated, decimal commas, CRLF, in ``encoding`` (° is 0xB0,
    µ 0xB5); ``cells``: {row: text} replacing T1's cell in that data row."""
    t, t1, _, e = _record()
    rows = [f"{a:g};{b:.4f};{c:.4f}".replace(".", ",") for a, b, c in zip(t, t1, e)]
    for row, text in (cells or {}).items():
        first, _, last = rows[row - 1].split(";")
        rows[row - 1] = f"{first};{text};{last}"
    path.write_bytes(("\r\n".join([";".join(header), *rows]) + "\r\n").encode(encoding))
    return path


@pytest.mark.parametrize("encoding", ["cp1252", "latin-1"])
def test_a_windows_export_is_refused_naming_data_encoding_and_init_writes_it(tmp_path, capsys,
                                                                             encoding):
    # before: refused "byte 0xb0 is not UTF-8 text (save the file as UTF-8)", no setting read it
    path = _windows(tmp_path / "win.csv", encoding)
    with pytest.raises(ContractError) as refusal:
        read_dataset(path, {"roles": {"error": ["dX"]}})
    assert "byte 0xb0" in str(refusal.value) and "data.encoding=cp1252" in str(refusal.value)
    assert refusal.value.file == path
    out = tmp_path / "init"
    assert main(["init", str(path), f"out={out}"]) == 0
    assert "win.csv: encoding cp1252 (not UTF-8)" in capsys.readouterr().out
    config = yaml.safe_load((out / "conf" / "data" / "win.yaml").read_text(encoding="utf-8"))
    assert config["encoding"] == "cp1252" and config["roles"]["error"] == ["dX"]
    ds, _ = read_dataset(path, {k: v for k, v in config.items() if k != "defaults"})
    t, t1, _, e = _record()
    frame = ds.campaigns["win_train"]
    assert list(frame.columns) == ["time", "T_T1", "E_dX"]       # '°C' and 'µm' read as units
    n = len(frame)
    np.testing.assert_allclose(frame[["time", "T_T1", "E_dX"]], np.c_[t, t1, e][:n], atol=1e-4)


def test_a_utf8_file_stays_utf8_in_the_config_init_writes(tmp_path):
    t, t1, _, e = _record()
    path = _windows(tmp_path / "utf8.csv", "utf-8")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    config = yaml.safe_load((tmp_path / "init/conf/data/utf8.yaml").read_text(encoding="utf-8"))
    assert "encoding" not in config                              # the default: UTF-8


def test_a_byte_the_encoding_does_not_read_is_refused_with_its_row_and_column(tmp_path, capsys):
    path = _windows(tmp_path / "odd.csv", cells={7: "21,55555"})
    path.write_bytes(path.read_bytes().replace(b"21,55555", b"21\x8155555"))  # 0x81: no cp1252 character
    out = tmp_path / "init"
    refused(["init", str(path), "data.encoding=cp1252", f"out={out}"], capsys, str(path),
            "line 8:", "'T1 [°C]'", "byte 0x81 is not cp1252")
    assert not out.exists()


def test_a_folder_written_in_cp1252_reads_its_manifest_with_the_same_encoding(tmp_path):
    root = tmp_path / "lab"
    root.mkdir()
    for cid in ("c1", "c2"):
        _windows(root / f"{cid}.csv")
    (root / "campaigns.csv").write_bytes(
        "campaign;file;split;notes\r\nc1;c1.csv;train;Halle 20 °C\r\nc2;c2.csv;test;µ-Abgleich\r\n"
        .encode("cp1252"))
    cfg = {"roles": {"error": ["dX"]}, "encoding": "cp1252"}
    ds, _ = read_dataset(root, cfg)
    assert list(ds.manifest["notes"]) == ["Halle 20 °C", "µ-Abgleich"]
    with pytest.raises(ContractError) as refusal:
        read_dataset(root, {"roles": {"error": ["dX"]}})
    assert refusal.value.file == root / "campaigns.csv" and "data.encoding=cp1252" in str(
        refusal.value)
    assert main(["init", str(root), f"out={tmp_path / 'init'}"]) == 0
    config = yaml.safe_load((tmp_path / "init/conf/data/lab.yaml").read_text(encoding="utf-8"))
    assert config["encoding"] == "cp1252"
    _windows(root / "c2.csv", "utf-8")     # saved again as UTF-8: never read '°C' as 'Â°C'
    with pytest.raises(ContractError) as refusal:
        read_dataset(root, cfg)
    assert refusal.value.file == root / "c2.csv" and "data.encoding=cp1252" in str(refusal.value)


@pytest.mark.parametrize("value", ["utf-16", "klingon"])
def test_an_encoding_that_cannot_be_read_is_refused_naming_the_key(tmp_path, capsys, value):
    path = _windows(tmp_path / "win.csv")
    refused(["init", str(path), f"data.encoding={value}", f"out={tmp_path / 'init'}"], capsys,
            "data.encoding", repr(value))


def _date_and_time(path: Path, header=("Datum", "Uhrzeit"), formats=("%d.%m.%Y", "%H:%M:%S"),
                   start: str = "2026-10-31 23:45:00") -> Path:
    """A German logger's export: the date and the time of day in two columns (crossing a
    midnight and a month), then the record."""
    t, t1, _, e = _record()
    stamps = pd.Timestamp(start) + pd.to_timedelta(t, unit="s")
    rows = [f"{s.strftime(formats[0])};{s.strftime(formats[1])};" + f"{b:.4f};{c:.4f}".replace(
        ".", ",") for s, b, c in zip(stamps, t1, e)]
    path.write_text("\n".join([";".join([*header, "T1 [°C]", "dX [µm]"]), *rows]) + "\n",
                    encoding="utf-8")
    return path


def test_a_date_and_a_time_of_day_in_two_columns_are_one_time_proposed_by_init(tmp_path, capsys):
    # before: both proposed 'ignore', and the run refused "no 'time' column ... set
    # data.sample_period_s"
    path = _date_and_time(tmp_path / "logger.csv")
    out = tmp_path / "init"
    assert main(["init", str(path), f"out={out}"]) == 0
    assert "time: 'Datum' + 'Uhrzeit', timestamps from 2026-10-31T23:45:00" in \
        capsys.readouterr().out
    config = yaml.safe_load((out / "conf/data/logger.yaml").read_text(encoding="utf-8"))
    assert config["roles"]["time"] == ["Datum", "Uhrzeit"]
    ds, report = read_dataset(path, {"roles": config["roles"]})
    (cid,) = ds.ids()
    assert list(ds.campaigns[cid].columns) == ["time", "T_T1", "E_dX"]
    np.testing.assert_allclose(ds.campaigns[cid]["time"], _record()[0])   # past midnight
    assert report["campaigns"][cid]["time_origin"] == "2026-10-31T23:45:00"


def test_data_time_reads_the_joined_date_and_time_of_day(tmp_path, capsys):
    path = _date_and_time(tmp_path / "us.csv", ("Date", "Time"), ("%m/%d/%Y", "%I:%M:%S %p"))
    roles = {"error": ["dX"], "time": ["Date", "Time"]}
    with pytest.raises(ContractError) as refusal:        # day or month first: never guessed
        read_dataset(path, {"roles": roles})
    assert "data.time=" in str(refusal.value)
    ds, report = read_dataset(path, {"roles": roles, "time": "%m/%d/%Y %I:%M:%S %p"})
    np.testing.assert_allclose(ds.campaigns["us"]["time"], _record()[0])
    assert report["campaigns"]["us"]["time_origin"] == "2026-10-31T23:45:00"


def test_a_time_of_day_cell_out_of_format_is_refused_naming_its_row(tmp_path, capsys):
    path = _date_and_time(tmp_path / "logger.csv")
    lines = path.read_text(encoding="utf-8").splitlines()
    lines[9] = lines[9].replace(":", ".", 1)               # '00.33:00'
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    out = tmp_path / "init"
    refused(["init", str(path), f"out={out}"], capsys, str(path), "column 'time'", "row 9",
            "date and the time of day joined")
    assert not out.exists()


@pytest.mark.parametrize("time, says", [("Uhrzeit", None),
                                        ("Datum", "date without a time of day")])
def test_a_time_of_day_or_a_date_alone_is_refused_not_read_wrapped(tmp_path, capsys, time, says):
    # a date alone repeats over a day: refused; a time of day alone goes back at midnight:
    # (data88b) that step back of about a day is unwrapped, a continuing time (was refused)
    path = _date_and_time(tmp_path / "logger.csv")
    other = {"Uhrzeit": "Datum", "Datum": "Uhrzeit"}[time]
    out = tmp_path / "init"
    keys = [f"data.roles.time={time}", f"data.roles.ignore=[{other}]", "data.roles.error=[dX]"]
    if says is None:
        ds, _ = read_dataset(path, {"roles": {"time": time, "ignore": [other], "error": ["dX"]}})
        time_s = ds.campaigns["logger"]["time"]
        np.testing.assert_allclose(time_s - time_s.iloc[0], _record()[0])
    else:
        refused(["init", str(path), *keys, f"out={out}"], capsys, str(path), says,
                "data.roles.time=[")
        assert not out.exists()
    path = _date_and_time(tmp_path / "zeit.csv", ("Datum", "Zeit"))   # 'Zeit' reads as a time
    ds, _ = read_dataset(path, {"roles": {"error": ["dX"]}})          # joined to its date
    np.testing.assert_allclose(ds.campaigns["zeit"]["time"], _record()[0])


def test_a_parquet_record_joins_its_date_and_time_of_day_too(tmp_path):
    t, t1, _, e = _record()
    stamps = pd.Timestamp("2026-10-31 23:45:00") + pd.to_timedelta(t, unit="s")
    path = tmp_path / "logger.parquet"
    pd.DataFrame({"Datum": stamps.strftime("%d.%m.%Y"), "Uhrzeit": stamps.strftime("%H:%M:%S"),
                  "T1": t1, "dX": e}).to_parquet(path)
    ds, _ = read_dataset(path, {"roles": {"error": ["dX"], "time": ["Datum", "Uhrzeit"]}})
    np.testing.assert_allclose(ds.campaigns["logger"][["time", "T_T1"]], np.c_[t, t1])


def test_a_stream_on_stdin_is_decoded_with_data_encoding():
    # before: monitor.input=- decoded stdin with the locale's encoding (UTF-8): a Windows
    # logger's '°' failed to decode, whatever the data config said
    from io import BytesIO, TextIOWrapper

    from thermocomp.core.io.stdin import stdin_text

    rows = "time;T_1 [°C]\n0;20,5\n"
    assert stdin_text(TextIOWrapper(BytesIO(rows.encode("cp1252"))), "cp1252") == rows
    with pytest.raises(ContractError) as refusal:
        stdin_text(TextIOWrapper(BytesIO(rows.encode("cp1252"))))
    assert "byte 0xb0" in str(refusal.value) and "data.encoding" in str(refusal.value)


@pytest.mark.parametrize("first", ["13:05:00", "28.11.2026"])
def test_a_stream_whose_time_lacks_its_date_or_time_of_day_is_told_what_a_stream_needs(first):
    # (round 45: a stream reads data.roles too, and the refusal says how to join the two)
    import pandas as pd

    from thermocomp.base.errors import ContractError
    from thermocomp.core.io.stdin import stream_seconds

    with pytest.raises(ContractError) as refused:
        stream_seconds(pd.Series([first, first]), "auto")
    assert "a stream's time is one column" in str(refused.value)
    assert "data.roles.time=[<date column>, <time column>]" in str(refused.value)
