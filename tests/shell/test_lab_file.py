"""A lab's own file in one command (issue 34, item 1): one CSV/Parquet record, roles by header
patterns, detected separators, a chronological cut, ``data.reference=auto``, ``thermocomp init``.

Every run is compared with a run of the same data in the contract's own form (a hand-cut folder
with an explicit mapping, or the simulator's own files): the numbers must be the same.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from conftest import ROOT, refused
from test_hostile import FAST, snapshot
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main

RECORD = ROOT / "datasets" / "fl_thermal" / "spindle_test.csv"
ROLES = ["data.roles.error=['ch*']", "data.roles.state=['spindle*']"]
MLR = ["model=mlr", *FAST]


def _metrics(out: Path) -> dict:
    return json.loads((out / "metrics.json").read_text())


def _test_scores(metrics: dict) -> dict:
    return {t: (m["test"]["rmse"], m["test"]["mae"]) for t, m in metrics["targets"].items()}


def _run(tmp_path: Path, name: str, *args: str) -> dict:
    out = tmp_path / name
    assert main(["run", *args, f"out={out}", *MLR]) == 0
    return _metrics(out)


def _hand_cut(record: Path, folder: Path, test_fraction: float) -> dict:
    """``record`` cut by hand as a lab did before: head/tail files, a manifest with
    ``continues``; returns the explicit mapping of its headers (``data.columns``)."""
    text = record.read_text(encoding="utf-8").splitlines()
    header, rows = text[0], text[1:]
    n_test = math.floor(len(rows) * test_fraction + 0.5)
    folder.mkdir()
    (folder / "a.csv").write_text("\n".join([header, *rows[:-n_test]]) + "\n", encoding="utf-8")
    (folder / "b.csv").write_text("\n".join([header, *rows[-n_test:]]) + "\n", encoding="utf-8")
    (folder / "campaigns.csv").write_text("campaign,file,split,continues\na,a.csv,train,\n"
                                          "b,b.csv,test,a\n")
    mapping = {}
    for raw in header.split(","):
        name = raw.split("(")[0]
        mapping[raw] = ("time" if raw.startswith("時間") else f"E_{name}" if name.startswith("ch")
                        else f"S_{name}" if name == "spindle" else f"T_{name}")
    return mapping


def test_the_vendored_record_goes_in_without_a_manifest_and_scores_as_the_hand_cut_folder(tmp_path):
    mapping = _hand_cut(RECORD, tmp_path / "cut", 0.1)
    conf = tmp_path / "conf" / "data"
    conf.mkdir(parents=True)         # the explicit mapping, as a lab's data config holds it
    (conf / "cut.yaml").write_text(yaml.safe_dump(
        {"defaults": ["default"], "path": str(tmp_path / "cut"), "columns": mapping,
         "reference": "none"}, allow_unicode=True), encoding="utf-8")
    by_hand = _run(tmp_path, "by_hand", f"hydra.searchpath=[file://{conf.parent}]", "data=cut")
    one_command = _run(tmp_path, "one", f"data.path={RECORD}", *ROLES, "data.test_fraction=0.1")
    assert set(one_command["targets"]) == {f"E_ch{i}" for i in range(1, 6)}
    for target, (rmse, mae) in _test_scores(by_hand).items():
        assert _test_scores(one_command)[target] == pytest.approx((rmse, mae), rel=1e-9)
    # the cut record's test part continues its train part: auto reads it absolute, state carried
    assert one_command["reference"] == "none"
    assert one_command["carry_over"] == {"spindle_test_test": ["spindle_test_train",
                                                              "spindle_test_test"]}
    report = json.loads((tmp_path / "one" / "ingest_report.json").read_text())
    assert report["reference"] == "none"
    assert report["column_map"]["ch3(um)"] == "E_ch3" and report["column_map"]["時間(s)"] == "time"
    assert [report["campaigns"][c]["rows"] for c in ("spindle_test_train", "spindle_test_test")] \
        == [len(pd.read_csv(tmp_path / "cut" / f)) for f in ("a.csv", "b.csv")]


def test_the_preset_runs_the_vendored_record_from_anywhere(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)          # data.path is relative to the project root, not the cwd
    by_roles = _run(tmp_path, "roles", f"data.path={RECORD}", *ROLES, "data.test_fraction=0.1")
    preset = _run(tmp_path, "preset", "data=fl_thermal")
    assert _test_scores(preset) == _test_scores(by_roles)


def test_the_authors_split_is_train_test_val_in_time():
    cfg = {"roles": {"error": ["ch*"], "state": ["spindle*"]}, "test_fraction": 0.2,
           "val_fraction": 0.2, "split_order": ["train", "test", "val"]}
    ds, report = read_dataset(RECORD, cfg)
    n = len(pd.read_csv(RECORD))
    parts = {ds.manifest.loc[c, "split"]: report["campaigns"][c]["record_rows"] for c in ds.ids()}
    assert parts == {"train": [0, n - 2 * round(0.2 * n)],
                     "test": [n - 2 * round(0.2 * n), n - round(0.2 * n)],
                     "val": [n - round(0.2 * n), n]}
    assert ds.manifest["continues"].tolist() == ["", "spindle_test_train", "spindle_test_test"]
    times = [ds.campaigns[c]["time"] for c in ds.ids()]
    assert all(b.iloc[0] > a.iloc[-1] for a, b in zip(times, times[1:]))  # one clock, in order


def _lab_export(src: Path, dest: Path) -> list[str]:
    """The simulated record ``src`` (its files end to end) as a lab's logger writes it: one file,
    a BOM, ';' and decimal commas, no time column, units in the headers, the error in mm and one
    temperature in kelvin; returns the roles that read it."""
    manifest = pd.read_csv(src / "campaigns.csv")
    record = pd.concat([pd.read_csv(src / f) for f in manifest["file"]], ignore_index=True)
    lab = pd.DataFrame()
    for column in record.columns.drop("time"):
        name, values = column[2:], record[column]
        if column == "T_amb":
            lab["hall air (°C)"] = values
        elif column == "T_motor":
            lab["motor [K]"] = values + 273.15
        elif column.startswith("T_"):
            lab[f"{name} (°C)"] = values
        elif column.startswith("E_"):
            lab[f"{name} [mm]"] = values / 1000
        else:
            lab[f"{name} (1/min)"] = values
    lab.to_csv(dest, sep=";", decimal=",", index=False, encoding="utf-8-sig", float_format="%.12g")
    return ["data.roles.error=[Z]", "data.roles.state=['spindle_rpm*']", "data.roles.ambient=['hall*']"]


def test_a_lab_export_of_a_simulated_record_gives_the_simulators_result(tmp_path):
    src = tmp_path / "sim"
    assert main(["simulate", "sim=long_record", f"data.path={src}", "track=false",
                 "sim.generator.duration_days=2"]) == 0
    roles = _lab_export(src, tmp_path / "logger.csv")
    assert (tmp_path / "logger.csv").read_bytes().startswith(b"\xef\xbb\xbf")
    original = _run(tmp_path, "original", f"data.path={src}", "data.reference=auto")
    lab = _run(tmp_path, "lab", f"data.path={tmp_path / 'logger.csv'}", *roles,
               "data.test_fraction=0.1", "data.sample_period_s=60")
    assert original["reference"] == lab["reference"] == "none"
    assert original["inputs"] == lab["inputs"]           # the same contract names, T_amb too
    for target, scores in _test_scores(original).items():
        assert _test_scores(lab)[target] == pytest.approx(scores, rel=1e-6)


def test_auto_reference_is_the_first_sample_on_the_default_simulated_dataset(tmp_path):
    src = tmp_path / "sim"
    assert main(["simulate", f"data.path={src}", "track=false", "sim.generator.n_campaigns=4"]) == 0
    assert _run(tmp_path, "auto", f"data.path={src}")["reference"] == "first_sample"


def _lab_file(path: Path, **extra) -> Path:
    rng = np.random.default_rng(0)
    t1 = 20 + np.cumsum(rng.normal(0, 0.05, 40))
    frame = pd.DataFrame({"ch1(um)": 3 * (t1 - t1[0]), "t1(°C)": t1, "t2(°C)": t1 + 1, **extra})
    frame.to_csv(path, index=False)
    return path


def test_a_missing_sample_period_is_an_error_not_a_guess(tmp_path, capsys):
    path = _lab_file(tmp_path / "lab.csv")
    out = tmp_path / "out"
    before = snapshot(out, tmp_path / "lab.csv")
    refused(["run", f"data.path={path}", "data.roles.error=['ch*']", "data.test_fraction=0.2",
             f"out={out}", *MLR], capsys, "lab.csv", "no 'time' column", "data.sample_period_s")
    assert snapshot(out, tmp_path / "lab.csv") == before


def test_every_column_not_read_is_named_in_one_message(tmp_path, capsys):
    # (twins98: 't1(°C)' beside 't1 [K]' is read, T_t1 and T_t1_2; a bare 't1' beside it names
    # the same T_t1, still refused)
    path = _lab_file(tmp_path / "lab.csv", operator=["anna"] * 40, t1=np.full(40, 294.0),
                     spindle=np.zeros(40))
    out = tmp_path / "out"
    before = snapshot(out)
    line = refused(["run", f"data.path={path}", "data.roles.error=['ch*']",
                    "data.roles.state=['spindle','ch*']", "data.sample_period_s=60",
                    "data.test_fraction=0.2", f"out={out}", *MLR], capsys, "lab.csv",
                   "'ch1(um)' is matched by data.roles.error and data.roles.state",
                   "'operator' is not numeric ('anna')", "'t1(°C)' and 't1' both give T_t1")
    assert "3 column(s) not read" in line
    assert snapshot(out) == before


def test_contract_columns_names_a_labs_headers():
    from thermocomp.core.io.roles import contract_columns

    headers = ["Zeit", "X-Achse [mm]", "spindle(RPM)", "t 1(°C)", "air(°C)", "T_spindle", "note"]
    assert contract_columns(headers, {"error": ["X*"], "state": ["spindle"], "ambient": ["air"],
                                      "ignore": ["note"]}, {"T_spindle": "T_head"}) == {
        "Zeit": "time", "X-Achse [mm]": "E_X-Achse", "spindle(RPM)": "S_spindle",
        "t 1(°C)": "T_t_1", "air(°C)": "T_amb", "T_spindle": "T_head"}


def test_units_in_headers_are_converted_to_the_contracts(tmp_path):
    t = np.arange(30) * 10.0
    pd.DataFrame({"t(min)": t / 60, "X(mm)": t / 1e4, "a(K)": 293.15 + t / 100,
                  "b(°F)": 68 + t / 100}).to_csv(tmp_path / "r.csv", index=False)
    ds, _ = read_dataset(tmp_path / "r.csv", {"roles": {"error": ["X"]}})
    frame = ds.campaigns["r"]
    np.testing.assert_allclose(frame["time"], t)
    np.testing.assert_allclose(frame["E_X"], t / 10)
    np.testing.assert_allclose(frame["T_a"], 20 + t / 100)
    np.testing.assert_allclose(frame["T_b"], 20 + t / 180)


def test_an_ambiguous_separator_names_the_key_to_set(tmp_path, capsys):
    path = tmp_path / "r.csv"
    path.write_text("time;E|X;T_a|b\n0;1|2;3|4\n60;1|2;3|4\n")
    refused(["run", f"data.path={path}", f"out={tmp_path / 'out'}", *MLR], capsys,
            "r.csv", "separator is ambiguous", "set data.delimiter")


def test_a_folder_without_a_test_split_holds_out_its_last_campaigns(tmp_path):
    folder = tmp_path / "ds"
    folder.mkdir()
    rows = []
    for k, start in enumerate(["2024-03-01", "2024-01-01", "2024-04-01", "2024-02-01"]):
        frame = pd.read_csv(_lab_file(folder / f"c{k}.csv"))
        frame.set_axis(["E_X", "T_1", "T_2"], axis=1).assign(time=np.arange(40) * 60.0).to_csv(
            folder / f"c{k}.csv", index=False)
        rows.append(f"c{k},c{k}.csv,train,{start}")
    (folder / "campaigns.csv").write_text("campaign,file,split,start\n" + "\n".join(rows) + "\n")
    ds, _ = read_dataset(folder, {"test_fraction": 0.25, "val_fraction": 0.25})
    assert ds.ids("test") == ["c2"] and ds.ids("val") == ["c0"]   # latest, then the one before
    assert sorted(ds.ids("train")) == ["c1", "c3"]


def test_init_prints_what_it_detected_and_writes_the_config_run_uses(tmp_path, capsys):
    path = _lab_file(tmp_path / "lab.csv", operator=["anna"] * 40, **{"spindle (rpm)": np.zeros(40)})
    text = path.read_text().replace(",", ";")          # a European export, BOM and all
    path.write_bytes(b"\xef\xbb\xbf" + text.replace(".", ",").encode())
    out = tmp_path / "init"
    assert main(["init", str(path), "data.sample_period_s=60", f"out={out}"]) == 0
    printed = capsys.readouterr().out
    assert "delimiter ';', decimal ','" in printed and "sample period: 60 s" in printed
    rows = {line.split()[0]: line.split()[1:] for line in printed.splitlines() if line.startswith("  ")}
    assert rows["ch1(um)"] == ["error", "E_ch1"] and rows["operator"][0] == "ignore"
    assert rows["spindle"] == ["(rpm)", "state", "S_spindle"]
    command = next(line for line in printed.splitlines() if line.startswith("next: thermocomp run"))
    overrides = [a.strip("'") for a in command.split()[3:]]
    by_init = _run(tmp_path, "by_init", *overrides)
    by_hand = _run(tmp_path, "by_hand", f"data.path={path}", "data.roles.error=['ch*']",
                   "data.roles.state=[spindle]", "data.roles.ignore=[operator]",
                   "data.sample_period_s=60", "data.test_fraction=0.1")
    assert _test_scores(by_init) == _test_scores(by_hand)


def test_init_refuses_a_file_it_cannot_time_and_writes_nothing(tmp_path, capsys):
    path = _lab_file(tmp_path / "lab.csv")
    refused(["init", str(path), f"out={tmp_path / 'init'}"], capsys, "data.sample_period_s")
    assert not (tmp_path / "init").exists()


def test_a_one_file_record_has_a_digest_of_its_own(tmp_path):
    # runs are matched to their dataset by this digest (promote): two records must differ
    from thermocomp.base.files import folder_digest

    a, b = _lab_file(tmp_path / "a.csv"), tmp_path / "b.csv"
    b.write_text(a.read_text().replace("20.", "21."))
    assert folder_digest(a) != folder_digest(b)


def test_a_folder_written_the_european_way_reads_as_written_the_contracts(tmp_path):
    from test_hostile import make_dataset

    plain = make_dataset(tmp_path / "plain")
    european = tmp_path / "european"
    european.mkdir()
    for f in plain.iterdir():
        frame = pd.read_csv(f)
        frame.to_csv(european / f.name, sep=";", decimal=",", index=False)
    ds, _ = read_dataset(european)               # data.delimiter, data.decimal: auto
    expected, _ = read_dataset(plain)
    assert ds.ids("test") == expected.ids("test")
    for cid, frame in expected.campaigns.items():
        pd.testing.assert_frame_equal(ds.campaigns[cid], frame)


def test_a_parquet_record_with_two_time_looking_columns_names_the_key_to_set(tmp_path):
    from thermocomp.core.io import ContractError

    t = np.arange(30) * 15.0
    frame = pd.DataFrame({"Zeit (s)": t, "time": t / 60, "X (um)": t / 100, "T1 (°C)": 20 + t / 1e3})
    frame.to_parquet(tmp_path / "r.parquet")
    with pytest.raises(ContractError, match=r"'Zeit \(s\)' and 'time' both look like the time "
                                            r"\(set data.roles.time\)"):
        read_dataset(tmp_path / "r.parquet", {"roles": {"error": ["X"]}})
    ds, report = read_dataset(tmp_path / "r.parquet", {"roles": {"error": ["X"], "time": "Zeit",
                                                                "ignore": ["time"]}})
    np.testing.assert_allclose(ds.campaigns["r"]["time"], t)
    assert report["column_map"] == {"Zeit (s)": "time", "X (um)": "E_X", "T1 (°C)": "T_T1"}


def test_an_explicit_first_sample_on_a_cut_record_is_warned_about(tmp_path, capsys):
    path = _lab_file(tmp_path / "lab.csv")
    metrics = _run(tmp_path, "out", f"data.path={path}", "data.roles.error=['ch*']",
                   "data.sample_period_s=60", "data.test_fraction=0.25",
                   "data.reference=first_sample")
    assert metrics["reference"] == "first_sample" and metrics["carry_over"] == {}
    warned = [ln for ln in capsys.readouterr().err.splitlines() if "no state carried" in ln]
    assert len(warned) == 1 and "lab_test continues lab_train" in warned[0]


def test_a_folder_without_a_split_column_is_cut_by_the_fraction(tmp_path):
    folder = tmp_path / "ds"
    folder.mkdir()
    for k in range(4):
        frame = pd.read_csv(_lab_file(folder / f"c{k}.csv"))
        frame.set_axis(["E_X (mm)", "T_1", "T_2"], axis=1).to_csv(folder / f"c{k}.csv", index=False)
    (folder / "campaigns.csv").write_text("campaign,file\n" + "".join(f"c{k},c{k}.csv\n"
                                                                        for k in range(4)))
    ds, _ = read_dataset(folder, {"test_fraction": 0.25, "sample_period_s": 60,
                                  "roles": {"error": ["E_*"]}})
    assert ds.ids("test") == ["c3"] and ds.ids("train") == ["c0", "c1", "c2"]
    frame = pd.read_csv(folder / "c0.csv")           # a unit in a contract name: converted
    np.testing.assert_allclose(ds.campaigns["c0"]["E_X"], frame["E_X (mm)"] * 1000)


def test_a_record_that_is_not_there_is_named(tmp_path, capsys):
    refused(["run", f"data.path={tmp_path / 'lab.csv'}", f"out={tmp_path / 'out'}", *MLR], capsys,
            "lab.csv", "no such file")


def test_the_deployed_model_takes_the_labs_names_of_columns_it_did_not_convert(tmp_path):
    from omegaconf import OmegaConf

    from thermocomp.core.io.own_headers import lab_names

    t = np.arange(30) * 10.0
    pd.DataFrame({"t(s)": t, "X(mm)": t / 1e4, "Y(um)": t, "a(°C)": 20 + t / 100,
                  "b(K)": 293.15 + t / 100}).to_csv(tmp_path / "r.csv", index=False)
    ds, _ = read_dataset(tmp_path / "r.csv", {"roles": {"error": ["X", "Y"]}})
    names = lab_names(OmegaConf.create({"data": {"columns": {}}}), ds)
    # renamed only: the lab's name carries the contract's values; converted ones do not
    assert names == {"time": ["t(s)"], "E_Y": ["Y(um)"], "T_a": ["a(°C)"]}


def test_init_keeps_every_reading_key_given_and_reads_a_manifest_as_run_does(tmp_path, capsys):
    folder = tmp_path / "ds"
    folder.mkdir()
    for k in range(4):
        frame = pd.read_csv(_lab_file(folder / f"c{k}.csv"))
        frame.set_axis(["E_X", "T_1", "T_2"], axis=1).assign(time=np.arange(40) * 60.0).to_csv(
            folder / f"c{k}.csv", index=False)
    # no split column: held out by data.test_fraction, which init must read the manifest with
    (folder / "campaigns.csv").write_text("campaign,file\n" + "".join(
        f"c{k},c{k}.csv\n" for k in range(4)))
    out = tmp_path / "init"
    assert main(["init", str(folder), "data.test_fraction=0.25", "data.max_gap_samples=2",
                 f"out={out}"]) == 0
    written = yaml.safe_load((out / "conf" / "data" / "ds.yaml").read_text())
    assert written["test_fraction"] == 0.25 and written["max_gap_samples"] == 2
    assert "interim" not in written and "thousands" not in written    # defaults left to default


def test_init_never_writes_beside_the_labs_record(tmp_path, capsys):
    path = _lab_file(tmp_path / "lab.csv")
    before = snapshot(tmp_path)
    refused(["init", str(path), "data.sample_period_s=60", f"out={tmp_path}"], capsys,
            "holds data.path")
    assert snapshot(tmp_path) == before
