"""A drift exclusion and a freeze with two sensors already out in the exported C (dep100, issue
34: deployed as scored; benchmarks/bench_dep100.py's ``machine``).  Served's drift judgement and
its freeze check take a sensor the others predict out whatever the set out (here the third).  The
C held a drift exclusion (``DRIFT_OUT``) or a freeze beside those out only where a place was free
(the second): it flagged ``SECOND`` and fed the reading to the model.  Now both are held beside
any number out where the set solves, as a range reading (dep99), a jump (dep99b) and a stepped
error (step99): the numpy mirror and the compiled C give served's corrections on every row.

test_export_dep99b's eight-sensor machine (``T_e`` and ``T_f`` in kelvin, both out): ``T_d``
+0.85 °C for good from row 35 (below its jump limit and its stepped check: served's drift
judgement takes it out at 36), and ``T_a`` held at its row-35 reading while ``T_e`` / ``T_f`` stay
in kelvin to row 49 (served's freeze check takes it out at 46).  Fails on 9bbbb214 (the mirror
flags ``SECOND`` at 36 and parts from served by 1.37 µm; at 46, 0.94 µm)."""

from __future__ import annotations

import numpy as np
import pytest

from test_export import needs_cc
from test_export_dep99b import K_ROWS, ONSET, SPIKE, faulted, held_as_served
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.watch import DRIFT_OUT, FREEZE
from thermocomp.apps.deploy.report import stream_rows

KELVIN, DRIFT_C, KELVIN_LAST = 273.15, 0.85, 49


@pytest.fixture(scope="module")
def machine(tmp_path_factory):
    """test_export_dep99b's :func:`faulted` (``T_e`` / ``T_f`` in kelvin), nothing else yet."""
    return faulted(tmp_path_factory.mktemp("dep100") / "data", lambda frame: None)


def _drift(frame):
    frame.loc[SPIKE:, "T_d"] += DRIFT_C


def _freeze(frame):
    frame.loc[ONSET + K_ROWS:KELVIN_LAST, ["T_e", "T_f"]] += KELVIN
    frame.loc[SPIKE:, "T_a"] = frame.loc[SPIKE, "T_a"]


@needs_cc
@pytest.mark.parametrize("fault, sensor, row, rule, why", [
    (_drift, "T_d", SPIKE + 1, DRIFT_OUT, "drift: self-prediction error"),
    (_freeze, "T_a", 46, FREEZE, "freeze:")], ids=["drift", "freeze"])
def test_a_drift_or_a_freeze_with_two_out_is_held_as_served(machine, tmp_path, fault, sensor, row,
                                                            rule, why):
    deployed, ss, base = machine
    frame = base.copy()
    fault(frame)
    run = stream_rows(deployed, frame, "K06")
    want = corrections(ss, run.y)
    times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
    moves = [(int(np.searchsorted(times, e["time"])), e["sensor"], e["to"], e["reason"])
             for e in run.events if e.get("sensor")]
    # served: the two out by range, then the third out by its drift or its freeze at row
    assert [m for m in moves if m[:3] == (row, sensor, "excluded")][0][3].startswith(why)
    assert {s for r, s, to, _ in moves if to == "excluded" and r < row} == {"T_e", "T_f"}
    assert not any(s in ("T_e", "T_f") and to == "ok" for r, s, to, _ in moves if r <= row)
    held_as_served(deployed, ss, frame, want, rule, tmp_path, at=row)   # 9bbbb214: SECOND at row
