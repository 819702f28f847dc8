"""Two healthy sensors the served monitor kept out (mon88, issue 34; benchmarks/bench_mon88.py).

lr9171 (deploy87's long record, R1b continuing R1a): ``T_col_back``, which the others predict,
spikes twice (the generator's outliers); each spike's two jumps were re-referenced, and their
sum, the others' prediction noise and the true change over the outage, stayed in its reference:
its error 0.28 °C off its field after the first, past its half band after the second, out to
the record's end (1.73 h).  The rule that took back the reference before the jumps where the
field reads it nearer (benchmarks/mon88_rule.patch, ``_field_undoes``) mended it but failed its
bar on fresh records (replay RMSE up to +6.4 %); mon89's spike (``InstantFaults._spike_back``:
a return to the field on the reference before the jump ends a spike) brings it back at each
spike's end.

cr9031 (audit86b's climate room) with ``T_amb`` frozen from a third of each test campaign: in
C11 the healthy ``T_nc_cabinet`` (within its band) was taken as the culprit and the frozen
``T_amb`` out with it as its blind partner; with ``T_amb`` out no sensor predicts
``T_nc_cabinet``, and it never passed its return.  Now a partner out frozen by the rule for a
sensor no other predicts clears it (``Readmission._blind_for_frozen``).  Since mon97 (benchmarks/
bench_mon97.py) the room's ``T_amb``, whose readings dither over their resolution, is out for its
freeze once constant past ``blind_run``, before the cabinet is ever taken for it; the partner's
return is tested on the monitor as it was (:func:`undithered`: a reading that does not dither,
judged by the field's freeze rule alone)."""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.deploy.report import plain, stream_rows
from thermocomp.core.continuation import lead_ins
from thermocomp.shell.cli import main

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

LONG = ("sim=long_record", "seed=9171", "sim.generator.duration_days=3.0",
        "sim.generator.test_fraction=0.2")
ROOM = ("sim=climate_room", "seed=9031", "sim.generator.n_runs=12",
        "sim.generator.duration_h=[3.0,4.0]", "sim.generator.test_fraction=0.25")


def deployed_record(folder: Path, sim: tuple, overrides: tuple = ()):
    """``(deployed MLR, ds, test ids)`` of the record ``sim`` draws into ``folder``."""
    from _ccode import deployed_on

    assert main(["-q", "simulate", *sim, f"data.path={folder}", "track=false"]) == 0
    return deployed_on(folder, "mlr", overrides)


def undithered(deployed):
    """A copy of ``deployed`` whose monitor takes no reading for dithered (mon97): a predicted
    sensor frozen only where the field moved by its band, as for a noiseless logger's reading."""
    deployed = copy.deepcopy(deployed)
    deployed.monitor._dither_run[:] = np.inf
    return deployed


def frozen_amb(frame: pd.DataFrame) -> pd.DataFrame:
    """``T_amb`` held at its reading from a third of the campaign on (audit86b's fault)."""
    out = frame.copy()
    out.loc[len(out) // 3:, "T_amb"] = out.loc[len(out) // 3, "T_amb"]
    return out


@pytest.fixture(scope="module")
def long_record(tmp_path_factory):
    """``(deployed, R1b, its lead-in)`` of lr9171."""
    deployed, ds, test_ids = deployed_record(tmp_path_factory.mktemp("lr9171") / "data", LONG,
                                             ("data.reference=none",))
    (test,) = test_ids
    return (deployed, ds.campaigns[test].reset_index(drop=True),
            lead_ins(plain(deployed).compensator, ds, test_ids)[test])


@pytest.fixture(scope="module")
def room(tmp_path_factory):
    """``(deployed, C11)`` of cr9031."""
    deployed, ds, _ = deployed_record(tmp_path_factory.mktemp("cr9031") / "data", ROOM)
    return deployed, ds.campaigns["C11"].reset_index(drop=True)


def _moves(events: list, sensor: str) -> list[tuple[str, float]]:
    return [(e["to"], e["time"]) for e in events if e.get("sensor") == sensor]


def test_a_spiked_sensor_the_field_predicts_comes_back_after_each_spike(long_record):
    deployed, frame, lead = long_record
    mon = deployed.monitor
    period = float(np.median(np.diff(frame["time"])))
    got = stream_rows(deployed, frame, "R1b", lead_in=lead)
    moves = _moves(got.events, "T_col_back")
    outs = [t for to, t in moves if to == "excluded"]
    assert len(outs) == 2                      # the generator's two spikes on it
    # back within its calm window (and confirm) of the spike's end: a spike is 1-3 samples
    for t in outs:
        back = [u for to, u in moves if to == "ok" and u > t]
        assert back and back[0] - t <= (3 + mon.window + mon.confirm) * period, moves
    assert moves[-1][0] == "ok"                # in at R1b's end


def test_a_partner_frozen_out_clears_the_healthy_sensor_taken_for_it(room):
    deployed, drawn = room
    deployed = undithered(deployed)        # the premise: T_amb not out for its freeze first
    frame = frozen_amb(drawn)
    mon = deployed.monitor
    period = float(np.median(np.diff(frame["time"])))
    events = stream_rows(deployed, frame, "C11").events
    cabinet, amb = _moves(events, "T_nc_cabinet"), _moves(events, "T_amb")
    assert [to for to, _ in amb] == ["excluded"]              # the frozen one: out to the end
    out = [t for to, t in cabinet if to == "excluded"]
    assert out                                                # taken for T_amb's error ...
    back = [t for to, t in cabinet if to == "ok" and t > out[0]]
    assert back and back[0] - out[0] <= (mon.window + mon.confirm) * period, cabinet
    assert cabinet[-1][0] == "ok"                             # ... and back in


def test_the_frozen_ambient_goes_out_for_its_freeze_before_the_cabinet_is_taken_for_it(room):
    """(mon97) Its readings dither: out once constant past ``blind_run``, the healthy cabinet
    never out (before mon97: the cabinet out at C11's third + 10 samples, ``T_amb`` with it)."""
    deployed, drawn = room
    frame = frozen_amb(drawn)
    mon = deployed.monitor
    j = mon.names.index("T_amb")
    events = stream_rows(deployed, frame, "C11").events
    out = [e for e in events if e.get("sensor") and e["to"] == "excluded"]
    assert [e["sensor"] for e in out] == ["T_amb"] and out[0]["reason"].startswith("freeze:"), out
    onset = float(frame["time"].iloc[len(frame) // 3])
    period = float(np.median(np.diff(frame["time"])))
    assert out[0]["time"] <= onset + (mon._blind_run[j] + 1) * period
    assert mon.dithered[j]


def test_the_room_as_drawn_stays_quiet(room):
    """The control: C11 as drawn, nothing excluded (on main too)."""
    deployed, frame = room
    assert not [e for e in stream_rows(deployed, frame, "C11").events if e.get("sensor")]
