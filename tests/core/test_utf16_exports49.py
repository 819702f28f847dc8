"""Excel's 'Unicode Text' export (UTF-16 with its byte-order mark, tab-separated, CRLF, a German
locale's decimal commas) reads as the same rows in a UTF-8 CSV file do (session 49): it was
refused with a remedy, the reader finding lines and fields in the bytes."""

from __future__ import annotations

import csv
import io as text_io
import json
import sys
from pathlib import Path

import pytest
import yaml

from conftest import FAST, ROOT, refused
from thermocomp.shell.cli import main

RECORD = ROOT / "datasets" / "fl_thermal" / "spindle_test.csv"
ROLES = ["data.roles.error=['ch*']", "data.roles.state=['spindle*']"]
MARKS = {"utf-16-le": b"\xff\xfe", "utf-16-be": b"\xfe\xff"}


def _record(rows: int = 400) -> list[list[str]]:
    with open(RECORD, encoding="utf-8", newline="") as f:
        return list(csv.reader(f))[:rows + 1]


def _utf8_csv(lines: list[list[str]], path: Path) -> Path:
    with open(path, "w", encoding="utf-8", newline="") as f:
        csv.writer(f).writerows(lines)
    return path


def _unicode_text(lines: list[list[str]], path: Path, codec: str = "utf-16-le") -> Path:
    """The rows as Excel saves them as 'Unicode Text' in a German locale."""
    text = "".join("\t".join(c if i == 0 else c.replace(".", ",") for c in line) + "\r\n"
                   for i, line in enumerate(lines))
    path.write_bytes(MARKS[codec] + text.encode(codec))
    return path


def _targets(tmp_path: Path, name: str, *args: str) -> dict:
    out = tmp_path / name
    assert main(["run", *args, "model=mlr", *FAST, f"out={out}"]) == 0
    return json.loads((out / "metrics.json").read_text())["targets"]


@pytest.mark.parametrize("codec", MARKS)
def test_a_measured_records_unicode_text_export_scores_as_its_csv(tmp_path, capsys, codec):
    lines = _record()
    (tmp_path / "c").mkdir()
    (tmp_path / "u").mkdir()
    plain = _utf8_csv(lines, tmp_path / "c" / "lab.csv")
    wide = _unicode_text(lines, tmp_path / "u" / "lab.txt", codec)
    assert main(["init", str(wide), *ROLES, f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "lab.txt: encoding UTF-16 (its byte-order mark), delimiter '\\t', decimal ','" in said
    config = tmp_path / "init" / "conf" / "data" / "lab.yaml"
    written = yaml.safe_load(config.read_text())
    assert written["delimiter"] == "\t" and written["decimal"] == "," and "encoding" not in written
    from_wide = _targets(tmp_path, "w", f"hydra.searchpath=[file://{config.parent.parent}]",
                         "data=lab")
    from_csv = _targets(tmp_path, "p", f"data.path={plain}", *ROLES, "data.test_fraction=0.1")
    assert set(from_wide) == {f"E_ch{i}" for i in range(1, 6)}
    assert from_wide == from_csv


@pytest.mark.parametrize("suffix", [".csv", ".txt"])     # .txt: Excel's own name for it
def test_a_folder_of_simulated_campaigns_exported_as_unicode_text_scores_as_its_csv(
        tmp_path, short_dataset, suffix):
    manifest = list(csv.DictReader(open(short_dataset / "campaigns.csv", encoding="utf-8")))
    for kind in ("c", "u"):
        (tmp_path / kind).mkdir()
    for entry in manifest:            # the runs in the manifest's order, named so
        with open(short_dataset / entry["file"], encoding="utf-8", newline="") as f:
            lines = list(csv.reader(f))
        name = f"run_{len(list((tmp_path / 'c').iterdir())) + 1}.csv"
        _utf8_csv(lines, tmp_path / "c" / name)
        _unicode_text(lines, tmp_path / "u" / Path(name).with_suffix(suffix))
    held_out = "data.test_fraction=0.34"
    assert _targets(tmp_path, "w", f"data.path={tmp_path / 'u'}", held_out) == \
        _targets(tmp_path, "p", f"data.path={tmp_path / 'c'}", held_out)


def test_a_bad_cell_of_a_unicode_text_export_is_refused_naming_the_file_and_its_line(
        tmp_path, capsys):
    lines = _record(40)
    lines[10][3] = "abc"                  # data row 10, line 11
    wide = _unicode_text(lines, tmp_path / "lab.txt")
    line = refused(["run", f"data.path={wide}", *ROLES, "data.test_fraction=0.1", *FAST,
                    f"out={tmp_path / 'o'}"], capsys, f"file {wide}", "line 11 (data row 10)",
                   "'abc'")
    assert "thermocomp-utf16" not in line
    assert not (tmp_path / "o").exists()


def test_bytes_that_are_no_utf16_character_are_refused_with_their_line(tmp_path, capsys):
    wide = _unicode_text(_record(40), tmp_path / "lab.txt")
    data = wide.read_bytes()
    cut = data.index("\r\n".encode("utf-16-le"), 200) + 4       # line 2 begins here or later
    wide.write_bytes(data[:cut] + "\udc00".encode("utf-16-le", "surrogatepass") + data[cut:])
    refused(["run", f"data.path={wide}", *ROLES, "data.test_fraction=0.1", *FAST,
             f"out={tmp_path / 'o'}"], capsys, f"file {wide}", "no UTF-16 character", "line ")


def test_a_stream_of_unicode_text_on_stdin_is_read(monkeypatch):
    from thermocomp.core.io.stdin import stdin_text
    text = "time\tT_a\tE_X\r\n0\t20,5\t1\r\n"
    stream = text_io.TextIOWrapper(text_io.BytesIO(b"\xff\xfe" + text.encode("utf-16-le")))
    monkeypatch.setattr(sys, "stdin", stream)
    assert stdin_text(sys.stdin) == text

