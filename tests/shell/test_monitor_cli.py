"""`thermocomp monitor` end to end: simulated sensor faults through the CLI, and hostile input.

The fault tests run the real commands (in process: ``conftest.cli``, the process boundary is
not their point): ``simulate`` with the ``sensor_faults``
effect on the most influential sensor of the default MLR model, then ``monitor``,
and compare ``monitor.json`` with the simulation's truth and with the monitor of
the same simulation without the fault (the same seed: the healthy reading is
paired with the faulty one sample by sample).
"""

from __future__ import annotations

import io
import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hydra.utils import instantiate
from omegaconf import OmegaConf

from conftest import ROOT, cli, influence, refused
from covering import covering
from thermocomp.core import io as tio
from thermocomp.core.compensator import Compensator
from thermocomp.shell.cli import main

KINDS = ("jump", "dropout", "spike_ref", "freeze", "drift")
AT_ONCE = ("jump", "dropout", "spike_ref")     # observable at the onset itself
LAG = 10                                        # samples allowed between observable and reported
FAULT = "sim.generator.effect_params.sensor_faults"


# scenario x kind, the cross product both fault tests below share (the same ``assert_caught``):
# make test keeps its covering set (tests/covering.py), so every kind and both scenarios run
# there, and dropout on the default scenario, whose test adds its own assertions (the missing
# counts); ids as the tests' own (``test[kind]``)
FAULT_TESTS = {
    "default": "test_a_simulated_fault_on_the_most_influential_sensor_is_caught_bounded_and_compensated",
    "swiss": "test_a_simulated_fault_on_the_swiss_lathe_is_caught_bounded_and_compensated"}
SCENARIO_KINDS = covering("the same assert_caught on the other scenario", keep=[("default", "dropout")],
                          join=lambda ids: f"{FAULT_TESTS[ids[0]]}[{ids[1]}]",
                          scenario=list(FAULT_TESTS), kind=KINDS)


def kinds_on(scenario: str) -> list:
    """:data:`SCENARIO_KINDS` of ``scenario``, by kind."""
    return [pytest.param(p.values[1], marks=p.marks, id=p.values[1])
            for p in SCENARIO_KINDS if p.values[0] == scenario]


# -- helpers ----------------------------------------------------------------------------------
def most_influential(path: Path) -> str:
    """The sensor whose reading moves the default MLR model's test correction most per °C:
    every sample after the first raised by 1 °C (a constant offset is removed by the reference
    sample, so it would move nothing)."""
    ds, _ = tio.read_dataset(path)
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    comp = Compensator(instantiate(OmegaConf.load(ROOT / "conf/model/mlr.yaml").estimator)).fit(train)
    effect = influence(comp, test)
    return max(effect, key=effect.get)


def run_monitor(path: Path, out: Path, *extra: str) -> dict:
    cli("monitor", f"data.path={path}", f"out={out}", "track=false", *extra)
    return json.loads((out / "monitor.json").read_text())


def simulate_fault(path: Path, kind: str, column: str, *extra: str) -> dict:
    """Simulate with the fault; its truth per affected campaign."""
    cli("simulate", f"data.path={path}", "track=false", "sim.generator.effects=[sensor_faults]",
               f"{FAULT}.kind={kind}", f"{FAULT}.column={column}", *extra)
    truth = json.loads(path.with_name(path.name + ".truth.json").read_text())
    return {c: t["effects"]["sensor_faults"] for c, t in truth["campaigns"].items()
            if "sensor_faults" in t.get("effects", {})}


def campaign_files(path: Path) -> dict[str, pd.DataFrame]:
    index = pd.read_csv(path / "campaigns.csv")
    return {c: pd.read_csv(path / f) for c, f in zip(index["campaign"], index["file"])}


def fault_check(healthy_path: Path, healthy: dict, faulty_path: Path, faults: dict,
                report: dict, sensor: str) -> dict:
    """What the acceptance looks at, per affected campaign and per target (numbers only)."""
    clean, bad = campaign_files(healthy_path), campaign_files(faulty_path)
    band = report["bands"]["warning_c"][list(report["sensors"]).index(sensor)]
    campaigns = {}
    for cid, truth in faults.items():
        t, h, f = bad[cid]["time"].to_numpy(), clean[cid][sensor].to_numpy(), bad[cid][sensor].to_numpy()
        others = [c for c in bad[cid].columns if c != sensor]
        assert bad[cid][others].equals(clean[cid][others]), f"{cid}: the pairing is broken"
        onset = truth["onset_index"]
        if truth["kind"] in AT_ONCE:
            observable = onset
        else:   # the reading departs from the healthy one by the warning band
            seen = np.flatnonzero((np.arange(len(t)) >= onset) & (np.abs(f - h) >= band))
            observable = int(seen[0]) if len(seen) else None
        mine = [e for e in report["events"] if e["campaign"] == cid and e["sensor"] == sensor]
        row = int(np.flatnonzero(np.isclose(t, mine[0]["time"]))[0]) if mine else None
        campaigns[cid] = {"onset": onset, "observable": observable, "reported": row,
                          "event": mine[0] if mine else None}
    targets = {}
    for name, r in report["targets"].items():
        lo, hi = r["bound"]
        targets[name] = {"all_finite": r["all_finite"], "max_abs_correction": r["max_abs_correction"],
                         "bound": max(abs(lo), abs(hi)), "rmse_adaptive": r["rmse_adaptive"],
                         "rmse_fixed": r["rmse_fixed"],
                         "ratio": r["rmse_adaptive"] / healthy["targets"][name]["rmse_adaptive"]}
    return {"campaigns": campaigns, "targets": targets}


def assert_caught(check: dict, kind: str) -> None:
    for cid, c in check["campaigns"].items():
        if c["observable"] is None:          # never departs by the band: only no false report
            assert c["reported"] is None or c["reported"] >= c["onset"], (cid, c)
            continue
        assert c["reported"] is not None, f"{cid}: {kind} never reported ({c})"
        assert c["onset"] <= c["reported"] <= c["observable"] + LAG, (cid, c)
    for name, t in check["targets"].items():
        assert t["all_finite"] and t["max_abs_correction"] <= t["bound"] + 1e-9, (name, t)
        assert t["ratio"] <= 1.5, (name, t)


# -- faults through the CLI -------------------------------------------------------------------
@pytest.fixture(scope="session")
def healthy(default_dataset, tmp_path_factory):
    out = tmp_path_factory.mktemp("healthy")
    return run_monitor(default_dataset, out), out, most_influential(default_dataset)


@pytest.mark.slow
def test_the_healthy_default_data_raises_no_sensor_event_and_draws_the_figures(healthy):
    report, out, _ = healthy
    assert not [e for e in report["events"] if e["sensor"] in report["sensors"]]
    assert all(s["state_counts"]["alarm"] == s["state_counts"]["excluded"] == 0
               for s in report["sensors"].values())
    for t in report["targets"].values():      # nothing to adapt: the same compensation
        assert t["rmse_adaptive"] == pytest.approx(t["rmse_fixed"], rel=1e-9)
    assert "missing" not in report
    assert sorted(p.name for p in (out / "monitor").iterdir()) == [
        "compensation.png", "self_prediction.png", "sensor_map.png"]


@pytest.mark.slow
@pytest.mark.parametrize("kind", kinds_on("default"))
def test_a_simulated_fault_on_the_most_influential_sensor_is_caught_bounded_and_compensated(
        healthy, default_dataset, tmp_path, kind):
    report_h, _, sensor = healthy
    path = tmp_path / "faulty"
    faults = simulate_fault(path, kind, sensor)
    assert faults and {f["column"] for f in faults.values()} == {sensor}
    report = run_monitor(path, tmp_path / "out", "plots=none")
    check = fault_check(default_dataset, report_h, path, faults, report, sensor)
    assert_caught(check, kind)
    if kind == "dropout":    # streamed as NaN, counted, named in the reason
        assert set(report["missing"]) == set(faults)
        assert all(report["missing"][c] == {sensor: f["end_index"] - f["onset_index"]}
                   for c, f in faults.items())
        assert all("dropout" in c["event"]["reason"] for c in check["campaigns"].values())


# the same on a second scenario: one 12 h production campaign of the Swiss-type lathe (12 sensors)
SWISS = ["sim=swiss_lathe_door", "sim.generator.calibration_hours=40"]
SWISS_GAPS: dict[str, str] = {}   # measured gaps, as strict xfails (none left)


@pytest.fixture(scope="session")
def swiss(tmp_path_factory):
    root = tmp_path_factory.mktemp("swiss")
    cli("simulate", f"data.path={root / 'healthy'}", "track=false", *SWISS)
    report = run_monitor(root / "healthy", root / "mon", "plots=none", *SWISS)
    return root / "healthy", report, most_influential(root / "healthy")


@pytest.mark.slow
@pytest.mark.parametrize("kind", [pytest.param(*p.values, marks=[*p.marks, pytest.mark.xfail(
    reason=SWISS_GAPS[p.id], strict=True)] if p.id in SWISS_GAPS else p.marks, id=p.id)
    for p in kinds_on("swiss")])
def test_a_simulated_fault_on_the_swiss_lathe_is_caught_bounded_and_compensated(swiss, tmp_path, kind):
    healthy_path, report_h, sensor = swiss
    faults = simulate_fault(tmp_path / "faulty", kind, sensor, *SWISS)
    report = run_monitor(tmp_path / "faulty", tmp_path / "out", "plots=none", *SWISS)
    assert_caught(fault_check(healthy_path, report_h, tmp_path / "faulty", faults, report, sensor),
                  kind)


@pytest.mark.slow
def test_a_noise_burst_on_the_swiss_lathe_blames_no_healthy_partner(swiss, tmp_path):
    # ±0.5 °C for 60 samples on the most influential sensor (an outside probe's case): its
    # coupled partner, a quantised sensor reading 3 equal samples while the noisy field moved,
    # was excluded as frozen, and the adaptive correction was 5x worse than the fixed one
    healthy_path, report_h, sensor = swiss
    path = tmp_path / "faulty"
    shutil.copytree(healthy_path, path)
    index = pd.read_csv(path / "campaigns.csv")
    for file in index[index["split"] == "test"]["file"]:
        df = pd.read_csv(path / file)
        k0 = len(df) // 2
        df.loc[k0:k0 + 59, sensor] += np.random.default_rng(0).normal(0.0, 0.5, 60)
        df.to_csv(path / file, index=False)
    report = run_monitor(path, tmp_path / "out", "plots=none", *SWISS)
    assert not [e for e in report["events"] if e["reason"].startswith("freeze")]
    for t, r in report["targets"].items():
        assert r["rmse_adaptive"] <= 1.1 * r["rmse_fixed"], (t, r)


# -- hostile input: exit 2, one line, nothing written -----------------------------------------
CONFIG_CASES = {
    "input=bad": (["monitor.input=bad"], ["monitor.input='bad': must be one of null, -"]),
    "warning_c=-1": (["monitor.bands.warning_c=-1"], ["monitor.bands.warning_c=-1: must be a number > 0"]),
    "alarm below warning": (["monitor.bands.alarm_c=0.2"],
                            ["monitor.bands.alarm_c=0.2: must be >= monitor.bands.warning_c=0.4"]),
    "window=0": (["monitor.window=0"], ["monitor.window=0: must be an integer >= 1"]),
    "window=abc": (["monitor.window=abc"], ["monitor.window='abc': must be an integer >= 1"]),
    "confirm=20": (["monitor.confirm=20"], ["monitor.confirm=20: must be <= monitor.window=10"]),
    "exclude_at=x": (["monitor.exclude_at=x"], ["monitor.exclude_at='x': must be one of warning, alarm"]),
    "pod.energy=2": (["monitor.pod.energy=2"], ["monitor.pod.energy=2: must be a number in (0, 1]"]),
    "pod.modes=0": (["monitor.pod.modes=0"], ["monitor.pod.modes=0: must be null or an integer >= 1"]),
    "pod.placement=svd": (["monitor.pod.placement=svd"], ["monitor.pod.placement='svd'"]),
    "guard.margin=-0.1": (["monitor.guard.margin=-0.1"],
                          ["monitor.guard.margin=-0.1: must be a number >= 0"]),
    "map_time_h=-1": (["monitor.map_time_h=-1"], ["monitor.map_time_h=-1: must be null or a number >= 0"]),
    "adaptive=maybe": (["monitor.adaptive=maybe"], ["monitor.adaptive='maybe': must be true or false"]),
}


@pytest.mark.parametrize("case", CONFIG_CASES)
def test_a_bad_monitor_value_is_refused_before_the_data_is_read(tmp_path, capsys, case):
    extra, says = CONFIG_CASES[case]
    # the dataset does not exist: the refusal names the key, so it came before any read
    refused(["monitor", f"data.path={tmp_path / 'nowhere'}", f"out={tmp_path / 'out'}",
             "track=false", *extra], capsys, *says)
    assert list(tmp_path.iterdir()) == []


@pytest.fixture(scope="session")
def small(default_dataset, tmp_path_factory) -> Path:
    """A copy of the default dataset with only 2 train and 2 test campaigns (fast)."""
    path = tmp_path_factory.mktemp("small") / "ds"
    shutil.copytree(default_dataset, path)
    index = pd.read_csv(path / "campaigns.csv")
    keep = pd.concat([index[index["split"] == s].head(2) for s in ("train", "test")])
    keep.to_csv(path / "campaigns.csv", index=False)
    return path


def _blank_cell(path: Path, split: str, column: str, row: int) -> tuple[str, str]:
    index = pd.read_csv(path / "campaigns.csv")
    cid, file = index[index["split"] == split][["campaign", "file"]].iloc[0]
    df = pd.read_csv(path / file)
    df[column] = df[column].astype(float)
    df.loc[row - 1, column] = np.nan
    df.to_csv(path / file, index=False)
    return cid, file


def test_a_train_campaign_with_a_missing_value_is_refused_naming_it(small, tmp_path, capsys):
    path = tmp_path / "ds"
    shutil.copytree(small, path)
    cid, file = _blank_cell(path, "train", "T_nose", 7)
    out = tmp_path / "out"
    refused(["monitor", f"data.path={path}", f"out={out}", "track=false", "plots=none"], capsys,
            f"train campaign {cid}", file, "column 'T_nose'", "row 7", "data.max_gap_samples")
    assert not out.exists()
    # repaired within the data limits, as `run` would read it
    assert main(["monitor", f"data.path={path}", f"out={out}", "track=false", "plots=none",
                 "data.max_gap_samples=1"]) == 0
    assert "missing" not in json.loads((out / "monitor.json").read_text())


def test_a_test_campaign_with_missing_values_streams_and_counts_them(small, tmp_path):
    path = tmp_path / "ds"
    shutil.copytree(small, path)
    cid, _ = _blank_cell(path, "test", "T_nose", 5)
    _blank_cell(path, "test", "E_Z", 9)
    report = run_monitor(path, tmp_path / "out", "plots=none")
    assert report["missing"] == {cid: {"T_nose": 1, "E_Z": 1}}
    assert all(t["all_finite"] for t in report["targets"].values())
    assert all(t["rmse_adaptive"] is not None for t in report["targets"].values())


def test_a_map_time_after_the_campaign_is_said(small, tmp_path, capsys):
    # 1e300 h was drawn at the last sample without a word
    out = tmp_path / "out"
    assert main(["monitor", f"data.path={small}", f"out={out}", "track=false", "plots=summary",
                 "monitor.map_time_h=1e300"]) == 0
    said = [ln for ln in capsys.readouterr().err.splitlines() if "map_time_h" in ln]
    assert len(said) == 1 and "after the end of campaign" in said[0] and "last sample" in said[0]
    assert (out / "monitor" / "sensor_map.png").exists()
    assert main(["monitor", f"data.path={small}", f"out={tmp_path / 'o2'}", "track=false",
                 "plots=summary", "monitor.map_time_h=1"]) == 0
    assert "map_time_h" not in capsys.readouterr().err


def _set_cells(path: Path, split: str, column: str, rows: slice, value: float) -> tuple[str, str]:
    index = pd.read_csv(path / "campaigns.csv")
    cid, file = index[index["split"] == split][["campaign", "file"]].iloc[0]
    df = pd.read_csv(path / file)
    df[column] = df[column].astype(float)
    df.loc[rows, column] = value
    df.to_csv(path / file, index=False)
    return cid, file


@pytest.fixture(scope="module")
def open_circuit(small, tmp_path_factory) -> tuple[Path, str, str, dict]:
    """``small`` with T_motor2 at 850 °C for 5 samples of its first test campaign: ``(the
    dataset, the campaign, its file, its monitor.json with plots=none)``; two tests read the
    monitor's report (each edits a copy of the dataset)."""
    path = tmp_path_factory.mktemp("open_circuit") / "ds"
    shutil.copytree(small, path)
    cid, file = _set_cells(path, "test", "T_motor2", slice(40, 44), 850.0)
    return path, cid, file, run_monitor(path, path.parent / "out", "plots=none")


def test_an_open_circuit_streams_from_a_test_file_and_is_refused_in_a_train_one(open_circuit, tmp_path,
                                                                              capsys):
    # 850 °C for 5 samples: a failing sensor, not kelvin (the column's median is in °C); the
    # deployed compensator is there to catch it, so a recorded test campaign streams with it
    path = tmp_path / "ds"
    shutil.copytree(open_circuit[0], path)
    _, cid, _, report = open_circuit
    mine = [e for e in report["events"] if e["campaign"] == cid and e["sensor"] == "T_motor2"]
    assert mine and mine[0]["to"] == "excluded" and mine[0]["reason"].startswith("out of range")
    assert all(t["all_finite"] for t in report["targets"].values())
    _, file = _set_cells(path, "train", "T_motor2", slice(40, 44), 850.0)
    out = tmp_path / "refused"
    refused(["monitor", f"data.path={path}", f"out={out}", "track=false", "plots=none"], capsys,
            file, "column 'T_motor2'", "row 41", "faulty reading")
    assert not out.exists()


def _stdin_rows(path: Path) -> pd.DataFrame:
    index = pd.read_csv(path / "campaigns.csv")
    return pd.read_csv(path / index[index["split"] == "test"]["file"].iloc[0])


def _bad_cell(df: pd.DataFrame) -> str:
    df = df.astype({"T_motor1": object})
    df.loc[11, "T_motor1"] = "n/a?"
    return df.to_csv(index=False)


STDIN_CASES = {
    "not CSV": (lambda df: "\x00\x01\x02 binary\n\x89PNG\n", ["<stdin>", "lacks a column"]),
    "empty": (lambda df: "", ["<stdin>", "not a CSV table with a header"]),
    "header only": (lambda df: ",".join(df.columns) + "\n", ["<stdin>", "no data row"]),
    "lacks a column": (lambda df: df.drop(columns="T_box2").to_csv(index=False),
                       ["<stdin>", "column 'T_box2'", "lacks a column"]),
    "non-numeric cell": (_bad_cell, ["<stdin>", "column 'T_motor1'", "row 12", "non-numeric"]),
    # a column the model does not read is still data (a traceback before)
    "non-numeric signal": (lambda df: df.astype({"S_spindle_rpm": object}).assign(
        S_spindle_rpm=lambda d: d["S_spindle_rpm"].where(d.index != 4, "abc")).to_csv(index=False),
        ["<stdin>", "column 'S_spindle_rpm'", "row 5", "non-numeric"]),
}


@pytest.mark.parametrize("case", STDIN_CASES)
def test_bad_stdin_is_refused_naming_where(small, tmp_path, capsys, monkeypatch, case):
    make, says = STDIN_CASES[case]
    monkeypatch.setattr("sys.stdin", io.StringIO(make(_stdin_rows(small))))
    refused(["monitor", "monitor.input=-", f"data.path={small}", f"out={tmp_path / 'out'}",
             "track=false"], capsys, *says)
    assert list(tmp_path.iterdir()) == []


def test_stdin_rows_with_empty_cells_stream_and_are_counted(small, tmp_path, monkeypatch, capsys):
    df = _stdin_rows(small)
    df.loc[20:, "T_motor2"] = np.nan
    monkeypatch.setattr("sys.stdin", io.StringIO(df.to_csv(index=False)))
    assert main(["monitor", "monitor.input=-", f"data.path={small}", f"out={tmp_path}",
                 "track=false", "plots=none"]) == 0
    report = json.loads((tmp_path / "monitor.json").read_text())
    assert report["missing"] == {"stdin": {"T_motor2": len(df) - 20}}
    first = next(e for e in report["events"] if e["sensor"] == "T_motor2")
    assert first["time"] == df["time"].iloc[20] and "dropout" in first["reason"]
    assert all(t["all_finite"] for t in report["targets"].values())


def test_stdin_rows_with_iso_8601_times_stream_as_their_seconds(small, tmp_path, monkeypatch, capsys):
    # the contract allows ISO 8601 in `time`, and ingest reads them; stdin refused them before
    df = _stdin_rows(small)
    iso = df.assign(time=(pd.Timestamp("2026-03-01T08:00:00+01:00")
                          + pd.to_timedelta(df["time"] - df["time"].iloc[0], unit="s"))
                    .map(lambda t: t.isoformat()))
    reports = {}
    for name, rows in (("seconds", df.assign(time=df["time"] - df["time"].iloc[0])), ("iso", iso)):
        monkeypatch.setattr("sys.stdin", io.StringIO(rows.to_csv(index=False)))
        assert main(["monitor", "monitor.input=-", f"data.path={small}", f"out={tmp_path / name}",
                     "track=false", "plots=none"]) == 0
        reports[name] = json.loads((tmp_path / name / "monitor.json").read_text())
    assert reports["iso"]["targets"] == reports["seconds"]["targets"]
    assert reports["iso"]["events"] == reports["seconds"]["events"]
    bad = iso.copy()
    bad.loc[7, "time"] = "2026-03-01 8 o'clock"
    monkeypatch.setattr("sys.stdin", io.StringIO(bad.to_csv(index=False)))
    refused(["monitor", "monitor.input=-", f"data.path={small}", f"out={tmp_path / 'bad'}",
             "track=false"], capsys, "<stdin>", "column 'time'", "row 8", "ISO 8601")
    assert not (tmp_path / "bad").exists()


def test_stdin_rows_are_read_as_the_campaign_files_are(small, tmp_path, monkeypatch, capsys):
    """A lab's logger rows (';', decimal commas, its own column names) stream through the data
    config the campaign files are read with; stdin ignored it before ('lacks a column
    T_...' for the whole ';'-joined header)."""
    lab = tmp_path / "lab"
    lab.mkdir()
    for f in small.iterdir():
        df = pd.read_csv(f)
        if f.name != "campaigns.csv":
            df = df.rename(columns={"T_motor1": "Motor 1"})
        df.to_csv(lab / f.name, index=False, sep=";", decimal=",")
    rows = _stdin_rows(small)
    settings = ["data.delimiter=;", "data.decimal=','", "data.columns={Motor 1:T_motor1}"]
    reports = {}
    for name, path, text, extra in (
            ("contract", small, rows.to_csv(index=False), []),
            ("lab", lab, rows.rename(columns={"T_motor1": "Motor 1"}).to_csv(index=False, sep=";",
                                                                             decimal=","), settings)):
        monkeypatch.setattr("sys.stdin", io.StringIO(text))
        out = tmp_path / f"{name}_out"      # not the lab's dataset: no stage writes into data.path
        assert main(["monitor", "monitor.input=-", f"data.path={path}", f"out={out}",
                     "track=false", "plots=none", *extra]) == 0, capsys.readouterr().err
        reports[name] = json.loads((out / "monitor.json").read_text())
    for t, got in reports["lab"]["targets"].items():
        want = reports["contract"]["targets"][t]
        assert got["rmse_fixed"] == pytest.approx(want["rmse_fixed"], rel=1e-9)
        assert got["rmse_adaptive"] == pytest.approx(want["rmse_adaptive"], rel=1e-9)


DATA_CASES = {
    "no test split": (lambda p: _splits(p, {"test": "val"}), [],
                      ["campaigns.csv", "column 'split'", "no 'test' campaign"]),
    "no train split": (lambda p: _splits(p, {"train": "val"}), [],
                       ["campaigns.csv", "no 'train' campaign"]),
    "2 temperature inputs": (lambda p: None, ["data.inputs=[T_nose,T_amb]"],
                             ["at least 3 temperature inputs", "T_nose"]),
    "pod.modes=999": (lambda p: None, ["monitor.pod.modes=999"], ["monitor:", "modes=999"]),
    "test lacks a column": (lambda p: _drop_test_column(p, "T_box1"), [],
                            ["column 'T_box1'", "lacks a column the model reads", ".csv, column"]),
}


def _splits(path: Path, mapping: dict) -> None:
    index = pd.read_csv(path / "campaigns.csv")
    index["split"] = index["split"].replace(mapping)
    index.to_csv(path / "campaigns.csv", index=False)


def _drop_test_column(path: Path, column: str) -> None:
    index = pd.read_csv(path / "campaigns.csv")
    file = index[index["split"] == "test"]["file"].iloc[-1]
    pd.read_csv(path / file).drop(columns=column).to_csv(path / file, index=False)


@pytest.mark.parametrize("case", DATA_CASES)
def test_data_the_monitor_cannot_use_is_refused(small, tmp_path, capsys, case):
    mutate, extra, says = DATA_CASES[case]
    path = tmp_path / "ds"
    shutil.copytree(small, path)
    mutate(path)
    refused(["monitor", f"data.path={path}", f"out={tmp_path / 'out'}", "track=false", *extra],
            capsys, *says)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ds"]


def test_event_times_are_seconds_from_the_campaign_start_whatever_the_file_clock(open_circuit, tmp_path):
    # CLI.md, monitor.json: "`time` is in seconds from the campaign start"
    path = tmp_path / "ds"
    shutil.copytree(open_circuit[0], path)
    _, cid, file, unshifted = open_circuit          # its monitor on the file's own clock
    t = pd.read_csv(path / file)["time"].to_numpy(float)
    times = {}
    for shift in (0.0, 36000.0):
        df = pd.read_csv(path / file)
        df["time"] = t + shift
        df.to_csv(path / file, index=False)
        report = run_monitor(path, tmp_path / f"mon{shift:g}", "plots=none") if shift else unshifted
        cli("replay", f"data.path={path}", f"out={tmp_path / f'rep{shift:g}'}", "track=false",
                   "monitor.adaptive=true")
        replayed = json.loads((tmp_path / f"rep{shift:g}" / "replay.json").read_text())["events"]
        times[shift] = ([e["time"] for e in report["events"] if e["campaign"] == cid],
                        report["sensors"]["T_motor2"]["first_alarm"]["time"],
                        [e["time"] for e in replayed if e["campaign"] == cid])
    assert times[36000.0] == times[0.0]
    events, first, replayed = times[0.0]
    assert first == pytest.approx(t[40] - t[0]) and first in events and first in replayed
