"""A spiking sensor no other predicts in the exported C (cmon87, issue 34): the code's monitor holds
it out for a jump as the served monitor does (re-referenced, held at its last reading, its
fallback model served, back after a calm window with its jumps undone where the reading
returned), where before it flagged ``BLIND``, passed the spike into the correction and the pack
was cut there (benchmarks/bench_cmon87.py).

bench_audit86b's lr9032 (``thermocomp simulate sim=long_record``, seed 9032, 3 days, R1b the last
fifth continuing R1a), MLR deployed adaptive with ``data.reference=none``: the simulator's own
one-sample spike on a sensor no other predicts in R1b, which R1b is streamed after R1a's last
864 rows (:data:`LEAD_ROWS`, ci102a; R1a whole before): the served monitor takes ``T_table`` out
at R1b's row 397 and back at 408, the same rows as after R1a whole."""

from __future__ import annotations

import subprocess

import numpy as np
import pytest

from conftest import copied_once, deployed_as_replay
from test_export import _compose, built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_export_cmon85 import _mirror, without
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections, fed
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import BLIND, JUMP
from thermocomp.apps.deploy.report import plain
from thermocomp.core.continuation import lead_ins

SEED = 9032
LEAD_ROWS = 864     # R1b's lead-in: its last 864 rows (R1b's length), not R1a's 3457 (ci102a)


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    return long_record(tmp_path_factory, SEED, LEAD_ROWS)


@pytest.fixture(scope="module")
def streams(record):
    """The served streams of ``record``'s model, made once for the module's tests and packs."""
    return ServedStreams(record[0])


def long_record(tmp_path_factory, seed: int, lead_rows: int | None = None):
    """``(deployed, its system with the monitor, R1b after its lead-in, the lead-in's rows,
    R1b, the lead-ins by campaign)`` of the long record ``seed``.  ``lead_rows``: R1b's lead-in
    cut to its last rows (ci102a: R1a's 3457 rows are 80 % of a module's streaming, streamed
    before the fault the test is about; the served stream, the mirror, the pack and the C all
    start from the cut lead-in's first row), else R1a whole.

    Simulated and fitted once per seed for a worker's tests, each caller given a deep copy
    (scopec: lr9132 was simulated and fitted by 12 modules' fixtures, lr9032 by two; the same
    seed and words make the same record and fit, and a copy of its own lets a module change it)."""
    return _record(*_simulated_mlr(tmp_path_factory, seed), lead_rows)


@copied_once
def _simulated_mlr(tmp_path_factory, seed: int) -> tuple:
    """:func:`_fitted_mlr`'s tuple of the long record ``seed``, simulated."""
    from thermocomp.shell.cli import main

    data = tmp_path_factory.mktemp(f"lr{seed}") / "data"
    assert main(["-q", "simulate", f"seed={seed}", f"data.path={data}", "track=false",
                 "sim=long_record", "sim.generator.duration_days=3.0",
                 "sim.generator.test_fraction=0.2"]) == 0
    return _fitted_mlr(f"data.path={data}", "data.reference=none")


def deployed_mlr(*words: str, lead_rows: int | None = None):
    """MLR run with ``words`` and deployed as ``replay`` deploys it: ``(deployed, its system with
    the monitor, the first test campaign after its lead-in, the lead-in's rows, that campaign by
    its name, the lead-ins by campaign)`` (quiet94c: a one-file record too); ``lead_rows``: each
    lead-in's last rows only (:func:`long_record`)."""
    return _record(*_fitted_mlr(*words), lead_rows)


def _fitted_mlr(*words: str) -> tuple:
    """``(deployed, its system with the monitor, the first test campaign's id, the dataset's
    campaigns, the lead-ins by campaign)`` of MLR run with ``words``."""
    cfg = _compose(*words, "track=false", "model=mlr")
    deployed, ds, test_ids = deployed_as_replay(cfg)
    leads = lead_ins(plain(deployed).compensator, ds, test_ids)
    return deployed, state_space(deployed, monitor=True), test_ids[0], ds.campaigns, leads


def _record(deployed, ss, test, campaigns, leads, lead_rows: int | None) -> tuple:
    """:func:`deployed_mlr`'s tuple of :func:`_fitted_mlr`'s, the lead-ins cut to ``lead_rows``."""
    if lead_rows is not None:
        leads = last_rows(leads, lead_rows)
    frame = fed(campaigns[test], leads.get(test))
    return deployed, ss, frame, len(frame) - len(campaigns[test]), {test: campaigns[test]}, leads


def last_rows(leads: dict, rows: int = LEAD_ROWS) -> dict:
    """Each lead-in of ``leads`` (by campaign) cut to its last ``rows`` (ci102a)."""
    return {c: lead.iloc[-rows:] for c, lead in leads.items()}


def _served_spike(streams, ss, tests, leads, lead) -> tuple[int, int, str]:
    """The served exclusion of a sensor no other predicts for a jump: ``(row, its return's row,
    sensor)``, 1-based in the fed frame (R1b after ``lead`` rows); its jumps undone on its
    return."""
    (test, campaign), = tests.items()
    times = campaign["time"].to_numpy(float) - campaign["time"].iloc[0]
    blind = {ss.inputs[i] for i, p in zip(ss.monitor["inputs"], ss.monitor["predictable"]) if not p}
    events = [e for e in streams.rows(campaign, test, lead_in=leads[test]).events
              if e.get("sensor") in blind]
    out = next(e for e in events if e["to"] == "excluded" and e["reason"].startswith("jump"))
    back = next(e for e in events if e["to"] == "ok" and e["sensor"] == out["sensor"]
                and e["time"] > out["time"])
    assert "undone" in back["reason"]
    row = lambda t: lead + int(np.searchsorted(times, t)) + 1      # noqa: E731
    return row(out["time"]), row(back["time"]), out["sensor"]


def held_as_served(record, folder, streams: ServedStreams | None = None, each=None
                   ) -> tuple[list, str, dict]:
    """The mirror and the compiled C of ``record`` equal to the served corrections on every row,
    nothing flagged, R1b's pack entry whole and its check passing (in ``folder``): ``(the
    mirror's exclusions (row, sensor, rule), the stream's stderr, the pack's summary)``.
    ``streams``: the served streams of ``record``'s model made so far (else new ones); ``each``:
    :func:`_mirror`'s, a test's own reading of the mirror's pass."""
    deployed, ss, frame, lead, tests, leads = record
    streams = ServedStreams(deployed) if streams is None else streams
    # keyed on the record's own campaign id, as its module's other tests read it (ci108b: not a
    # second stream of the same rows under "R1b"; the id names events only, never ``y``)
    want = corrections(ss, streams.rows(frame, next(iter(tests))).y)
    got, out, missed = _mirror(ss, frame, each=each)
    assert not missed and np.max(np.abs(got - want)) < 1e-9
    files, summary = conformance_pack(deployed, ss, tests, leads, served=streams)
    entry = summary["campaigns"][0]
    assert (entry["rows"], entry["cut"]) == (len(frame), None)
    stream = built_stream(folder, {**exported_files(deployed, "c"), **files})
    c, said = _streamed(stream, frame, ss.inputs)
    assert c.shape == want.shape and np.max(np.abs(c - want)) < 1e-9        # every row
    assert "not in the code" not in said
    script = subprocess.run(["sh", "check/check.sh"], cwd=folder, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr
    return out, said, summary


@needs_cc
def test_a_spiking_sensor_no_other_predicts_is_held_by_the_code_as_served(record, streams,
                                                                           tmp_path):
    deployed, ss, frame, lead, tests, leads = record
    row, back, sensor = _served_spike(streams, ss, tests, leads, lead)
    out, _, summary = held_as_served(record, tmp_path, streams)
    assert (row, sensor, JUMP) in out
    assert all(e["cut"] is None for e in summary["campaigns"])


def test_an_export_before_cmon87_flags_the_spike(record, streams):
    """Arrays without ``blind_jump``: the jump flagged (``BLIND``) at the served exclusion's row,
    the correction parting from the served one while the sensor is out, and the pack cut there."""
    deployed, ss, frame, lead, tests, leads = record
    row, back, _ = _served_spike(streams, ss, tests, leads, lead)
    old = without(ss, "blind_jump")
    got, _, missed = _mirror(old, frame)
    assert missed and missed[0] == (row, BLIND)
    want = corrections(ss, streams.rows(frame, "R1b").y)
    parted = np.flatnonzero(np.abs(got - want).max(axis=1) > 1e-9) + 1
    assert parted.min() == row and parted.max() < back
    _, summary = conformance_pack(deployed, old, tests, leads, served=streams)
    assert summary["campaigns"][0]["rows"] == row - 1
