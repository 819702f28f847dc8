"""A dropout or a freeze of a sensor no other predicts in the exported C (cmon84, issue 34): the
code's monitor excludes it as the served one does, holds it at its last reading, serves its
fallback model while it is out (after a dropout, the model again once it reads: its held reading)
and re-admits it after a calm window, where before it refused the sample (``MISSING_BLIND``) or
flagged the freeze (``BLIND``) and the pack was cut there: of the rules the code did not hold,
the two that cut the most pack rows (benchmarks/bench_cmon84.py).

test_export_cmon82c's machine (``T_u`` no other predicts), its last test campaign with ``T_u``
missing for ``LOST`` rows from the middle row, or held at its reading there to the end, deployed with its
fallback model (the default) and without one."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from covering import covering
from test_export import needs_cc
from test_export_cmon80 import assert_packed_as_served
from test_export_cmon82c import RAMP, RATE, ROWS, _deployed, _machine, _served_moves
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.watch import (
    BLIND,
    DROPOUT,
    EXCLUDED,
    FREEZE,
    MISSING_BLIND,
    NOT_IN_CODE,
)
from thermocomp.apps.deploy.report import stream_rows

# rows lost: a dropout, then read again; a freeze to the campaign's end (its return would be a
# jump while out, which the served return may undo: not in the code)
LOST = {"dropout": 6, "freeze": ROWS - ROWS // 2}


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    return _machine(tmp_path_factory.mktemp("cmon84") / "data")


@pytest.fixture(scope="module")
def deployments(record):
    """``_deployed(record, fallbacks)``, made once per ``fallbacks`` for the module's tests, which
    read it (ci104b: five fits of two models before); its frame copied by :func:`_lost`."""
    made: dict = {}

    def deployed(fallbacks: str):
        if fallbacks not in made:
            made[fallbacks] = _deployed(record, fallbacks)
        return made[fallbacks]
    return deployed


def _lost(frame, kind: str = "dropout"):
    """The record as simulated (test_export_cmon82c's ramp undone), ``T_u`` missing (or held at
    its reading there: a freeze) ``LOST`` rows from the middle row."""
    out = frame.copy()
    half = ROWS // 2
    out.loc[half:half + 2 * RAMP - 1, "T_u"] -= RATE * np.r_[np.arange(RAMP), RAMP - np.arange(RAMP)]
    out.loc[half:half + LOST[kind] - 1, "T_u"] = np.nan if kind == "dropout" else out.loc[half, "T_u"]
    return out


def _mirror(ss, frame):
    """Per row the numpy mirror's correction, the law set it serves, whether it refused the
    sample and the rule not in the code it flagged (0: none); the rows it excluded ``T_u``."""
    sim = Simulator(ss)
    sim.reset()
    got, sets, refused, missed, out = [], [], [], [], []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        got.append(sim.step(u, t))
        sets.append(sim.serving)
        refused.append(sim.refused)
        missed.append(sim.watch.missed if sim.watch.flags & NOT_IN_CODE else 0)
        if sim.watch.flags & EXCLUDED and sim.watch.rule in (DROPOUT, FREEZE):
            out.append(i + 1)
    return np.array(got), sets, refused, missed, out


KINDS, FALLBACKS = ("dropout", "freeze"), ("unobservable", "none")


@needs_cc
@pytest.mark.parametrize("fallbacks, kind", covering(
    "the same hold-out under the other fallbacks", fallbacks=FALLBACKS, kind=KINDS))
def test_a_sensor_no_other_predicts_is_held_out_by_the_code_as_served(deployments, tmp_path,
                                                                      fallbacks, kind):
    deployed, frame = deployments(fallbacks)
    frame = _lost(frame, kind)
    ss = state_space(deployed, monitor=True)
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index("T_u")
    assert not ss.monitor["predictable"][k]
    moves = [(r, to) for r, to, _ in _served_moves(deployed, frame) if to in ("excluded", "ok")]
    assert [to for _, to in moves] == ["excluded", "ok"][:2 if kind == "dropout" else 1], moves
    gone, back = moves[0][0], moves[-1][0] if kind == "dropout" else len(frame) + 1
    assert ROWS // 2 < gone <= ROWS // 2 + LOST[kind] < back
    want = corrections(ss, stream_rows(deployed, frame, "K06").y)
    got, sets, refused, missed, out = _mirror(ss, frame)
    assert out == [gone] and not any(refused) and not any(missed)
    assert np.max(np.abs(got - want)) < 1e-9
    # the fallback model while it is out (after a dropout, the model on its held reading once it
    # reads again)
    fell = int(fallbacks == "unobservable")
    until = ROWS // 2 + LOST[kind] + 1 if kind == "dropout" else back
    assert sets == [0] * (gone - 1) + [fell] * (until - gone) + [0] * (len(frame) - until + 1)
    assert_packed_as_served(tmp_path, deployed, ss, "K06", frame, want)


def test_an_export_before_cmon84_refuses_the_missing_reading_and_flags_the_freeze(deployments):
    """Arrays without ``blind_drop``: the first missing reading refused (``MISSING_BLIND``), the
    freeze flagged (``BLIND``) where the served monitor excludes it; the pack cut there."""
    deployed, frame = deployments("unobservable")
    ss = state_space(deployed, monitor=True)
    old = dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items() if k != "blind_drop"})
    for kind, rule in (("dropout", MISSING_BLIND), ("freeze", BLIND)):
        lost = _lost(frame, kind)
        row = _served_moves(deployed, lost)[0][0]
        _, _, refused, missed, out = _mirror(old, lost)
        assert not out and missed.index(rule) + 1 == row
        assert refused.index(True) + 1 == row if kind == "dropout" else not any(refused)
        _, summary = conformance_pack(deployed, old, {"K06": lost})
        assert summary["campaigns"][0]["rows"] <= row - (kind == "dropout")
