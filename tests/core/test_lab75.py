"""A lab's raw files (lab75): an infinite reading (a Campbell Scientific logger's ``INF`` /
``-INF``, ``Infinity``) is a missing value, said with its column and rows, in the file and on
stdin, and ``init`` lists it as no mark; a header quoted twice (AmeriFlux's ``_21`` tables,
``\"\"\"TIMESTAMP_START\"\"\"``) is its text; a TOA5 column whose unit no sensor of the model has
(``W/m^2``, ``m/s``) is proposed ``data.roles.ignore`` by ``init``, and ``run`` names it with its
unit.  ``tests/data/lab75/halle_toa5.dat`` is campbell74's table with ``INF`` twice, ``-INF``,
``Infinity`` and four more channels (``W/m^2``, ``m/s``, ``%``, ``W``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from conftest import thermocomp
from test_nines74 import FLUX
from test_nines74 import ROLES as FLUX_ROLES
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.stdin import read_stream

HALLE = Path(__file__).parents[1] / "data" / "lab75" / "halle_toa5.dat"
ROLES = {"roles": {"error": ["d*"], "ignore": ["SW_in_Avg", "WS_ms"]}, "max_gap_samples": 2}


def test_an_infinite_reading_is_missing_in_the_file_and_on_stdin(caplog):
    """``INF`` twice in ``T_spindle_Avg`` (a gap of 2, interpolated), ``-INF``, ``Infinity``:
    said with their lines; a stream on stdin reads the same cells as missing.  Before: "infinite
    value inf", refused (exit 2) unless ``data.missing_values`` listed each spelling."""
    ds, report = read_dataset(HALLE, ROLES)
    df = ds.campaigns[ds.ids()[0]]
    assert report["campaigns"][ds.ids()[0]]["repairs"] == {
        "T_spindle_Avg": 2, "T_column_Avg": 2, "T_air_Avg": 1}       # (and a "NAN")
    assert df["T_spindle_Avg"].iloc[4:6].to_numpy() == pytest.approx(
        21.106 + (21.967 - 21.106) * np.array([1, 2]) / 3)
    assert np.isfinite(df.drop(columns="time").to_numpy()).all()
    assert ("column 'T_spindle_Avg': 2 infinite reading(s) (line 9 (data row 5), line 10 (data "
            "row 6)): a logger's overflow or an open input, read as missing") in caplog.text
    assert "column 'T_column_Avg': 1 infinite reading(s) (line 18 (data row 14))" in caplog.text
    streamed, missing = read_stream(HALLE.read_text(), ["T_spindle_Avg"],
                                    ReadOptions.from_cfg(ROLES))
    assert missing == {"T_spindle_Avg": 2, "T_column_Avg": 2, "T_air_Avg": 1}
    assert streamed["T_spindle_Avg"].isna().to_numpy().nonzero()[0].tolist() == [4, 5]
    assert "<stdin>: column 'T_air_Avg': 1 infinite reading(s) (data row 11)" in caplog.text


def test_init_then_run_read_a_toa5_file_with_infinities_and_foreign_units(tmp_path):
    """No key given: the read says each infinity (no ``missing_values`` written), ``init``
    proposes the ``W/m^2`` and ``m/s`` columns ``ignore`` naming their units (lab76: the
    humidity in ``%`` too), ``W`` a state; ``run model=mlr`` reads the config it wrote.
    Before: init refused ("unit 'W/m^2' is not a temperature's"), and with them ignored by hand
    it wrote ``missing_values: [INF, ...]``."""
    done = thermocomp("init", str(HALLE), f"out={tmp_path}")
    said = done.stdout
    assert ("column 'T_spindle_Avg': 2 infinite reading(s) (line 9 (data row 5), line 10 (data "
            "row 6))") in done.stderr, done.stderr       # (lab76: the read's, said once)
    assert ("'SW_in_Avg [W/m^2]': unit 'W/m^2' is no temperature's, displacement's nor machine "
            "state's") in said
    for line in ("SW_in_Avg [W/m^2]      ignore (left out) -", "WS_ms [m/s]            ignore "
                 "(left out) -", "P_spindle_Avg [W]      state        S_P_spindle_Avg",
                 "RH_Avg [%]             ignore (left out) -"):     # (lab76: a humidity)
        assert line in said, said
    written = (tmp_path / "conf" / "data" / "halle_toa5.yaml").read_text()
    assert "missing_values" not in written and "max_gap_samples: 2" in written
    ran = thermocomp("run", f"hydra.searchpath=[file://{tmp_path / 'conf'}]", "data=halle_toa5",
                     "model=mlr", "eval.validation=false", "track=false", "plots=none",
                     f"out={tmp_path / 'run'}").stdout
    assert "E_dZ_Avg" in ran and "state carried over" in ran


def test_run_names_each_column_of_a_foreign_unit_in_one_message():
    """Never read as °C: both columns, their units and the key that leaves them out."""
    with pytest.raises(ContractError) as refused:
        read_dataset(HALLE, {"roles": {"error": ["d*"]}, "max_gap_samples": 2})
    said = str(refused.value)
    assert "2 column(s) not read" in said
    for header, unit, name in (("SW_in_Avg [W/m^2]", "W/m^2", "SW_in_Avg"),
                               ("WS_ms [m/s]", "m/s", "WS_ms")):
        assert (f"{header!r}: unit {unit!r} is not a temperature's (°C, K, °F) nor a "
                f"displacement's or a machine state's: no sensor of the model? "
                f"data.roles.ignore=[{name}]") in said, said


def twice_quoted(path: Path) -> Path:
    """The realexport73 flux table with its names quoted twice, as AmeriFlux's ``_21`` tables
    ship (``\"\"\"TIMESTAMP_START\"\"\"``)."""
    lines = FLUX.read_text().splitlines()
    lines[0] = lines[0].replace('"', '"""')
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_header_quoted_twice_is_its_text_in_the_file_and_on_stdin(tmp_path):
    """Before: the names read as ``'"TIMESTAMP_START"'``: no time found, no role matched."""
    path = twice_quoted(tmp_path / "flux_21.dat")
    cfg = {"roles": FLUX_ROLES}
    ds, _ = read_dataset(path, cfg)
    plain, _ = read_dataset(FLUX, cfg)
    df, want = ds.campaigns[ds.ids()[0]], plain.campaigns[plain.ids()[0]]
    assert list(df.columns) == list(want.columns) and "E_T_1_9_1" in df.columns
    np.testing.assert_array_equal(df.to_numpy(), want.to_numpy())
    streamed, _ = read_stream(path.read_text(), ["T_1_5_1"], ReadOptions.from_cfg(cfg))
    assert streamed["T_1_5_1"].tolist() == want["T_1_5_1"].tolist()
    assert np.diff(streamed["time"]).tolist() == [1800.0] * (len(streamed) - 1)


def test_a_note_in_parentheses_is_no_foreign_unit():
    """Only a unit the units row states, or one written as a unit (per s, m, h, m^2, a power),
    is left out by ``init``: a lab's note, ``T1 (front/left)``, is refused as before."""
    from thermocomp.core.io.units import foreign_unit

    assert all(map(foreign_unit, ("W/m^2", "m/s", "W/m2", "g/m³", "umol/m^2/s", "unitless")))
    assert not any(map(foreign_unit, ("front/left", "front", "mm/rev", "W", "%", "°C", "mm/min")))
    assert foreign_unit("front", stated=True) and not foreign_unit("W", stated=True)
