"""A local clock's daylight saving change in a time column without a zone (lab77): the reader
names the zone to set, from the date and the local hour of the step (the zones whose clocks
change then), as the data contract decides: refused where the clock goes back (an ambiguous
hour), said where it jumps forward; a step on no zone's change date names none.  Before: 'e.g.
data.timezone=Europe/Berlin' whatever the date or the zone, and 'daylight saving time ending?'
for an hour set back in July.  The exported stream.c says the step back as the reader does."""

from __future__ import annotations

import io
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from conftest import FAST
from test_export import needs_cc
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.timestamps import dst_zones
from thermocomp.shell.cli import main

ROWS = 60


def local_log(path: Path, start_utc: str, zone: str, set_back_s: float = 0.0) -> Path:
    """Three temperatures and an error every 10 min on ``zone``'s wall clock (no offset written;
    ``set_back_s``: from row 31 on, the clock set back by hand)."""
    utc = pd.date_range(start_utc, periods=ROWS, freq="10min", tz="UTC")
    wall = utc.tz_convert(zone).tz_localize(None)
    wall = wall.where(np.arange(ROWS) < 31, wall - pd.Timedelta(seconds=set_back_s))
    rng = np.random.default_rng(7756)
    t = np.linspace(20, 25, ROWS) + rng.normal(0, 0.05, ROWS)
    pd.DataFrame({"time": wall.strftime("%Y-%m-%dT%H:%M:%S"), "T_a": t, "T_b": 0.5 * t + 10,
                  "T_c": 22 + np.sin(np.arange(ROWS) / 7), "E_X": 2 * t}).to_csv(path, index=False)
    return path


@pytest.mark.parametrize(("start", "zone", "says"), [
    ("2026-10-24 20:00", "Europe/Berlin", "daylight saving time ending on 2026-10-25 in "),
    # (every US zone goes back at 01:59 local: New York named first, Chicago among them)
    ("2026-11-01 02:00", "America/Chicago", "daylight saving time ending on 2026-11-01 in "),
])
def test_a_clock_set_back_at_a_dst_date_is_refused_naming_the_zone(tmp_path, start, zone, says):
    with pytest.raises(ContractError, match="the clock set back by an hour") as found:
        read_dataset(local_log(tmp_path / "log.csv", start, zone), {})
    said = str(found.value)
    assert says in said and ": set data.timezone to the one it was written in (e.g. " in said
    first = "Europe/Berlin" if zone == "Europe/Berlin" else "America/New_York"
    assert f"zones ({first}, " in said and f"(e.g. data.timezone={first})" in said
    assert ("Europe/" in said) == zone.startswith("Europe/")
    # (row 30 at 02:50 local, row 31 at 02:00: 29 and 24 periods after the first)
    assert zone in dst_zones(pd.read_csv(tmp_path / "log.csv")["time"][0], 29 * 600.0,
                             24 * 600.0)


def test_a_clock_set_back_on_no_dst_date_names_no_zone(tmp_path):
    with pytest.raises(ContractError) as found:
        read_dataset(local_log(tmp_path / "log.csv", "2026-07-14 20:00", "Europe/Berlin",
                               set_back_s=3000), {})
    assert ("the clock set back by an hour, at no zone's daylight saving time ending (a clock "
            "set by hand or by a time server? data.timezone does not read it)"
            ) in str(found.value)


def test_a_clock_jumping_forward_at_a_dst_date_is_said_naming_the_zone(tmp_path, caplog):
    path = local_log(tmp_path / "log.csv", "2026-03-28 20:00", "Europe/Berlin")
    ds, _ = read_dataset(path, {})
    assert len(ds.campaigns["log"]) == ROWS
    assert ("line 32 (data row 31): the clock jumps an hour forward, read as an hour without "
            "samples, daylight saving time beginning on 2026-03-29 in ") in caplog.text
    assert "(e.g. data.timezone=Europe/Berlin)" in caplog.text
    ds, _ = read_dataset(path, {"timezone": "Europe/Berlin"})      # (what it says reads it)
    np.testing.assert_allclose(np.diff(ds.campaigns["log"]["time"]), 600.0)


@needs_cc
def test_the_compiled_stream_says_a_clock_set_back_as_the_reader_does(tmp_path):
    train = local_log(tmp_path / "train.csv", "2026-03-10 20:00", "Europe/Berlin")
    assert main(["run", f"data.path={train}", "data.test_fraction=0.3", "model=arx", *FAST,
                 f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", f"data.path={train}", "data.test_fraction=0.3", "track=false",
                 "export.format=c", f"export.model={tmp_path / 'run' / 'model.pkl'}",
                 f"out={tmp_path / 'code'}"]) == 0
    code = tmp_path / "code"
    compiled(code)
    autumn = local_log(tmp_path / "autumn.csv", "2026-10-24 20:00", "Europe/Berlin")
    done = subprocess.run([str(code / "stream")], input=autumn.read_bytes(), capture_output=True)
    assert done.returncode == 0, done.stderr
    said = [ln for ln in done.stderr.decode().splitlines() if ln.startswith("stream: line 32:")]
    assert len(said) == 1 and ("is not after the last read (17400 s): the clock set back by an "
                               "hour, daylight saving time ending? this stream reads no "
                               "data.timezone") in said[0], done.stderr


def test_a_stream_on_stdin_says_a_clock_set_back_as_the_reader_does(tmp_path, monkeypatch,
                                                                     capsys):
    """``monitor.input=-`` (the served path's reader): before, nothing said; the time rule
    went on over the repeated hour."""
    train = local_log(tmp_path / "train.csv", "2026-03-10 20:00", "Europe/Berlin")
    autumn = local_log(tmp_path / "autumn.csv", "2026-10-24 20:00", "Europe/Berlin")
    monkeypatch.setattr("sys.stdin", io.StringIO(autumn.read_text()))
    assert main(["monitor", f"data.path={train}", "data.test_fraction=0.3", *FAST,
                 "monitor.input=-", f"out={tmp_path / 'piped'}"]) == 0
    assert ("<stdin>, column 'time', data row 31: the clock set back by an hour, daylight saving "
            "time ending on 2026-10-25 in ") in (said := capsys.readouterr().err), said
    assert "(e.g. data.timezone=Europe/Berlin)" in said


def test_a_served_block_set_back_says_what_its_client_can_do(tmp_path, caplog, capsys):
    """tidy77: a served block's clock set back said the reader's 'set data.timezone=...', which
    a served model does not read (its blocks are read on no zone), and named '<stdin>'.  It says
    the block's row and to send the time with its offset; the block sent so is read without a
    word."""
    import copy

    from test_export import _compose
    from thermocomp.apps.deploy.pyfunc import CompensatorModel
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    train = local_log(tmp_path / "train.csv", "2026-03-10 20:00", "Europe/Berlin")
    cfg = _compose(f"data.path={train}", "model=mlr", "track=false", "monitor.adaptive=false")
    ds, ids, _, _ = read_streamed(cfg, test=False)
    deployed = deployable_model(cfg, ds, ids, None, "serve.model")[0]
    block = pd.read_csv(local_log(tmp_path / "autumn.csv", "2026-10-24 20:00", "Europe/Berlin"))
    offset = block.assign(time=pd.DatetimeIndex(block["time"]).tz_localize(
        "Europe/Berlin", ambiguous="infer").strftime("%Y-%m-%dT%H:%M:%S%z"))

    def said(frame: pd.DataFrame) -> str:
        capsys.readouterr()
        caplog.clear()
        with caplog.at_level("WARNING"):
            CompensatorModel(copy.deepcopy(deployed)).predict(None, frame, {"reset": True})
        return caplog.text + capsys.readouterr().err

    text = said(block)
    assert ("column 'time', data row 31 of the block: the clock set back by an hour, daylight "
            "saving time ending on 2026-10-25 in ") in text, text
    assert ("a served model reads no data.timezone: send the time with its UTC offset or in UTC "
            "(Z) (e.g. 2026-10-25T02:00:00+01:00, Europe/Berlin's clock after the change)") in text
    assert "<stdin>" not in text and "set data.timezone" not in text
    assert "clock set back" not in said(offset)
