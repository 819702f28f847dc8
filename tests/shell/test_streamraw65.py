"""The compiled stream reads a lab's raw file as thermocomp read it (streamraw65): a unit row
under the header, a Windows logger's cp1252 header bytes, the header written again in the middle
of the file (a logger restarted), and ``data.missing_values``' marks
(``benchmarks/bench_streamraw65.py``: the wire EDM's eight raw day files)."""

from __future__ import annotations

import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from conftest import FAST
from test_export import needs_cc
from test_stranger65 import _compiled_stream_equals_its_pack
from thermocomp.shell.cli import main


def logger_file(path, units: bool, encoding: str, again: int | None, mark: int | None = None):
    """A logger's day file: ``;``, decimal commas, the date and the time of day in two columns,
    a sensor named with an umlaut; ``units``: the units in a row under the header (else in the
    header), ``again``: the header (and unit row) written again before that data row, ``mark``:
    ``---`` in T Ständer at that data row."""
    rng = np.random.default_rng(6565)
    t = np.arange(240) * 60.0
    heat = 20 + 3 * (1 - np.exp(-t / 3000)) + rng.normal(0, 0.02, t.size)
    hall = 19 + 0.0005 * t + rng.normal(0, 0.02, t.size)
    stamps = pd.Timestamp("2027-06-14 08:00") + pd.to_timedelta(t, unit="s")
    if units:
        head = ["Datum;Uhrzeit;T Ständer;T Halle;dX", ";;°C;°C;µm"]
    else:
        head = ["Datum;Uhrzeit;T Ständer [°C];T Halle [°C];dX [µm]"]
    lines = list(head)
    for k, (s, a, b) in enumerate(zip(stamps, heat, hall)):
        if k == again:
            lines += head
        cell = "---" if k == mark else f"{a:.2f}".replace(".", ",")
        lines.append(f"{s:%d.%m.%Y};{s:%H:%M:%S};{cell};{b:.2f};{2.5 * (a - 20):.2f}"
                     .replace(".", ",").replace(",", ".", 2))
    path.write_bytes(("\r\n".join(lines) + "\r\n").encode(encoding))
    return path


def _common(path, encoding: str) -> list[str]:
    return [f"data.path={path}", "data.roles.time=[Datum,Uhrzeit]", "data.roles.error=[dX]",
            "data.test_fraction=0.3", "data.reference=none", f"data.encoding={encoding}"]



def _mlr_stream(tmp_path, common) -> Path:
    """The folder of an MLR run on ``common``'s record exported as C, its ``stream`` built."""
    assert main(["run", *common, *FAST, "model=mlr", "plots=none", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c", "export.check=false",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    code = tmp_path / "code"
    compiled(code)
    return code


@needs_cc
@pytest.mark.parametrize("units, encoding, again", [
    (True, "utf-8", None),       # before: "the header ... lacks input column T_Ständer"
    (False, "cp1252", None),     # before: the same ('St\344nder [\260C]' is not its UTF-8 name)
    (False, "utf-8", 150),       # before: "row 152: input T_Ständer has no finite value"
    (True, "cp1252", 150),       # the wire EDM's day file: all three at once
])
def test_the_compiled_stream_reads_the_loggers_raw_file_as_the_reader_does(tmp_path, units,
                                                                           encoding, again):
    path = logger_file(tmp_path / "day.csv", units, encoding, again)
    _compiled_stream_equals_its_pack(tmp_path, path, _common(path, encoding))


@needs_cc
def test_a_missing_value_mark_is_a_missing_value_and_another_word_no_number(tmp_path):
    # before: any cell that was no number was read as a missing value, silently: the stream's
    # refusal said "has no finite value" of a mark and of a word alike
    train = logger_file(tmp_path / "train.csv", False, "utf-8", None, mark=20)
    common = _common(train, "utf-8") + ["data.missing_values=['---']", "data.max_gap_samples=1"]
    code = _mlr_stream(tmp_path, common)
    raw = train.read_bytes()
    # the mark: a missing value of an input, which the plain stream refuses at its row (as
    # replay's plain stream does; the reader interpolated it in this train record)
    done = subprocess.run(["./stream"], cwd=code, input=raw, capture_output=True)
    said = done.stderr.decode()
    assert done.returncode == 2 and "line 22: input T_Ständer has no finite value" in said
    assert "a data.missing_values mark" in said
    assert len(done.stdout.decode().splitlines()) == 1 + 20          # the rows before it
    # a word the model's data.missing_values does not list: no number, refused as the reader
    # refuses it
    done = subprocess.run(["./stream"], cwd=code, input=raw.replace(b";---;", b";n.v.;"),
                          capture_output=True)
    assert done.returncode == 2
    assert "line 22: input T_Ständer: 'n.v.' is no number" in done.stderr.decode()


@needs_cc
def test_another_files_header_in_the_stream_says_to_stream_each_file_by_itself(tmp_path):
    # before: "row 243: input T_Ständer has no finite value" (another day file's header read as
    # a row); the header written again is left out, another is said for what it is
    path = logger_file(tmp_path / "day.csv", True, "cp1252", None)
    common = _common(path, "cp1252")
    code = _mlr_stream(tmp_path, common)
    raw = path.read_bytes()
    # the next day's file under the logger's new configuration: its units in its header
    other = logger_file(tmp_path / "next.csv", False, "cp1252", None).read_bytes()
    done = subprocess.run(["./stream"], cwd=code, input=raw + raw, capture_output=True)
    assert done.returncode == 0 and len(done.stdout.splitlines()) == 1 + 2 * 240
    done = subprocess.run(["./stream"], cwd=code, input=raw + other, capture_output=True)
    assert done.returncode == 2 and len(done.stdout.splitlines()) == 1 + 240
    assert "line 243 is a header other than the first" in done.stderr.decode()
    assert "stream each file by itself" in done.stderr.decode()


def test_export_as_c_refuses_a_character_set_stream_c_does_not_decode(tmp_path):
    # before: exported, and stream.c read the file's bytes as UTF-8 (its headers not found)
    path = logger_file(tmp_path / "day.csv", False, "cp1250", None)
    common = _common(path, "cp1250")
    assert main(["run", *common, *FAST, "model=mlr", "plots=none", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c", "export.check=false",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 2
    assert not (tmp_path / "code" / "stream.c").exists()
