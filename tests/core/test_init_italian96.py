"""An Italian PC's export with a unit row (stop 96, benchmarks/bench_audit96.py ``lab``).

Its speeds' unit ``giri/min`` (revolutions per minute) was no unit the reader knew: under the
headers the unit row was then read as data, every column refused as text ("no column reads as
a measured error ...; the numeric columns: 'Data e ora'"), and in a header (``[giri/min]``) the
speed was left out as a unit of no sensor.  French ``tr/min`` and English ``rev/min`` alike; and a
unit row with a unit of no sensor (a coolant's ``l/min``) was read as data so too.
"""

from __future__ import annotations

import pytest
import yaml

from thermocomp.core.io.roles import contract_columns
from thermocomp.shell.cli import main

HEADERS = ["Data e ora", "Temperatura ambiente", "Temperatura testa motrice", "Errore X",
           "Velocità mandrino", "Porta"]


def lab_file(path, speed_unit: str):
    """Excel's ``sep=;`` line, the headers, a unit row under them (``giri/min``, ``-``), 40 rows
    a minute apart with offset timestamps, decimal commas and thousands dots (``5.000``)."""
    rows = ["sep=;", ";".join(HEADERS), ";".join(["", "°C", "°C", "µm", speed_unit, "-"])]
    for i in range(40):
        rows.append(";".join([f"2027-03-27 21:{10 + i:02d}:00+01:00",
                              f"{20 + 0.01 * i:.2f}".replace(".", ","),
                              f"{21 + 0.05 * i:.2f}".replace(".", ","),
                              f"{0.4 * i:.1f}".replace(".", ","),
                              "5.000" if i % 10 < 5 else "3.000", str(i // 20)]))
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return path


@pytest.mark.parametrize("unit", ["giri/min", "tr/min", "rev/min"])
def test_a_unit_row_with_a_speed_in_the_labs_language_is_read(tmp_path, unit):
    path = lab_file(tmp_path / "prova.csv", unit)
    assert main(["init", str(path), "data.test_fraction=0.25", f"out={tmp_path / 'init'}"]) == 0
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "prova.yaml").read_text())
    assert config["roles"]["error"] == ["Errore X"]         # (refused before: the unit row as data)
    assert config["roles"]["state"] == ["Velocità mandrino", "Porta"]
    assert config["thousands"] == "."


def test_a_header_in_giri_per_minute_is_a_state():
    named = contract_columns(["t [s]", "T1 [°C]", "Errore X [µm]", "Velocità mandrino [giri/min]",
                              "Vitesse broche [tr/min]"], {"error": ["Errore X"]})
    assert named["Velocità mandrino [giri/min]"] == "S_Velocità_mandrino"     # (left out before)
    assert named["Vitesse broche [tr/min]"] == "S_Vitesse_broche"


def test_a_unit_row_with_a_unit_of_no_sensor_is_read_and_its_column_left_out(tmp_path):
    # a coolant's flow in l/min under the speed's header: the row was read as data (every
    # column refused as text); now a unit row, the flow left out by its unit as in a header
    path = lab_file(tmp_path / "prova.csv", "l/min")
    assert main(["init", str(path), "data.test_fraction=0.25", f"out={tmp_path / 'init'}"]) == 0
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "prova.yaml").read_text())
    assert config["roles"]["error"] == ["Errore X"]
    assert config["roles"]["state"] == ["Porta"]
    assert "Velocità mandrino" in config["roles"]["ignore"]


def test_a_mark_without_a_digit_is_no_misgrouped_thousand(tmp_path, capsys):
    # 'n.d.' (not available) in a temperature of a file with thousands dots: init refused the
    # speeds' '5.000' at data row 1 ("a thousands separator? set data.thousands='.'"), and a run
    # with data.thousands='.' said 'n.d.' "does not group its digits by three"
    path = lab_file(tmp_path / "prova.csv", "giri/min")
    lines = path.read_text(encoding="utf-8").splitlines()
    cells = lines[3 + 19].split(";")
    cells[2] = "n.d."
    lines[3 + 19] = ";".join(cells)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    assert main(["init", str(path), "data.test_fraction=0.25", f"out={tmp_path / 'init'}"]) == 0
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "prova.yaml").read_text())
    assert config["thousands"] == "." and config["missing_values"] == ["n.d."]
    capsys.readouterr()
    assert main(["ingest", f"data.path={path}", "data.thousands=.", "data.decimal=,",
                 "data.delimiter=;", "data.roles.error=[Errore X]",
                 "data.roles.state=['Velocità mandrino',Porta]"]) == 2
    said = capsys.readouterr().err
    assert "column 'T_testa_motrice', line 23 (data row 20): value 'n.d.' is not a number" in said
    assert "data.missing_values" in said
