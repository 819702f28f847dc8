"""A jig borer's LabVIEW program logging a TDMS file a run (stranger80): DAQmx's two tasks as two
groups, the thermocouples' at 30 s (``unit_string`` ``Deg C``), the probes' and the PLC's at
10 s started 20 s later (``dX`` in ``um``, the quill's travel ``W Pinole [mm]``), no time channel
(each channel's ``wf_start_time`` / ``wf_increment``), an open thermocouple's NaN in one run
(``benchmarks/bench_stranger80.py`` writes the lab's full record; these are a few rows of
test_stranger68's linear runs)."""

from __future__ import annotations

import datetime as dt
from pathlib import Path

import numpy as np
import pytest

from test_stranger68 import linear_run
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

nptdms = pytest.importorskip("nptdms")

START = dt.datetime(2027, 3, 15, 6)           # UTC (07:00 CET)


def _run(folder: Path, run: int, nan_rows: int = 0, fast_nan: int = 0) -> Path:
    """``KBM_<run>.tdms``: ``Temperaturen`` (three channels at 30 s, ``nan_rows`` NaN in
    ``Ständer``), ``Wege+CNC`` (dX, dZ in um and the quill's travel in mm, at 10 s from 20 s
    on: the 30 s rows' values held three times, the linear map of the held temperatures;
    ``fast_nan`` NaN in the travel)."""
    from nptdms import ChannelObject, GroupObject, RootObject, TdmsWriter

    folder.mkdir(parents=True, exist_ok=True)
    values = linear_run(8011, run)
    temps = values[:, :3].copy()
    temps[40:40 + nan_rows, 1] = np.nan
    start = np.datetime64(START + dt.timedelta(days=run - 1), "us")
    slow = {"wf_start_time": start, "wf_increment": 30.0, "unit_string": "Deg C"}
    late = {"wf_start_time": start + np.timedelta64(20, "s"), "wf_increment": 10.0}
    objs = [RootObject(), GroupObject("Temperaturen"), GroupObject("Wege+CNC")]
    objs += [ChannelObject("Temperaturen", name, temps[:, j], properties=slow)
             for j, name in enumerate(["Halle", "Ständer", "Pinole"])]
    fast = np.repeat(values, 3, axis=0)[2:]          # (held: the 10 s rows of the 30 s rows)
    objs += [ChannelObject("Wege+CNC", name, fast[:, k], properties={**late, "unit_string": "um"})
             for name, k in (("dX", 3), ("dZ", 4))]
    travel = np.where((np.arange(fast.shape[0]) // 90) % 2, 250.0, 0.0)
    travel[100:100 + fast_nan] = np.nan
    objs.append(ChannelObject("Wege+CNC", "W Pinole [mm]", travel, properties=late))
    path = folder / f"KBM_{run}.tdms"
    with TdmsWriter(path) as w:
        w.write_segment(objs)
    return path


def test_init_proposes_a_slow_channels_gap_in_the_rows_of_the_grid_it_holds_it_onto(tmp_path, capsys):
    """6 NaN of a 30 s channel are 18 rows of the 10 s grid the record is held onto: init
    proposed ``data.max_gap_samples=6`` (the channel's own samples) and its own read refused it
    ("gap of 18 missing values (grid rows ...) is longer than data.max_gap_samples=6", exit 2)."""
    for run in (1, 2, 3):
        _run(tmp_path / "kbm", run, nan_rows=6 * (run == 2))
    assert main(["init", str(tmp_path / "kbm"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "data.resample_s=10 s" in said and "data.max_gap_samples=18" in said, said
    # (the run named by its channel: "180 s of 'value'", a column the lab never wrote)
    assert "is 18 samples, 180 s of 'Ständer [Deg C]'" in said, said
    conf = (tmp_path / "init" / "conf" / "data" / "kbm.yaml").read_text()
    assert "max_gap_samples: 18" in conf and "resample_s: 10.0" in conf, conf
    # the read with it: the 18 grid rows interpolated (one fewer refused, as the read counts)
    roles = {"error": ["dX", "dZ"], "state": ["W Pinole"]}
    ds, _ = read_dataset(tmp_path / "kbm", {"roles": roles, "max_gap_samples": 18,
                                            "resample_s": 10.0, "test_fraction": 0.34})
    assert not ds.campaigns["KBM_2"]["T_Ständer"].isna().any()
    with pytest.raises(Exception, match="gap of 18 missing values"):
        read_dataset(tmp_path / "kbm", {"roles": roles, "max_gap_samples": 17,
                                        "resample_s": 10.0, "test_fraction": 0.34})


def test_init_names_a_probe_as_the_fastest_error_tag_not_an_axis_travel(tmp_path, capsys):
    """The quill's travel in mm is read as an error until its span says it is a position: the
    grid's period was said to be "the fastest error tag 'W Pinole [mm]'" (a tie, the first in
    the file's order), a few lines before it was proposed a state."""
    for run in (1, 2):
        _run(tmp_path / "kbm", run)
    assert main(["init", str(tmp_path / "kbm"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "the fastest error tag 'dX [um]'" in said, said
    assert "'W Pinole [mm]' spans 250 mm" in said and "proposed as a state" in said, said


def test_a_gap_refused_names_the_channels_own_sample_not_a_row_of_an_unseen_long_file(tmp_path, capsys):
    """The refusal named "data row 161 ... of the long file" (the temporary file the channels
    at their own rates are written to, never the lab's): now the channel's own sample, the one
    that began the gap (row 40 of the 30 s channel: its 41st sample)."""
    from conftest import FAST, refused

    for run in (1, 2, 3):
        _run(tmp_path / "kbm", run, nan_rows=6 * (run == 2))
    path = tmp_path / "kbm" / "KBM_2.tdms"
    said = refused(["run", f"data.path={tmp_path / 'kbm'}", "data.roles.error=[dX,dZ]",
                    "data.roles.state=[W Pinole]", "data.resample_s=10", "data.max_gap_samples=6",
                    "data.test_fraction=0.34", *FAST, f"out={tmp_path / 'out'}"], capsys,
                   f"file {path}, column 'Ständer [Deg C]': gap of 18 missing values",
                   "the tag's sample there is its sample 41)",
                   "(group 'Temperaturen', channel 'Ständer')")
    assert "long file" not in said and "data row" not in said


def test_a_fast_channels_gap_is_proposed_as_its_own_rows_not_the_slowest_channels(tmp_path, capsys):
    """The look read the channels written long as one column: its runs' channel unknown, a gap
    of the 10 s quill travel would have been taken as the 30 s channels' (3x the rows); each
    channel's run is its own now: 7 NaN of the 10 s channel are 7 grid rows, and the slow
    channels' 2 NaN 6."""
    for run in (1, 2, 3):
        _run(tmp_path / "kbm", run, nan_rows=2 * (run == 3), fast_nan=7 * (run == 2))
    assert main(["init", str(tmp_path / "kbm"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "is 7 samples, 70 s of 'W Pinole [mm]': data.max_gap_samples=7" in said, said
    conf = (tmp_path / "init" / "conf" / "data" / "kbm.yaml").read_text()
    assert "max_gap_samples: 7\n" in conf, conf
