"""The exported C holds the warned air of a one-campaign training (quiet94c, issue 34;
benchmarks/bench_quiet94c.py): the served monitor fitted on ONE campaign warns its ambient
sensors' drift and never excludes them for it (quiet94), and the export now writes that flag
(``warn_only``, the C's ``MON_WARN_ONLY``), so that the C's drift rule leaves the air's error
out of its evidence as served.  Before, the C excluded a healthy ``T_amb`` where the served
monitor did not, and the deployed corrections parted from the scored ones.

bench_quiet93's seed 9559 (``simulate`` 3 campaigns of 4-5 h at 300 s, the longest one the lab's
one-file record, cut by ``data.test_fraction=0.25``): main's drift rule excludes its healthy
``T_amb`` in the test part (quiet93's trace)."""

from __future__ import annotations

import dataclasses
import subprocess

import numpy as np
import pandas as pd
import pytest

from test_export import built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_export_cmon85 import _mirror
from test_export_cmon87 import deployed_mlr
from thermocomp.apps.deploy.export import exported_files, not_in_code
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.report import stream_rows

SEED = 9559


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """:func:`test_export_cmon87.deployed_mlr`'s tuple of the one-campaign swiss record."""
    from thermocomp.shell.cli import main

    folder = tmp_path_factory.mktemp(f"swiss{SEED}")
    assert main(["-q", "simulate", f"seed={SEED}", f"data.path={folder / 'sim'}", "track=false",
                 "sim.generator.n_campaigns=3", "sim.generator.duration_h=[4.0,5.0]"]) == 0
    index = pd.read_csv(folder / "sim" / "campaigns.csv")
    pd.read_csv(folder / "sim" / index.loc[index["duration_h"].idxmax(), "file"]).to_csv(
        folder / "record.csv", index=False)
    return deployed_mlr(f"data.path={folder / 'record.csv'}", "data.test_fraction=0.25")


def test_one_campaign_exports_the_air_as_warned_and_no_longer_names_it(record):
    deployed, ss, *_ = record
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    assert [c for c, w in zip(names, ss.monitor["warn_only"]) if w] == ["T_amb"]
    assert not any("a drift of" in left for left in not_in_code(deployed, "c"))


@needs_cc
def test_the_compiled_c_follows_the_served_monitor_on_the_healthy_air(record, tmp_path):
    deployed, ss, frame, _, tests, leads = record
    (test, _), = tests.items()
    want = corrections(ss, stream_rows(deployed, frame, test).y)
    served = stream_rows(deployed, frame, test).events
    assert not [e for e in served if e["to"] == "excluded"]          # served: the air kept in
    got, out, missed = _mirror(ss, frame)
    assert not out and not missed and np.max(np.abs(got - want)) < 1e-9
    files, summary = conformance_pack(deployed, ss, tests, leads)
    assert all(e["cut"] is None for e in summary["campaigns"])
    stream = built_stream(tmp_path, {**exported_files(deployed, "c"), **files})
    c, said = _streamed(stream, frame, ss.inputs)
    assert c.shape == want.shape and np.max(np.abs(c - want)) < 1e-9        # every row
    assert "not in the code" not in said
    script = subprocess.run(["sh", "check/check.sh"], cwd=tmp_path, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr


def test_an_export_before_the_flag_excludes_the_air_and_parts(record):
    """Arrays without ``warn_only`` (an export before quiet94c): main's drift rule takes the
    healthy air out and the code's corrections part from the served ones."""
    deployed, ss, frame, _, tests, _ = record
    (test, _), = tests.items()
    old = dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items() if k != "warn_only"})
    got, out, _ = _mirror(old, frame)
    assert [name for _, name, _ in out] == ["T_amb"], out
    want = corrections(ss, stream_rows(deployed, frame, test).y)
    assert np.abs(got - want).max() > 1e-3
