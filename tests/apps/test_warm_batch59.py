"""A lead-in streamed in one go (``run_rows``, ``stream_steps``) leaves the state the row-by-row
stream leaves, and takes the row-by-row path where a row needs it (warm59)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from test_deploy import _library, campaigns
from thermocomp.apps.deploy import AdaptiveCompensator, OutOfEnvelopeError, StreamingCompensator
from thermocomp.apps.deploy.streaming import MissingValueError, warm
from thermocomp.core.context import row_context, stream_steps
from thermocomp.core.models import LagBank

FAMILIES = ["mlr", "pcr", "arx", "arx_ar", "lagbank", "lagbank_ar", "hammerstein", "ati_arx"]


def _family(name: str):
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import ARX

    if name == "arx_ar":          # the feedback and the delays both carried
        return Compensator(ARX(ar=True, delays=(0, 3), max_inputs=2))
    if name == "lagbank":
        return Compensator(LagBank(n_taus=3))
    if name == "lagbank_ar":
        return Compensator(LagBank(n_taus=3, ar=True))
    return _library(name)


def _flat(state, labels: list | None = None) -> np.ndarray:
    """Every number of a (nested) stream state, in order (a flag as 0/1, None as nothing); its
    words (a guard's state per target) appended to ``labels``."""
    labels = [] if labels is None else labels
    if state is None:
        return np.zeros(0)
    if isinstance(state, str):
        labels.append(state)
        return np.zeros(0)
    if isinstance(state, dict):
        state = [state[k] for k in sorted(state)]
    if isinstance(state, (tuple, list)) or (isinstance(state, np.ndarray) and state.dtype == object):
        return np.concatenate([np.zeros(0)] + [_flat(v, labels) for v in state])
    return np.asarray(state, dtype=float).ravel()


def _same(a, b) -> None:
    words_a, words_b = [], []
    a, b = _flat(a, words_a), _flat(b, words_b)
    assert a.shape == b.shape and words_a == words_b
    np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-12, equal_nan=True)


@pytest.fixture(scope="module")
def data():
    camps = campaigns(3, k=6, n=240)
    return camps, {c: camps[c] for c in list(camps)[:4]}


def _rows(deployed, df):
    from thermocomp.core.context import TIME

    return df[deployed.columns_].to_numpy(float), df[TIME].to_numpy(float)


def _loop(deployed, X, t, clamps: list | None = None) -> np.ndarray:
    """The row-by-row stream (warm before warm59): each row through ``_step``, a missing value
    passed over; each row's clamp count appended to ``clamps``."""
    y = np.full((len(X), len(deployed.targets_)), np.nan)
    for i in range(len(X)):
        try:
            y[i], n = deployed._step(X[i], t[i])
        except MissingValueError:
            continue
        if clamps is not None:
            clamps.append(n)
    return y


def _lead(camps) -> pd.DataFrame:
    """A lead-in of three campaigns joined on one clock (a long record cut in files)."""
    parts, offset = [], 0.0
    for c in ("K00", "K01", "K02"):
        df = camps[c].copy()
        df["time"] += offset
        offset = float(df["time"].iloc[-1]) + 60.0
        parts.append(df)
    return pd.concat(parts, ignore_index=True)


@pytest.mark.parametrize("name", FAMILIES)
@pytest.mark.parametrize("policy", ["clamp", "off"])
def test_a_lead_in_in_one_go_leaves_the_state_row_by_row_leaves(data, name, policy):
    camps, train = data
    comp = _family(name).fit(train)
    s = StreamingCompensator.from_training(comp, train, policy=policy)
    # off: three campaigns joined (far outside the envelope); clamp: a training one (inside it)
    X, t = _rows(s, _lead(camps) if policy == "off" else camps["K01"])
    s.reset()
    looped = _loop(s, X, t)
    expected = s._snapshot()
    s.reset()
    assert _stepped_rows(s, X, t) == [0]              # the reference; the rest in one go
    s.reset()
    y, clamps, dx = s.run_rows(X, t)
    assert s.n_samples_ == len(X) and not clamps.any()
    _same(s._states, expected[2])
    assert s._clock is None or s._clock.snapshot() == pytest.approx(expected[7], nan_ok=True)
    np.testing.assert_allclose(y, looped, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(s.last_x_, dx[-1])
    # the campaign after it streams on from the same state
    Xn, tn = _rows(s, camps["K03"])
    tn = tn + t[-1] + 60.0
    after = s.run_rows(Xn, tn)[0]
    s._restore(expected)
    np.testing.assert_allclose(after, _loop(s, Xn, tn), rtol=1e-9, atol=1e-9)


def _stepped_rows(s, X, t, on_refused=None) -> list[int]:
    """The rows ``run_rows`` passes to ``_step`` (the row-by-row path)."""
    rows, step = [], s._step
    index = {X[i].tobytes(): i for i in range(len(X))}

    def spy(x, time, clocked=False):
        rows.append(index[np.asarray(x).tobytes()])
        return step(x, time, clocked)

    s._step = spy
    try:
        s.run_rows(X, t, on_refused=on_refused)
    finally:
        del s._step
    return rows


@pytest.mark.parametrize("name", ["lagbank", "arx_ar"])
def test_a_missing_value_and_an_excess_take_the_row_by_row_path(data, name):
    camps, train = data
    comp = _family(name).fit(train)
    s = StreamingCompensator.from_training(comp, train, policy="clamp", pattern=False)
    lead = camps["K01"].copy()                        # a training campaign: inside the envelope
    lead.loc[100, "T_2"] = np.nan                     # a dropout: passed over, state held
    lead.loc[180, "T_1"] += 80.0                      # far out: clamped, the held stream forks
    X, t = _rows(s, lead)
    s.reset()
    looped = _loop(s, X, t)
    expected = s._snapshot()
    s.reset()
    rows = _stepped_rows(s, X, t, on_refused=lambda i, exc: None)
    # the first row sets the reference; from the fork on every row streams both ways
    assert rows == [0, 100, *range(180, len(X))]
    _same(s._states, expected[2])
    _same(s._held, expected[5])
    assert s.n_samples_ == expected[4] == len(X) - 1
    s.reset()
    y = s.run_rows(X, t, on_refused=lambda i, exc: None)[0]
    np.testing.assert_allclose(y, looped, rtol=1e-9, atol=1e-9, equal_nan=True)


def test_warm_refuses_an_excess_at_its_row_under_refuse(data):
    camps, train = data
    comp = _family("lagbank").fit(train)
    s = StreamingCompensator.from_training(comp, train, policy="refuse")
    lead = camps["K01"].copy()
    lead.loc[150, "T_1"] += 80.0
    with pytest.raises(OutOfEnvelopeError, match=f"row 151 of {len(lead)}: input T_1"):
        warm(s, lead)
    assert s.n_samples_ == 0                          # reset, as before


@pytest.mark.parametrize("faults", [False, True])
def test_the_adaptive_stream_in_one_go_equals_its_row_by_row_stream(data, faults):
    camps, train = data
    comp = _family("lagbank").fit(train)
    s = StreamingCompensator.from_training(comp, train, policy="clamp")
    a = AdaptiveCompensator.from_training(s, train)
    # quiet: one campaign, every sensor ok throughout (the monitor's and the guard's blocks run
    # to its end); faults: three joined (a jump at each join), a dropout, a missing state
    lead = _lead(camps) if faults else camps["K01"].copy()
    if faults:
        lead.loc[200, "T_2"] = np.nan                 # the monitor reconstructs it
        lead.loc[201:205, "S_rpm"] = np.nan           # held by the adaptive compensator
    X, t = _rows(a, lead)
    a.reset()
    looped = np.array([a._step(X[i], t[i])[0] for i in range(len(X))])
    expected, events = a._snapshot(), a.last_events_
    a.reset()
    y, _ = a.run_rows(X, t)
    np.testing.assert_allclose(y, looped, rtol=1e-9, atol=1e-9)
    got = a._snapshot()
    _same(got[0][2], expected[0][2])                  # the models' states
    for k in range(1, len(got)):                      # the monitor, the guard, the clock, ...
        _same(got[k], expected[k])
    assert a.last_events_ == events


def test_a_fast_loggers_lead_in_in_one_go_keeps_the_freeze_rings_rows_as_row_by_row(data):
    """(dep106) At 10 s the monitor's ring keeps one row per 28.125 s: in one go the same rows,
    their numbers and times, as row by row."""
    camps, train = data
    train = {k: v.assign(time=v["time"] / 6) for k, v in train.items()}
    a = AdaptiveCompensator.from_training(
        StreamingCompensator.from_training(_family("mlr").fit(train), train, policy="clamp"), train)
    X, t = _rows(a, camps["K01"].assign(time=camps["K01"]["time"] / 6))
    a.reset()
    looped = np.array([a._step(X[i], t[i])[0] for i in range(len(X))])
    expected = a._snapshot()
    assert 0 < np.isfinite(a.monitor._past_n).sum() < len(X) / 2      # rows were skipped
    a.reset()
    np.testing.assert_allclose(a.run_rows(X, t)[0], looped, rtol=1e-9, atol=1e-9)
    for got, want in zip(a._snapshot(), expected):
        _same(got, want)

def test_lag_bank_block_equals_its_steps_on_irregular_and_missing_times():
    rng = np.random.default_rng(59)
    n, p = 300, 3
    X = rng.normal(size=(n, p)).cumsum(axis=0)
    time = np.arange(n) * 60.0
    y = X @ rng.normal(size=p) + rng.normal(0, 0.1, n)
    bank = LagBank(n_taus=4, ar=True).fit(X, y, context=pd.DataFrame({"time": time}))
    state = bank.stream_init()
    for i in range(5):
        _, state = bank.stream_step(X[i], state, {"time": time[i]})
    block = X[5:]
    irregular = time[5:] + np.r_[0.0, rng.uniform(0, 30, n - 6).cumsum()]   # every step its own
    gappy = time[5:].copy()
    gappy[40:43] = np.nan                            # a missing time: one period on (time rule)
    gappy[100:] += 600.0                             # a gap: a run of another step
    for t in (time[5:], irregular, gappy):
        context = {"campaign": "c", "time": t}
        y_block, s_block = bank.stream_steps(block, state, context)
        y_loop, s_loop = stream_steps(_NoBlock(bank), block, state, context)
        np.testing.assert_allclose(y_block, y_loop, rtol=1e-9, atol=1e-12)
        _same(s_block, s_loop)


class _NoBlock:
    """An estimator's ``stream_step`` alone: :func:`stream_steps` loops over it."""

    def __init__(self, est):
        self.stream_step = est.stream_step


def test_row_context_takes_each_rows_values_and_keeps_the_scalars():
    ctx = {"campaign": "c", "ambient_c0": 21.0, "time": np.array([0.0, 60.0])}
    assert row_context(ctx, 1, 2) == {"campaign": "c", "ambient_c0": 21.0, "time": 60.0}


@pytest.mark.parametrize("pattern", [True, False])
def test_a_lead_in_beyond_the_envelope_streams_as_row_by_row_under_clamp(data, pattern):
    # three campaigns joined leave the envelope: along the training pattern a row passes as
    # is (in one go with its neighbours), off it the clamp forks (row by row from there)
    camps, train = data
    comp = _family("lagbank").fit(train)
    s = StreamingCompensator.from_training(comp, train, policy="clamp", pattern=pattern)
    X, t = _rows(s, _lead(camps))
    s.reset()
    counted: list = []
    looped = _loop(s, X, t, counted)
    expected = s._snapshot()
    s.reset()
    y, clamps, _ = s.run_rows(X, t)
    assert clamps.tolist() == counted and (not pattern or not any(counted[:240]))
    np.testing.assert_allclose(y, looped, rtol=1e-9, atol=1e-9)
    _same(s._states, expected[2])
    _same(s._held, expected[5])
    assert s._bounds == pytest.approx(expected[8])


def _along(rng, heat: float, n: int = 240) -> pd.DataFrame:
    """Three sensors heating together (one pattern), the error following them."""
    t = np.arange(n) * 60.0
    h = heat * (1 - np.exp(-t / 3000.0))
    return pd.DataFrame({"time": t, "T_1": 20 + h + rng.normal(0, 0.01, n),
                         "T_2": 20 + 0.5 * h + rng.normal(0, 0.01, n),
                         "T_3": 20 + 0.8 * h + rng.normal(0, 0.01, n),
                         "E_Z": 2 * h + rng.normal(0, 0.01, n)})


def test_a_hotter_lead_in_along_the_training_pattern_streams_in_one_go():
    from thermocomp.core.compensator import Compensator

    rng = np.random.default_rng(5)
    train = {f"K{i}": _along(rng, 8.0) for i in range(4)}
    s = StreamingCompensator.from_training(Compensator(LagBank(n_taus=3)).fit(train), train,
                                           policy="clamp")
    X, t = _rows(s, _along(rng, 12.0))              # half as hot again: past the envelope
    s.reset()
    counted: list = []
    looped = _loop(s, X, t, counted)
    expected = s._snapshot()
    s.reset()
    assert _stepped_rows(s, X, t) == [0]              # passed as is, as _step passes them
    out = ((X - X[0] < s.envelope.lo) | (X - X[0] > s.envelope.hi)).any(axis=1)
    assert s.envelope.basis is not None and out.sum() > 100 and not any(counted)
    _same(s._states, expected[2])
    s.reset()
    np.testing.assert_allclose(s.run_rows(X, t)[0], looped, rtol=1e-9, atol=1e-9)


def test_hammerstein_block_holds_a_missing_state_as_its_steps_do(data):
    camps, train = data
    comp = _family("hammerstein").fit(train)
    est = comp.estimators_["E_Z"]
    assert est.state_columns_                         # a machine state enters (S_door)
    df = camps["K04"]
    X = df[list(comp.selected_["E_Z"])].to_numpy(float)
    X = X - X[0]
    context = {"campaign": "c", "time": df["time"].to_numpy(float)}
    for c in est.state_columns_:
        values = df[c].to_numpy(float).copy()
        values[100:140] = np.nan                      # a state not read: the last one held
        context[c] = values
    state = est.stream_init({"campaign": "c", "time": 0.0})
    y_block, s_block = est.stream_steps(X, state, context)
    y_loop, s_loop = stream_steps(_NoBlock(est), X, state, context)
    np.testing.assert_allclose(y_block, y_loop, rtol=1e-9, atol=1e-12)
    _same(s_block, s_loop)
