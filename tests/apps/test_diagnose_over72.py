"""planted72: a state times a temperature's rise over the air's (``Effect.over``).

The year-round VMC's planted position effect acts through a column tilt, back less front, two
nodes no sensor reads: one sensor's rise reads it with R^2 0.82-0.85, ``T_box1``'s rise over
``T_amb``'s with 0.94-0.96 (``benchmarks/bench_planted72.py tilt``).  With 8 train campaigns the
single products lost 1-3 campaigns and the bank of all the rises saturated, so seed 515 accepted
nothing; the product over the air gains in all 8 and is taken.  It exports (overexport72; refused
by name before): a product's derived input with its second factor less the air's, ``r_a (r_b -
r_c)``, in C, Structured Text and the Simulator as the served model streams it.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from test_diagnose_few import diagnosis
from test_diagnose_positions61 import INPUTS, gantry, train_problem
from test_export import needs_cc, parses_as_the_parsed_block
from test_export_auto57 import TOLERANCE_UM, _proved
from test_export_inputs_product62 import _diagnosed, _gantry
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.apps.diagnose.augmented import AugmentedRegressor
from thermocomp.apps.diagnose.candidates import CandidateOptions, candidates
from thermocomp.apps.diagnose.features import Effect, effect_features
from thermocomp.core.models import MLR, LagBank

OVER = {"kind": "interaction", "transform": "product", "column": "S_y_pos", "other": "T_rail_top",
        "over": "T_amb"}


def test_a_product_over_the_air_is_the_lever_times_the_rise_less_the_airs():
    frame = gantry().campaigns["C0"]
    context = frame[["time", "S_y_pos", "T_rail_top", "T_amb"]].assign(campaign="C0")
    e = Effect(**OVER)
    F = effect_features(e, np.zeros((len(frame), 1)), context)
    rise = lambda c: frame[c].to_numpy() - frame[c].iloc[0]       # noqa: E731
    assert np.allclose(F[:, 0], rise("S_y_pos") * (rise("T_rail_top") - rise("T_amb")))
    assert e.context_columns == ["S_y_pos", "T_rail_top", "T_amb"]
    assert "over T_amb" in e.title and Effect.from_dict(e.to_dict()) == e


def test_the_product_over_the_air_streams_as_it_predicts():
    ds = gantry()
    frames = [ds.campaigns[c] for c in ("C0", "C1")]
    inputs = ["T_rail", "T_head"]
    X = [f[inputs] - f[inputs].iloc[0] for f in frames]
    ctx = [f[["time", "S_y_pos", "T_rail_top", "T_amb"]].assign(campaign=c)
           for f, c in zip(frames, ("C0", "C1"))]
    model = AugmentedRegressor(MLR(), [OVER])
    model.fit(pd.concat(X).to_numpy(), pd.concat([f["E_Y"] for f in frames]).to_numpy(),
              pd.concat(ctx, ignore_index=True))
    batch = model.predict(X[1].to_numpy(), ctx[1])
    state, streamed = model.stream_init(), []
    for x, (_, row) in zip(X[1].to_numpy(), ctx[1].iterrows()):
        value, state = model.stream_step(x, state, row.to_dict())
        streamed.append(value)
    assert np.allclose(streamed, batch, atol=1e-9)


def test_the_search_tries_each_sensor_over_each_ambient_sensor():
    got = [c for c in candidates(train_problem(), INPUTS, set(), [], CandidateOptions()) if c.over]
    assert set(got) == {Effect("interaction", "product", "S_y_pos", other=t, over="T_amb")
                        for t in INPUTS[1:]}


def test_seed_515s_planted_tilt_is_taken_over_the_air():
    j = diagnosis("axis_position", 515)
    top = [e for e in j["effects"] if e["accepted"]][0]
    assert (top["column"], top["effect"].get("over")) == ("S_pos_Y", "T_amb")
    assert top["evidence"]["p_value_family"] <= 0.01
    assert j["after"]["test_rmse"] <= 0.6 * j["before"]["test_rmse"]
    assert not j["control_ever_clears_bar"]


@needs_cc
def test_the_product_over_the_air_exports_and_equals_the_stream(tmp_path, parsed_block):
    """export62's gantry (a rail ``T_a``, its top plate ``T_b``, the air, a saddle's position):
    the position times the plate's rise over the air's, around a lag bank (which lags the derived
    input too).  The compiled C, the Structured Text and the Simulator equal ``replay`` (the served
    model's stream, the clamp acting) to 1e-9 µm; export refused it by name before."""
    over = {**OVER, "other": "T_b", "frame": "absolute"}
    stream, tests, _ = _diagnosed(_gantry(tmp_path / "data"), [over], LagBank(n_taus=2))
    ss = state_space(stream)
    state, plate, air = (ss.inputs.index(c) for c in ("S_y_pos", "T_b", "T_amb"))
    assert ss.derived == [[state, plate, 0, 1]] and ss.derived_over == [air]
    assert "product(T_b rise over T_amb) (absolute)" in ss.provenance["laws"]["E_X"]
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    parses_as_the_parsed_block(exported_files(stream, "st")["compensator.st"], parsed_block)
