"""A sensor out for a freeze alone, back on readings off its held value, in the exported C
(freeze84, issue 34): the code's monitor re-admits it where the served one does.

A six-sensor machine (MLR, deployed adaptive, no fallback model) whose sensors warm together,
logged to 0.01 °C.  On the last test campaign ``T_2`` holds its reading for ``HELD`` rows while
the field moves past its band (the freeze takes it out), then catches up with its true reading
over ``CATCH_UP`` rows.  The served monitor takes it back on its second reading off the held
value (readmission.py); the numpy mirror and the compiled code (gcc -Wall -Wextra -Werror)
exclude and re-admit it on the same rows, flag nothing and give the served corrections on every
row.  An export before freeze84 (no ``thawed``) flags the return it does not hold."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

import test_export
from conftest import deployed_as_replay
from test_export import CAMPAIGNS, needs_cc
from test_export_cmon80 import streamed_as_served
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.watch import (
    EXCLUDED,
    FREEZE,
    NO_THAW,
    NOT_IN_CODE,
    READMITTED,
    THAWED,
)
from thermocomp.apps.deploy.report import stream_rows

ROWS, START, HELD, CATCH_UP = 300, 150, 12, 6


def _machine(root):
    """test_export's six campaigns of six sensors (module doc), one sample every 100 s."""
    root.mkdir(parents=True)
    t = np.arange(ROWS)
    for i, (cid, _) in enumerate(CAMPAIGNS):
        rng = np.random.default_rng(i)
        warm = 3 * (1 - np.exp(-t / 80)) + 1.5 * np.sin(t / 23 + i)
        gradient = 1.5 * np.sin(t / 53 + i)
        x = 20 + np.round(warm[:, None] + gradient[:, None] * np.linspace(-0.5, 0.5, 6)
                          + rng.normal(scale=0.02, size=(ROWS, 6)), 2)
        frame = pd.DataFrame(x, columns=[f"T_{k}" for k in range(6)])
        frame.insert(0, "time", t * 100.0)
        frame["E_X"] = 3 * (x[:, 1] - x[0, 1]) - 1.2 * (x[:, 4] - x[0, 4]) + rng.normal(0, 0.2, ROWS)
        frame.to_csv(root / f"{cid}.csv", index=False)
    pd.DataFrame([(c, f"{c}.csv", s, "") for c, s in CAMPAIGNS],
                 columns=["campaign", "file", "split", "notes"]).to_csv(root / "campaigns.csv",
                                                                        index=False)
    return root


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR, its system with the monitor, the record with T_2 held and caught up)``."""
    root = _machine(tmp_path_factory.mktemp("freeze84") / "data")
    cfg = test_export._compose(f"data.path={root}", "track=false", "monitor.adaptive=true",
                               "model=mlr", "monitor.fallbacks=none")
    deployed, ds, test_ids = deployed_as_replay(cfg)
    frame = ds.campaigns[test_ids[-1]].reset_index(drop=True)
    x = frame["T_2"].to_numpy(float)
    end = START + HELD
    frame.loc[START:end - 1, "T_2"] = x[START]
    w = np.arange(1, CATCH_UP + 1) / CATCH_UP
    frame.loc[end:end + CATCH_UP - 1, "T_2"] = np.round(
        x[START] * (1 - w) + x[end:end + CATCH_UP] * w, 2)
    return deployed, state_space(deployed, monitor=True), frame


def _mirror(ss, frame) -> tuple[np.ndarray, list[tuple[int, int, int]]]:
    """The numpy mirror's corrections, and its (row, flag, rule) of each exclusion, re-admission
    and rule it does not hold."""
    sim = Simulator(ss)
    sim.reset()
    got, moves = [], []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        got.append(sim.step(u, t))
        for flag in (EXCLUDED, READMITTED, NOT_IN_CODE):
            if sim.watch.flags & flag:
                moves.append((i + 1, flag,
                              sim.watch.missed if flag == NOT_IN_CODE else sim.watch.rule))
    return np.array(got), moves


def _served_moves(deployed, frame) -> list[tuple[int, str, str]]:
    times = frame["time"].to_numpy(float)
    return [(int(np.searchsorted(times, e["time"])) + 1, e["to"], e["reason"].split(":")[0])
            for e in stream_rows(deployed, frame, "K06").events
            if e.get("sensor") == "T_2" and "excluded" in (e["to"], e["from"])]


@needs_cc
def test_the_code_takes_a_sensor_back_from_a_freeze_where_the_served_monitor_does(served, tmp_path):
    deployed, ss, frame = served
    (out, to, why), (back, to2, _) = _served_moves(deployed, frame)
    assert (to, why, to2) == ("excluded", "freeze", "ok")
    assert START + HELD < back < START + HELD + CATCH_UP       # on its readings, not a window
    want = corrections(ss, stream_rows(deployed, frame, "K06").y)
    got, moves = _mirror(ss, frame)
    assert moves == [(out, EXCLUDED, FREEZE), (back, READMITTED, THAWED)]
    assert np.max(np.abs(got - want)) < 1e-9
    streamed_as_served(tmp_path, deployed, ss, "K06", frame, want)


def test_an_export_before_freeze84_flags_the_return(served):
    """Without ``thawed`` the mirror flags the served return and keeps the sensor out."""
    deployed, ss, frame = served
    back = _served_moves(deployed, frame)[1][0]
    old = {k: v for k, v in ss.monitor.items() if k != "thawed"}
    _, moves = _mirror(dataclasses.replace(ss, monitor=old), frame)
    assert (back, NOT_IN_CODE, NO_THAW) in moves
    assert not [m for m in moves if m[1] == READMITTED and m[0] <= back]


def _still_then_frozen(frame, at: int, rows: int, hold: int):
    """``frame`` with every sensor standing still (its reading at ``at``, dithering 0.02 °C on the
    0.01 °C logger) for ``rows`` rows from ``at``, ``T_2`` held at its reading from ``at + rows -
    hold`` on (mon105d: a frozen sensor whose own past stood still)."""
    still = frame.copy()
    rng = np.random.default_rng(7)
    cols = [f"T_{k}" for k in range(6)]
    level = still.loc[at, cols].to_numpy(float)
    still.loc[at:at + rows - 1, cols] = np.round(level + rng.normal(scale=0.02, size=(rows, 6)), 2)
    first = at + rows - hold
    still.loc[first:at + rows - 1, "T_2"] = still.loc[first, "T_2"]
    return still.iloc[:at + rows].reset_index(drop=True)


@needs_cc
def test_a_still_sensor_frozen_by_its_run_is_read_held_by_the_code_as_served(served, tmp_path):
    """(mon105d) Out for a freeze by its run alone after its own readings stood still, the served
    model reads ``T_2`` at its held value (mon105c); the mirror and the C read it so too: the
    served corrections on every row, nothing flagged as not in the code.  An export before it (no
    ``spread``) reads its stand-in there and parts from the served model."""
    deployed, ss, frame = served
    still = _still_then_frozen(frame, 100, 60, 40)
    want = corrections(ss, stream_rows(deployed, still, "K06").y)
    got, moves = _mirror(ss, still)
    assert [m[1:] for m in moves] == [(EXCLUDED, FREEZE)], moves
    assert np.max(np.abs(got - want)) < 1e-9
    old = {k: v for k, v in ss.monitor.items() if k != "spread"}
    before, _ = _mirror(dataclasses.replace(ss, monitor=old), still)
    assert np.max(np.abs(before - want)) > 1e-3           # the held value moved the correction
    streamed_as_served(tmp_path, deployed, ss, "K06", still, want)
