"""A stepped self-prediction error with two sensors already out in the exported C (step99, issue
34: deployed as scored; benchmarks/bench_step99.py, dl9902's ambient row 994).  Served's stepped
check takes a sensor the others predict out whatever the set out (here the third).  The C held a
stepped error (``STEP_OUT``) beside those out only where a place was free (the second): it
flagged ``SECOND`` and fed the stepped reading to the model.  Now it is held beside any number
out where the set solves, as dep99 holds a range reading and dep99b a jump: the numpy mirror and
the compiled C give served's corrections on every row.

test_export_dep99b's eight-sensor machine and faults (``T_e`` and ``T_f`` in kelvin, both out),
but ``T_c`` stepped +0.85 °C for good while they are out: below its jump limit (+0.95 is a jump),
its self-prediction error stepped past the alarm band.  Fails on 4b0de502 (the mirror flags
``SECOND`` at the step and parts from served by 0.175 µm on 45 rows)."""

from __future__ import annotations

import numpy as np
import pytest

from test_export import needs_cc
from test_export_dep99b import SPIKE, faulted, held_as_served
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.watch import STEP_OUT
from thermocomp.apps.deploy.report import stream_rows

STEP = 0.85


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """test_export_dep99b's :func:`faulted` with ``T_c`` stepped ``STEP`` for good at ``SPIKE``."""
    def step(frame):
        frame.loc[SPIKE:, "T_c"] += STEP
    return faulted(tmp_path_factory.mktemp("step99") / "data", step)


@needs_cc
def test_a_stepped_error_with_two_out_is_held_as_served(served, tmp_path):
    deployed, ss, frame = served
    run = stream_rows(deployed, frame, "K06")
    want = corrections(ss, run.y)
    times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
    moves = [(int(np.searchsorted(times, e["time"])), e["sensor"], e["to"], e["reason"])
             for e in run.events if e.get("sensor")]
    # served: the two out by range, then T_c out by its stepped error as the third
    assert [m for m in moves if m[:3] == (SPIKE, "T_c", "excluded")][0][3].startswith(
        "jump: self-prediction error stepped")
    assert {s for r, s, to, _ in moves if to == "excluded" and r < SPIKE} == {"T_e", "T_f"}
    assert not any(s in ("T_e", "T_f") and to == "ok" for r, s, to, _ in moves if r <= SPIKE)
    held_as_served(deployed, ss, frame, want, STEP_OUT, tmp_path)     # 4b0de502: SECOND at the step
