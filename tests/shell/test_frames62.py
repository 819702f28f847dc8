"""One frame for a probe-cycle record, whatever command reads it (frames62).

The rows before an error's first measurement (and after its last) are the campaign's own rows,
kept by every read: the temperatures were measured there, so a stream warms on them, and the
error is scored on its measured rows only.  ``run`` trimmed them as incomplete edges
(``data.max_edge_samples``, else refused) while ``replay`` streamed them: a lag model's state then
started at other rows and the two parted.  A record without machine states runs
``model=hammerstein`` as the plain lag bank: said, and ``model=auto`` validates it once.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, UNTRACKED, thermocomp
from thermocomp.apps.sim.probe import probe_cycle_copy
from thermocomp.core.io.read import read_dataset

EVERY, FIRST = 20, 13       # a probe cycle every 20 samples, the first 13 samples in


def late_probe(rows):
    """The probe's rows: every EVERY-th from FIRST on."""
    return rows % EVERY == FIRST


# what the old rule needed to read the record at all (its rows before the first probe trimmed):
# given to both commands, so that the old code ran and parted, and harmless now
EDGE = "data.max_edge_samples=50"


@pytest.fixture(scope="module")
def dense(tmp_path_factory):
    """Three days of a machining centre at 1 min, one record cut in a train and a test file, the
    test file continuing the train one (``data.reference=none``: state carried over)."""
    path = tmp_path_factory.mktemp("frames62") / "dense"
    thermocomp("simulate", "sim=long_record", "seed=62", f"data.path={path}", *UNTRACKED,
               "sim.generator.duration_days=3")
    return path


@pytest.fixture(scope="module")
def late(dense, tmp_path_factory):
    return probe_cycle_copy(dense, tmp_path_factory.mktemp("frames62") / "late", late_probe)


@pytest.fixture(scope="module")
def lagbank_run(late, tmp_path_factory):
    """``run`` of the lag bank on ``late`` (the replay test's overrides), made once: the replay
    test and the export test read its model.pkl and metrics (neither edits them)."""
    out = tmp_path_factory.mktemp("frames62") / "run"
    thermocomp("run", f"data.path={late}", EDGE, "model=lagbank", f"out={out}", *UNTRACKED, "plots=none")
    return out


@pytest.fixture(scope="module")
def plain(late, tmp_path_factory):
    """``late`` without its ``S_`` columns, written once (read by two tests)."""
    return _without_states(late, tmp_path_factory.mktemp("frames62") / "plain")


def _without_states(source, dest):
    """``source``'s campaigns without their ``S_`` columns (a record of temperatures and errors
    only)."""
    dest.mkdir()
    for f in source.glob("*.csv"):
        df = pd.read_csv(f)
        df.drop(columns=[c for c in df.columns if c.startswith("S_")]).to_csv(dest / f.name,
                                                                              index=False)
    return dest


def test_rows_before_the_first_probe_are_read_not_trimmed(late, dense, tmp_path):
    """No data.max_edge_samples needed, no row dropped: the first measured row is where the
    probe measured, the temperatures before it are there.  (Refused before: '13 incomplete rows
    at the campaign start'.)"""
    ds, report = read_dataset(late)
    raw = pd.read_csv(late / "R1b.csv")
    test = ds.campaigns["R1b"]
    assert len(test) == len(raw) and report["campaigns"]["R1b"]["trimmed"] == {"start": 0, "end": 0}
    assert np.flatnonzero(np.isfinite(test["E_Z"].to_numpy()))[0] == FIRST
    np.testing.assert_allclose(test["time"].to_numpy(), raw["time"].to_numpy())


def test_a_dense_records_missing_edge_is_still_refused(dense, tmp_path):
    """A dense column's empty first cells are incomplete edge rows as before: refused without
    data.max_edge_samples, never back-filled.  (A guard: it passes on the old code too.)"""
    broken = tmp_path / "broken"
    broken.mkdir()
    for f in dense.glob("*.csv"):
        df = pd.read_csv(f)
        if f.name == "R1b.csv":
            df.loc[:2, "T_motor"] = np.nan
        df.to_csv(broken / f.name, index=False)
    run = thermocomp("run", f"data.path={broken}", f"out={tmp_path / 'out'}", *FAST, check=False)
    assert run.returncode == 2 and "3 incomplete rows at the campaign start" in run.stderr


def _run_and_replay(data: list[str], family: str, tmp_path, run=None) -> tuple[dict, dict]:
    """``run`` then ``replay`` of its model.pkl; ``run``: a folder where that run was made."""
    if run is None:
        run = tmp_path / "run"
        thermocomp("run", *data, f"model={family}", f"out={run}", *UNTRACKED, "plots=none")
    thermocomp("replay", *data, f"replay.model={run / 'model.pkl'}",
               f"out={tmp_path / 'replay'}", *UNTRACKED, "plots=none")
    return (json.loads((run / "metrics.json").read_text())["targets"],
            json.loads((tmp_path / "replay" / "replay.json").read_text())["targets"])


@pytest.mark.parametrize("family", ["lagbank", "arx"])
def test_run_scores_what_replay_streams(family, late, tmp_path, request):
    """The test file continues the train one: run predicts it joined to its predecessor, replay
    warms the stream on it; both from the same rows now, so run's test RMSE is replay's batch
    RMSE and its stream's.  (Before: run trimmed the 13 rows before each file's first probe,
    replay streamed the test file's; lagbank E_Z 1.79 against 1.77 um on seed 62.)"""
    made = request.getfixturevalue("lagbank_run") if family == "lagbank" else None
    metrics, replay = _run_and_replay([f"data.path={late}", EDGE], family, tmp_path, made)
    for target, r in replay.items():
        test = metrics[target]["test"]
        assert r["n_samples"] == test["rows"] and r["measured_rows"] == test["measured_rows"]
        assert abs(r["rmse_batch"] - test["rmse"]) < 1e-9, (target, r["rmse_batch"], test["rmse"])
        assert r["max_abs_stream_minus_batch"] < 1e-9


def test_a_one_file_records_cut_is_the_batchs(late, tmp_path):
    """One file, cut by data.test_fraction: replay cuts it where run does.  The probe's last
    measurement 7 rows before the end: the stream's cut had taken those rows for an incomplete
    edge the batch trims (the batch keeps them), and its test part started 7 rows early."""
    df = pd.read_csv(late / "R1a.csv")
    measured = df["E_Z"].notna().to_numpy().copy()
    measured[len(df) - 7:] = False
    df.loc[~measured, "E_Z"] = np.nan
    df.to_csv(tmp_path / "record.csv", index=False)
    data = [f"data.path={tmp_path / 'record.csv'}", "data.test_fraction=0.2", "data.reference=none",
            EDGE]
    metrics, replay = _run_and_replay(data, "lagbank", tmp_path)
    test = metrics["E_Z"]["test"]
    assert replay["E_Z"]["n_samples"] == test["rows"]
    assert abs(replay["E_Z"]["rmse_batch"] - test["rmse"]) < 1e-9


def test_hammerstein_without_states_says_it_is_the_lag_bank(plain, tmp_path):
    """No S_ column: one warning line, in run's output and metrics.json; the figures are the lag
    bank's."""
    runs = {}
    for family in ("hammerstein", "lagbank"):
        run = thermocomp("run", f"data.path={plain}", EDGE, f"model={family}",
                         f"out={tmp_path / family}", *FAST)
        runs[family] = (run, json.loads((tmp_path / family / "metrics.json").read_text()))
    run, metrics = runs["hammerstein"]
    said = [line for line in run.stderr.splitlines() if "model=hammerstein" in line]
    assert len(said) == 1 and "no machine-state column" in said[0] and "model=lagbank" in said[0]
    assert len(metrics["warnings"]) == 1 and said[0].endswith(metrics["warnings"][0])
    assert "warnings" not in runs["lagbank"][1]
    assert metrics["targets"]["E_Z"]["test"]["rmse"] == runs["lagbank"][1]["targets"]["E_Z"]["test"]["rmse"]


def test_auto_validates_the_lag_bank_once(plain, tmp_path):
    """model=auto among mlr, lagbank and hammerstein on a record without S_ columns: hammerstein
    is skipped as lagbank's very model, not validated a second time; the blend is of the
    validated candidates, its weights summing to 1."""
    thermocomp("run", f"data.path={plain}", EDGE, "model=auto",
               "model.candidates=[mlr,lagbank,hammerstein]", f"out={tmp_path / 'auto'}", *FAST)
    auto = json.loads((tmp_path / "auto" / "metrics.json").read_text())["targets"]["E_Z"]["auto"]
    assert "hammerstein" not in auto["candidates"] and "hammerstein" not in auto["validation_s"]
    assert auto["skipped"]["hammerstein"].startswith("the same model as lagbank")
    assert set(auto["weights"]) <= {"mlr", "lagbank"}
    assert sum(auto["weights"].values()) == pytest.approx(1.0, abs=1e-3)


def test_the_export_packs_corrections_are_what_run_scored(late, lagbank_run, tmp_path):
    """export's check pack feeds the code the test file after its lead-in (the train file it
    continues): its expected corrections on the test file's rows are minus run's predictions
    there, row for row, from the first row (before: run's test file started 13 rows later)."""
    from thermocomp.core import continuation
    from thermocomp.shell.model_store import load_model

    thermocomp("export", f"data.path={late}", EDGE, *UNTRACKED, "monitor.adaptive=false",
               f"export.model={lagbank_run / 'model.pkl'}", "export.format=c",
               f"out={tmp_path / 'code'}")
    pack = json.loads((tmp_path / "code" / "check" / "check.json").read_text())
    entry = next(e for e in pack["campaigns"] if e["campaign"] == "R1b")
    expected = pd.read_csv(tmp_path / "code" / entry["folder"] / "expected.csv")
    own = expected.iloc[entry["lead_in_rows"]:].to_numpy(float)
    ds, _ = read_dataset(late, {"max_edge_samples": 50})
    predicted, _ = continuation.predict(load_model(lagbank_run / "model.pkl"), ds, ["R1b"])
    assert entry["cut"] is None and own.shape == (len(predicted["R1b"]), 1)
    assert np.abs(own[:, 0] + predicted["R1b"]["E_Z"].to_numpy()).max() < 1e-9
