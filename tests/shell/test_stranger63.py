"""What a stranger met on a trunnion mill's lab files (stranger63, ``bench_stranger63.py``);
each test fails on the code before its mend."""

from __future__ import annotations

import io
import re

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from conftest import FAST
from test_export import _compose, needs_cc
from test_lab_export53 import _clock_file, _streamed
from test_lab_stream52 import DATA
from thermocomp.apps.deploy.streaming import replay
from thermocomp.shell.builders import deploy_stream
from thermocomp.shell.cli import main
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


def _c_against_replay(tmp_path, path, *data) -> float:
    """The largest |C - replay| of the lag bank ``compiled`` exports (``data``: more data
    overrides), streamed the lab's rows of runs 3 and 4 as they are in ``path``."""
    common = (f"data.path={path}", *DATA, *data)
    assert main(["run", *common, "model=lagbank", *FAST, f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "monitor.adaptive=false", "export.format=c", "track=false",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    compiled(tmp_path / "code")
    cfg = _compose(*common, "model=lagbank", "monitor.adaptive=false", "track=false")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    stream = deploy_stream(cfg, load_model(tmp_path / "run" / "model.pkl"),
                           {c: ds.campaigns[c] for c in train_ids})
    want = np.vstack([-replay(stream, ds.campaigns[c])[stream.targets_].to_numpy(float)
                      for c in test_ids])
    lines = path.read_text(encoding="utf-8-sig").splitlines()
    rows = [ln for ln in lines[1:] if ln.split(";")[0] in "34"]
    run = _streamed(tmp_path / "code" / "stream", "\n".join([lines[0], *rows]) + "\n")
    assert run.returncode == 0, run.stderr
    got = pd.read_csv(io.BytesIO(run.stdout)).to_numpy(float)
    assert got.shape == want.shape
    return float(np.abs(got - want).max())


@needs_cc
def test_the_compiled_c_reads_a_two_digit_year_as_replay_does(tmp_path):
    # before: stream.c refused '15.03.23 08:00' ("no number of seconds nor a date")
    path = _two_digit_years(_clock_file(tmp_path / "alle.csv"))
    assert _c_against_replay(tmp_path, path) <= 1e-9


@needs_cc
@pytest.mark.parametrize("form", ["%d.%m.%y %H:%M", "%d.%m.%Y %H:%M"])
def test_export_takes_a_day_first_format_stream_c_reads_when_data_time_names_it(tmp_path, form):
    # before: "export.format=c: the time column 'Zeit' is read as data.time=%d.%m.%y %H:%M,
    # which stream.c cannot convert" (exit 2): the format the reader's refusal had asked for
    path = _two_digit_years(_clock_file(tmp_path / "alle.csv"))
    if "%Y" in form:                      # four digits again, still no seconds
        text = path.read_text(encoding="utf-8-sig")
        path.write_text(re.sub(r"(\d\d\.\d\d\.)(\d\d) ", r"\g<1>20\2 ", text),
                        encoding="utf-8-sig")
    assert _c_against_replay(tmp_path, path, f"data.time={form}") <= 1e-9
