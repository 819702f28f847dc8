"""`thermocomp export` writes the conformance pack (feed61): per campaign the rows the code takes
(``check/<campaign>/rows.csv``: time and the code's inputs under contract names, in the
contract's units) and the corrections it must give (``expected.csv``: the served model's, as
``replay`` streams them); the compiled ``stream --check`` compares its output with them and
names the first row and target beyond the tolerance.  A record in a form ``stream.c`` does not
read (JSON Lines) goes in through the reader."""

from __future__ import annotations

import io
import json
import re
import subprocess

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, deployed_as_replay, refused
from test_export import StructuredText, _compose, _make_dataset, _trained, built_stream, needs_cc
from test_run_column52 import _long, _runs
from test_stream_units60 import _in_lab_units, dated_runs
from thermocomp.apps.deploy.streaming import replay
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import load_model
from thermocomp.shell.source import read_streamed

PLAIN = ("monitor.adaptive=false", "track=false")


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("check61") / "data")


def _checked(binary, campaign_folder) -> subprocess.CompletedProcess:
    with open(campaign_folder / "rows.csv", "rb") as rows:
        return subprocess.run([str(binary), "--check", str(campaign_folder / "expected.csv")],
                              stdin=rows, capture_output=True)


def _changed_coefficient(source: str) -> str:
    """``compensator.c`` with the last input coefficient of the last law's B0 row moved by a
    millionth of itself."""
    line = next(ln for ln in source.splitlines() if ln.startswith("static const double B0["))
    numbers = re.findall(r"-?\d+\.\d+(?:e[-+]?\d+)?", line.split("=", 1)[1])
    last = numbers[-1]
    changed = line[::-1].replace(last[::-1], repr(float(last) * (1 + 1e-6))[::-1], 1)[::-1]
    return source.replace(line, changed)


@needs_cc
def test_the_pack_is_replay_and_the_compiled_check_passes_and_names_a_changed_coefficients_row(
        dataset, tmp_path, capsys):
    # before: export wrote the code alone (no check/, no --check): what a lab's build must give
    # for given rows was nowhere
    model = _trained(dataset, tmp_path, "lagbank")
    out = tmp_path / "code"
    common = (f"data.path={dataset}", *PLAIN)
    assert main(["export", *common, f"export.model={model}", "export.format=c", f"out={out}"]) == 0
    pack = json.loads((out / "check" / "check.json").read_text())
    assert [e["campaign"] for e in pack["campaigns"]] == ["K05", "K06"]      # the test split
    tol_um, tol_rel = pack["tolerance_um"], pack["tolerance_relative"]
    assert 0 < tol_um <= 1e-6 and 0 < tol_rel <= 1e-6 and pack["why"]   # far below a machine's
    cfg = _compose(*common, "model=lagbank")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    stream = deploy_stream(cfg, load_model(model), {c: ds.campaigns[c] for c in train_ids})
    for c in test_ids:
        rows = pd.read_csv(out / "check" / c / "rows.csv")
        assert list(rows.columns) == ["time", *stream.compensator.inputs_]
        assert np.array_equal(rows.to_numpy(float), ds.campaigns[c][rows.columns].to_numpy(float))
        expected = pd.read_csv(out / "check" / c / "expected.csv")
        want = -replay(stream, ds.campaigns[c])[stream.targets_].to_numpy(float)
        assert list(expected.columns) == ["C_X", "C_Z"] and len(expected) == len(rows) == 40
        assert np.abs(expected.to_numpy(float) - want).max() <= 1e-12
    binary = built_stream(out)
    script = subprocess.run(["sh", "check/check.sh"], cwd=out, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr
    assert script.stderr.count("stream: check passed: 40 rows") == 2
    # one coefficient moved by a millionth: the first row beyond the tolerance is named
    (out / "compensator.c").write_text(_changed_coefficient((out / "compensator.c").read_text()))
    binary = built_stream(out)
    failed = _checked(binary, out / "check" / "K05")
    assert failed.returncode == 1, failed.stderr
    got = pd.read_csv(io.BytesIO(failed.stdout)).to_numpy(float)
    want = pd.read_csv(out / "check" / "K05" / "expected.csv").to_numpy(float)[:len(got)]
    off = ~(np.abs(got - want) <= tol_um + tol_rel * np.abs(want))
    assert off[-1].any() and not off[:-1].any()       # it stopped at the first row beyond
    row, target = len(got), ["C_X", "C_Z"][int(np.argmax(off[-1]))]
    assert target == "C_Z"                             # the law whose coefficient moved
    assert f"check failed at input line {row + 1} (row {row} of the stream): {target} = " \
        in failed.stderr.decode()
    # an unknown campaign is refused naming it; export.check=false writes no pack
    refused(["export", *common, f"export.model={model}", "export.campaigns=[K99]",
             f"out={tmp_path / 'none'}"], capsys, "export.campaigns names 'K99'", "'K01'")
    assert main(["export", *common, f"export.model={model}", "export.check=false",
                 f"out={tmp_path / 'bare'}"]) == 0
    assert not (tmp_path / "bare" / "check").exists()


def test_a_plc_harness_runs_the_packs_rows_through_the_structured_text_as_expected(dataset,
                                                                                   tmp_path):
    # the harness docs/to-the-machine.md describes: each row of rows.csv one call of
    # FB_ThermoComp (u in its order, reset on the first row), c against expected.csv (before: no
    # pack)
    model = _trained(dataset, tmp_path, "lagbank")
    out = tmp_path / "st"
    assert main(["export", f"data.path={dataset}", "track=false", f"export.model={model}",
                 "export.format=st", f"out={out}"]) == 0
    pack = json.loads((out / "check" / "check.json").read_text())
    assert not (out / "check" / "check.sh").exists()            # no stream to run
    for entry in pack["campaigns"]:
        fb = StructuredText((out / "compensator.st").read_text())
        rows = pd.read_csv(out / entry["folder"] / "rows.csv")
        want = pd.read_csv(out / entry["folder"] / "expected.csv").to_numpy(float)
        got = np.array([fb(row[1:], row[0], i == 0) for i, row in enumerate(rows.to_numpy(float))])
        assert len(got) == entry["rows"] == 40
        assert (np.abs(got - want) <= pack["tolerance_um"]
                + pack["tolerance_relative"] * np.abs(want)).all()


def _json_lines(path, runs: list[pd.DataFrame]):
    """The runs as a gateway's JSON Lines: one object a sample, the run number ``Lauf``."""
    lines = [json.dumps({"Lauf": k, **row}, ensure_ascii=False)
             for k, r in enumerate(runs, 1) for row in r.to_dict("records")]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


@needs_cc
def test_a_json_lines_record_in_lab_units_reaches_the_code_through_the_pack(tmp_path):
    # before: stream.c refused a JSON Lines file ("convert the file to CSV") and export wrote no
    # rows in the form it reads; the lab converted by hand (and its units: °F, K, mm, min)
    runs = _in_lab_units(_runs())
    path = _json_lines(tmp_path / "alle.jsonl", runs)
    common = (f"data.path={path}", "data.roles.error=[dX]", "data.roles.campaign=Lauf",
              "data.test_fraction=0.5", "track=false")
    assert main(["run", *common, "model=lagbank", *FAST, f"out={tmp_path / 'run'}"]) == 0
    out = tmp_path / "code"     # the default deployment: adaptive, its guard in the code
    assert main(["export", *common, f"export.model={tmp_path / 'run' / 'model.pkl'}",
                 "export.format=c", f"out={out}"]) == 0
    listed = json.loads((out / "check" / "check.json").read_text())["campaigns"]
    assert [(e["campaign"], e["rows"], e["cut"]) for e in listed] == [
        ("Lauf_3", 30, None), ("Lauf_4", 30, None)]
    rows = pd.read_csv(out / "check" / "Lauf_3" / "rows.csv")
    assert list(rows.columns) == ["time", "T_T0", "T_T1"]          # contract names and units
    lab = runs[2]
    assert np.allclose(rows["time"], lab["Zeit [min]"] * 60, rtol=0, atol=1e-9)
    assert np.allclose(rows["T_T0"], (lab["T0 [°F]"] - 32) * 5 / 9, rtol=0, atol=1e-9)
    assert np.allclose(rows["T_T1"], lab["T1 [K]"] - 273.15, rtol=0, atol=1e-9)
    binary = built_stream(out)
    for campaign in ("Lauf_3", "Lauf_4"):
        run = _checked(binary, out / "check" / campaign)
        assert run.returncode == 0, run.stderr
        assert b"check passed: 30 rows" in run.stderr


@needs_cc
def test_a_date_and_time_of_day_found_by_auto_are_joined_by_the_compiled_stream(tmp_path):
    # before: data.roles.time=auto joined them, export wrote code whose stream.c read the date
    # column as the time and refused every row ("a time of day alone" / "a date alone"); then
    # refused at export; stranger65: stream.c joins them, as the reader does
    from test_export import checked_pack

    runs = dated_runs()
    path = _long(tmp_path / "alle.csv", runs)
    common = (f"data.path={path}", "data.roles.error=[dX]", "data.roles.campaign=Lauf",
              "data.test_fraction=0.5")
    assert main(["run", *common, "model=lagbank", *FAST, f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, *PLAIN, "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    checked_pack(tmp_path / "code")
    done = subprocess.run([str(tmp_path / "code" / "stream")], input=path.read_bytes(),
                          capture_output=True)
    assert done.returncode == 0, done.stderr
    assert len(done.stdout.splitlines()) == sum(len(r) for r in runs) + 1


def test_a_campaign_is_cut_where_the_served_models_sensor_monitor_acts(dataset):
    # the monitor is not in the code: no build can give the served model's corrections once it
    # excludes a sensor; the pack stops before that row and says why (before: no pack)
    from thermocomp.apps.deploy.export import state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack
    from thermocomp.apps.deploy.report import stream_rows

    cfg = _compose(f"data.path={dataset}", "track=false", "monitor.adaptive=true", "model=mlr")
    deployed, ds, test_ids = deployed_as_replay(cfg)
    healthy, faulty = (ds.campaigns[c].reset_index(drop=True).copy() for c in test_ids)
    faulty.loc[len(faulty) // 2:, "T_b"] += 8.0            # one sensor leaves the others
    events = stream_rows(deployed, faulty, "K06").events
    excluded = [e for e in events if e.get("sensor") == "T_b" and e["to"] == "excluded"]
    assert excluded, events
    row = int(np.flatnonzero(faulty["time"].to_numpy() == excluded[0]["time"])[0]) + 1
    files, summary = conformance_pack(deployed, state_space(deployed),
                                      {"K05": healthy, "K06": faulty})
    assert [(e["campaign"], e["rows"], e["cut"]) for e in summary["campaigns"]] == [
        ("K05", 40, None),
        ("K06", row - 1, {"row": row, "why": "the served model's sensor monitor acted there, "
                                             "which is not in the code"})]
    assert files["check/K06/expected.csv"].count("\n") == row       # the header and row - 1 rows
