"""A range reading that takes a sensor out where the first one out comes back in the same sample,
in the exported C (swap99, issue 34): the code's monitor judges the first's return in the set
without the range sensor before it refuses the reading, and takes the swap as the served monitor
does (benchmarks/bench_swap99.py: tr9828's ``T_ram`` beyond its range while the blind
``T_coolant_return`` was out; served took ``T_ram`` out and ``T_coolant_return`` back, the code
kept ``T_coolant_return`` out, 22.7 µm apart).

A six-sensor machine whose field has four sources, its POD four modes (``min_active`` 5, as the
trunnion's 8 of 9): with one sensor out, the field is not rebuilt without a second.  ``T_5``
drops out for five samples; at the sample the served monitor re-admits it, ``T_0`` reads beyond
its range."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from conftest import deployed_as_replay, served_rows
from test_export import _compose, needs_cc
from test_export_cmon80 import streamed_as_served
from test_export_cmon85 import _mirror, without
from thermocomp.apps.deploy.export import state_space
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.watch import RANGE

NAMES = [f"T_{k}" for k in range(6)]
FIRST, RANGED = "T_5", "T_0"          # out for a dropout, then beyond its range at its return
PERIOD = 20.0
MIX = np.random.default_rng(99).normal(size=(6, 4))     # four sources, six sensors


def _campaign(seed: int, rows: int) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    t = np.arange(rows)
    sources = np.c_[[np.sin(t / (40 + 13 * k) + rng.uniform(0, 6)) * (1 + 0.002 * t)
                     for k in range(4)]].T
    x = 20 + sources @ MIX.T + rng.normal(scale=0.01, size=(rows, 6))
    frame = pd.DataFrame(x, columns=NAMES)
    frame.insert(0, "time", t * PERIOD)
    frame["E_X"] = 2.0 * (x[:, 0] - x[0, 0]) - 1.0 * (x[:, 3] - x[0, 3])
    frame["E_Z"] = 1.5 * (x[:, 5] - x[0, 5]) + 0.5 * (x[:, 2] - x[0, 2])
    return frame


@pytest.fixture(scope="module")
def machine(tmp_path_factory):
    """``(adaptive MLR, its system with the monitor, the test campaign with the dropout, the row
    its sensor is re-admitted, 0-based)``."""
    data = tmp_path_factory.mktemp("swap99") / "data"
    data.mkdir()
    split = {"K01": "train", "K02": "train", "K03": "train", "K04": "test"}
    for k, cid in enumerate(split):
        _campaign(k, 600 if split[cid] == "train" else 400).to_csv(data / f"{cid}.csv", index=False)
    pd.DataFrame([(c, f"{c}.csv", s, "") for c, s in split.items()],
                 columns=["campaign", "file", "split", "notes"]).to_csv(data / "campaigns.csv",
                                                                         index=False)
    deployed, ds, test_ids = deployed_as_replay(_compose(
        f"data.path={data}", "track=false", "model=mlr", "monitor.adaptive=true",
        "monitor.pod.modes=4", "monitor.fallbacks=none"))
    frame = ds.campaigns[test_ids[0]].reset_index(drop=True)
    frame.loc[100:104, FIRST] = np.nan
    back = next(e["time"] for e in served_rows(deployed, frame, "K04").events
                if e.get("sensor") == FIRST and e.get("to") == "ok")
    return deployed, state_space(deployed, monitor=True), frame, int(back / PERIOD)


def _ranged(frame, row: int, sensor: str = RANGED) -> pd.DataFrame:
    out = frame.copy()
    out.loc[row:row + 2, sensor] += 30.0            # beyond its range (+- 10 degC) for 3 rows
    return out


def _moves(deployed, frame) -> list[tuple]:
    return [(int(e["time"] / PERIOD), e["sensor"], e["to"]) for e in
            served_rows(deployed, frame, "K04").events if e.get("to") in ("excluded", "ok")]


def test_the_field_is_not_rebuilt_without_two_and_served_swaps(machine):
    deployed, ss, frame, back = machine
    assert ss.monitor["min_active"] == len(NAMES) - 1 and all(ss.monitor["ported_out"])
    moves = _moves(deployed, _ranged(frame, back))
    assert moves[:3] == [(100, FIRST, "excluded"), (back, RANGED, "excluded"), (back, FIRST, "ok")]


@needs_cc
def test_the_code_takes_the_swap_as_served(machine, tmp_path):
    """The mirror and the compiled C equal to the served corrections on every row, nothing
    flagged, the pack not cut (fails on 4fafc59a: ``RANGE`` flagged at the swap's row)."""
    deployed, ss, frame, back = machine
    faulty = _ranged(frame, back)
    want = corrections(ss, served_rows(deployed, faulty, "K04").y)
    got, out, missed = _mirror(ss, faulty)
    assert not missed and np.max(np.abs(got - want)) < 1e-9
    assert (back + 1, RANGED) in [(row, sensor) for row, sensor, _ in out]
    streamed_as_served(tmp_path, deployed, ss, "K04", faulty, want)


def test_an_export_before_swap99_flags_the_range_reading(machine):
    """Arrays without ``range_swap``: ``RANGE`` flagged at the swap's row, parting there."""
    deployed, ss, frame, back = machine
    faulty = _ranged(frame, back)
    got, _, missed = _mirror(without(ss, "range_swap"), faulty)
    assert missed and missed[0] == (back + 1, RANGE)
    want = corrections(ss, served_rows(deployed, faulty, "K04").y)
    assert (np.flatnonzero(np.abs(got - want).max(axis=1) > 1e-9) + 1).min() == back + 1


def test_no_swap_where_the_first_is_not_back_in_that_sample_flagged_as_before(machine):
    """The range reading one sample before the first's return (its wait not out): served holds
    too few to rebuild the field; the code refuses the reading as before, ``RANGE`` flagged."""
    deployed, ss, frame, back = machine
    faulty = _ranged(frame, back - 1)
    assert (back - 1, FIRST, "ok") not in _moves(deployed, faulty)
    _, _, missed = _mirror(ss, faulty)
    assert missed and missed[0] == (back, RANGE)
