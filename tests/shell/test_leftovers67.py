"""Issue 34's follow-ups left by stop 66 (leftovers67), each a defect shown on the old code.

1. A ``#`` comment line among the rows (a lab's logger writing ``# marker: tool change``
   mid-run): the file reader refused it ("expected 7 fields, got 1"), a stream left out every
   ``#`` line under a commented header or under any unit row, unsaid.  One rule now
   (``core/io/again.py``): in a file that writes ``#`` comments (its preamble, or its header)
   such a line is left out and said by its line, file and stream alike; in a file that writes
   none, a ``#`` line of another width is refused by both, in the same words.
2. stream.c's messages counted rows from the header: a file with a preamble was named lines off
   the reader's ``line N (data row n)``; and it left a ``#`` line out only under a commented
   header.
3. A volumetric export cut by the end of logging while a cycle was measured: that last cycle
   refused the whole record; now left out, said (mid-record still refused).
4. The bench scenarios (``edm65``, ``tsc66``, ``portal64``, ``trunnion63``) declare their
   parameters once (:class:`~thermocomp.apps.sim.scenario.DeclaredScenario`).
"""

from __future__ import annotations

import io
import json
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from conftest import FAST, refused
from test_export import needs_cc
from test_stranger66 import ROLES, folders
from test_volstranger66 import calibrated, lab_files, raw  # noqa: F401 (a fixture)
from thermocomp.shell.cli import main

# -- 1. a '#' comment among the rows ------------------------------------------------------------

BENCHMARKS = Path(__file__).resolve().parents[2] / "benchmarks"
MARK = "# marker: tool change\n"


def _marked(path, at: int) -> str:
    """``path``'s text with the logger's note before its line ``at + 1``."""
    lines = path.read_text().splitlines(keepends=True)
    return "".join(lines[:at] + [MARK] + lines[at:])


@pytest.fixture(scope="module")
def plain_run(tmp_path_factory):
    """``(out, daq, plain)``: a lag bank run on the plain export of the DAQ's runs, made once: the
    comment test compares the marked DAQ file's run with it, lab_stream exports it."""
    tmp_path = tmp_path_factory.mktemp("leftovers67c")
    daq, plain = folders(tmp_path)
    out = tmp_path / "run"
    assert main(["run", f"data.path={plain}", *ROLES, *FAST, "model=lagbank", "plots=none",
                 f"out={out}"]) == 0
    return out, daq, plain


def test_a_comment_among_the_rows_of_a_commented_file_is_left_out_by_file_and_stream(
        plain_run, tmp_path, monkeypatch, capsys):
    # before: the file reader refused the DAQ's run ("line 108 (data row 101): expected 7
    # fields, got 1"); the stream left it out, unsaid; now both leave it out and say its line
    daq, plain = folders(tmp_path)
    test = sorted(daq.glob("*.txt"))[-1]
    marked = _marked(test, 7 + 100)
    args = [*ROLES, *FAST, "model=lagbank"]
    test.write_text(marked)
    assert main(["run", f"data.path={daq}", *args, "plots=none", f"out={tmp_path / 'out-daq'}"]) == 0
    said = "line 108: a '#' comment among the rows (the file writes '#' comments"
    assert f"{test}, {said}" in capsys.readouterr().err
    got, want = (json.loads((out / "metrics.json").read_text())["targets"]["E_dZ1"]
                 for out in (tmp_path / "out-daq", plain_run[0]))    # (plain_run: the same run)
    for split in ("train", "test"):
        assert got[split]["rmse"] == pytest.approx(want[split]["rmse"], rel=1e-12)
    monitor = ["monitor", f"data.path={plain}", *args]
    assert main([*monitor, f"out={tmp_path / 'file'}"]) == 0
    monkeypatch.setattr("sys.stdin", io.StringIO(marked))
    assert main([*monitor, "monitor.input=-", f"out={tmp_path / 'piped'}"]) == 0
    assert f"<stdin>, {said}" in capsys.readouterr().err
    from_file, piped = (json.loads((tmp_path / name / "monitor.json").read_text())["targets"]
                        for name in ("file", "piped"))
    assert piped["E_dZ1"]["rmse_fixed"] == pytest.approx(from_file["E_dZ1"]["rmse_fixed"],
                                                         rel=1e-9)


@pytest.mark.parametrize("units", [False, True], ids=["plain", "unit-row"])
def test_a_hash_line_in_a_file_without_comments_is_refused_alike_by_file_and_stream(
        tmp_path, monkeypatch, capsys, units):
    # before: the file reader said "expected 6 fields, got 1" (not what the line is); the stream
    # said "non-numeric value" in column 'time', or, under a unit row, left the line out unsaid
    _, plain = folders(tmp_path)
    test = sorted(plain.glob("*.csv"))[-1]
    if units:
        lines = test.read_text().splitlines(keepends=True)
        test.write_text("".join([lines[0].replace(" [s]", "").replace(" [degC]", "")
                                 .replace(" [rpm]", "").replace(" [um]", ""),
                                 "s,degC,degC,degC,rpm,um\n", *lines[1:]]))
    marked = _marked(test, 101 + units)
    line = f"line {102 + units}"
    said = "expected 6 fields, got 1: a '#' line among the rows, of other than the header's width"
    stream = ["monitor", f"data.path={plain}", *ROLES, *FAST, "model=lagbank",
              "monitor.input=-", f"out={tmp_path / 'piped'}"]
    monkeypatch.setattr("sys.stdin", io.StringIO(marked))
    refused(stream, capsys, f"file <stdin>, {line}: {said}")
    test.write_text(marked)
    refused(["run", f"data.path={plain}", *ROLES, *FAST, "plots=none", f"out={tmp_path / 'run'}"],
            capsys, f"file {test}, {line} (data row 101): {said}")


# -- 1 and 2. the compiled stream: a '#' comment among the rows; the file's own line numbers -------

@pytest.fixture(scope="module")
def lab_stream(plain_run):
    """``(stream, daq, plain)``: ``stream`` compiled from plain_run's lag bank (its lags read the
    time)."""
    run, daq, plain = plain_run
    args = [f"data.path={plain}", *ROLES, *FAST]
    code = run.parent / "c"
    assert main(["export", *args, f"export.model={run / 'model.pkl'}",
                 "export.format=c", "export.check=false", f"out={code}"]) == 0
    compiled(code)
    return code / "stream", daq, plain


def _streamed(stream, text: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(stream)], input=text, text=True, capture_output=True)


@needs_cc
def test_the_compiled_stream_leaves_a_comment_out_of_a_file_that_writes_them(lab_stream):
    # before: "row 102 has not 7 cells" (file line 108) where the '#' block is above a header
    # not itself a comment (only a commented header's '#' lines were left out); now left out,
    # as the reader leaves it out, and said
    stream, daq, plain = lab_stream
    csv = sorted(plain.glob("*.csv"))[-1]
    want = _streamed(stream, csv.read_text())
    assert want.returncode == 0 and len(want.stdout.splitlines()) == 1 + 180
    lines = sorted(daq.glob("*.txt"))[-1].read_text().splitlines(keepends=True)
    for header in (lines[6], lines[6].removeprefix("# ")):
        text = "".join(lines[:6] + [header] + lines[7:7 + 100] + [MARK] + lines[7 + 100:])
        got = _streamed(stream, text)
        assert got.returncode == 0 and got.stdout == want.stdout, got.stderr
        assert "stream: line 108: a '#' comment among the rows" in got.stderr
    # in a file that writes no comment: refused, saying what the line is
    got = _streamed(stream, _marked(csv, 1 + 100))
    assert got.returncode == 2
    assert "stream: line 102 has not 6 cells: a '#' line among the rows: a comment?" in got.stderr


@needs_cc
def test_the_compiled_stream_leaves_a_block_of_comments_under_the_rows_out(lab_stream):
    # (stranger75) before: "line 182 has not 6 cells: a '#' line among the rows" -- a logger's
    # run summary under the rows of a file that writes no comment, which the reader leaves out
    stream, _, plain = lab_stream
    text = sorted(plain.glob("*.csv"))[-1].read_text()
    want = _streamed(stream, text)
    block = "# --- run summary ---\n# samples: 180\n\n# note: run 6, mandrel 300 mm, checked\n"
    got = _streamed(stream, text + block)
    assert got.returncode == 0 and got.stdout == want.stdout, got.stderr
    assert "stream: lines 182-185: a '#' block under the rows (a logger's summary): left out" in got.stderr
    lines = text.splitlines(keepends=True)        # a row after it: refused at the '#' line
    got = _streamed(stream, "".join(lines[:-1]) + block + lines[-1])
    assert got.returncode == 2
    assert "stream: line 181 has not 6 cells: a '#' line among the rows: a comment?" in got.stderr


@needs_cc
def test_the_compiled_stream_names_the_files_own_line_as_the_reader_does(lab_stream, tmp_path,
                                                                         capsys):
    # before: the rows were counted from the header ("row 21: input T_Bed: 'n.v.' is no
    # number"); the reader names the file's line 23 (a logger's two lines above the header)
    stream, _, plain = lab_stream
    rows = sorted(plain.glob("*.csv"))[-1].read_text().splitlines(keepends=True)
    cells = rows[20].split(",")
    rows[20] = ",".join([*cells[:2], "n.v.", *cells[3:]])
    text = "".join(["Logger: TC-2\n", "Operator: lab\n", *rows])
    got = _streamed(stream, text)
    assert got.returncode == 2 and "stream: line 23: input T_Bed: 'n.v.' is no number" \
        in got.stderr, got.stderr
    lab = tmp_path / "lab.csv"
    lab.write_text(text)
    refused(["run", f"data.path={lab}", *ROLES, *FAST, "plots=none", f"out={tmp_path / 'r'}"],
            capsys, "line 23 (data row 20)")


# -- 3. a volumetric export cut while a cycle was measured ---------------------------------------

def _half_measured(folder, campaign: str, row: int) -> int:
    """The cycle at 0-based ``row`` (negative: from the end) of ``campaign``'s file with the
    distances of its last half of the poses empty (an export cut while it was measured);
    returns its data row."""
    f = folder / f"{campaign}.csv"
    df = pd.read_csv(f, sep=";", decimal=",")
    e = [c for c in df.columns if c.startswith("E_")]
    poses = list(dict.fromkeys(c.split("_")[1] for c in e))
    late = [c for c in e if c.split("_")[1] in poses[len(poses) // 2:]]
    df.loc[df.index[row], late] = np.nan
    df.to_csv(f, sep=";", decimal=",", index=False, float_format="%.6f")
    return int(df.index[row]) + 1


def test_a_trailing_half_measured_cycle_is_left_out_saying_so_one_mid_record_refused(
        raw, tmp_path, capsys):  # noqa: F811
    # before: calibrate, run and ingest refused the whole record ("data row 7: campaign
    # validation_week: 100 of the 200 distances measured in this cycle ... cannot identify the
    # parameters: measure its poses again or drop the row"); now that last cycle is left out,
    # said, and the record calibrates as with the row deleted
    cut, dropped = tmp_path / "cut", tmp_path / "dropped"
    lab_files(raw, cut, unit_mm=True)
    lab_files(raw, dropped, unit_mm=True)
    row = _half_measured(cut, "validation_week", -1)
    f = dropped / "validation_week.csv"
    df = pd.read_csv(f, sep=";", decimal=",", dtype=str)
    df.iloc[:-1].to_csv(f, sep=";", index=False)
    got, want = calibrated(cut, tmp_path / "out_cut"), calibrated(dropped, tmp_path / "out_dropped")
    said = capsys.readouterr().err
    assert f"{cut / 'validation_week.csv'}, data row {row}: campaign validation_week's last cycle" \
        in said and "left out" in said
    assert list(got) == list(want)
    for cid in want:
        assert np.array_equal(got[cid].to_numpy(float), want[cid].to_numpy(float), equal_nan=True)
    report = json.loads((tmp_path / "out_cut" / "calibration.json").read_text())
    assert report["cut_cycles"]["validation_week"]["row"] == row
    assert report["n_cycles"] == sum(len(df) for df in want.values())
    # the stages: evaluate validates the ingested series against the distances without it
    common = ["experiment=volumetric_large_mill", f"data.path={cut}", f"data.interim={tmp_path / 'i'}",
              f"model_path={tmp_path / 'model.pkl'}", *FAST, "data.targets=[E_ZZ1,E_XZ1]"]
    assert main(["ingest", *common]) == 0 and main(["train", *common]) == 0
    assert main(["evaluate", *common, f"out={tmp_path / 'staged'}"]) == 0
    staged = json.loads((tmp_path / "staged" / "metrics.json").read_text())["volumetric"]
    assert main(["run", *common, f"out={tmp_path / 'run'}"]) == 0
    whole = json.loads((tmp_path / "run" / "metrics.json").read_text())["volumetric"]
    assert staged["distance_error"]["rms_after"] == pytest.approx(
        whole["distance_error"]["rms_after"], rel=1e-9)
    # one so measured before a campaign's last: still refused, naming its row
    mid = tmp_path / "mid"
    lab_files(raw, mid, unit_mm=True)
    row = _half_measured(mid, "validation_week", -2)
    refused(["calibrate", f"data.path={mid}", f"out={tmp_path / 'out_mid'}", "track=false"],
            capsys, f"data row {row}: campaign validation_week:", "cannot identify the parameters")


# -- 4. a bench scenario declares its parameters once ---------------------------------------------

def test_a_scenario_declares_its_parameters_once(monkeypatch):
    # before: each bench scenario spelled an __init__ of the measurement chain's parameters and a
    # super().__init__ call (get_params read its signature); now its fields are the one list
    # the constructor, the config's key check and the truth's params come from (the 77 files
    # of the four stranger benches' `write` byte-identical before and after)
    from thermocomp.apps.sim.scenario import CHAIN, DeclaredScenario
    from thermocomp.base.errors import ConfigError
    from thermocomp.shell.build import build

    monkeypatch.syspath_prepend(str(BENCHMARKS))
    from edm65 import Edm65
    from portal64 import Portal64

    gen = Edm65(days=1, sample_period_s=600.0, error_noise_um=0.3, seed=5)
    assert isinstance(gen, DeclaredScenario)
    params = gen.get_params()
    assert list(params) == ["days", "sample_period_s", *CHAIN]
    assert (params["days"], params["error_noise_um"], params["seed"]) == (1, 0.3, 5)
    assert gen.generate()[1]["params"] == params
    # a chain default the scenario changes keeps the chain's place; its own parameters first
    assert list(Portal64().get_params())[:6] == ["weeks", "one_record", "sample_period_s",
                                                 "error_period_s", "error_gaps", CHAIN[0]]
    assert Portal64().error_noise_um != Edm65().error_noise_um
    with pytest.raises(TypeError):            # keywords only: no positional order to misread
        Edm65(1, 600.0)
    monkeypatch.setenv("THERMOCOMP_TARGETS", "edm65.")
    with pytest.raises(ConfigError, match=r"sim.generator.dayz: .*did you mean sim.generator.days"):
        build({"_target_": "edm65.Edm65", "dayz": 1}, "sim.generator")
