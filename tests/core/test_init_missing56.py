"""`thermocomp init` given a file that is not there, a name mistyped (session 56)."""

from __future__ import annotations

import pytest

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError
from thermocomp.shell.cli import main


def test_init_of_a_mistyped_file_says_there_is_no_such_file_and_the_close_name(tmp_path, capsys):
    # refused "file <dir>/Lab.CSV/campaigns.csv: manifest not found (a dataset folder needs
    # campaigns.csv)": the file looked for as a folder
    (tmp_path / "lab.csv").write_text("time,T_1,E_X\n0,20,0\n60,20.1,0.2\n", encoding="utf-8")
    assert main(["init", str(tmp_path / "Lab.CSV"), f"out={tmp_path / 'init'}"]) == 2
    assert capsys.readouterr().err.strip().endswith(
        f"file {tmp_path / 'Lab.CSV'}: no such file or folder: did you mean 'lab.csv'?")
    assert not (tmp_path / "init").exists()


def test_a_dataset_folder_that_is_not_there_is_named_so(tmp_path):
    # refused "file <dir>/runs/campaigns.csv: manifest not found": as if the folder were there
    with pytest.raises(ContractError, match=r"runs: no such file or folder \(data.path: a dataset "
                                            r"folder or one record's file\)$"):
        read_dataset(tmp_path / "runs")
