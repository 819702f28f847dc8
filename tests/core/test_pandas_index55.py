"""A record a data scientist saved with pandas, its time as the frame's index (``df.to_parquet()``,
``df.to_csv()``): the index of timestamps is the time, as ``init`` proposes it, in one file or in
a folder of runs ordered by their first timestamps.  Before, ``run`` dropped a Parquet file's
unnamed index and refused the file for want of a time, while ``init`` proposed
``'__index_level_0__'`` as the time; a CSV file's index column (no header) was refused the same way."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import yaml

from thermocomp.core.io import ContractError, read_dataset
from thermocomp.shell.cli import main

ROLES = {"roles": {"error": ["dX*"]}}


def _frame(n: int = 40, start: str = "2026-03-01 08:00") -> pd.DataFrame:
    rng = np.random.default_rng(55)
    index = pd.date_range(start, periods=n, freq="30s", tz="Europe/Berlin")
    t1 = 20.0 + np.cumsum(rng.normal(0.0, 0.05, n))
    return pd.DataFrame({"T1 [°C]": t1, "dX [µm]": 2.0 * (t1 - t1[0])}, index=index)


def _times(ds, cid: str) -> np.ndarray:
    return ds.campaigns[cid]["time"].to_numpy()


@pytest.mark.parametrize("save", ["parquet", "csv"])
def test_an_unnamed_index_of_timestamps_is_the_time(tmp_path, save):
    frame = _frame()
    path = tmp_path / f"lab.{save}"
    frame.to_parquet(path) if save == "parquet" else frame.to_csv(path)
    ds, _ = read_dataset(path, ROLES)
    (cid,) = ds.ids()
    np.testing.assert_allclose(_times(ds, cid), 30.0 * np.arange(len(frame)))
    np.testing.assert_allclose(ds.campaigns[cid]["E_dX"], frame["dX [µm]"])


def test_a_named_time_column_wins_over_the_index_which_is_then_left_out(tmp_path):
    frame = _frame()
    frame.insert(0, "time", 10.0 * np.arange(len(frame)))      # its own seconds, not the index's
    frame.to_parquet(tmp_path / "lab.parquet")
    ds, _ = read_dataset(tmp_path / "lab.parquet", ROLES)
    (cid,) = ds.ids()
    np.testing.assert_allclose(_times(ds, cid), 10.0 * np.arange(len(frame)))
    assert list(ds.campaigns[cid].columns) == ["time", "T_T1", "E_dX"]


def test_an_index_of_row_numbers_is_still_left_out(tmp_path):
    frame = _frame().reset_index(drop=True).iloc[5:]       # a filtered frame: index 5, 6, ...
    frame.to_parquet(tmp_path / "lab.parquet")
    with pytest.raises(ContractError, match="no 'time' column"):
        read_dataset(tmp_path / "lab.parquet", ROLES)
    ds, _ = read_dataset(tmp_path / "lab.parquet", {**ROLES, "sample_period_s": 30.0})
    assert list(ds.campaigns[ds.ids()[0]].columns) == ["time", "T_T1", "E_dX"]


def test_init_proposes_the_index_as_the_time_and_its_config_reads_the_file(tmp_path, capsys):
    path = tmp_path / "lab.parquet"
    _frame().to_parquet(path)
    out = tmp_path / "init"
    assert main(["init", str(path), "data.roles.error=[dX*]", f"out={out}"]) == 0
    printed = capsys.readouterr().out
    assert "time: the column without a header, timestamps from 2026-03-01T08:00:00" in printed
    assert "__index_level_0__" not in printed
    config = yaml.safe_load((out / "conf/data/lab.yaml").read_text(encoding="utf-8"))
    ds, _ = read_dataset(path, {k: v for k, v in config.items() if k != "defaults"})
    assert {c: len(f) for c, f in ds.campaigns.items()} == {"lab_train": 36, "lab_test": 4}


def test_a_folder_of_runs_saved_by_pandas_is_ordered_by_the_index_timestamps(tmp_path):
    folder = tmp_path / "runs"
    folder.mkdir()
    # names in the opposite order of the runs: the first timestamps decide which run is last
    _frame(start="2026-03-02 08:00").to_parquet(folder / "a.parquet")
    _frame(start="2026-03-01 08:00").to_parquet(folder / "b.parquet")
    ds, _ = read_dataset(folder, {**ROLES, "test_fraction": 0.5})
    assert ds.manifest["split"].to_dict() == {"b": "train", "a": "test"}
