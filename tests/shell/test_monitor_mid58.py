"""A stream on stdin started in the middle of a campaign, not said to continue one (lead58).

The monitor streams it from a reset: a model of changes from a campaign's first sample reads
them from the stream's first row and misses the warm-up before it.  It went by without a word;
now a first row whose temperature pattern is far from every training campaign's start (a share
of a training warm-up) is said, and a stream from the campaign's start is not."""

from __future__ import annotations

import io

import pandas as pd
import pytest

from thermocomp.shell.cli import main

pytestmark = pytest.mark.slow
SAID = "its first row does not look like a campaign's start"


@pytest.fixture(scope="module")
def lathe(tmp_path_factory):
    raw = tmp_path_factory.mktemp("mid58") / "raw"
    assert main(["simulate", "sim=swiss_lathe_door", "seed=5811", f"data.path={raw}",
                 "sim.generator.calibration_hours=16", "sim.generator.production_hours=6",
                 "track=false"]) == 0
    return raw


@pytest.mark.parametrize("first_row, said", [(0, False), (120, True)])
def test_a_stream_started_mid_campaign_is_said(lathe, tmp_path, monkeypatch, capsys, first_row,
                                               said):
    rows = pd.read_csv(lathe / "production.csv").iloc[first_row:]     # 2 h in: 120 rows of 60 s
    monkeypatch.setattr("sys.stdin", io.StringIO(rows.to_csv(index=False)))
    assert main(["monitor", f"data.path={lathe}", "sim=swiss_lathe_door", "monitor.input=-",
                 f"out={tmp_path}", "track=false", "plots=none"]) == 0
    err = capsys.readouterr().err
    assert (SAID in err) is said
    if said:
        assert "nearest training start (calibration)" in err and "monitor.continues" in err
