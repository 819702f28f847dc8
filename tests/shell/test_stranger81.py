"""A wire EDM's SINUMERIK trace saved as XML, a file a run (stranger81): the ``frameHeader``'s
``dataSignal`` s (the NC / PLC variables traced: the lab's user data ``/NC/_N_NC_GD9_ACX/T_...``,
an axis' ``aaIm[u1,1]``), ``rec`` rows of ``time`` and ``f<id>`` values, a value the NC did not
deliver left out of its row (``benchmarks/bench_stranger81.py`` writes the lab's full record;
these are a few rows of test_stranger68's linear runs)."""

from __future__ import annotations

import datetime as dt
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

GUD = "/NC/_N_NC_GD9_ACX/"
SIGNALS = [(GUD + "T_HALLE", "°C"), (GUD + "T_STAENDER", "°C"), (GUD + "T_OBERARM", "°C"),
           (GUD + "DX_DRAHT", "um"), (GUD + "DY_DRAHT", "um"),
           ("/Channel/MachineAxis/aaIm[u1,3]", "mm")]
START = dt.datetime(2027, 5, 10, 7)


def _trace(folder: Path, run: int, missing: int = 0) -> Path:
    """``KT_<run>.xml``: linear_run's rows every 60 s and Z at 0 / 100 mm; ``missing`` rows
    from row 40 without T_STAENDER's attribute."""
    folder.mkdir(parents=True, exist_ok=True)
    values = np.column_stack([linear_run(8111, run), np.where(np.arange(ROWS) % 40 < 20, 0, 100)])
    start = START + dt.timedelta(days=run - 1)
    head = "".join(f'<dataSignal id="{i}" name="{n}" type="DOUBLE" unit="{u}"/>'
                   for i, (n, u) in enumerate(SIGNALS, start=1))
    recs = "".join(
        f'<rec time="{60.0 * k:.3f}" ' + " ".join(
            f'f{i}="{v:.5f}"' for i, v in enumerate(row, start=1)
            if not (i == 2 and 40 <= k < 40 + missing)) + "/>\n"
        for k, row in enumerate(values))
    path = folder / f"KT_{run}.xml"
    path.write_text('<?xml version="1.0" encoding="UTF-8"?>\n<traceCaptureFile version="1.0">'
                    '<traceCaptureSetup name="Thermik"/><traceData>'
                    f'<dataFrame name="Trace 1" startTime="{start:%Y-%m-%dT%H:%M:%S}.000">'
                    f'<frameHeader>{head}</frameHeader>\n{recs}</dataFrame></traceData>'
                    '</traceCaptureFile>\n', encoding="utf-8")
    return path


def test_a_folder_of_traces_reads_as_campaigns_timed_by_their_start(tmp_path):
    """(Before: "manifest not found ...; its files, .xml (2), are no kind read as a run".)  Each
    trace a campaign, its signals by their variable's last part (the axis' index no unit), its
    rows timed from the frame's startTime (the NC's clock: no zone said)."""
    for run in (1, 2):
        _trace(tmp_path / "edm", run)
    ds, _ = read_dataset(tmp_path / "edm", {"roles": {"error": ["D?_DRAHT"], "state": ["aaIm*"]},
                                            "test_fraction": 0.5})
    assert list(ds.campaigns) == ["KT_1", "KT_2"]
    frame = ds.campaigns["KT_2"]
    names = ["T_HALLE", "T_STAENDER", "T_OBERARM", "E_DX_DRAHT", "E_DY_DRAHT"]
    assert sorted(frame.columns) == sorted(["time", *names, "S_aaIm_u1_3"])
    np.testing.assert_array_equal(frame["time"], np.arange(ROWS) * 60.0)
    np.testing.assert_allclose(frame[names], linear_run(8111, 2), atol=1e-5)
    assert str(ds.manifest["start"].iloc[1]) == "2027-05-11 07:00:00"


def test_init_proposes_a_trace_folders_roles_and_gap(tmp_path, capsys):
    """A value the NC did not deliver (no attribute in 6 rows) is a gap init proposes."""
    for run in (1, 2, 3):
        _trace(tmp_path / "edm", run, missing=6 * (run == 2))
    assert main(["init", str(tmp_path / "edm"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "a SINUMERIK trace" in said and "data.max_gap_samples=6" in said, said
    conf = (tmp_path / "init" / "conf" / "data" / "edm.yaml").read_text()
    assert "error:\n  - DX_DRAHT\n  - DY_DRAHT" in conf and "- aaIm_u1_3" in conf, conf


def test_a_trace_cut_short_is_refused_naming_the_file(tmp_path, capsys):
    path = _trace(tmp_path, 1)
    path.write_text(path.read_text()[:2000], encoding="utf-8")
    refused(["run", f"data.path={path}", "data.roles.error=[D?_DRAHT]", *FAST,
             f"out={tmp_path / 'out'}"], capsys, f"file {path}: not a SINUMERIK trace that is read")


def test_a_plc_variable_named_t_halle_is_proposed_the_ambient(tmp_path, capsys):
    """The lab's PLC names its variables ``T_<place>``: ``T_HALLE`` (the hall's air) read as a
    contract name, a machine temperature (before: ``ambient: []``, the air modelled as a part)."""
    _trace(tmp_path / "edm", 1)
    _trace(tmp_path / "edm", 2)
    assert main(["init", str(tmp_path / "edm"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "ambient: 'T_HALLE [°C]' (its name" in said, said
    conf = (tmp_path / "init" / "conf" / "data" / "edm.yaml").read_text()
    assert "ambient:\n  - T_HALLE\n" in conf, conf
    ds, _ = read_dataset(tmp_path / "edm", {"roles": {"error": ["D?_DRAHT"], "ambient": ["T_HALLE"]},
                                            "test_fraction": 0.5})
    assert "T_amb" in ds.campaigns["KT_1"] and "T_HALLE" not in ds.campaigns["KT_1"]
    # (a temperature whose name says no air stays one)
    assert "T_STAENDER" in ds.campaigns["KT_1"]


def test_an_xml_beside_the_traces_that_is_none_is_no_run_and_refused_alone(tmp_path, capsys):
    """A trace's settings saved beside the traces (root ``traceSetup``): init crashed in pyarrow
    ("Parquet magic bytes not found in footer", a traceback) reading it as a run."""
    for run in (1, 2):
        _trace(tmp_path / "edm", run)
    setup = tmp_path / "edm" / "Thermik_setup.xml"
    setup.write_text('<?xml version="1.0"?><traceSetup><signal name="T"/></traceSetup>')
    assert main(["init", str(tmp_path / "edm"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "campaign KT_1: train" in said and "Thermik_setup" not in said, said
    refused(["init", str(setup), f"out={tmp_path / 'init2'}"], capsys,
            f"file {setup}: an .xml file is read as a SINUMERIK trace (root <traceCaptureFile>); "
            "its root element is <traceSetup>")


def test_a_trace_piped_into_monitor_is_refused_as_a_trace(tmp_path, monkeypatch, capsys):
    """(Before: "1 column(s) not read: '<?xml version=...' is not numeric", its XML read as a
    CSV table of one column.)"""
    import io as _io

    for run in (1, 2):
        path = _trace(tmp_path / "edm", run)
    monkeypatch.setattr("sys.stdin", _io.TextIOWrapper(_io.BytesIO(path.read_bytes())))
    said = refused(["monitor", f"data.path={tmp_path / 'edm'}", "data.roles.error=[D?_DRAHT]",
                    "data.test_fraction=0.5", *FAST, "monitor.input=-", f"out={tmp_path / 'out'}"],
                   capsys, "stdin holds a SINUMERIK trace's XML (its signature), no rows of text: "
                   "give the file as data.path=<file>")
    assert "numeric" not in said


def test_two_traces_of_one_session_are_one_records_channels_at_their_rates(tmp_path, capsys):
    """A session's two traces in one file, the temperatures every 60 s and the wire's errors
    every 20 s from the same start: one record (its channels on a grid, as a TDMS log's two
    tasks), not two runs refused as "runs whose channels differ"."""
    slow, fast = _trace(tmp_path / "a", 1), _trace(tmp_path / "b", 1)
    text_slow, text_fast = slow.read_text(), fast.read_text()
    head, body = text_slow.split("<traceData>")
    frames = body.split("</traceData>")[0]
    fast_frame = text_fast.split("<traceData>")[1].split("</traceData>")[0]
    fast_frame = fast_frame.replace('name="Trace 1"', 'name="Trace 2"').replace(
        'time="', 'time="x').replace("/NC/_N_NC_GD9_ACX/T_", "/NC/_N_NC_GD9_ACX/U_")
    fast_frame = re.sub(r'time="x([\d.]+)"', lambda m: f'time="{float(m[1]) / 3:.3f}"', fast_frame)
    slow_frame = re.sub(r'<dataSignal id="[45]"[^>]*/>', "", frames)
    one = tmp_path / "KT_1.xml"
    one.write_text(head + "<traceData>" + slow_frame + fast_frame + "</traceData></traceCaptureFile>\n",
                   encoding="utf-8")
    assert main(["init", str(one), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "data.resample_s=20" in said, said
    conf = (tmp_path / "init" / "conf" / "data" / "KT_1.yaml").read_text()
    assert "resample_s: 20.0" in conf and "- DX_DRAHT" in conf, conf


@pytest.mark.parametrize("damage, says", [
    (('f2="', 'f2="n/a'), "dataFrame 'Trace 1', signal '/NC/_N_NC_GD9_ACX/T_STAENDER' (f2), rec 1: "
                          "'n/a"),
    (('<rec time="60.000"', '<rec'), "dataFrame 'Trace 1', rec 2: no time"),
    (('startTime="2027', 'startTime="27'), "dataFrame 'Trace 1': startTime '27-05-10T07:00:00.000' "
                                          "is no ISO 8601 time")])
def test_a_damaged_trace_is_refused_naming_frame_signal_and_row(tmp_path, capsys, damage, says):
    path = _trace(tmp_path, 1)
    path.write_text(path.read_text().replace(*damage, 1), encoding="utf-8")
    refused(["run", f"data.path={path}", "data.roles.error=[D?_DRAHT]", *FAST,
             f"out={tmp_path / 'out'}"], capsys, f"file {path}: {says}")


def test_a_start_time_with_its_offset_is_read_as_that_instant(tmp_path):
    """A ``startTime`` written with its offset is that instant (UTC), not the NC's clock."""
    for run in (1, 2):
        path = _trace(tmp_path / "edm", run)
        path.write_text(path.read_text().replace('.000">', '.000+02:00">', 1), encoding="utf-8")
    ds, _ = read_dataset(tmp_path / "edm", {"roles": {"error": ["D?_DRAHT"]}, "test_fraction": 0.5,
                                            "timezone": "America/New_York"})
    assert ds.manifest["start"].iloc[1] == pd.Timestamp("2027-05-11 05:00", tz="UTC")
