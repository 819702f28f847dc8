"""A lab's raw export whose only time is a dateless ``h:mm:ss`` under a header no time header
names (``Uhrzeit``), and a served session's pause between blocks (data92).

The refusal of such a column offered ``data.time=of_day`` for "the time of day as the time";
typed, it was refused again by the same message (the key says what the time column holds, and
there was none): it now names ``data.roles.time`` beside it.  A served session reading a
dateless clock warned of nothing where a pause between two blocks reads as well a day longer
(the file reader warns of it in a file): now warned, by the file's pause rule."""

from __future__ import annotations

import logging
import re

import pandas as pd

from conftest import refused
from test_data88b import _clock, _record
from thermocomp.core.io.stdin import stream_stamps
from thermocomp.shell.cli import main


def _raw_clock(rows: pd.DataFrame, header: str = "Uhrzeit") -> str:
    """``rows`` as a lab's PC writes them: a BOM, ``;``, decimal commas, units in the headers,
    CRLF, the time a dateless ``h:mm:ss`` under ``header`` (past midnight)."""
    clock = _clock(rows)
    head = [header, "T a [°C]", "T b [°C]", "T c [°C]", "dX [µm]"]
    body = [[r.Time, *(repr(float(v)).replace(".", ",") for v in (r.T_a, r.T_b, r.T_c, r.E_X))]
            for r in clock.itertuples(index=False)]
    return "\ufeff" + "".join(";".join(cells) + "\r\n" for cells in [head, *body])


def test_the_refusals_time_of_day_key_typed_as_written_reads_the_file(tmp_path, capsys):
    rows = _record(921)
    # (data92b: 'Uhrzeit' names a time of day, read so with no key: a header no time header names)
    (tmp_path / "lab.csv").write_bytes(_raw_clock(rows, "Erfasst").encode("utf-8"))
    said = refused(["init", str(tmp_path / "lab.csv"), f"out={tmp_path / 'a'}"], capsys,
                   "lab.csv", "column 'time'", "data row 1", "data.time=of_day")
    keys = re.findall(r"data\.[\w.]+=[^\s)]+", said.rpartition("the time of day as the time, ")[2])
    assert "data.time=of_day" in keys
    # before: the key alone, typed, was refused by this very message
    assert main(["init", str(tmp_path / "lab.csv"), *keys, f"out={tmp_path / 'b'}"]) == 0
    written = next((tmp_path / "b" / "conf" / "data").glob("*.yaml")).read_text()
    assert "time: Erfasst" in written and "time: of_day" in written


def _served_clock(pause_s: float) -> pd.Series:
    """A dateless clock from 21:30 (blocks of 7 rows), ``pause_s`` more before row 15."""
    rows = _record(922)
    rows = rows.assign(time=rows["time"] + pause_s * (rows.index >= 14))
    return _clock(rows)["Time"]


def _warned(clock: pd.Series, caplog) -> list[str]:
    carried = [float("nan"), 0.0]
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        for a in range(0, len(clock), 7):
            stream_stamps(clock.iloc[a:a + 7].reset_index(drop=True), served=True, carried=carried)
    return [r.getMessage() for r in caplog.records if "a day lost" in r.getMessage()]


def test_a_served_session_warns_of_a_pause_between_blocks_a_day_could_hide(caplog):
    # before: the blocks after a 10 h pause (120 sample periods) read on in silence: a day more
    # or less between two blocks gives the same corrections
    [said] = _warned(_served_clock(10 * 3600.0), caplog)
    assert "data row 1 of the block" in said and "since the session's last block" in said
    assert "timestamp" in said and "reset=true" in said
    assert not _warned(_served_clock(0.0), caplog)            # a clock without a pause: nothing
