"""The ATI report's coldest- and warmest-campaign baselines are fitted on one campaign each by
design (paper 003, Sect. 4.3), as mutual prediction fits one campaign per model: a model whose
fit falls back on one campaign (``model=auto`` blending an ATI member) said "ATI: 1 training
campaign(s) with 1 distinct ambient(s) ..." after "fitting auto on 9 train campaigns" (the
5-axis centre of benchmarks/bench_new_machines58.py), as if the run had one."""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd

from thermocomp.base.errors import FallbackWarning
from thermocomp.core.compensator import Compensator
from thermocomp.core.io.contract import Dataset
from thermocomp.core.models import MLR
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.core.scoring.evaluation import ati_report


def campaign(ambient, seed, n=30):
    rng = np.random.default_rng(seed)
    t1 = ambient + np.cumsum(rng.uniform(0.05, 0.3, n))
    return pd.DataFrame({"time": np.arange(n) * 300.0, "T_1": t1,
                         "T_amb": ambient + rng.normal(0, 0.01, n),
                         "E_Z": 2.0 * (t1 - t1[0]) + rng.normal(0, 0.05, n)})


def test_the_one_campaign_baselines_say_no_fallback():
    ambients = {"A": 8.0, "B": 14.0, "C": 21.0, "D": 27.0, "E": 18.0}
    frames = {c: campaign(a, i) for i, (c, a) in enumerate(ambients.items())}
    manifest = pd.DataFrame({"file": [f"{c}.csv" for c in frames],
                             "split": ["train"] * 4 + ["test"]},
                            index=pd.Index(list(frames), name="campaign"))
    ds = Dataset(manifest, frames, "five", {})
    comp = Compensator(ATIRegressor(MLR())).fit({c: frames[c] for c in "ABCD"})
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        report = ati_report(comp, ds, lambda: Compensator(ATIRegressor(MLR())), name="cmeans")
    assert report["baseline_campaigns"]["coldest"]["campaign"] == "A"
    assert not [w for w in said if issubclass(w.category, FallbackWarning)], [str(w.message) for w in said]
