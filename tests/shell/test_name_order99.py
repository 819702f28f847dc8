"""A lab's folder of runs named by their day-first dates (``Lauf 02.02.2023.csv`` first by name,
last in time), no manifest, with ``data.test_fraction``: the last run in time is held out, and
the line after said the files were "read as train campaigns in name order (data.test_fraction
holds the last out)", the last by name to a reader (audit99)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.shell.cli import main


def _dated_runs(folder):
    folder.mkdir()
    for day in ("11.01.2023", "31.01.2023", "02.02.2023"):
        start = pd.Timestamp(f"{day[6:]}-{day[3:5]}-{day[:2]} 08:00")
        t = np.arange(60) * 60.0
        temp = 20 + 2 * np.sin(t / 900)
        pd.DataFrame({"Zeit": [f"{start + pd.Timedelta(seconds=s):%d.%m.%Y %H:%M:%S}" for s in t],
                      "T_spindle": temp, "E_Z": 3 * (temp - 20)}).to_csv(folder / f"Lauf {day}.csv",
                                                                          index=False)
    return folder


def test_the_folder_line_does_not_say_the_last_by_name_is_held_out(tmp_path, capsys):
    folder = _dated_runs(tmp_path / "runs")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().err.splitlines()
    assert "[thermocomp] held out by start time: test ['Lauf 02.02.2023']" in said
    line = next(m for m in said if "campaign files read as" in m)
    assert "holds the last out" not in line and "train but those held out above" in line
