"""A folder whose manifest lists one campaign (a simulated one-record machine, edm65's: audit99)
with ``data.test_fraction``: refused saying "lower data.test_fraction", which no fraction obeys
(each held-out split takes a whole campaign); it names the campaign's file to give instead, as
a folder of one file without a manifest does (vol57)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from conftest import refused
from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.record import hold_out


def _one_record_folder(folder):
    folder.mkdir()
    t = np.arange(200) * 60.0
    temp = 20 + 2 * np.sin(t / 3000)
    pd.DataFrame({"time": t, "T_spindle": temp, "E_Z": 3 * (temp - 20)}).to_csv(
        folder / "record.csv", index=False)
    (folder / "campaigns.csv").write_text("campaign,file,split,start\n"
                                          "record,record.csv,train,2027-06-07T00:00\n")
    return folder


@pytest.mark.parametrize("fraction", ["0.25", "0.01"])
def test_a_manifest_of_one_campaign_names_its_file(tmp_path, capsys, fraction):
    folder = _one_record_folder(tmp_path / "sim")
    line = refused(["ingest", f"data.path={folder}", f"data.test_fraction={fraction}",
                    "track=false"], capsys, f"data.path={folder / 'record.csv'}", "campaigns.csv")
    assert "lower data.test_fraction" not in line


def test_two_campaigns_for_test_and_val_are_too_few_whatever_the_fractions(tmp_path):
    manifest = pd.DataFrame({"file": ["a.csv", "b.csv"], "split": ["train", "train"]},
                            index=pd.Index(["a", "b"], name="campaign"))
    opts = SimpleNamespace(test_fraction=0.01, val_fraction=0.01, split_order=["train", "val", "test"],
                           split_overrides=None)
    with pytest.raises(ContractError, match="2 train campaign.s. are too few .* val, test") as got:
        hold_out(manifest, opts, tmp_path)
    assert "lower" not in str(got.value)
