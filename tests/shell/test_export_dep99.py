"""A logger card of several sensors beyond range in the exported C (dep99, issue 34: deployed as
scored; benchmarks/bench_dep99.py).  Three ``T_`` inputs read in kelvin for ``K_ROWS`` samples,
then in °C again: the served monitor takes the three out at once (each read as missing, no cap
on the sensors out), the model reading the one no other predicts held at its last reading in and
the others rebuilt by the POD from the sensor left in, and re-admits them together a window after
the return.  The C held at most two out and passed such a sample by its monitor (not in the
code), the model reading the kelvin values.  Now its monitor holds an out set of any size: the
numpy mirror and the compiled C give served's corrections on every row, nothing flagged.

test_export_unit_back98's four-sensor machine (test_export_cmon82c's: ``T_u`` no other predicts;
no fallback model), its last test campaign.  Fails on 4fafc59a (the C passes the card's samples
by, flagged, and parts from served by tens of µm)."""

from __future__ import annotations

import numpy as np

from test_export import built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_export_unit_back98 import K_ROWS, KELVIN, ONSET, served  # noqa: F401 -- the fixture
from thermocomp.apps.deploy.export import Simulator, exported_files
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.report import stream_rows

CARD = ["T_a", "T_b", "T_u"]


@needs_cc
def test_a_card_of_three_beyond_range_is_held_out_as_served(served, tmp_path):  # noqa: F811
    deployed, ss, campaign = served
    frame = campaign.copy()
    frame.loc[ONSET:ONSET + K_ROWS - 1, CARD] += KELVIN
    run = stream_rows(deployed, frame, "K06")
    want = corrections(ss, run.y)
    out = {e["sensor"] for e in run.events if e.get("to") == "excluded"}
    assert out == set(CARD)                   # served: the three out at once, no fallback
    assert not any(e.get("to") == "excluded" and e["sensor"] not in CARD for e in run.events)
    sim = Simulator(ss)
    sim.reset()
    U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    mirror, outs = [], set()
    for i in range(len(frame)):
        mirror.append(sim.step(U[i], t[i]))
        outs.add(tuple(sorted(ss.inputs[k] for k in sim.watch.idx[~sim.watch._active()])))
    assert np.max(np.abs(np.array(mirror) - want)) < 1e-9                    # every row
    assert max(map(len, outs)) == len(CARD) and tuple(sorted(CARD)) in outs   # the set out
    stream = built_stream(tmp_path, exported_files(deployed, "c"))
    got, said = _streamed(stream, frame, ss.inputs)
    assert got.shape == want.shape and np.max(np.abs(got - want)) < 1e-9      # every row
    assert "not in the code" not in said
    assert f"line {ONSET + 2}: monitor: T_a: out of range: read as missing, excluded" in said
