"""A deployed model fed a record that lacks its columns (journey63): the refusal names the file
as it is and each column it lacks."""

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.source import check_streamed_columns


@pytest.fixture
def record(tmp_path):
    """One lab file (the record cut 80/20 into a train and a test part) and a dataset folder."""
    t = np.arange(50) * 60.0
    df = pd.DataFrame({"time": t, "T_a": 20 + t / 3000, "T_b": 21 + t / 4000, "E_X": t / 600})
    path = tmp_path / "messung.csv"
    df.to_csv(path, index=False)
    return path


def test_a_one_file_record_is_named_as_the_file_not_joined_to_itself(record):
    """A model of other columns replayed on a lab's one file named
    'spindle_test.csv/spindle_test.csv' (the record's path joined to its own name)."""
    ds, _ = read_dataset(record, {"test_fraction": 0.2})
    with pytest.raises(ContractError) as err:
        check_streamed_columns(ds, ds.ids("test"), ["T_a", "T_missing"], "the deployed model")
    assert err.value.file == record
    assert str(err.value).startswith(f"file {record}, column 'T_missing': ")
    folder = record.parent / "raw"         # a dataset folder's campaign: its own file in it
    folder.mkdir()
    for cid in ("K1", "K2"):
        pd.read_csv(record).to_csv(folder / f"{cid}.csv", index=False)
    (folder / "campaigns.csv").write_text("campaign,file,split\nK1,K1.csv,train\nK2,K2.csv,test\n")
    ds, _ = read_dataset(folder)
    with pytest.raises(ContractError) as err:
        check_streamed_columns(ds, ["K2"], ["T_missing"], "the deployed model")
    assert err.value.file == folder / "K2.csv"


def test_several_columns_lacking_are_counted_and_listed_not_joined_into_one_name(record):
    """Twelve columns a swiss-lathe model reads, lacking in the spindle record, were shown as one
    column named 'T_amb,T_headstock,...'."""
    ds, _ = read_dataset(record, {"test_fraction": 0.2})
    with pytest.raises(ContractError) as err:
        check_streamed_columns(ds, ds.ids("test"), ["T_a", "T_c", "T_d"], "the deployed model")
    assert err.value.column is None
    assert str(err.value).endswith("lacks 2 columns the deployed model reads: T_c, T_d")

