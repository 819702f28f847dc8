"""The envelope's pattern tolerance priced on held-out training blocks (clamp75,
``promote.envelope.priced``; benchmarks/bench_clamp75.py).

One record of a linear machine whose bed keeps warming, one of its sensors faster and faster
(its share grows with the square of the time): every later block of the record leaves the pattern of the
rows before it, and the model reads that move right.  Priced on the record's own forward blocks,
the gate widens and the night that continues the record is clamped less and closer to the
truth; a sensor 30 K out still leaves the widened pattern and is clamped; the exported code
carries the priced tolerance.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.deploy import StreamingCompensator, replay
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR

DT_S, TRAIN_ROWS, ROWS = 60.0, 600, 700


def _record() -> pd.DataFrame:
    rng = np.random.default_rng(1)
    t = np.arange(ROWS) * DT_S
    hours = t / 3600.0
    rise = 2 * (1 - np.exp(-t / 3000.0))
    amb = 20 + 0.8 * np.sin(2 * np.pi * t / 5400.0)
    bed = 0.3 * hours
    noise = 0.01 * rng.standard_normal((4, ROWS))
    f = {"time": t, "T_1": amb + 5 * rise + noise[0], "T_2": amb + 3 * rise + bed + noise[1],
         "T_3": amb + rise + 2 * bed + 0.02 * hours ** 2 + noise[2], "T_amb": amb + noise[3]}
    f["E_X"] = 4 * f["T_1"] - 2 * f["T_2"] + 3 * f["T_3"]
    return pd.DataFrame(f)


@pytest.fixture(scope="module")
def deployed():
    whole = _record()
    train = {"R": whole.iloc[:TRAIN_ROWS].reset_index(drop=True)}
    comp = Compensator(MLR(), reference="none").fit(train)
    streams = {p: StreamingCompensator.from_training(comp, train, priced=p) for p in (False, True)}
    return streams, train["R"], whole.iloc[TRAIN_ROWS:].reset_index(drop=True)


def test_the_gate_widens_where_the_record_read_its_own_excursions_better(deployed):
    streams, lead, night = deployed
    trained, priced = streams[False].envelope, streams[True].envelope
    assert trained.tol_factor == 1.0 and not trained.priced
    assert priced.tol_factor > 1.5
    assert priced.tol == pytest.approx(trained.tol * priced.tol_factor)
    err = {}
    for p, stream in streams.items():
        out = replay(stream, night, lead_in=lead)
        err[p] = (out["n_clamped"].gt(0).sum(), np.sqrt(np.mean((out["E_X"] - night["E_X"]) ** 2)))
    assert err[True][0] < err[False][0]              # fewer rows clamped ...
    assert err[True][1] < 0.9 * err[False][1]        # ... and the night nearer the truth


def test_a_sensor_far_out_is_clamped_and_the_code_carries_the_priced_tolerance(deployed):
    streams, lead, night = deployed
    stream = streams[True]
    broken = night.head(20).copy()
    broken.loc[10:, "T_2"] += 30.0
    out = replay(stream, broken, lead_in=lead)
    assert out["n_clamped"].iloc[10:].gt(0).all()
    ss = state_space(stream)
    assert ss.pattern_tol == pytest.approx(stream.envelope.tol)
    sim, fresh = Simulator(ss), replay(stream, broken)   # the exported arithmetic = the stream
    u, t = broken[stream.columns_].to_numpy(float), broken["time"].to_numpy(float)
    corrections = np.array([sim.step(r, s)[0] for r, s in zip(u, t)])
    assert fresh["n_clamped"].gt(0).any()
    np.testing.assert_allclose(-corrections, fresh["E_X"], atol=1e-6)
