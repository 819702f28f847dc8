"""A test software's ``[Header]`` block over its table states the test's start (isoleft67): taken
as the campaign's start only under a key that says a start and nothing else, with an ISO 8601
date and time (``Test start<TAB>2027-05-07 12:00:00``); a ``Date`` line (an export's date, maybe)
beside a ``Start time`` of a clock time alone is not taken, and ``init`` says why."""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.core import io
from thermocomp.shell.cli import main


def nest_files(folder, heads: dict, seed: int = 1) -> None:
    """A sensor nest's TAB files (benchmarks/bench_iso67.py's layout, small): ``[Header]``, its
    ``key<TAB>value`` lines (``heads[name]``), ``[Data]``, the table, the time ``hh:mm:ss.s``
    since the test's start."""
    folder.mkdir()
    rng = np.random.default_rng(seed)
    for name, lines in heads.items():
        t = np.arange(0, 40 * 60, 60)
        temp = 20 + np.cumsum(rng.normal(0, 0.05, t.size))
        e = 3 * (temp - 20) + rng.normal(0, 0.1, t.size)
        head = ["[Header]", "Software\tNestLog 3.1", "Standard\tISO 230-3:2020", *lines,
                "Sample rate\t60 s", "[Data]", "Time\tE_X1\tT_1"]
        rows = [f"{s // 3600:02d}:{s % 3600 // 60:02d}:{s % 60:02d}.0\t{b:.3f}\t{a:.3f}"
                for s, a, b in zip(t, temp, e)]
        (folder / f"{name}.txt").write_text("\r\n".join(head + rows) + "\r\n")


def test_a_header_blocks_test_start_orders_the_campaigns(tmp_path, capsys):
    # named otherwise than in time: 01_a began last, so it is the one held out
    nest_files(tmp_path / "nest", {
        "01_a": ["Date\t01.12.2027", "Test start\t2027-05-10 07:00:00"],
        "02_b": ["Date\t01.12.2027", "Test start\t2027-05-07 12:00:00"],
        "03_c": ["Date\t01.12.2027", "Test start\t2027-05-08 07:00:00"]})
    assert main(["init", str(tmp_path / "nest"), f"out={tmp_path / 'init'}",
                 "data.time=elapsed"]) in (0, None)
    out = capsys.readouterr().out
    assert "campaign 01_a: test" in out and "campaign 03_c: train" in out
    assert ("3 of 3 files without timestamps state their start in a 'Test start' line of the "
            "block above its table") in out
    ds = io.read_dataset(tmp_path / "nest", {"test_fraction": 0.34, "time": "elapsed"})[0]
    assert ds.manifest.loc["01_a", "split"] == "test"
    assert pd.Timestamp(ds.manifest.loc["02_b", "start"]) == pd.Timestamp("2027-05-07 12:00:00")


def test_a_date_beside_a_clock_time_is_not_taken_and_init_says_why(tmp_path, capsys):
    # the iso67 nest's own block: 'Date' (which may be the export's) and 'Start time' a time
    nest_files(tmp_path / "nest", {
        "01_a": ["Date\t10.05.2027", "Start time\t07:00:00"],
        "02_b": ["Date\t07.05.2027", "Start time\t12:00:00"],
        "03_c": ["Date\t08.05.2027", "Start time\t07:00:00"]})
    assert main(["init", str(tmp_path / "nest"), f"out={tmp_path / 'init'}",
                 "data.time=elapsed"]) in (0, None)
    out = capsys.readouterr().out
    assert "campaign 03_c: test" in out                 # name order, as before
    assert ("01_a.txt: its 'Start time' (07:00:00) holds no date (a 'Date' line beside it may be "
            "the export's): not taken as its start") in out
    # a 'Date' holding a date and a time is no start either (an export's, maybe)
    nest_files(tmp_path / "dated", {"01_a": ["Date\t2027-05-10 07:00:00"],
                                    "02_b": ["Date\t2027-05-07 12:00:00"]})
    ds = io.read_dataset(tmp_path / "dated", {"test_fraction": 0.5, "time": "elapsed"})[0]
    assert ds.manifest.loc["02_b", "split"] == "test"


def test_the_iso67_bench_scenario_builds(monkeypatch):
    # merged beside leftovers67's DeclaredScenario, Iso67's own __init__ refused every simulate
    # (TypeError: 9 positional arguments): benchmarks/bench_iso67.py write exit 1
    from pathlib import Path

    from thermocomp.apps.sim.scenario import CHAIN

    monkeypatch.syspath_prepend(str(Path(__file__).resolve().parents[2] / "benchmarks"))
    from iso67 import Iso67

    gen = Iso67(weeks_later=1, seed=3)
    params = gen.get_params()
    assert list(params) == ["weeks_later", *CHAIN]
    assert (params["weeks_later"], params["error_noise_um"], params["seed"]) == (1, 0.1, 3)


def test_a_day_first_start_is_taken_and_an_ambiguous_one_said(tmp_path, capsys):
    # German test software writes '10.05.2027 07:00:00' (dots: day first); slashes only where a
    # field past 12 says the order; '03/05/2027' (either) is left, and init says why
    nest_files(tmp_path / "nest", {
        "01_a": ["Test start\t10.05.2027 07:00:00,5"],
        "02_b": ["Test start\t07.05.2027 12:00"],
        "03_c": ["Test start\t05/08/2027 07:00:00"],        # ambiguous: left
        "04_d": ["Test start\t13/05/2027 07:00:00"],       # day first: the last to begin
        "05_e": ["Test start\t32.05.2027 07:00:00"]})      # no such day: left, said
    assert main(["init", str(tmp_path / "nest"), f"out={tmp_path / 'init'}",
                 "data.time=elapsed"]) in (0, None)
    out = capsys.readouterr().out
    assert ("03_c.txt, 05_e.txt state none (its 'Test start' (05/08/2027 07:00:00) is no date and time "
            "(ISO 8601, day first with dots, or with slashes and a field past 12)): the campaigns "
            "are held out in name order") in out
    ds = io.read_dataset(tmp_path / "nest", {"test_fraction": 0.2, "time": "elapsed"})[0]
    starts = pd.to_datetime(ds.manifest["start"])
    assert pd.isna(starts["03_c"]) and pd.isna(starts["05_e"])
    assert starts["01_a"] == pd.Timestamp("2027-05-10 07:00:00.5")
    assert starts["02_b"] == pd.Timestamp("2027-05-07 12:00:00")
    assert starts["04_d"] == pd.Timestamp("2027-05-13 07:00:00")
    assert ds.manifest.loc["05_e", "split"] == "test"          # name order, as said


def test_a_start_either_order_reads_is_read_in_data_dayfirsts(tmp_path):
    """dates85: the key every reader of dates with slashes reads (before: '05/08/2027' left
    whatever the key said)."""
    nest_files(tmp_path / "nest", {"01_a": ["Test start\t05/08/2027 07:00:00"],
                                   "02_b": ["Test start\t06/08/2027 07:00:00"]})
    for dayfirst, days in ((True, [(8, 5), (8, 6)]), (False, [(5, 8), (6, 8)])):
        ds = io.read_dataset(tmp_path / "nest", {"test_fraction": 0.5, "time": "elapsed",
                                                 "dayfirst": dayfirst})[0]
        assert list(pd.to_datetime(ds.manifest["start"])) == [
            pd.Timestamp(2027, month, day, 7) for month, day in days]
