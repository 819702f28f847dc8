"""The ranking behind `compare` and the champion gate of `promote` (pure functions)."""

import math

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.metrics import split_scores
from thermocomp.core.scoring.leaderboard import (
    baseline_rows,
    beats,
    is_validation,
    persistence_summary,
    rank,
    summary,
    to_markdown,
    validation_method,
)
from thermocomp.core.scoring.results import e_p95_at


def _targets(scale_x=1.0, scale_z=1.0, n=241, dt=60.0, seed=0):
    rng = np.random.default_rng(seed)
    out = {}
    for t, scale in (("E_X", scale_x), ("E_Z", scale_z)):
        y = {c: np.cumsum(rng.normal(0, 1, n)) for c in ("A", "B")}
        r = {c: scale * rng.normal(0, 1, n) for c in y}
        out[t] = {"test": split_scores(y, r, dt, "range", None)}
    return out


def test_e_p95_is_interpolated_in_the_curve_and_null_beyond_the_campaigns():
    e = {"window_s": [60.0, 1800.0, 5400.0], "after": [1.0, 2.0, 4.0], "before": [3.0, 5.0, 9.0]}
    assert e_p95_at(e, 3600.0) == pytest.approx(3.0)
    assert e_p95_at(e, 3600.0, "before") == pytest.approx(7.0)
    assert e_p95_at(e, 8 * 3600.0) is None
    assert e_p95_at({"window_s": [], "after": []}, 60.0) is None
    real = _targets()["E_X"]["test"]["e_p95"]                 # 4 h campaigns at 1 min
    direct = np.interp(3600.0, real["window_s"], real["after"])
    assert e_p95_at(real, 3600.0) == pytest.approx(direct)


def test_summary_per_target_and_mean():
    targets = _targets(scale_x=1.0, scale_z=3.0)
    x, z, mean = summary(targets, "E_X"), summary(targets, "E_Z"), summary(targets)
    assert z["rsd_mean"] > 2 * x["rsd_mean"]
    assert mean["rsd_mean"] == pytest.approx((x["rsd_mean"] + z["rsd_mean"]) / 2)
    te = targets["E_X"]["test"]
    assert x["rms_reduction_pct"] == pytest.approx(100 * (1 - te["rms_after"] / te["rms_before"]))
    assert x["e_p95_8h"] is None and x["e_p95_1h"] is not None
    with pytest.raises(KeyError, match="E_Q"):
        summary(targets, "E_Q")


def test_rank_orders_by_criterion_missing_last_and_beats_respects_direction():
    rows = [{"run_id": "a", "rsd_mean": 2.0, "rms_reduction_pct": 80.0},
            {"run_id": "b", "rsd_mean": None, "rms_reduction_pct": None},
            {"run_id": "c", "rsd_mean": 1.0, "rms_reduction_pct": 90.0}]
    assert list(rank(rows, "rsd_mean")["run_id"]) == ["c", "a", "b"]
    assert list(rank(rows, "rms_reduction_pct")["run_id"]) == ["c", "a", "b"]
    assert list(rank(rows, "rsd_mean", descending=True)["run_id"]) == ["a", "c", "b"]
    # a test column as the printed table heads it (test:rsd_mean) was refused
    assert list(rank(rows, "test:rms_reduction_pct")["run_id"]) == ["c", "a", "b"]
    with pytest.raises(KeyError, match="nope"):
        rank(rows, "nope")
    assert beats(1.0, 2.0, "rsd_mean") and not beats(2.0, 1.0, "rsd_mean")
    assert not beats(1.0, 1.0, "rsd_mean")                       # a tie keeps the champion
    assert not beats(1.9, 2.0, "rsd_mean", min_improvement=0.2)
    assert beats(91.0, 90.0, "rms_reduction_pct") and not beats(89.0, 90.0, "rms_reduction_pct")
    assert beats(1.0, None, "rsd_mean") and not beats(None, 1.0, "rsd_mean")
    assert not beats(math.nan, 1.0, "rsd_mean")
    md = to_markdown(rank(rows, "rsd_mean"))
    assert md.splitlines()[2].startswith("| c") and "n/a" in md


def test_summary_carries_the_validation_figures_that_rank_and_the_test_ones_beside():
    targets = _targets(scale_x=1.0, scale_z=3.0)
    assert summary(targets)["val_rmse"] is None               # eval.validation=false: no figure
    for t, v in (("E_X", 1.0), ("E_Z", 3.0)):
        targets[t]["validation"] = {"rmse": v, "rsd_mean": v / 2, "rsd_sd": None,
                                    "method": "leave-campaigns-out (4 folds)"}
    x, mean = summary(targets, "E_X"), summary(targets)
    assert (x["val_rmse"], mean["val_rmse"], mean["val_rsd_mean"]) == (1.0, 2.0, 1.0)
    assert mean["val_rsd_sd"] is None and mean["rsd_mean"] == pytest.approx(
        (x["rsd_mean"] + summary(targets, "E_Z")["rsd_mean"]) / 2)
    assert validation_method(targets) == "leave-campaigns-out (4 folds)"
    assert is_validation("val_rmse") and not is_validation("rsd_mean")
    rows = [{"run_id": "a", "val_rmse": 2.0, "rmse": 0.1}, {"run_id": "b", "val_rmse": 1.0, "rmse": 9.0}]
    table = rank(rows)                                           # default: validation RMSE
    assert list(table["run_id"]) == ["b", "a"]
    header = to_markdown(table).splitlines()[0]
    assert "val_rmse" in header and "test:rmse" in header


def test_persistence_baseline_row_from_the_runs_metrics():
    rng = np.random.default_rng(4)
    targets = _targets()
    for t, m in targets.items():   # the persistence block score() writes: its residual's figures
        y = {c: np.cumsum(rng.normal(0, 1, 241)) for c in ("A", "B")}
        r = {c: y[c] - np.r_[0.0, y[c][:-1]] for c in y}
        m["persistence"] = split_scores(y, r, 60.0, with_before_after=False)
    x, mean = persistence_summary(targets, "E_X"), persistence_summary(targets)
    p = targets["E_X"]["persistence"]
    assert (x["rmse"], x["rsd_mean"], x["rsd_sd"]) == (p["rmse"], p["rsd_mean"], p["rsd_sd"])
    before = targets["E_X"]["test"]["rms_before"]
    assert x["rms_reduction_pct"] == pytest.approx(100 * (1 - p["rmse"] / before))
    assert mean["rmse"] == pytest.approx((p["rmse"] + targets["E_Z"]["persistence"]["rmse"]) / 2)
    rows = baseline_rows([mean, None, dict(mean), x])   # runs on the same data share one baseline
    assert [r["model"] for r in rows] == ["persistence (baseline)"] * 2
    assert persistence_summary({"E_X": {"test": {}}}) is None   # metrics of an older run


def test_the_markdown_table_rounds_a_column_with_a_missing_figure():
    table = pd.DataFrame({"run": ["a", "b"], "e_p95_1h": [3.0209619546576048, None],
                          "n": [1, 2]})
    rows = to_markdown(table).splitlines()[2:]
    assert "| 3.02 " in rows[0] and "n/a" in rows[1] and "3.0209" not in "".join(rows)


def test_compare_reports_the_test_mae_beside_the_rmse_and_can_sort_by_it():
    """MAE (what fl_thermal's authors report) is a test column of compare and of the baseline
    row, the mean over targets of each run's metrics.json ``mae``; it reports, never chooses."""
    targets = _targets(scale_x=1.0, scale_z=3.0)
    x, z, mean = summary(targets, "E_X"), summary(targets, "E_Z"), summary(targets)
    assert x["mae"] == targets["E_X"]["test"]["mae"] and mean["mae"] == pytest.approx(
        (x["mae"] + z["mae"]) / 2)
    assert 0 < x["mae"] < x["rmse"]
    rows = [{"run_id": "a", "val_rmse": 1.0, "mae": 2.0}, {"run_id": "b", "val_rmse": 2.0, "mae": 1.0}]
    assert list(rank(rows, "test:mae")["run_id"]) == ["b", "a"]
    assert "test:mae" in to_markdown(rank(rows)).splitlines()[0]
    assert not is_validation("mae")
