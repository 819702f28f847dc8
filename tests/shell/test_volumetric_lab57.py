"""A lab's artefact data as a lab hands it (vol57): a set-up written in µm, a cycle of
temperatures without any distance, and its own CSV export (`;`, decimal commas)."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from conftest import refused, simulated
from thermocomp.apps.sim.volumetric import LargeMillVolumetric
from thermocomp.shell.cli import main


@pytest.fixture(scope="module")
def raw(tmp_path_factory):
    gen = LargeMillVolumetric(train_hours=3.0, test_hours=2.0, seed=4)
    return simulated(gen, tmp_path_factory.mktemp("vollab") / "raw")


def _copy(raw, dest, setup=None):
    shutil.copytree(raw, dest)
    if setup:
        path = dest / "volumetric.json"
        d = json.loads(path.read_text())
        setup(d)
        path.write_text(json.dumps(d))
    return dest


def _in_um(d):
    """Every length of the set-up in µm: consistent within itself, only a thousand times off."""
    m = d["machine"]
    m["ranges"] = {a: [1000 * v for v in r] for a, r in m["ranges"].items()}
    m["tool"] = [1000 * v for v in m["tool"]]
    d["artefact"]["length_mm"] *= 1000
    for pose in d["poses"]:
        pose["centre"] = [1000 * v for v in pose["centre"]]


def test_a_set_up_written_in_um_is_refused_as_one(raw, tmp_path, capsys):
    """It was calibrated (exit 0): the positioning and straightness parameters as in mm, every
    angular one (µm/m over levers a thousand times too long) a thousandth of its size."""
    data = _copy(raw, tmp_path / "um", _in_um)
    refused(["calibrate", f"data.path={data}", f"out={tmp_path / 'o'}", "track=false"], capsys,
            "volumetric.json", "machine.ranges.X", "in µm?")


def test_pose_centres_in_um_say_the_unit(raw, tmp_path, capsys):
    def centres(d):
        for pose in d["poses"]:
            pose["centre"] = [1000 * v for v in pose["centre"]]

    data = _copy(raw, tmp_path / "centres", centres)
    refused(["calibrate", f"data.path={data}", f"out={tmp_path / 'o'}", "track=false"], capsys,
            "outside its travel", "in µm? divide them by 1000")


def test_a_cycle_without_any_distance_is_named_as_one(raw, tmp_path, capsys):
    data = _copy(raw, tmp_path / "empty")
    path = data / "train_week.parquet"
    df = pd.read_parquet(path)
    df.loc[3, [c for c in df.columns if c.startswith("E_")]] = np.nan
    df.to_parquet(path)
    line = refused(["calibrate", f"data.path={data}", f"out={tmp_path / 'o'}", "track=false"],
                   capsys, "train_week.parquet", "data row 4", "every E_ cell of the row empty",
                   "drop the row")
    assert line.count("cannot identify the parameters") <= 1, line


def test_the_labs_own_csv_export_calibrates_to_the_same_parameters(raw, tmp_path):
    data = _copy(raw, tmp_path / "lab")
    manifest = pd.read_csv(data / "campaigns.csv")
    for i, row in manifest.iterrows():
        df = pd.read_parquet(data / row["file"])
        (data / row["file"]).unlink()
        manifest.loc[i, "file"] = row["file"].replace(".parquet", ".csv")
        df.to_csv(data / manifest.loc[i, "file"], sep=";", decimal=",", index=False)
    manifest.to_csv(data / "campaigns.csv", sep=";", index=False)
    for name, path in (("clean", raw), ("lab", data)):
        out = tmp_path / f"{name}_out"
        assert main(["calibrate", f"data.path={path}", f"out={out}", "track=false"]) == 0
    for f in (tmp_path / "clean_out" / "parameters").glob("*.parquet"):
        pd.testing.assert_frame_equal(pd.read_parquet(f),
                                      pd.read_parquet(tmp_path / "lab_out" / "parameters" / f.name))


def test_a_pose_not_measured_in_one_campaign_is_its_columns_left_empty(raw, tmp_path, capsys):
    """The validation week without one pose: its columns dropped are refused naming the pose
    and the fix, empty columns (the fix) calibrate that week from the other poses; the training
    week is identified as before.  The empty columns were refused as a logger's unused
    channels, whose fix (data.roles.ignore) was then refused as a pose without columns."""
    pose = json.loads((raw / "volumetric.json").read_text())["poses"][-1]["name"]
    data = _copy(raw, tmp_path / "dropped")
    path = data / "validation_week.parquet"
    df = pd.read_parquet(path)
    gone = [c for c in df.columns if c.startswith(f"E_{pose}_B")]
    df.drop(columns=gone).to_parquet(path)
    refused(["calibrate", f"data.path={data}", f"out={tmp_path / 'o'}", "track=false"], capsys,
            f"pose {pose}", "keeps its columns with empty cells")
    data = _copy(raw, tmp_path / "empty")
    df.loc[:, gone] = np.nan
    df.to_parquet(data / "validation_week.parquet")
    for name, source in (("clean", raw), ("empty", data)):
        assert main(["calibrate", f"data.path={source}", f"out={tmp_path / name}_out",
                     "track=false"]) == 0
    clean, empty = (tmp_path / f"{n}_out" / "parameters" for n in ("clean", "empty"))
    pd.testing.assert_frame_equal(pd.read_parquet(clean / "train_week.parquet"),
                                  pd.read_parquet(empty / "train_week.parquet"))
    assert len(pd.read_parquet(empty / "validation_week.parquet")) == len(df)
