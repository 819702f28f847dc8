"""A process historian's long export (``Timestamp;TagName;Value;Quality``, each tag logged on
change at its own times) read as the wide record: detected, each tag held onto the grid of
``data.resample_s`` (sample and hold), a non-Good sample missing, the period an error when not
given (naming the key and the tags' median intervals), bad input refused with file, column and
row.  Before historian60 such a file was read as a wide one: its ``TagName``, ``Value`` and
``Quality`` columns had no role."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.options import ReadOptions

PROBE, BEARING, AIR = "MC07.Probe.Z_um", "MC07.Spindle.Bearing.Temp", "MC07.Hall.Air.Temp"
START = pd.Timestamp("2026-11-02 06:00:00")


def samples(seed: int = 60) -> pd.DataFrame:
    """On-change samples: the probe every 10 s, the bearing every 60-180 s, the air every
    300 s, each at its own offset (a historian's irregular stamps)."""
    rng = np.random.default_rng(seed)
    rows = []
    for k in range(0, 3600, 10):
        rows.append((k, PROBE, round(5 * np.sin(k / 900) + rng.normal(0, 0.2), 2), "Good"))
    t = 3
    while t < 3600:
        rows.append((t, BEARING, round(20 + t / 1000 + rng.normal(0, 0.01), 2), "Good"))
        t += int(rng.integers(60, 181))
    for k in range(7, 3600, 300):
        rows.append((k, AIR, round(19 + k / 5000, 2), "Good"))
    frame = pd.DataFrame(rows, columns=["s", "TagName", "Value", "Quality"]).sort_values(
        "s", kind="stable").reset_index(drop=True)
    frame.insert(0, "Timestamp", (START + pd.to_timedelta(frame.pop("s"), unit="s")).dt.strftime(
        "%d.%m.%Y %H:%M:%S"))
    return frame


def write(frame: pd.DataFrame, path) -> None:
    """As a German historian export: ``;``, decimal commas."""
    frame.to_csv(path, sep=";", decimal=",", index=False)


CFG = {"roles": {"error": ["MC07.Probe.Z"]}, "resample_s": 10, "test_fraction": 0.25,
       "max_gap_samples": 0}


def held(frame: pd.DataFrame, tag: str, grid_s: np.ndarray) -> np.ndarray:
    """The tag's value at each grid time by sample and hold, from the samples themselves."""
    own = frame[frame["TagName"] == tag]
    seconds = (pd.to_datetime(own["Timestamp"], format="%d.%m.%Y %H:%M:%S") - START
               ).dt.total_seconds().to_numpy()
    good = (own["Quality"] == "Good").to_numpy()
    value = np.where(good, own["Value"].to_numpy(float), np.nan)
    at = np.searchsorted(seconds, grid_s, side="right") - 1
    return value[at]


def test_a_long_file_is_detected_and_a_wide_one_is_not(tmp_path):
    from thermocomp.core.io.historian_layout import long_layout

    write(samples(), tmp_path / "pi.csv")
    layout = long_layout(tmp_path / "pi.csv", ReadOptions.from_cfg({}))
    assert layout is not None
    assert [layout.header[i] for i in (layout.time, layout.tag, layout.value, layout.quality)] \
        == ["Timestamp", "TagName", "Value", "Quality"]
    # a wide file of three columns with a run's label (each label's rows together): not long
    wide = pd.DataFrame({"time": np.arange(40.0), "Versuch": ["K01"] * 20 + ["K02"] * 20,
                         "dX [um]": np.linspace(0, 1, 40)})
    wide.to_csv(tmp_path / "wide.csv", index=False)
    assert long_layout(tmp_path / "wide.csv", ReadOptions.from_cfg({})) is None


def test_each_tag_is_held_onto_the_grid_from_its_last_sample(tmp_path):
    frame = samples()
    write(frame, tmp_path / "pi.csv")
    ds, report = read_dataset(tmp_path / "pi.csv", CFG)
    first = report["campaigns"][ds.ids()[0]]
    origin = pd.Timestamp(first["time_origin"]).tz_localize(None)
    assert (origin - START).total_seconds() == 7.0   # every tag has a sample (the air's first)
    checked = 0
    for cid in ds.ids():
        campaign = ds.campaigns[cid]
        grid = (pd.Timestamp(report["campaigns"][cid]["time_origin"]).tz_localize(None)
                - START).total_seconds() + campaign["time"].to_numpy()
        assert np.allclose(np.diff(grid), 10.0)
        for tag, name in ((PROBE, "E_MC07.Probe.Z"), (BEARING, "T_MC07.Spindle.Bearing.Temp"),
                          (AIR, "T_MC07.Hall.Air.Temp")):
            got, expected = campaign[name].to_numpy(), held(frame, tag, grid)
            # (as referenced: the first sample's value subtracted, or not)
            assert np.allclose(got - got[0], expected - expected[0], atol=1e-9), (cid, name)
            checked += len(got)
    last = (pd.to_datetime(frame["Timestamp"], format="%d.%m.%Y %H:%M:%S").max()
            - START).total_seconds()
    assert checked == 3 * (int((last - 7) // 10) + 1)      # the grid runs to the last stamp


def test_a_sample_not_good_is_missing_until_the_tags_next_sample(tmp_path):
    frame = samples()
    bad = frame.index[frame["TagName"] == BEARING][5]
    frame.loc[bad, "Quality"] = "Bad"
    write(frame, tmp_path / "pi.csv")
    stamp = (pd.to_datetime(frame.loc[bad, "Timestamp"], format="%d.%m.%Y %H:%M:%S")
             - START).total_seconds()
    later = frame.index[(frame["TagName"] == BEARING) & (frame.index > bad)][0]
    until = (pd.to_datetime(frame.loc[later, "Timestamp"], format="%d.%m.%Y %H:%M:%S")
             - START).total_seconds()
    ds, _ = read_dataset(tmp_path / "pi.csv", CFG, missing="keep")
    record = pd.concat([ds.campaigns[c] for c in ds.ids()])
    grid = 7.0 + record["time"].to_numpy()
    missing = record["T_MC07.Spindle.Bearing.Temp"].isna().to_numpy()
    assert np.array_equal(missing, (grid >= stamp) & (grid < until))
    # repaired as a wide file's gap: longer than data.max_gap_samples, refused naming the tag
    # and the long file's row of the sample that began it
    with pytest.raises(ContractError) as exc:
        read_dataset(tmp_path / "pi.csv", CFG)
    assert exc.value.column == BEARING and exc.value.row == bad + 1
    assert "data.max_gap_samples=0" in str(exc.value) and str(tmp_path / "pi.csv") in str(exc.value)


def test_a_long_file_without_a_period_is_refused_naming_the_key_and_the_tags_intervals(tmp_path):
    write(samples(), tmp_path / "pi.csv")
    with pytest.raises(ContractError) as exc:
        read_dataset(tmp_path / "pi.csv", {k: v for k, v in CFG.items() if k != "resample_s"})
    said = str(exc.value)
    assert "data.resample_s" in said and f"{PROBE} 10 s" in said and f"{AIR} 300 s" in said


@pytest.mark.parametrize("spoil, column, says", [
    ("repeat", "Value", "two samples at"),
    ("text", "Value", "is not a number, and its quality says Good"),
    ("quality", "Quality", "quality 'Substitute?' is read by no rule"),
    ("time", "Timestamp", "is not a time in data.time's format"),   # (the wide reader's message)
])
def test_bad_samples_are_refused_with_file_column_and_row(tmp_path, spoil, column, says):
    frame = samples()
    at = int(frame.index[frame["TagName"] == BEARING][4])
    if spoil == "repeat":                    # the same stamp again, another value
        extra = frame.loc[[at]].assign(Value=frame.loc[at, "Value"] + 1)
        frame = pd.concat([frame.loc[:at], extra, frame.loc[at + 1:]], ignore_index=True)
        at += 1
    elif spoil == "text":
        frame["Value"] = frame["Value"].astype(object)
        frame.loc[at, "Value"] = "I/O Timeout"
    elif spoil == "quality":
        frame.loc[at, "Quality"] = "Substitute?"
    else:
        frame.loc[at, "Timestamp"] = "02.11.2026 25:00:00"
    write(frame, tmp_path / "pi.csv")
    with pytest.raises(ContractError) as exc:
        read_dataset(tmp_path / "pi.csv", CFG)
    assert exc.value.column == column and exc.value.row == at + 1, str(exc.value)
    assert says in str(exc.value) and str(exc.value).startswith(f"file {tmp_path / 'pi.csv'}")


def test_a_gap_refused_says_the_longest_gap_of_its_column(tmp_path):
    """A historian's Bad scans (or a wide file's empty cells) were refused one gap at a time:
    the stranger raised data.max_gap_samples to 2, then met a gap of 3 further on."""
    frame = samples()
    probe = frame.index[frame["TagName"] == PROBE]
    frame.loc[probe[[20]], "Quality"] = "Bad"                 # a gap of 1 grid row first
    frame.loc[probe[[200, 201, 202]], "Quality"] = "Bad"      # then one of 3
    write(frame, tmp_path / "pi.csv")
    with pytest.raises(ContractError) as exc:
        read_dataset(tmp_path / "pi.csv", CFG)
    assert exc.value.row == probe[20] + 1
    assert "its longest gap is 3 values, data.max_gap_samples=3 interpolates every one" \
        in str(exc.value)
    read_dataset(tmp_path / "pi.csv", {**CFG, "max_gap_samples": 3})


def test_a_silence_of_every_tag_is_left_without_rows_not_held(tmp_path, caplog):
    """No tag logged for over 100 grid steps (the collector off): no row there, said."""
    frame = samples()
    seconds = (pd.to_datetime(frame["Timestamp"], format="%d.%m.%Y %H:%M:%S") - START
               ).dt.total_seconds()
    late = seconds > 1800
    frame.loc[late, "Timestamp"] = (START + pd.to_timedelta(seconds[late] + 7200, unit="s")
                                    ).dt.strftime("%d.%m.%Y %H:%M:%S")
    write(frame, tmp_path / "pi.csv")
    ds, report = read_dataset(tmp_path / "pi.csv", {**CFG, "reference": "none"})
    origin = pd.Timestamp(report["campaigns"][ds.ids()[0]]["time_origin"]).tz_localize(None)
    times = np.concatenate([origin - START + pd.to_timedelta(ds.campaigns[c]["time"], unit="s")
                            for c in ds.ids()]) / pd.Timedelta(seconds=1)
    last_before = seconds[~late].max()
    assert not ((times > last_before) & (times < seconds[late].min() + 7200)).any()
    assert any("where no tag logged for over 100 grid periods" in r.getMessage()
               for r in caplog.records)


def test_runs_of_a_historian_one_file_each_or_a_batch_tag(tmp_path):
    """The wide files' mechanisms, unchanged: a folder's files a campaign each, a batch tag a
    run column (``data.roles.campaign``)."""
    folder = tmp_path / "runs"
    folder.mkdir()
    write(samples(1), folder / "run_1.csv")
    write(samples(2), folder / "run_2.csv")
    ds, _ = read_dataset(folder, {**CFG, "test_fraction": 0.5})
    assert ds.ids() == ["run_1", "run_2"] and ds.ids("test") == ["run_2"]
    frame = samples()
    batch = pd.DataFrame({"Timestamp": [(START + pd.Timedelta(seconds=s)).strftime(
        "%d.%m.%Y %H:%M:%S") for s in (1, 1800)], "TagName": "MC07.Batch.No",
        "Value": [1.0, 2.0], "Quality": "Good"})
    write(pd.concat([frame, batch]), tmp_path / "batch.csv")
    ds, _ = read_dataset(tmp_path / "batch.csv", {**CFG, "test_fraction": 0.5, "roles": {
        **CFG["roles"], "campaign": "MC07.Batch.No"}})
    assert ds.ids() == ["MC07.Batch.No_1", "MC07.Batch.No_2"]
    end = 7 + ds.campaigns["MC07.Batch.No_1"]["time"].iloc[-1]   # (its grid began at 7 s)
    assert end < 1800 <= end + 10        # the first run: every grid row before batch 2's sample


def test_an_opc_quality_byte_reads_192_as_good_and_0_as_bad(tmp_path):
    frame = samples()
    bearing = frame.index[frame["TagName"] == BEARING]
    frame["Quality"] = 192
    frame.loc[bearing[5], "Quality"] = 0
    write(frame.rename(columns={"Quality": "Status"}), tmp_path / "pi.csv")
    ds, _ = read_dataset(tmp_path / "pi.csv", CFG, missing="keep")
    record = pd.concat([ds.campaigns[c] for c in ds.ids()])
    missing = int(record["T_MC07.Spindle.Bearing.Temp"].isna().sum())
    stamps = pd.to_datetime(frame.loc[bearing[[5, 6]], "Timestamp"], format="%d.%m.%Y %H:%M:%S")
    assert missing == len(pd.date_range(START + pd.Timedelta(seconds=7), stamps.iloc[1],
                                        freq="10s", inclusive="left").intersection(
        pd.date_range(stamps.iloc[0], stamps.iloc[1], freq="1s")))
