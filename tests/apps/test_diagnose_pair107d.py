"""Issue 34: the room's level law and an effect that hide each other are taken together (diag107d,
benchmarks/bench_diag107d.py).

With 8 train campaigns neither the lean level law nor a hidden source clears
alone: the law loses in a held-out campaign the source still fills, and the source's gain is buried
under the campaigns' levels.  Taken the law, the source clears the next round, and the pair clears
against the model before it (every held-out campaign gains): both are taken.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.apps.diagnose import search as search_module
from thermocomp.apps.diagnose.candidates import CandidateOptions
from thermocomp.apps.diagnose.refit_null import MovedDrivers, Mover, _orders, drivers, refit_pvalue
from thermocomp.core.compensator import Compensator
from thermocomp.core.io.contract import Dataset
from thermocomp.core.models import MLR

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from bench_diag108 import null_room  # noqa: E402 (the clean room of the benches diag108-111 count)

FAMILIES = ("ambient_interval", "signal")


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


def test_the_level_law_and_a_source_masking_each_other_are_taken_together():
    options = SearchOptions(max_effects=2, candidates=CandidateOptions(families=FAMILIES))
    j = diagnose(_room_with_source(), Compensator(MLR()), options=options).to_json("E_X")
    first = j["rounds"][0]
    assert not any(e["evidence"]["clears_bar"] for e in first["evaluated"])
    law, source = [e for e in j["effects"] if e["accepted"]]
    assert law["kind"] == "ambient_interval" and law["evidence"]["n_features"] == 1
    assert source["column"] == "S_hyd" and source["evidence"]["clears_bar"]
    assert source["evidence"]["p_value_refit"] <= 0.01        # the pair beat its moved drivers (diag111)
    assert j["after"]["test_rmse"] < 0.2 * j["before"]["test_rmse"]


def test_a_level_law_clearing_the_flips_in_a_clean_room_does_not_beat_its_moved_ambients(monkeypatch):
    """diag111: in bench_diag108's clean room 16 (campaign offsets independent of the air) the lean
    level law gains 22 % in CV at a family-wise flip p <= 0.01; refitted with the campaigns'
    starting ambients moved among them it does as well within the first permutations (refit p > 0.01),
    while the planted pair above beats all 99."""
    store = {}
    run = search_module.Search.run

    def kept(self, *args, **kwargs):
        store[self.problem.target] = self
        return run(self, *args, **kwargs)

    monkeypatch.setattr(search_module.Search, "run", kept)
    options = SearchOptions(max_effects=2, candidates=CandidateOptions(families=FAMILIES))
    diagnose(null_room(16), Compensator(MLR()), options=options, targets=["E_X"])
    s = store["E_X"]
    s.effects = []
    evals, _, _, _ = s._round(s.cv.run(s.inputs(), []), s._read_columns(), 1)
    law = max((ev for ev in evals if ev.effect.transform in search_module.LEAN_LEVEL), key=lambda ev: ev.gain)
    assert law.p_family <= 0.01 and law.gain_pct >= 5.0
    assert refit_pvalue(s.cv, s.inputs(), [], [law.effect], law.result.rmse, alpha=0.01) > 0.01
    # diag111c: the permutations' refits share each fold's inputs factor and level weights; the
    # same CV RMSE as refits that factor every fold anew, and the identity refits the observed
    fits, orders = {}, _orders(len(set(s.cv.problem.campaigns.tolist())), 4, seed=0)
    for order in orders:
        shared, anew = _refit_rmse(s, [law.effect], order, fits), _refit_rmse(s, [law.effect], order, None)
        assert shared == pytest.approx(anew, rel=1e-10, abs=0)
    (head,) = fits.values()               # the lean law does not learn: the pieces' path, one head
    assert len(head.factors) == len(set(s.cv.problem.campaigns.tolist()))   # a factor per campaign
    identity = np.arange(len(orders[0]))
    assert _refit_rmse(s, [law.effect], identity, {}) == pytest.approx(law.result.rmse, rel=1e-10, abs=0)


def _refit_rmse(s, tested, order, fits):
    """One permutation's refit of ``tested`` on ``s``'s CV: the folds' inputs factored once and
    shared (``fits`` a dict), or lstsq in every fit (``fits`` None, diag111's refits)."""
    p = s.cv.problem
    names = list(dict.fromkeys(p.campaigns.tolist()))
    columns = [c for e in tested for c in drivers(e, p.context.columns)]
    cv = MovedDrivers(s.cv, Mover(p.context, p.campaigns, columns, names)(order), [], fits)
    cv._fixed = fits
    return cv.run(s.inputs(), tested).rmse
