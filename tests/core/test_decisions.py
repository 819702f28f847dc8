"""Issue 35 item 4: decisions that left the stages for the core, tested as pure functions on
hand-made values (no config, no registry, no command)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.base.errors import ConfigError
from thermocomp.core.io import ContractError, ReadOptions
from thermocomp.core.io.detect import data_config, proposed_roles
from thermocomp.core.io.stdin import read_stream
from thermocomp.core.models.auto import as_chosen, candidate_family, check_candidates
from thermocomp.core.scoring.comparison import compare_json, headline_line, shown_table


def test_a_stream_on_stdin_is_read_as_a_campaign_file():
    text = "\ufefftime;T_a;E_X\n0;20,5;1\n2;;2\n"
    df, missing = read_stream(text, ["T_a"], ReadOptions(delimiter="auto", decimal=","))
    assert df["T_a"].tolist()[0] == 20.5 and np.isnan(df["T_a"].iloc[1])
    assert missing == {"T_a": 1}


def test_stdin_timestamps_become_seconds_from_the_first_row():
    text = "time,T_a\n2024-01-01T00:00:00Z,1\n2024-01-01T00:01:30Z,2\n"
    df, _ = read_stream(text, ["T_a"], ReadOptions())
    assert df["time"].tolist() == [0.0, 90.0]


@pytest.mark.parametrize("text, says", [("time,T_a\n", "no data row"),
                                        ("time,T_b\n0,1\n", "lacks a column"),
                                        ("time,T_a\n0,1\n1,hot\n", "non-numeric")])
def test_a_bad_stream_is_refused_naming_what(text, says):
    with pytest.raises(ContractError, match=says):
        read_stream(text, ["T_a"], ReadOptions())


def test_roles_are_proposed_from_the_units_and_text_is_ignored():
    header = ["time", "spindle [rpm]", "X error [µm]", "T front [°C]", "operator"]
    first = dict(zip(header, ["0", "1000", "1.5", "20.1", "anna"]))
    roles = proposed_roles(header, first, ReadOptions())
    assert roles["state"] == ["spindle"] and roles["error"] == ["X error"]
    assert roles["ignore"] == ["operator"]


def test_given_roles_are_kept_as_they_are():
    opts = ReadOptions(roles={"error": ["dX"]})
    assert proposed_roles(["dX [rpm]"], {"dX [rpm]": "1"}, opts)["state"] == []


def test_the_data_config_keeps_what_differs_from_the_defaults(tmp_path):
    record = tmp_path / "r.csv"
    record.write_text("time\n0\n")
    defaults = {"thousands": None, "time": "auto", "interim": "data/interim", "test_fraction": None}
    given = {"thousands": ".", "time": "auto", "interim": "elsewhere", "test_fraction": None}
    config = data_config(record, given, ReadOptions(delimiter=";"), {"error": []}, defaults)
    assert config["thousands"] == "." and "time" not in config and "interim" not in config
    assert config["test_fraction"] == 0.1        # one record: its last tenth is the test split
    assert data_config(tmp_path, given, ReadOptions(), {}, defaults)["test_fraction"] == 0.1
    (tmp_path / "campaigns.csv").write_text("campaign,file,split\nK1,r.csv,train\n")  # all train
    assert data_config(tmp_path, given, ReadOptions(), {}, defaults)["test_fraction"] == 0.1
    (tmp_path / "campaigns.csv").write_text("campaign,file,split\nK1,r.csv,test\n")  # its own test
    assert "test_fraction" not in data_config(tmp_path, given, ReadOptions(), {}, defaults)


def _ranked():
    return pd.DataFrame({"run_id": ["aaaaaaaaaa", "bbbbbbbbbb"], "model": ["mlr", "arx"],
                         "select": ["pearson", "pearson"], "val_rmse": [1.0, 2.0],
                         "rmse": [1.5, 2.5], "e_p95_8h": [np.nan, np.nan]})


def test_the_shown_table_marks_the_baseline_and_drops_empty_columns():
    base = {"model": "persistence", "needs_measured_error_online": True, "rmse": 9.0,
            "val_rmse": None, "e_p95_8h": None}
    shown = shown_table(_ranked(), [base])
    assert shown["run"].tolist() == ["aaaaaaaa", "bbbbbbbb", "baseline"]
    assert shown["model"].iloc[-1].startswith("persistence: ")
    assert "e_p95_8h" not in shown.columns and "run_id" not in shown.columns
    assert shown_table(_ranked(), [])["run"].tolist() == ["aaaaaaaa", "bbbbbbbb"]


def test_compare_json_names_the_best_run_and_what_was_not_used_to_choose():
    basis = {"figure": "val_rmse", "mode": "simulation", "fallback": {}}
    j = compare_json(_ranked(), "val_rmse", "mean", "p1", [], basis)
    assert j["best"]["run_id"] == "aaaaaaaaaa" and j["n_runs"] == 2
    assert j["ranked_by_validation"] and "rmse" in j["reported_not_used_to_choose"]
    assert list(j["runs"]) == ["00_aaaaaaaa", "01_bbbbbbbb"]


def test_sorting_by_a_test_figure_is_said_to_be_no_choice():
    assert "do not choose" in headline_line("p", 2, "rmse", "mean", {})
    basis = {"figure": "val_rmse", "mode": "simulation", "fallback": {}}
    assert "simulation-mode validation" in headline_line("p", 2, "val_rmse", "mean", basis)


@pytest.mark.parametrize("name, family", [("lagbank", "lagbank"), ("ati", "mlr"),
                                          ("ati+arx", "arx")])
def test_a_candidate_names_its_family(name, family):
    assert candidate_family(name) == family


@pytest.mark.parametrize("name", ["auto", "x+arx", " ", "ati+ati"])
def test_a_candidate_that_names_no_family_is_refused(name):
    with pytest.raises(ConfigError, match="not a model family"):
        candidate_family(name)


@pytest.mark.parametrize("candidates, params, says", [
    ("mlr", {}, "must be a list"), (["mlr"], [], "candidate_params"),
    ([], {}, "is empty"), (["mlr"], {"arx": {}}, "not among")])
def test_the_candidates_settings_are_checked_for_shape(candidates, params, says):
    with pytest.raises(ConfigError, match=says):
        check_candidates(candidates, params, {})


def test_as_chosen_fixes_each_targets_family_only_for_an_auto_template():
    class Est:
        def __init__(self):
            self.params = {}

        def get_params(self, deep=False):
            return {"chosen": None}

    class Template:
        estimator = Est()

        def set_params(self, **kw):
            self.set = kw
            return self

    class Chose:
        def __init__(self, family):
            self.family_ = family

    fitted = type("F", (), {"estimators_": {"E_X": Chose("arx"), "E_Y": Chose("mlr")}})()
    template = Template()
    assert as_chosen(template, fitted).set == {"estimator__chosen": {"E_X": "arx", "E_Y": "mlr"}}
    plain = Template()
    assert as_chosen(plain, object()) is plain and not hasattr(plain, "set")


def test_two_baselines_of_one_dataset_name_their_runs():
    """In the first-sample frame a late first probe's label is completed by each model's own
    y_hat(m), so persistence differs per run (stranger62's hobbing bench: 1.83 and 1.86 um):
    two rows both called 'baseline' left a reader to guess which is whose."""
    from thermocomp.core.scoring.leaderboard import FIGURES, baseline_rows

    figures = {f: None for f in FIGURES}
    found = [{**figures, "rmse": 1.83, "run_id": "aaaaaaaaaa"},
             {**figures, "rmse": 1.86, "run_id": "bbbbbbbbbb"}]
    shown = shown_table(_ranked(), baseline_rows(found))
    assert shown["run"].tolist()[-2:] == ["baseline of aaaaaaaa", "baseline of bbbbbbbb"]
    one = baseline_rows([found[0], {**found[1], "rmse": 1.83}])
    assert shown_table(_ranked(), one)["run"].tolist()[-1] == "baseline"
