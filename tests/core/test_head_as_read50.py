"""``init``'s look at a file (:func:`thermocomp.core.io.detect.head`) converts a workbook or a
UTF-16 text itself, beside :func:`thermocomp.core.io.plain.as_read` (its layout line names the
sheet, the encoding): the header and first row it sees must be the ones the reader reads."""

import openpyxl
import pytest

from thermocomp.core.io.detect import head
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.plain import as_read, is_converted
from thermocomp.core.io.workbook import HEAD_ROWS

ROWS = [["time [s]", "T_spindle [°C]", "E_X [µm]"], [0.0, 21.5, 0.25], [60.0, 21.75, 0.5]]


def _utf16(path):
    path.write_text("".join("\t".join(map(str, r)) + "\n" for r in ROWS), encoding="utf-16")


def _workbook(path):
    book = openpyxl.Workbook()
    book.active.title = "Messung"
    for row in ROWS:
        book.active.append(row)
    book.save(path)


@pytest.mark.parametrize("name, write, said", [("run.xlsx", _workbook, "sheet 'Messung'"),
                                              ("run.txt", _utf16, "encoding UTF-16")])
def test_a_converted_files_head_is_the_one_the_reader_reads(tmp_path, name, write, said):
    sample = tmp_path / name
    write(sample)
    opts = ReadOptions.from_cfg({})
    assert is_converted(sample)
    _, header, first, layout = head(sample, opts)
    with as_read(sample, opts, rows=HEAD_ROWS) as (source, source_opts):
        _, read_header, read_first, _ = head(source, source_opts)
    assert (header, first) == (read_header, read_first) and header[0] == "time [s]"
    assert layout.startswith(f"{name}: {said}")
