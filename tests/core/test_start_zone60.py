"""A manifest ``start`` written without an offset is on ``data.timezone``'s clock, as a file's
timestamps without one are: a campaign dated by the manifest and one dated by its file's first
stamp compare on one clock (before: the manifest's read as UTC, the file's as local time)."""

from __future__ import annotations

import pandas as pd

from test_start_instants59 import _folder
from thermocomp.core import io
from thermocomp.core.continuation import predecessors
from thermocomp.core.io.instants import start_instants

BERLIN = {"timezone": "Europe/Berlin"}


def test_a_naive_start_is_an_instant_on_the_zone_given():
    got = start_instants(pd.Series(["2026-07-01T08:00:00", "2026-07-01T08:00:00+00:00"]),
                         zone="Europe/Berlin")
    assert list(got) == [pd.Timestamp("2026-07-01T06:00:00Z"), pd.Timestamp("2026-07-01T08:00:00Z")]


def test_the_latest_campaign_on_the_local_clock_is_held_out(tmp_path):
    """K1 dated in the manifest at 08:00, K2 by its file at 09:30, both Berlin time (summer:
    UTC+2): K2 is the later; with K1's start read as UTC (08:00Z) K2 (07:30Z) came first and
    K1, the earlier run, was held out as the test."""
    _folder(tmp_path, {"K1": ("train", "2026-07-01T08:00:00", None, 20),
                       "K2": ("train", "", "2026-07-01T09:30:00", 20)})
    (tmp_path / "campaigns.csv").write_text(
        pd.read_csv(tmp_path / "campaigns.csv", keep_default_na=False)
        .drop(columns="split").to_csv(index=False))
    ds, _ = io.read_dataset(tmp_path, {**BERLIN, "test_fraction": 0.5})
    assert ds.ids("test") == ["K2"]


def test_a_record_cut_in_two_continues_on_the_local_clock(tmp_path):
    """A: 3 h from 06:00 Berlin (manifest, no offset); B's file starts at 09:00 Berlin, one
    period after A's last row: B continues A (with A's start read as 06:00Z, B began 2 h
    before A ended: no continuation)."""
    _folder(tmp_path, {"A": ("train", "2026-07-01T06:00:00", None, 180),
                       "B": ("test", "", "2026-07-01T09:00:00", 20)})
    ds, _ = io.read_dataset(tmp_path, BERLIN)
    assert predecessors(ds) == {"B": "A"}
