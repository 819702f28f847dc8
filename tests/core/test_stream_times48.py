"""A stream's timestamps are read as a campaign file's are (one parser: timestamps.parsed)."""

import pandas as pd
import pytest

from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.read import read_campaign
from thermocomp.core.io.stdin import read_stream, stream_seconds

FORMS = {
    "iso": ["2026-03-29T00:59:59", "2026-03-29T01:00:14.5", "2026-03-29T01:00:29"],
    "offset": ["2026-03-29T00:59:59+01:00", "2026-03-29T01:00:14+01:00", "2026-03-29T01:00:29Z"],
    "decimal comma": ["2026-03-29 00:59:59,500", "2026-03-29 01:00:14,250", "2026-03-29 01:00:29"],
    "day first": ["29.03.2026 00:59:59", "29.03.2026 01:00:14,250", "29.03.2026 01:00:29.5"],
    "nanoseconds": ["2026-03-29T00:59:59.123456789", "2026-03-29T01:00:14.5",
                    "2026-03-29T01:00:29.000000001"],
}


def _file_seconds(tmp_path, values, zone):
    path = tmp_path / "c.csv"
    path.write_text("time;T_a;E_X\n" + "".join(f"{v};{20 + i};{i}\n" for i, v in enumerate(values)))
    table, _ = read_campaign(path, {"timezone": zone} if zone else None)
    return table.column("time").to_pylist()


@pytest.mark.parametrize("zone", [None, "Europe/Berlin"])
@pytest.mark.parametrize("form", FORMS)
def test_a_stream_reads_its_times_as_a_file_does(tmp_path, form, zone):
    values = FORMS[form]
    assert stream_seconds(pd.Series(values), "auto", zone).tolist() == \
        _file_seconds(tmp_path, values, zone)


def test_a_time_without_the_offset_the_first_row_has_is_refused_with_its_row():
    # pandas read it as UTC: an hour off on a CET logger, without a word
    with pytest.raises(ContractError, match=r"data row 2.*with zone offset"):
        stream_seconds(pd.Series(["2026-03-29T00:59:59+01:00", "2026-03-29T01:00:14"]), "auto")


def test_a_fraction_on_a_later_row_of_a_formatted_time_is_read():
    # the format was widened to %S.%f for every row, and the first row (no fraction) refused
    times = pd.Series(["29/03/2026 00:59:59", "29/03/2026 01:00:14,5"])
    assert stream_seconds(times, "%d/%m/%Y %H:%M:%S").tolist() == [0.0, 15.5]


def test_a_missing_time_stays_missing_for_the_guard():
    times = pd.Series(["2026-03-29T00:59:59", None, " 2026-03-29T01:00:29 "])
    seconds = stream_seconds(times, "auto").tolist()
    assert seconds[0] == 0.0 and pd.isna(seconds[1]) and seconds[2] == 30.0


@pytest.mark.parametrize("fmt", ["auto", "%d.%m.%Y %H:%M:%S"])
def test_a_stream_whose_first_time_is_missing_reads_the_times_after_it(fmt):
    # a logger's first row without its time: was refused as 'data row 2: non-numeric value'
    # (auto: the form taken from row 1's missing cell) or 'value nan is not ...' at row 1
    times = pd.Series([None, "29.03.2026 01:00:14,5", "29.03.2026 01:00:29"])
    seconds = stream_seconds(times, fmt).tolist()
    assert pd.isna(seconds[0]) and seconds[1:] == [0.0, 14.5]


def test_a_stream_of_logger_rows_without_a_first_time_streams_its_rows():
    text = "time;T_a;E_X\n;20,5;1\n29.03.2026 01:00:14,5;20,6;2\n29.03.2026 01:00:29;20,7;3\n"
    frame, missing = read_stream(text, ["T_a"], ReadOptions.from_cfg({"delimiter": ";", "decimal": ","}))
    assert frame["T_a"].tolist() == [20.5, 20.6, 20.7] and missing == {"time": 1}
    assert frame["time"].tolist()[1:] == [0.0, 14.5]


def test_a_file_reads_a_time_padded_after_its_delimiter(tmp_path):
    # 'T_a; time' (a logger's '; '): the numbers were read, the time cell ' 2026-...' refused
    path = tmp_path / "padded.csv"
    path.write_text("T_a; time; E_X\n20.5; 2026-03-29 00:59:59; 1\n20.6; 2026-03-29 01:00:14; 2\n")
    table, _ = read_campaign(path)
    assert table.column("time").to_pylist() == [0.0, 15.0]


def test_a_bad_time_after_a_fraction_the_reader_skips_is_refused_with_its_row(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("time;T_a;E_X\n29.03.2026 00:59:59;20;1\n29.03.2026 01:00:14,5;21;1\n"
                    "29.03.2026 01:0x:29;22;1\n")
    with pytest.raises(ContractError, match=r"line 4 \(data row 3\).*01:0x:29"):
        read_campaign(path)


def _unnamed_error(tmp_path):
    path = tmp_path / "lab.csv"
    path.write_text("timestamp_ms,Spindle,Ambient,dX\n" + "".join(
        f"{1774742399000 + 15000 * i},{20 + 0.1 * i},20,{0.5 * i}\n" for i in range(20)))
    return path


def test_init_without_an_error_column_names_the_setting_and_the_columns(tmp_path, capsys):
    # before: "no E_ column: a campaign needs at least one measured error" (an ambient word in a
    # header), or, without one, "'dX' has no role ... `thermocomp init <data.path>` proposes them"
    # from init itself
    from conftest import refused
    path = _unnamed_error(tmp_path)
    refused(["init", str(path), f"out={tmp_path / 'out'}"], capsys, "no column reads as a measured",
            "data.roles.error=[<header>]", "'Spindle', 'Ambient', 'dX'")
    path.write_text(path.read_text().replace("Ambient", "Column"))
    refused(["init", str(path), f"out={tmp_path / 'out'}"], capsys, "data.roles.error=[<header>]")
    assert not (tmp_path / "out").exists()


def test_a_run_whose_roles_name_no_error_says_which_setting_and_columns(tmp_path, capsys):
    from conftest import refused
    path = _unnamed_error(tmp_path)
    refused(["run", f"data.path={path}", "data.roles.ambient=[Ambient]", f"out={tmp_path / 'o'}"],
            capsys, "no E_ column", "data.roles.error=[<header>]", "'Spindle', 'Ambient', 'dX'")
