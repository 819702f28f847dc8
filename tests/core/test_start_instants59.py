"""The manifest's ``start`` read by one rule (``core/io/instants.py``) wherever campaigns are
ordered or joined by it: a start with an offset and one without compare in UTC, an empty start
is not known, a day-first start is refused naming its row."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.core import io
from thermocomp.core.continuation import predecessors
from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.instants import start_instants
from thermocomp.core.scoring.evaluation import holdout_scheme

PERIOD = 60.0


def _folder(root, campaigns: dict) -> None:
    """``campaigns``: id -> (split, start cell, first timestamp of an ISO-timed file or None
    for a file timed in seconds, rows)."""
    rng = np.random.default_rng(0)
    rows = []
    for cid, (split, start, stamped, n) in campaigns.items():
        temp = np.cumsum(rng.normal(0, 0.1, n)) + 20
        frame = pd.DataFrame({"time": np.arange(n) * PERIOD, "T_a": temp,
                              "E_Z": 2 * temp + rng.normal(0, 0.1, n)})
        if stamped:
            times = pd.Timestamp(stamped) + pd.to_timedelta(frame["time"], unit="s")
            frame["time"] = [t.isoformat() for t in times]
        frame.to_csv(root / f"{cid}.csv", index=False)
        rows.append({"campaign": cid, "file": f"{cid}.csv", "split": split, "start": start})
    pd.DataFrame(rows).to_csv(root / "campaigns.csv", index=False)


def test_one_rule_for_a_start_with_an_offset_one_without_and_an_empty_one():
    cells = pd.Series(["2026-01-01T01:00:00+01:00", "2026-01-01T00:00:00", "", None, np.nan,
                       pd.Timestamp("2026-01-01T00:00:00Z")], index=list("abcdef"), dtype=object)
    got = start_instants(cells)
    assert got.dtype == "datetime64[ns, UTC]" and list(got.index) == list("abcdef")
    assert got["a"] == got["b"] == got["f"] == pd.Timestamp("2026-01-01T00:00:00Z")
    assert got[["c", "d", "e"]].isna().all()
    with pytest.raises(ContractError, match=r"data row 2: start '28.11.2026 13:05' is not an "
                                            r"ISO 8601 time"):
        start_instants(pd.Series(["2026-11-28T13:05", "28.11.2026 13:05"]))


def test_a_record_cut_with_a_naive_start_continued_by_a_file_stamped_with_its_offset(tmp_path):
    """A's start written without an offset, B's empty and filled from its timestamps
    (``+00:00``): B starts one period after A ends, so it continues A (the carry-over gave up
    on the mixed column and saw two campaigns)."""
    _folder(tmp_path, {"A": ("train", "2026-01-01T00:00:00", None, 180),
                       "B": ("test", "", "2026-01-01T03:00:00+00:00", 20),
                       "C": ("test", "", "2026-01-01T04:00:00+00:00", 20)})
    ds, _ = io.read_dataset(tmp_path)
    assert predecessors(ds) == {"B": "A"}


def test_the_holdout_is_ordered_by_the_same_instants(tmp_path):
    """The test campaign, dated by its file's timestamps with an offset, came before the train
    ones dated without: held out among them, not after them (the manifest's order)."""
    _folder(tmp_path, {"K1": ("train", "2026-01-02T00:00:00", None, 20),
                       "K2": ("train", "2026-01-03T00:00:00", None, 20),
                       "K3": ("test", "", "2026-01-01T00:00:00+01:00", 20)})
    ds, _ = io.read_dataset(tmp_path)
    assert holdout_scheme(ds) == "interleaved"


def test_an_empty_start_leaves_the_manifest_order_and_no_carry_over(tmp_path):
    _folder(tmp_path, {"K1": ("train", "2026-01-03T00:00:00", None, 20),
                       "K2": ("train", "2026-01-02T00:00:00+00:00", None, 20),
                       "K3": ("test", "", None, 20)})
    ds, _ = io.read_dataset(tmp_path)
    assert holdout_scheme(ds) == "forward" and predecessors(ds) == {}


def test_the_last_campaigns_held_out_by_the_same_instants(tmp_path):
    """``data.test_fraction`` holds out the latest campaign: K1's start one hour before K2's
    once its offset is read, K3 dated by its file (with an offset) the latest."""
    _folder(tmp_path, {"K1": ("train", "2026-01-02T01:30:00+02:00", None, 20),
                       "K2": ("train", "2026-01-02T00:00:00", None, 20),
                       "K3": ("train", "", "2026-01-02T02:00:00+01:00", 20)})
    (tmp_path / "campaigns.csv").write_text(
        pd.read_csv(tmp_path / "campaigns.csv", keep_default_na=False)
        .drop(columns="split").to_csv(index=False))
    ds, _ = io.read_dataset(tmp_path, {"test_fraction": 0.34})
    assert ds.ids("test") == ["K3"]
    ds, _ = io.read_dataset(tmp_path, {"test_fraction": 0.67})
    assert ds.ids("test") == ["K2", "K3"]


def test_a_day_first_start_is_refused_naming_its_row(tmp_path):
    _folder(tmp_path, {"K1": ("train", "2026-01-02T00:00:00", None, 20),
                       "K2": ("test", "03.01.2026 00:00", None, 20)})
    with pytest.raises(ContractError, match=r"column 'start', data row 2: start "
                                            r"'03.01.2026 00:00' is not an ISO 8601 time"):
        io.read_dataset(tmp_path)
