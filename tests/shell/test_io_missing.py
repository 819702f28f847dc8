"""Reading records that keep their missing values (``read_dataset(..., missing="keep")``, issue 14).

The monitor streams a campaign as the machine saw it: NaN where a cell is
empty, no trimmed row, no interpolated gap.  Everything else the reader
refuses stays refused, and the default (``"repair"``) is unchanged.
"""

from __future__ import annotations

import io
import json

import numpy as np
import pandas as pd
import pytest

from conftest import thermocomp
from test_io_read import write_raw
from thermocomp.apps.sim import YearRoundSpindle
from thermocomp.core.io import ContractError, read_campaign, read_dataset, write_dataset
from thermocomp.core.io.read import ReadOptions

# Empty cells at the start (T_1), in the middle (T_0: 2, E_X: 1) and at the end (T_0, S_door).
K01 = """time,T_0,T_1,E_X,S_door
0,20.0,,0.0,0
60,20.1,21.1,0.5,0
120,,21.2,1.0,1
180,,21.3,,1
240,20.5,21.4,2.0,0
300,,21.5,2.5,
"""
K02 = "time,T_0,T_1,E_X,S_door\n0,19.0,20.0,0.0,0\n60,19.5,20.5,1.0,0\n"


def as_read(text: str) -> pd.DataFrame:
    return pd.read_csv(io.StringIO(text)).astype(float)


def test_keep_leaves_every_empty_cell_nan_and_counts_it(tmp_path):
    root = write_raw(tmp_path / "ds", {"K01.csv": K01, "K02.csv": K02})
    ds, report = read_dataset(root, missing="keep")
    for cid, text in (("K01", K01), ("K02", K02)):
        want = as_read(text)
        pd.testing.assert_frame_equal(ds.campaigns[cid], want)   # NaN where the file is empty
        entry = report["campaigns"][cid]
        assert entry["rows"] == entry["source_rows"] == len(want)
        assert entry["repairs"] == {} and entry["trimmed"] == {"start": 0, "end": 0}
        counts = want.isna().sum()
        assert entry["missing"] == {c: int(n) for c, n in counts.items() if n}
    assert report["missing"] == {"T_0": 3, "T_1": 1, "E_X": 1, "S_door": 1}
    assert report["repairs"] == {} and "missing" not in report["settings"]


def test_repair_is_the_default_and_unchanged(tmp_path):
    root = write_raw(tmp_path / "ds", {"K01.csv": K01, "K02.csv": K02})
    with pytest.raises(ContractError, match="data.max_edge_samples=0"):
        read_dataset(root)
    cfg = {"max_gap_samples": 2, "max_edge_samples": 1}
    ds, report = read_dataset(root, cfg)
    again, report_again = read_dataset(root, cfg, missing="repair")
    assert json.dumps(report, sort_keys=True) == json.dumps(report_again, sort_keys=True)
    assert "missing" not in report and "missing" not in report["campaigns"]["K01"]
    assert "missing" not in report["settings"]
    frame = ds.campaigns["K01"]
    pd.testing.assert_frame_equal(frame, again.campaigns["K01"])
    # Repaired: first and last rows trimmed, the gaps interpolated; no NaN left.
    assert frame["time"].tolist() == [60, 120, 180, 240] and not frame.isna().any().any()
    assert report["campaigns"]["K01"]["repairs"] == {"T_0": 2, "E_X": 1}
    # Where a value was read, keep and repair agree.
    kept = read_dataset(root, cfg, missing="keep")[0].campaigns["K01"].iloc[1:5].to_numpy()
    valid = ~np.isnan(kept)
    np.testing.assert_array_equal(frame.to_numpy()[valid], kept[valid])


@pytest.mark.parametrize("text, column, row, match", [
    ("time,T_0,E_X\n0,,0\n60,,1\n", "T_0", None, "no valid value"),
    ("time,T_0,E_X\n0,20,0\n60,,x\n", "E_X", 2, "'x' is not a number"),
    ("time,T_0,E_X\n0,20,0\n,21,1\n", "time", 2, "missing time"),
    ("time,T_0,E_X\n0,20,0\nNaN,21,1\n", "time", 2, "missing time"),
    ("time,T_0,E_X\n0,20,0\n60,300,\n", "T_0", 2, "kelvin"),
])
def test_keep_still_refuses_what_is_not_missing(tmp_path, text, column, row, match):
    root = write_raw(tmp_path / "ds", {"K01.csv": text})
    with pytest.raises(ContractError, match=match) as info:
        read_dataset(root, missing="keep")
    message = str(info.value)
    assert "K01.csv" in message and f"'{column}'" in message
    assert row is None or f"row {row}" in message


def test_keep_with_resampling_leaves_the_grid_points_next_to_a_missing_sample_missing(tmp_path):
    text = "time,T_0,E_X\n0,0,0\n10,10,1\n20,,2\n30,30,3\n40,40,4\n"
    write_raw(tmp_path / "ds", {"K01.csv": text})
    table, report = read_campaign(tmp_path / "ds" / "K01.csv",
                                  ReadOptions(resample_s=5.0, missing="keep"))
    frame = table.to_pandas()
    assert frame["E_X"].tolist() == [0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4]
    t0 = frame["T_0"].to_numpy()
    assert np.isnan(t0[3:6]).all() and t0[[0, 1, 2, 6, 7, 8]].tolist() == [0, 5, 10, 30, 35, 40]
    assert report["missing"] == {"T_0": 1}


def test_missing_mode_is_checked():
    with pytest.raises(ValueError, match="missing"):
        ReadOptions(missing="drop")


# --- a dataset whose test campaign has a sensor dropout (the sensor_faults effect) -------------

def dropout_dataset(path, **params):
    """Small year-round dataset, dropout on T_motor1 in the test campaigns; (path, truth)."""
    ds, truth = YearRoundSpindle(n_campaigns=4, duration_h=(4.0, 4.5), seed=1, effects=["sensor_faults"],
                                 effect_params={"sensor_faults": {"kind": "dropout", "column": "T_motor1",
                                                                  **params}}).generate()
    return write_dataset(ds, path), truth


@pytest.mark.parametrize("params, setting", [({}, "data.max_edge_samples=0"),
                                             ({"duration_samples": 3}, "data.max_gap_samples=0")])
def test_a_dropout_is_refused_by_default_and_read_with_keep(tmp_path, params, setting):
    path, truth = dropout_dataset(tmp_path / "ds", **params)
    with pytest.raises(ContractError, match=setting) as info:
        read_dataset(path)
    assert "'T_motor1'" in str(info.value)
    ds, report = read_dataset(path, missing="keep")
    faults = truth["undeclared_effects"][0]["campaigns"]
    assert faults and set(faults) == set(ds.ids("test"))
    for cid in ds.ids():
        frame = ds.campaigns[cid]
        empty = np.flatnonzero(frame.isna().to_numpy().any(axis=1))
        if cid in faults:
            assert empty.tolist() == list(range(faults[cid]["onset_index"], faults[cid]["end_index"]))
            assert frame.columns[frame.isna().any()].tolist() == ["T_motor1"]
            assert report["campaigns"][cid]["missing"] == {"T_motor1": len(empty)}
        else:
            assert empty.size == 0 and report["campaigns"][cid]["missing"] == {}
    written = pd.read_csv(path / f"{ds.ids('test')[0]}.csv")
    pd.testing.assert_frame_equal(ds.campaigns[ds.ids("test")[0]], written.astype(float))


@pytest.mark.slow
def test_run_on_a_dropout_exits_2_naming_the_setting(tmp_path):
    path, _ = dropout_dataset(tmp_path / "ds")
    out = tmp_path / "out"
    proc = thermocomp("run", f"data.path={path}", f"out={out}", "track=false", "plots=none",
                      check=False)
    assert proc.returncode == 2
    (line,) = proc.stderr.strip().splitlines()[-1:]
    assert "T_motor1" in line and "data.max_edge_samples" in line and ".csv" in line
    assert "Traceback" not in proc.stderr and not out.exists()
