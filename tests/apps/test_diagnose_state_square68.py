"""speedsq68: a state's own instant law that is not linear in it (a spindle's centrifugal
shrink, ``E_Z ~ -n^2``) is a candidate of ``diagnose``: the square of a state signal
(``benchmarks/bench_speedsq68.py``).  Before, a state was tried raw, lagged and times the
temperatures' rises only: the raw speed is the law's chord, no candidate the law itself.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pandas as pd

from thermocomp.apps.diagnose import CONTROL, SearchOptions, diagnose
from thermocomp.apps.diagnose.candidates import CandidateOptions, candidates
from thermocomp.apps.diagnose.cv import Problem
from thermocomp.apps.diagnose.features import Effect
from thermocomp.core.compensator import Compensator
from thermocomp.core.io.contract import Dataset
from thermocomp.core.models import MLR

STEP_S = 60.0
SHRINK_UM_PER_KRPM2 = -0.04


def _campaign(rng, start_krpm: float = 0.0) -> pd.DataFrame:
    """A spindle speed spectrum (5 steps of 40-70 min from 2-12 krpm, then 2 h at rest); the
    bearings and the head heated by ``10 + 12 n + 1.2 n^2`` W; E_Z their growth plus the
    centrifugal shrink ``-0.04 n^2`` µm, instant with the speed."""
    speeds = [start_krpm * 1000.0] * 10
    for n in rng.choice(np.arange(2, 13), size=5, replace=False):
        speeds += [1000.0 * n] * int(rng.uniform(40, 70))
    speeds += [0.0] * 120
    rpm = np.array(speeds)
    k = rpm / 1000.0
    heat = np.where(rpm > 0, 10 + 12 * k + 1.2 * k**2, 0.0)
    air = 20.0 + 0.5 * np.sin(np.arange(len(k)) * STEP_S / 3600 / 24 * 2 * np.pi + rng.uniform(0, 6))
    bearing, head = np.empty(len(k)), np.empty(len(k))
    bearing[0], head[0] = air[0], air[0]
    for i in range(1, len(k)):
        bearing[i] = bearing[i - 1] + STEP_S * (heat[i] - 2 * (bearing[i - 1] - air[i])
                                                - 6 * (bearing[i - 1] - head[i - 1])) / 3e4
        head[i] = head[i - 1] + STEP_S * (6 * (bearing[i - 1] - head[i - 1])
                                          - 10 * (head[i - 1] - air[i])) / 1.2e5
    e_z = -3.5 * (bearing - 20) - 5.5 * (head - 20) + SHRINK_UM_PER_KRPM2 * k**2
    e_z = e_z - e_z[0] + rng.normal(0, 0.1, len(k))
    noisy = lambda v: v + rng.normal(0, 0.02, len(k))                    # noqa: E731
    return pd.DataFrame({"time": np.arange(len(k)) * STEP_S, "T_amb": noisy(air),
                         "T_front": noisy(bearing), "T_head": noisy(head),
                         "S_speed": rpm, "E_Z": e_z})


@lru_cache(maxsize=None)
def spindle(seed: int = 6805, shrink: bool = True) -> Dataset:
    rng = np.random.default_rng(seed)
    ids = [f"R{k}" for k in range(8)]
    frames = {c: _campaign(rng) for c in ids}
    if not shrink:      # the same runs without the law (the speed's heat alone)
        for f in frames.values():
            f["E_Z"] -= SHRINK_UM_PER_KRPM2 * (f["S_speed"] / 1000.0) ** 2
    manifest = pd.DataFrame({"campaign": ids, "split": ["train"] * 6 + ["test"] * 2})
    return Dataset(manifest.set_index("campaign"), frames, name="spindle68")


def _problem(frames: dict) -> tuple[Problem, list]:
    inputs = ["T_amb", "T_front", "T_head"]
    stacked = pd.concat(frames.values(), ignore_index=True)
    groups = np.repeat(list(frames), [len(f) for f in frames.values()])
    X = stacked[inputs] - stacked.groupby(groups)[inputs].transform("first")
    return Problem(X, stacked["E_Z"].to_numpy(), stacked.assign(campaign=groups), groups, groups,
                   "E_Z"), inputs


def test_a_states_square_is_a_candidate_in_the_frames_a_state_is_tried():
    ds = spindle()
    problem, inputs = _problem({c: ds.campaigns[c] for c in ds.ids("train")})
    got = candidates(problem, inputs, set(), [], CandidateOptions())
    squares = {e for e in got if e.transform == "square" and e.column in ("S_speed", CONTROL)}
    # every run starts at rest: one frame (absolute and referenced differ by nothing)
    assert squares == {Effect("nonlinear", "square", "S_speed"),
                       Effect("nonlinear", "square", CONTROL)}
    # runs that start at different speeds: the absolute square too
    rng = np.random.default_rng(1)
    problem, _ = _problem({f"R{k}": _campaign(rng, start_krpm=2.0 * k) for k in range(4)})
    got = candidates(problem, inputs, set(), [], CandidateOptions())
    assert {e for e in got if e.transform == "square" and e.column == "S_speed"} == {
        Effect("nonlinear", "square", "S_speed"),
        Effect("nonlinear", "square", "S_speed", frame="absolute")}
    # no family "nonlinear": no square at all
    options = CandidateOptions(families=("signal", "interaction"))
    assert not [e for e in candidates(problem, inputs, set(), [], options)
                if e.transform == "square"]


def test_diagnose_accepts_a_speeds_instant_square_law_and_its_test_improves():
    d = diagnose(spindle(), Compensator(MLR()), targets=["E_Z"],
                 options=SearchOptions(max_effects=1))
    j = d.to_json("E_Z")
    accepted = [e for e in j["effects"] if e["accepted"]]
    assert [a["effect"] for a in accepted] == [
        {"kind": "nonlinear", "transform": "square", "column": "S_speed"}]
    assert j["after"]["test_rmse"] < 0.6 * j["before"]["test_rmse"]
    assert not j["control_ever_clears_bar"]


def test_without_the_law_no_square_of_the_speed_is_accepted():
    d = diagnose(spindle(shrink=False), Compensator(MLR()), targets=["E_Z"],
                 options=SearchOptions(max_effects=1))
    j = d.to_json("E_Z")
    assert not [e for e in j["effects"] if e["accepted"] and e["effect"]["transform"] == "square"]
