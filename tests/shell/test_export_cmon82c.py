"""A sensor no other predicts, excluded for explaining the others' errors, in the exported C
(cmon82c, issue 34): the code's sensor monitor excludes it as the served adaptive model's
monitor does, holds it at its last reading and re-admits it where the others pass their bands
with it in, instead of flagging it.

A four-sensor machine (MLR, deployed adaptive): ``T_a``, ``T_b``, ``T_c`` warm together, ``T_u``
(its own cycle, a little of it in ``T_a``) is a sensor no other predicts.  On the last test
campaign ``T_u`` ramps down ``RATE`` °C a row from the middle row for ``RAMP`` rows, then back
as fast, true after: its leak takes ``T_b`` out of its band, the served monitor excludes ``T_u``
as explaining it and re-admits it once back.  Without a fallback model (``monitor.fallbacks=
none``: the model reads the sensor held) the C flagged the exclusion before
(``TC_MON_NOT_IN_CODE``) and the pack was cut there; now the compiled code (gcc -Wall -Wextra
-Werror) gives the served corrections on every row and the pack, not cut, passes.  With one
(the default: the served correction is then the model fitted without it): test_export_cmon83."""

from __future__ import annotations

import dataclasses
import subprocess

import numpy as np
import pandas as pd
import pytest

import test_export
from conftest import deployed_as_replay
from test_export import CAMPAIGNS, built_stream, needs_cc
from test_export_cmon80 import _streamed
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.watch import (
    BLIND_OUT,
    EXCLUDED,
    NOT_IN_CODE,
    READMITTED,
)
from thermocomp.apps.deploy.report import stream_rows

ROWS, RATE, RAMP = 80, -0.8, 20


def _machine(root, rows: int = ROWS):
    """test_export's six campaigns, four sensors (module doc), one sample every 2 min."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(2)
    t = np.arange(rows) * 120.0
    for i, (cid, _) in enumerate(CAMPAIGNS):
        amb = 16 + 2.5 * i
        w1, w2 = (4 + i % 3) * (1 - np.exp(-t / 1500)), (2 + i % 2) * (1 - np.exp(-t / 4000))
        u = amb + 1.5 * np.sin(t / 900 + 1.7 * i)
        a = amb + w1 + 0.2 * (u - amb) + rng.normal(0, 0.05, rows)
        b = amb + 0.6 * w1 + w2 + rng.normal(0, 0.05, rows)
        pd.DataFrame({"time": t, "T_a": a, "T_b": b,
                      "T_c": amb + w2 + 0.3 * w1 + rng.normal(0, 0.05, rows),
                      "T_u": u + rng.normal(0, 0.05, rows),
                      "E_X": 3 * (a - a[0]) - 1.2 * (b - b[0]) + rng.normal(0, 0.2, rows),
                      "E_Z": 2 * (b - b[0]) + rng.normal(0, 0.2, rows),
                      "S_door": (np.arange(rows) % 10 < 2).astype(float)}).to_csv(
            root / f"{cid}.csv", index=False)
    pd.DataFrame([(c, f"{c}.csv", s, "") for c, s in CAMPAIGNS],
                 columns=["campaign", "file", "split", "notes"]).to_csv(root / "campaigns.csv",
                                                                        index=False)
    return root


def _deployed(folder, fallbacks: str, model: str = "mlr"):
    """Adaptive MLR (or ``model``) on :func:`_machine`'s record as replay deploys it
    (test_export's ``adaptive_mlr``), ``monitor.fallbacks=<fallbacks>``: ``(deployed, the ramped
    record)``."""
    cfg = test_export._compose(f"data.path={folder}", "track=false", "monitor.adaptive=true",
                               f"model={model}", f"monitor.fallbacks={fallbacks}")
    deployed, ds, test_ids = deployed_as_replay(cfg)
    frame = ds.campaigns[test_ids[-1]].reset_index(drop=True)
    half = ROWS // 2
    ramp = np.r_[np.arange(RAMP), RAMP - np.arange(RAMP), np.zeros(ROWS - half - 2 * RAMP)]
    frame.loc[half:, "T_u"] += RATE * ramp
    return deployed, frame


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    return _machine(tmp_path_factory.mktemp("cmon82c") / "data")


@pytest.fixture(scope="module")
def served(record):
    """``(adaptive MLR without a fallback model, its system with the monitor, the ramped
    record)``."""
    deployed, frame = _deployed(record, "none")
    return deployed, state_space(deployed, monitor=True), frame


def _served_moves(deployed, frame) -> list[tuple[int, str, str]]:
    times = frame["time"].to_numpy(float)
    return [(int(np.searchsorted(times, e["time"])) + 1, e["to"], e["reason"])
            for e in stream_rows(deployed, frame, "K06").events if e.get("sensor") == "T_u"]


def _code_moves(ss, frame) -> list[tuple[int, str]]:
    """The rows (1-based) the numpy mirror of the code excludes / re-admits ``T_u``; it must flag
    nothing it does not hold."""
    sim = Simulator(ss)
    sim.reset()
    out = []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        sim.step(u, t)
        assert not sim.watch.flags & NOT_IN_CODE, (i + 1, sim.watch.missed)
        if sim.watch.flags & EXCLUDED and sim.watch.rule == BLIND_OUT:
            out.append((i + 1, "excluded"))
        if sim.watch.flags & READMITTED:
            out.append((i + 1, "ok"))
    return out


@needs_cc
def test_a_sensor_no_other_predicts_is_excluded_and_held_by_the_code_as_served(served, tmp_path):
    deployed, ss, frame = served
    assert not ss.monitor["predictable"][ss.monitor["inputs"].index(ss.inputs.index("T_u"))]
    moves = _served_moves(deployed, frame)
    assert [to for _, to, _ in moves if to in ("excluded", "ok")] == ["excluded", "ok"], moves
    assert "explains the others'" in moves[0][2]
    assert _code_moves(ss, frame) == [(r, to) for r, to, _ in moves if to in ("excluded", "ok")]
    files, summary = conformance_pack(deployed, ss, {"K06": frame})
    assert (summary["campaigns"][0]["rows"], summary["campaigns"][0]["cut"]) == (len(frame), None)
    stream = built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    want = corrections(ss, stream_rows(deployed, frame, "K06").y)
    got, said = _streamed(stream, frame, ss.inputs)
    assert got.shape == want.shape and np.max(np.abs(got - want)) < 1e-9        # every row
    assert "held at its last reading" in said and "not in the code" not in said
    script = subprocess.run(["sh", "check/check.sh"], cwd=tmp_path, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr


def test_an_export_before_cmon82c_flags_the_exclusion_as_before(served):
    """Arrays without ``blind_out`` (an export before cmon82c): flagged at the served exclusion."""
    deployed, ss, frame = served
    row = [r for r, to, _ in _served_moves(deployed, frame) if to == "excluded"][0]
    old = {k: v for k, v in ss.monitor.items() if k != "blind_out"}
    sim = Simulator(dataclasses.replace(ss, monitor=old))
    sim.reset()
    flagged = []
    for u, t in zip(frame[ss.inputs].to_numpy(float), frame["time"]):
        sim.step(u, t)
        flagged.append(bool(sim.watch.flags & NOT_IN_CODE))
    assert flagged.index(True) == row - 1
