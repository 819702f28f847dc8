"""`compare` and `promote` choose by the deployed mode's validation (issue 34, item 2).

A deployed compensator runs in simulation (its own free run), so a run scored with
``eval.mode=one_step`` also records its simulation-mode validation and the sweep is ranked by
that one.  The data make the two rankings disagree: the error is a slow drift (read by ``T_2``)
plus a fast part (read by ``T_1``).  One-step, persistence carries the drift and ``T_1`` alone
wins; in simulation only ``T_2`` reaches the drift and ``T_1`` alone is far worse.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from conftest import LIGHT
from test_deploy import mlflow_store
from thermocomp.core.scoring import leaderboard
from thermocomp.core.scoring.leaderboard import rank, summary
from thermocomp.shell.cli import main

INPUTS = {"fast": "[T_1]", "slow": "[T_2]"}


def slow_and_fast(root, errors, n_campaigns: int = 5, rows: int = 80, seed: int = 0):
    """Campaigns (the last one test) of two sensors, ``T_2`` reading a slow ramp and ``T_1`` a
    fast random signal; ``errors(slow, fast, rng)``: the ``E_`` columns."""
    rng = np.random.default_rng(seed)
    root.mkdir(parents=True)
    manifest = []
    for i in range(n_campaigns):
        t = np.arange(rows) * 60.0
        slow = (2.0 + i) * (1 - np.exp(-t / (1500.0 + 300 * i)))
        fast = rng.normal(0.0, 1.0, rows)
        cid = f"K{i:02d}"
        pd.DataFrame({"time": t, "T_1": 20 + fast, "T_2": 20 + slow, **errors(slow, fast, rng)}
                     ).to_csv(root / f"{cid}.csv", index=False)
        manifest.append((cid, f"{cid}.csv", "test" if i == n_campaigns - 1 else "train", ""))
    pd.DataFrame(manifest, columns=["campaign", "file", "split", "notes"]).to_csv(
        root / "campaigns.csv", index=False)
    return root


def drift_and_fast(root):
    """The error is 3 µm/K of the slow ramp plus 1 µm/K of the fast signal."""
    return slow_and_fast(root, lambda slow, fast, rng: {
        "E_X": 3.0 * slow + 1.0 * fast + rng.normal(0.0, 0.02, slow.size)})


def sweep_runs(uri: str, root) -> list:
    """The child runs of the sweeps in the store at ``uri``, each with its ``metrics.json``
    (downloaded below ``root``)."""
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    exp = client.get_experiment_by_name("thermocomp").experiment_id
    return [(r, json.loads(open(client.download_artifacts(r.info.run_id, "metrics.json",
                                                          str(root))).read()))
            for r in client.search_runs([exp]) if r.data.tags.get("thermocomp.sweep") != "parent"]


def _metrics(out) -> dict:
    return json.loads((out / "metrics.json").read_text())


def test_a_one_step_run_records_the_simulation_validation_of_the_same_model(tmp_path, capsys):
    data = drift_and_fast(tmp_path / "ds")
    common = ["run", f"data.path={data}", "track=false", *LIGHT, f"data.inputs={INPUTS['slow']}"]
    assert main([*common, "eval.mode=simulation", f"out={tmp_path / 'sim'}"]) == 0
    assert main([*common, "eval.mode=one_step", f"out={tmp_path / 'one'}"]) == 0
    sim, one = _metrics(tmp_path / "sim"), _metrics(tmp_path / "one")
    recorded = one["targets"]["E_X"]["validation_simulation"]
    assert recorded == sim["targets"]["E_X"]["validation"]        # the same folds, the same fits
    assert one["targets"]["E_X"]["validation"]["rmse"] != recorded["rmse"]
    assert "validation_simulation" not in sim["targets"]["E_X"]   # no copy of itself
    # what ranks: the simulation figure, for both runs alike
    assert summary(one["targets"])["val_rmse"] == summary(sim["targets"])["val_rmse"]
    assert leaderboard.validation_mode(one) == leaderboard.validation_mode(sim) == "simulation"


def test_an_old_one_step_run_falls_back_to_its_own_validation_ranked_after_the_others():
    entry = {"test": {"rmse": 1.0}, "validation": {"rmse": 0.1, "method": "leave-campaigns-out"}}
    old = {"mode": "one_step", "targets": {"E_X": entry}}          # made before the key existed
    assert leaderboard.validation_mode(old) == "one_step"
    assert summary(old["targets"])["val_rmse"] == 0.1
    rows = [{"run_id": "old", "val_rmse": 0.1, "val_mode": "one_step"},
            {"run_id": "sim", "val_rmse": 0.9, "val_mode": "simulation"},
            {"run_id": "none", "val_rmse": None, "val_mode": None}]
    assert list(rank(rows)["run_id"]) == ["sim", "old", "none"]


@pytest.fixture(scope="module")
def two_mode_sweep(tmp_path_factory):
    """``-m eval.mode=simulation,one_step`` over the two input sets, tracked in a fresh store."""
    root = tmp_path_factory.mktemp("choose")
    data = drift_and_fast(root / "ds")
    uri = mlflow_store(root)
    sweep = root / "sweep"
    assert main(["run", "-m", f"data.path={data}", f"tracking_uri={uri}", *LIGHT,
                 "eval.mode=simulation,one_step", f"data.inputs={INPUTS['fast']},{INPUTS['slow']}",
                 f"hydra.sweep.dir={sweep}"]) == 0
    runs = {}
    for r, metrics in sweep_runs(uri, root):
        runs[r.info.run_id] = {"inputs": r.data.params["data.inputs"], "mode": metrics["mode"],
                               "own": metrics["targets"]["E_X"]["validation"]["rmse"],
                               "simulation": summary(metrics["targets"])["val_rmse"],
                               "logged": r.data.metrics}
    assert len(runs) == 4
    return {"root": root, "data": data, "uri": uri, "sweep": sweep, "runs": runs}


def _best(runs: dict, key: str) -> str:
    return min(runs, key=lambda r: runs[r][key])


def test_the_two_rankings_differ_on_this_data(two_mode_sweep):
    runs = two_mode_sweep["runs"]
    by_own, by_sim = runs[_best(runs, "own")], runs[_best(runs, "simulation")]
    assert (by_own["inputs"], by_own["mode"]) == ("['T_1']", "one_step")
    assert by_sim["inputs"] == "['T_2']"


def test_a_one_step_run_logs_its_simulation_validation_to_mlflow(two_mode_sweep):
    runs = two_mode_sweep["runs"].values()
    for one in (r for r in runs if r["mode"] == "one_step"):
        sim = next(r for r in runs if r["mode"] == "simulation" and r["inputs"] == one["inputs"])
        assert one["logged"]["E_X.validation_simulation.rmse"] == sim["logged"]["E_X.val.rmse"]


def test_promote_chooses_by_the_simulation_mode_validation_and_says_so(two_mode_sweep, capsys):
    s, runs = two_mode_sweep, two_mode_sweep["runs"]
    out = s["root"] / "promote"
    assert main(["promote", f"data.path={s['data']}", f"tracking_uri={s['uri']}",
                 f"compare.sweep={s['sweep']}", f"out={out}", "monitor.adaptive=false"]) == 0
    said = capsys.readouterr()
    report = json.loads((out / "promote.json").read_text())
    chosen = runs[report["run_id"]]
    assert chosen["inputs"] == "['T_2']"
    assert chosen["simulation"] == min(r["simulation"] for r in runs.values())
    assert report["candidate"]["score"] == pytest.approx(chosen["simulation"])
    assert report["ranked_by"] == {"figure": "val_rmse", "mode": "simulation", "fallback": {}}
    assert "simulation-mode validation" in said.err


def test_compare_ranks_by_the_simulation_mode_validation_and_says_so(two_mode_sweep, capsys):
    s, runs = two_mode_sweep, two_mode_sweep["runs"]
    out = s["root"] / "compare"
    assert main(["compare", f"tracking_uri={s['uri']}", f"compare.sweep={s['sweep']}",
                 f"compare.out={out}"]) == 0
    printed = capsys.readouterr().out
    report = json.loads((out / "compare.json").read_text())
    assert report["ranked_by"] == {"figure": "val_rmse", "mode": "simulation", "fallback": {}}
    ranked = [report["runs"][k] for k in sorted(report["runs"])]
    assert [r["val_rmse"] for r in ranked] == sorted(r["simulation"] for r in runs.values())
    assert runs[report["best"]["run_id"]]["inputs"] == "['T_2']"
    assert "simulation-mode validation" in printed


def test_compare_says_the_mode_of_the_test_figures_it_reports(two_mode_sweep, capsys):
    """audit96b: the validation columns are the simulation mode's whatever ``eval.mode``, the
    reported test columns the run's own; a one_step run's test RMSE (its one-step figure) read
    beside the simulation-mode validation with nothing saying so.  Fails on 324eb8b2 (no
    ``test_mode`` column)."""
    s, runs = two_mode_sweep, two_mode_sweep["runs"]
    out = s["root"] / "compare_modes"
    assert main(["compare", f"tracking_uri={s['uri']}", f"compare.sweep={s['sweep']}",
                 f"compare.out={out}"]) == 0
    assert "test_mode" in capsys.readouterr().out
    table = pd.read_csv(out / "compare.csv").set_index("run_id")
    assert table["val_mode"].eq("simulation").all()
    assert {run_id: table.loc[run_id, "test_mode"] for run_id in runs} == {
        run_id: r["mode"] for run_id, r in runs.items()}
