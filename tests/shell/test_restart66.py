"""Files of one record whose time starts again at 0, fed to a deployed stream (restart66).

A lab's day files, each logger run from 0, that continue one another (the manifest's
``continues``) are one campaign: ``run``, ``replay`` and the check pack join them one sample
period apart, each file's own steps after.  The deployed stream fed them after one another (the
compiled ``stream`` one process per file with ``--state``, or the files piped whole; the
Python stream, the Simulator, the Structured Text) judged each time against the last time read
only: a restarted file's times were taken one period apart until they passed the last file's
end, then read as they were, a step back by all of them (the lag bank's ``exp(-dt/tau)``
growing; 13.0 µm from the pack on the record of day files of 200, 280 and 240 minutes below).  Now a
time not after the last read followed by one after it is a clock that restarted: the stream
counts on with it from one period after the previous row, as the batch joins the files.
"""

from __future__ import annotations

import io
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST
from test_export import StructuredText, _compiled, _streamed, checked_pack, needs_cc, own_expected
from test_export_first_time import AGREE_UM, _corrections, _deployed
from test_export_guard import _rows, _simulated, _st
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.shell.cli import main


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    from test_export import _make_dataset

    return _make_dataset(tmp_path_factory.mktemp("restart") / "data")


@needs_cc
@pytest.mark.parametrize("adaptive", (True, False), ids=("adaptive", "plain"))
def test_a_clock_that_starts_again_steps_as_the_record_joined_in_every_form(dataset, tmp_path,
                                                                           adaptive):
    # before: the Python stream 21497 um off (adaptive; plain 6.96 um) once the restarted times
    # passed the last one read
    deployed, complete = _deployed(dataset, adaptive)
    complete = complete.assign(time=complete["time"] - complete["time"].iloc[0])
    k = len(complete) // 3                 # the later file longer: its times pass the first's
    restarted = complete.copy()
    restarted.loc[k:, "time"] = complete["time"].iloc[k:] - complete["time"].iloc[k]
    assert restarted["time"].iloc[-1] > restarted["time"].iloc[k - 1]
    # the record joined one period apart at the restart: on this grid, the complete record
    expected = _corrections(deployed, complete)
    cols, ss = deployed.columns_, state_space(deployed)
    forms = {"python stream": _corrections(deployed, restarted),
             "simulator": _simulated(ss, [restarted], cols),
             "c": _streamed(_compiled(deployed, tmp_path), _rows([restarted], cols)).to_numpy(float),
             "st": _st(StructuredText(exported_files(deployed, "st")["compensator.st"]),
                       [restarted], cols)}
    for form, got in forms.items():
        assert np.max(np.abs(got - expected)) <= AGREE_UM, form


LENGTHS = (200, 280, 240)      # a lab's day files, one row a minute


def day_files(folder: Path, hours: bool = False) -> list[Path]:
    """The day files of one record (a column heated in steps that E_X follows through a 20-min
    lag), each file's time from 0 s (``hours``: headed ``time [h]``, in hours to four decimals),
    and a manifest whose ``continues`` chains them."""
    folder.mkdir(parents=True)
    rng = np.random.default_rng(6606)
    n = sum(LENGTHS)
    power = np.repeat(rng.uniform(0, 1, n // 60 + 1), 60)[:n]
    heat, lag = np.zeros(n), np.zeros(n)
    for k in range(1, n):
        heat[k] = heat[k - 1] + (4 * power[k] - heat[k - 1]) * 60 / 1800
        lag[k] = lag[k - 1] + (heat[k] - lag[k - 1]) * 60 / 1200
    hall = 19 + 0.5 * np.sin(np.arange(n) * 60 / 20000)
    column = hall + heat + rng.normal(0, 0.01, n)
    dx = 3.0 * lag + 0.8 * (hall - 19) + rng.normal(0, 0.02, n)
    paths, manifest, start = [], ["campaign,file,split,continues"], 0
    for f, rows in enumerate(LENGTHS):
        part = slice(start, start + rows)
        time = {"time [h]": (np.arange(rows) / 60).round(4)} if hours else {
            "time": np.arange(rows) * 60.0}
        pd.DataFrame({**time, "T_column": column[part].round(3),
                      "T_hall": hall[part].round(3), "E_X": dx[part].round(3)}
                     ).to_csv(folder / f"day{f + 1}.csv", index=False)
        paths.append(folder / f"day{f + 1}.csv")
        manifest.append(f"day{f + 1},day{f + 1}.csv,{'test' if f == len(LENGTHS) - 1 else 'train'},"
                        f"{f'day{f}' if f else ''}")
        start += rows
    (folder / "campaigns.csv").write_text("\n".join(manifest) + "\n")
    return paths


@needs_cc
def test_the_compiled_stream_fed_day_files_from_0_gives_its_pack(tmp_path):
    # before: 11.6 um from the pack from the second file's 201st row on (its time past the first
    # file's last), the same in one process per file and in the files piped whole
    paths = day_files(tmp_path / "lab")
    common = [f"data.path={paths[0].parent}", "data.reference=none"]
    assert main(["run", *common, *FAST, "model=lagbank", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    code = tmp_path / "code"
    checked_pack(code)
    want = pd.read_csv(own_expected(code)[0]).to_numpy(float)
    assert want.shape[0] == sum(LENGTHS)              # the pack: the record joined

    got, said = [], []
    for path in paths:
        done = subprocess.run(["./stream", "--state", str(tmp_path / "state")], cwd=code,
                              input=path.read_bytes(), capture_output=True)
        assert done.returncode == 0, done.stderr
        said.append(done.stderr.decode())
        got.append(pd.read_csv(io.BytesIO(done.stdout)).to_numpy(float))
    assert np.abs(np.concatenate(got) - want).max() < 1e-9
    # where the rule sets in, said: the second and third file's first row
    assert ["line 2: the time (0 s) is not after the last read" in s for s in said] == [
        False, True, True], said

    text = paths[0].read_text() + "".join(p.read_text().split("\n", 1)[1] for p in paths[1:])
    done = subprocess.run(["./stream"], cwd=code, input=text.encode(), capture_output=True)
    assert done.returncode == 0, done.stderr
    assert np.abs(pd.read_csv(io.BytesIO(done.stdout)).to_numpy(float) - want).max() < 1e-9


@needs_cc
def test_the_check_pack_of_a_lab_time_headed_time_in_hours_passes(tmp_path):
    # before: the pack's rows.csv heads its time `time` (s); stream.c read that header as the
    # lab's `time [h]` (a header whose unit is in a unit row), in hours: 0.163 um off at row 2,
    # the pack failed its own check
    paths = day_files(tmp_path / "lab", hours=True)
    common = [f"data.path={paths[0].parent}", "data.reference=none"]
    assert main(["run", *common, *FAST, "model=lagbank", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    checked_pack(tmp_path / "code")
    # the lab's own file, in hours: its time read as the reader reads it (no 'no time column')
    done = subprocess.run(["./stream"], cwd=tmp_path / "code", input=paths[0].read_bytes(),
                          capture_output=True)
    assert done.returncode == 0 and b"no time column" not in done.stderr, done.stderr
