"""A lab's date that no calendar has (stop 97, benchmarks/bench_audit97.py ``lab``).

A tab-delimited export with ``dd.mm.yyyy hh:mm:ss`` stamps is read by a strptime format, and
Arrow's reads day 29-31 of a shorter month as the next month's first days: a mistyped
``31.02.2027 04:19:00`` (data row 500 of seed 9826's file) was read as 2027-03-03 and refused as
"time decreases ... sort them by their time", and a logger's leap day in a common year
(``29.02.2027 00:04:00`` between 28.02 23:59 and 01.03 00:01) was read as March 1 without a word,
where the exported C refuses the row ("the time is no ... date and time").  Now the cell is
refused as written, its file, column and row named.
"""

from __future__ import annotations

from datetime import datetime, timedelta

import pyarrow as pa
import pytest
import yaml

from thermocomp.core.io.timestamps import parsed, time_type
from thermocomp.shell.cli import main

DAY_FIRST = "%d.%m.%Y %H:%M:%S"
START = datetime(2027, 2, 28, 23, 40)


def tab_export(path, stamps: list[str]):
    """A German PC's tab-delimited export: stamps, ``_degC`` / ``_um`` suffixes, a trailing tab."""
    rows = ["Zeitstempel\tTemp_Spindel_degC\tTemp_Halle_degC\tFehler_X_um\t"]
    rows += [f"{s}\t{21 + 0.02 * i:.2f}\t{20 + 0.01 * (i % 7):.2f}\t{0.3 * i:.1f}\t"
             for i, s in enumerate(stamps)]
    path.write_bytes(("\r\n".join(rows) + "\r\n").encode())
    return path


def stamps(n: int = 40) -> list[str]:
    return [f"{START + timedelta(minutes=i):{DAY_FIRST}}" for i in range(n)]


def test_a_tab_export_with_day_first_stamps_is_read(tmp_path):
    path = tab_export(tmp_path / "messung.txt", stamps())
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "messung.yaml").read_text())
    assert config["delimiter"] == "\t" and config["roles"]["error"] == ["Fehler_X"]


@pytest.mark.parametrize("row, written", [(25, "29.02.2027 00:04:00"),    # a leap day in 2027
                                          (10, "31.02.2027 23:49:00")])
def test_a_day_its_month_has_not_is_refused_as_written(tmp_path, capsys, row, written):
    cells = stamps()
    cells[row - 1] = written
    path = tab_export(tmp_path / "messung.txt", cells)
    capsys.readouterr()
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 2
    said = capsys.readouterr().err
    assert f"data row {row})" in said and repr(written) in said and "day of the calendar" in said
    assert "messung.txt" in said and "'time'" in said
    assert not (tmp_path / "init").exists()


def test_the_strptime_path_refuses_a_missing_day_and_keeps_a_leap_day():
    target = time_type(DAY_FIRST, "")
    with pytest.raises(pa.ArrowInvalid, match="no such day"):
        parsed(pa.array(["30.04.2027 23:59:00", "31.04.2027 00:00:00"]), target, DAY_FIRST)
    got = parsed(pa.array(["29.02.2028 00:00:00", "1.3.2028 0:01:00"]), target, DAY_FIRST)
    assert [s.as_py() for s in got] == [datetime(2028, 2, 29), datetime(2028, 3, 1, 0, 1)]


def test_a_stream_refuses_a_missing_day_naming_its_row():
    # a served block or monitor.input=- reads its stamps by the same function: it read
    # 29.02.2027 as March 1 (the C, fed the same rows, refuses the row)
    import pandas as pd

    from thermocomp.core.io.contract import ContractError
    from thermocomp.core.io.stdin import stream_stamps

    with pytest.raises(ContractError, match=r"row 2\b.*'29\.02\.2027 00:04:00' is not a day of the calendar"):
        stream_stamps(pd.Series(["28.02.2027 23:59:00", "29.02.2027 00:04:00"]))
