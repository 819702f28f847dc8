"""Issue 34, item 4: the room's lean level law only where its wide law can never clear (diag107,
benchmarks/bench_diag107.py).

``ambient_linear`` (every input x (A0 - 20 °C)) saturates the train campaigns when its regressors
and the intercept can take one value per campaign a fold trains on (one test block per campaign):
never accepted, it buried real effects, and one regressor (``ambient_scaled``) reads the law there.
Where the wide law can be taken, it alone is offered: beside it the lean one won as the simpler
and read the law less well (bench_remeasure62's planted:4011 E_Y +4.0 %: diag106e).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.apps.diagnose.candidates import CandidateOptions
from thermocomp.core.compensator import Compensator
from thermocomp.core.io.contract import Dataset
from thermocomp.core.models import MLR

LEAN = ("least-squares fit x (ambient_c0", "mean x (ambient_c0")
WIDE = "model inputs x (ambient_c0 - 20°C)"


def _room(n_inputs: int, n_campaigns: int = 12, n: int = 120, seed: int = 3) -> Dataset:
    """Campaigns at room levels 14-34 °C (every third one a test), the error the inputs' rises
    scaled by the level (beta 0.02 /K): the climate room's law (docs/simulation.md)."""
    rng = np.random.default_rng(seed)
    b = rng.normal(0.0, 1.0, n_inputs)
    frames, rows = {}, []
    for k in range(n_campaigns):
        cid, a0 = f"C{k + 1:02d}", rng.uniform(14, 34)
        rise = np.cumsum(rng.normal(0.05, 0.2, (n, n_inputs)), axis=0)
        df = pd.DataFrame({"time": np.arange(n) * 300.0, "T_amb": a0 + 0.02 * rng.standard_normal(n)})
        for i in range(n_inputs):
            df[f"T_{i + 1}"] = a0 + rise[:, i] + 0.02 * rng.standard_normal(n)
        df["E_X"] = (1 - 0.02 * (a0 - 20)) * (rise @ b) + 0.05 * rng.standard_normal(n)
        frames[cid] = df
        rows.append({"campaign": cid, "file": f"{cid}.csv", "split": "test" if (k + 1) % 3 == 0 else "train"})
    return Dataset(pd.DataFrame(rows).set_index("campaign"), frames, name="room")


def _diagnosis(n_inputs: int) -> dict:
    options = SearchOptions(max_effects=1, candidates=CandidateOptions(families=("ambient_interval",)))
    return diagnose(_room(n_inputs), Compensator(MLR()), options=options).to_json("E_X")


def _offered(j: dict) -> list[str]:
    first = j["rounds"][0]
    return [e["transform"] for e in first["evaluated"]] + [s["transform"] for s in first["screened"]]


def test_where_the_wide_law_saturates_the_campaigns_the_lean_one_is_taken():
    j = _diagnosis(7)             # 8 inputs and the intercept on 7 campaigns a fold trains on
    assert j["cv"]["units"] == 8 and j["cv"]["test_blocks"] == 8
    wide = next(e for e in j["rounds"][0]["evaluated"] if e["transform"] == WIDE)
    assert wide["evidence"]["n_features"] == 8 and not wide["evidence"]["clears_bar"]
    (taken,) = [e for e in j["effects"] if e["accepted"]]
    assert LEAN[0] in taken["transform"] and taken["evidence"]["n_features"] == 1
    assert j["after"]["test_rmse"] < 0.2 * j["before"]["test_rmse"]


def test_where_the_wide_law_can_be_tested_the_lean_one_is_not_offered():
    j = _diagnosis(2)             # 3 inputs: the wide law can clear, and does
    assert j["cv"]["units"] == 8 and j["cv"]["test_blocks"] == 8
    (taken,) = [e for e in j["effects"] if e["accepted"]]
    assert taken["transform"] == WIDE and taken["evidence"]["n_features"] == 3
    assert not any(lean in t for t in _offered(j) for lean in LEAN)
    assert j["after"]["test_rmse"] < 0.5 * j["before"]["test_rmse"]
