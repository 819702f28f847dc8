"""What the reader says of a file is said once per stage run (small69): ``init`` reads a file
more than once (its look for a run counter, then the record), and each read said its warnings
again: stranger68's workbook had its first sheet's ``Maximum`` footer said twice, and a header
written again inside a sheet (keyed by the temporary CSV file, another at each look) too."""

from __future__ import annotations

import datetime as dt

import openpyxl

from test_stranger68 import NAMES, UNITS, _cover, _run_sheet
from thermocomp.base import log
from thermocomp.shell.cli import main

AGAIN_ROW = 60      # the sheet's row where the logger wrote its header again (a restart)


def _workbook(path, runs: int = 2):
    """stranger68's macro workbook (a cover, a sheet per run, a ``Maximum`` row under an empty
    row), run 1's header and unit rows written again at :data:`AGAIN_ROW`."""
    book = openpyxl.Workbook()
    _cover(book, runs)
    for run in range(1, runs + 1):
        _run_sheet(book.create_sheet(f"Run {run}"), run, dt.datetime(2027, 6, 12 + 2 * run, 6))
    sheet = book["Run 1"]
    sheet.insert_rows(AGAIN_ROW, 2)
    for column, (name, unit) in enumerate(zip(["Date / time", *NAMES], [None, *UNITS]), 1):
        sheet.cell(row=AGAIN_ROW, column=column, value=name)
        sheet.cell(row=AGAIN_ROW + 1, column=column, value=unit)
    book.save(path)
    return path


def test_init_of_a_workbook_says_each_sheets_footer_and_header_again_once(tmp_path, capsys):
    book = _workbook(tmp_path / "MTC800.xlsx")
    assert main(["init", str(book), f"out={tmp_path / 'init'}"]) == 0
    err = capsys.readouterr().err
    for run in (1, 2):
        assert err.count(f"sheet 'Run {run}': footer left out (1 line(s) under the data: "
                         "'Maximum,") == 1, err
    assert err.count(f"sheet 'Run 1', row {AGAIN_ROW}: the file's header written again") == 1, err


def test_init_of_a_csv_record_says_its_footer_once(tmp_path, capsys):
    path = tmp_path / "lab.csv"
    rows = [f"{60 * i},{20 + 0.01 * i:.2f},{21 + 0.02 * i:.2f},{0.1 * i:.2f}" for i in range(60)]
    path.write_text("t [s],T_a [°C],T_b [°C],dX [µm]\n" + "\n".join(rows) + "\nEnd of data\n",
                    encoding="utf-8")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    err = capsys.readouterr().err
    assert err.count("lab.csv: footer left out (1 line(s) under the data: 'End of data')") == 1, err


def test_only_the_readers_notes_are_said_once_and_only_within_a_stage_run(tmp_path, capsys):
    from thermocomp.core.io.again import warn  # a reader's warning (core/io registered)

    log.configure("INFO")
    for _ in range(2):
        warn(tmp_path / "a.csv", (7,))
    with log.said_once():
        for _ in range(3):
            warn(tmp_path / "a.csv", (7,))
            warn(tmp_path / "b.csv", (7,))         # another file: its own text
            log.logger.warning("link lost")        # a connection's event: each time
    err = capsys.readouterr().err
    assert err.count("a.csv, line 7: the file's header written again") == 2 + 1, err
    assert err.count("b.csv, line 7: the file's header written again") == 1, err
    assert err.count("link lost") == 3, err
