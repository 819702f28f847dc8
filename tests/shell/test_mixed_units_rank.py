"""`compare` and `promote` rank by a mean over targets of one unit (isoleft67).

A sensor nest's tilts (µm/m) beside its X, Y, Z (µm): the mean over every target added two units.
The data make the two means disagree: ``E_X`` (µm) follows a slow drift read by ``T_2``, the tilt
``E_Tilt_A`` (µm/m, large) a fast signal read by ``T_1``.  By the mean over both (before), the run
on ``T_1`` ranked first for its tilt, though its X is several µm worse; by the mean over the µm
targets, the run on ``T_2``, said so.  A record of one unit ranks as before
(tests/shell/test_choose_by_simulation.py: its ``ranked_by`` exactly as it was).
"""

from __future__ import annotations

import json

import pytest

from conftest import LIGHT
from test_choose_by_simulation import slow_and_fast, sweep_runs
from test_deploy import mlflow_store
from thermocomp.core.scoring.champion import champion_validation
from thermocomp.core.scoring.leaderboard import mean_label, mean_over, rank, summary
from thermocomp.shell.cli import main

LABEL = "mean of E_X (µm; E_Tilt_A in µm/m left out)"


def drift_and_tilt(root):
    """``E_X`` 3 µm/K of the slow ramp (``T_2``), ``E_Tilt_A`` 40 µm/m per K of the fast signal
    (``T_1``)."""
    return slow_and_fast(root, lambda slow, fast, rng: {
        "E_X": 3.0 * slow + rng.normal(0.0, 0.02, slow.size),
        "E_Tilt_A": 40.0 * fast + rng.normal(0.0, 0.05, slow.size)})


@pytest.fixture(scope="module")
def tilt_sweep(tmp_path_factory):
    """``-m`` over the two input sets, tracked in a fresh store; each run's metrics."""
    root = tmp_path_factory.mktemp("mixed")
    data = drift_and_tilt(root / "ds")
    uri = mlflow_store(root)
    sweep = root / "sweep"
    assert main(["run", "-m", f"data.path={data}", f"tracking_uri={uri}", *LIGHT,
                 "data.inputs=[T_1],[T_2]", f"hydra.sweep.dir={sweep}"]) == 0
    runs = {}
    for r, metrics in sweep_runs(uri, root):
        val = {t: m["validation"]["rmse"] for t, m in metrics["targets"].items()}
        runs[r.info.run_id] = {"inputs": r.data.params["data.inputs"], "val": val,
                               "targets": metrics["targets"]}
    assert len(runs) == 2
    return {"root": root, "data": data, "uri": uri, "sweep": sweep, "runs": runs}


def _by(runs: dict, key) -> str:
    return runs[min(runs, key=lambda r: key(runs[r]["val"]))]["inputs"]


def test_the_mean_over_the_um_targets_leaves_the_tilt_out(tilt_sweep):
    runs = tilt_sweep["runs"]
    # the data as meant: the two means choose differently
    assert _by(runs, lambda v: (v["E_X"] + v["E_Tilt_A"]) / 2) == "['T_1']"
    assert _by(runs, lambda v: v["E_X"]) == "['T_2']"
    for r in runs.values():
        assert mean_over(r["targets"]) == (["E_X"], ["E_Tilt_A"])
        assert summary(r["targets"])["val_rmse"] == pytest.approx(r["val"]["E_X"])
        assert summary(r["targets"], "E_Tilt_A")["val_rmse"] == pytest.approx(r["val"]["E_Tilt_A"])
        assert mean_label(r["targets"]) == LABEL


def test_compare_ranks_by_the_um_mean_and_says_which_targets(tilt_sweep, capsys):
    s, runs = tilt_sweep, tilt_sweep["runs"]
    out = s["root"] / "compare"
    assert main(["compare", f"tracking_uri={s['uri']}", f"compare.sweep={s['sweep']}",
                 f"compare.out={out}"]) == 0
    printed = capsys.readouterr().out
    report = json.loads((out / "compare.json").read_text())
    assert runs[report["best"]["run_id"]]["inputs"] == "['T_2']"
    assert report["ranked_by"]["mean_over"] == [LABEL]
    assert LABEL in printed
    # one tilt ranks by itself, as asked
    assert main(["compare", f"tracking_uri={s['uri']}", f"compare.sweep={s['sweep']}",
                 f"compare.out={out}", "compare.target=E_Tilt_A"]) == 0
    report = json.loads((out / "compare.json").read_text())
    assert runs[report["best"]["run_id"]]["inputs"] == "['T_1']"
    assert "mean_over" not in report["ranked_by"]


def test_promote_takes_the_um_best_and_tags_what_it_was_ranked_by(tilt_sweep, capsys):
    s, runs = tilt_sweep, tilt_sweep["runs"]
    out = s["root"] / "promote"
    assert main(["promote", f"data.path={s['data']}", f"tracking_uri={s['uri']}",
                 f"compare.sweep={s['sweep']}", f"out={out}", "monitor.adaptive=false"]) == 0
    report = json.loads((out / "promote.json").read_text())
    chosen = runs[report["run_id"]]
    assert chosen["inputs"] == "['T_2']"
    assert report["candidate"]["score"] == pytest.approx(chosen["val"]["E_X"])
    assert report["ranked_by"]["mean_over"] == [LABEL]
    from mlflow import MlflowClient

    tags = MlflowClient(s["uri"]).get_model_version(report["model_name"], report["version"]).tags
    assert tags["criterion_target"] == LABEL


def test_a_champion_scored_by_the_mean_of_two_units_is_no_score_to_beat():
    old = {"dataset_hash": "d", "criterion_target": "mean", "validation_mode": "simulation",
           "metric.val_rmse": "3.5"}
    targets = ["E_X", "E_Tilt_A"]
    score, why = champion_validation(old, "val_rmse", mean_label(targets), "d", "simulation")
    assert score is None and "another target" in why
    # one unit: the tag and the comparison as before
    assert mean_label(["E_X", "E_Z"]) == "mean" and mean_label(["E_AX", "E_Tilt_A"]) == "mean"
    assert champion_validation(old, "val_rmse", mean_label(["E_X", "E_Z"]), "d",
                               "simulation") == (3.5, None)


def test_one_unit_ranks_exactly_as_before():
    rows = [{"run_id": "a", "val_rmse": 2.0}, {"run_id": "b", "val_rmse": 1.0}]
    assert list(rank(rows)["run_id"]) == ["b", "a"]
    entry = {"test": {"rmse": 1.0}, "validation": {"rmse": 0.4, "method": "leave-campaigns-out"}}
    other = {"test": {"rmse": 3.0}, "validation": {"rmse": 0.8, "method": "leave-campaigns-out"}}
    for targets in ({"E_X": entry, "E_Z": other}, {"E_AX": entry, "E_Tilt_A": other}):
        assert mean_over(targets) == (list(targets), [])
        assert summary(targets)["val_rmse"] == pytest.approx(0.6)


def test_the_lab_matrix_table_says_each_targets_unit(tmp_path):
    """benchmarks/lab_matrix.py's table: it headed every target's figures ``run (µm)``."""
    import sys
    from pathlib import Path

    benchmarks = Path(__file__).resolve().parents[2] / "benchmarks"
    sys.path.insert(0, str(benchmarks))
    try:
        import lab_matrix
    finally:
        sys.path.remove(str(benchmarks))
    run = {"E_X1": 0.3, "E_Z": 0.9, "E_Tilt_A": 5.0}
    row = {"cell": "iso-mlr-plain", "run": run, "replay": run, "replay-run": 0.0,
           "stream-batch": 1e-14, "promote": 0.6, "run_mean": 0.6, "check": 0}
    (tmp_path / "matrix-iso.jsonl").write_text(json.dumps(row) + "\n")
    text = lab_matrix.table(tmp_path, "iso")
    assert "run (µm)" not in text
    assert "E_X1 µm / E_Z µm / E_Tilt_A µm/m" in text
    assert "the mean over E_X1, E_Z (µm)" in text
