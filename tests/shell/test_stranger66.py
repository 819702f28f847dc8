"""What a stranger met on a twin-spindle turning centre's DAQ export (stranger66,
``bench_stranger66.py``); each test fails on the code before its mend.  Small files: a few hours
a run, not the bench's 40 h runs."""

from __future__ import annotations

import io
import json
import subprocess

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from conftest import FAST, refused
from test_export import needs_cc
from thermocomp.shell.cli import main

HEADERS = ["t [s]", "Air [degC]", "Bed [degC]", "Headstock 1 [degC]", "n1 [rpm]", "dZ1 [um]"]


def runs(count: int = 3, rows: int = 180) -> list[pd.DataFrame]:
    """Runs of a lathe at 60 s: the headstock warms with the speed, dZ1 follows it and the
    bed; each run's clock from 0."""
    out = []
    for k in range(count):
        rng = np.random.default_rng(66 + k)
        t = np.arange(rows) * 60.0
        speed = np.repeat(rng.integers(8, 36, rows // 30 + 1) * 100.0, 30)[:rows]
        head = 20 + np.cumsum(speed / 3500 - (np.arange(rows) > 0) * 0.004 * k) * 0.05
        bed = 20 + 0.3 * np.sin(t / 7000 + k) + rng.normal(0, 0.02, rows)
        air = 21 + 0.5 * np.sin(t / 9000) + rng.normal(0, 0.02, rows)
        dz = 6.0 * (head - head[0]) - 2.0 * (bed - bed[0]) + rng.normal(0, 0.2, rows)
        out.append(pd.DataFrame(dict(zip(HEADERS, [t, air, bed, head, speed, dz]))))
    return out


def daq_file(frame: pd.DataFrame, k: int) -> str:
    """As the lab's DAQ script writes a run: a ``#`` comment block, the header a comment line
    too, TAB-separated with a trailing TAB on every line."""
    head = ["# TC-2 thermal test", "# instrument: DAQ970A", f"# run: {k + 1:02d}",
            "# start: 2027-03-08 06:00:00", "# sample period: 60 s", "#",
            "# " + "\t".join(frame.columns) + "\t"]
    rows = ["\t".join(f"{v:.3f}" for v in row) + "\t" for row in frame.to_numpy()]
    return "\n".join(head + rows) + "\n"


def folders(tmp_path):
    """The runs as the DAQ wrote them, and as a plain CSV export of the same numbers."""
    daq, plain = tmp_path / "daq", tmp_path / "plain"
    daq.mkdir()
    plain.mkdir()
    for k, frame in enumerate(runs()):
        (daq / f"TC2_run{k + 1:02d}.txt").write_text(daq_file(frame, k))
        frame.to_csv(plain / f"TC2_run{k + 1:02d}.csv", index=False, float_format="%.3f")
    return daq, plain


ROLES = ["data.roles.error=[dZ1]", "data.roles.state=[n1]", "data.test_fraction=0.34"]


@pytest.fixture(scope="module")
def plain_run(tmp_path_factory) -> dict:
    """``run`` of the plain CSV export of :func:`runs` (the same numbers in every test): its
    ``metrics.json`` targets, made once for the two tests that compare a DAQ file's run to it."""
    root = tmp_path_factory.mktemp("stranger66")
    _, plain = folders(root)
    assert main(["run", f"data.path={plain}", *ROLES, *FAST, "plots=none", f"out={root / 'out'}"]) == 0
    return json.loads((root / "out" / "metrics.json").read_text())["targets"]


def test_a_header_written_as_a_comment_under_a_comment_block_is_read(tmp_path, plain_run):
    # before: the header line '# t [s]<TAB>Air [degC]...' was read with its '#', and the time
    # column '# t [s]' refused: "1 column(s) not read: '# t [s]': unit 's' is not a
    # temperature's"; now read as the plain export of the same numbers is
    daq, _ = folders(tmp_path)
    assert main(["run", f"data.path={daq}", *ROLES, *FAST, "plots=none",
                 f"out={tmp_path / 'out-daq'}"]) == 0
    got = json.loads((tmp_path / "out-daq" / "metrics.json").read_text())["targets"]
    want = plain_run
    assert list(got) == list(want) == ["E_dZ1"]
    assert got["E_dZ1"]["test"]["rmse"] == pytest.approx(want["E_dZ1"]["test"]["rmse"], rel=1e-12)
    # a sample counter headed '#' is no comment: the header is read as written
    frame = runs(count=1)[0]
    frame.insert(0, "#", np.arange(len(frame)))
    path = tmp_path / "counted.csv"
    frame.to_csv(path, index=False)
    assert main(["ingest", f"data.path={path}", "data.roles.error=[dZ1]",
                 "data.roles.state=[n1]", "data.roles.ignore=['#']", "data.test_fraction=0.3",
                 f"out={tmp_path / 'counted'}"]) == 0


def test_a_comment_header_streams_on_stdin_as_the_file_reads(tmp_path, monkeypatch, capsys):
    # before: the test run as the DAQ wrote it, piped into `monitor monitor.input=-`, was read
    # with its '# t [s]' header (the time column not found), and the block written again mid-run
    # as values; now as the campaign file streams
    daq, plain = folders(tmp_path)
    args = [f"data.path={plain}", *ROLES, *FAST, "model=lagbank"]
    assert main(["monitor", *args, f"out={tmp_path / 'file'}"]) == 0
    lines = sorted(daq.glob("*.txt"))[-1].read_text().splitlines(keepends=True)
    test = "".join(lines[:7 + 100] + lines[:7] + lines[7 + 100:])   # its block again mid-run
    monkeypatch.setattr("sys.stdin", io.StringIO(test))
    assert main(["monitor", *args, "monitor.input=-", f"out={tmp_path / 'piped'}"]) == 0
    capsys.readouterr()
    from_file = json.loads((tmp_path / "file" / "monitor.json").read_text())["targets"]
    piped = json.loads((tmp_path / "piped" / "monitor.json").read_text())["targets"]
    assert piped["E_dZ1"]["rmse_fixed"] == pytest.approx(from_file["E_dZ1"]["rmse_fixed"],
                                                         rel=1e-9)


@needs_cc
def test_the_compiled_stream_reads_the_time_of_a_comment_header(tmp_path):
    # before: stream.c took the DAQ file's header '# t [s]' for no time column ("samples taken
    # one period apart"): after a sample not taken its lags ran a period behind the model's; and
    # refused the DAQ's block written again ("row 101 has not 7 cells")
    daq, plain = folders(tmp_path)
    code = tmp_path / "c"
    args = [f"data.path={plain}", *ROLES, *FAST]
    assert main(["run", *args, "model=lagbank", "plots=none", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *args, f"export.model={tmp_path / 'run' / 'model.pkl'}",
                 "export.format=c", f"out={code}"]) == 0
    compiled(code)
    lines = sorted(daq.glob("*.txt"))[-1].read_text().splitlines(keepends=True)
    del lines[7 + 60]                                    # a sample not taken: 120 s apart
    # and the DAQ's block and header written again (a restart), left out as the reader does
    as_daq = "".join(lines[:7 + 100] + lines[:7] + lines[7 + 100:])
    as_csv = "".join(ln.lstrip("# ").replace("\t\n", "\n").replace("\t", ",")
                     for ln in lines[6:])
    # and an input's name first in the comment header (the header found by naming every input)
    moved = "".join(ln if ln.startswith("#") and not ln.startswith("# t [s]") else
                    "\t".join([ln.split("\t")[1], ln.split("\t")[0], *ln.split("\t")[2:]])
                    for ln in lines[:7 + 100] + lines[7 + 100:])
    moved = moved.replace("Air [degC]\t# t [s]", "# Air [degC]\tt [s]", 1)
    assert "\n# Air [degC]\tt [s]\tBed" in moved
    out = [subprocess.run([str(code / "stream")], input=text, text=True, capture_output=True,
                          check=True) for text in (as_daq, as_csv, moved)]
    got, want, swapped = (pd.read_csv(io.StringIO(o.stdout)).to_numpy(float) for o in out)
    assert got.shape == want.shape == (179, 1) and np.abs(got - want).max() <= 1e-12
    assert np.abs(swapped - want).max() <= 1e-12
    assert "no time column" not in out[0].stderr + out[1].stderr + out[2].stderr


def test_a_last_line_cut_off_while_written_is_refused_saying_so(tmp_path, capsys):
    # before: "file ..., line 188 (data row 180): expected 7 fields, got 3" -- right, but not
    # why nor what to do; now it names the last line, cut off, and says to delete it
    daq, _ = folders(tmp_path)
    last = sorted(daq.glob("*.txt"))[1]
    text = last.read_text()
    body = text[:-1]
    last.write_text(body[:body.rindex("\n") + 1 + 20])        # the DAQ stopped mid-row
    line = refused(["run", f"data.path={daq}", *ROLES, *FAST, "plots=none",
                    f"out={tmp_path / 'out'}"], capsys, str(last), "line 187 (data row 180)",
                   "last line holds 3 of its 7 fields", "cut off", "delete that line")
    assert "expected 7 fields" not in line
    assert not (tmp_path / "out" / "metrics.json").exists()


# --- a diagnosed model of a record without an air sensor (nor a manifest ambient_c) -----------

def _without_ambient(root):
    """The door machine of test_export_effects59, its air sensor not named an ambient one (T_amb
    -> T_air) and without the manifest's ambient_c: what the turning centre's lab gave ('Air')."""
    from test_export_effects59 import _door

    data = _door(root)
    for path in data.glob("K*.csv"):
        pd.read_csv(path).rename(columns={"T_amb": "T_air"}).to_csv(path, index=False)
    manifest = pd.read_csv(data / "campaigns.csv").drop(columns="ambient_c")
    manifest.to_csv(data / "campaigns.csv", index=False)
    return data


@pytest.mark.parametrize("effect", [
    {"kind": "dynamics", "transform": "first_order_lag", "column": "T_a", "tau_s": 3600.0,
     "initial_state": ["T_a", "T_b"], "initial_directions": 2},
    {"kind": "signal", "transform": "first_order_lag", "column": "S_door", "tau_s": 600.0}],
    ids=["initial-state", "plain-lag"])
def test_a_diagnosed_model_without_an_ambient_streams_and_exports_as_it_runs(tmp_path, effect):
    # before: every diagnosed model (any effect) declared the campaign's initial ambient, and
    # without an air sensor or a manifest ambient_c its stream refused the first row ("the model
    # needs the campaign's initial ambient temperature"): diagnose's deployed "after" was the
    # error uncompensated (147.55 µm against run's 1.61 on the turning centre), replay exited 2
    # and the C refused each campaign; the lag's initial state reads A0 where it is known and
    # the mean of its sensors' first values else, in batch, and now in the stream, the C and
    # the Structured Text
    from test_export import _compiled, _stdin, _streamed
    from test_export_auto57 import StructuredText
    from test_export_diagnosed59 import _diagnosed
    from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
    from thermocomp.apps.deploy.streaming import replay

    stream, tests, comp = _diagnosed(_without_ambient(tmp_path / "data"), [effect])
    streamed = [replay(stream, df) for df in tests]
    expected = np.vstack([-s[stream.targets_].to_numpy(float) for s in streamed])
    assert np.isfinite(expected).all() and np.abs(expected).max() > 1.0
    # where no input leaves the envelope, the stream is the batch model (run's figure)
    plain = [df.iloc[:len(df) // 2 - 1] for df in tests]
    for df in plain:
        batch = comp.predict({"test": df})["test"]
        assert np.allclose(replay(stream, df)[stream.targets_].to_numpy(float),
                           batch[stream.targets_].to_numpy(float), atol=1e-9, rtol=0)
    got = _streamed(_compiled(stream, tmp_path), _stdin(stream, tests)).to_numpy(float)
    assert np.abs(got - expected).max() <= 1e-9
    sim, rows, st = Simulator(state_space(stream)), [], []
    fb = StructuredText(exported_files(stream, "st")["compensator.st"])
    for df in tests:
        sim.reset()
        for k, (u, t) in enumerate(zip(df[stream.columns_].to_numpy(float), df["time"])):
            rows.append(sim.step(u, t))
            st.append(fb(u, t, k == 0))
    assert np.abs(np.array(rows) - expected).max() <= 1e-9
    assert np.abs(np.array(st) - expected).max() <= 1e-9


def test_a_comment_block_written_again_with_its_header_is_left_out(tmp_path, capsys, plain_run):
    # before: a DAQ restarted mid-run writes its '#' block (another start time) and its header
    # again: the header was left out, the '#' lines above it refused "expected 7 fields, got 1";
    # now left out with it, and the run reads as the plain export of its numbers
    daq, _ = folders(tmp_path)
    path = sorted(daq.glob("*.txt"))[0]
    lines = path.read_text().splitlines(keepends=True)
    block = [ln.replace("06:00:00", "09:17:00") for ln in lines[:7]]
    path.write_text("".join(lines[:7 + 90] + block + lines[7 + 90:]))
    assert main(["run", f"data.path={daq}", *ROLES, *FAST, "plots=none",
                 f"out={tmp_path / 'out-daq'}"]) == 0
    assert f"{path}, line 98: the file's header written again" in capsys.readouterr().err
    got = json.loads((tmp_path / "out-daq" / "metrics.json").read_text())["targets"]
    want = plain_run
    assert got["E_dZ1"]["test"]["rmse"] == pytest.approx(want["E_dZ1"]["test"]["rmse"], rel=1e-12)
    assert got["E_dZ1"]["train"]["rmse"] == pytest.approx(want["E_dZ1"]["train"]["rmse"],
                                                          rel=1e-12)


def test_a_diagnosed_model_without_an_ambient_monitors_a_stdin_stream(tmp_path, monkeypatch,
                                                                     capsys):
    # before: `monitor monitor.input=-` of such a model asked for monitor.ambient_c ("the model
    # reads each campaign's ambient from the manifest's ambient_c"); it streams as the file does
    data = _without_ambient(tmp_path / "data")
    conf = tmp_path / "conf" / "model"
    conf.mkdir(parents=True)
    (conf / "diag66.yaml").write_text(
        "name: mlr+diagnosed\nestimator:\n  _target_: thermocomp.apps.diagnose.AugmentedRegressor\n"
        "  _convert_: all\n  reference: first_sample\n  effects:\n    E_X:\n"
        "    - {kind: dynamics, transform: first_order_lag, column: T_a, tau_s: 3600.0,\n"
        "       initial_state: [T_a, T_b], initial_directions: 2}\n"
        "  estimator: {_target_: thermocomp.core.models.linear.MLR, fit_intercept: true}\n")
    args = [f"hydra.searchpath=[file://{tmp_path / 'conf'}]", f"data.path={data}",
            "model=diag66", *FAST]
    assert main(["run", *args, "plots=none", f"out={tmp_path / 'run'}"]) == 0
    model = f"monitor.model={tmp_path / 'run' / 'model.pkl'}"
    assert main(["monitor", *args, model, f"out={tmp_path / 'file'}"]) == 0
    first = pd.read_csv(data / "campaigns.csv").query("split == 'test'")["file"].iloc[0]
    monkeypatch.setattr("sys.stdin", io.StringIO((data / first).read_text()))
    assert main(["monitor", *args, model, "monitor.input=-", f"out={tmp_path / 'piped'}"]) == 0
    capsys.readouterr()
    from_file = json.loads((tmp_path / "file" / "monitor.json").read_text())
    piped = json.loads((tmp_path / "piped" / "monitor.json").read_text())["targets"]
    fixed = [r["rmse_fixed"] for r in piped.values()]
    assert np.isfinite(fixed).all() and min(fixed) > 0
    assert set(piped) == set(from_file["targets"])
