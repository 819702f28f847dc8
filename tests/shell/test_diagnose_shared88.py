"""Issue 34 (diag88b): a lag from the campaign's start takes ONE start transient shared by the
campaigns, ``1 - exp(-(t - t0)/tau)``, in place of k directions of the sensors' initial distances
whose per-campaign offsets fit the first readings' noise, one level per campaign
(benchmarks/bench_diag88b.py)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from test_diagnose import _dataset
from thermocomp.apps.diagnose import AugmentedRegressor, Effect
from thermocomp.apps.diagnose.candidates import CandidateOptions
from thermocomp.apps.diagnose.features import effect_features
from thermocomp.base.errors import ParameterError
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR

TAU = 1800.0


def _start(k: int) -> Effect:
    return Effect("dynamics", "first_order_lag", "T_a", tau_s=TAU, initial_state=("T_a", "T_b"),
                  initial_directions=k)


def _context(n_campaigns=8, n=40, seed=0) -> pd.DataFrame:
    """Campaigns that start off the ambient by different amounts, steady afterwards."""
    rng = np.random.default_rng(seed)
    rows = []
    for c in range(n_campaigns):
        time = np.arange(n) * 300.0 + rng.uniform(0, 1e5)      # a start of its own
        first = 20.0 + rng.normal(0.0, 2.0, 2)
        rows.append(pd.DataFrame({"campaign": f"C{c}", "time": time, "ambient_c0": 20.0,
                                  "T_a": first[0], "T_b": first[1]}))
    return pd.concat(rows, ignore_index=True)


def _in_sample_fit(Z: np.ndarray, y: np.ndarray) -> np.ndarray:
    Z = np.column_stack([np.ones(len(y)), Z])
    return Z @ np.linalg.lstsq(Z, y, rcond=None)[0]


def test_a_shared_start_is_one_transient_with_no_level_per_campaign():
    ctx = _context()
    g = ctx["campaign"].to_numpy()
    elapsed = ctx["time"] - ctx.groupby("campaign")["time"].transform("first")
    decay = 1.0 - np.exp(-elapsed.to_numpy() / TAU)
    shared = effect_features(_start(0), np.zeros((len(ctx), 1)), ctx, g)
    learned = effect_features(_start(2), np.zeros((len(ctx), 1)), ctx, g)
    # the lag of a steady T_a is flat: the start block is the whole signal, one regressor
    assert shared.shape[1] == 2 and learned.shape[1] == 3
    np.testing.assert_allclose(shared[:, 1], decay, atol=1e-12)
    # labels in the first-sample frame: each campaign's first reading's noise is a level from
    # the second sample on, here aligned with the sensors' initial distances (a chance match)
    offsets = ctx[["T_a", "T_b"]].to_numpy() - 20.0
    level = offsets @ np.array([0.3, -0.2])
    level -= level.mean()
    y = 0.8 * decay - level * (elapsed.to_numpy() > 0)
    level_of = pd.Series(level).groupby(g).first()

    def fitted_levels(block):
        late = elapsed.to_numpy() > 4 * TAU            # the transient settled
        fit = pd.Series(_in_sample_fit(block[:, 1:], y)[late]).groupby(g[late]).mean()
        return fit.loc[level_of.index].to_numpy()

    # two directions take the campaigns' levels; one transient cannot: the same for every campaign
    assert np.corrcoef(fitted_levels(learned), -level_of)[0, 1] > 0.99
    assert np.ptp(fitted_levels(shared)) < 1e-9


def test_a_shared_start_streams_as_it_predicts_and_reads_no_sensor_at_the_start():
    ds = _dataset(door_gain=2.0, n_campaigns=8, test_every=100)
    effects = [Effect("dynamics", "lowpass_inputs", tau_s=3600, initial_state=["T_a", "T_b"],
                      initial_directions=0), _start(0)]
    assert [e.context_columns for e in effects] == [[], ["T_a"]]
    assert effects[0].start_width == 1 and not effects[0].learns
    comp = Compensator(AugmentedRegressor(MLR(), [e.to_dict() for e in effects]),
                       inputs=["T_a", "T_b", "T_amb"]).fit(ds.campaigns)
    est = comp.estimators_["E_Z"]
    df = ds.campaigns["C01"]
    batch = comp.predict({"C01": df})["C01"]["E_Z"].to_numpy()
    ref, a0 = df.iloc[0], float(df.iloc[0]["T_amb"])
    state, streamed = est.stream_init(context={"ambient_c0": a0}), []
    for _, row in df.iterrows():
        x = np.array([row["T_a"] - ref["T_a"], row["T_b"] - ref["T_b"], row["T_amb"] - ref["T_amb"]])
        y, state = est.stream_step(x, state, context={**row.to_dict(), "ambient_c0": a0})
        streamed.append(y)
    np.testing.assert_allclose(streamed, batch, atol=1e-8)


def test_diagnose_tries_the_shared_start_by_default_and_k_directions_on_request():
    assert CandidateOptions().initial_directions == (0,)
    assert Effect.from_dict(_start(0).to_dict()) == _start(0)
    assert "shared by the campaigns" in _start(0).label
    with pytest.raises(ParameterError, match="initial_directions"):
        _start(-1)
    with pytest.raises(ParameterError, match="initial_directions"):
        _start(3)
