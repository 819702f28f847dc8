"""ATI on a record of day files chained by ``continues``: its days as the units (ati106).

Joined, such a record is one campaign (``continuation.fit_campaigns``): ATI saw one initial ambient
and kept one model (audit105, edm65's six train days).  ``unit_h=24`` makes each 24 h block its
own unit keyed by its own ambient; predicted, every interval's model runs through the whole
campaign and the block's interval answers, and the stream does the same row by row.
"""

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.deploy.export.errors import NotExportable
from thermocomp.apps.deploy.export.laws import _intervals
from thermocomp.core.context import stream_steps
from thermocomp.core.models import MLR
from thermocomp.core.models.ati import ATIRegressor

DAY_ROWS = 48          # a sample every 30 min
PERIOD_S = 1800.0


def record(levels, seed=0, law=0.06, shift=0.0):
    """Days at the ambient ``levels`` (°C) as one record: a machine sensor T_1 heated each day
    from the room's level, and an error whose sensitivity grows ``law`` per K of the day's level
    (the seasonal law ATI is for), shifted each day by a draw of s.d. ``shift`` µm (what no
    sensor explains).  Returns ``(X, y, context)``; time runs on across the days."""
    rng = np.random.default_rng(seed)
    rows = []
    for day, level in enumerate(levels):
        heat = 4.0 * np.sin(np.linspace(0.0, np.pi, DAY_ROWS)) + rng.normal(0, 0.02, DAY_ROWS)
        t1 = level + heat
        amb = level + rng.normal(0, 0.01, DAY_ROWS)
        e = (1 + law * (level - 20.0)) * 2.0 * heat + rng.normal(0, 0.05, DAY_ROWS) \
            + rng.normal(0, shift)
        time = (day * DAY_ROWS + np.arange(DAY_ROWS)) * PERIOD_S
        rows.append(pd.DataFrame({"time": time, "T_1": t1, "T_amb": amb, "E_X": e}))
    df = pd.concat(rows, ignore_index=True)
    context = pd.DataFrame({"campaign": "R", "time": df.time, "ambient_c0": df.T_amb.iloc[0],
                            "T_1": df.T_1, "T_amb": df.T_amb})
    return df[["T_1", "T_amb"]].to_numpy(), df.E_X.to_numpy(), context


LEVELS = [15.0, 24.0, 18.0, 29.0, 21.0, 27.0, 16.0, 28.0]   # six train days, two test days
TRAIN = 6 * DAY_ROWS


def fitted(**params):
    X, y, ctx = record(LEVELS)
    est = ATIRegressor(MLR(), candidates=(1, 2, 3), unit_h=24, **{"ambient_interaction": True, **params})
    return est.fit(X[:TRAIN], y[:TRAIN], context=ctx.iloc[:TRAIN]), X, y, ctx


def test_a_chained_records_days_are_the_units_and_the_test_days_keyed_by_their_own_ambient():
    est, X, y, ctx = fitted()
    assert len(est.campaign_ambient_) == 6          # six days, not one chain
    predicted = est.predict(X, context=ctx)          # the test days predicted continuing the chain
    plain = MLR().fit(X[:TRAIN], y[:TRAIN]).predict(X)
    error = np.sqrt(np.mean((predicted[TRAIN:] - y[TRAIN:]) ** 2))
    error_plain = np.sqrt(np.mean((plain[TRAIN:] - y[TRAIN:]) ** 2))
    assert error < 0.5 * error_plain
    # keyed by the chain's first ambient alone (the whole record one unit) it would be no better
    first = est.predict(X, context=ctx.assign(T_amb=ctx.T_amb.iloc[0]))
    assert np.sqrt(np.mean((first[TRAIN:] - y[TRAIN:]) ** 2)) > 2 * error


@pytest.mark.parametrize("params", [{}, {"ambient_interaction": False}])
def test_the_stream_switches_at_each_day_as_the_batch_does(params):
    est, X, y, ctx = fitted(**params)
    assert est.n_intervals_ > 1 or any(est.interactions_)
    predicted = est.predict(X, context=ctx)
    start = {"campaign": "R", "time": ctx.time[0], "ambient_c0": ctx.ambient_c0[0]}
    cols = {c: ctx[c].to_numpy() for c in ("time", "T_1", "T_amb")}
    state, out = est.stream_init(start), []
    for lo, hi in [(0, 30), (30, 31), (31, 150), (150, len(X))]:     # blocks across the days' edges
        y_part, state = stream_steps(est, X[lo:hi], state,
                                     {"campaign": "R", "ambient_c0": ctx.ambient_c0[0],
                                      **{c: v[lo:hi] for c, v in cols.items()}})
        out.append(y_part)
    assert np.max(np.abs(np.concatenate(out) - predicted)) < 1e-9
    state, rows = est.stream_init(start), []
    for i in range(3 * DAY_ROWS):
        v, state = est.stream_step(X[i], state, {"campaign": "R", "ambient_c0": ctx.ambient_c0[0],
                                                 **{c: cols[c][i] for c in cols}})
        rows.append(v)
    assert np.max(np.abs(np.array(rows) - predicted[:3 * DAY_ROWS])) < 1e-9
    with pytest.raises(NotExportable, match="unit_h=24"):
        _intervals(est)                               # the code keys a campaign once


def test_the_base_model_alone_is_kept_where_it_leaves_the_days_out_better():
    # no seasonal law, the days shifted by what no sensor explains: a slope in the ambient fitted
    # on six days' shifts (ed10035's six train days: 2 intervals tested 4.35 µm, the base 3.97)
    X, y, ctx = record(LEVELS, law=0.0, shift=0.3)
    est = ATIRegressor(MLR(), candidates=(1, 2, 3), unit_h=24, ambient_interaction=True)
    est.fit(X[:TRAIN], y[:TRAIN], context=ctx.iloc[:TRAIN])
    plain = est.elbow_["plain_model"]
    chosen = est.elbow_["n_intervals"].index(est.elbow_["chosen"])
    assert plain["sm"] + plain["sd"] <= est.elbow_["sm"][chosen] + est.elbow_["sd"][chosen]
    assert est.n_intervals_ == 1 and est.interactions_ == [False]
    np.testing.assert_allclose(est.predict(X, context=ctx), MLR().fit(X[:TRAIN], y[:TRAIN]).predict(X),
                               atol=1e-9)
