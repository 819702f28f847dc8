"""``stream.c`` fed a lab's TDMS log or MATLAB file as it is (session 62,
benchmarks/bench_labfiles62.py, the Swiss-type lathe's export step): "the header ... lacks input
column T_Spindle_motor", its bytes read as a header line.  Now refused saying it is binary and to
convert it to CSV first, as the export's check/<campaign>/rows.csv are."""

from __future__ import annotations

import subprocess

import numpy as np
import pytest
import scipy.io as sio

from test_export import needs_cc
from test_lab_stream52 import compiled
from test_run_column52 import _long, _runs

nptdms = pytest.importorskip("nptdms")


@needs_cc
def test_the_stream_refuses_a_tdms_log_or_a_mat_file_saying_it_is_binary(tmp_path):
    from nptdms import ChannelObject, GroupObject, RootObject, TdmsWriter

    binary = compiled(tmp_path, _long(tmp_path / "alle.csv", _runs()))
    tdms, mat = tmp_path / "day.tdms", tmp_path / "d.mat"
    with TdmsWriter(str(tdms)) as w:
        w.write_segment([RootObject({}), GroupObject("G"),
                         ChannelObject("G", "T0", np.arange(5.0), {"unit_string": "Deg C"})])
    sio.savemat(mat, {"data": {"T0": np.arange(5.0)}})
    for path, kind in ((tdms, "a National Instruments TDMS log"), (mat, "a MATLAB .mat file")):
        run = subprocess.run([str(binary)], input=path.read_bytes(), capture_output=True)
        said = run.stderr.decode(errors="replace").strip()
        assert run.returncode == 2 and said.startswith(f"stream: {kind} is binary, not read here")
