"""Issue 34: the forward scheme's refit null, the candidate's drivers shifted in time (diag112b,
benchmarks/bench_diag112b.py).

On clean records the forward scheme's flips over validation blocks took lags that explain nothing
(bench_diag111d ``forward``: 4 of 200).  The one a round would take is now refitted with its drivers
shifted circularly in time (:mod:`thermocomp.apps.diagnose.shift_null`) and must beat the shifts.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.apps.diagnose.candidates import CandidateOptions
from thermocomp.apps.diagnose.shift_null import offsets
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from bench_diag111d import null_record  # noqa: E402 (the clean one-record room bench_diag111d counts)

FAMILIES = ("signal", "dynamics")


def _diagnosed(dataset) -> dict:
    options = SearchOptions(max_effects=1, candidates=CandidateOptions(families=FAMILIES))
    return diagnose(dataset, Compensator(MLR()), options=options, targets=["E_X"]).to_json("E_X")


def _round1_best(j: dict) -> dict:
    tested = [e for e in j["rounds"][0]["evaluated"] if e["evidence"]["p_value_family"] is not None]
    return min(tested, key=lambda e: e["evidence"]["p_value_family"])


def test_a_clean_records_lag_clearing_the_flips_does_not_beat_its_shifted_input():
    """Record 31: a lag of T_6 (the base reads T_6 itself) gains at a family p <= .01 on the forward
    flips and was taken; shifted in time, its input does as well within 99 shifts."""
    j = _diagnosed(null_record(31))
    best = _round1_best(j)
    assert best["kind"] == "dynamics" and best["column"] == "T_6"
    assert best["evidence"]["p_value_family"] <= 0.01
    assert not [e for e in j["effects"] if e["accepted"]]
    assert best["evidence"]["p_value_refit"] > 0.01


def test_a_planted_signal_beats_every_shift():
    """The same record with E_X moved by the hydraulic unit S_hyd reads (1 µm/K): taken, p 0.01."""
    ds = null_record(31)
    for df in ds.campaigns.values():
        df["E_X"] += df["S_hyd"] - df["S_hyd"].iloc[0]
    j = _diagnosed(ds)
    (taken,) = [e for e in j["effects"] if e["accepted"]]
    assert taken["column"] == "S_hyd" and taken["evidence"]["p_value_refit"] == pytest.approx(0.01)


def test_shifts_stay_a_block_from_the_identity_and_are_all_taken_where_few():
    few = offsets(100, 30, 99, seed=0)
    assert few.tolist() == list(range(30, 71))          # 41 < 99: every one, floor 1/42 > .01
    drawn = offsets(960, 36, 99, seed=0)
    assert len(np.unique(drawn)) == 99 and drawn.min() >= 36 and drawn.max() <= 960 - 36
