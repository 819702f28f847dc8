"""autodiag99b (issue 34): ``model.diagnosed=true`` gives ``model=auto`` one more candidate per
target, ``diagnosed``: MLR with the effects ``diagnose``'s own search accepts on the train split
(:func:`thermocomp.apps.diagnose.search_train`, no test split), voted like any candidate
(benchmarks/bench_autodiag99b.py: mt9888 E_X 10.28 -> 3.22 um, autodiag99's trace to 1e-9).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from hydra import compose, initialize_config_dir

import thermocomp.shell.cli  # noqa: F401  (registers the config's resolvers)
from test_diagnose_few import few
from thermocomp.apps.diagnose import AugmentedRegressor
from thermocomp.base.paths import conf_dir
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR
from thermocomp.core.models.auto import AutoRegressor
from thermocomp.core.models.base import ForTargets
from thermocomp.shell.builders import build_compensator


def _campaigns(n: int = 4, rows: int = 120) -> dict:
    rng = np.random.default_rng(3)
    out = {}
    for k in range(n):
        t = np.arange(rows) * 60.0
        a, b = np.cumsum(rng.normal(0, 0.1, rows)), np.cumsum(rng.normal(0, 0.1, rows))
        out[f"C{k}"] = pd.DataFrame({"time": t, "T_a": a, "T_b": b, "E_A": 2 * a + b * a,
                                     "E_B": a - b + rng.normal(0, 0.01, rows)})
    return out


def test_a_candidate_for_some_targets_is_validated_on_those_only():
    only = ForTargets({"E_A": AugmentedRegressor(MLR(), [{"kind": "interaction", "transform": "product",
                                                           "column": "T_a", "other": "T_b"}])})
    auto = AutoRegressor(candidates={"mlr": MLR(), "diagnosed": only}, n_folds=3)
    comp = Compensator(auto, inputs=["T_a", "T_b"], reference="none").fit(_campaigns())
    assert "diagnosed" in comp.estimators_["E_A"].validation_
    assert "diagnosed" not in comp.estimators_["E_B"].validation_      # nothing for E_B: left out
    assert comp.estimators_["E_B"].validation_.keys() >= {"mlr", "persistence", "none"}


def _cfg(*overrides: str):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=["model=auto", "model.candidates=[mlr]",
                                                        "data.targets=[E_Y]", *overrides])


def test_the_key_adds_what_diagnose_accepts_on_the_train_split_and_nothing_when_off():
    ds, truth = few("axis_position", 0)          # test_diagnose_few: diagnose accepts S_pos_Y
    off = build_compensator(_cfg(), ds=ds)
    assert set(off.estimator.candidates) == {"mlr"}
    on = build_compensator(_cfg("model.diagnosed=true", "diagnose.max_effects=2"), ds=ds)
    given = on.estimator.candidates["diagnosed"].for_target("E_Y")
    # the planted effect accepted first, as diagnose accepts it (test_diagnose_few)
    assert (given.effects[0]["kind"], given.effects[0]["column"]) == (
        "interaction", truth["undeclared_effects"][0]["column"])
    assert on.estimator.candidates["diagnosed"].for_target("E_X") is None
