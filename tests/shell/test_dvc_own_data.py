"""`dvc repro` of the study with `conf/data/default.yaml` pointed at a lab's folder of runs, as
docs/dvc.md says: the simulate stage writes the twin's dataset to its own folder, and the study
ingests the lab's runs (their own headers, `;`, decimal commas, wall-clock times) untouched.
Until the simulate stage named its folder it wrote to `data.path`, the lab's, and refused it:
the pipeline could not run on a lab's data at all."""

import pandas as pd
import pytest

from conftest import SHORT_KEYS, copy_project, dvc, set_keys

pytestmark = pytest.mark.slow


def _lab_runs(folder) -> dict:
    """Three short runs as a lab's logger writes them; returns each file's bytes."""
    folder.mkdir()
    for run in range(3):
        start = pd.Timestamp(f"2024-03-0{run + 1} 08:00")
        hours = pd.Series(range(30)) / 6
        frame = pd.DataFrame({
            "Zeit": (start + pd.to_timedelta(hours, unit="h")).dt.strftime("%d.%m.%Y %H:%M:%S"),
            "Spindel [°C]": 21 + 3 * (1 - 0.8 ** hours.index) + run,
            "Bett [°C]": 20.5 + 0.1 * hours,
            "dX [µm]": 4 * (1 - 0.8 ** hours.index) + 0.5 * hours})
        frame.to_csv(folder / f"Lauf_{run + 1}.csv", sep=";", decimal=",", index=False)
    return {f.name: f.read_bytes() for f in folder.iterdir()}


def test_the_study_ingests_a_labs_folder_and_simulates_beside_it(tmp_path):
    dest, env = copy_project(tmp_path / "proj")
    set_keys(dest / "conf/sim/yearround_spindle.yaml", **SHORT_KEYS)
    lab = tmp_path / "lab"
    written = _lab_runs(lab)
    data = dest / "conf/data/default.yaml"              # the lab's path, roles and held-out share
    data.write_text(data.read_text().replace("path: data/raw/${sim_dataset:}", f"path: {lab}", 1))
    set_keys(data, error="[dX]", test_fraction=0.3)
    dvc("repro", "ingest", cwd=dest, env=env)
    assert {f.name: f.read_bytes() for f in lab.iterdir()} == written      # the lab's, untouched
    assert (dest / "data/raw/yearround_spindle/campaigns.csv").is_file()   # the twin's, apart
    manifest = pd.read_csv(dest / "data/interim/default/campaigns.csv")
    assert dict(zip(manifest.campaign, manifest.split)) == {
        "Lauf_1": "train", "Lauf_2": "train", "Lauf_3": "test"}
    run = pd.read_parquet(dest / "data/interim/default" / manifest.file.iloc[0])
    assert {"T_Spindel", "T_Bett", "E_dX"} <= set(run.columns)
