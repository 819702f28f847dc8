"""Hostile input: a unit that changes inside a file, and a thousands separator.

A logger switched to °F (or a probe to mm) part way through a campaign is refused naming the
file, the column and the first row in the new unit; a physical step (a door opens, a sensor
fault offsets one reading) and every simulated scenario read as before.
"""

from __future__ import annotations

import io
import logging
import shutil

import numpy as np
import pandas as pd
import pytest

from conftest import refused
from covering import covering
from test_hostile import edit_csv, snapshot
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.shell.cli import main


def from_row(column, row, convert):
    """Rows ``row`` (1-based data row) and after of ``column`` in another unit."""
    def mutate(df):
        df[column] = df[column].where(df.index < row - 1, convert(df[column]))
    return mutate


FAHRENHEIT = lambda c: (c * 1.8 + 32).round(2)  # noqa: E731 -- as a logger writes it
MILLIMETRES = lambda um: (um / 1000).round(5)  # noqa: E731


# -- item 6: a unit change inside a file --------------------------------------------------

UNIT_CASES = {
    "°F from row 15": ("K02", "T_0", FAHRENHEIT, "°F of the °C before"),
    "°F ambient from row 15": ("K03", "T_amb", FAHRENHEIT, "°F of the °C before"),
    "mm from row 15": ("K02", "E_X", MILLIMETRES, "mm of the µm before"),
    "nm from row 15": ("K01", "E_X", lambda um: um * 1000, "1000x the rows before"),
}


@pytest.mark.parametrize("command, case", covering(
    "the same step check under another command", command=["run", "ingest", "monitor"],
    case=list(UNIT_CASES)))
def test_a_unit_changed_inside_a_file_is_refused_at_its_row(paths, capsys, case, command):
    cid, column, convert, unit = UNIT_CASES[case]
    edit_csv(paths["ds"] / f"{cid}.csv", from_row(column, 15, convert))
    before = snapshot(paths["out"], paths["interim"], paths["model"], paths["ds"])

    refused([command, *paths["args"]], capsys, f"{cid}.csv", f"column '{column}'", "row 15",
            unit, "data.max_step_ratio=5")

    assert snapshot(paths["out"], paths["interim"], paths["model"], paths["ds"]) == before


def test_the_row_named_is_the_files_after_a_trimmed_edge_or_a_kept_empty_cell(paths, capsys):
    # rows are 1-based data rows of the source file: one incomplete first row dropped
    # (data.max_edge_samples=1), or an empty cell a streamed test campaign keeps (monitor)
    def trimmed(df):
        df["T_amb"] = df["T_amb"].where(df.index != 0)
        from_row("T_0", 15, FAHRENHEIT)(df)

    def gap(df):
        df["T_0"] = df["T_0"].where(df.index != 9)
        from_row("T_0", 15, FAHRENHEIT)(df)
    edit_csv(paths["ds"] / "K02.csv", trimmed)
    refused(["ingest", *paths["args"], "data.max_edge_samples=1"], capsys, "K02.csv",
            "column 'T_0'", "row 15")
    edit_csv(paths["ds"] / "K02.csv", lambda df: df.__setitem__("T_0", df["T_0"].where(
        df.index < 14, (df["T_0"] - 32) / 1.8)))
    edit_csv(paths["ds"] / "K04.csv", gap)
    refused(["monitor", *paths["args"], "data.max_edge_samples=1"], capsys, "K04.csv",
            "column 'T_0'", "row 15")


@pytest.fixture
def default_copy(default_dataset, tmp_path):
    return shutil.copytree(default_dataset, tmp_path / "yearround_spindle")


@pytest.mark.parametrize("column, convert, unit", [("T_motor1", FAHRENHEIT, "°F"),
                                                   ("E_Z", MILLIMETRES, "mm")])
def test_the_probes_unit_changes_in_the_default_dataset_are_refused(default_copy, tmp_path,
                                                                    capsys, column, convert,
                                                                    unit):
    # the probe's case: K05 from row 40 (21.3 °C -> 70.2, or 41.4 µm -> 0.0414) ran with exit 0
    edit_csv(default_copy / "K05.csv", from_row(column, 40, convert))
    refused(["ingest", f"data.path={default_copy}", f"data.interim={tmp_path / 'interim'}",
             "track=false"], capsys, "K05.csv", f"column '{column}'", "row 40", unit)
    assert not (tmp_path / "interim").exists()


def test_the_step_check_switched_off_reads_the_changed_unit(paths):
    edit_csv(paths["ds"] / "K02.csv", from_row("T_0", 15, FAHRENHEIT))
    ds, _ = read_dataset(paths["ds"], {"max_step_ratio": None})
    assert ds.campaigns["K02"]["T_0"].iloc[14] > 60


@pytest.mark.parametrize("value", ["nan", "inf", "0", "-1", "abc"])
def test_a_bad_max_step_ratio_is_refused(paths, capsys, value):
    refused(["ingest", *paths["args"], f"data.max_step_ratio={value}"], capsys,
            "data.max_step_ratio")


def _shifted(df, columns, row, kelvin):
    for c in columns:
        df[c] = df[c] + np.where(df.index >= row - 1, kelvin, 0.0)


@pytest.mark.parametrize("columns, kelvin", [(["T_amb"], 3.0), (["T_amb"], -4.0),
                                             (["T_0", "T_amb"], 3.0), (["T_0"], 8.0)])
def test_a_physical_step_is_read(paths, caplog, columns, kelvin):
    # a door opens at a one-minute sample (the ambient jumps a few K and stays), or a fault
    # offsets a sensor: a step the column does not make, but no unit accounts for it
    edit_csv(paths["ds"] / "K02.csv", lambda df: _shifted(df, columns, 15, kelvin))
    with caplog.at_level(logging.WARNING):
        ds, _ = read_dataset(paths["ds"])
    assert ds.campaigns["K02"][columns[0]].diff().abs().max() >= abs(kelvin) - 0.5
    assert "unit" not in caplog.text


def test_a_unit_fit_while_other_sensors_step_is_warned_not_refused(paths, caplog):
    # T_0 reads as °F from row 15, but T_amb steps 5 K at the same row: an event, not sure
    def mutate(df):
        from_row("T_0", 15, FAHRENHEIT)(df)
        _shifted(df, ["T_amb"], 15, 5.0)
    edit_csv(paths["ds"] / "K02.csv", mutate)
    with caplog.at_level(logging.WARNING):
        read_dataset(paths["ds"])
    assert "K02.csv, column 'T_0', line 16 (data row 15)" in caplog.text and "real event" in caplog.text


# Each scenario of conf/sim at a small size, with every undeclared effect that it plants
# (doors, faults that offset or freeze a sensor, spikes): none of them is a unit change.
SCENARIOS = {
    "yearround_spindle": [],
    "column_moving_source": ["sim.generator.train_hours=20", "sim.generator.test_hours=10"],
    "large_mill_week": ["sim.generator.train_hours=30", "sim.generator.test_hours=20"],
    "swiss_lathe_door": ["sim.generator.calibration_hours=20",
                         "sim.generator.production_hours=8"],
    "long_record": ["sim.generator.duration_days=4"],
    "climate_room": ["sim.generator.n_runs=6"],
    "fleet": ["sim.generator.n_machines=2", "sim.generator.days=3", "sim.generator.test_days=1"],
    "large_mill_volumetric": ["sim.generator.train_hours=12", "sim.generator.test_hours=6"],
}
EFFECTS = ("sim.generator.effects=[door,hidden_source,lag_node,axis_position,sensor_drift,"
           "ambient_law,sensor_faults]")


@pytest.mark.parametrize("scenario", SCENARIOS)
def test_no_simulated_scenario_has_a_unit_change(tmp_path, capsys, caplog, scenario):
    effects = [] if scenario in ("fleet", "large_mill_volumetric") else [EFFECTS]
    path = tmp_path / scenario
    assert main(["simulate", f"sim={scenario}", f"data.path={path}", "track=false",
                 *SCENARIOS[scenario], *effects]) == 0
    capsys.readouterr()
    missing = "keep_errors" if (path / "volumetric.json").is_file() else "repair"
    with caplog.at_level(logging.WARNING):
        read_dataset(path, {"max_step_ratio": 5.0}, missing=missing)
    assert "unit changes" not in caplog.text


def test_the_default_dataset_passes_and_its_unit_changes_are_found(default_dataset):
    # sensitivity, on every T_ and E_ column of the 24 campaigns: °F from mid-campaign on is
    # always found; mm only where the level is well above the noise (E_X of ~5 µm, 0.4 µm
    # noise, is not)
    from thermocomp.core.io.steps import UNITS, unit_change

    ds, _ = read_dataset(default_dataset)
    found = {"T": [], "E": []}
    for frame in ds.campaigns.values():
        half = len(frame) // 2
        for column in frame.columns:
            kind = column[0]
            if kind in found:
                x = frame[column].to_numpy()
                y = np.concatenate((x[:half], (x[half:] * 1.8 + 32) if kind == "T"
                                    else x[half:] / 1000))
                level = abs(x[half - 1])
                found[kind].append((unit_change(y, 5.0, UNITS[kind])[0] == half - 1, level))
    assert all(hit for hit, _ in found["T"])
    assert all(hit for hit, level in found["E"] if level > 20)


# -- item 14: a thousands separator --------------------------------------------------------


def _grouped_speeds(df):
    """An S_ column written as a lab's export writes it: ``"6,000"`` (quoted)."""
    df["S_rpm"] = [f"{v:,.0f}" for v in np.where(df.index % 2, 6000.0, 12000.0)]


@pytest.mark.parametrize("command", ["run", "ingest", "monitor"])
def test_a_thousands_separator_is_named_not_blamed_on_a_decimal_comma(paths, capsys, command):
    edit_csv(paths["ds"] / "K03.csv", _grouped_speeds)
    before = snapshot(paths["out"], paths["interim"], paths["model"], paths["ds"])

    line = refused([command, *paths["args"]], capsys, "K03.csv", "column 'S_rpm'", "row 1",
                   "'12,000'", "a thousands separator? set data.thousands=','")

    assert "decimal" not in line
    assert snapshot(paths["out"], paths["interim"], paths["model"], paths["ds"]) == before


def test_data_thousands_reads_grouped_digits(paths, capsys):
    for cid in ("K01", "K02", "K03", "K04"):
        edit_csv(paths["ds"] / f"{cid}.csv", _grouped_speeds)
    assert main(["ingest", *paths["args"], "data.thousands=,"]) == 0
    ds, _ = read_dataset(paths["ds"], {"thousands": ","})
    assert ds.campaigns["K03"]["S_rpm"].tolist()[:2] == [12000.0, 6000.0]


def test_a_european_export_reads_with_a_point_for_thousands(paths):
    # 6.000 with a decimal comma: the hint names '.', and data.thousands='.' reads it
    for cid in ("K01", "K02", "K03", "K04"):
        path = paths["ds"] / f"{cid}.csv"
        df = pd.read_csv(path).assign(S_rpm=lambda d: np.where(d.index % 2, "6.000", "1.500"))
        df.to_csv(path, index=False, sep=";", decimal=",")
    cfg = {"delimiter": ";", "decimal": ","}
    with pytest.raises(ContractError, match=r"line 2 \(data row 1\): value '1.500' .*data.thousands='.'"):
        read_dataset(paths["ds"], cfg)
    ds, _ = read_dataset(paths["ds"], {**cfg, "thousands": "."})
    assert ds.campaigns["K01"]["S_rpm"].tolist()[:2] == [1500.0, 6000.0]
    assert ds.campaigns["K01"]["T_0"].between(15, 30).all()  # the decimal comma still reads


def test_a_decimal_comma_is_still_named_when_the_column_has_one(paths):
    # '6,000' alone could be either; '21,35' in the same column settles it
    def mutate(df):
        df["T_0"] = df["T_0"].map(lambda v: f"{v:.2f}")
        df.loc[2, "T_0"], df.loc[5, "T_0"] = "21,000", "21,35"
    edit_csv(paths["ds"] / "K02.csv", mutate)
    with pytest.raises(ContractError, match=r"line 4 \(data row 3\): value '21,000' .*decimal comma"):
        read_dataset(paths["ds"])


def test_a_cell_not_grouped_by_three_is_refused(paths):
    def mutate(df):
        _grouped_speeds(df)
        df.loc[6, "S_rpm"] = "6,00"
    edit_csv(paths["ds"] / "K02.csv", mutate)
    with pytest.raises(ContractError, match=r"K02.csv, column 'S_rpm', line 8 \(data row 7\): .*by three"):
        read_dataset(paths["ds"], {"thousands": ","})


@pytest.mark.parametrize("value", ["'.'", "x", "1", "' '", "'--'"])
def test_a_bad_data_thousands_is_refused(paths, capsys, value):
    refused(["ingest", *paths["args"], f"data.thousands={value}"], capsys, "data.thousands")


def test_monitor_stdin_reads_grouped_digits_with_data_thousands(default_copy, tmp_path, capsys,
                                                                monkeypatch):
    index = pd.read_csv(default_copy / "campaigns.csv")
    keep = pd.concat([index[index["split"] == s].head(2) for s in ("train", "test")])
    keep.to_csv(default_copy / "campaigns.csv", index=False)
    rows = pd.read_csv(default_copy / keep["file"].iloc[-1])
    rows["time"] = rows["time"].map(lambda t: f"{t:,.0f}")          # 1,200 s from row 5
    args = ["monitor", "monitor.input=-", f"data.path={default_copy}", f"out={tmp_path / 'out'}",
            "track=false", "plots=none"]
    monkeypatch.setattr("sys.stdin", io.StringIO(rows.to_csv(index=False)))
    refused(args, capsys, "<stdin>", "column 'time'", "row 5")
    monkeypatch.setattr("sys.stdin", io.StringIO(rows.to_csv(index=False)))
    assert main([*args, "data.thousands=,"]) == 0
