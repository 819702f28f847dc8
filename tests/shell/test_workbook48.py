"""A lab's Excel workbook goes in as its CSV export does (session 48): ``data.path=<file>.xlsx``,
its first sheet or ``data.sheet``, read through the CSV reader, so ``init`` and ``run`` give on
it what they give on the same rows written as CSV; a message names the sheet and its row."""

from __future__ import annotations

import csv
import datetime as dt
import json
import re
import sys
import zipfile
from pathlib import Path

import openpyxl
import pytest
import yaml

from conftest import FAST, ROOT, refused
from thermocomp.shell.cli import main

RECORD = ROOT / "datasets" / "fl_thermal" / "spindle_test.csv"
ROWS = 300
START = dt.datetime(2026, 11, 28, 13, 5)
PREAMBLE = ["Logger FL-1", "exported 28.11.2026"]
GAP = 100          # data row (0-based) whose t5 is empty, repaired with data.max_gap_samples=1
FORMULAS = (150, 151)   # data rows (0-based) whose ch2 is a formula: its cached value is read
EMPTY_AFTER = 200       # an empty sheet row (a line of empty cells in the CSV) after this one
ROLES = ["data.roles.error=['ch*']", "data.roles.state=['spindle*']", "data.max_gap_samples=1"]


def _rows() -> tuple[list[str], list[str], list[list]]:
    """The shipped record's first ``ROWS`` rows, its time as dates 15 s apart: the header (units
    in the header for the state and errors), a unit row (the temperatures'), the rows."""
    with open(RECORD, encoding="utf-8", newline="") as f:
        lines = list(csv.reader(f))
    header = ["Zeit", *lines[0][1:]]
    header = [h.replace("(°C)", "") for h in header]          # their unit in the unit row
    units = ["°C" if h.startswith("t") else "" for h in header]
    rows = [[START + dt.timedelta(seconds=float(r[0])), *map(float, r[1:])]
            for r in lines[1:ROWS + 1]]
    rows[GAP][header.index("t5")] = None
    return header, units, rows


def _workbook(path: Path, first_sheet: str | None = None, bad: tuple[int, str] | None = None):
    """The rows as a lab's workbook (sheet 'Messung'; ``first_sheet``: a sheet of notes before
    it); ``bad``: (data row, text) put in ch1.  ch2's cells ``FORMULAS`` are formulas with the
    value Excel saves beside them."""
    header, units, rows = _rows()
    book = openpyxl.Workbook()
    notes = book.active
    if first_sheet:
        notes.title = first_sheet
        notes.append(["Prüfstand 3, Spindel B"])
        sheet = book.create_sheet("Messung")
    else:
        sheet, notes.title = notes, "Messung"
    for line in PREAMBLE:
        sheet.append([line])
    sheet.append(header)
    sheet.append(units)
    cached = {}
    for i, row in enumerate(rows):
        row = list(row)
        if i in FORMULAS:
            cell = f"{openpyxl.utils.get_column_letter(header.index('ch2(um)') + 1)}{sheet.max_row + 1}"
            cached[cell], row[header.index("ch2(um)")] = row[header.index("ch2(um)")], "=1*1"
        if bad is not None and i == bad[0]:
            row[header.index("ch1(um)")] = bad[1]
        sheet.append(row)
        if i == EMPTY_AFTER:
            sheet.append([])
    book.save(path)
    _cache(path, book.index(sheet) + 1, cached)
    return path


def _cache(path: Path, number: int, values: dict) -> None:
    """Give the formula cells ``values`` of the ``number``-th sheet as Excel saves them beside
    the formula (openpyxl writes none: it does not calculate)."""
    with zipfile.ZipFile(path) as z:
        parts = {n: z.read(n) for n in z.namelist()}
    part = f"xl/worksheets/sheet{number}.xml"       # (openpyxl's name of it)
    xml = parts[part].decode()
    for cell, value in values.items():
        xml, n = re.subn(rf'(<c r="{cell}"[^>]*><f>[^<]*</f>)<v\s*/?>(</v>)?',
                         rf"\g<1><v>{value!r}</v>", xml)
        assert n == 1, cell
    parts[part] = xml.encode()
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in parts.items():
            z.writestr(name, data)


def _csv_export(path: Path) -> Path:
    """The same rows as the lab's CSV export (',', '.', ISO 8601 times, an empty line of cells)."""
    header, units, rows = _rows()
    width = len(header)
    with open(path, "w", encoding="utf-8", newline="") as f:
        out = csv.writer(f)
        for line in PREAMBLE:
            out.writerow([line] + [""] * (width - 1))
        out.writerows([header, units])
        for i, row in enumerate(rows):
            out.writerow(["" if v is None else v.isoformat() if isinstance(v, dt.datetime)
                          else repr(v) for v in row])
            if i == EMPTY_AFTER:
                out.writerow([""] * width)
    return path


def _init(tmp_path: Path, name: str, record: Path, *args: str) -> dict:
    out = tmp_path / name
    assert main(["init", str(record), "data.max_gap_samples=1", *args, f"out={out}"]) == 0
    return yaml.safe_load((out / "conf" / "data" / f"{record.stem}.yaml").read_text())


def _run(tmp_path: Path, name: str, config: Path) -> dict:
    out = tmp_path / name
    assert main(["run", f"hydra.searchpath=[file://{config.parent.parent}]", f"data={config.stem}",
                 "model=mlr", *FAST, f"out={out}"]) == 0
    return json.loads((out / "metrics.json").read_text())


def test_init_and_run_on_a_workbook_give_what_they_give_on_its_csv_export(tmp_path, capsys):
    (tmp_path / "x").mkdir()
    (tmp_path / "c").mkdir()
    book = _workbook(tmp_path / "x" / "lab.xlsx", first_sheet="Info")
    export = _csv_export(tmp_path / "c" / "lab.csv")
    from_book = _init(tmp_path, "init_x", book, "data.sheet=Messung")
    said = capsys.readouterr()
    # the empty row's own row in the sheet: under the preamble, the header, the unit row and 201
    # data rows
    assert f"{book}, sheet 'Messung', row {len(PREAMBLE) + 2 + EMPTY_AFTER + 2} (data row " \
           f"{EMPTY_AFTER + 2}): 1 row(s) of empty cells left out" in said.err
    assert "lab.xlsx: sheet 'Messung', header on row 3 (2 row(s) above it left out), units from " \
           "row 4; rows counted from row 5" in said.out
    from_csv = _init(tmp_path, "init_c", export)
    assert {k: v for k, v in from_book.items() if k not in ("path", "sheet")} == \
        {k: v for k, v in from_csv.items() if k not in ("path", "delimiter", "decimal")}
    assert from_book["sheet"] == "Messung" and "delimiter" not in from_book
    assert from_book["roles"]["error"] == [f"ch{i}" for i in range(1, 6)]
    x = _run(tmp_path, "run_x", tmp_path / "init_x" / "conf" / "data" / "lab.yaml")
    c = _run(tmp_path, "run_c", tmp_path / "init_c" / "conf" / "data" / "lab.yaml")
    assert set(x["targets"]) == {f"E_ch{i}" for i in range(1, 6)}
    assert {t: m["test"] for t, m in x["targets"].items()} == \
        {t: m["test"] for t, m in c["targets"].items()}
    report = json.loads((tmp_path / "run_x" / "ingest_report.json").read_text())
    assert report["repairs"] == {"T_t5": 1}          # the empty cell: a gap, repaired
    assert report["campaigns"]["lab_train"]["time_origin"].startswith("2026-11-28T13:05:00")


def test_a_bad_cell_is_refused_with_the_workbook_the_sheet_and_its_row(tmp_path, capsys):
    book = _workbook(tmp_path / "lab.xlsx", bad=(9, "n. gem."))
    row = len(PREAMBLE) + 2 + 9 + 1        # the sheet's row, as Excel numbers it
    refused(["run", f"data.path={book}", *ROLES, "data.test_fraction=0.1",
             f"out={tmp_path / 'out'}", *FAST], capsys,
            f"file {book}, sheet 'Messung', column 'E_ch1', row {row} (data row 10): "
            "value 'n. gem.' is not a number")
    assert not (tmp_path / "out").exists()
    assert not list(Path(tmp_path).glob("**/*.csv"))       # the sheet's CSV file: removed


def test_a_sheet_the_workbook_lacks_is_refused_naming_its_sheets(tmp_path, capsys):
    book = _workbook(tmp_path / "lab.xlsx", first_sheet="Info")
    refused(["init", str(book), "data.sheet=Messdaten", f"out={tmp_path / 'init'}"], capsys,
            f"file {book}: data.sheet='Messdaten' is no sheet of it: its sheets are 'Info', "
            "'Messung'")
    # a name that reads as a number: quoted (2 would say the second sheet? no: names only)
    refused(["init", str(book), "data.sheet=2", f"out={tmp_path / 'init'}"], capsys,
            "data.sheet=2: must be null or a sheet's name", "data.sheet=\"'2024'\"")
    # the first sheet, a page of notes, holds no table: the first that does is read when none is
    # named (stranger68; the notes were read, refused as such a CSV is): here its gap refused
    refused(["init", str(book), f"out={tmp_path / 'init'}"], capsys,
            f"file {book}, sheet 'Messung', column 'T_t5'")
    assert not (tmp_path / "init").exists()


def test_a_folder_of_workbooks_holds_out_its_last_run_by_time(tmp_path):
    header, units, rows = _rows()
    folder = tmp_path / "runs"
    folder.mkdir()
    # named against their time: 'a' ran after 'b'
    for name, part in (("b", rows[:150]), ("a", rows[150:])):
        book = openpyxl.Workbook()
        for row in [header, units, *part]:
            book.active.append(row)
        book.save(folder / f"{name}.xlsx")
    (folder / "~$a.xlsx").write_bytes(b"\x00" * 165)          # Excel's lock file: no run
    assert main(["run", f"data.path={folder}", "data.test_fraction=0.5", *ROLES, "model=mlr",
                 *FAST, f"out={tmp_path / 'out'}"]) == 0
    report = json.loads((tmp_path / "out" / "ingest_report.json").read_text())
    assert {c: e["split"] for c, e in report["campaigns"].items()} == {"a": "test", "b": "train"}
    assert main(["init", str(folder), *ROLES, f"out={tmp_path / 'init'}"]) == 0
    written = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text())
    assert "delimiter" not in written and written["test_fraction"] == 0.1


@pytest.mark.parametrize("name, content, says", [
    ("old.xls", b"\xd0\xcf\x11\xe0" + b"\x00" * 60, "an Excel 97-2003 workbook, which is not read: "
     "save it as an Excel workbook (.xlsx), or its sheet as CSV"),
    ("locked.xlsx", b"\xd0\xcf\x11\xe0" + b"\x00" * 60, "an encrypted workbook"),
    ("text.xlsx", b"time,dX\n0,1\n", "not a workbook that is read (BadZipFile")],
    ids=["xls", "encrypted", "not-a-zip"])
def test_a_workbook_that_is_not_read_is_refused_with_the_remedy(tmp_path, capsys, name, content,
                                                                 says):
    (tmp_path / name).write_bytes(content)
    refused(["run", f"data.path={tmp_path / name}", f"out={tmp_path / 'out'}", *FAST], capsys,
            f"file {tmp_path / name}: {says}")


def test_a_workbook_without_openpyxl_names_the_extra(tmp_path, capsys, monkeypatch):
    book = _workbook(tmp_path / "lab.xlsx")
    monkeypatch.setitem(sys.modules, "openpyxl", None)       # as if not installed
    refused(["init", str(book), f"out={tmp_path / 'init'}"], capsys,
            "an Excel workbook (data.path=<file>.xlsx) needs openpyxl", "pip install -e '.[excel]'")


def test_numbers_typed_as_text_with_a_decimal_comma_are_read_as_numbers(tmp_path, capsys):
    # pasted from a European export, '0,38' stays text in the sheet: refused ("not numeric", or
    # "set data.decimal=','", which had no effect on a sheet: its CSV is written with '.')
    header, units, rows = _rows()
    book, plain = openpyxl.Workbook(), openpyxl.Workbook()
    for wb, as_text in ((book, True), (plain, False)):
        sheet = wb.active
        sheet.append(header)
        sheet.append(units)
        for row in rows:
            sheet.append([f"{v!r}".replace(".", ",") if as_text and isinstance(v, float) else v
                          for v in row])
    book.save(tmp_path / "text.xlsx")
    plain.save(tmp_path / "plain.xlsx")
    args = [*ROLES, "data.test_fraction=0.1", *FAST]
    refused(["run", f"data.path={tmp_path / 'text.xlsx'}", "data.decimal=.", *args,
             f"out={tmp_path / 'o'}"], capsys, "sheet 'Sheet'", "is not numeric ('26,19")
    got = {}
    for name, decimal in (("text", "auto"), ("text_set", ","), ("plain", "auto")):
        book = tmp_path / f"{name.split('_')[0]}.xlsx"
        assert main(["run", f"data.path={book}", f"data.decimal={decimal}", *args, "model=mlr",
                     f"out={tmp_path / name}"]) == 0
        got[name] = {t: (m["test"]["rmse"], m["test"]["mae"]) for t, m in json.loads(
            (tmp_path / name / "metrics.json").read_text())["targets"].items()}
    assert got["text"] == got["text_set"] == got["plain"]


def test_init_writes_the_head_of_a_sheet_once(tmp_path, capsys, monkeypatch):
    # the header look and the layout line each wrote the sheet's first rows as CSV (session 49)
    from thermocomp.core.io import workbook
    written = []
    real = workbook._write
    monkeypatch.setattr(workbook, "_write", lambda path, sheet, out, rows, comma:
                        written.append(rows) or real(path, sheet, out, rows, comma))
    book = _workbook(tmp_path / "lab.xlsx")
    _init(tmp_path, "init", book)
    assert written.count(workbook.HEAD_ROWS) == 1, written
    assert "lab.xlsx: sheet 'Messung', header on row 3" in capsys.readouterr().out
