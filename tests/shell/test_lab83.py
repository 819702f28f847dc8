"""A historian's long text export with a run of samples not Good (lab83): ``init`` counts each
tag's run of missing grid rows on its own, in the grid the read holds the tag onto, and proposes
the ``data.max_gap_samples`` its own read accepts, naming the long file, the tag and its row.
Before, the long file's cells were never scanned (it is read through a converted grid): nothing
was proposed and init's own read refused the probe's six Bad samples (exit 2)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import yaml

from conftest import FAST, refused, thermocomp
from test_historian60 import AIR, PROBE, START, samples, write


def _bad(frame: pd.DataFrame, tag: str, first: int, count: int) -> pd.DataFrame:
    """``count`` of the tag's samples from its ``first`` marked Bad."""
    at = frame.index[frame["TagName"] == tag][first:first + count]
    return frame.assign(Quality=frame["Quality"].where(~frame.index.isin(at), "Bad")), at


def _seconds(frame: pd.DataFrame, rows) -> np.ndarray:
    return (pd.to_datetime(frame.loc[rows, "Timestamp"], format="%d.%m.%Y %H:%M:%S") - START
            ).dt.total_seconds().to_numpy()


def test_init_counts_a_fast_tags_bad_run_on_its_own_grid_and_its_read_accepts_it(tmp_path):
    frame, at = _bad(samples(), PROBE, 100, 6)
    write(frame, tmp_path / "pi.csv")
    out = tmp_path / "out"
    said = thermocomp("init", f"data.path={tmp_path / 'pi.csv'}", f"out={out}").stdout
    config = yaml.safe_load((out / "conf" / "data" / "pi.yaml").read_text())
    # the probe logs on the grid's own period: one grid row a Bad sample
    assert config["resample_s"] == 10.0 and config["max_gap_samples"] == len(at)
    assert (f"inside a file is {len(at)} samples, {10 * len(at)} s of 'MC07.Probe.Z_um' "
            f"(from data row {at[0] + 1} of pi.csv)") in said
    thermocomp("run", f"hydra.searchpath=[file://{out / 'conf'}]", "data=pi", f"out={out}",
               "model=mlr", *FAST)
    assert (out / "metrics.json").exists()


def test_a_slow_tags_bad_sample_is_its_own_interval_in_grid_rows(tmp_path):
    frame, at = _bad(samples(), AIR, 4, 1)
    write(frame, tmp_path / "pi.csv")
    out = tmp_path / "out"
    thermocomp("init", f"data.path={tmp_path / 'pi.csv'}", f"out={out}")
    config = yaml.safe_load((out / "conf" / "data" / "pi.yaml").read_text())
    air = frame.index[frame["TagName"] == AIR]
    bad, good = _seconds(frame, [at[0], air[list(air).index(at[0]) + 1]])
    probe = _seconds(frame, frame.index[frame["TagName"] == PROBE])
    # the grid points at or after the Bad sample and before the air's next one
    start = max(_seconds(frame, frame.groupby("TagName").head(1).index))
    grid = start + 10 * np.arange(int((probe.max() - start) // 10) + 1)
    assert config["max_gap_samples"] == int(((grid >= bad) & (grid < good)).sum())


def test_a_gap_longer_than_the_key_is_refused_naming_the_long_file_tag_and_row(tmp_path, capsys):
    frame, at = _bad(samples(), PROBE, 100, 6)
    write(frame, tmp_path / "pi.csv")
    refused(["run", f"data.path={tmp_path / 'pi.csv'}", "data.roles.error=[MC07.Probe.Z]",
             "data.resample_s=10", f"data.max_gap_samples={len(at) - 1}",
             f"out={tmp_path / 'out'}", *FAST], capsys,
            f"file {tmp_path / 'pi.csv'}, column {PROBE!r}, data row {at[0] + 1}",
            f"gap of {len(at)} missing values")
