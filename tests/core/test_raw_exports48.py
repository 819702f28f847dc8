"""A lab's raw export, round 5 (session 48): a numeric column that is no temperature."""

from __future__ import annotations

from conftest import refused


def test_a_spindle_speed_read_as_a_temperature_is_not_called_kelvin(tmp_path, capsys):
    # 'S' (a CNC's spindle speed) has no role pattern: read as a temperature by default; its
    # 3000 was refused "temperatures look like kelvin, convert to °C"
    path = tmp_path / "lab.csv"
    path.write_text("time,T1 [°C],S,dX [µm]\n" + "".join(
        f"{15 * i},{20 + 0.1 * i},{3000 if i % 7 else 0},{0.5 * i}\n" for i in range(40)))
    line = refused(["init", str(path), f"out={tmp_path / 'out'}"], capsys, "column 'T_S'",
                   "no temperature, in °C or kelvin", "data.roles.state=['S']")
    assert "convert to °C" not in line


def test_kelvin_is_still_called_kelvin(tmp_path, capsys):
    path = tmp_path / "lab.csv"
    path.write_text("time,T1,dX [µm]\n" + "".join(
        f"{15 * i},{293.15 + 0.1 * i},{0.5 * i}\n" for i in range(40)))
    refused(["init", str(path), f"out={tmp_path / 'out'}"], capsys, "look like kelvin")
