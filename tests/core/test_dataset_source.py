"""One dataset source: ``io`` opens a dataset for a batch or a stream with its digest, a
volumetric folder is an adapter calibrated once per digest, and the stages read ``data.path``
through one shell function (issue 35, item 2)."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused, simulated
from test_hostile import edit_csv, make_dataset
from thermocomp.base.files import folder_digest
from thermocomp.base.log import logger
from thermocomp.core.io import ContractError
from thermocomp.core.io.source import open_dataset

GAPS = {"max_gap_samples": 2}


def _blank(root, cid, column, rows):
    edit_csv(root / f"{cid}.csv", lambda df: df.__setitem__(column, df[column].where(
        ~df.index.isin(rows))))


def test_the_digest_is_the_folders_and_follows_its_bytes(tmp_path):
    root = make_dataset(tmp_path / "ds")
    ds = open_dataset(root)
    assert ds.meta["digest"] == folder_digest(root)     # the run's dataset_hash tag: one definition
    assert ds.meta["read_report"]["rows"] == sum(len(df) for df in ds.campaigns.values())
    edit_csv(root / "K02.csv", lambda df: df.__setitem__("E_X", df["E_X"] + 1e-3))
    assert open_dataset(root).meta["digest"] != ds.meta["digest"]


def test_a_stream_keeps_the_test_gaps_and_repairs_the_train_ones(tmp_path):
    root = make_dataset(tmp_path / "ds")
    _blank(root, "K01", "T_0", [10, 11])    # train: repaired within max_gap_samples
    _blank(root, "K04", "T_0", [7])         # test: streamed as the machine saw it
    batch, stream = open_dataset(root, GAPS), open_dataset(root, GAPS, stream=True)
    assert not batch.campaigns["K04"]["T_0"].isna().any()
    assert np.isnan(stream.campaigns["K04"]["T_0"].iloc[7])
    assert stream.meta["missing"] == {"K04": {"T_0": 1}}
    assert not stream.campaigns["K01"]["T_0"].isna().any()
    np.testing.assert_allclose(stream.campaigns["K01"]["T_0"], batch.campaigns["K01"]["T_0"])
    # a train gap beyond what may be repaired is refused, naming the campaign and the column
    _blank(root, "K02", "T_amb", [5, 6, 7])
    with pytest.raises(ContractError, match="train campaign K02") as err:
        open_dataset(root, GAPS, stream=True)
    assert err.value.column == "T_amb"


@pytest.fixture(scope="module")
def volumetric(tmp_path_factory):
    from thermocomp.apps.sim.volumetric import LargeMillVolumetric

    return simulated(LargeMillVolumetric(train_hours=4.0, test_hours=2.0, seed=3),
                     tmp_path_factory.mktemp("vol") / "raw")


SETTINGS = {"outlier_z": 6.0, "column_share": 0.5, "require_seen": ["positioning", "straightness"],
            "prior": None}


def test_a_volumetric_folder_is_calibrated_once_per_digest_and_keeps_its_calibration(
        volumetric, monkeypatch, tmp_path):
    import shutil

    from thermocomp.apps.volumetric import source

    calls = []
    real = source.calibrate_folder
    monkeypatch.setattr(source, "calibrate_folder", lambda *a, **k: calls.append(a) or real(*a, **k))
    monkeypatch.setattr(source, "_CACHE", {})
    first = source.open_volumetric(volumetric, {}, SETTINGS)
    again = source.open_volumetric(volumetric, {}, SETTINGS)
    assert len(calls) == 1
    cal = first.meta["calibrator"]
    # the parameter series, with the calibration that identified them in its metadata
    assert [c for c in first.columns if c.startswith("E_")] == cal.names_
    assert sorted(first.meta["calibration"]["parameters"]) == sorted(cal.names_)
    assert first.meta["digest"] == folder_digest(volumetric)
    assert {c for c in first.meta["distances"].columns if c.startswith("E_")} >= set(
        cal.design_.columns)
    # a copy: what one caller changes, the next does not see
    again.campaigns.pop(again.ids()[0])
    assert len(source.open_volumetric(volumetric, {}, SETTINGS).campaigns) == len(first.campaigns)
    # other settings or other bytes: calibrated again
    source.open_volumetric(volumetric, {}, {**SETTINGS, "outlier_z": 4.0})
    assert len(calls) == 2
    # a ball off its certificate in every cycle: left out, and said each time it is opened
    copy = shutil.copytree(volumetric, tmp_path / "raw")
    column = sorted(cal.design_.columns)[0]
    for f in pd.read_csv(copy / "campaigns.csv")["file"]:
        df = pd.read_parquet(copy / f)
        df[column] += 1000.0
        df.to_parquet(copy / f, index=False)
    said = []
    handler = logging.Handler()
    handler.emit = lambda r: said.append(r.getMessage())
    logger.addHandler(handler)
    try:
        excluded = [[e["column"] for e in source.open_volumetric(copy, {}, SETTINGS)
                     .meta["calibration"]["excluded"]] for _ in range(2)]
    finally:
        logger.removeHandler(handler)
    assert len(calls) == 3 and excluded == [[column], [column]]
    warned = [m for m in said if "flagged in more than" in m]
    assert len(warned) == 2 and column in warned[0] and warned[0] == warned[1]


def test_run_and_replay_read_the_data_path_through_the_one_source(tmp_path, monkeypatch):
    from thermocomp.shell import source
    from thermocomp.shell.cli import main

    root = make_dataset(tmp_path / "ds")
    opened = []
    real = source.open_dataset
    monkeypatch.setattr(source, "open_dataset",
                        lambda *a, **k: opened.append(k.get("stream", False)) or real(*a, **k))
    args = [f"data.path={root}", f"out={tmp_path / 'out'}", "data.reference=auto", *FAST]
    assert main(["run", *args]) == 0
    assert main(["replay", *args, f"replay.model={tmp_path / 'out' / 'model.pkl'}",
                 f"out={tmp_path / 'replay'}"]) == 0
    assert opened == [False, True]      # once each: a batch for run, a stream for replay


@pytest.mark.parametrize("stage", ["train", "evaluate"])
def test_a_stage_refuses_an_ingest_of_data_that_changed_since(paths, tmp_path, capsys, stage):
    # before, ingest recorded data.path's name and options only: a corrected file in the same
    # folder was trained and scored from the stale ingest, exit 0 and no word of it
    from thermocomp.shell.cli import main

    args = [*paths["args"], f"data.processed={tmp_path / 'processed'}"]
    assert main(["ingest", *args]) == 0 and main(["train", *args]) == 0
    edit_csv(paths["ds"] / "K02.csv", lambda df: df.__setitem__("E_X", df["E_X"] * 2))
    refused([stage, *args], capsys, "ingest_report.json", "changed since it was ingested",
            "run `thermocomp ingest` with this config first")
    assert main(["ingest", *args]) == 0     # ingested again: read (by a model trained on it)
    assert stage == "train" or main(["train", *args]) == 0
    assert main([stage, *args]) == 0
