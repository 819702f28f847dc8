"""A lab's data in, the last gaps (data88): ``connect.warm``'s log of several runs (LabVIEW
sessions appended to one file) warms the stream on the last, the campaign running when it was
logged (it was refused: "stream one run")."""

from __future__ import annotations

import copy
import re

import numpy as np
import pandas as pd
import pytest

from conftest import LIGHT, offline_connection
from test_data86b import STARTS, _gb_folder
from test_export import _compose
from test_stranger69 import ROWS, _lvm, _values
from thermocomp.core.io import ContractError
from thermocomp.core.io.stdin import TIME_ORIGIN
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import load_model
from thermocomp.shell.source import read_streamed
from thermocomp.shell.stages.connect import _warm_rows

HALF = ROWS // 2


@pytest.fixture(scope="module")
def fitted(tmp_path_factory):
    """An en-GB LabVIEW record (three runs), a lag bank fitted on it (a model with memory)."""
    root = tmp_path_factory.mktemp("data88")
    folder = _gb_folder(root / "runs")
    assert main(["init", str(folder), f"out={root / 'init'}"]) == 0
    common = [f"hydra.searchpath=[file://{root / 'init' / 'conf'}]", "data=runs",
              "model=lagbank", *LIGHT, "track=false"]
    assert main(["run", *common, f"out={root / 'run'}"]) == 0
    cfg = _compose(*common)
    ds, train_ids, _, _ = read_streamed(cfg, test=False)[:4]
    stream = deploy_stream(cfg, load_model(root / "run" / "model.pkl"),
                           {c: ds.campaigns[c] for c in train_ids})
    return root, common, stream


def _gb_lvm(path, start, values) -> str:
    """``values`` as an en-GB PC's LabVIEW writes them (dates day first) at ``path``: its text."""
    text = _lvm(path, start, values).read_bytes().decode("cp1252")
    text = re.sub(r"(\d{4})/(\d\d)/(\d\d)", r"\3/\2/\1", text)
    path.write_bytes(text.encode("cp1252"))
    return text


def test_connect_warm_on_a_log_of_two_sessions_warms_on_the_last(fitted, tmp_path, capsys):
    # before: "the LabVIEW Measurement File streamed holds 2 sessions ...: stream one run"
    # (exit 2): a VI that appends each run to one file leaves such a log at a restart
    root, common, stream = fitted
    earlier = _gb_lvm(tmp_path / "earlier.lvm", STARTS[1], _values(2))
    running = _gb_lvm(tmp_path / "running.lvm", STARTS[2], _values(3)[:HALF])
    _gb_lvm(tmp_path / "whole.lvm", STARTS[2], _values(3))
    (tmp_path / "log.lvm").write_bytes((earlier + "\r\n" + running).encode("cp1252"))
    frames = {name: _warm_rows(_compose(*common, f"connect.warm={tmp_path / name}"), stream)
              for name in ("running.lvm", "log.lvm", "whole.lvm")}
    assert ("the log holds 2 runs (sessions); the stream is warmed on the last"
            in capsys.readouterr().err)
    alone, logged = frames["running.lvm"], frames["log.lvm"]
    assert len(logged) == HALF
    np.testing.assert_array_equal(logged.to_numpy(float), alone.to_numpy(float))
    assert logged.attrs[TIME_ORIGIN] == alone.attrs[TIME_ORIGIN]
    # joined at the running campaign's sample HALF: corrections as the client that never stopped
    cols = list(stream.columns_) + (["time"] if "time" not in stream.columns_ else [])
    rows = frames["whole.lvm"][cols].to_numpy(float)

    def stepped(first, warm=None):
        conn = offline_connection(copy.deepcopy(stream), warm=warm)
        return np.array([conn._step("run3", list(r), k, k) for k, r in enumerate(rows)
                         if k >= first]), conn

    never_stopped, _ = stepped(0)
    resumed, conn = stepped(HALF, warm=logged)
    assert [e["event"] for e in conn.events][-1] == "warmed"
    np.testing.assert_allclose(resumed, never_stopped[HALF:], atol=1e-9)
    cold, _ = stepped(HALF)
    assert np.abs(cold - never_stopped[HALF:]).max() > 1e-3     # the warm-up matters here


def test_a_time_of_day_goes_in_by_the_fix_its_refusal_gives(tmp_path, capsys):
    # before: "... or set data.sample_period_s"; set, the same refusal again (the column still
    # read as the time): the fix given did not read the file.  (data88b: one that passes
    # midnight reads with no key, tests/shell/test_data88b.py; this one ends at 23:35)
    t = pd.date_range("2027-03-05 22:00", periods=20, freq="300s")
    rng = np.random.default_rng(1)
    temp = 20 + np.cumsum(rng.normal(0, 0.05, (20, 2)), axis=0)
    path = tmp_path / "night.csv"
    pd.DataFrame({"Time": t.strftime("%H:%M:%S"), "T_a": temp[:, 0], "T_b": temp[:, 1],
                  "E_X": 2 * temp[:, 0] - temp[:, 1]}).to_csv(path, index=False)
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 2
    err = capsys.readouterr().err
    fix = re.search(r"or leave it out and time the rows by their period, (\S+) (\S+)=<s>", err)
    assert fix is not None, err
    assert main(["init", str(path), f"out={tmp_path / 'init2'}", fix.group(1),
                 f"{fix.group(2)}=300"]) == 0, capsys.readouterr().err


def _catman(path, t0: str, rows: int = 30) -> None:
    """A catman AP ASCII export (TAB, ``.``, the channel header; T0 as the PC writes it)."""
    rng = np.random.default_rng(2)
    temp = 20 + np.cumsum(rng.normal(0, 0.05, rows))
    columns = [("Time  1 - default sample rate", "s", np.arange(rows) * 60.0),
               ("T Spindel", "°C", temp), ("Weg X", "µm", np.round(3 * (temp - 20), 3))]
    head = ["File:\tD:\\catman\\RUN.BIN", "Comment:\t", "catman Version:\tcatmanAP 5.6.1",
            f"Export:\t{t0}", f"Channels:\t{len(columns)}", ""]
    for k, (name, unit, _) in enumerate(columns, start=1):
        head += [f"Channel {k}:\t{name}", f"Unit:\t{unit}", "Comment:\t",
                 "Sample rate:\t0.01667", f"T0:\t{t0}", f"Length:\t{rows}", ""]
    lines = head + ["\t".join(c[0] for c in columns)]
    lines += ["\t".join(f"{c[2][i]:.3f}" for c in columns) for i in range(rows)]
    path.write_bytes(("\r\n".join(lines) + "\r\n").encode("cp1252"))


def test_a_catman_date_that_reads_the_same_either_way_asks_no_order(tmp_path, capsys):
    # before: T0 '05/05/2027 07:00:00' refused "day or month first?", though either answer
    # reads the 5th of May; a T0 that reads two ways is still refused, naming data.dayfirst
    _catman(tmp_path / "same.TXT", "05/05/2027 07:00:00")
    assert main(["init", str(tmp_path / "same.TXT"), f"out={tmp_path / 'init'}"]) == 0, \
        capsys.readouterr().err
    written = (tmp_path / "init" / "conf" / "data" / "same.yaml").read_text()
    assert "dayfirst" not in written           # no order taken: none carried to the model
    _catman(tmp_path / "either.TXT", "03/05/2027 07:00:00")
    assert main(["init", str(tmp_path / "either.TXT"), f"out={tmp_path / 'init2'}"]) == 2
    assert "data.dayfirst=true|false" in capsys.readouterr().err


def test_a_catman_folder_whose_dates_settle_nothing_is_refused_naming_its_files(tmp_path,
                                                                              capsys):
    # before: the first file's reader refused alone ("file T01.TXT, column 'T0', line 11: date
    # '03/05/2027 07:00:00' is day or month first?"): the user choosing was shown one date
    folder = tmp_path / "tests"
    folder.mkdir()
    for k, t0 in enumerate(("03/05/2027", "04/05/2027", "05/05/2027", "06/05/2027"), start=1):
        _catman(folder / f"T{k:02d}.TXT", f"{t0} 07:00:00")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 2
    err = capsys.readouterr().err
    assert "T01.TXT, column 'T0', line 11: date '03/05/2027 07:00:00' is day or month first?" in err
    assert "no file of the record settles it: the dates with slashes of 3 files read either way" in err
    assert "T01.TXT, T02.TXT, T04.TXT" in err           # T03's 05/05 reads one date either way
    assert "run 2027-05-03 to 2027-05-06 read day first, 2027-03-05 to 2027-06-05 month first" in err
    assert "data.dayfirst=true|false" in err
    assert main(["init", str(folder), f"out={tmp_path / 'init2'}", "data.dayfirst=true"]) == 0


def test_a_bad_cell_in_connect_warms_log_names_the_log_not_stdin(fitted, tmp_path):
    # before: "file <stdin>, column ...": the log is read as a stream is, and named so
    root, common, stream = fitted
    _gb_lvm(tmp_path / "log.lvm", STARTS[2], _values(3)[:HALF])
    text = (tmp_path / "log.lvm").read_bytes().decode("cp1252").splitlines()
    row = next(i for i, line in enumerate(text) if line[:1].isdigit()) + 3
    cells = text[row].split("\t")
    cells[1] = "#WERT"
    text[row] = "\t".join(cells)
    (tmp_path / "log.lvm").write_bytes("\r\n".join(text).encode("cp1252"))
    with pytest.raises(ContractError) as said:
        _warm_rows(_compose(*common, f"connect.warm={tmp_path / 'log.lvm'}"), stream)
    assert str(said.value).startswith(f"file {tmp_path / 'log.lvm'}, column ")
    assert "<stdin>" not in str(said.value)
