"""A lab's error header with a note after its unit, the sign convention (session 56)."""

from __future__ import annotations

import pytest

from thermocomp.core.io import read_dataset

NOTE = "(+ = Werkzeug weg vom Werkstück)"


def test_a_unit_in_brackets_followed_by_a_note_is_the_headers_unit(tmp_path):
    # 'dX [mm] (+ = ...)': the note, the last bracket, was read as the unit and refused ("unit
    # '+ = Werkzeug weg vom Werkstück' is not an error's"); data.columns, the only way round,
    # converts nothing and read the millimetres as µm
    path = tmp_path / "lab.csv"
    path.write_text(f"time,T_spindle,dX [mm] {NOTE}\n0,20.00,0.0000\n60,20.10,0.0015\n"
                    "120,20.25,0.0032\n", encoding="utf-8")
    ds, _ = read_dataset(path, {"roles": {"error": ["dX*"]}})
    (frame,) = ds.campaigns.values()
    assert list(frame.columns) == ["time", "T_spindle", "E_dX"]
    assert frame["E_dX"].tolist() == pytest.approx([0.0, 1.5, 3.2])
