"""Issue 35 item 4: decisions that left the stages for the applications, tested as pure
functions on hand-made values (no config, no registry, no command)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps import fleet
from thermocomp.apps.deploy import server
from thermocomp.apps.deploy.adapt import adapt_figures, finite_rms
from thermocomp.apps.deploy.promotion import (
    Candidate,
    check_dataset,
    deploy_key,
    find_registered,
    validation_figures,
    version_tags,
)
from thermocomp.apps.deploy.report import adapt_line, replay_lines
from thermocomp.apps.diagnose.outputs import diagnosed_model, experiment, search_options
from thermocomp.apps.monitor.stdin import stdin_chain
from thermocomp.base.errors import ConfigError


def _candidate(**kw):
    c = Candidate("run1", {"model.name": "mlr", "select.name": "all"}, "digest1", 1.0,
                  "simulation", "simulation", {}, {"val_rmse": 1.0})
    c.deploy_key, c.figures = "k1", {"val_rmse": 1.0, "rmse": 2.0}
    c.kind = {"adaptive": False, "pod": None}
    for k, v in kw.items():
        setattr(c, k, v)
    return c


def _version(n, **tags):
    return SimpleNamespace(version=str(n), tags=tags)


def test_the_deploy_key_follows_what_builds_the_deployed_object_only():
    monitor = {"window": 20, "model": "a.pkl", "input": None, "map_time_h": 1.0}
    key = deploy_key(True, monitor, {"margin": 0.1})
    # the monitor stage's own keys do not make another deployment
    assert deploy_key(True, {**monitor, "model": "b.pkl", "map_time_h": 3.0}, {"margin": 0.1}) == key
    assert deploy_key(True, {**monitor, "window": 30}, {"margin": 0.1}) != key
    assert deploy_key(False, monitor, {"margin": 0.1}) == deploy_key(False, {}, {"margin": 0.1})
    assert deploy_key(True, monitor, {"margin": 0.2}) != key


def test_a_run_scored_on_another_dataset_is_refused(tmp_path):
    check_dataset({"dataset_hash": "abc"}, {}, "r", "abc", tmp_path)
    with pytest.raises(ConfigError, match="is not the dataset run r was scored on"):
        check_dataset({"dataset_hash": "abd"}, {}, "r", "abc", tmp_path)
    # before the tag existed: its data.path param
    check_dataset({}, {"data.path": str(tmp_path)}, "r", "abc", tmp_path)
    with pytest.raises(ConfigError, match="trained and validated on data.path="):
        check_dataset({}, {"data.path": str(tmp_path / "other")}, "r", "abc", tmp_path)


def test_the_validation_figures_need_the_criterion():
    metrics = {"targets": {"E_X": {"validation": None}}}
    with pytest.raises(ConfigError, match="has no metrics.json"):
        validation_figures({}, "r", "val_rmse", "mean")
    with pytest.raises(ConfigError, match="has no val_rmse"):
        validation_figures(metrics, "r", "val_rmse", "mean")


def test_a_candidate_already_registered_the_same_way_is_found():
    cand = _candidate()
    same = {"dataset_hash": "d", "deploy_config": "k1"}
    asked = []

    def versions():
        asked.append(1)
        return [_version(2, **same, source_run_id="other"), _version(1, **same, model_digest="digest1")]

    assert find_registered(None, versions, cand, "d").version == "1"
    # deployed another way, or on another dataset: a new version
    assert find_registered(None, lambda: [_version(1, dataset_hash="d", deploy_config="k2",
                                                   source_run_id="run1")], cand, "d") is None
    assert find_registered(None, lambda: [_version(1, **same, source_run_id="run1")], cand, "e") is None
    # the champion with the same figures holds it: the registry is not searched
    champion = _version(5, **same, **{"metric.val_rmse": "1", "metric.rmse": "2"})
    asked.clear()
    assert find_registered(champion, versions, cand, "d") is champion and not asked


def test_a_new_versions_tags_say_where_it_comes_from():
    class DS:
        name = "set"
        manifest = pd.DataFrame({"split": ["train", "test"]}, index=["c1", "c2"])

        def ids(self, split=None):
            return [c for c, s in self.manifest["split"].items() if split in (None, s)]

    tags = version_tags(_candidate(deviation=0.00123), DS(), dataset_hash="d",
                        commit=("abc", True), criterion="val_rmse", target="mean",
                        policy="clip", outputs=["corr_E_X", "n_clamped"])
    assert (tags["train_campaigns"], tags["test_campaigns"]) == ("c1", "c2")
    assert tags["stream_deviation_um"] == "0.00123" and tags["pod_modes"] == "none"
    assert (tags["git_commit"], tags["git_dirty"], tags["model"]) == ("abc", True, "mlr")
    assert tags["metric.val_rmse"] == "1" and tags["outputs"] == "corr_E_X,n_clamped"


class _Adaptation:
    def figures(self, j):
        return {"method": "bias", "gain": 1.0, "bias_um": float(j), "n_references": 3}


def test_the_frozen_rmse_skips_what_is_not_finite():
    assert finite_rms(np.array([3.0, np.nan, -3.0, np.inf])) == pytest.approx(3.0)
    assert finite_rms(np.array([np.nan])) is None
    figures = adapt_figures(_Adaptation(), [np.array([[1.0, np.nan]]), np.array([[-1.0, np.nan]])],
                            ["E_X", "E_Y"])
    assert figures["E_X"]["rmse_frozen"] == pytest.approx(1.0)
    assert figures["E_Y"]["rmse_frozen"] is None and figures["E_Y"]["bias_um"] == 1.0
    assert adapt_figures(_Adaptation(), [], ["E_X"])["E_X"]["rmse_frozen"] is None


def test_the_adapt_line_says_frozen_and_adapted_of_each_scored_target():
    targets = {"E_X": {"rmse": 1.0, "adapt": {"method": "rls", "n_references": 4, "rmse_frozen": 2.0}},
               "E_Y": {"rmse": None, "adapt": {"method": "rls", "n_references": 4, "rmse_frozen": 2.0}}}
    assert adapt_line(targets, "frozen -> adapted", "rmse") == [
        "adapt (rls, 4 references): RMSE frozen -> adapted E_X 2.000 -> 1.000"]
    assert adapt_line({"E_X": {"rmse": 1.0}}, "x", "rmse") == []


def test_the_replay_table_has_a_row_per_target_and_the_events_when_adaptive():
    row = {"n_samples": 10, "max_abs_stream_minus_batch": 0.0, "rmse": 1.5, "rmse_batch": None,
           "us_per_sample": 12.0}
    lines = replay_lines({"targets": {"E_X": row, "E_Y": row}, "adaptive": True, "events": [{}],
                          "excluded_inputs": ["T_a"]})
    assert len(lines) == 4 and lines[1].split()[:2] == ["E_X", "10"]
    assert lines[1].split()[4] == "-" and lines[-1] == "events: 1, excluded at a campaign's end: T_a"
    assert len(replay_lines({"targets": {"E_X": row}, "adaptive": False})) == 2


def _group(rmse, train_rows):
    test = {"rmse": rmse, "rms_before": 2 * rmse, "rms_after": rmse}
    y = {f"c{rmse}": np.array([2 * rmse, -2 * rmse])}
    r = {f"c{rmse}": np.array([rmse, -rmse])}
    return {"fit_time_s": 1.0, "targets": {"E_X": {"test": test}},
            "pooled": {"E_X": {"train": {f"t{rmse}": (train_rows, 4.0 * train_rows, 0.1)},
                               "test": (y, r, 1.0)}}}


def test_the_fleet_pools_every_groups_campaigns_and_names_the_worst():
    metrics, table = fleet.fleet_metrics({"M1": _group(1.0, 2), "M2": _group(3.0, 2)},
                                         {"model": "mlr"}, "range", 50)
    assert list(table["group"]) == ["M1", "M2"] and "pooled" not in metrics["groups"]["M1"]
    s = metrics["fleet"]["E_X"]
    assert s["worst_group"] == "M2" and s["test_rmse"]["mean"] == pytest.approx(2.0)
    # pooled: sqrt((2+18)/4) on the test split, sqrt(16/4) on the train split
    assert metrics["targets"]["E_X"]["test"]["rmse"] == pytest.approx(np.sqrt(5.0))
    assert metrics["targets"]["E_X"]["train"]["rmse"] == pytest.approx(2.0)
    assert metrics["fit_time_s"] == 2.0


def test_the_diagnosed_model_wraps_the_ati_around_the_base():
    effect = SimpleNamespace(to_dict=lambda: {"kind": "lag"})
    model = diagnosed_model({"_target_": "M"}, {"_target_": "ATI", "_partial_": True}, "first",
                            {"E_X": [effect]}, "mlr+diagnosed", {"E_X": 0.5, "E_Y": 0.0})
    est = model["estimator"]
    assert est["estimator"] == {"_target_": "ATI", "base_estimator": {"_target_": "M"}}
    assert est["alpha"] == {"E_X": 0.5} and est["effects"] == {"E_X": [{"kind": "lag"}]}
    assert diagnosed_model({"_target_": "M"}, None, "first", {}, "n")["estimator"]["alpha"] is None


def test_the_experiment_pins_what_the_diagnosis_ran_with():
    exp = experiment("base", True, {"select": {"name": "pearson"}, "denoise": None}, "none",
                     ["T_a"], "one_step")
    assert exp["defaults"] == [{"override /model": "diagnosed"}, {"override /ati": "none"},
                               {"override /select": "pearson"}]
    assert exp["data"] == {"reference": "none", "inputs": ["T_a"]} and "denoise" not in exp
    assert exp["eval"] == {"mode": "one_step"} and exp["name"] == "base-diagnosed"


def test_the_search_settings_are_read_from_plain_values():
    d = dict(max_effects=2, min_gain_pct=1, alpha=0.05, shortlist=3, n_folds=4, n_blocks=5,
             seed=7, cv="blocked", min_train_fraction=0.5, shrink=True, taus_s=[60, 120],
             n_squares=1, fault_ratio=2, families=["lag"], initial_directions=[1])
    options = search_options(d)
    assert options.candidates.taus_s == (60.0, 120.0) and options.seed == 7


class _DS:
    def __init__(self, ids):
        self._ids = ids

    def ids(self, split=None):
        return self._ids


def test_a_stream_on_stdin_without_ambient_needs_the_campaign_it_continues():
    assert stdin_chain(_DS(["a"]), None, ambient_given=False, reference="none", data_path="p") == []
    with pytest.raises(ConfigError, match="monitor.input=-"):
        stdin_chain(_DS(["a"]), None, ambient_given=True, reference="none", data_path="p")
    with pytest.raises(ConfigError, match="monitor.continues=b: no such campaign"):
        stdin_chain(_DS(["a"]), "b", ambient_given=False, reference="none", data_path="p")
    with pytest.raises(ConfigError, match="data.reference=first"):
        stdin_chain(_DS(["a"]), "a", ambient_given=False, reference="first", data_path="p")


@pytest.mark.parametrize("host, loopback", [("localhost", True), ("127.0.0.1", True),
                                            ("::1", True), ("0.0.0.0", False),
                                            ("machine.example", False)])
def test_only_a_loopback_host_is_local(host, loopback):
    assert server.is_loopback(host) is loopback


def test_the_server_runs_one_worker_with_the_limits_in_its_environment(tmp_path):
    argv, env = server.server_command(str(tmp_path), "sqlite:///x.db", host="127.0.0.1", port=5001,
                                      timeout_s=2.5, max_rows=7, max_body_mb=0.5)
    assert argv[argv.index("--workers") + 1] == "1" and argv[argv.index("--port") + 1] == "5001"
    assert (env[server.ROWS_ENV], env[server.BODY_ENV]) == ("7", str(2**19))
    assert env["MLFLOW_SCORING_SERVER_REQUEST_TIMEOUT"] == "3"
