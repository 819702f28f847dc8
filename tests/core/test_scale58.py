"""A year's record at small size: what broke at full size (scale58) behaves on a few rows."""

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.io import Dataset, read_dataset, write_dataset


def _late_record(time_s: np.ndarray) -> Dataset:
    manifest = pd.DataFrame({"file": [""], "split": ["train"]},
                            index=pd.Index(["R1"], name="campaign"))
    n = len(time_s)
    frame = pd.DataFrame({"time": time_s, "T_a": np.linspace(20.0, 21.0, n),
                          "E_Z": np.linspace(0.0, 3.0, n)})
    return Dataset(manifest, {"R1": frame}, "late")


@pytest.mark.parametrize("step", [60.0, 0.5])
def test_written_time_keeps_every_sample_past_1e7_s(tmp_path, step):
    # 200 days in: %.6g wrote 60 s steps as 100 s ones, two rows at one time (refused on read)
    time_s = 200 * 86400.0 + step * np.arange(50)
    write_dataset(_late_record(time_s), tmp_path / "ds")

    ds, _ = read_dataset(tmp_path / "ds")

    np.testing.assert_array_equal(ds.campaigns["R1"]["time"].to_numpy(), time_s)
