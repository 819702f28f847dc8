"""A lab's artefact measurements as its software exports them (session 66, volstranger66):
the distance deviations in mm under their contract names (``E_S2x1d1_B01_B02 [mm]``), ``;`` and
decimal commas, and the temperatures of a separate logger beside them."""

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
    """A small record of a lab's set-up: 5 balls at 15°, the diagonals only (S2+S3), new seed."""
    gen = LargeMillVolumetric(train_hours=3.0, test_hours=2.0, n_balls=5, length_mm=1000.0,
                              misalignment_deg=15.0, sets=("S2", "S3"), seed=6621)
    return simulated(gen, tmp_path_factory.mktemp("vs66") / "raw")


def lab_files(raw, dest, unit_mm: bool) -> list[str]:
    """``raw`` as CSV, ``;`` and decimal commas, the distances to 0.1 µm: in mm under headers
    saying so (``unit_mm``), or in µm under the contract's names; returns the E_ names."""
    dest.mkdir()
    shutil.copy(raw / "volumetric.json", dest / "volumetric.json")
    manifest = pd.read_csv(raw / "campaigns.csv")
    for _, row in manifest.iterrows():
        df = pd.read_parquet(raw / row["file"])
        e = [c for c in df.columns if c.startswith("E_")]
        df[e] = df[e].round(1)
        if unit_mm:
            df[e] = df[e] / 1000.0
            df = df.rename(columns={c: f"{c} [mm]" for c in e})
        df.to_csv(dest / f"{row['campaign']}.csv", sep=";", decimal=",", index=False,
                  float_format="%.6f")
    manifest.assign(file=[f"{c}.csv" for c in manifest["campaign"]]).to_csv(
        dest / "campaigns.csv", index=False)
    return e


def cycle_files(raw, folder) -> str:
    """An artefact software's file per cycle (a header block, then pose; ball i; ball j;
    deviation in mm) of ``raw``'s first three cycles; returns the first pose."""
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
    return e[0].split("_")[1]


def calibrated(data, out) -> dict:
    assert main(["calibrate", f"data.path={data}", f"out={out}", "track=false"]) in (0, None)
    return {cid: df for cid, df in io.read_dataset(out / "parameters")[0].campaigns.items()}


def test_distances_in_mm_under_their_contract_names_calibrate_as_in_um(raw, tmp_path):
    # a header 'E_S2x1d1_B01_B02 [mm]' was refused without data.roles ('not a prefix plus an
    # identifier-like name ... map it with data.columns', one mapping per distance column),
    # though a contract name with a unit reads as that name, converted (docs/data-format.md)
    lab_files(raw, tmp_path / "mm", unit_mm=True)
    lab_files(raw, tmp_path / "um", unit_mm=False)
    in_mm = calibrated(tmp_path / "mm", tmp_path / "out_mm")
    in_um = calibrated(tmp_path / "um", tmp_path / "out_um")
    assert list(in_mm) == list(in_um)
    for cid in in_um:
        assert list(in_mm[cid].columns) == list(in_um[cid].columns)
        e = [c for c in in_um[cid].columns if c.startswith("E_")]
        assert len(e) > 10
        assert np.allclose(in_mm[cid][e].to_numpy(), in_um[cid][e].to_numpy(), rtol=1e-9, atol=1e-9)
    report = json.loads((tmp_path / "out_mm" / "calibration.json").read_text())
    assert report["campaigns"] == json.loads(
        (tmp_path / "out_um" / "calibration.json").read_text())["campaigns"]


def test_a_logger_file_beside_the_distances_names_a_few_of_them_not_every_one(raw, tmp_path, capsys):
    # the refusal of a folder of two loggers (the temperatures in one file, the artefact's
    # distances in another) listed every distance column: 4 poses x 10 distances here, 420 on
    # a lab's 7-ball bar in 20 poses (7,973 characters in one line)
    folder = tmp_path / "lab"
    folder.mkdir()
    shutil.copy(raw / "volumetric.json", folder / "volumetric.json")
    df = pd.read_parquet(raw / "train_week.parquet")
    e = [c for c in df.columns if c.startswith("E_")]
    t = [c for c in df.columns if c.startswith("T_")]
    df[["time", *e]].to_csv(folder / "artefakt.csv", index=False)
    df[["time", *t]].to_csv(folder / "logger.csv", index=False)
    line = refused(["calibrate", f"data.path={folder}", f"out={tmp_path / 'out'}", "track=false"],
                   capsys, "logger.csv: no E_ column, and artefakt.csv beside it holds errors",
                   f"{', '.join(e[:5])} and {len(e) - 5} more) without a temperature",
                   "join them into one file first")
    assert e[5] not in line
    assert not (tmp_path / "out").exists()


def test_init_reads_a_volumetric_folder_as_calibrate_does(raw, tmp_path, capsys):
    # a ball not probed in a few cycles of one pose (its distances empty) is calibrated from
    # the others; init refused it as a gap longer than data.max_gap_samples, 'refused here as
    # run would refuse it', and run takes it
    lab_files(raw, tmp_path / "lab", unit_mm=True)
    f = tmp_path / "lab" / "train_week.csv"
    df = pd.read_csv(f, sep=";", decimal=",")
    gone = [c for c in df.columns if c.startswith("E_S2x1d1_") and "B02" in c]
    assert len(gone) == 4
    df.loc[3:6, gone] = np.nan
    df.to_csv(f, sep=";", decimal=",", index=False, float_format="%.6f")
    assert main(["init", str(tmp_path / "lab"), f"out={tmp_path / 'init'}"]) in (0, None)
    config = tmp_path / "init" / "conf" / "data" / "lab.yaml"
    assert config.is_file()
    out = capsys.readouterr().out
    assert "next: thermocomp run" in out
    # what init wrote reads the folder as calibrate reads it
    searchpath = f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]"
    assert main(["calibrate", searchpath, "data=lab", f"out={tmp_path / 'cal'}", "track=false"]) in (0, None)
    report = json.loads((tmp_path / "cal" / "calibration.json").read_text())
    assert report["n_cycles"] == len(df) + len(pd.read_csv(tmp_path / "lab" / "validation_week.csv", sep=";"))


def test_an_export_of_one_distance_per_row_is_refused_saying_the_layout(raw, tmp_path, capsys):
    # an artefact software's file per cycle (a header block, then pose; ball i; ball j;
    # deviation) was refused as 'Pose' and three more columns without a role, pointing at
    # data.roles for a layout no role reads
    folder = tmp_path / "cycles"
    pose = cycle_files(raw, folder)
    refused(["calibrate", f"data.path={folder}", f"out={tmp_path / 'out'}", "track=false"], capsys,
            "zyklus_001.csv, line 6: one distance per row", f"pose {pose!r} in a cell",
            "one measurement cycle per row", f"E_{pose}_B01_B02 [mm]")
    assert not (tmp_path / "out").exists()


def test_init_writes_no_pattern_per_contract_name_with_a_unit_and_reads_the_same(raw, tmp_path,
                                                                                  capsys):
    # init wrote every distance's name into data.roles.error (200 here, 420 on a 7-ball bar
    # in 20 poses), though such a header reads as its name without any pattern
    e = lab_files(raw, tmp_path / "lab", unit_mm=True)
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
    pose = cycle_files(raw, folder)
    said = refused(["calibrate", f"data.path={folder}", f"out={tmp_path / 'cal'}",
                    "track=false"], capsys, "zyklus_001.csv, line 6: one distance per row")
    line = refused(["init", str(folder), f"out={tmp_path / 'init'}"], capsys,
                   "zyklus_001.csv, line 6: one distance per row", f"pose {pose!r} in a cell",
                   "one measurement cycle per row", f"E_{pose}_B01_B02 [mm]")
    assert line == said
    assert not (tmp_path / "init").exists()
