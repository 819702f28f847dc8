"""Issue 34: the room's level law and an effect that hide each other are taken together (diag107d,
benchmarks/bench_diag107d.py); the pair's family-wise p counts the choice of lean law (diag108,
benchmarks/bench_diag108.py).

With 8 train campaigns neither the lean level law nor a hidden source clears
alone: the law loses in a held-out campaign the source still fills, and the source's gain is buried
under the campaigns' levels.  Taken the law, the source clears the next round, and the pair clears
against the model before it (every held-out campaign gains): both are taken.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.apps.diagnose import search as search_module
from thermocomp.apps.diagnose.candidates import CandidateOptions
from thermocomp.core.compensator import Compensator
from thermocomp.core.io.contract import Dataset
from thermocomp.core.models import MLR


def _room_with_source(n_inputs: int = 7, n_campaigns: int = 12, n: int = 120, seed: int = 3) -> Dataset:
    """test_diagnose_level107's room (the inputs' rises scaled by the level, beta 0.02 /K) plus a
    hydraulic unit switched on and off, read only by ``S_hyd``, starting at its own level above the
    air in each campaign, moving E_X 1 µm/K."""
    rng = np.random.default_rng(seed)
    b = rng.normal(0.0, 1.0, n_inputs)
    frames, rows = {}, []
    for k in range(n_campaigns):
        cid, a0 = f"C{k + 1:02d}", rng.uniform(14, 34)
        rise = np.cumsum(rng.normal(0.05, 0.2, (n, n_inputs)), axis=0)
        df = pd.DataFrame({"time": np.arange(n) * 300.0, "T_amb": a0 + 0.02 * rng.standard_normal(n)})
        for i in range(n_inputs):
            df[f"T_{i + 1}"] = a0 + rise[:, i] + 0.02 * rng.standard_normal(n)
        on = np.repeat(rng.integers(0, 2, n // 12), 12).astype(float)
        hyd = np.full(n, rng.uniform(0, 3))
        for t in range(1, n):
            hyd[t] = hyd[t - 1] + (3.0 * on[t] - hyd[t - 1]) * 0.15
        df["S_hyd"] = a0 + hyd + 0.05 * rng.standard_normal(n)
        df["E_X"] = (1 - 0.02 * (a0 - 20)) * (rise @ b) + hyd + 0.05 * rng.standard_normal(n)
        frames[cid] = df
        rows.append({"campaign": cid, "file": f"{cid}.csv", "split": "test" if (k + 1) % 3 == 0 else "train"})
    return Dataset(pd.DataFrame(rows).set_index("campaign"), frames, name="room")


@pytest.fixture(scope="module")
def diagnosed_room():
    """The room diagnosed once, with every round and family-wise test that the pair step ran."""
    families = ("ambient_interval", "signal")
    options = SearchOptions(max_effects=2, candidates=CandidateOptions(families=families))
    Search, maxt = search_module.Search, search_module.sign_flip_maxt
    shipped_round, shipped_pair = Search._round, Search._level_pair
    pair_step = {"rounds": [], "tests": [], "inside": False}

    def spied_round(self, current, used, step):
        out = shipped_round(self, current, used, step)
        if pair_step["inside"]:
            family = [ev for ev in out[0] if not ev.control and ev.effect.transform != "remove"]
            pair_step["rounds"].append((self.effects[-1].transform, len(family)))
        return out

    def spied_pair(self, *args):
        pair_step["inside"] = True
        try:
            return shipped_pair(self, *args)
        finally:
            pair_step["inside"] = False

    def spied_maxt(D, *args, **kwargs):
        if pair_step["inside"]:
            pair_step["tests"].append(np.atleast_2d(D).shape[0])
        return maxt(D, *args, **kwargs)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(Search, "_round", spied_round)
        mp.setattr(Search, "_level_pair", spied_pair)
        mp.setattr(search_module, "sign_flip_maxt", spied_maxt)
        j = diagnose(_room_with_source(), Compensator(MLR()), options=options).to_json("E_X")
    return j, pair_step


def test_the_level_law_and_a_source_masking_each_other_are_taken_together(diagnosed_room):
    j, _ = diagnosed_room
    first = j["rounds"][0]
    assert not any(e["evidence"]["clears_bar"] for e in first["evaluated"])
    law, source = [e for e in j["effects"] if e["accepted"]]
    assert law["kind"] == "ambient_interval" and law["evidence"]["n_features"] == 1
    assert source["column"] == "S_hyd" and source["evidence"]["clears_bar"]
    assert j["after"]["test_rmse"] < 0.2 * j["before"]["test_rmse"]


def test_the_pairs_family_is_every_lean_laws_next_round(diagnosed_room):
    """The law of most gain was picked on the same campaigns: the pair is tested family-wise over
    the pairs of every lean law round 1 refitted, not of the picked law's round only (diag108)."""
    j, pair_step = diagnosed_room
    labels = {search_module.Effect("ambient_interval", t).label: t for t in search_module.LEAN_LEVEL}
    refitted = {labels[e["transform"]] for e in j["rounds"][0]["evaluated"] if e["transform"] in labels}
    assert refitted == set(search_module.LEAN_LEVEL)
    assert sorted(law for law, _ in pair_step["rounds"]) == sorted(refitted)
    # the pair's test (the last one of the step; each round's own bar runs before it) holds every pair
    assert pair_step["tests"][-1] == sum(n for _, n in pair_step["rounds"])
