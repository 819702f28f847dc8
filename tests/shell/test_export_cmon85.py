"""A drift with a sensor out already in the exported C (cmon85, issue 34): the code's monitor
solves the operator of an active set it does not hold (its POD basis in the code, a Cholesky of
the reduced normal system), so that with one sensor out (a dropout) it judges the drift of the
others and takes a second out as the served monitor does, where before it flagged ``DRIFT`` and
the pack was cut there (benchmarks/bench_cmon85.py).

The column machine (``thermocomp simulate sim=column_moving_source``, seed 8841 of this task),
MLR deployed adaptive as by default, its test campaign with bench_cmon82's sensor missing for a
quarter of the rows after the middle (bench_cmon84's dropout)."""

from __future__ import annotations

import copy
import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import copied_once, deployed_as_replay
from test_export import _compose, needs_cc
from test_export_cmon80 import assert_packed_as_served
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.served import ServedStreams, frame_digest
from thermocomp.apps.deploy.export.watch import (
    DRIFT,
    DRIFT_OUT,
    DROPOUT,
    EXCLUDED,
    NOT_IN_CODE,
    CodeMonitor,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

SEED = 8841


def column_record(tmp_path_factory, fault: str):
    """``(deployed, its system with the monitor, the test campaign with bench_cmon84's
    ``fault``)`` on the column machine of seed :data:`SEED` (cmon85's and cmon86's record)."""
    deployed, ss, faults = _column(tmp_path_factory)
    return deployed, ss, faults[fault]


def _column(tmp_path_factory):
    from bench_cmon82 import _sensor
    from bench_cmon84 import _column_faults

    deployed, ss, frame = column_system(tmp_path_factory)
    return deployed, ss, _column_faults(frame, _sensor(ss))


@copied_once
def column_system(tmp_path_factory):
    """``(deployed, its system with the monitor, the test campaign)`` of the column machine of
    seed :data:`SEED`: simulated and fitted once for a worker's tests, each caller given a deep
    copy (scopec: four modules' fixtures simulated and fitted the same machine; a copy of its own
    lets a module plant its fault in the frame)."""
    from thermocomp.shell.cli import main

    data = tmp_path_factory.mktemp(f"column{SEED}") / "data"
    assert main(["-q", "simulate", f"seed={SEED}", f"data.path={data}", "track=false",
                 "sim=column_moving_source"]) == 0
    cfg = _compose(f"data.path={data}", "track=false", "model=mlr")
    deployed, ds, test_ids = deployed_as_replay(cfg)
    ss = state_space(deployed, monitor=True)
    # a copy of its own, as conftest.fl_thermal_served's: the reader's columns are Arrow's
    # read-only buffers, written in place once ``ds`` is collected (mon98b's fixture failed so
    # in a full run, "assignment destination is read-only", as the collector's timing had it)
    return deployed, ss, ds.campaigns[test_ids[0]].reset_index(drop=True).copy()


def without(ss, feature: str):
    """``ss`` as exported before ``feature`` (its monitor key) was in the code."""
    return dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items() if k != feature})


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, its system with the monitor, the test campaign with the dropout)``."""
    return column_record(tmp_path_factory, "dropout")


@pytest.fixture(scope="module")
def streams(record):
    """The served streams of ``record``'s model, made once for the module's tests and packs."""
    return ServedStreams(record[0])


_LEADS: dict = {}       # {(id(ss), the lead-in's digest): (ss, the mirror after it, got, out, missed)}


def _mirror(ss, frame, lead: int = 0, rows: int | None = None, each=None):
    """The numpy mirror's corrections, its exclusions ``(row, sensor, rule)`` and the rows it
    flags ``(row, rule)`` not in the code.  ``lead``: ``frame``'s first rows are a lead-in other
    calls feed ``ss`` too (a record's planted copies): stepped once, the mirror's state after it
    deep-copied for each (as the pack's ``_Lead`` shares it; cmon89: 6 of 4321 rows, 3457 the
    lead-in).  ``rows``: only ``frame``'s first rows stepped (ci104b: a test reading the first
    flag needs no row after it; a row's outputs depend on no later row).  ``each(i, sim)``:
    called after each row's step (0-based ``i``; ``lead`` 0 only), for a test's own reading of
    the same pass (ci104b: no second pass of the same rows)."""
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    U, times = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    end = len(frame) if rows is None else min(rows, len(frame))

    def stepped(sim, start: int, stop: int) -> tuple[list, list, list]:
        got, out, missed = [], [], []
        for i in range(start, stop):
            got.append(sim.step(U[i], times[i]))
            w = sim.watch
            if w.flags & EXCLUDED:
                out.append((i + 1, names[w.sensor], w.rule))
            if w.flags & NOT_IN_CODE:
                missed.append((i + 1, w.missed))
            if each is not None:
                each(i, sim)
        return got, out, missed

    sim = Simulator(ss)
    sim.reset()
    if not lead:
        got, out, missed = stepped(sim, 0, end)
        return np.array(got), out, missed
    assert each is None and end > lead, "each / rows within the lead-in: with lead=0 only"
    key = (id(ss), frame_digest(frame.iloc[:lead]))
    if key not in _LEADS:           # (ss kept: its id names no other system while cached)
        _LEADS[key] = (ss, sim, *stepped(sim, 0, lead))
    _, at_lead, got, out, missed = _LEADS[key]
    rest = stepped(copy.deepcopy(at_lead), lead, end)
    return np.array(got + rest[0]), out + rest[1], missed + rest[2]


def _served_out(streams: ServedStreams, frame) -> list[tuple[int, str, str]]:
    """The served monitor's exclusions: ``(row, sensor, why)``, 1-based."""
    times = frame["time"].to_numpy(float)
    return [(int(np.searchsorted(times, e["time"])) + 1, e["sensor"], e["reason"].split(":")[0])
            for e in streams.rows(frame, "test").events
            if e.get("sensor") and e["to"] == "excluded"]


def test_the_solved_operator_is_the_served_one(record):
    """Of every set with one or two sensors out, the solve gives the served ``pod.operator``
    (its pinv) and leverages (its QR)."""
    deployed, ss, _ = record
    mon, code = deployed.monitor, CodeMonitor(ss.monitor)
    n = code.n
    for out in [np.arange(n) == j for j in range(n)] + [np.isin(np.arange(n), (0, j))
                                                         for j in range(1, n)]:
        want_M, want_lev = mon._operator(~out)
        M, lev = code._solved(~out)
        assert np.max(np.abs(M[:, ~out] - want_M)) < 1e-9 and np.max(np.abs(lev - want_lev)) < 1e-9


def test_a_square_set_is_solved_within_its_condition_not_its_square(record):
    """(qr103) Square sets (as many sensors in as modes, 20 drawn): the solve (a QR of the basis
    rows) parts from served's pinv by less than 2 eps cond max|M|.  On 40 such draws (conditions
    9.3 to 3.0e4) the QR measured 0.2-0.74 eps cond max|M|; 8afba209's Cholesky of the normal
    system, which squares the condition, 1.6-1.1e4 (1.5e-3 apart at cond 3e4): it fails here."""
    deployed, ss, _ = record
    mon, code = deployed.monitor, CodeMonitor(ss.monitor)
    phi, draw = np.asarray(ss.monitor["basis"], float), np.random.default_rng(103)
    for _ in range(20):
        active = np.isin(np.arange(code.n), draw.choice(code.n, phi.shape[1], replace=False))
        want_M, want_lev = mon._operator(active)
        bound = 2 * np.finfo(float).eps * np.linalg.cond(phi[active]) * max(1.0, np.abs(want_M).max())
        M, lev = code._solved(active)
        assert np.max(np.abs(M[:, active] - want_M)) < bound and np.max(np.abs(lev - want_lev)) < 1e-9


@needs_cc
def test_a_drift_with_a_sensor_out_is_followed_by_the_code_as_served(record, streams, tmp_path):
    deployed, ss, frame = record
    served = _served_out(streams, frame)
    # the served monitor: the sensor out for its dropout, then a drift exclusion while it is out
    assert served[0][2] == "dropout" and any(why == "drift" for _, _, why in served[1:]), served
    want = corrections(ss, streams.rows(frame, "test").y)
    got, out, missed = _mirror(ss, frame)
    assert not missed and np.max(np.abs(got - want)) < 1e-9
    assert [(r, s) for r, s, _ in out] == [(r, s) for r, s, _ in served]
    assert [rule for *_, rule in out][:1] == [DROPOUT] and DRIFT_OUT in [rule for *_, rule in out]
    assert_packed_as_served(tmp_path, deployed, ss, "test", frame, want, streams)


def test_an_export_before_cmon85_flags_the_drift_with_a_sensor_out(record, streams):
    """Arrays without ``solve``: the drift beyond the band with the dropout out flagged (``DRIFT``)
    at the served exclusion's row or before, and the pack cut there."""
    deployed, ss, frame = record
    row = next(r for r, _, why in _served_out(streams, frame) if why == "drift")
    _, _, missed = _mirror(without(ss, "solve"), frame, rows=row)       # (its first flag)
    assert missed and missed[0][1] == DRIFT and missed[0][0] <= row
    _, summary = conformance_pack(deployed, without(ss, "solve"), {"test": frame}, served=streams)
    assert summary["campaigns"][0]["rows"] < row
