"""A refusal of a lab's column names its header and a fix that matches it (session 56)."""

from __future__ import annotations

import pytest

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError

ROLES = {"error": ["dX*"]}


def test_an_empty_sensor_column_is_refused_with_a_role_pattern_that_matches_its_header(tmp_path):
    # refused "column 'T_Kanal_7': ... leave it out (data.roles.ignore)": the contract name
    # given there as the pattern, data.roles.ignore=[T_Kanal_7], matches no header of the file
    # and the same refusal came back
    path = tmp_path / "lab.csv"
    path.write_text("Zeit,Spindel [°C],Kanal 7 [°C],dX [µm]\n" + "".join(
        f"{60 * i},{20 + 0.1 * i:.2f},,{0.3 * i:.1f}\n" for i in range(10)), encoding="utf-8")
    with pytest.raises(ContractError) as refused:
        read_dataset(path, {"roles": ROLES})
    assert refused.value.column == "T_Kanal_7"
    assert refused.value.reason.endswith("leave it out (data.roles.ignore=['Kanal 7']) (its header "
                                         "in the file: 'Kanal 7 [°C]')")
    ds, _ = read_dataset(path, {"roles": {**ROLES, "ignore": ["Kanal 7"]}})
    assert list(next(iter(ds.campaigns.values())).columns) == ["time", "T_Spindel", "E_dX"]


def test_every_empty_channel_of_a_logger_is_refused_in_one_message(tmp_path):
    # one refusal per unused channel, each a run of the command to learn the next one
    path = tmp_path / "lab.csv"
    path.write_text("Zeit,Spindel [°C],Kanal 7 [°C],Kanal 8 [°C],dX [µm]\n" + "".join(
        f"{60 * i},{20 + 0.1 * i:.2f},,,{0.3 * i:.1f}\n" for i in range(10)), encoding="utf-8")
    with pytest.raises(ContractError) as refused:
        read_dataset(path, {"roles": ROLES})
    assert refused.value.reason == (
        "column has no valid value (every cell is empty), nor has 'T_Kanal_8': not measured? leave "
        "them out (data.roles.ignore=['Kanal 7', 'Kanal 8']) (their headers in the file: "
        "'Kanal 7 [°C]', 'Kanal 8 [°C]')")
    ds, _ = read_dataset(path, {"roles": {**ROLES, "ignore": ["Kanal 7", "Kanal 8"]}})
    assert list(next(iter(ds.campaigns.values())).columns) == ["time", "T_Spindel", "E_dX"]
