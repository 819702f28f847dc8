"""Good-path tests of thermocomp.core.io.read: reading, repairs, resampling, ingest."""

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from thermocomp.core.io import (
    INGEST_REPORT,
    ContractError,
    Dataset,
    ingest,
    load_interim,
    read_dataset,
    write_dataset,
)
from thermocomp.core.io import tables as io_tables


def write_raw(root: Path, files: dict, splits: dict | None = None) -> Path:
    """Dataset folder from {file name: CSV text or Arrow table}; ids are the stems."""
    root.mkdir(parents=True, exist_ok=True)
    lines = ["campaign,file,split"]
    for name, content in files.items():
        if isinstance(content, pa.Table):
            pq.write_table(content, root / name)
        else:
            (root / name).write_text(content)
        cid = Path(name).stem
        lines.append(f"{cid},{name},{(splits or {}).get(cid, 'train')}")
    (root / "campaigns.csv").write_text("\n".join(lines) + "\n")
    return root


def example_dataset() -> Dataset:
    rng = np.random.default_rng(0)
    manifest = pd.DataFrame(
        {"file": ["", ""], "split": ["train", "test"], "ambient_c": [20.5, 23.0],
         "start": ["2024-01-08T07:30:00", "2024-07-02T13:00:00"], "notes": ["cold", "warm"]},
        index=pd.Index(["K01", "K02"], name="campaign"))
    campaigns = {}
    for cid, n in (("K01", 40), ("K02", 25)):
        time = np.cumsum(rng.integers(1, 4, n)).astype(float) * 30.0
        campaigns[cid] = pd.DataFrame({
            "time": time,
            "T_spindle": np.round(20 + rng.normal(size=n).cumsum() * 0.1, 3),
            "T_amb": np.round(20 + rng.normal(size=n) * 0.2, 3),
            "E_X": np.round(rng.normal(size=n).cumsum(), 3),
            "E_Z": np.round(rng.normal(size=n).cumsum(), 3),
            "S_door": (rng.random(n) > 0.8).astype(float),
        })
    return Dataset(manifest, campaigns, "example")


@pytest.mark.parametrize("fmt", ["csv", "parquet"])
def test_round_trip_through_write_dataset(tmp_path, fmt):
    original = example_dataset()
    write_dataset(original, tmp_path / "ds", fmt=fmt)

    ds, report = read_dataset(tmp_path / "ds")

    assert ds.name == "ds" and ds.ids() == ["K01", "K02"]
    assert ds.ids("test") == ["K02"]
    for cid, frame in original.campaigns.items():
        pd.testing.assert_frame_equal(ds.campaigns[cid], frame, check_exact=False, rtol=1e-12)
        assert (ds.campaigns[cid].dtypes == np.float64).all()
    assert report["rows"] == 65
    assert report["campaigns"]["K01"] == {
        "file": f"K01.{fmt}", "split": "train", "rows": 40, "source_rows": 40,
        "time": "seconds", "repairs": {}, "trimmed": {"start": 0, "end": 0}}
    assert report["columns"] == {"T": ["T_spindle", "T_amb"], "E": ["E_X", "E_Z"],
                                 "S": ["S_door"]}


def test_manifest_metadata_is_kept_and_typed(tmp_path):
    write_dataset(example_dataset(), tmp_path / "ds")

    manifest = read_dataset(tmp_path / "ds")[0].manifest

    assert list(manifest.columns) == ["file", "split", "ambient_c", "start", "notes"]
    assert manifest["ambient_c"].dtype == np.float64
    assert manifest.loc["K02", "start"] == pd.Timestamp("2024-07-02 13:00")
    assert manifest.loc["K01", "notes"] == "cold"


def test_columns_are_ordered_time_then_roles_in_file_order(tmp_path):
    csv = "S_door,E_X,time,T_b,T_a\n0,1.5,0,20,21\n1,1.6,1,20.5,21.5\n"
    write_raw(tmp_path / "ds", {"K01.csv": csv})

    frame = read_dataset(tmp_path / "ds")[0].campaigns["K01"]

    assert list(frame.columns) == ["time", "T_b", "T_a", "E_X", "S_door"]
    assert frame["E_X"].tolist() == [1.5, 1.6]


def test_mapping_and_sample_period_for_foreign_csv(tmp_path):
    csv = "T0,T1,delta L\n20.0,21.0,0.0\n20.5,21.2,1.5\n21.0,21.4,2.5\n"
    write_raw(tmp_path / "ds", {"run1.csv": csv})
    cfg = {"columns": {"T0": "T_0", "T1": "T_1", "delta L": "E_L"}, "sample_period_s": 30}

    ds, report = read_dataset(tmp_path / "ds", cfg)

    frame = ds.campaigns["run1"]
    assert list(frame.columns) == ["time", "T_0", "T_1", "E_L"]
    assert frame["time"].tolist() == [0.0, 30.0, 60.0]
    assert frame["E_L"].tolist() == [0.0, 1.5, 2.5]
    assert report["campaigns"]["run1"]["time"] == "sample_period_s"


def test_config_may_be_an_omegaconf_dictconfig(tmp_path):
    omegaconf = pytest.importorskip("omegaconf")
    write_raw(tmp_path / "ds", {"K01.csv": "Zeit,T0,dL\n0,20,0\n60,20.5,1\n"})
    cfg = omegaconf.OmegaConf.create(
        {"path": "ignored", "columns": {"Zeit": "time", "T0": "T_0", "dL": "E_L"},
         "max_gap_samples": 1, "split_overrides": {"K01": "val"}})

    ds, report = read_dataset(tmp_path / "ds", cfg)

    assert list(ds.campaigns["K01"].columns) == ["time", "T_0", "E_L"]
    assert ds.ids("val") == ["K01"]
    json.dumps(report)


def test_time_column_wins_over_sample_period(tmp_path):
    write_raw(tmp_path / "ds", {"K01.csv": "time,T_0,E_X\n5,20,0\n7,20,1\n"})

    frame = read_dataset(tmp_path / "ds", {"sample_period_s": 1.0})[0].campaigns["K01"]

    assert frame["time"].tolist() == [5.0, 7.0]


def test_iso_timestamps_become_seconds_since_first_sample(tmp_path):
    csv = ("time,T_0,E_X\n2024-03-01T08:00:00,20,0\n2024-03-01T08:00:30.5,20.1,0.5\n"
           "2024-03-01T09:00:00,21,2\n")
    write_raw(tmp_path / "ds", {"K01.csv": csv})

    ds, report = read_dataset(tmp_path / "ds")

    assert ds.campaigns["K01"]["time"].tolist() == [0.0, 30.5, 3600.0]
    assert report["campaigns"]["K01"]["time"] == "iso8601"
    assert report["campaigns"]["K01"]["time_origin"] == "2024-03-01T08:00:00"


def test_iso_timestamps_with_zone_offsets_compare_instants(tmp_path):
    # The clock changes offset mid-campaign; the instants are 60 s apart.
    csv = ("time,T_0,E_X\n2024-03-31T00:59:00Z,20,0\n2024-03-31T03:00:00+02:00,20,1\n"
           "2024-03-31T03:01:00+02:00,20,2\n")
    write_raw(tmp_path / "ds", {"K01.csv": csv})

    frame = read_dataset(tmp_path / "ds", {"time": "iso8601"})[0].campaigns["K01"]

    assert frame["time"].tolist() == [0.0, 60.0, 120.0]


def test_parquet_timestamps_and_integer_columns(tmp_path):
    table = pa.table({
        "time": pa.array(pd.date_range("2024-01-01", periods=4, freq="10s")),
        "T_0": pa.array([20, 21, 22, 23], pa.int32()),
        "E_X": [0.0, 0.5, 1.0, 1.5],
        "S_door": [False, True, True, False],
    })
    write_raw(tmp_path / "ds", {"K01.parquet": table})

    frame = read_dataset(tmp_path / "ds")[0].campaigns["K01"]

    assert frame["time"].tolist() == [0.0, 10.0, 20.0, 30.0]
    assert (frame.dtypes == np.float64).all()
    assert frame["S_door"].tolist() == [0.0, 1.0, 1.0, 0.0]


def test_gap_repair_interpolates_in_time_and_is_counted(tmp_path):
    # Uneven time: the gap at t=2 and t=4 lies between t=1 (10) and t=8 (80).
    k01 = "time,T_0,E_X\n0,0,0\n1,10,1\n2,,2\n4,,3\n8,80,4\n9,90,\n10,100,6\n"
    k02 = "time,T_0,E_X\n0,20,0\n1,,1\n2,22,2\n"
    write_raw(tmp_path / "ds", {"K01.csv": k01, "K02.csv": k02})

    ds, report = read_dataset(tmp_path / "ds", {"max_gap_samples": 2})

    assert ds.campaigns["K01"]["T_0"].tolist() == [0, 10, 20, 40, 80, 90, 100]
    assert ds.campaigns["K01"]["E_X"].tolist() == [0, 1, 2, 3, 4, 5, 6]
    assert ds.campaigns["K02"]["T_0"].tolist() == [20, 21, 22]
    assert report["campaigns"]["K01"]["repairs"] == {"T_0": 2, "E_X": 1}
    assert report["campaigns"]["K02"]["repairs"] == {"T_0": 1}
    assert report["repairs"] == {"T_0": 3, "E_X": 1}


def test_gap_repair_across_arrow_chunks(tmp_path, monkeypatch):
    monkeypatch.setattr(io_tables, "_CSV_BLOCK_BYTES", 2048)  # a few hundred rows per chunk
    rng = np.random.default_rng(1)
    n = 5_000
    time = np.cumsum(rng.uniform(0.5, 2.0, n))
    truth = np.round(20 + np.sin(time / 300), 4)
    holes = np.sort(rng.choice(np.arange(1, n - 3), 120, replace=False))
    holes = np.unique(np.concatenate([holes, holes[::4] + 1]))  # some 2-sample gaps
    measured = truth.copy()
    measured[holes] = np.nan
    frame = pd.DataFrame({"time": time, "T_0": measured, "E_X": truth})
    write_raw(tmp_path / "ds", {"K01.csv": frame.to_csv(index=False)})

    ds, report = read_dataset(tmp_path / "ds", {"max_gap_samples": 3})

    valid = np.flatnonzero(~np.isnan(measured))
    expected = np.interp(time, time[valid], measured[valid])
    np.testing.assert_allclose(ds.campaigns["K01"]["T_0"], expected, rtol=1e-12)
    assert report["repairs"] == {"T_0": len(holes)}


def test_incomplete_edge_rows_are_trimmed_not_filled(tmp_path):
    csv = "time,T_0,T_1,E_X\n0,20,,0\n1,20,,1\n2,20,21,2\n3,20,21,3\n4,20,21,\n"
    write_raw(tmp_path / "ds", {"K01.csv": csv})

    ds, report = read_dataset(tmp_path / "ds", {"max_edge_samples": 2})

    frame = ds.campaigns["K01"]
    assert frame["time"].tolist() == [2.0, 3.0]
    assert not frame.isna().any().any()
    entry = report["campaigns"]["K01"]
    assert entry["trimmed"] == {"start": 2, "end": 1}
    assert (entry["rows"], entry["source_rows"]) == (2, 5)
    assert entry["repairs"] == {}


def test_resampling_onto_a_uniform_grid(tmp_path):
    write_raw(tmp_path / "ds", {"K01.csv": "time,T_0,E_X\n0,0,0\n1,10,1\n3,30,9\n4.2,42,12\n"})

    ds, report = read_dataset(tmp_path / "ds", {"resample_s": 0.5})

    frame = ds.campaigns["K01"]
    np.testing.assert_allclose(frame["time"], np.arange(0, 4.01, 0.5))
    np.testing.assert_allclose(frame["T_0"], frame["time"] * 10)
    assert frame["E_X"].iloc[4] == pytest.approx(5.0)  # t=2 between (1, 1) and (3, 9)
    assert report["campaigns"]["K01"]["rows"] == 9
    assert report["campaigns"]["K01"]["resampled_s"] == 0.5


def test_without_resample_s_time_is_kept_as_given(tmp_path):
    write_raw(tmp_path / "ds", {"K01.csv": "time,T_0,E_X\n0,0,0\n1,10,1\n3,30,9\n"})

    frame = read_dataset(tmp_path / "ds")[0].campaigns["K01"]

    assert frame["time"].tolist() == [0.0, 1.0, 3.0]


def test_split_override(tmp_path):
    csv = "time,T_0,E_X\n0,20,0\n1,20,1\n"
    write_raw(tmp_path / "ds", {"K01.csv": csv, "K02.csv": csv}, splits={"K02": "test"})

    ds, report = read_dataset(tmp_path / "ds", {"split_overrides": {"K01": "val", "K02": "train"}})

    assert ds.ids("val") == ["K01"] and ds.ids("train") == ["K02"] and ds.ids("test") == []
    assert report["campaigns"]["K02"]["split"] == "train"


def test_semicolon_separated_decimal_comma_csv(tmp_path):
    write_raw(tmp_path / "ds", {"K01.csv": "time;T_0;E_X\n0;20,5;0\n1;20,75;1,25\n"})

    frame = read_dataset(tmp_path / "ds", {"delimiter": ";", "decimal": ","})[0].campaigns["K01"]

    assert frame["T_0"].tolist() == [20.5, 20.75]
    assert frame["E_X"].tolist() == [0.0, 1.25]


def _snapshot(folder: Path) -> dict:
    return {p.name: (p.read_bytes(), p.stat().st_mtime_ns) for p in sorted(folder.iterdir())}


def test_ingest_writes_parquet_dataset_and_report(tmp_path):
    raw = tmp_path / "raw"
    write_dataset(example_dataset(), raw)
    before = _snapshot(raw)

    report = ingest(raw, tmp_path / "interim", {"split_overrides": {"K01": "val"}})

    out = tmp_path / "interim"
    assert sorted(p.name for p in out.iterdir()) == [
        "K01.parquet", "K02.parquet", "campaigns.csv", INGEST_REPORT]
    assert json.loads((out / INGEST_REPORT).read_text()) == report
    assert report["dataset"] == "raw" and report["rows"] == 65
    manifest = pd.read_csv(out / "campaigns.csv")
    assert manifest.columns[:3].tolist() == ["campaign", "file", "split"]
    assert manifest["split"].tolist() == ["val", "test"]
    assert _snapshot(raw) == before

    reread, _ = read_dataset(raw)
    interim = load_interim(out)
    assert interim.meta["ingest_report"] == report
    assert interim.ids("val") == ["K01"]
    assert interim.manifest.loc["K02", "start"] == pd.Timestamp("2024-07-02 13:00")
    for cid, frame in reread.campaigns.items():
        pd.testing.assert_frame_equal(interim.campaigns[cid], frame)
    assert read_dataset(out)[1]["rows"] == 65  # the interim is a contract dataset itself


def test_ingest_replaces_a_previous_destination(tmp_path):
    raw = write_raw(tmp_path / "raw", {"K01.csv": "time,T_0,E_X\n0,20,0\n1,20,1\n"})
    out = tmp_path / "interim"
    out.mkdir()
    (out / "stale.parquet").write_bytes(b"old")

    ingest(raw, out)

    assert not (out / "stale.parquet").exists()
    assert load_interim(out).campaigns["K01"]["E_X"].tolist() == [0.0, 1.0]


def test_load_interim_refuses_a_folder_not_written_by_ingest(tmp_path):
    raw = write_raw(tmp_path / "raw", {"K01.csv": "time,T_0,E_X\n0,20,0\n1,20,1\n"})

    with pytest.raises(ContractError, match="ingest_report.json"):
        load_interim(raw)
