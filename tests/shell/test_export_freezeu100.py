"""A freeze of a sensor no other predicts, with two sensors already out, in the exported C
(freezeu100, issue 34: deployed as scored; benchmarks/bench_freezeu100.py).  Served's freeze check
takes a frozen sensor out whatever the set out and rebuilds one no other predicts as its last
reading.  The C held such a freeze (cmon84) with none out, but beside those out took only one the
others predict (``_second_kind``): it flagged ``SECOND`` and fed the frozen reading to the model.
Now the freeze of one no other predicts counts as its dropout's kind: held where the field is
rebuilt without it and the set solves, the numpy mirror and the compiled C give served's
corrections on every row.

test_export_dep99b's eight-sensor machine: ``T_e`` and ``T_f`` in kelvin rows 20-49 (both out),
``T_u`` (its own cycle, no other predicts it) held at its row-35 reading from 35: served's freeze
check takes it out at 46 as the third.  Fails on 063630e6 (the mirror flags ``SECOND`` at 46 and
parts from served by 0.177 µm, 16 rows)."""

from __future__ import annotations

import numpy as np

from test_export import needs_cc
from test_export_dep99b import K_ROWS, ONSET, SPIKE, faulted, held_as_served
from test_export_dep100 import KELVIN, KELVIN_LAST
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.watch import FREEZE
from thermocomp.apps.deploy.report import stream_rows

FROZEN_OUT = 46      # served's freeze check: T_u constant 12 samples, its blind run passed


def _freeze_u(frame):
    frame.loc[ONSET + K_ROWS:KELVIN_LAST, ["T_e", "T_f"]] += KELVIN      # (faulted: the first K_ROWS)
    frame.loc[SPIKE:, "T_u"] = frame.loc[SPIKE, "T_u"]


@needs_cc
def test_a_freeze_of_one_no_other_predicts_with_two_out_is_held_as_served(tmp_path):
    deployed, ss, frame = faulted(tmp_path / "data", _freeze_u)
    assert not deployed.monitor._predictable[list(deployed.monitor.names).index("T_u")]
    run = stream_rows(deployed, frame, "K06")
    want = corrections(ss, run.y)
    times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
    moves = [(int(np.searchsorted(times, e["time"])), e["sensor"], e["to"], e["reason"])
             for e in run.events if e.get("sensor")]
    # served: the two out by range, then T_u out by its freeze as the third
    assert [m for m in moves if m[:3] == (FROZEN_OUT, "T_u", "excluded")][0][3].startswith("freeze:")
    assert {s for r, s, to, _ in moves if to == "excluded" and r < FROZEN_OUT} == {"T_e", "T_f"}
    assert not any(s in ("T_e", "T_f") and to == "ok" for r, s, to, _ in moves if r <= FROZEN_OUT)
    held_as_served(deployed, ss, frame, want, FREEZE, tmp_path, at=FROZEN_OUT)  # 063630e6: SECOND
