"""A lab's NI TDMS log and MATLAB .mat file through `init` and the reader (session 62,
benchmarks/bench_labfiles62.py, the Swiss-type lathe).

Before: both refused, "a record's file is .csv, .txt, ... not .tdms".  Read now through the CSV
their channels are written to (:mod:`thermocomp.core.io.labfile`): a TDMS group's channels timed
by NI's waveform properties, their units from ``unit_string``; groups as runs or as one record's
channel groups; channels at two rates held onto one grid (the historian's path); a .mat file's
struct of vectors, matrix and names, struct array (runs), v5 through SciPy and -v7.3 through h5py
(column-major, transposed back); a MATLAB table refused saying how to save it.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest
import scipy.io as sio
import yaml

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.detect import proposed_roles
from thermocomp.core.io.historian_layout import long_layout
from thermocomp.core.io.options import ReadOptions
from thermocomp.shell.cli import main

nptdms = pytest.importorskip("nptdms")
h5py = pytest.importorskip("h5py")

T0 = np.datetime64("2026-11-02T05:30:00")
N = 60


def _temps(seed=0, n=N):
    rng = np.random.default_rng(seed)
    t = 20 + np.cumsum(np.abs(rng.normal(0, 0.03, n)))
    air = 19 + 0.01 * np.sin(np.arange(n) / 7)
    return t, air, 3 * (t - t[0]) + rng.normal(0, 0.05, n)


def _wf(start=T0, step=10.0, **more):
    return {"wf_start_time": start, "wf_increment": step, "wf_start_offset": 0.0, **more}


def write_tdms(path, groups):
    """``groups``: {group: [(channel, values, properties)]}."""
    from nptdms import ChannelObject, GroupObject, RootObject, TdmsWriter

    path.parent.mkdir(parents=True, exist_ok=True)
    objects = [RootObject({"name": "test"})]
    for group, channels in groups.items():
        objects.append(GroupObject(group))
        objects += [ChannelObject(group, name, np.asarray(v), props) for name, v, props in channels]
    with TdmsWriter(str(path)) as w:
        w.write_segment(objects)
    return path


def daq_log(path, t=T0, seed=0):
    """LabVIEW's DAQmx logging: a temperature task's group and a displacement task's."""
    temp, air, dx = _temps(seed)
    return write_tdms(path, {
        "Temperatures": [("Spindle nose", temp, {"unit_string": "Deg C", **_wf(t)}),
                         ("Room [degC]", air, _wf(t))],
        "Displacement": [("Probe X", dx / 1000, {"unit_string": "mm", **_wf(t)})]})


def test_a_daqs_tdms_log_is_read_by_ni_timing_and_units(tmp_path):
    path = daq_log(tmp_path / "day.tdms")
    ds, _ = read_dataset(path, {"roles": {"ambient": ["Room"]}})
    (cid,) = ds.ids()
    df = ds.campaigns[cid]
    temp, air, dx = _temps(0)
    assert list(df.columns) == ["time", "T_Spindle_nose", "T_amb", "E_Probe_X"]
    assert np.allclose(np.diff(df["time"]), 10.0)                   # wf_increment
    assert df["E_Probe_X"].to_numpy() == pytest.approx(dx, abs=1e-9)   # mm -> µm
    assert df["T_Spindle_nose"].to_numpy() == pytest.approx(temp)


def test_init_reads_a_folder_of_tdms_days_a_campaign_each(tmp_path, capsys):
    for day in range(3):
        daq_log(tmp_path / "lab" / f"Test_{day}.tdms", T0 + np.timedelta64(day, "D"), seed=day)
    out = tmp_path / "init"
    assert main(["init", str(tmp_path / "lab"), "data.test_fraction=0.34", f"out={out}"]) == 0
    said = capsys.readouterr().out
    assert "a TDMS log" in said and "timestamps from 2026-11-02T05:30:00+00:00" in said
    config = yaml.safe_load((out / "conf" / "data" / "lab.yaml").read_text())
    assert config["roles"]["ambient"] == ["Room"] and config["roles"]["error"] == ["Probe X"]
    assert "delimiter" not in config and "decimal" not in config      # (no text: no separators)


def test_groups_of_the_same_channels_one_after_another_are_runs(tmp_path, capsys):
    groups = {}
    for k in range(3):
        temp, air, dx = _temps(k)
        wf = _wf(T0 + np.timedelta64(k, "D"))
        groups[f"Run {k + 1}"] = [("Spindle nose", temp, {"unit_string": "degC", **wf}),
                                  ("Room", air, {"unit_string": "degC", **wf}),
                                  ("dX", dx, {"unit_string": "um", **wf})]
    path = write_tdms(tmp_path / "runs.tdms", groups)
    out = tmp_path / "init"
    assert main(["init", str(path), "data.test_fraction=0.34", f"out={out}"]) == 0
    config = yaml.safe_load((out / "conf" / "data" / "runs.yaml").read_text())
    assert config["roles"]["campaign"] == "run"
    ds, _ = read_dataset(path, {k: v for k, v in config.items() if k != "path"})
    assert ds.ids() == ["Run_1", "Run_2", "Run_3"]


def test_a_folders_file_of_several_runs_is_refused_naming_them(tmp_path, capsys):
    # before: each file's runs read as one campaign, the days between them a pause nothing said
    for name in ("a", "b"):
        groups = {}
        for k in range(2):
            temp, air, dx = _temps(k)
            wf = _wf(T0 + np.timedelta64(k, "D"))
            groups[f"Run {k + 1}"] = [("Spindle nose", temp, {"unit_string": "degC", **wf}),
                                      ("dX", dx, {"unit_string": "um", **wf})]
        write_tdms(tmp_path / "lab" / f"{name}.tdms", groups)
    out = tmp_path / "init"
    assert main(["init", str(tmp_path / "lab"), "data.test_fraction=0.5", f"out={out}"]) == 2
    said = capsys.readouterr().err
    assert "a.tdms: 2 runs in one file ('Run 1', 'Run 2'): a folder's file is one campaign" in said
    assert not (out / "conf").exists()


def test_channels_at_two_rates_are_held_onto_the_error_channels_grid(tmp_path, capsys):
    temp, air, _ = _temps(0)
    fast = 3 * (np.interp(np.arange(5 * N) / 5, np.arange(N), temp) - temp[0])
    path = write_tdms(tmp_path / "rates.tdms", {"Log": [
        ("Spindle nose", temp, {"unit_string": "degC", **_wf()}),
        ("Room", air, {"unit_string": "degC", **_wf()}),
        ("dX", fast, {"unit_string": "um", **_wf(step=2.0)})]})
    out = tmp_path / "init"
    assert main(["init", str(path), f"out={out}"]) == 0
    config = yaml.safe_load((out / "conf" / "data" / "rates.yaml").read_text())
    assert config["resample_s"] == 2.0
    ds, _ = read_dataset(path, {k: v for k, v in config.items() if k != "path"})
    df = next(iter(ds.campaigns.values()))
    assert np.allclose(np.diff(df["time"]), 2.0)


def test_channels_of_two_lengths_without_a_time_are_refused_naming_them(tmp_path, capsys):
    temp, _, dx = _temps(0)
    path = write_tdms(tmp_path / "bad.tdms", {"Log": [
        ("Spindle nose", temp, {"unit_string": "degC"}),
        ("dX", np.repeat(dx, 10), {"unit_string": "um"})]})
    out = tmp_path / "init"
    assert main(["init", str(path), f"out={out}"]) == 2
    said = capsys.readouterr().err
    assert "bad.tdms" in said and "group 'Log', channel 'dX' 600" in said and "wf_increment" in said
    assert not (out / "conf").exists()                       # nothing half-written


def test_a_gap_in_a_channel_is_refused_naming_file_group_channel_and_row(tmp_path):
    temp, air, dx = _temps(0)
    temp[20:30] = np.nan
    path = write_tdms(tmp_path / "gap.tdms", {"Temperatures": [
        ("Spindle nose", temp, {"unit_string": "degC", **_wf()}),
        ("Room", air, {"unit_string": "degC", **_wf()}),
        ("dX", dx, {"unit_string": "um", **_wf()})]})
    with pytest.raises(ContractError) as info:
        read_dataset(path, {"roles": {"ambient": ["Room"]}})
    assert info.value.file == path and info.value.row == 21
    assert "group 'Temperatures', channel 'Spindle nose'" in str(info.value)


def test_a_tdms_log_without_nptdms_names_the_extra(tmp_path, monkeypatch, capsys):
    path = daq_log(tmp_path / "day.tdms")
    monkeypatch.setitem(sys.modules, "nptdms", None)
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 2
    assert "pip install -e '.[tdms]'" in capsys.readouterr().err


# --- MATLAB ---------------------------------------------------------------------------------

DATENUM_T0 = 719529.0 + (T0 - np.datetime64("1970-01-01T00:00:00")).astype(float) / 86400


def test_a_struct_of_vectors_with_datenum_time_and_units(tmp_path, capsys):
    temp, air, dx = _temps(0)
    path = tmp_path / "data.mat"
    sio.savemat(path, {"data": {"time": DATENUM_T0 + np.arange(N) * 10 / 86400, "Tspindle": temp,
                                "Troom": air, "dX": dx[:, None], "name": "run 1",
                                "units": {"Tspindle": "degC", "Troom": "degC", "dX": "um"}}})
    out = tmp_path / "init"
    assert main(["init", str(path), f"out={out}"]) == 0
    said = capsys.readouterr()
    assert "data.mat: data.time read as MATLAB datenums" in said.out + said.err
    config = yaml.safe_load((out / "conf" / "data" / "data.yaml").read_text())
    assert config["roles"]["ambient"] == ["Troom"]          # (a T before the air's word)
    ds, _ = read_dataset(path, {k: v for k, v in config.items() if k != "path"})
    df = ds.campaigns[ds.ids()[0]]
    assert np.allclose(np.diff(df["time"]), 10.0, atol=1e-3)
    assert df["E_dX"].to_numpy() == pytest.approx(dx[:len(df)])


def _v73(path, build):
    """An HDF5 file behind MATLAB's 512-byte header, as ``save -v7.3`` writes it."""
    with h5py.File(path, "w", userblock_size=512) as f:
        build(f)
    with open(path, "r+b") as f:
        f.write(b"MATLAB 7.3 MAT-file, Platform: GLNXA64".ljust(116) + b"\0" * 8 + b"\x00\x02IM")
    return path


def _char(group, name, text):
    d = group.create_dataset(name, data=np.array([[ord(c)] for c in text], np.uint16))
    d.attrs["MATLAB_class"] = np.bytes_("char")
    return d


def test_a_v73_matrix_is_transposed_back_to_matlabs_columns(tmp_path):
    temp, air, dx = _temps(0)
    matrix = np.column_stack([np.arange(N) * 10.0, temp, air, dx])    # MATLAB's N x 4

    def build(f):
        d = f.create_dataset("X", data=matrix.T)                     # stored column-major: 4 x N
        d.attrs["MATLAB_class"] = np.bytes_("double")
        refs = f.create_group("#refs#")
        names = [_char(refs, f"n{i}", s).ref for i, s in
                 enumerate(["t [s]", "Spindle [degC]", "Room [degC]", "dX [um]"])]
        c = f.create_dataset("names", data=np.array(names, dtype=h5py.ref_dtype)[:, None])
        c.attrs["MATLAB_class"] = np.bytes_("cell")

    path = _v73(tmp_path / "m.mat", build)
    ds, _ = read_dataset(path, {"roles": {"ambient": ["Room"]}, "test_fraction": None})
    df = ds.campaigns[ds.ids()[0]]
    assert df["time"].to_numpy() == pytest.approx(np.arange(N) * 10.0)
    assert df["E_dX"].to_numpy() == pytest.approx(dx)
    assert df["T_Spindle"].to_numpy() == pytest.approx(temp)


def _runs(k):
    temp, air, dx = _temps(k)
    return {"name": f"Test {k + 1}", "t": np.arange(N) * 10.0, "Tspindle": temp, "Tamb": air, "dX": dx}


UNITS = {"t": "s", "Tspindle": "degC", "Tamb": "degC", "dX": "um"}


def test_a_struct_array_is_runs_in_v5_and_v73_alike(tmp_path):
    runs = [_runs(k) for k in range(3)]
    array = np.empty((1, 3), dtype=[(f, object) for f in [*runs[0], "units"]])
    for k, run in enumerate(runs):
        array[0, k] = tuple(v if isinstance(v, str) else v[:, None] for v in run.values()) + (UNITS,)
    sio.savemat(tmp_path / "v5.mat", {"runs": array})

    def build(f):
        refs, count = f.create_group("#refs#"), iter(range(10**6))
        group = f.create_group("runs")
        group.attrs["MATLAB_class"] = np.bytes_("struct")
        group.attrs["MATLAB_fields"] = np.array(                 # (MATLAB's field order)
            [np.array(list(n), "S1") for n in [*runs[0], "units"]],
            dtype=h5py.vlen_dtype(np.dtype("S1")))
        for field in [*runs[0], "units"]:
            made = []
            for run in runs:
                name = f"r{next(count)}"
                if field == "name":
                    made.append(_char(refs, name, run[field]).ref)
                elif field == "units":
                    g = refs.create_group(name)
                    g.attrs["MATLAB_class"] = np.bytes_("struct")
                    for u, text in UNITS.items():
                        _char(g, u, text)
                    made.append(g.ref)
                else:
                    d = refs.create_dataset(name, data=run[field][None, :])
                    d.attrs["MATLAB_class"] = np.bytes_("double")
                    made.append(d.ref)
            group.create_dataset(field, data=np.array(made, dtype=h5py.ref_dtype)[:, None])

    _v73(tmp_path / "v73.mat", build)
    read = [read_dataset(tmp_path / f, {"roles": {"campaign": "run"}})[0] for f in ("v5.mat", "v73.mat")]
    assert read[0].ids() == read[1].ids() == ["Test_1", "Test_2", "Test_3"]
    for cid in read[0].ids():
        assert read[0].campaigns[cid].equals(read[1].campaigns[cid])
    assert list(read[0].campaigns["Test_1"].columns) == ["time", "T_Tspindle", "T_Tamb", "E_dX"]


def test_a_v73_file_without_h5py_names_the_extra_and_a_v5_file_needs_none(tmp_path, monkeypatch,
                                                                         capsys):
    temp, air, dx = _temps(0)

    def build(f):
        g = f.create_group("data")
        g.attrs["MATLAB_class"] = np.bytes_("struct")
        for name, v in (("t", np.arange(N) * 10.0), ("Tspindle_degC", temp), ("dX_um", dx)):
            g.create_dataset(name, data=v[None, :]).attrs["MATLAB_class"] = np.bytes_("double")

    v73 = _v73(tmp_path / "v73.mat", build)
    sio.savemat(tmp_path / "v5.mat", {"data": {"t": np.arange(N) * 10.0, "Tspindle_degC": temp,
                                               "dX_um": dx}})
    monkeypatch.setitem(sys.modules, "h5py", None)
    assert main(["init", str(v73), f"out={tmp_path / 'a'}"]) == 2
    assert "pip install -e '.[matlab]'" in capsys.readouterr().err
    assert main(["init", str(tmp_path / "v5.mat"), f"out={tmp_path / 'b'}"]) == 0


def test_a_matlab_table_is_refused_saying_how_to_save_it(tmp_path, capsys):
    def build(f):
        d = f.create_dataset("T", data=np.array([[3707764736, 2, 1, 1, 1, 1]], np.uint32))
        d.attrs["MATLAB_class"] = np.bytes_("table")
        d.attrs["MATLAB_object_decode"] = np.int32(3)

    path = _v73(tmp_path / "t.mat", build)
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 2
    said = capsys.readouterr().err
    assert "variable 'T' is a MATLAB table" in said and "table2struct(T, 'ToScalar', true)" in said


def test_a_field_of_another_length_is_refused_naming_variable_and_field(tmp_path):
    temp, air, dx = _temps(0)
    sio.savemat(tmp_path / "d.mat", {"data": {"Tspindle": temp, "dX": dx[::2]}})
    with pytest.raises(ContractError, match=r"variable 'data': field 'dX' has 30 values"):
        read_dataset(tmp_path / "d.mat", {})


# --- mended on the way -------------------------------------------------------------------

def test_a_long_file_cut_by_the_sniffed_window_inside_its_stamp_is_long(tmp_path):
    # before: the 64 KiB window's last line, cut inside its stamp, was a row without a tag:
    # the long file was read as wide ("no column reads as a measured error")
    head = "time,channel,value\n"

    def row(i, width):
        return (f"2026-11-02T05:{i // 60 % 60:02d}:{i % 60:02d}.000000+00:00,"
                f"{'Spindle' if i % 2 else 'Ambient'} [degC],{20 + i / 1e4:.{width}f}\n")

    width = next(w for w in range(4, 12) if 1 <= (65536 - len(head)) % len(row(0, w)) <= 30)
    path = tmp_path / "long.csv"
    path.write_text(head + "".join(row(i, width) for i in range(3000)))
    assert long_layout(path, ReadOptions()) is not None


def test_matlabs_troom_is_proposed_the_ambient():
    header = ["t", "Troom [degC]", "Tspindle [degC]", "dX [um]"]
    roles = proposed_roles(header, dict.fromkeys(header, "1.0"), ReadOptions())
    assert roles["ambient"] == ["Troom"]



def test_a_v5_table_scipy_gives_as_an_opaque_record_is_refused_alike(tmp_path, monkeypatch):
    # SciPy reads a table saved v5 as an opaque record (s0, s1, s2 its class, arr): as loadmat
    # gives it (no MATLAB here to save one)
    opaque = np.empty((1, 1), dtype=[("s0", object), ("s1", object), ("s2", object), ("arr", object)])
    opaque[0, 0] = (b"", b"MCOS", b"table", np.zeros((6, 1), np.uint32))
    sio.savemat(tmp_path / "t.mat", {"x": np.arange(3.0)})
    monkeypatch.setattr(sio, "loadmat", lambda *a, **k: {"__header__": b"", "T": opaque})
    with pytest.raises(ContractError, match=r"variable 'T' is a MATLAB table.*table2struct"):
        read_dataset(tmp_path / "t.mat", {})


def test_runs_of_one_file_timed_differently_are_refused_naming_them(tmp_path):
    # before: the untimed run's rows were written without the time cell, under the time header
    runs = np.empty((1, 2), dtype=[("t", object), ("T1", object), ("dX_um", object)])
    temp, _, dx = _temps(0)
    runs[0, 0] = (np.arange(N)[:, None] * 10.0, temp[:, None], dx[:, None])
    runs[0, 1] = (np.array([[0.0]]), temp[:, None], dx[:, None])     # its time a scalar: none
    sio.savemat(tmp_path / "r.mat", {"runs": runs})
    with pytest.raises(ContractError, match=r"'runs\(1\)' in seconds, 'runs\(2\)' untimed"):
        read_dataset(tmp_path / "r.mat", {"roles": {"campaign": "run"}})


def test_a_field_of_rising_datenums_is_the_time_whatever_its_name(tmp_path):
    # before: 'dn' read as a temperature of 7.4e5 degrees
    temp, air, dx = _temps(0)
    sio.savemat(tmp_path / "d.mat", {"data": {"dn": DATENUM_T0 + np.arange(N) * 10 / 86400,
                                              "T1_degC": temp, "dX_um": dx}})
    ds, report = read_dataset(tmp_path / "d.mat", {"roles": {"error": ["dX"]}})
    (cid,) = ds.ids()
    assert list(ds.campaigns[cid].columns) == ["time", "T_T1", "E_dX"]
    assert np.allclose(np.diff(ds.campaigns[cid]["time"]), 10.0, atol=1e-3)
    assert report["campaigns"][cid]["time_origin"].startswith("2026-11-02T05:30:00")


def _staggered_long(path, before: int):
    """A long file of two tags every 10 s, 'b' starting 8 ms after 'a', 'a' with ``before``
    samples before it."""
    t0 = np.datetime64("2026-11-02T05:30:00.000")
    lines = ["time,channel,value"]
    for i in range(-before + 1, 30):
        lines.append(f"{t0 + np.timedelta64(10_000 * i, 'ms')}+00:00,T_a,{20 + i / 100:.2f}")
    for i in range(30):
        lines.append(f"{t0 + np.timedelta64(10_000 * i + 8, 'ms')}+00:00,E_b,{i / 10:.1f}")
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("before, said", [(1, False), (3, True)])
def test_a_grid_start_is_said_only_where_samples_before_it_are_not_read(tmp_path, caplog, before,
                                                                        said):
    # before: said for every file where tags start apart (DAQmx tasks 4-16 ms apart: 10 warnings
    # at every read), though each tag's last sample before the start is held there
    path = _staggered_long(tmp_path / "long.csv", before)
    ds, _ = read_dataset(path, {"resample_s": 10})
    df = ds.campaigns[ds.ids()[0]]
    assert df["T_a"].iloc[0] == pytest.approx(20.0)          # held from 8 ms before the grid
    assert ("before it are not read" in caplog.text) is said
    assert ("2 sample(s) before it are not read" in caplog.text) is said       # 'a''s first two


def test_a_fields_unit_is_asked_for_as_data_units_not_as_a_header(tmp_path, capsys):
    """A MATLAB field has no header a lab can edit: the refusal asks for data.units (stranger62:
    it suggested 'dX [µm]'), and that override is read."""
    temp, air, dx = _temps(0)
    path = tmp_path / "data.mat"
    sio.savemat(path, {"data": {"time": np.arange(N) * 10.0, "Tspindle": temp, "Troom": air,
                                "dX": dx[:, None]}})
    assert main(["init", str(path), f"out={tmp_path / 'a'}"]) == 2
    said = capsys.readouterr().err
    assert "data.units={dX: um}" in said and "'dX [µm]'" not in said
    assert main(["init", str(path), f"out={tmp_path / 'b'}", "data.units={dX: um}"]) == 0
