"""A lab's files in (data87): a unit changed under an unchanged header is refused on stdin
(``monitor.input=-``) as on the file, at the same column and row."""

from __future__ import annotations

import io
import shutil

import pandas as pd
import pytest

from test_hostile_units import FAHRENHEIT, MILLIMETRES, from_row
from thermocomp.shell.cli import main

KELVIN = lambda c: (c + 273.15).round(2)  # noqa: E731 -- as a logger writes it

# (column prefix, conversion from row 15 on); the error column the one of the largest level
# (mm of a 0.3 µm reading is within the noise of zero: no step to judge, on the file too)
CHANGES = {"°F": ("T_", FAHRENHEIT), "K": ("T_", KELVIN), "mm": ("E_", MILLIMETRES),
           "none": ("T_", lambda c: c)}


def _error_line(err: str) -> str | None:
    return next((ln for ln in err.splitlines() if ln.startswith("thermocomp: error")), None)


@pytest.mark.parametrize("change", CHANGES)
def test_a_unit_changed_under_its_header_is_refused_on_stdin_as_on_the_file(
        short_dataset, tmp_path, capsys, monkeypatch, change):
    # data87: the file was refused naming column and row; the same rows piped in were
    # monitored with exit 0 (a °F or kelvin sensor an exclusion event, a mm probe a worse
    # RMSE), the data in another unit scored as the machine's
    folder = shutil.copytree(short_dataset, tmp_path / "ds")
    index = pd.read_csv(folder / "campaigns.csv")
    name = index.loc[index["split"] == "test", "file"].iloc[0]
    rows = pd.read_csv(folder / name)
    prefix, convert = CHANGES[change]
    columns = [c for c in rows.columns if c.startswith(prefix)]
    column = max(columns, key=lambda c: rows[c].abs().median())
    from_row(column, 15, convert)(rows)
    args = ["monitor", f"data.path={folder}", "track=false", "plots=none"]
    monkeypatch.setattr("sys.stdin", io.StringIO(rows.to_csv(index=False)))
    piped = main([*args, "monitor.input=-", f"out={tmp_path / 'stdin'}"])
    said = _error_line(capsys.readouterr().err)
    rows.to_csv(folder / name, index=False)
    on_file = main([*args, f"out={tmp_path / 'file'}"])
    file_said = _error_line(capsys.readouterr().err)
    assert piped == on_file == (0 if change == "none" else 2), (said, file_said)
    if change == "none":
        return
    assert f"file <stdin>, column '{column}', data row 15: " in said, said
    assert f"{name}, column '{column}', line 16 (data row 15): " in file_said, file_said
    assert said.split("data row 15: ", 1)[1] == file_said.split("data row 15): ", 1)[1]
