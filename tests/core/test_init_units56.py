"""What a header's unit says, for `init`'s proposals and `run`'s reading alike (session 56).

A stranger's two lab exports (benchmarks/bench_new_machines56.py) needed every role spelled out:
an on/off flag's ``[-]`` was refused as no temperature's unit, one role given stopped every
proposal, and ``Y position [mm]`` read as an error.
"""

from __future__ import annotations

import pytest
import yaml

from thermocomp.core.io import ContractError
from thermocomp.core.io.roles import contract_columns
from thermocomp.shell.cli import main


def lab_file(path, headers, sep=","):
    """30 rows a minute apart: time, then per header a slow ramp (a flag: 0/1 blocks)."""
    rows = [sep.join(["Zeit [s]", *headers])]
    for i in range(30):
        cells = [str(60 * i)]
        for k, h in enumerate(headers):
            cells.append(str((i // 5) % 2) if "[-]" in h or "[1]" in h
                         else f"{20 + 0.05 * i * (k + 1):.2f}")
        rows.append(sep.join(cells))
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return path


def init_roles(tmp_path, path, *args):
    assert main(["init", str(path), "data.test_fraction=0.25", *args,
                 f"out={tmp_path / 'init'}"]) == 0
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / f"{path.stem}.yaml").read_text())
    return config["roles"]


def test_a_dimensionless_flag_is_proposed_as_a_state(tmp_path):
    # '[-]' was read as a temperature and refused: "unit '-' is not a temperature's"
    path = lab_file(tmp_path / "lab.csv", ["Tisch [°C]", "dY [µm]", "Kühlmittel ein [-]",
                                           "Zähler [1]", "Leistung [kW]"])
    roles = init_roles(tmp_path, path)
    assert roles["state"] == ["Kühlmittel ein", "Zähler", "Leistung"]
    assert roles["error"] == ["dY"]


def test_one_role_given_the_other_headers_still_get_proposals(tmp_path):
    # with data.roles.state given nothing else was proposed: "no column reads as a measured error"
    path = lab_file(tmp_path / "lab.csv", ["Tisch [°C]", "Hallentemperatur [°C]", "dY [µm]",
                                           "Pumpe [-]", "Drehzahl [1/min]"])
    roles = init_roles(tmp_path, path, "data.roles.state=['Pumpe*']")
    assert roles["state"] == ["Pumpe*", "Drehzahl"]       # the user's pattern kept as given
    assert roles["error"] == ["dY"] and roles["ambient"] == ["Hallentemperatur"]


def test_the_users_pattern_wins_where_it_matches(tmp_path):
    # 'Y position' would be proposed a state; the user says it is an error. 'Spindle speed' is
    # matched by nothing given: proposed a state (it was read as a temperature in rpm, refused)
    path = lab_file(tmp_path / "lab.csv", ["T1 [°C]", "Y position [mm]", "Spindle speed [rpm]"])
    roles = init_roles(tmp_path, path, "data.roles.error=['Y position*']")
    assert roles["error"] == ["Y position*"] and roles["state"] == ["Spindle speed"]


def test_a_length_named_as_a_position_is_a_state_and_a_displacement_an_error(tmp_path):
    # 'Y position [mm]' was proposed an error (its mm)
    path = lab_file(tmp_path / "lab.csv", ["T1 [°C]", "Y position [mm]", "Querachse dZ [mm]",
                                           "X error [µm]", "Zpos [mm]"])
    roles = init_roles(tmp_path, path)
    assert roles["state"] == ["Y position", "Zpos"]
    assert roles["error"] == ["Querachse dZ", "X error"]


def test_a_length_named_by_its_axis_alone_is_listed_not_guessed(tmp_path, capsys):
    # 'X [mm]' and 'Y-Achse [mm]' were proposed errors silently: a position or an error?
    path = lab_file(tmp_path / "lab.csv", ["T1 [°C]", "dZ [µm]", "X [mm]", "Y-Achse [mm]"])
    assert main(["init", str(path), "data.test_fraction=0.25", f"out={tmp_path / 'init'}"]) == 2
    err = capsys.readouterr().err
    # (stranger69: 'Y-Achse [mm]' spans 5.8 mm here, more than a thermal error does: a position,
    # proposed a state as any length of such a span is; 'X [mm]' spans 4.35 mm: still asked)
    assert "1 column(s) not read" in err and "'Y-Achse [mm]'" not in err
    for header, base in (("X [mm]", "X"),):
        assert (f"'{header}' is a length named by its axis alone: the error "
                f"(data.roles.error=['{base}']) or its position (data.roles.state=['{base}'])?") in err
    assert not (tmp_path / "init").exists()
    # the user's word settles it, and the config reads
    roles = init_roles(tmp_path, path, "data.roles.state=[X]", "data.roles.error=['Y-Achse']")
    assert roles["state"] == ["X"] and roles["error"] == ["Y-Achse", "dZ"]


def test_the_only_length_named_by_its_axis_is_named_in_the_refusal(tmp_path, capsys):
    # no error proposed at all: the refusal says which column could be it, and how to say so
    path = lab_file(tmp_path / "lab.csv", ["T1 [°C]", "Z [mm]"])
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 2
    err = capsys.readouterr().err
    assert "no column reads as a measured error" in err
    assert "'Z [mm]' is a length named by its axis alone" in err


def test_run_reads_headers_no_pattern_names_by_their_units():
    # the same rule when a run is given some roles: these were read as temperatures, refused
    headers = ["Zeit [s]", "T1 [°C]", "Zustellung dY [µm]", "Querachse dZ [mm]", "Y position [mm]",
               "Hydraulik ein [-]", "Drehmoment [Nm]", "Scheibe [1/min]", "Messuhr [mm]", "note"]
    assert contract_columns(headers, {"ignore": ["note"]}) == {
        "Zeit [s]": "time", "T1 [°C]": "T_T1", "Zustellung dY [µm]": "E_Zustellung_dY",
        "Querachse dZ [mm]": "E_Querachse_dZ", "Y position [mm]": "S_Y_position",
        "Hydraulik ein [-]": "S_Hydraulik_ein", "Drehmoment [Nm]": "S_Drehmoment",
        "Scheibe [1/min]": "S_Scheibe", "Messuhr [mm]": "E_Messuhr"}


def test_run_lists_a_length_named_by_its_axis_alone():
    with pytest.raises(ContractError, match=r"'X \[mm\]' is a length named by its axis alone"):
        contract_columns(["time", "T1 [°C]", "dZ [µm]", "X [mm]"], {"error": ["dZ"]})
