"""A spindle test rig's HBM catman ASCII exports with their channel header, a file a test
(stranger84): a header block, a block a channel (``Channel 2:`` its name, ``Unit:``,
``Comment:``, ``Sample rate:``, ``T0:``, ``Length:``), then the table, each rate group's time
channel first (``benchmarks/bench_stranger84.py`` writes the lab's full record; these are a few
rows of test_stranger68's linear runs)."""

from __future__ import annotations

import datetime as dt
import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

from conftest import FAST, refused
from test_export import checked_pack, needs_cc
from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

# (name, unit): three thermocouples, the two probes
CHANNELS = [("T air", "°C"), ("T housing", "°C"), ("T front bearing", "°C"), ("MCS X1", "µm"),
            ("MCS Z", "µm")]
START = dt.datetime(2027, 5, 3, 7)
SLOW = 4                  # two groups: the temperatures every 4th probe sample


def export(folder: Path, run: int, groups: int = 1, german: bool = False) -> Path:
    """``SP_T<run>.TXT``: linear_run's rows every 10 s, in one rate group or two (the probes at
    10 s, the temperatures at 40 s), English (TAB, ``.``) or German (``;``, ``,``)."""
    folder.mkdir(parents=True, exist_ok=True)
    values = linear_run(8726, run)
    start = START + dt.timedelta(days=run - 1)
    sep = ";" if german else "\t"
    num = (lambda v: v.replace(".", ",")) if german else str
    stamp = f"{start:%d.%m.%Y %H:%M:%S}" if german else f"{start:%m/%d/%Y %H:%M:%S}"
    rows = {"probes": np.arange(ROWS), "temps": np.arange(0, ROWS, SLOW if groups == 2 else 1)}
    laid = [("probes", [3, 4]), ("temps", [0, 1, 2])] if groups == 2 else [("probes", [3, 4, 0, 1, 2])]
    columns = []
    for g, (group, chans) in enumerate(laid, start=1):
        idx = rows[group]
        period = 10.0 * (idx[1] - idx[0])
        columns.append((f"Time  {g} - default sample rate", "s", period,
                        [num(f"{k * period:.1f}") for k in range(idx.size)]))
        columns += [(*CHANNELS[c], period, [num(f"{v:.5f}") for v in values[idx, c]]) for c in chans]
    lines = [f"File:{sep}D:\\catman\\SP_T{run}.BIN", f"Comment:{sep}test {run}",
             f"catman Version:{sep}catmanAP 5.6.1", ""]
    for k, (name, unit, period, cells) in enumerate(columns, start=1):
        lines += [f"Channel {k}:{sep}{name}", f"Unit:{sep}{unit}", f"Comment:{sep}",
                  f"Sample rate:{sep}{num(f'{1 / period:.5f}')}", f"T0:{sep}{stamp}",
                  f"Length:{sep}{len(cells)}", ""]
    lines.append(sep.join(c[0] for c in columns))
    for i in range(ROWS):
        lines.append(sep.join(c[3][i] if i < len(c[3]) else "" for c in columns))
    text = "\r\n".join(lines) + "\r\n"
    path = folder / f"SP_T{run}.TXT"
    path.write_bytes(text.encode("cp1252"))
    return path


# (dates84: an English export's T0 05/03/2027 is month first only by data.dayfirst=false)
ROLES = {"roles": {"error": ["MCS*"]}, "encoding": "cp1252", "test_fraction": 0.5,
         "dayfirst": False}
# one group's file: the lines above its first sample (the header block's 4, a block of 7 lines
# per channel and its time channel, the column row)
TOP = 4 + 7 * (1 + len(CHANNELS)) + 1


@pytest.mark.parametrize("german", [False, True])
def test_a_folder_of_catman_exports_reads_its_channels_by_their_blocks(tmp_path, german):
    """(Before: init refused the folder, "no column reads as a measured error ...; the numeric
    columns: none": the export's header and channel blocks read as the table.)  The names and
    units are the blocks', the time the block's T0 plus the time channel's seconds."""
    for run in (1, 2):
        export(tmp_path / "rig", run, german=german)
    ds, _ = read_dataset(tmp_path / "rig", ROLES)
    assert list(ds.campaigns) == ["SP_T1", "SP_T2"]
    frame = ds.campaigns["SP_T2"]
    names = ["T_air", "T_housing", "T_front_bearing", "E_MCS_X1", "E_MCS_Z"]
    assert sorted(frame.columns) == sorted(["time", *names])
    np.testing.assert_array_equal(frame["time"], np.arange(ROWS) * 10.0)
    np.testing.assert_allclose(frame[names].to_numpy(), linear_run(8726, 2), atol=1e-5)
    assert str(ds.manifest["start"].iloc[1]) == "2027-05-04 07:00:00"


def test_two_rate_groups_are_held_onto_the_fast_groups_grid(tmp_path):
    """The temperatures' group at 40 s beside the probes' at 10 s: each its own time channel,
    the slow group's cells empty under its last sample; held onto data.resample_s."""
    for run in (1, 2):
        export(tmp_path / "rig", run, groups=2)
    ds, _ = read_dataset(tmp_path / "rig", {**ROLES, "resample_s": 10.0})
    frame = ds.campaigns["SP_T1"]
    expected = linear_run(8726, 1)
    np.testing.assert_allclose(frame["E_MCS_Z"], expected[:, 4], atol=1e-5)
    held = expected[(np.arange(ROWS) // SLOW) * SLOW, 1]        # sample and hold
    np.testing.assert_allclose(frame["T_housing"], held, atol=1e-5)


def test_init_reads_a_two_group_folder_in_one_try(tmp_path, capsys):
    for run in (1, 2, 3):
        export(tmp_path / "rig", run, groups=2)
    assert main(["init", str(tmp_path / "rig"), "data.dayfirst=false",
                 f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "HBM catman's ASCII export" in said and "data.resample_s=10" in said, said
    conf = (tmp_path / "init" / "conf" / "data" / "rig.yaml").read_text()
    assert "error:\n  - MCS X1\n  - MCS Z" in conf and "resample_s: 10.0" in conf, conf


def _spoiled(tmp_path, change) -> Path:
    for run in (1, 2):
        path = export(tmp_path / "rig", run)
    path.write_bytes(change(path.read_bytes()))
    return path


@pytest.mark.parametrize("change, says", [
    (lambda b: b[:-20],
     ["the file's last line holds", "cut off while it was written",
      f"line {TOP + ROWS} (data row {ROWS})"]),
    (lambda b: b"\r\n".join(b.split(b"\r\n")[:-11]) + b"\r\n",
     [f"holds {ROWS - 10} of its {ROWS} samples", "its block's Length",
      f"line {TOP + ROWS - 10} (data row {ROWS - 10})"]),
    (lambda b: re.sub(rb"\r\n70\.0\t[^\t]*\t", b"\r\n70.0\t1.2#4\t", b, count=1),
     ["channel 2 'MCS X1'", "'1.2#4' is no number", f"line {TOP + 8} (data row 8)"]),
])
def test_a_spoiled_export_is_refused_naming_its_line(tmp_path, capsys, change, says):
    path = _spoiled(tmp_path, change)
    said = refused(["init", str(tmp_path / "rig"), "data.dayfirst=false", f"out={tmp_path / 'init'}"],
                   capsys, *says)
    assert str(path) in said


@pytest.mark.parametrize("groups", [1, 2])
def test_a_catman_export_piped_into_monitor_streams_as_the_file_does(tmp_path, monkeypatch, capsys,
                                                                    groups):
    """The test run piped in as catman wrote it streams to the RMSE its file streams to; two
    rate groups held as the file's grid holds them (before: "'channel' is not numeric", the
    long table of channels at their own rates read as a wide one)."""
    import io as _io
    import json

    for run in (1, 2):
        path = export(tmp_path / "rig", run, groups=groups)
    common = ["monitor", f"data.path={tmp_path / 'rig'}", "data.roles.error=[MCS*]",
              "data.encoding=cp1252", "data.test_fraction=0.5", "data.resample_s=10",
              "data.dayfirst=false", *FAST]
    assert main([*common, f"out={tmp_path / 'file'}"]) == 0
    monkeypatch.setattr("sys.stdin", _io.TextIOWrapper(_io.BytesIO(path.read_bytes())))
    assert main([*common, "monitor.input=-", f"out={tmp_path / 'pipe'}"]) == 0, capsys.readouterr().err
    said = [json.loads((tmp_path / k / "monitor.json").read_text())["targets"] for k in ("file", "pipe")]
    for target in ("E_MCS_X1", "E_MCS_Z"):
        assert said[1][target]["n_samples"] == ROWS
        assert said[1][target]["rmse_fixed"] == pytest.approx(said[0][target]["rmse_fixed"], rel=1e-12)


@needs_cc
def test_the_compiled_stream_refuses_a_catman_export_naming_the_command_that_converts_it(
        tmp_path, capsys):
    """Refused at the first channel block, the command named; the rows it writes stream."""
    for run in (1, 2):
        path = export(tmp_path / "rig", run)
    common = [f"data.path={tmp_path / 'rig'}", "data.roles.error=[MCS*]", "data.encoding=cp1252",
              "data.dayfirst=false", "data.test_fraction=0.5"]
    assert main(["run", *common, *FAST, "model=mlr", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    checked_pack(tmp_path / "code")
    stream = str(tmp_path / "code" / "stream")
    done = subprocess.run([stream], capture_output=True, input=path.read_bytes())
    assert done.returncode == 2 and done.stdout == b""
    assert (b"stream: line 5 is HBM catman's channel block (Channel 1:): its channels are named in "
            b"blocks above the table; convert it to the rows the served model reads it as: "
            b"`thermocomp rows FILE") in done.stderr, done.stderr
    capsys.readouterr()
    assert main(["rows", str(path), *common[1:4]]) == 0
    rows = capsys.readouterr().out
    streamed = subprocess.run([stream], capture_output=True, input=rows.encode())
    assert streamed.returncode == 0, streamed.stderr
    assert len(streamed.stdout.decode().splitlines()) == ROWS + 1
