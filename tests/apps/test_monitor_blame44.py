"""Who the monitor blames when a sensor that no other predicts drifts (a cut long_record, as in
test_deployed_as_scored44: its `record` fixture)."""

from __future__ import annotations

import json

from conftest import FAST, thermocomp
from test_deployed_as_scored44 import drifted, record  # noqa: F401  (record: the module's fixture)

UNSEEN = "T_table"     # its own mode: observable false, yet it weighs a little in the others' fits


def test_a_drift_no_other_sensor_predicts_is_not_blamed_on_a_healthy_sensor(record, tmp_path):  # noqa: F811
    """1 K/h on T_table from 10 samples into the test part.  Unseen by itself, it leaks onto
    the sensors that give it weight until one (T_xdrive) leaves its band; the culprit rule, blind
    to T_table, then excluded the healthy T_bed_right (which only hid T_xdrive's error) and kept
    the drifting one.  Now T_table, whose exclusion brings them back within band, is out and
    stays out while it drifts (calm alone had re-admitted it 10 samples later), and the
    correction is the model's fitted without it (sub71, monitor.fallbacks)."""
    cut = ("data.test_fraction=0.1", *FAST)
    thermocomp("run", f"data.path={record}", *cut, "model=mlr", f"out={tmp_path / 'run'}")
    drifting = drifted(record, tmp_path / "run", UNSEEN, tmp_path / "data")
    thermocomp("monitor", f"data.path={drifting}", *cut,
               f"monitor.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'mon'}")
    report = json.loads((tmp_path / "mon" / "monitor.json").read_text())
    assert report["sensors"][UNSEEN]["observable"] is False
    assert report["events"], "the drift leaks past a band before the record ends"
    # (sub71: out, its correction is the model fitted without it, the switch rate-limited once:
    # E_Z adaptive 19.61 -> 15.29 µm, fixed 20.57)
    assert [(e["sensor"], e["to"]) for e in report["events"] if e["sensor"]] == [(UNSEEN, "excluded")]
    assert {e["to"] for e in report["events"] if not e["sensor"]} <= {"rate_limited", "free"}
    assert report["targets"]["E_Z"]["rmse_adaptive"] < 0.8 * report["targets"]["E_Z"]["rmse_fixed"]
    reason = report["events"][0]["reason"]
    assert reason.startswith("drift: its reading explains the others'") and "no other sensor" in reason
    healthy = [s for s in report["sensors"] if s != UNSEEN]
    assert all(report["sensors"][s]["state_counts"]["excluded"] == 0 for s in healthy)
