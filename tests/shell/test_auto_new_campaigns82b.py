"""``model=auto`` on one train record tested on new campaigns keeps MLR (auto82b,
``benchmarks/bench_auto82b.py``): its folds are blocks of that one record, none holds out a new
campaign's conditions, so their evidence for another family is not evidence for the test.  Where
the test continues the train record the folds hold out what the test holds out: they choose.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from conftest import FAST
from test_model_auto import PAIR, lagged
from thermocomp.shell.cli import main


def _cycles(rng, k: int, n: int, cycle: int, dt: float) -> pd.DataFrame:
    """``n`` rows of heat / cool cycles at level ``k``: ``E_B`` a slow lag of ``T_0`` (the lag
    bank's), ``E_A`` static (MLR's)."""
    on = ((np.arange(n) % cycle) < 0.45 * cycle).astype(float) * (4 + k)
    heat = lagged(on, 600.0, dt)
    t0 = 20.0 + 0.4 * k + heat + rng.normal(0, 0.02, n)
    t1 = 20.0 + 0.4 * k + 0.3 * heat + rng.normal(0, 0.02, n)
    e_a = 3 * (t0 - t0[0]) - (t1 - t1[0]) + rng.normal(0, 0.3, n)
    e_b = 6 * lagged(t0 - t0[0], 2400.0, dt) + rng.normal(0, 0.05, n)
    return pd.DataFrame({"time": np.arange(n) * dt, "T_0": t0, "T_1": t1, "E_A": e_a, "E_B": e_b})


def one_record(root: Path, continues: bool) -> Path:
    """One long train campaign K01 (six heat / cool cycles), then two test campaigns.
    ``continues``: K02 is the record's seventh cycle (its clock goes on, the manifest says so),
    else a new campaign (its clock restarts, another level and start state); K03 is new."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(8301)
    dt, cycle = 60.0, 80
    record = _cycles(rng, 0, 7 * cycle, cycle, dt)
    frames = {"K01": record.iloc[:6 * cycle],
              "K02": record.iloc[6 * cycle:] if continues else _cycles(rng, 1, cycle, cycle, dt),
              "K03": _cycles(rng, 2, cycle, cycle, dt)}
    for name, frame in frames.items():
        frame.to_csv(root / f"{name}.csv", index=False)
    pd.DataFrame({"campaign": list(frames), "file": [f"{n}.csv" for n in frames],
                  "split": ["train", "test", "test"], "continues": ["", "K01" if continues else "", ""]}
                 ).to_csv(root / "campaigns.csv", index=False)
    return root


def _auto(data: Path, out: Path, *extra: str) -> dict:
    assert main(["run", f"data.path={data}", f"out={out}", *FAST, "model=auto", PAIR, *extra]) == 0
    targets = json.loads((out / "metrics.json").read_text())["targets"]
    return {t: {k: v for k, v in m["auto"].items() if k != "validation_s"} for t, m in targets.items()}


def test_one_train_record_tested_on_new_campaigns_keeps_mlr_and_says_why(tmp_path):
    data = one_record(tmp_path / "new", continues=False)
    kept = _auto(data, tmp_path / "rule")
    folds = _auto(data, tmp_path / "folds", "model.estimator.unseen_campaigns=folds")
    # the folds (blocks of the one record) are for the lag bank on E_B ...
    assert folds["E_B"]["weights"].get("lagbank", 0) > 0.5
    assert folds["E_B"]["candidates"]["lagbank"] < folds["E_B"]["candidates"]["mlr"]
    # ... and the rule keeps MLR, its validation reported as before, the reason saying why
    for t, a in kept.items():
        assert a["weights"] == {"mlr": 1.0} and a["chosen"] == "mlr"
        assert "test campaigns do not continue it" in a["reason"]
        assert "one record" in a["scheme"]
        assert a["candidates"] == folds[t]["candidates"]


def test_a_test_that_continues_the_train_record_leaves_the_choice_to_the_folds(tmp_path):
    data = one_record(tmp_path / "cont", continues=True)
    kept = _auto(data, tmp_path / "rule")
    folds = _auto(data, tmp_path / "folds", "model.estimator.unseen_campaigns=folds")
    assert kept == folds
    assert kept["E_B"]["weights"].get("lagbank", 0) > 0.5
    assert not any("do not continue" in a["reason"] for a in kept.values())


def test_another_value_of_the_key_is_refused_with_its_name(tmp_path, capsys):
    data = one_record(tmp_path / "new", continues=False)
    assert main(["run", f"data.path={data}", f"out={tmp_path / 'out'}", *FAST, "model=auto", PAIR,
                 "model.estimator.unseen_campaigns=maybe"]) == 2
    assert "unseen_campaigns" in capsys.readouterr().err
