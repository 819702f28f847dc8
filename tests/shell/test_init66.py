"""init's leftovers from session 66's stranger passes (init66): a DAQ file's `# start:` line is its
campaign's start (the volumetric ones, init on a lab's distances, are in test_volstranger66)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.core import io
from thermocomp.shell.cli import main


def daq_files(folder, starts: dict, seed: int = 1) -> None:
    """A DAQ script's TAB files, a ``#`` block over each (``# start: ...`` where ``starts``
    gives one), the header a comment too, the time in seconds from each run's 0."""
    folder.mkdir()
    rng = np.random.default_rng(seed)
    for name, start in starts.items():
        t = np.arange(0.0, 40 * 60.0, 60.0)
        temp = 20 + np.cumsum(rng.normal(0, 0.05, t.size))
        e = 3 * (temp - 20) + rng.normal(0, 0.1, t.size)
        head = ["# DAQ thermal test", *([f"# start: {start}"] if start else []),
                "# sample period: 60 s", "#", "# t [s]\tT_1 [degC]\tE_X [um]"]
        rows = [f"{a:.0f}\t{b:.3f}\t{c:.2f}" for a, b, c in zip(t, temp, e)]
        (folder / f"{name}.txt").write_text("\n".join(head + rows) + "\n")


def test_a_daq_files_start_line_orders_its_campaigns(tmp_path, capsys):
    # each file's time counts seconds from its run's start, the start only in its '#' block:
    # the runs were ordered by file name (run_c held out, though run_a came last)
    daq_files(tmp_path / "daq", {"run_a": "2027-03-10 06:00:00", "run_b": "2027-03-08 06:00:00",
                                 "run_c": "2027-03-09 06:00:00"})
    assert main(["init", str(tmp_path / "daq"), f"out={tmp_path / 'init'}"]) in (0, None)
    out = capsys.readouterr().out
    assert "campaign run_a: test" in out and "campaign run_c: train" in out
    assert "3 of 3 files without timestamps state their start in a '# start:' line" in out
    ds = io.read_dataset(tmp_path / "daq", {"test_fraction": 0.34})[0]
    assert ds.manifest.loc["run_a", "split"] == "test"
    assert pd.Timestamp(ds.manifest.loc["run_b", "start"]) == pd.Timestamp("2027-03-08 06:00:00")
    # a file without the line: no start for each, the runs held out in name order, said
    daq_files(tmp_path / "some", {"run_a": "2027-03-10 06:00:00", "run_b": None,
                                  "run_c": "2027-03-09 06:00:00"})
    assert main(["init", str(tmp_path / "some"), f"out={tmp_path / 'init2'}"]) in (0, None)
    out = capsys.readouterr().out
    assert "run_b.txt states none: the campaigns are held out in name order" in out
    assert "campaign run_c: test" in out
