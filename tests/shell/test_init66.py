"""init's leftovers from session 66's stranger passes (init66): a volumetric export's distances
under their contract names with a unit written as no pattern each, the one-distance-per-row
export refused by init as calibrate refuses it."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest
import yaml

from conftest import refused, simulated
from thermocomp.apps.sim.volumetric import LargeMillVolumetric
from thermocomp.core import io
from thermocomp.shell.cli import main


@pytest.fixture(scope="module")
def raw(tmp_path_factory):
    """A small volumetric record: 5 balls at 15°, the diagonals only (S2+S3)."""
    gen = LargeMillVolumetric(train_hours=3.0, test_hours=2.0, n_balls=5, length_mm=1000.0,
                              misalignment_deg=15.0, sets=("S2", "S3"), seed=6621)
    return simulated(gen, tmp_path_factory.mktemp("init66") / "raw")


def lab_files(raw, dest) -> list[str]:
    """``raw`` as a lab's software writes it: ``;``, decimal commas, the distances in mm under
    their contract names with the unit (``E_S2x1d1_B01_B02 [mm]``); returns the E_ names."""
    dest.mkdir()
    shutil.copy(raw / "volumetric.json", dest / "volumetric.json")
    manifest = pd.read_csv(raw / "campaigns.csv")
    for _, row in manifest.iterrows():
        df = pd.read_parquet(raw / row["file"])
        e = [c for c in df.columns if c.startswith("E_")]
        df[e] = df[e].round(1) / 1000.0
        df.rename(columns={c: f"{c} [mm]" for c in e}).to_csv(
            dest / f"{row['campaign']}.csv", sep=";", decimal=",", index=False,
            float_format="%.6f")
    manifest.assign(file=[f"{c}.csv" for c in manifest["campaign"]]).to_csv(
        dest / "campaigns.csv", index=False)
    return e


def test_init_writes_no_pattern_per_contract_name_with_a_unit_and_reads_the_same(raw, tmp_path,
                                                                                  capsys):
    # init wrote every distance's name into data.roles.error (200 here, 420 on a 7-ball bar
    # in 20 poses), though such a header reads as its name without any pattern
    e = lab_files(raw, tmp_path / "lab")
    assert main(["init", str(tmp_path / "lab"), f"out={tmp_path / 'init'}"]) in (0, None)
    assert f"{len(e)} contract names with a unit" in capsys.readouterr().out
    conf = tmp_path / "init" / "conf" / "data"
    short = yaml.safe_load((conf / "lab.yaml").read_text())
    assert short["roles"]["error"] == []
    # the long config (each distance a pattern, as init wrote it) reads and calibrates the same
    long = {**short, "roles": {**short["roles"], "error": list(e)}}
    (conf / "long.yaml").write_text(yaml.safe_dump(long, sort_keys=False))
    plain = {k: v for k, v in short.items() if k != "defaults"}
    a = io.read_dataset(tmp_path / "lab", plain)[0]
    b = io.read_dataset(tmp_path / "lab", {**plain, "roles": long["roles"]})[0]
    assert a.ids() == b.ids()
    for cid in a.ids():
        pd.testing.assert_frame_equal(a.campaigns[cid], b.campaigns[cid])
    searchpath = f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]"
    out = {}
    for name in ("lab", "long"):
        assert main(["calibrate", searchpath, f"data={name}", f"out={tmp_path / ('cal_' + name)}",
                     "track=false"]) in (0, None)
        out[name] = io.read_dataset(tmp_path / f"cal_{name}" / "parameters")[0]
    assert json.loads((tmp_path / "cal_lab" / "calibration.json").read_text())["campaigns"] == \
        json.loads((tmp_path / "cal_long" / "calibration.json").read_text())["campaigns"]
    for cid in out["long"].ids():
        x, y = out["lab"].campaigns[cid], out["long"].campaigns[cid]
        assert list(x.columns) == list(y.columns)
        assert np.array_equal(x.to_numpy(float), y.to_numpy(float), equal_nan=True)


def test_init_refuses_one_distance_per_row_as_calibrate_does(raw, tmp_path, capsys):
    # an artefact software's file per cycle (a header block, then pose; ball i; ball j;
    # deviation): calibrate named the layout the reader takes, init said "no 'time' column"
    folder = tmp_path / "cycles"
    folder.mkdir()
    shutil.copy(raw / "volumetric.json", folder / "volumetric.json")
    df = pd.read_parquet(raw / "train_week.parquet")
    e = [c for c in df.columns if c.startswith("E_")]
    for k in range(3):
        rows = [f"{c.split('_')[1]};{int(c.split('_')[2][1:])};{int(c.split('_')[3][1:])};"
                f"{df[c].iloc[k] / 1000:.4f}".replace(".", ",") for c in e]
        (folder / f"zyklus_{k + 1:03d}.csv").write_text(
            "Messprogramm;Kugelplatte\nDatum;24.03.2023\nEinheit;mm\n\n"
            "Pose;Kugel i;Kugel j;Abweichung [mm]\n" + "\n".join(rows) + "\n")
    pose = e[0].split("_")[1]
    said = refused(["calibrate", f"data.path={folder}", f"out={tmp_path / 'cal'}",
                    "track=false"], capsys, "zyklus_001.csv, line 6: one distance per row")
    line = refused(["init", str(folder), f"out={tmp_path / 'init'}"], capsys,
                   "zyklus_001.csv, line 6: one distance per row", f"pose {pose!r} in a cell",
                   "one measurement cycle per row", f"E_{pose}_B01_B02 [mm]")
    assert line == said
    assert not (tmp_path / "init").exists()


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
