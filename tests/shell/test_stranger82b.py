"""A 5-axis machining centre's Yokogawa GX20 data converted to ASCII by Universal Viewer, a file a
run (stranger82b): a header block of ``"key","value"`` rows, the channel table (``Channel``,
``Tag``: the lab's names, ``Unit``: ``C`` for °C), then ``"Date Time"``, the channels, a row a
sample, ``Burnout`` for a broken thermocouple, the probing cycle's error written every 10th row
and blank in between (``benchmarks/bench_stranger82b.py`` writes the lab's full record; these
are a few rows of test_stranger68's linear runs)."""

from __future__ import annotations

import datetime as dt
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST
from test_export import checked_pack, needs_cc
from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

# (channel, tag, unit): three thermocouples, the probing cycle's dX / dZ, the A axis
CHANNELS = [("0001", "HALLE", "C"), ("0002", "SPINDEL", "C"), ("0003", "BETT", "C"),
            ("C005", "DX_TCP", "um"), ("C006", "DZ_TCP", "um"), ("C003", "A_POS", "deg")]
START = dt.datetime(2027, 9, 6, 6)
PROBE = 10        # the errors written every PROBE rows


def gx20(folder: Path, run: int, burnout: int = 0) -> Path:
    """``GX20_<yyMMdd>_060000.csv``: linear_run's rows every 60 s, A at 0 / 90 deg, the errors
    on every PROBE-th row; ``burnout`` samples of ``SPINDEL`` from row 40 written ``Burnout``."""
    folder.mkdir(parents=True, exist_ok=True)
    values = np.column_stack([linear_run(8342, run), np.where(np.arange(ROWS) % 40 < 20, 0, 90)])
    start = START + dt.timedelta(days=run - 1)
    row = lambda key, cells: ",".join(f'"{c}"' for c in [key, *cells])  # noqa: E731
    lines = [row("Universal Viewer", ["R4.04.01"]), row("Model", ["GX20"]),
             row("File Name", [f"LAUF{run}.GDS"]), row("Start Time", [f"{start:%Y/%m/%d %H:%M:%S}"]),
             "", row("Channel", [c for c, _, _ in CHANNELS]), row("Tag", [t for _, t, _ in CHANNELS]),
             row("Tag Comment", ["" for _ in CHANNELS]), row("Unit", [u for _, _, u in CHANNELS]),
             "", row("Date Time", [c for c, _, _ in CHANNELS])]
    for k, v in enumerate(values):
        cells = [f"{x:.5f}" for x in v]
        if k % PROBE:
            cells[3] = cells[4] = ""
        if 40 <= k < 40 + burnout:
            cells[1] = "Burnout"
        lines.append(f"{start + dt.timedelta(seconds=60 * k):%Y/%m/%d %H:%M:%S}.0," + ",".join(cells))
    path = folder / f"GX20_{start:%y%m%d_%H%M%S}.csv"
    path.write_text("\r\n".join(lines) + "\r\n", encoding="ascii")
    return path


CONF = {"roles": {"error": ["D?_TCP"], "state": ["A_*"]}, "test_fraction": 0.5,
        "max_gap_samples": 3}


def test_a_folder_of_gx20_exports_reads_its_channels_by_their_tags(tmp_path):
    """(Before: init refused the folder, "no column reads as a measured error ...; the numeric
    columns: 'C', 'C#2' ...": the Unit row taken for the header.)  The names are the tags, the
    unit ``C`` a temperature's, a Burnout a missing value, the probing cycle's blanks left
    missing (never filled)."""
    for run in (1, 2):
        gx20(tmp_path / "dmu", run, burnout=3 * (run == 2))
    ds, _ = read_dataset(tmp_path / "dmu", CONF)
    assert list(ds.campaigns) == ["GX20_270906_060000", "GX20_270907_060000"]
    frame = ds.campaigns["GX20_270907_060000"]
    names = ["T_HALLE", "T_SPINDEL", "T_BETT", "E_DX_TCP", "E_DZ_TCP"]
    assert sorted(frame.columns) == sorted(["time", *names, "S_A_POS"])
    np.testing.assert_array_equal(frame["time"], np.arange(ROWS) * 60.0)
    expected = linear_run(8342, 2)
    kept = np.r_[0:40, 43:ROWS]
    np.testing.assert_allclose(frame[names[:3]].to_numpy()[kept], expected[kept, :3], atol=1e-5)
    probed = np.arange(ROWS) % PROBE == 0
    errors = frame[names[3:]].to_numpy()
    assert np.isnan(errors[~probed]).all()
    np.testing.assert_allclose(errors[probed], expected[probed, 3:], atol=1e-5)


def test_init_proposes_a_gx20_folders_roles(tmp_path, capsys):
    for run in (1, 2, 3):
        gx20(tmp_path / "dmu", run, burnout=4 * (run == 2))
    assert main(["init", str(tmp_path / "dmu"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "a Yokogawa viewer's ASCII export" in said and "data.max_gap_samples=4" in said, said
    conf = (tmp_path / "init" / "conf" / "data" / "dmu.yaml").read_text()
    assert "error:\n  - DX_TCP\n  - DZ_TCP" in conf and "- A_POS" in conf, conf


def test_a_gx20_export_piped_into_monitor_streams_as_the_file_does(tmp_path, monkeypatch, capsys):
    import io as _io
    import json

    for run in (1, 2):
        path = gx20(tmp_path / "dmu", run)
    common = ["monitor", f"data.path={tmp_path / 'dmu'}", "data.roles.error=[D?_TCP]",
              "data.roles.state=[A_*]", "data.test_fraction=0.5", *FAST]
    assert main([*common, f"out={tmp_path / 'file'}"]) == 0
    monkeypatch.setattr("sys.stdin", _io.TextIOWrapper(_io.BytesIO(path.read_bytes())))
    assert main([*common, "monitor.input=-", f"out={tmp_path / 'pipe'}"]) == 0, capsys.readouterr().err
    said = [json.loads((tmp_path / k / "monitor.json").read_text())["targets"] for k in ("file", "pipe")]
    for target in ("E_DX_TCP", "E_DZ_TCP"):
        assert said[1][target]["rmse_fixed"] == pytest.approx(said[0][target]["rmse_fixed"], rel=1e-12)


@needs_cc
def test_the_compiled_stream_refuses_a_gx20_export_naming_the_command_that_converts_it(
        tmp_path, capsys):
    """(Before, on the bench's file: exit 2 on "line 13: input T_amb has no finite value ..."
    after a header line on stdout: the Tag row taken for the header, the Tag Comment row for a
    sample.)  Refused at its first line, nothing written, the command named; the rows it writes
    stream."""
    for run in (1, 2):
        path = gx20(tmp_path / "dmu", run)
    common = [f"data.path={tmp_path / 'dmu'}", "data.roles.error=[D?_TCP]",
              "data.roles.state=[A_*]", "data.test_fraction=0.5"]
    assert main(["run", *common, *FAST, "model=mlr", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    checked_pack(tmp_path / "code")
    stream = str(tmp_path / "code" / "stream")
    done = subprocess.run([stream], capture_output=True, input=path.read_bytes())
    assert done.returncode == 2 and done.stdout == b""
    assert (b"stream: line 1 is a Yokogawa viewer's header block (\"Universal Viewer\"): its "
            b"channels are named in its Tag row, its columns by channel number; convert it to the "
            b"rows the served model reads it as: `thermocomp rows FILE") in done.stderr, done.stderr
    semicolon = path.read_bytes().replace(b'","', b'";"')
    assert subprocess.run([stream], capture_output=True, input=semicolon).stderr == done.stderr
    capsys.readouterr()
    assert main(["rows", str(path), *common[1:3]]) == 0
    streamed = subprocess.run([stream], capture_output=True, input=capsys.readouterr().out.encode())
    assert streamed.returncode == 0, streamed.stderr
    assert len(streamed.stdout.decode().splitlines()) == ROWS + 1


def test_a_date_and_a_time_column_and_over_marks_read_as_the_viewer_writes_them(tmp_path):
    """The viewer's other layout (``"Date","Time"``, two columns) is the same times; ``+Over`` /
    ``-Over`` (out of range) are missing cells as ``Burnout`` is."""
    lines = gx20(tmp_path / "a", 1).read_text().splitlines()
    top = next(k for k, line in enumerate(lines) if line.startswith('"Date Time"'))
    lines[top] = lines[top].replace('"Date Time",', '"Date","Time",')
    for k in range(ROWS):
        cells = lines[top + 1 + k].replace(" ", ",", 1).split(",")
        if k in (40, 41):
            cells[3] = "+Over" if k == 40 else "-Over"      # SPINDEL (after the date and the time)
        lines[top + 1 + k] = ",".join(cells)
    path = tmp_path / "b" / "GX20_270906_060000.csv"
    path.parent.mkdir()
    path.write_text("\r\n".join(lines) + "\r\n")
    ds, _ = read_dataset(path, CONF)
    frame = pd.concat(ds.campaigns.values())          # (the one file cut into train and test)
    np.testing.assert_array_equal(frame["time"], np.arange(ROWS) * 60.0)
    expected = linear_run(8342, 1)
    kept = np.r_[0:40, 42:ROWS]
    np.testing.assert_allclose(frame["T_SPINDEL"].to_numpy()[kept], expected[kept, 1], atol=1e-5)


def test_a_semicolon_export_with_decimal_commas_reads_as_the_comma_one(tmp_path):
    """(Before, by the reader of the comma export: "4 column(s) not read: 'Unit' is not numeric
    ...", a European PC's export, ``;`` and ``21,3``, its first line not taken for the viewer's.)
    The same frame as the comma export's."""
    one = gx20(tmp_path / "a", 1)
    lines = [line if line.startswith('"') or not line else
             ";".join(c.replace(".", ",") if k else c for k, c in enumerate(line.split(",")))
             for line in one.read_text().splitlines()]
    lines = [line.replace('","', '";"') for line in lines]
    two = tmp_path / "b" / one.name
    two.parent.mkdir()
    two.write_text("\r\n".join(lines) + "\r\n")
    frames = [pd.concat(read_dataset(p, CONF)[0].campaigns.values()) for p in (one, two)]
    assert frames[1].shape == frames[0].shape
    pd.testing.assert_frame_equal(frames[1], frames[0])
