"""Two sensors' wires exchanged mid-stream, read as an exchange by served, the numpy mirror and
the compiled C alike (wires100, issue 34; benchmarks/bench_wires100.py); and (dep101) both
readings missing in one sample held as served (benchmarks/bench_dep101.py).  Before it, served read
the two steps as two offsets (each re-referenced, out, back on the other's dynamics: wires99's
pt9851 77.66 µm off the healthy corrections) and the C parted from served at the swap sample.

test_export_dep99b's eight-sensor machine (seven ``T_`` sensors warmed by two heats, ``T_u`` no
other predicts; MLR deployed adaptive, no fallback model), its last test campaign healthy, with
``T_a`` and ``T_f`` (3 °C apart there) exchanged from row ``SWAP`` on.  Fails on 9bbbb214: served
names no exchange and parts from its healthy corrections (and the mirror from served) after it."""

from __future__ import annotations

import numpy as np
import pytest

import test_export
from conftest import deployed_as_replay
from test_export import built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_export_dep99b import _machine, held_as_served
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space, watch
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.watch import DROPOUT, NOT_IN_CODE, REREFERENCED
from thermocomp.apps.deploy.report import stream_rows

SWAP, PAIR, BACK = 40, ["T_a", "T_f"], 10
WIRES_EXCHANGED = getattr(watch, "WIRES_EXCHANGED", -1)    # (9bbbb214: no such rule)


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR as replay deploys it, its system with the monitor, the healthy campaign)``."""
    deployed, ds, test_ids = deployed_as_replay(test_export._compose(
        f"data.path={_machine(tmp_path_factory.mktemp('wires100') / 'data')}", "track=false",
        "monitor.adaptive=true", "monitor.fallbacks=none"))
    return deployed, state_space(deployed, monitor=True), ds.campaigns[test_ids[-1]].reset_index(drop=True)


@pytest.fixture(scope="module")
def stream(served, tmp_path_factory):
    """The compiled C of ``served`` (``stream.c``), built once for the module's cases."""
    return built_stream(tmp_path_factory.mktemp("wires100c"), exported_files(served[0], "c"))


def _served(deployed, ss, frame):
    run = stream_rows(deployed, frame, "K06")
    times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
    moves = [(int(np.searchsorted(times, e["time"])), e["sensor"], e["to"])
             for e in run.events if e.get("sensor")]
    return corrections(ss, run.y), moves


def _swapped(frame):
    swapped = frame.copy()
    swapped.loc[SWAP:, PAIR] = frame.loc[SWAP:, PAIR[::-1]].to_numpy()
    assert abs(frame.loc[SWAP, PAIR[0]] - frame.loc[SWAP, PAIR[1]]) > 2.0
    return swapped


def test_served_reads_two_wires_exchanged_as_an_exchange(served):
    deployed, ss, frame = served
    healthy, none = _served(deployed, ss, frame)
    assert none == []
    want, moves = _served(deployed, ss, _swapped(frame))
    # an exchange named on both sensors at the swap row, nothing else; the healthy corrections
    assert moves == [(SWAP, "T_a", "exchanged"), (SWAP, "T_f", "exchanged")]   # 9bbbb214: jumps
    assert np.max(np.abs(want - healthy)) < 1e-9


@needs_cc
def test_the_mirror_and_the_compiled_c_read_them_exchanged_as_served(served, stream):
    deployed, ss, frame = served
    healthy, _ = _served(deployed, ss, frame)
    swapped = _swapped(frame)
    sim = Simulator(ss)
    sim.reset()
    U, t = swapped[ss.inputs].to_numpy(float), swapped["time"].to_numpy(float)
    mirror = []
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    for i in range(len(swapped)):
        mirror.append(sim.step(U[i], t[i]))
        w = sim.watch
        assert not w.flags & NOT_IN_CODE, (i, w.missed)
        said = (w.flags & REREFERENCED, w.rule, names[w.sensor] if w.sensor >= 0 else None)
        # 9bbbb214: the two jumps at the swap row (JUMP), their returns after
        assert said == ((REREFERENCED, WIRES_EXCHANGED, "T_a") if i == SWAP else (0, 0, None)), i
    assert np.max(np.abs(np.array(mirror) - healthy)) < 1e-9          # served's, every row
    got, said = _streamed(stream, swapped, ss.inputs)
    assert got.shape == healthy.shape and np.max(np.abs(got - healthy)) < 1e-9
    assert "not in the code" not in said


@needs_cc
def test_both_readings_missing_in_one_sample_held_by_the_mirror_and_the_c_as_served(served, stream):
    """(dep101) The drop: ``T_a`` and ``T_f`` both missing from row ``SWAP`` on.  Served takes
    both out and rebuilds them from the field; the mirror and the compiled C hold them so too
    (7676398c refused the sample and every one after it: ``MISSING_SECOND``)."""
    deployed, ss, frame = served
    dropped = frame.copy()
    dropped.loc[SWAP:, PAIR] = np.nan
    want, moves = _served(deployed, ss, dropped)
    assert [m for m in moves if m[0] == SWAP] == [(SWAP, "T_a", "excluded"), (SWAP, "T_f", "excluded")]
    held_as_served(deployed, ss, dropped, want, DROPOUT, None, at=SWAP, out=2, built=stream)


@needs_cc
def test_a_third_dropout_beside_the_pair_and_their_return_held_as_served(served, stream):
    """(dep103) The drop for ``BACK`` rows, the pair's readings then back, and ``T_b`` missing from
    ``SWAP`` + 5 on: a dropout beside two out.  Served takes ``T_b`` out as the third and the pair
    back later; the mirror and the compiled C hold them so too (4a21da2b refused ``T_b``'s row and
    every one after it: ``MISSING_SECOND``, the two-slot cap kept for a dropout; 4b70457f too)."""
    deployed, ss, frame = served
    dropped = frame.copy()
    dropped.loc[SWAP:SWAP + BACK - 1, PAIR] = np.nan
    dropped.loc[SWAP + 5:, "T_b"] = np.nan
    want, moves = _served(deployed, ss, dropped)
    assert (SWAP + 5, "T_b", "excluded") in moves
    assert {s for r, s, to in moves if to == "ok" and r >= SWAP + BACK} == set(PAIR)   # back
    held_as_served(deployed, ss, dropped, want, DROPOUT, None, at=SWAP + 5, out=3, built=stream)
