"""``monitor monitor.input=- monitor.continues=<run>`` with a logger's ISO 8601 timestamps: the
gap between the run's last row and the stream's first is said as for a time in seconds
(smallmends58 said it on one clock of seconds only: the stream's timestamps were counted from
its own first, whose instant was not kept)."""

from __future__ import annotations

import io

import numpy as np
import pandas as pd
import pytest

from conftest import FAST
from test_monitor_lab57 import ROLES, _run
from thermocomp.shell.cli import main

PERIOD = 60.0
STARTS = ("2026-11-30T06:00:00", "2026-12-01T06:00:00")


@pytest.fixture(scope="module")
def stamped(tmp_path_factory):
    """``messung.csv``: two runs (the second held out) timed by the logger's clock, ``Zeit``."""
    rng = np.random.default_rng(5911)
    runs = []
    for k, (start, rows) in enumerate(zip(STARTS, (240, 180))):
        run = _run(rng, rows)
        seconds = run.pop("Zeit [s]")
        stamps = pd.Timestamp(start) + pd.to_timedelta(seconds, unit="s")
        runs.append(run.assign(Lauf=k + 1).assign(Zeit=stamps.dt.strftime("%Y-%m-%dT%H:%M:%S")))
    root = tmp_path_factory.mktemp("isogap")
    pd.concat(runs)[["Lauf", "Zeit", *runs[0].columns[:-2]]].to_csv(
        root / "messung.csv", sep=";", decimal=",", index=False)
    return root / "messung.csv"


@pytest.mark.parametrize("after, said", [(85, True), (1, False)])
def test_an_iso_stamped_stream_said_to_continue_a_run_says_the_gap(
        stamped, tmp_path, monkeypatch, capsys, after, said):
    """The stream's first stamp 85 periods after run 1's last (84 rows missing): said, as a
    stream in seconds on run 1's clock is; right after its last row: nothing said."""
    whole = pd.read_csv(stamped, sep=";", decimal=",")
    run1 = whole[whole["Lauf"] == 1].drop(columns="Lauf")
    end = pd.Timestamp(run1["Zeit"].iloc[-1])
    rows = pd.concat([run1.iloc[-1:]] * 30, ignore_index=True)     # the machine as run 1 left it
    rows["Zeit"] = [(end + pd.Timedelta(seconds=(after + k) * PERIOD)).isoformat()
                    for k in range(len(rows))]
    monkeypatch.setattr("sys.stdin", io.StringIO(rows.to_csv(sep=";", decimal=",", index=False)))
    assert main(["monitor", f"data.path={stamped}", f"out={tmp_path / 'o'}", *ROLES, *FAST,
                 "data.reference=none", "monitor.input=-", "monitor.continues=Lauf_1"]) == 0
    err = capsys.readouterr().err
    assert ("after Lauf_1's last" in err) is said, err
    if said:
        assert f"is {after - 1} sample(s) ({(after - 1) * PERIOD / 60:.3g} min) after" in err
