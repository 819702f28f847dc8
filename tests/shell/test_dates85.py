"""A CSV table's dates with slashes decided as a lab file's are (dates85): where no day or month
is past 12, a run across midnight (a date one order reads as a day on, the other as a month on)
settles the order, as it did for a catman T0 or a Scope View time since dates84; and the order a
model was trained in (``data.dayfirst``, or the one its record settled) is the order its served
blocks and its exported stream read the lab's rows in."""

from __future__ import annotations

import copy
import datetime as dt

import numpy as np
import pandas as pd
import pytest

from conftest import refused
from test_dates84 import piped_as_its_file
from test_export import needs_cc
from test_stranger65 import _compiled_stream_equals_its_pack
from thermocomp.core.io import read_dataset


def _run(path, start: dt.datetime, day_first: bool = True, rows: int = 60, run: int = 1):
    """A run of a CSV table every minute from ``start``, its time ``dd/mm/yyyy HH:MM:SS`` (an
    en-GB PC's) or ``mm/dd/yyyy`` (an en-US one's)."""
    t = pd.date_range(start, periods=rows, freq="60s")
    heat = (t - t[0]).total_seconds().to_numpy() / (rows * 60.0)
    pd.DataFrame({"time": t.strftime("%d/%m/%Y %H:%M:%S" if day_first else "%m/%d/%Y %H:%M:%S"),
                  "T_a": 20 + 3 * heat, "T_b": 20 + 2 * heat ** 2,
                  "T_c": 20 + np.sin(3 * heat + run), "E_x": 3.0 * heat + np.sin(3 * heat + run)
                  }).to_csv(path, index=False)
    return path


def _folder(root, day_first: bool = True, night=(True, False)):
    """Two runs, the first from the 3rd of May 23:30 into the 4th where ``night``, the second
    from the 5th at 07:00; no day or month past 12."""
    root.mkdir()
    for run, (day, across) in enumerate(zip((3, 5), night), start=1):
        start = dt.datetime(2027, 5, day, 23, 30) if across else dt.datetime(2027, 5, day, 7)
        _run(root / f"run_{run}.csv", start, day_first, run=run)
    return root


@pytest.mark.parametrize("day_first", [True, False])
def test_a_run_across_midnight_settles_the_order_of_the_whole_folder(tmp_path, day_first):
    """03/05 23:59 then 04/05 00:00 (a minute day first, a month month first; US: 05/03 then
    05/04).  Before: refused, "day or month first? set data.time ...", at the first row."""
    ds, _ = read_dataset(_folder(tmp_path / "csv", day_first), {"test_fraction": 0.5})
    assert list(ds.manifest["start"]) == [pd.Timestamp(2027, 5, 3, 23, 30),
                                          pd.Timestamp(2027, 5, 5, 7)]
    assert ds.campaigns["run_1"]["time"].max() == 59 * 60.0


def test_a_one_file_record_across_midnight_is_read_in_its_order(tmp_path):
    path = _run(tmp_path / "night.csv", dt.datetime(2027, 5, 3, 23, 30))
    ds, _ = read_dataset(path, {"test_fraction": 0.3})
    assert ds.manifest["start"].iloc[0] == pd.Timestamp(2027, 5, 3, 23, 30)


def test_init_writes_the_order_a_night_run_settled(tmp_path, capsys):
    from thermocomp.shell.cli import main

    root = _folder(tmp_path / "csv")
    assert main(["init", str(root), f"out={tmp_path / 'init'}"]) == 0
    out = capsys.readouterr().out
    assert ("the order its rows say (its run: its data row 31, '04/05/2027 00:00:00': a day on "
            "read so, a month on or back read the other way)") in out
    assert "'%d/%m/%Y %H:%M:%S'" in (tmp_path / "init" / "conf" / "data" / "csv.yaml").read_text()


def test_dates_either_order_reads_as_a_run_are_refused_naming_file_column_row_and_key(tmp_path,
                                                                                      capsys):
    root = _folder(tmp_path / "csv", night=(False, False))
    said = refused(["init", str(root), f"out={tmp_path / 'init'}"], capsys,
                   "column 'time', line 2 (data row 1)",
                   "'03/05/2027 07:00:00' is day or month first",
                   "data.dayfirst=true", "data.dayfirst=false")
    assert str(root / "run_1.csv") in said


def test_files_whose_runs_settle_other_orders_are_refused_naming_both(tmp_path, capsys):
    root = tmp_path / "csv"
    root.mkdir()
    _run(root / "run_1.csv", dt.datetime(2027, 5, 3, 23, 30))
    _run(root / "run_2.csv", dt.datetime(2027, 5, 5, 23, 30), day_first=False, run=2)
    said = refused(["init", str(root), f"out={tmp_path / 'init'}"], capsys,
                   "day first", "month first", "'05/06/2027 00:00:00'", "data.dayfirst")
    assert str(root / "run_1.csv") in said and str(root / "run_2.csv") in said


def _served(tmp_path, root, *keys):
    """The served model trained on ``root`` (a lag bank reads the time)."""
    from test_export import _compose
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    cfg = _compose(f"data.path={root}", "data.test_fraction=0.5", *keys, "model=lagbank",
                   "track=false", "monitor.adaptive=false")
    ds, train, _, _ = read_streamed(cfg, test=False)
    return deployable_model(cfg, ds, train, None, "serve.model")[0]


@pytest.mark.parametrize("night, keys", [((False, False), ["data.dayfirst=true"]),
                                         ((True, False), [])])
def test_the_served_model_reads_the_labs_rows_in_the_order_it_was_trained_in(tmp_path, night,
                                                                             keys):
    """The key set (or the order a night run settled) travels with the model: a block of the
    lab's rows 05/05 07:00 .. (either order) is served as the same rows timed in seconds.
    Before: the model carried no order (``slashed_`` None) and every block was refused, "day or
    month first? set data.time"."""
    from thermocomp.apps.deploy.pyfunc import CompensatorModel

    deployed = _served(tmp_path, _folder(tmp_path / "csv", night=night), *keys)
    block = pd.read_csv(_run(tmp_path / "next.csv", dt.datetime(2027, 5, 7, 23, 30), run=3))
    seconds = block.assign(time=np.arange(len(block)) * 60.0)
    served, timed = (CompensatorModel(copy.deepcopy(deployed)).predict(None, b, {"reset": True})
                     for b in (block, seconds))
    assert "C_x" in served.columns
    np.testing.assert_array_equal(served["C_x"], timed["C_x"])
    assert deployed.slashed_.startswith("%d/%m/")


@needs_cc
def test_the_exported_stream_reads_the_labs_rows_in_data_dayfirsts_order(tmp_path):
    """``TC_SLASHED`` from the key (before: 0, the compiled stream refused the file's every
    time as no time)."""
    path = _run(tmp_path / "run.csv", dt.datetime(2027, 5, 3, 7), rows=200)
    _compiled_stream_equals_its_pack(tmp_path, path, [f"data.path={path}", "data.dayfirst=true",
                                                      "data.test_fraction=0.3",
                                                      "data.reference=none"])


def test_a_stream_of_the_labs_rows_reads_in_the_order_a_night_run_settled(tmp_path, monkeypatch):
    """``monitor.input=-``: the test run piped in, 05/05 23:30 into 06/05 (a month on read month
    first), scores as its file does, read in the order its record's night runs settled (no key;
    before: the record refused)."""
    said = piped_as_its_file(tmp_path, monkeypatch, _folder(tmp_path / "csv", night=(True, True)),
                             "model=lagbank")
    assert said[1]["n_samples"] == 60
    assert said[1]["rmse_fixed"] == pytest.approx(said[0]["rmse_fixed"], rel=1e-12)
