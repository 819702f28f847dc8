"""A lab's raw export as a stranger brings it (issue 34, item 1): hand-written files off the
happy path.  Each is read to the values it holds, or refused in one line naming the file and the
column (and row), never read silently wrong."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from conftest import refused
from thermocomp.core.io import read_dataset
from thermocomp.core.io.detect import proposed_roles
from thermocomp.core.io.options import ReadOptions
from thermocomp.shell.cli import main

ROWS = 30


def _record():
    """A warming machine, one sample a minute: time (s), two temperatures (°C), an error (µm)."""
    rng = np.random.default_rng(4)
    t = np.arange(ROWS) * 60.0
    t1 = 20 + 6 * (1 - np.exp(-t / 600)) + rng.normal(0, 0.02, ROWS)
    t2 = 21 + 3 * (1 - np.exp(-t / 900)) + rng.normal(0, 0.02, ROWS)
    return t, t1, t2, 4.0 * (t1 - t1[0]) - t2 + rng.normal(0, 0.1, ROWS)


def _write(path: Path, header: list[str], columns, sep: str = ",", end: str = "") -> Path:
    rows = [sep.join(f"{v:.6g}" for v in row) + end for row in zip(*columns)]
    path.write_text("\n".join([sep.join(header) + end, *rows]) + "\n", encoding="utf-8")
    return path


def _read(path: Path, **cfg):
    ds, _ = read_dataset(path, cfg)
    (frame,) = ds.campaigns.values()
    return frame


def test_a_unit_written_quantity_slash_unit_is_read_as_the_unit_not_as_part_of_the_name(tmp_path):
    # ISO 80000 headers: before, 'delta L / um' was a temperature T_delta_L_um (an error read
    # as a model input, silently) and 'Zeit / s' no time column
    t, t1, t2, e = _record()
    path = _write(tmp_path / "lab.csv", ["Zeit / s", "T1 / °C", "T2 / K", "delta L / um",
                                         "dZ/mm"], [t, t1, t2 + 273.15, e, e / 1000])
    header = path.read_text(encoding="utf-8").splitlines()[0].split(",")
    roles = proposed_roles(header, {h: "1" for h in header}, ReadOptions())
    assert roles["error"] == ["delta L", "dZ"]             # what `thermocomp init` proposes
    frame = _read(path, roles=roles)
    assert list(frame.columns) == ["time", "T_T1", "T_T2", "E_delta_L", "E_dZ"]
    np.testing.assert_allclose(frame["time"], t)
    np.testing.assert_allclose(frame["T_T2"], t2, atol=1e-3)      # kelvin converted
    np.testing.assert_allclose(frame["E_dZ"], e, atol=1e-3)       # mm converted
    np.testing.assert_allclose(frame["E_delta_L"], e, atol=1e-3)


@pytest.mark.parametrize("header", ["Datum/Zeit", "on/off"])
def test_a_slash_inside_a_name_is_no_unit(header):
    from thermocomp.core.io.roles import split_unit

    assert split_unit(header) == (header, None)


def _excel(path: Path, cells: list[str] | None = None) -> Path:
    """``;``-separated, decimal commas, a separator closing every line (Excel's empty last
    column); ``cells``: what that column holds row by row (empty by default)."""
    t, t1, t2, e = _record()
    _write(path, ["Zeit [s]", "T1 [°C]", "T2 [°C]", "dX [µm]"], [t, t1, t2, e], sep=";", end=";")
    lines = path.read_text(encoding="utf-8").replace(".", ",").splitlines()
    lines[1:] = [ln + cell for ln, cell in zip(lines[1:], cells or [""] * ROWS)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_an_empty_last_column_without_header_is_left_out(tmp_path, capsys):
    # before: refused ("'' gives no name"), and no data.roles pattern could name it
    path = _excel(tmp_path / "excel.csv")
    t, t1, t2, e = _record()
    frame = _read(path, roles={"error": ["dX"]})
    assert list(frame.columns) == ["time", "T_T1", "T_T2", "E_dX"]
    np.testing.assert_allclose(frame[["T_T1", "T_T2"]], np.c_[t1, t2], atol=1e-3)
    out = tmp_path / "init"
    assert main(["init", str(path), f"out={out}"]) == 0
    assert "(no header)" in capsys.readouterr().out


def test_a_column_without_header_that_holds_values_is_refused_naming_its_row(tmp_path, capsys):
    path = _excel(tmp_path / "excel.csv", [""] * 6 + ["Müller"] + [""] * (ROWS - 7))
    out = tmp_path / "init"
    refused(["init", str(path), f"out={out}"], capsys, str(path), "row 7", "column 5",
            "'Müller'")
    assert not out.exists()
