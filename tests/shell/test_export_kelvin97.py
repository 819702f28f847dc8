"""Every reading beyond its range at once in the exported C (kelvin97, issue 34: deployed as
scored): the logger's unit switched to kelvin mid-stream (every ``T_`` input +273.15).  The served
monitor excludes every sensor; nothing is left to rebuild the field from, so the model reads the
last field and the correction holds.  The C passed such a sample by its monitor (not in the code)
with the model reading the kelvin values: its correction followed them at the guard's rate limit
(tr9828: 134.8 -> 185.45 µm where the served held 115.2, benchmarks/bench_kelvin97.py).  Now the
numpy mirror and the compiled C read the last field too, as served, on every row (still flagged:
the sensors' return is not in the code).

On test_export's three-sensor record (MLR, deployed adaptive, test_export_cmon80's fixture).  The
unit case fails on f59b6361 (the C parts from the served correction from the change's row on);
the whole logger's dropout (every input missing) held the mirror's correction as served while the
C's ``tc_step`` refused the rows (``stream`` exit 2 at the first); (dep105b) now the mirror and the
C read the last field there, as served, and re-admit the sensors a window after the readings'
return: the C's stream passes it (fails on 7a8d6cf2: exit 2)."""

from __future__ import annotations

import numpy as np
import pytest

from test_export import built_stream, needs_cc
from test_export_cmon80 import HALF, _streamed, served  # noqa: F401 -- the fixture
from thermocomp.apps.deploy.export import Simulator, exported_files
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.report import stream_rows

KELVIN = 273.15


def _changed(frame, kind):
    out = frame.copy()
    temps = [c for c in out.columns if c.startswith("T_")]
    if kind == "kelvin":       # every temperature in kelvin from the middle row on
        out.loc[HALF:, temps] += KELVIN
    else:                      # the whole logger drops out: every input missing for five rows
        out.loc[HALF:HALF + 4, [c for c in out.columns if c != "time"]] = np.nan
    return out


@needs_cc
@pytest.mark.parametrize("kind", ["kelvin", "whole_dropout"])
def test_every_reading_out_holds_the_correction_as_served(served, tmp_path, kind):  # noqa: F811
    deployed, ss, campaign = served
    frame = _changed(campaign, kind)
    want = corrections(ss, stream_rows(deployed, frame, "K06").y)
    if kind == "kelvin":       # served: every sensor out, the correction held to the end
        events = stream_rows(deployed, frame, "K06").events
        assert {e["sensor"] for e in events if e.get("to") == "excluded"} == {"T_a", "T_b", "T_amb"}
        assert np.max(np.abs(want[HALF:] - want[HALF])) < 1e-12
    sim = Simulator(ss)
    sim.reset()
    U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    mirror = np.array([sim.step(U[i], t[i]) for i in range(len(frame))])
    assert np.max(np.abs(mirror - want)) < 1e-9                              # every row
    stream = built_stream(tmp_path, exported_files(deployed, "c"))
    got, said = _streamed(stream, frame, ss.inputs)
    assert got.shape == want.shape and np.max(np.abs(got - want)) < 1e-9      # every row
    if kind != "kelvin":       # (dep105b) held, then all three re-admitted together, as served
        back = [e["sensor"] for e in stream_rows(deployed, frame, "K06").events if e.get("to") == "ok"]
        assert back == ["T_a", "T_b", "T_amb"] and "not in the code" not in said
        assert "re-admitted" in said
        return
    # flagged: the sensors' return is the served monitor's alone
    assert "not in the code: a reading beyond its training range" in said
