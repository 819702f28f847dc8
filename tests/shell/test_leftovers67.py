"""Issue 34's follow-ups left by stop 66 (leftovers67), each a defect shown on the old code.

1. A ``#`` comment line among the rows (a lab's logger writing ``# marker: tool change``
   mid-run): the file reader refused it ("expected 7 fields, got 1"), a stream left out every
   ``#`` line under a commented header or under any unit row, unsaid.  One rule now
   (``core/io/again.py``): in a file that writes ``#`` comments (its preamble, or its header)
   such a line is left out and said by its line, file and stream alike; in a file that writes
   none, a ``#`` line of another width is refused by both, in the same words.
"""

from __future__ import annotations

import io
import json

import pytest

from conftest import FAST, refused
from test_stranger66 import ROLES, folders
from thermocomp.shell.cli import main

# -- 1. a '#' comment among the rows ------------------------------------------------------------

MARK = "# marker: tool change\n"


def _marked(path, at: int) -> str:
    """``path``'s text with the logger's note before its line ``at + 1``."""
    lines = path.read_text().splitlines(keepends=True)
    return "".join(lines[:at] + [MARK] + lines[at:])


def test_a_comment_among_the_rows_of_a_commented_file_is_left_out_by_file_and_stream(
        tmp_path, monkeypatch, capsys):
    # before: the file reader refused the DAQ's run ("line 108 (data row 101): expected 7
    # fields, got 1"); the stream left it out, unsaid; now both leave it out and say its line
    daq, plain = folders(tmp_path)
    test = sorted(daq.glob("*.txt"))[-1]
    marked = _marked(test, 7 + 100)
    args = [*ROLES, *FAST, "model=lagbank"]
    assert main(["run", f"data.path={plain}", *args, "plots=none",
                 f"out={tmp_path / 'out-plain'}"]) == 0
    test.write_text(marked)
    assert main(["run", f"data.path={daq}", *args, "plots=none", f"out={tmp_path / 'out-daq'}"]) == 0
    said = "line 108: a '#' comment among the rows (the file writes '#' comments"
    assert f"{test}, {said}" in capsys.readouterr().err
    got, want = (json.loads((tmp_path / name / "metrics.json").read_text())["targets"]["E_dZ1"]
                 for name in ("out-daq", "out-plain"))
    for split in ("train", "test"):
        assert got[split]["rmse"] == pytest.approx(want[split]["rmse"], rel=1e-12)
    monitor = ["monitor", f"data.path={plain}", *args]
    assert main([*monitor, f"out={tmp_path / 'file'}"]) == 0
    monkeypatch.setattr("sys.stdin", io.StringIO(marked))
    assert main([*monitor, "monitor.input=-", f"out={tmp_path / 'piped'}"]) == 0
    assert f"<stdin>, {said}" in capsys.readouterr().err
    from_file, piped = (json.loads((tmp_path / name / "monitor.json").read_text())["targets"]
                        for name in ("file", "piped"))
    assert piped["E_dZ1"]["rmse_fixed"] == pytest.approx(from_file["E_dZ1"]["rmse_fixed"],
                                                         rel=1e-9)


@pytest.mark.parametrize("units", [False, True], ids=["plain", "unit-row"])
def test_a_hash_line_in_a_file_without_comments_is_refused_alike_by_file_and_stream(
        tmp_path, monkeypatch, capsys, units):
    # before: the file reader said "expected 6 fields, got 1" (not what the line is); the stream
    # said "non-numeric value" in column 'time', or, under a unit row, left the line out unsaid
    _, plain = folders(tmp_path)
    test = sorted(plain.glob("*.csv"))[-1]
    if units:
        lines = test.read_text().splitlines(keepends=True)
        test.write_text("".join([lines[0].replace(" [s]", "").replace(" [degC]", "")
                                 .replace(" [rpm]", "").replace(" [um]", ""),
                                 "s,degC,degC,degC,rpm,um\n", *lines[1:]]))
    marked = _marked(test, 101 + units)
    line = f"line {102 + units}"
    said = "expected 6 fields, got 1: a '#' line among the rows, of other than the header's width"
    stream = ["monitor", f"data.path={plain}", *ROLES, *FAST, "model=lagbank",
              "monitor.input=-", f"out={tmp_path / 'piped'}"]
    monkeypatch.setattr("sys.stdin", io.StringIO(marked))
    refused(stream, capsys, f"file <stdin>, {line}: {said}")
    test.write_text(marked)
    refused(["run", f"data.path={plain}", *ROLES, *FAST, "plots=none", f"out={tmp_path / 'run'}"],
            capsys, f"file {test}, {line} (data row 101): {said}")

