"""ATI's ambient interaction needs distinct ambient LEVELS, not runs whose start differs by noise.

rig40 (benchmarks/bench_other_machine.py): three train runs of a room held at (or ramped from)
20 °C started at 19.97 / 19.98 / 19.99 °C; ATI's 20 °C interval counted three "distinct" ambients,
fitted a slope in the ambient on their 0.02 K spread, and the test run that started at 20.08 °C
extrapolated it (E_X test 0.91 µm against MLR's 0.37; benchmarks/bench_ati_ramp.py).
"""

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.compensator import Compensator
from thermocomp.core.metrics import rmse
from thermocomp.core.models import MLR
from thermocomp.core.models.ati import ATIRegressor

NOISE = 0.05   # µm, the probe's noise on the synthetic error


def room_run(start, seed, ramp=0.0, n=120):
    """A run whose room starts at ``start`` °C (ramped by ``ramp`` K over the run): a heated
    sensor T_1, the room sensor T_amb, and an error whose sensitivity grows 2 %/K of the start."""
    rng = np.random.default_rng(seed)
    T1 = start + np.cumsum(rng.uniform(0.0, 0.2, n)) + np.linspace(0.0, ramp, n)
    df = pd.DataFrame({"time": np.arange(n) * 120.0, "T_1": T1,
                       "T_amb": start + np.linspace(0.0, ramp, n) + rng.normal(0, 0.01, n)})
    df["E_X"] = (1 + 0.02 * (start - 20)) * 2.0 * (T1 - T1[0]) + rng.normal(0, NOISE, n)
    return df


def test_runs_started_within_a_rooms_swing_are_one_level_and_a_spread_is_several():
    from thermocomp.core.models.ati import AMBIENT_RESOLUTION_C, ambient_levels

    assert ambient_levels([19.97, 19.98, 19.99]) == 1
    assert ambient_levels([15.0, 20.0, 25.0, 19.99]) == 3
    # a continuous spread counts about one level per resolution: no chain merges it into one
    spread = np.arange(28.0, 31.0, 0.3)
    assert ambient_levels(spread) == pytest.approx(3.0 / AMBIENT_RESOLUTION_C, abs=1)
    assert ambient_levels([np.nan, 20.0]) == 1
    # three real levels in one interval still take the interaction
    train = {f"a{a}": room_run(a, i) for i, a in enumerate((15.0, 20.0, 25.0, 30.0))}
    est = Compensator(ATIRegressor(MLR(), n_intervals=1, ambient_interaction=True),
                      inputs=["T_1"]).fit(train).estimators_["E_X"]
    assert est.interactions_ == [True]


def test_no_slope_in_ambient_from_three_runs_at_one_set_point():
    # two ramped runs and one held, all from ~20 °C, as rig40's 20 °C interval
    train = {"r1": room_run(19.97, 1, ramp=10.0), "r2": room_run(19.99, 2),
             "r5": room_run(19.98, 3, ramp=10.0)}
    test = {"r7": room_run(20.08, 7)}
    comp = Compensator(ATIRegressor(MLR(), n_intervals=1, ambient_interaction=True),
                       inputs=["T_1"]).fit(train)
    est = comp.estimators_["E_X"]
    assert est.interactions_ == [False]      # 0.02 K of spread identifies no slope
    residual = comp.measured(test)["r7"]["E_X"] - comp.predict(test)["r7"]["E_X"]
    plain = Compensator(MLR(), inputs=["T_1"]).fit(train)
    residual_plain = comp.measured(test)["r7"]["E_X"] - plain.predict(test)["r7"]["E_X"]
    # the held-level run 0.09 K warmer is predicted as the level's own model predicts it (0.09 µm
    # here); the slope fitted on the 0.02 K spread extrapolated to 0.20 µm
    assert rmse(residual) == pytest.approx(rmse(residual_plain), rel=1e-9)
    assert rmse(residual) < 2.5 * NOISE

