"""What a stranger met on a trunnion mill's lab files (stranger63, ``bench_stranger63.py``);
each test fails on the code before its mend."""

from __future__ import annotations

import io

import numpy as np
import pandas as pd

from test_export import _compose, needs_cc
from test_lab_export53 import _clock_file, _streamed
from test_lab_stream52 import DATA, compiled
from thermocomp.apps.deploy.streaming import replay
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.model_store import load_model
from thermocomp.shell.source import read_streamed


def _two_digit_years(path):
    """The lab's file with its day-first times as Excel's German style writes them: a two-digit
    year and no seconds (``15.03.23 08:00``)."""
    text = path.read_text(encoding="utf-8-sig")
    stamps = pd.Series(text.splitlines()[1:]).str.split(";").str[1]
    for stamp in stamps.unique():
        text = text.replace(stamp, pd.Timestamp(pd.to_datetime(stamp, format="%d.%m.%Y %H:%M:%S")
                                                ).strftime("%d.%m.%y %H:%M"))
    path.write_text(text, encoding="utf-8-sig")
    return path


def test_a_day_first_time_with_a_two_digit_year_reads_as_the_four_digit_one(tmp_path):
    # before: "value '15.03.23 08:00' is not an ISO 8601 timestamp" (exit 2), the dotted date
    # known with a four-digit year only
    four = _clock_file(tmp_path / "four.csv")
    two = _two_digit_years(_clock_file(tmp_path / "two.csv"))
    assert "15.03.23 08:00;" in two.read_text(encoding="utf-8-sig")
    read = {}
    for name, path in (("four", four), ("two", two)):
        ds = read_streamed(_compose(f"data.path={path}", *DATA, "track=false"))[0]
        read[name] = {c: df["time"].to_numpy(float) for c, df in ds.campaigns.items()}
    assert read["two"].keys() == read["four"].keys()
    for cid, times in read["four"].items():
        assert np.array_equal(read["two"][cid], times)


@needs_cc
def test_the_compiled_c_reads_a_two_digit_year_as_replay_does(tmp_path):
    # before: stream.c refused '15.03.23 08:00' ("no number of seconds nor a date")
    path = _two_digit_years(_clock_file(tmp_path / "alle.csv"))
    binary = compiled(tmp_path, path)
    cfg = _compose(f"data.path={path}", *DATA, "model=lagbank", "monitor.adaptive=false",
                   "track=false")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    stream = deploy_stream(cfg, load_model(tmp_path / "run" / "model.pkl"),
                           {c: ds.campaigns[c] for c in train_ids})
    want = np.vstack([-replay(stream, ds.campaigns[c])[stream.targets_].to_numpy(float)
                      for c in test_ids])
    lines = path.read_text(encoding="utf-8-sig").splitlines()
    rows = [ln for ln in lines[1:] if ln.split(";")[0] in "34"]
    run = _streamed(binary, "\n".join([lines[0], *rows]) + "\n")
    assert run.returncode == 0, run.stderr
    got = pd.read_csv(io.BytesIO(run.stdout)).to_numpy(float)
    assert got.shape == want.shape
    assert np.abs(got - want).max() <= 1e-9
