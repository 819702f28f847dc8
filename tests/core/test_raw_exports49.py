"""A lab's raw export, round 6 (session 49)."""

from __future__ import annotations

import codecs
import csv
import datetime as dt
import json

import pytest

from conftest import FAST, ROOT
from thermocomp.shell.cli import main

RECORD = ROOT / "datasets" / "fl_thermal" / "spindle_test.csv"
ROLES = ["data.roles.error=['ch*']", "data.roles.state=['spindle*']"]


def stamped_runs(folder, write) -> None:
    """The shipped record's first 300 rows as two runs of timestamped rows, named against
    their time ('a' ran after 'b'), each written by ``write(lines, path)``."""
    with open(RECORD, encoding="utf-8", newline="") as f:
        lines = list(csv.reader(f))[:301]
    start = dt.datetime(2026, 11, 28, 13, 5)
    rows = [[(start + dt.timedelta(seconds=float(r[0]))).isoformat(), *r[1:]] for r in lines[1:]]
    folder.mkdir()
    for name, part in (("b", rows[:150]), ("a", rows[150:])):
        write([["Zeit", *lines[0][1:]], *part], folder / f"{name}.csv")


def _german(sep: str, mark: bytes, codec: str):
    """A writer of the rows as a German locale's export: ``sep``, decimal commas, ``mark``."""
    def write(lines, path) -> None:
        path.write_bytes(mark + "".join(sep.join(c.replace(".", ",") if i else c for c in line)
                                        + "\r\n" for i, line in enumerate(lines)).encode(codec))
    return write


@pytest.mark.parametrize("write", [_german(";", b"", "utf-8"),
                                   _german("\t", codecs.BOM_UTF16_LE, "utf-16-le")],
                         ids=["csv", "unicode text"])
def test_a_folder_of_decimal_comma_runs_holds_out_its_last_run_by_time(tmp_path, write):
    # the first timestamp was looked for with data.decimal=auto unresolved: the temperatures
    # '26,21' read as text, the look failed, and the runs were ordered by name ('a' held out
    # as train, 'b', which ran first, as test); a UTF-16 run (Excel's 'Unicode Text') was
    # refused before session 49
    stamped_runs(tmp_path / "runs", write)
    assert main(["run", f"data.path={tmp_path / 'runs'}", "data.test_fraction=0.5", *ROLES,
                 "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    report = json.loads((tmp_path / "out" / "ingest_report.json").read_text())
    assert {c: e["split"] for c, e in report["campaigns"].items()} == {"a": "test", "b": "train"}
