"""A lab's one export put in a folder of its own (vol57): `init` and `run data.test_fraction`
held out nothing and were refused naming a campaigns.csv that is not there ("1 train
campaign(s) cannot be split ... lower data.test_fraction"); they name the file to give."""

from __future__ import annotations

import numpy as np
import pandas as pd
import yaml

from conftest import refused
from thermocomp.shell.cli import main


def _one_export(folder):
    folder.mkdir()
    t = np.arange(200) * 60.0
    temp = 20 + 2 * np.sin(t / 3000)
    pd.DataFrame({"time": t, "T_spindle": temp, "E_Z": 3 * (temp - 20)}).to_csv(folder / "week.csv",
                                                                             index=False)
    return folder


def test_init_on_a_folder_of_one_file_reads_the_file(tmp_path, capsys):
    # (refused naming the file to give until newmachine58: init reads it as the record, as a
    # folder's one long file of runs numbered in a column is)
    folder = _one_export(tmp_path / "export")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0
    assert "one file and no campaigns.csv: read as the record week.csv" in capsys.readouterr().out
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "week.yaml").read_text())
    assert config["path"] == str(folder / "week.csv")


def test_run_with_a_test_fraction_on_it_says_the_same(tmp_path, capsys):
    folder = _one_export(tmp_path / "export")
    refused(["run", f"data.path={folder}", "data.test_fraction=0.2", "track=false", "plots=none",
             f"out={tmp_path / 'o'}"], capsys, f"data.path={folder / 'week.csv'}")
