"""A surface grinder's logger writing one HDF5 file (stranger77): a group a day, in each a
``time`` dataset of epoch seconds (CF's ``units``: ``seconds since 1970-01-01 00:00:00``) and a
dataset per channel with its ``units`` attribute, a text dataset of notes; from the third day
on a sensor replaced, its channel under a new name (``benchmarks/bench_stranger77.py`` writes
the lab's full record; these are a few rows of test_stranger68's linear runs)."""

from __future__ import annotations

import datetime as dt
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

h5py = pytest.importorskip("h5py")

NAMES = ["hall air", "column", "spindle", "probe dX", "probe dZ"]
UNITS = ["degC", "degC", "degC", "um", "um"]
START = dt.datetime(2027, 3, 1, 5, tzinfo=dt.timezone.utc)
NEW_FROM = 3                        # the spindle's sensor replaced from the third day on


def _logger(path: Path, days: int = 4, track_order: bool = False) -> Path:
    """``days`` groups ``yyyymmdd``, each a run of ``linear_run`` at 60 s (``track_order``: the
    file tracks the order its datasets were created in)."""
    with h5py.File(path, "w", track_order=track_order) as f:
        for day in range(1, days + 1):
            start = START + dt.timedelta(days=day - 1)
            group = f.create_group(f"{start:%Y%m%d}", track_order=track_order)
            time = group.create_dataset("time", data=start.timestamp() + 60.0 * np.arange(ROWS))
            time.attrs["units"] = "seconds since 1970-01-01 00:00:00"
            values = linear_run(7746, day)
            for j, (name, unit) in enumerate(zip(NAMES, UNITS)):
                if name == "spindle" and day >= NEW_FROM:
                    name = "spindle (new)"
                data = group.create_dataset(name, data=values[:, j].astype(np.float32))
                data.attrs["units"] = unit
            group.create_dataset("operator", data=np.array([b"shift A", b"shift B"]))
    return path


def test_a_group_a_day_reads_as_runs_timed_in_utc_each_channel_in_its_units(tmp_path):
    """(Before: "a record's file is .csv, ... .lvm, not .h5".)"""
    path = _logger(tmp_path / "SG630.h5", days=2)
    ds, _ = read_dataset(path, {"roles": {"error": ["probe*"], "campaign": "run"},
                                "test_fraction": 0.5})
    assert list(ds.campaigns) == ["run_20270301", "run_20270302"]
    assert list(ds.manifest["split"]) == ["train", "test"]
    assert ds.manifest["start"].iloc[1] == pd.Timestamp("2027-03-02 05:00", tz="UTC")
    frame = ds.campaigns["run_20270302"]
    # (HDF5 lists a group's datasets by name where the file does not track their order)
    names = ["T_hall_air", "T_column", "T_spindle", "E_probe_dX", "E_probe_dZ"]
    assert sorted(frame.columns) == sorted(["time", *names])
    np.testing.assert_array_equal(frame["time"], np.arange(ROWS) * 60.0)
    np.testing.assert_allclose(frame[names], linear_run(7746, 2), rtol=1e-6, atol=1e-5)


@pytest.mark.parametrize("tracked", [True, False])
def test_a_groups_channels_are_in_their_creation_order_where_tracked_else_said(tmp_path, caplog,
                                                                             tracked):
    """(lab78) A logger's column order is its datasets' creation order where the file tracks
    it; where it does not, HDF5 lists them by name, and that is said (it was not)."""
    path = _logger(tmp_path / "SG630.h5", days=2, track_order=tracked)
    with caplog.at_level("INFO", logger="thermocomp"):
        ds, _ = read_dataset(path, {"roles": {"error": ["probe*"], "campaign": "run"},
                                    "test_fraction": 0.5})
    said = [r.getMessage() for r in caplog.records if "track_order" in r.getMessage()]
    columns = list(ds.campaigns["run_20270302"].columns)
    created = ["time", "T_hall_air", "T_column", "T_spindle", "E_probe_dX", "E_probe_dZ"]
    if tracked:
        assert columns == created and said == []
    else:
        assert columns != created
        assert ("SG630.h5: group '/20270302' does not track the order its datasets were created "
                "in (h5py's track_order): its channels are read in the order HDF5 lists them, "
                "by name") in said


def test_init_maps_the_replaced_sensor_and_its_config_runs(tmp_path, capsys):
    """The spindle's channel renamed from day 3: ``run 'x' holds other channels than run 'y'``
    before; now the runs are read, ``init`` proposes the entry reading the new name as the old
    and no ``data.max_edge_samples`` for the new channel's empty days (11515 on the lab's
    file: 8 days of rows dropped wherever an edge is missing); the entry read, one column."""
    path = _logger(tmp_path / "SG630.h5")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert ("'spindle (new) [degC]' from run_20270303 on, in the campaigns without 'T_spindle' "
            "(in every other): one sensor renamed") in said
    assert "max_edge_samples" not in said
    conf = (tmp_path / "init" / "conf" / "data" / "SG630.yaml").read_text()
    assert "spindle (new) [degC]: T_spindle" in conf and "max_edge_samples" not in conf
    assert main(["run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=SG630",
                 "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert metrics["targets"]["E_probe_dZ"]["test"]["rmse"] < 0.2      # (the map is linear)
    ds, _ = read_dataset(path, {"roles": {"error": ["probe*"], "campaign": "run"},
                                "columns": {"spindle (new) [degC]": "T_spindle"}})
    for day in (2, 4):
        frame = ds.campaigns[f"run_2027030{day}"]
        np.testing.assert_allclose(frame["T_spindle"], linear_run(7746, day)[:, 2], rtol=1e-6)


def test_a_dataset_of_two_dimensions_is_refused_naming_file_and_dataset(tmp_path, capsys):
    path = _logger(tmp_path / "SG630.h5", days=2)
    with h5py.File(path, "a") as f:
        f["20270302"].create_dataset("strain", data=np.zeros((ROWS, 3)))
    refused(["run", f"data.path={path}", "data.roles.error=[probe*]", "data.roles.campaign=run",
             *FAST, f"out={tmp_path / 'out'}"], capsys,
            f"file {path}: dataset '/20270302/strain' has shape ({ROWS}, 3): a channel is "
            "one-dimensional")
    assert not (tmp_path / "out").exists()


def test_the_file_piped_into_monitor_is_refused_as_a_binary_file(tmp_path, monkeypatch, capsys):
    """(Before: "byte 0x89 is not utf-8 text (set data.encoding to the stream's character
    set, e.g. cp1252)", a wrong way out: no encoding reads an HDF5 file.)"""
    import io as _io
    path = _logger(tmp_path / "SG630.h5", days=2)
    rows = pd.concat([pd.DataFrame(linear_run(7746, day), columns=NAMES).assign(
        run=f"day{day}", time=60.0 * np.arange(ROWS)) for day in (1, 2)])
    rows.to_csv(table := tmp_path / "SG630.csv", index=False)      # (the record as CSV rows)
    monkeypatch.setattr("sys.stdin", _io.TextIOWrapper(_io.BytesIO(path.read_bytes())))
    said = refused(["monitor", f"data.path={table}", "data.roles.error=[probe*]",
                    "data.roles.campaign=run", "data.test_fraction=0.5", *FAST,
                    "monitor.input=-", f"out={tmp_path / 'out'}"], capsys,
                   "stdin holds an HDF5 file (its signature), no rows of text: give the file as "
                   "data.path=<file>")
    assert "cp1252" not in said


def _with_wheelhead(path: Path, wheelhead: bool = True) -> Path:
    """Two days of :func:`_logger`'s file, the second idle: ``wheelhead Z`` (mm) travelling 360
    mm on the first, held on the second; the probe dX dead on the second (a constant)."""
    _logger(path, days=2)
    with h5py.File(path, "a") as f:
        for day, group in enumerate(sorted(f), start=1):
            if wheelhead:
                z = np.linspace(0.0, 360.0, ROWS) if day == 1 else np.full(ROWS, 120.0)
                f[group].create_dataset("wheelhead Z", data=z.astype(np.float32)).attrs[
                    "units"] = "mm"
            if day == 2:
                f[group]["probe dX"][...] = np.float32(1.5)
    return path


def test_init_says_no_constant_error_of_a_travel_it_proposes_as_a_state(tmp_path, capsys):
    """tidy77: init's first look reads a length by its unit as an error, for its span: the
    wheelhead Z, held on an idle day, was said 'E_wheelhead_Z constant over the whole campaign
    (a dead channel?)' before init proposed it as a state.  Said only of the roles proposed
    (the dead probe, in either file), and by the reader as it was."""
    path = _with_wheelhead(tmp_path / "SG630.h5")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    out, err = capsys.readouterr()
    assert "'wheelhead Z [mm]' spans 360 mm" in out and "proposed as a state" in out
    dead = "column 'E_probe_dX': constant over the whole campaign (a dead channel?)"
    assert "E_wheelhead_Z" not in err and err.count(dead) == 1, err
    plain = _with_wheelhead(tmp_path / "SG631.h5", wheelhead=False)      # (one look)
    assert main(["init", str(plain), f"out={tmp_path / 'init2'}"]) == 0
    assert capsys.readouterr().err.count(dead) == 1
    read_dataset(path, {"roles": {"error": ["probe*", "wheelhead*"], "campaign": "run"},
                        "max_abs_error": None})
    assert "column 'E_wheelhead_Z': constant over the whole campaign" in capsys.readouterr().err
