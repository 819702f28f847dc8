"""A reference error measured now and then (a probe cycle) on a dense temperature log (sparse61).

The error is measured on 1 row in 30, the cells in between empty: read as such
(``data.sparse_targets=auto``), never interpolated, the models fitted and scored on the measured
rows, their inputs' dynamics on every row; a dense target with one long gap is refused as before.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from sklearn.linear_model import LinearRegression

from conftest import FAST, UNTRACKED, thermocomp
from thermocomp.apps.sim.probe import probe_cycle_copy
from thermocomp.core.io.read import read_dataset
from thermocomp.shell.model_store import load_model

EVERY = 30          # a probe cycle every 30 min on a 1-min log


@pytest.fixture(scope="module")
def dense(tmp_path_factory):
    """A Swiss-type lathe's 80 h calibration and 24 h production run, the error measured at
    every 60 s sample."""
    path = tmp_path_factory.mktemp("sparse61") / "dense"
    thermocomp("simulate", "sim=swiss_lathe_door", "seed=61", f"data.path={path}", *UNTRACKED,
               "sim.generator.error_period_s=60.0")
    return path


@pytest.fixture(scope="module")
def sparse(dense, tmp_path_factory):
    return probe_cycle_copy(dense, tmp_path_factory.mktemp("sparse61") / "sparse",
                   lambda rows: rows % EVERY == 0)


@pytest.fixture(scope="module")
def sparse_run(sparse, tmp_path_factory):
    """``run`` of the sparse record with a family, FAST: ``(its folder, the finished process)``,
    each family's made once in the module (the lagbank's is read by two tests)."""
    made = {}

    def run(family: str):
        if family not in made:
            out = tmp_path_factory.mktemp(f"sparse-{family}")
            args = [f"model={family}", *FAST, *(["model.candidates=[mlr,arx,lagbank]"]
                                                if family == "auto" else [])]
            made[family] = out, thermocomp("run", f"data.path={sparse}", f"out={out}", *args)
        return made[family]
    return run


def test_read_as_a_probe_cycle_never_interpolated(sparse):
    """Even where data.max_gap_samples would bridge the gaps, the empty cells stay empty (an
    interpolated error is a line nobody measured), and the report counts the measured rows."""
    ds, report = read_dataset(sparse, {"max_gap_samples": EVERY})
    for cid, df in ds.campaigns.items():
        measured = np.isfinite(df["E_X"].to_numpy())
        assert np.array_equal(np.flatnonzero(measured), np.arange(0, len(df), EVERY))
        entry = report["campaigns"][cid]["sparse_targets"]["E_X"]
        assert entry == {"measured": int(measured.sum()), "every": EVERY}
    assert report["repairs"] == {}
    # data.sparse_targets=false: the gaps are gaps again (interpolated where allowed)
    ds, report = read_dataset(sparse, {"max_gap_samples": EVERY, "sparse_targets": False})
    assert np.isfinite(ds.campaigns["calibration"]["E_X"]).all() and "E_X" in report["repairs"]


def test_a_resampled_probe_cycle_keeps_its_measurements(sparse):
    """data.resample_s puts each measurement on its nearest grid point, as measured; it
    interpolates the temperatures only."""
    raw, _ = read_dataset(sparse)
    ds, report = read_dataset(sparse, {"resample_s": 120.0})
    before, after = raw.campaigns["production"], ds.campaigns["production"]
    measured = np.isfinite(after["E_X"].to_numpy())
    assert report["campaigns"]["production"]["sparse_targets"]["E_X"] == {
        "measured": int(measured.sum()), "every": EVERY // 2}
    np.testing.assert_array_equal(after["E_X"][measured], before["E_X"].dropna())
    np.testing.assert_array_equal(after["time"][measured], before["time"][before["E_X"].notna()])


def test_the_rows_before_the_first_measurement_are_kept(dense, tmp_path):
    """The first measurement 3 rows in: those rows are the campaign's own (frames62: the
    temperatures were measured there, a stream warms on them), read without
    data.max_edge_samples; in the first-sample frame the temperatures are referenced at the
    first row (the deployed stream's first sample), the error at its first measurement."""
    from thermocomp.core.frame import stack

    late = probe_cycle_copy(dense, tmp_path / "late", lambda rows: rows % EVERY == 3)
    thermocomp("run", f"data.path={late}", f"out={tmp_path / 'a'}", *FAST)
    ds, report = read_dataset(late)
    assert report["campaigns"]["production"]["trimmed"] == {"start": 0, "end": 0}
    m = stack({"production": ds.campaigns["production"]}, ["T_amb"], ["E_X"])
    assert m.X["T_amb"].iloc[0] == 0 and np.isnan(m.Y["E_X"].iloc[:3]).all() \
        and m.Y["E_X"].iloc[3] == 0


def test_the_fit_sees_the_measured_rows_only(sparse):
    """MLR's law is the least squares of the measured rows: no interpolated y entered it."""
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.frame import stack
    from thermocomp.core.models import MLR

    ds, _ = read_dataset(sparse)
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    comp = Compensator(MLR()).fit(train)
    m = stack(train, comp.inputs_, comp.targets_)
    rows = np.isfinite(m.Y["E_X"].to_numpy())
    assert rows.sum() == len(train["calibration"]) // EVERY + 1
    expected = LinearRegression().fit(m.X[rows], m.Y["E_X"][rows])
    np.testing.assert_allclose(comp.estimators_["E_X"].coef_, expected.coef_, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("family", ["mlr", "arx", "lagbank", "auto"])
def test_a_sparse_record_runs_and_scores_its_measured_rows(family, dense, sparse, sparse_run, tmp_path):
    """End to end; the test RMSE on the measured rows stays close to that of the same family
    fitted on the dense record, scored on the same rows (it fits on 1/30 of them).  Bound 1.5:
    benchmarks/bench_sparse61.py measured the ratio sparse / dense at 1 row in 30 on this
    record (seed 61) at 0.98-1.20 for mlr, arx, lagbank and auto (mlr, arx, lagbank), and at
    1.00-1.49 over six families on another seed (6121); the persistence baseline, a model
    that knows nothing of the temperatures, is 2.1-2.5x their sparse RMSE there."""
    args = [f"model={family}", *FAST, *(["model.candidates=[mlr,arx,lagbank]"]
                                        if family == "auto" else [])]
    thermocomp("run", f"data.path={dense}", f"out={tmp_path / 'dense'}", *args)
    out, run = sparse_run(family)
    assert "E_X measured on 1 row in 30" in run.stderr
    metrics = json.loads((out / "metrics.json").read_text())
    comp = load_model(tmp_path / "dense" / "model.pkl")
    ds, _ = read_dataset(sparse)
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    pred, meas = comp.predict(test), comp.measured(test)
    for target, figures in metrics["targets"].items():
        residual = (meas["production"][target] - pred["production"][target]).to_numpy()
        measured = np.isfinite(residual)
        assert figures["test"]["measured_rows"] == measured.sum() == len(residual) // EVERY + 1
        dense_rmse = float(np.sqrt(np.mean(residual[measured] ** 2)))
        assert figures["test"]["rmse"] < 1.5 * dense_rmse, (target, figures["test"]["rmse"], dense_rmse)
        assert figures["test_one_step"]["ahead_of_last_measured_rows"] == EVERY


def test_a_dense_target_with_one_long_gap_is_still_refused(dense, tmp_path, capsys):
    """A probe that died for two hours is a gap, not a probe cycle: refused as before.  (A
    guard of the old behaviour: it passes without the change too.)"""
    broken = probe_cycle_copy(dense, tmp_path / "broken", lambda rows: (rows < 300) | (rows >= 420))
    run = thermocomp("run", f"data.path={broken}", f"out={tmp_path / 'out'}", *FAST, check=False)
    assert run.returncode == 2
    assert "gap of 120 missing values (rows 301-420) is longer than data.max_gap_samples=0" \
        in run.stderr


def test_one_step_goes_from_the_last_probe_reading(sparse, tmp_path):
    """eval.mode=one_step (sparse62; refused before): each measured test row predicted from the
    previous probe reading by the one-step law, as the saved model recomputes it."""
    out = tmp_path / "a"
    thermocomp("run", f"data.path={sparse}", f"out={out}", "model=mlr", "eval.mode=one_step", *FAST)
    figures = json.loads((out / "metrics.json").read_text())["targets"]["E_X"]
    assert figures["test"]["ahead_of_last_measured_rows"] == EVERY
    comp = load_model(out / "model.pkl")
    ds, _ = read_dataset(sparse)
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    pred, meas = comp.predict(test, mode="one_step"), comp.measured(test)
    simulated = comp.predict(test)["production"]["E_X"].to_numpy()
    y, p = meas["production"]["E_X"].to_numpy(), pred["production"]["E_X"].to_numpy()
    rows = np.flatnonzero(np.isfinite(y))
    law = comp.one_step_["E_X"]
    # the law from the previous measurement (the first row: the model's own simulation)
    assert p[rows[0]] == simulated[rows[0]]
    prev = rows[:-1]
    expected = y[prev] + law.k_ * (simulated[rows[1:]] - simulated[prev]) \
        - law.g_ * (y[prev] - simulated[prev])
    assert np.allclose(p[rows[1:]], expected, rtol=0, atol=1e-9)
    assert np.isclose(figures["test"]["rmse"], np.sqrt(np.mean((y[rows] - p[rows]) ** 2)))


def test_an_ar_term_is_refused_in_one_line(sparse, tmp_path):
    """The previous error is not measured at most samples: ARX's forced AR term is refused
    (exit 2, one line), not a crash."""
    run = thermocomp("run", f"data.path={sparse}", f"out={tmp_path / 'b'}", "model=arx",
                     "model.estimator.ar=true", *FAST, check=False)
    assert run.returncode == 2 and "ARX.ar=true needs the error measured at every sample" in run.stderr


def test_replay_streams_the_dense_inputs_and_scores_the_measured_rows(sparse, sparse_run, tmp_path):
    """Replay streams every row and compares on the measured ones: as the batch scored it."""
    run, _ = sparse_run("lagbank")                   # run model=lagbank, FAST
    thermocomp("replay", f"replay.model={run / 'model.pkl'}", f"data.path={sparse}",
               f"out={tmp_path / 'replay'}", *UNTRACKED, "plots=none", "adapt.method=bias")
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())
    metrics = json.loads((run / "metrics.json").read_text())
    for target, r in replay["targets"].items():
        assert r["measured_rows"] == metrics["targets"][target]["test"]["measured_rows"]
        assert r["n_samples"] == metrics["targets"][target]["test"]["rows"]
        assert r["rmse_batch"] == pytest.approx(metrics["targets"][target]["test"]["rmse"])
        assert r["adapt"]["n_references"] > 0 and np.isfinite(r["rmse"])


def test_init_says_the_probe_cycle_once(sparse, tmp_path):
    """init's report and the read's own line had said it twice per target (stranger62)."""
    run = thermocomp("init", str(sparse), f"out={tmp_path / 'init'}")
    said = (run.stdout + run.stderr).splitlines()
    for target in ("E_X", "E_Y"):
        assert sum(f"{target} measured on 1 row in {EVERY}" in line for line in said) == 1, target
