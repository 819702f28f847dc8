"""A lab's one export put in a folder of its own (vol57): `init` and `run data.test_fraction`
held out nothing and were refused naming a campaigns.csv that is not there ("1 train
campaign(s) cannot be split ... lower data.test_fraction"); they name the file to give."""

from __future__ import annotations

import numpy as np
import pandas as pd

from conftest import refused


def _one_export(folder):
    folder.mkdir()
    t = np.arange(200) * 60.0
    temp = 20 + 2 * np.sin(t / 3000)
    pd.DataFrame({"time": t, "T_spindle": temp, "E_Z": 3 * (temp - 20)}).to_csv(folder / "week.csv",
                                                                             index=False)
    return folder


def test_init_on_a_folder_of_one_file_names_the_file_to_give(tmp_path, capsys):
    folder = _one_export(tmp_path / "export")
    line = refused(["init", str(folder)], capsys, f"data.path={folder / 'week.csv'}")
    assert "campaigns.csv" not in line


def test_run_with_a_test_fraction_on_it_says_the_same(tmp_path, capsys):
    folder = _one_export(tmp_path / "export")
    refused(["run", f"data.path={folder}", "data.test_fraction=0.2", "track=false", "plots=none",
             f"out={tmp_path / 'o'}"], capsys, f"data.path={folder / 'week.csv'}")
