"""A lab's two loggers, temperatures in one file and displacements in another (session 56)."""

from __future__ import annotations

import pytest

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError


def two_loggers(folder) -> None:
    """One run's samples, its temperatures in one file and its errors (mm) in another."""
    folder.mkdir()
    times = [f"2026-10-24T19:{m:02d}:00" for m in range(30, 40)]
    (folder / "temperatures.csv").write_text("time,T_spindle,T_bed\n" + "".join(
        f"{t},{20 + 0.1 * i:.2f},{21 - 0.05 * i:.2f}\n" for i, t in enumerate(times)))
    (folder / "displacements.csv").write_text("time,dX [mm],dZ [mm]\n" + "".join(
        f"{t},{0.001 * i:.4f},{-0.002 * i:.4f}\n" for i, t in enumerate(times)))


def test_a_folder_of_two_loggers_files_is_refused_naming_the_file_with_the_errors(tmp_path):
    # the temperatures' file was refused for having no error column, asking to name one in it
    # (data.roles.error=[<header>]): the errors are in the other file, not joined by these names
    two_loggers(tmp_path / "lab")
    roles = {"roles": {"error": ["d*"]}}
    with pytest.raises(ContractError) as refused:
        read_dataset(tmp_path / "lab", roles)
    message = str(refused.value)
    assert "temperatures.csv: no E_ column, and displacements.csv beside it holds errors " \
           "(E_dX, E_dZ) without a temperature" in message
    # (twolog70: files named as one run's pair are joined; these are named apart)
    assert ("joined by time, where their names are one stem and a last word each "
            "(run03_temp.csv and run03_disp.csv): rename them so") in message
