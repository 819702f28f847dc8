"""Real exports, not written from memory (realexport73): a Campbell Scientific logger's AmeriFlux
table (``yyyymmddHHMM`` timestamps) and LabVIEW 2026's own ``.lvm`` files, excerpts vendored in
``tests/data/realexport73/`` (MIT; its README says where each comes from)."""

from __future__ import annotations

import datetime as dt
import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from conftest import LIGHT, UNTRACKED, thermocomp
from thermocomp.core.io.lvm import lvm_records
from thermocomp.core.io.stdin import stream_stamps

DATA = Path(__file__).parents[1] / "data" / "realexport73"
FLUX = DATA / "21031_Statistics_AmeriFlux37_head.dat"
# the soil record as a stranger names it: the deepest soil temperature as the target, two
# shallower ones as the inputs, every other column (radiation, moisture, wind ...) left out
ROLES = ("data.roles.error=[T_1_9_1]",
         "data.roles.ignore=[ALB,NETRAD,SW_*,LW*,PPFD_IN,VWC*,Ka*,BulkEC*,WS,WD,T_CANOPY,"
         "T_SI111_body,T_1_3_1,T_1_4_1,T_1_5_1,T_1_6_1,T_1_7_1,T__1_8_1]")


def test_an_ameriflux_tables_timestamp_start_is_its_time_and_its_end_left_out(tmp_path):
    """``TIMESTAMP_START`` (``202503272330``) is the time, every 30 min; before, no column was
    the time (``set data.sample_period_s``), and named, its digits were seconds (70 s, then 30)."""
    said = thermocomp("init", str(FLUX), *ROLES, f"out={tmp_path}").stdout
    assert "time: 'TIMESTAMP_START', timestamps from 2025-03-27T23:30:00" in said, said
    assert "sample period: 1800 s, 16 rows" in said, said
    assert "TIMESTAMP_END    DAQ's own    - (left out: no measurement)" in said, said


def test_a_stream_reads_the_tables_digits_as_its_timestamps():
    """``monitor monitor.input=-``: the piped table's ``TIMESTAMP_START`` column, read by pandas
    as integers, is timestamps (before: seconds, every 70 or 30 s)."""
    ns, valid = stream_stamps(pd.read_csv(FLUX)["TIMESTAMP_START"])
    assert valid.all()
    assert pd.Timestamp(ns[0]) == pd.Timestamp("2025-03-27 23:30")
    assert np.diff(ns).tolist() == [1800 * 10**9] * 15


@pytest.mark.skipif(shutil.which("gcc") is None, reason="no C compiler")
def test_the_exported_c_reads_the_tables_timestamps_as_the_model_did(tmp_path):
    """``stream.c`` fed the raw table gives the check pack's corrections (a lag bank: its lags in
    seconds); before, it read ``202503280000`` as seconds, 70 s after ``202503272330``."""
    data = (f"data.path={FLUX}", *ROLES, "data.test_fraction=0.25")
    thermocomp("run", *data, "model=lagbank", *UNTRACKED, *LIGHT, f"out={tmp_path / 'run'}")
    code = tmp_path / "code"
    thermocomp("export", f"export.model={tmp_path / 'run' / 'model.pkl'}", *data,
               "export.format=c", *UNTRACKED, f"out={code}")
    compiled(code)
    with FLUX.open() as rows:
        streamed = subprocess.run([str(code / "stream")], stdin=rows, capture_output=True,
                                  text=True, check=True).stdout
    got = pd.read_csv(__import__("io").StringIO(streamed))["C_T_1_9_1"].to_numpy()
    expected = pd.concat(pd.read_csv(code / c["folder"] / "expected.csv")
                         for c in json.loads((code / "check" / "check.json").read_text())["campaigns"]
                         # (not the copies the C's monitor is checked on, nor deploy89's cold start)
                         if "planted" not in c and "cold_start" not in c)
    assert len(got) == 16
    assert np.abs(got - expected.iloc[:, -1].to_numpy()).max() < 1e-9


def test_labviews_default_express_vi_file_is_timed_by_its_delta_x():
    """``X_Columns No``: LabVIEW heads an ``X_Value`` column and leaves it empty; the time is the
    segment's ``Date``/``Time`` plus ``Delta_X`` steps (before: ``NaT``, refused)."""
    [run] = lvm_records(DATA / "express_default.lvm")
    start = dt.datetime(2026, 10, 15, 2, 26, 2, 431218)
    assert [c.header for c in run.channels] == ["Untitled", "Untitled 1"]
    for channel, values in zip(run.channels, ([1.0, 2.5, -3.25], [4.0, 5.0, 6.0])):
        assert channel.values.tolist() == values
        assert channel.time.astype("datetime64[us]").tolist() == [
            start + dt.timedelta(seconds=s) for s in range(3)]


def test_a_second_labview_session_appending_to_the_file_is_a_run(capsys, tmp_path):
    """A VI run again writes the file header again before its segment: a run of its own (before:
    "a segment begins with its 'Channels' line"); here with fewer channels, refused saying so."""
    first, second = lvm_records(DATA / "appended_runs.lvm")
    assert (first.label, second.label) == ("appended_runs_1", "appended_runs_2")
    assert [c.values.tolist() for c in first.channels] == [[1.0, 2.5, -3.25], [4.0, 5.0, 6.0]]
    assert [c.values.tolist() for c in second.channels] == [[7.0, 8.0]]
    assert second.channels[0].time[0].astype("datetime64[us]").tolist() == dt.datetime(
        2026, 10, 15, 2, 26, 7, 299774)
    proc = thermocomp("init", str(DATA / "appended_runs.lvm"), f"out={tmp_path}", check=False)
    assert proc.returncode == 2
    assert "run 'appended_runs_2' holds other channels than run 'appended_runs_1'" in proc.stderr


def test_a_record_too_short_for_a_validation_fold_is_refused_naming_the_fold(tmp_path):
    """The table's first 8 rows, cut 6 / 2: forward chaining's first fold fits a lag bank on one
    row. Refused with exit status 2 naming the fold's rows and the way out (before: the model's
    ``ValueError`` escaped as a traceback, exit status 1)."""
    short = tmp_path / "short.dat"
    short.write_text("".join(FLUX.read_text().splitlines(keepends=True)[:9]))
    proc = thermocomp("run", f"data.path={short}", *ROLES, "data.test_fraction=0.25",
                      "model=lagbank", *UNTRACKED, *LIGHT, f"out={tmp_path / 'run'}", check=False)
    assert proc.returncode == 2, proc.stderr
    assert ("validation: a fold fits on the first 1 row of short_train, too few: LagBank needs at "
            "least 3 samples") in proc.stderr, proc.stderr
    assert "eval.validation=false" in proc.stderr
    assert not (tmp_path / "run" / "metrics.json").exists()
