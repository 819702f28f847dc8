"""Run as a stranger would, off the happy path (session 47): a lab's folder of runs in which one
run has a sensor more or one less than the others."""

from __future__ import annotations

import pytest
import yaml

from conftest import refused
from test_raw_exports44 import _record, _write
from thermocomp.shell.cli import main


def _runs(folder, odd: str):
    """Three runs of one rig (no manifest); ``run_2`` has a sensor more (``extra``) or less."""
    folder.mkdir()
    t, t1, t2, e = _record()
    for k in (1, 2, 3):
        header, columns = ["time [s]", "T1 [°C]", "T2 [°C]", "dX [µm]"], [t, t1 + k, t2, e]
        if k == 2 and odd == "extra":
            header, columns = [*header, "T3 [°C]"], [*columns, t2 + 1]
        if k == 2 and odd == "missing":
            header, columns = [h for h in header if h != "T2 [°C]"], [t, t1 + k, e]
        _write(folder / f"run_{k}.csv", header, columns)
    return folder


@pytest.mark.parametrize("odd, column, says", [("extra", "T_T3", "only 1 of 3 campaigns have it"),
                                               ("missing", "T_T2", "1 of 3 campaigns lack it")])
def test_init_refuses_a_folder_whose_runs_differ_in_a_sensor_as_run_does(tmp_path, capsys, odd,
                                                                         column, says):
    # before: init wrote the data config and said 'next: thermocomp run ...', which then
    # refused the folder; now init refuses it as run does, naming the file and the remedy
    folder = _runs(tmp_path / "runs", odd)
    refused(["init", str(folder), f"out={tmp_path / 'init'}"], capsys,
            f"file {folder / 'run_2.csv'}", f"column '{column}'", says, "data.inputs")
    assert not (tmp_path / "init").exists()
    assert main(["init", str(folder), "data.inputs=[T_T1]", f"out={tmp_path / 'init'}"]) == 0
    written = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text())
    assert written["inputs"] == ["T_T1"]
