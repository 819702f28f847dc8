"""The compiled stream at the joins of a lab's files of one clock (weekjoin66).

A record cut into consecutive files whose time runs on (elapsed hours written to four
decimals, as the portal mill's weekly files: a 60 s logger steps 59.76 or 60.12 s) is one
campaign: ``run`` and ``replay`` join the files, ``export``'s check pack holds the joined rows.
The join put one sample period (the mean step, 60.00 s) between a file's last row and the next
file's first, where the files' own clock says 59.76 or 60.12 s, as the compiled stream reads
it (the files streamed on in one process, or one process per file with ``--state``): the
stream parted from its pack at each join (4.9e-4 µm on the portal mill's diagnosed MLR,
dying away over ~800 rows).  Now a join on one clock keeps the step the clock shows.
"""

from __future__ import annotations

import io
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd

from conftest import FAST
from test_export import checked_pack, needs_cc, own_expected
from thermocomp.shell.cli import main

ROWS = 240        # rows per file, one a minute


def lab_files(folder: Path, files: int = 3) -> list[Path]:
    """``files`` TAB files of one record, decimal commas, a two-line preamble, the time as
    elapsed hours to four decimals that run on from file to file; a column heated in steps
    that E_dX follows through a 20-min lag (what a lag bank's state carries across a join)."""
    folder.mkdir(parents=True)
    rng = np.random.default_rng(6601)
    n = files * ROWS
    t = np.arange(n) * 60.0
    power = np.repeat(rng.uniform(0, 1, n // 60 + 1), 60)[:n]
    heat = np.zeros(n)
    for k in range(1, n):
        heat[k] = heat[k - 1] + (4 * power[k] - heat[k - 1]) * 60 / 1800
    hall = 19 + 0.5 * np.sin(t / 20000)
    column = hall + heat + rng.normal(0, 0.01, n)
    lag = np.zeros(n)
    for k in range(1, n):
        lag[k] = lag[k - 1] + (heat[k] - lag[k - 1]) * 60 / 1200
    dx = 3.0 * lag + 0.8 * (hall - 19) + rng.normal(0, 0.02, n)
    paths = []
    for f in range(files):
        lines = ["Machine;PM-12", "Operator: K. Brandt",
                 "t [h]\tT column [°C]\tT hall [°C]\tdX [µm]"]
        for k in range(f * ROWS, (f + 1) * ROWS):
            lines.append("\t".join([f"{t[k] / 3600:.4f}", f"{column[k]:.2f}", f"{hall[k]:.2f}",
                                    f"{dx[k]:.2f}"]).replace(".", ","))
        paths.append(folder / f"week{f + 1}.txt")
        paths[-1].write_text("\n".join(lines) + "\n", encoding="utf-8")
    return paths


def test_a_join_on_one_clock_keeps_the_step_the_clock_shows(tmp_path):
    # before: the joined record stepped one mean period (60.00 s) at each join where the
    # files' hours step 60.12 s: the only step of the record not read from its clock
    from thermocomp.core.continuation import chains, joined
    from thermocomp.core.io import read_dataset

    paths = lab_files(tmp_path / "lab")
    ds, _ = read_dataset(paths[0].parent, {"roles": {"error": ["dX"]}})
    ids = chains(ds)[ds.ids()[-1]]
    assert ids == ds.ids()
    whole = joined(ds, ids)
    read = np.concatenate([ds.campaigns[c]["time"].to_numpy(float) for c in ids])
    steps = np.diff(whole["time"].to_numpy(float))
    np.testing.assert_allclose(steps, np.diff(read), rtol=0, atol=1e-6)
    assert set(np.round(steps[ROWS - 1::ROWS], 2)) <= {59.76, 60.12}


@needs_cc
def test_the_compiled_stream_fed_the_files_gives_its_pack_at_the_joins(tmp_path):
    # before: 1e-4 um and more from the pack at each join's first row (the lag's state stepped
    # 60.00 s in the pack, 60.12 s in the stream), within 1e-9 elsewhere
    paths = lab_files(tmp_path / "lab")
    common = [f"data.path={paths[0].parent}", "data.roles.error=[dX]", "data.test_fraction=0.3"]
    assert main(["run", *common, *FAST, "model=lagbank", "plots=none",
                 f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    code = tmp_path / "code"
    checked_pack(code)
    want = pd.read_csv(own_expected(code)[0]).to_numpy(float)
    assert want.shape[0] == 3 * ROWS                    # the pack: the record joined

    # one process per file, --state carrying the campaign from one to the next
    got = []
    for path in paths:
        done = subprocess.run(["./stream", "--state", str(tmp_path / "state")], cwd=code,
                              input=path.read_bytes(), capture_output=True)
        assert done.returncode == 0, done.stderr
        got.append(pd.read_csv(io.BytesIO(done.stdout)).to_numpy(float))
    got = np.concatenate(got)
    assert got.shape == want.shape
    assert np.abs(got - want).max() < 1e-9

    # the files streamed on in one process (each later file's preamble and header left out)
    text = paths[0].read_text(encoding="utf-8") + "".join(
        "".join(p.read_text(encoding="utf-8").splitlines(keepends=True)[3:]) for p in paths[1:])
    done = subprocess.run(["./stream"], cwd=code, input=text.encode(), capture_output=True)
    assert done.returncode == 0, done.stderr
    assert np.abs(pd.read_csv(io.BytesIO(done.stdout)).to_numpy(float) - want).max() < 1e-9
