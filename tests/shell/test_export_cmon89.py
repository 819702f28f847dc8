"""An instant fault as the second sensor out in the exported C (cmon89, issue 34): with one
sensor out already, a dropout or a reading beyond its range of a sensor the others predict, and
the jump of a sensor no other predicts, are taken out as the second, as the served monitor does,
where before the code refused the row (``MISSING_SECOND``) or flagged it (``RANGE``, ``SECOND``)
and the conformance pack's planted copies were cut there (benchmarks/bench_cmon89.py).

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days, R1b the last fifth continuing
R1a), MLR deployed adaptive with ``data.reference=none``, with one spike planted in R1b: ``T_motor``
(no other sensor predicts it) -2.18 degC at row 430, three rows before the middle row from which
the pack plants its faults on ``T_head_left``; the simulator's own +2.41 degC outlier of
``T_zdrive`` (no other predicts it) at row 666 meets the planted freeze's drift exclusion.  R1b
streamed after R1a's last 864 rows (:data:`LEAD_ROWS`, ci102a; R1a whole before): the rows the
tests read are R1b's, the same on both."""

from __future__ import annotations

import subprocess

import pytest

from test_export import built_stream, needs_cc
from test_export_cmon85 import _mirror, without
from test_export_cmon87 import LEAD_ROWS, long_record
from thermocomp.apps.deploy.export import exported_files
from thermocomp.apps.deploy.export.pack import conformance_pack, fed
from thermocomp.apps.deploy.export.served import ServedStreams
from thermocomp.apps.deploy.export.watch import MISSING_SECOND, RANGE, SECOND, planted

SEED = 9132
SPIKE = ("T_motor", 430, -2.18)     # (sensor, R1b's row 1-based, degC)


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """lr9132 with its spike in R1b: ``(deployed, ss, R1b's lead-in rows, {R1b: frame}, leads)``."""
    deployed, ss, _, lead, tests, leads = long_record(tmp_path_factory, SEED, LEAD_ROWS)
    (test, campaign), = tests.items()
    sensor, row, size = SPIKE
    campaign = campaign.copy()
    campaign.loc[campaign.index[row - 1], sensor] += size
    return deployed, ss, lead, {test: campaign}, leads


@pytest.fixture(scope="module")
def streams(record):
    """The served streams of ``record``'s model, made once for the module's tests and packs."""
    return ServedStreams(record[0])


def _copies(summary) -> dict[str, dict]:
    """The pack's planted copies by fault (``jump``, ``freeze``, ``dropout``, ``range``)."""
    return {e["campaign"].split(".")[1]: e for e in summary["campaigns"] if "planted" in e}


@needs_cc
def test_an_instant_fault_as_the_second_out_is_what_the_code_does_as_served(record, streams,
                                                                           tmp_path):
    """Every planted copy kept whole (on main the dropout and the range copies were cut at the
    dropout's first row, the freeze copy at ``T_zdrive``'s jump), and the compiled C gives the
    served corrections on every row of every campaign of the pack."""
    deployed, ss, lead, tests, leads = record
    files, summary = conformance_pack(deployed, ss, tests, leads, served=streams)
    copies = _copies(summary)
    assert {"freeze", "dropout", "range"} <= set(copies)
    for fault, entry in copies.items():
        assert entry["cut"] is None, (fault, entry["cut"])
        assert entry["rows"] == entry["lead_in_rows"] + len(next(iter(tests.values()))), fault
    built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    script = subprocess.run(["sh", "check/check.sh"], cwd=tmp_path, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr


def test_an_export_before_cmon89_flags_the_second_instant_fault(record, streams):
    """Arrays without ``second_instant``: the copies' second outs flagged where served takes them
    out (a dropout refused, a range reading and a blind sensor's jump flagged), as before."""
    deployed, ss, lead, tests, leads = record
    old = without(ss, "second_instant")
    (test, campaign), = tests.items()
    half = len(campaign) // 2
    want = {"dropout": (lead + half + 1, MISSING_SECOND), "range": (lead + half + 1, RANGE),
            "freeze": (lead + 666, SECOND)}
    for cid, (df, _, _) in planted(ss, tests).items():
        fault = cid.split(".")[1]
        if fault in want:
            _, _, missed = _mirror(old, fed(df, leads.get(test)), lead, want[fault][0])  # (its flag)
            assert missed and missed[0] == want[fault], fault
            _, _, now = _mirror(ss, fed(df, leads.get(test)), lead)
            assert not now, (fault, now[:3])
    _, summary = conformance_pack(deployed, old, tests, leads, served=streams)
    assert {f: e["rows"] for f, e in _copies(summary).items() if f in want} == {
        f: row - 1 for f, (row, _) in want.items()}
