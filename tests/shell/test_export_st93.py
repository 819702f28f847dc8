"""The Structured Text block says when its sensors fault (st93, issue 34): an adaptive model's
``FB_ThermoComp`` outputs the monitor's detection the C checks without the POD (a reading not
measured, beyond the monitor's range, a jump), ``mon_flag`` / ``mon_rule`` / ``mon_sensor`` with
the C's codes, where before the ST held none of the monitor and computed on silently.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days), MLR deployed adaptive with
``data.reference=none``; its first 300 fed rows, healthy (no event of the served monitor or the
C's there), and with a fault planted at row 201 on the first monitored sensor the others predict
(benchmarks/bench_st93.py scores it on fresh records).  ci102h: 1100 rows and the fault at 1001
before; 200 healthy rows before the fault hold the same subject (the served event, the C's and the
block's flag at the fault's row), 100 rows after it as before."""

from __future__ import annotations

import numpy as np
import pytest

from test_export import TOLERANCE_UM, StructuredText
from test_export_cmon85 import _mirror
from test_export_cmon87 import long_record
from thermocomp.apps.deploy.export import exported_files
from thermocomp.apps.deploy.export.watch import DROPOUT, JUMP, OFF_RANGE, REASONS

SEED = 9132
ROWS, FAULT, LOST = 300, 200, 5         # rows fed, the fault's first (0-based), rows it lasts


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, ss, the fed rows, the ST block, the sensor faults are planted on)``."""
    deployed, ss, frame, *_ = long_record(tmp_path_factory, SEED)
    m = ss.monitor
    k = next(k for k, p in enumerate(m["predictable"]) if p and m["ported_out"][k])
    block = exported_files(deployed, "st")["compensator.st"]
    return deployed, ss, frame.iloc[:ROWS].reset_index(drop=True), block, k


def _st(block, ss, frame) -> tuple[np.ndarray, list, list]:
    """The block's corrections, its flags ``(row 1-based, sensor, rule)`` and its refusals."""
    fb = StructuredText(block)
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    got, flags, refused = [], [], []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        got.append(fb(u, t, i == 0))
        v = fb.vars
        if v["mon_flag"]:
            flags.append((i + 1, names[int(v["mon_sensor"])], int(v["mon_rule"])))
        refused.append(bool(v["refused"]))
    return np.array(got), flags, refused


def _served(deployed, frame) -> list[tuple[int, str, str]]:
    """The served monitor's exclusions ``(row 1-based, sensor, why)`` streaming ``frame``."""
    deployed.reset()
    X, t = frame[deployed.columns_].to_numpy(float), frame["time"].to_numpy(float)
    out = []
    for i in range(len(frame)):
        deployed._step(X[i], t[i])
        out += [(i + 1, e["sensor"], e["reason"].split(":")[0]) for e in deployed.last_events_
                if e.get("sensor") and e["to"] == "excluded"]
    return out


def test_a_healthy_record_is_never_flagged_and_the_block_is_the_c(record):
    deployed, ss, frame, block, _ = record
    got, flags, refused = _st(block, ss, frame)
    want, out, missed = _mirror(ss, frame, FAULT)      # (its first FAULT rows the cases' too)
    assert not out and not missed and not _served(deployed, frame)     # healthy, as both see it
    assert flags == [] and not any(refused)
    assert np.max(np.abs(got - want)) <= TOLERANCE_UM


def _planted(frame, ss, k, kind):
    m = ss.monitor
    name = ss.inputs[m["inputs"][k]]
    df = frame.copy()
    if kind == "jump":                  # (watch.planted's: twice its step limit, it stays)
        df.loc[FAULT:, name] += 2.0 * m["jump_lim"][k]
    elif kind == "spike":               # as much for LOST rows, then back
        df.loc[FAULT:FAULT + LOST - 1, name] += 2.0 * m["jump_lim"][k]
    elif kind == "dropout":
        df.loc[FAULT:FAULT + LOST - 1, name] = np.nan
    else:                               # beyond its range by its margin again, within U_LIMIT
        df.loc[FAULT:FAULT + LOST - 1, name] = 2.0 * m["hi_lim"][k] - m["hi_c"][k]
    return df, name


@pytest.mark.parametrize("kind, rule, why", [("jump", JUMP, "jump"), ("spike", JUMP, "jump"),
                                             ("dropout", DROPOUT, "dropout"),
                                             ("range", OFF_RANGE, "out of range")])
def test_a_planted_fault_raises_the_flag_at_the_served_event(record, kind, rule, why):
    deployed, ss, frame, block, k = record
    df, name = _planted(frame, ss, k, kind)
    got, flags, refused = _st(block, ss, df)
    row = FAULT + 1
    # the served monitor and the C exclude the sensor at the row, for the rule the block names
    assert _served(deployed, df)[0] == (row, name, why)
    assert _mirror(ss, df, FAULT)[1][0] == (row, name, rule)
    assert REASONS[rule].startswith(why)
    # a jump flagged once (its return, a spike's end, is the fault over: not flagged)
    lasting = 1 if kind in ("jump", "spike") else LOST
    assert flags == [(row + i, name, rule) for i in range(lasting)]
    if kind in ("jump", "spike"):      # re-referenced by its whole step: read on, nothing refused
        assert not any(refused)
    else:                   # the sensor not read: the sample refused, the last correction held
        assert [i + 1 for i, r in enumerate(refused) if r] == list(range(row, row + LOST))
        assert np.array_equal(got[row - 1:row + LOST - 1], np.repeat(got[row - 2:row - 1], LOST, 0))
