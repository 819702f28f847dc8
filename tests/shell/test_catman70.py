"""A lab's HBM catman ASCII exports of an ISO 230-3 spindle rig's tests (catman70): a block of
``key:<TAB>value`` lines above the table, then a row of channel names (catman's time channel
``Zeit  1 - Standardmessrate``), a row of units and rows describing the channels (their
comments; ``T0`` / ``dt``) before the samples; catman Easy on a German PC (Windows-1252,
decimal commas, one file per test, the time in seconds) or catman AP on an English PC (UTF-16,
the tests appended in one file, the time as dates, silent between the tests)
(``benchmarks/bench_catman70.py`` writes the lab's full record; these are a few rows of it)."""

from __future__ import annotations

import codecs
import contextlib
import datetime as dt
import io
import json
import logging
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import FAST, refused
from test_export import needs_cc
from test_stranger65 import _compiled_stream_equals_its_pack
from test_stranger68 import ROWS, linear_run
from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError
from thermocomp.shell.cli import main

NAMES = [("T Luft", "T air"), ("T Ständer", "T column"), ("T Lager vorn", "T front bearing"),
         ("Sonde X1", "MCS X1"), ("Sonde Z", "MCS Z"), ("Drehzahl", "Spindle speed")]
UNITS = [("°C", "°C"), ("°C", "°C"), ("°C", "°C"), ("µm", "µm"), ("µm", "µm"), ("1/min", "rpm")]
TIME = ("Zeit  1 - Standardmessrate", "Time  1 - default sample rate")
EASY = ["Datei:\tC:\\Users\\Pruefstand\\catman\\Spindeltest_{k:02d}.BIN",
        "Kommentar:\tISO 230-3 Spindeltest {k:02d}", "catman Version:\tcatman Easy 5.4.2",
        "Export:\t05.04.2027 19:00:12", ""]
EASY_ROLES = {"roles": {"error": ["Sonde*"]}}       # (the others' roles: their units)
ROLES = "data.roles.error=['Sonde*']"
AP_ROLES = {"roles": {"error": ["MCS*"]}}
AP = ["File:\tD:\\Measurements\\week17.bin", "Comment:\tISO 230-3 spindle tests",
      "catman Version:\tcatman AP 5.6.1", "Export:\t04/30/2027 18:00:00", ""]


def _values(run: int) -> np.ndarray:
    """A test's rows: test_stranger68's three temperatures and two errors, the speed."""
    speed = np.where(np.arange(ROWS) < 60, 3000.0 * run, 0.0)
    return np.round(np.column_stack([linear_run(7133, run), speed]), 3)


def _easy(path: Path, k: int, values: np.ndarray) -> Path:
    """A test as catman Easy on a German PC exports it: a comments row under the units."""
    comments = ["", "MX1609 Typ K", "MX1609 Typ K", "MX1609 Typ K", "MCS kapazitiv, 0-500 µm",
                "MCS kapazitiv, 0-500 µm", "Analogausgang Umrichter"]
    rows = [[TIME[0], *(n[0] for n in NAMES)], ["s", *(u[0] for u in UNITS)], comments]
    rows += [[f"{30.0 * i:.3f}", *(f"{v:.4f}" for v in row)] for i, row in enumerate(values)]
    text = [line.format(k=k) for line in EASY] + ["\t".join(r).replace(".", ",") for r in rows]
    path.write_bytes(("\r\n".join(text) + "\r\n").encode("cp1252"))
    return path


def _ap(path: Path, tests: list[tuple[dt.datetime, np.ndarray]]) -> Path:
    """The tests as catman AP on an English PC exports each, appended in one UTF-16 file: T0 and
    dt rows under the units, the time as dates."""
    first = tests[0][0]
    rows = [[TIME[1], *(n[1] for n in NAMES)], ["", *(u[1] for u in UNITS)],
            ["T0", *[f"{first:%m/%d/%Y %H:%M:%S}"] * len(NAMES)], ["dt", *["30"] * len(NAMES)]]
    for start, values in tests:
        rows += [[f"{start + dt.timedelta(seconds=30 * i):%m/%d/%Y %H:%M:%S}",
                  *(f"{v:.4f}" for v in row)] for i, row in enumerate(values)]
    path.write_bytes(("\r\n".join(AP + ["\t".join(r) for r in rows]) + "\r\n").encode("utf-16"))
    return path


def _easy_folder(root: Path) -> Path:
    root.mkdir()
    for k in (1, 2, 3):
        _easy(root / f"Spindeltest_{k:02d}.TXT", k, _values(k))
    return root


def _week(path: Path) -> Path:
    return _ap(path, [(dt.datetime(2027, 4, 26 + 2 * (k - 1), 7), _values(k)) for k in (1, 2, 3)])


def test_a_catman_easy_folder_reads_its_names_over_the_units_and_the_comments_row(tmp_path):
    """Before: the unit row was taken for the header (the names row above it, the comments row
    under it: no row of numbers within two lines), 'no column reads as a measured error'."""
    ds, _ = read_dataset(_easy_folder(tmp_path / "rig"), {"test_fraction": 0.34,
                                                         "encoding": "cp1252", **EASY_ROLES})
    assert list(ds.manifest["split"]) == ["train", "train", "test"]
    frame = ds.campaigns["Spindeltest_02"]
    assert list(frame.columns) == ["time", "T_Luft", "T_Ständer", "T_Lager_vorn", "E_Sonde_X1",
                                   "E_Sonde_Z", "S_Drehzahl"]
    np.testing.assert_allclose(frame["time"].to_numpy()[:3], [0.0, 30.0, 60.0])
    np.testing.assert_allclose(frame.iloc[:, 1:].to_numpy(), _values(2))


@pytest.fixture(scope="module")
def easy_run(tmp_path_factory) -> tuple[Path, str, Path]:
    """The catman Easy folder, what ``init`` said of it and ``run``'s out folder (model=mlr on
    init's config), made once: the init and run tests below only read them."""
    tmp_path = tmp_path_factory.mktemp("easy_run")
    folder = _easy_folder(tmp_path / "rig")
    said = io.StringIO()
    with contextlib.redirect_stdout(said):
        assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0
    assert main(["run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=rig",
                 "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    return folder, said.getvalue(), tmp_path


def test_init_names_catmans_time_channel_and_run_fits_the_probes(easy_run):
    """Before: refused; with the table found, catman's time channel ``Zeit  1 -
    Standardmessrate [s]`` was 'not read' (no time header), one more try for data.roles.time."""
    _, said, tmp_path = easy_run
    assert "header on line 6 (5 line(s) above it left out), units from line 7; rows counted " \
           "from line 9" in said
    assert "time: 'Zeit  1 - Standardmessrate [s]', in s" in said
    assert "  Drehzahl [1/min]                state        S_Drehzahl" in said
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert set(metrics["targets"]) == {"E_Sonde_X1", "E_Sonde_Z"}
    assert metrics["targets"]["E_Sonde_X1"]["test"]["rmse"] < 0.2     # (the map is linear)


def test_a_catman_file_piped_into_monitor_streams_as_the_folder_reads(easy_run, tmp_path,
                                                                      monkeypatch):
    """Before: 'file <stdin>: 6 column(s) not read: 'T Luft [°C]' is not numeric ('MX1609 Typ
    K')' (the comments row under the units read as a sample)."""
    folder, _, made = easy_run
    data = [f"hydra.searchpath=[file://{made / 'init' / 'conf'}]", "data=rig"]
    text = (folder / "Spindeltest_03.TXT").read_bytes().decode("cp1252")
    monkeypatch.setattr(sys, "stdin", io.StringIO(text))
    assert main(["monitor", *data, "monitor.input=-", "track=false",
                 "promote.envelope.policy=off",        # (test 3 runs faster than the others)
                 f"monitor.model={made / 'out' / 'model.pkl'}", f"out={tmp_path / 'mon'}"]) == 0
    run = json.loads((made / "out" / "metrics.json").read_text())["targets"]
    report = json.loads((tmp_path / "mon" / "monitor.json").read_text())
    assert report["events"] == []
    for target, r in report["targets"].items():
        assert abs(r["rmse_fixed"] - run[target]["test"]["rmse"]) < 1e-9


def test_a_bad_cell_under_the_channel_rows_is_refused_naming_its_line(tmp_path, capsys):
    folder = _easy_folder(tmp_path / "rig")
    path = folder / "Spindeltest_02.TXT"
    lines = path.read_bytes().split(b"\r\n")
    lines[20] = lines[20].replace(b"\t", b"\tx", 1)       # line 21: data row 13 (from line 9)
    path.write_bytes(b"\r\n".join(lines))
    refused(["run", f"data.path={folder}", "data.test_fraction=0.34", "data.encoding=cp1252", ROLES,
             *FAST,
             f"out={tmp_path / 'out'}"], capsys,
            f"file {path}, column 'T_Luft', line 21 (data row 13): value 'x20,2810' is not a "
            "number (its header in the file: 'T Luft [°C]')")
    assert not (tmp_path / "out").exists()


def test_tests_appended_in_one_catman_ap_file_split_at_its_pauses(tmp_path, caplog):
    """Before: the T0 row was read as the first sample (the unit row the header); now the file
    reads, and, one record pausing two days between its tests, says data.runs_at_pauses, which
    reads each test as a campaign (the last held out)."""
    path = _week(tmp_path / "week17.txt")
    with caplog.at_level(logging.WARNING, logger="thermocomp"):
        ds, _ = read_dataset(path, {"test_fraction": 0.34, **AP_ROLES})
    assert "data.runs_at_pauses=true (each stretch between the pauses a run)" in caplog.text
    assert list(ds.manifest.index) == ["week17_train", "week17_test"]
    ds, _ = read_dataset(path, {"test_fraction": 0.34, "runs_at_pauses": True, **AP_ROLES})
    assert list(ds.manifest.index) == ["week17_1", "week17_2", "week17_3"]
    assert list(ds.manifest["split"]) == ["train", "train", "test"]
    frame = ds.campaigns["week17_3"]
    assert list(frame.columns) == ["time", "T_air", "T_column", "T_front_bearing", "E_MCS_X1",
                                   "E_MCS_Z", "S_Spindle_speed"]
    np.testing.assert_allclose(frame["time"].to_numpy()[:2], [0.0, 30.0])   # its own clock
    np.testing.assert_allclose(frame.iloc[:, 1:].to_numpy(), _values(3))


@pytest.mark.parametrize("extra, says", [
    (["data.runs_at_pauses=true"], "data.runs_at_pauses: the time never pauses for more than "
                                   "100 sample periods (30 s): one run"),
    (["data.runs_at_pauses=true", "data.roles.campaign=Drehzahl"],
     "data.roles.campaign and data.runs_at_pauses both split one file into its runs"),
    (["data.runs_at_pauses=yes"], "data.runs_at_pauses must be true or false, got 'yes'")])
def test_runs_at_pauses_refused_where_it_splits_nothing(tmp_path, capsys, extra, says):
    path = _easy(tmp_path / "one.TXT", 1, _values(1))
    refused(["run", f"data.path={path}", "data.test_fraction=0.3", "data.encoding=cp1252", ROLES,
             *extra,
             *FAST,
             f"out={tmp_path / 'out'}"], capsys, says)
    assert not (tmp_path / "out").exists()


def test_init_writes_runs_at_pauses_and_replay_equals_run(tmp_path, capsys):
    path = _week(tmp_path / "week17.txt")
    assert main(["init", str(path), "data.runs_at_pauses=true", f"out={tmp_path / 'init'}"]) == 0
    assert "runs_at_pauses: true" in (tmp_path / "init" / "conf" / "data" / "week17.yaml"
                                      ).read_text(encoding="utf-8")
    data = [f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=week17"]
    assert main(["run", *data, "model=lagbank", *FAST, f"out={tmp_path / 'out'}"]) == 0
    assert main(["replay", *data, f"replay.model={tmp_path / 'out' / 'model.pkl'}",
                 "promote.envelope.policy=off",        # (test 3 runs faster than the others)
                 "track=false", f"out={tmp_path / 'replay'}"]) == 0
    run = json.loads((tmp_path / "out" / "metrics.json").read_text())["targets"]
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())["targets"]
    for target in ("E_MCS_X1", "E_MCS_Z"):
        assert abs(replay[target]["rmse"] - run[target]["test"]["rmse"]) < 1e-9


@needs_cc
def test_the_compiled_stream_reads_a_catman_easy_file_as_the_reader_does(tmp_path):
    """Before: 'stream: line 8: input T_Luft: 'MX1609 Typ K' is no number' (the comments row
    under the units read as a sample)."""
    path = _easy(tmp_path / "Spindeltest_01.TXT", 1, _values(1))
    _compiled_stream_equals_its_pack(tmp_path, path, [
        f"data.path={path}", "data.encoding=cp1252", ROLES, "data.test_fraction=0.3",
        "data.reference=none"], rows=ROWS)


@needs_cc
def test_the_compiled_stream_restarts_each_appended_test_as_the_reader_splits_them(tmp_path):
    """Before: the raw UTF-16 file read as no header ('lacks input column T_air'); converted to
    UTF-8, its en-US dates refused (TC_SLASHED 0: the order was not looked for in a UTF-16
    file) and, given data.time, the three tests streamed as one (the held-out test's
    corrections off by the state the others left).  deploy71: the UTF-16 file as written (it
    was refused, 'convert the file to UTF-8 first (iconv ...)'), little- or big-endian, gives
    what its UTF-8 copy gives; two bytes that are no character are refused as the reader
    refuses them, naming the line and the bytes."""
    path = _week(tmp_path / "week17.txt")
    common = [f"data.path={path}", "data.runs_at_pauses=true", "data.test_fraction=0.34",
              "data.roles.error=['MCS*']"]
    _compiled_stream_equals_its_pack(tmp_path, path, common, rows=3 * ROWS, first=2 * ROWS)

    def streamed(data: bytes) -> subprocess.CompletedProcess:
        return subprocess.run([str(tmp_path / "code" / "stream")], input=data, capture_output=True)

    text = path.read_bytes().decode("utf-16")
    as_written = streamed(path.read_bytes())
    for other in (text.encode("utf-8"), codecs.BOM_UTF16_BE + text.encode("utf-16-be")):
        done = streamed(other)
        assert done.returncode == 0 and done.stdout == as_written.stdout, done.stderr
    lines = text.splitlines(keepends=True)
    lines[11] = lines[11][:5] + "\ud800" + lines[11][5:]          # a lone surrogate, line 12
    for name, data in (("surrogate", codecs.BOM_UTF16_LE + "".join(lines).encode(
            "utf-16-le", "surrogatepass")), ("odd", path.read_bytes()[:-1])):
        bad = tmp_path / f"{name}.txt"
        bad.write_bytes(data)
        with pytest.raises(ContractError) as reader:
            read_dataset(bad, {"runs_at_pauses": True, "test_fraction": 0.34, **AP_ROLES})
        said = str(reader.value).split(", ", 1)[1].split(" (")[0]   # 'line 12: bytes 1064-1065 ...'
        done = streamed(data)
        assert done.returncode == 2 and f"stream: {said} (".encode() in done.stderr, done.stderr
