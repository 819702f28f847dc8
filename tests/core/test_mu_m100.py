"""A micrometre written ``mu m`` (stop 100, benchmarks/bench_audit100.py ``lab``).

A keyboard without µ spells it ``um`` (read) or ``mu m``: ``Weg Y [mu m]`` was no length, so the
error column was not read ("no column reads as a measured error ... the numeric columns: ...
'dX [mu m]'"), and where another error was read, refused as a temperature's unknown unit.
"""

from __future__ import annotations

from thermocomp.core.io.roles import contract_columns, split_unit
from thermocomp.core.io.units import role_by_unit


def test_a_header_in_mu_m_is_an_error_in_micrometres():
    assert [split_unit(h) for h in ("dX [mu m]", "dY (mu m)")] == [("dX", "mu m"), ("dY", "mu m")]
    assert role_by_unit("dX", "mu m") == "error"           # (before: None, no role from it)
    named = contract_columns(["t [s]", "T1 [°C]", "Weg Y [mu m]"], {"error": ["Weg*"]})
    assert named["Weg Y [mu m]"] == "E_Weg_Y"                # (before: refused, unit 'mu m')

