"""The order a lab file's dates with slashes settled travels with the model (data86): a Scope
View export's run across midnight settles the order for the whole folder, as a CSV table's does
(dates85), and the order a catman / Scope / LabVIEW record settled -- by a run or a day past 12,
no ``data.dayfirst`` given -- is the one its served model, a stream of its lab's export
(``monitor.input=-``) and its exported ``TC_SLASHED`` read the lab's rows in."""

from __future__ import annotations

import copy
import datetime as dt
import io
import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from bench_data86 import scope_export  # noqa: E402 (the lab's writer, shared with its bench)

NIGHT = dt.datetime(2027, 2, 1, 23, 40)          # 01/02 23:40 into 02/02 (240 rows of 10 s)
DAYS = (NIGHT, dt.datetime(2027, 2, 3, 7), dt.datetime(2027, 2, 5, 7))
KEYS = ["data.roles.error=[Tracker*]", "data.encoding=cp1252"]
OPTIONS = {"roles": {"error": ["Tracker*"]}, "encoding": "cp1252", "test_fraction": 0.34}


def _rig(root, starts=DAYS):
    """Runs of a spindle warm-up as an en-GB PC's Scope View exports them (dd/mm/yyyy)."""
    root.mkdir()
    rng = np.random.default_rng(9010)
    for run, start in enumerate(starts, start=1):
        scope_export(root / f"Scope_{run}.csv", rng, start, 240, run=run)
    return root


def test_one_runs_night_settles_the_order_of_every_file_of_the_folder(tmp_path, capsys):
    """The mornings of the 3rd and the 5th read day first, as the 1st's run across midnight says
    (before: refused at Scope_2.csv, "day or month first? ... set data.dayfirst")."""
    root = _rig(tmp_path / "rig")
    ds, _ = read_dataset(root, OPTIONS)
    assert list(ds.manifest["start"]) == [pd.Timestamp(s) for s in DAYS]
    assert main(["init", str(root), f"out={tmp_path / 'init'}"]) == 0
    assert ("dates with slashes read day first, as Scope_1.csv's '02/02/2027' (its run: a day "
            "on read so, a month on or back read the other way) says") in capsys.readouterr().out
    assert "dayfirst: true" in (tmp_path / "init" / "conf" / "data" / "rig.yaml").read_text()


def test_files_whose_runs_settle_other_orders_are_refused_naming_both(tmp_path):
    root = _rig(tmp_path / "rig", (NIGHT, dt.datetime(2027, 2, 3, 23, 40)))
    second = root / "Scope_2.csv"              # its dates written month first: 02/03, 02/04
    text = second.read_bytes().decode("cp1252")
    second.write_bytes(text.replace("03/02/2027", "02/03/2027").replace("04/02/2027", "02/04/2027")
                       .encode("cp1252"))
    with pytest.raises(Exception, match=r"'02/02/2027' \(its run.*\) is day first, but file "
                                        r".*Scope_2.csv's '02/04/2027' \(its run.*\) month first"):
        read_dataset(root, OPTIONS)


def _night_record(tmp_path):
    """The night run's file alone, a record (its reader settles its order; no key)."""
    return _rig(tmp_path / "rig") / "Scope_1.csv"


def test_the_served_model_reads_the_labs_rows_in_the_order_its_night_record_settled(tmp_path):
    """A block of the lab's rows of the 5th (either order) is served as the same rows timed in
    seconds.  Before: ``slashed_`` None, the block refused ("day or month first? set data.time
    ... or data.dayfirst")."""
    from test_dates85 import _served
    from thermocomp.apps.deploy.pyfunc import CompensatorModel

    path = _night_record(tmp_path)
    deployed = _served(tmp_path, path, *KEYS)
    assert deployed.slashed_ == "%d/%m/%Y %H:%M:%S"
    lab = read_dataset(path.parent, OPTIONS)[0].campaigns["Scope_3"]
    inputs = [c for c in deployed.columns_ if c != "time"]
    stamps = pd.Timestamp(DAYS[2]) + pd.to_timedelta(lab["time"], unit="s")
    block = lab[inputs].assign(time=stamps.dt.strftime("%d/%m/%Y %H:%M:%S").to_numpy())
    served, timed = (CompensatorModel(copy.deepcopy(deployed)).predict(None, b, {"reset": True})
                     for b in (block, lab[inputs].assign(time=lab["time"].to_numpy())))
    np.testing.assert_array_equal(served["C_Tracker_dX"], timed["C_Tracker_dX"])


def test_a_scope_export_piped_in_reads_in_the_order_its_record_settled(tmp_path, monkeypatch):
    """``monitor.input=-``: the 5th's export (no day past 12, no night) piped in is read day
    first, as the night record was.  Before: refused, "day or month first? ... set
    data.dayfirst"."""
    path = _night_record(tmp_path)
    common = ["monitor", f"data.path={path}", "data.test_fraction=0.5", *KEYS, *FAST]
    monkeypatch.setattr("sys.stdin", io.StringIO(
        (path.parent / "Scope_3.csv").read_bytes().decode("cp1252")))
    assert main([*common, "monitor.input=-", f"out={tmp_path / 'pipe'}"]) == 0
    said = json.loads((tmp_path / "pipe" / "monitor.json").read_text())["targets"]
    assert said["E_Tracker_dX"]["n_samples"] == 240         # (the export's every row)


def test_a_piped_export_saying_the_other_order_is_refused_naming_its_date(tmp_path, monkeypatch,
                                                                          capsys):
    """An en-US PC's export of the 13th (``05/13/2027``) piped into the model of the en-GB
    night record: refused naming the date and its line (no reading in an order it rules out)."""
    from conftest import refused

    path = _night_record(tmp_path)
    us = tmp_path / "us.csv"
    scope_export(us, np.random.default_rng(9010), dt.datetime(2027, 5, 13, 7), 40)
    text = us.read_bytes().decode("cp1252").replace("13/05/2027", "05/13/2027")
    monkeypatch.setattr("sys.stdin", io.StringIO(text))
    refused(["monitor", f"data.path={path}", "data.test_fraction=0.5", *KEYS, *FAST,
             "monitor.input=-", f"out={tmp_path / 'pipe'}"], capsys,
            "file <stdin>, line 2: date '05/13/2027' says its dates with slashes are month "
            "first, but the record the model was trained on says day first")


def test_the_exported_stream_reads_the_labs_rows_in_the_order_its_record_settled(tmp_path):
    """``TC_SLASHED`` 1 (before: 0, the compiled stream refused the lab's dates as no time)."""
    path = _night_record(tmp_path)
    common = [f"data.path={path}", "data.test_fraction=0.5", *KEYS, *FAST]
    assert main(["run", *common, "model=mlr", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, f"export.model={tmp_path / 'run' / 'model.pkl'}",
                 "export.format=c", "export.check=false", f"out={tmp_path / 'c'}"]) == 0
    said = [ln for f in (tmp_path / "c").glob("*.[ch]") for ln in f.read_text().splitlines()
            if ln.startswith("#define TC_SLASHED")]
    assert said and said[0].split()[2] == "1"


def test_a_catman_records_day_past_12_travels_with_its_served_model(tmp_path):
    """A catman export of the 13th (its T0 '13/05/2027'), a record of its own, no key: its
    served model reads the lab's rows day first (before: ``slashed_`` None)."""
    from test_dates84 import _gb_folder
    from test_dates85 import _served

    path = _gb_folder(tmp_path / "rig", days=(12, 13)) / "SP_T1.TXT"
    deployed = _served(tmp_path, path, "data.roles.error=[MCS*]", "data.encoding=cp1252")
    assert deployed.slashed_ == "%d/%m/%Y %H:%M:%S"


@pytest.mark.parametrize("starts, said", [
    ((dt.datetime(2027, 5, 3, 7), dt.datetime(2027, 5, 13, 7)), ("Scope_2.csv", "13/05/2027", False)),
    ((dt.datetime(2027, 5, 3, 7), dt.datetime(2027, 5, 4, 23)), ("Scope_2.csv", "05/05/2027", True)),
])
def test_the_folder_check_reads_only_what_it_needs(tmp_path, monkeypatch, starts, said):
    """The order a folder's files say (a 13th's day; a run across midnight 2 h into the file),
    found reading a morning's head and tail and the night's text up to its midnight, not every
    file whole (before: every byte of every file read and looked at)."""
    import builtins

    from thermocomp.core.io import dayfirst
    from thermocomp.core.io.plain import lab_dayfirst

    root = tmp_path / "rig"
    root.mkdir()
    rng = np.random.default_rng(9010)
    for run, start in enumerate(starts, start=1):
        scope_export(root / f"Scope_{run}.csv", rng, start, 20_000, period_s=1.0, run=run)
    read = []

    class Counted:                     # a file whose reads are counted (bytes or characters)
        def __init__(self, f):
            self.f = f

        def read(self, *size):
            out = self.f.read(*size)
            read.append(len(out))
            return out

        def __getattr__(self, name):
            return getattr(self.f, name)

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            self.f.close()

    monkeypatch.setattr(dayfirst, "open", lambda *a, **kw: Counted(builtins.open(*a, **kw)),
                        raising=False)
    found = lab_dayfirst(sorted(root.iterdir()), "cp1252")
    assert (found.day_first, found.file.name, found.date, found.run) == (True, *said)
    assert sum(read) < 0.3 * sum(f.stat().st_size for f in root.iterdir())
