"""Two exports of a lab's PC appended into one file, each with Excel's ``sep=;`` line above its
header (stop 96, ``benchmarks/bench_audit96.py lab``): the reader leaves the second ``sep=;``
line out with the header written again under it (stranger66: a preamble's line written again
above the header); the compiled stream refused it, ``stream: line 724 has not 19 cells``, after
printing the rows above it.  Now it leaves the line out with the header, as the reader does; a
preamble's line not followed by the header is refused as before."""

from __future__ import annotations

import subprocess

import pytest

from test_export import needs_cc
from test_stranger65 import _compiled_stream_equals_its_pack
from test_streamraw65 import _common, _mlr_stream, logger_file

AGAIN = 150                 # the data row the second export starts at


def appended(tmp_path, units: bool):
    """test_streamraw65's day file (its header written again before data row :data:`AGAIN`),
    each header under Excel's ``sep=;`` line."""
    path = logger_file(tmp_path / "day.csv", units, "utf-8", AGAIN)
    lines = path.read_bytes().decode().split("\r\n")
    head = lines[0]
    out = ["sep=;", lines[0]]
    for line in lines[1:]:
        out += ["sep=;", line] if line == head else [line]
    path.write_bytes("\r\n".join(out).encode())
    return path


@needs_cc
@pytest.mark.parametrize("units", (False, True), ids=("units in headers", "unit row"))
def test_the_compiled_stream_leaves_a_second_exports_sep_line_out_as_the_reader(tmp_path, units):
    path = appended(tmp_path, units)
    _compiled_stream_equals_its_pack(tmp_path, path, _common(path, "utf-8"))


@needs_cc
def test_a_preamble_line_among_the_rows_without_the_header_is_refused_as_before(tmp_path):
    path = appended(tmp_path, False)
    code = _mlr_stream(tmp_path, _common(path, "utf-8"))
    lines = path.read_bytes().decode().split("\r\n")
    at = lines.index("sep=;", 1)
    del lines[at + 1]                       # the second header gone: a stray 'sep=;' line
    done = subprocess.run([str(code / "stream")], input="\r\n".join(lines).encode(),
                          capture_output=True)
    assert done.returncode == 2
    assert f"stream: line {at + 1} has not 5 cells" in done.stderr.decode()
