"""The served streams a pack makes, handed to the next pack of the same model (ci99): a second pack
streams the served model over no row it streamed already and is the pack made without them, to
the byte; the caller's own stream of a campaign is the pack's; a frame changed in place is a new
stream (entries keyed on the rows' content, not on the frame object).  The record is
test_export_lead_perf87b's (a test campaign after a lead-in, its planted copies sharing it)."""

from __future__ import annotations

import numpy as np

from test_export_cmon85 import without
from test_export_lead_perf87b import _counted, continued  # noqa: F401  (the module's fixture)
from thermocomp.apps.deploy.export.pack import conformance_pack, fed
from thermocomp.apps.deploy.export.served import ServedStreams


def test_a_second_pack_streams_no_served_row_again_and_is_the_pack_made_alone(continued,  # noqa: F811
                                                                             monkeypatch):
    deployed, ss, campaigns, lead_ins = continued
    (cid, campaign), = campaigns.items()
    frame = fed(campaign, lead_ins[cid])
    streams = ServedStreams(deployed)
    steps = _counted(monkeypatch, type(deployed), "_step")
    mine = streams.rows(frame, cid)                            # the caller's stream first
    assert len(steps) == len(frame)
    files, summary = conformance_pack(deployed, ss, campaigns, lead_ins, served=streams)
    entries = [e for e in summary["campaigns"] if "cold_start" not in e]
    assert len(entries) > 2                                    # copies planted on the lead-in
    # the lead-in and the campaign's rows before the plant once (ci101), each planted copy's rows
    # after it, the cold start: the campaign's own rows are the caller's stream (not stepped again)
    lead, rows = len(lead_ins[cid]), len(campaign)
    half = rows // 2
    assert len(steps) - len(frame) == lead + half + (len(entries) - 1) * (rows - half) + rows
    assert streams.y(frame, lambda: None) is mine.y
    old = without(ss, "blind_jump")
    before = len(steps)
    again = conformance_pack(deployed, old, campaigns, lead_ins, served=streams)
    assert len(steps) == before                                # nothing served streamed again
    assert again == conformance_pack(deployed, old, campaigns, lead_ins)    # the pack alone's
    assert (files, summary) == conformance_pack(deployed, ss, campaigns, lead_ins)


def test_a_frame_changed_in_place_is_streamed_anew(continued, monkeypatch):  # noqa: F811
    deployed, _, campaigns, _ = continued
    (cid, campaign), = campaigns.items()
    frame = campaign.reset_index(drop=True).copy()
    streams = ServedStreams(deployed)
    first = streams.rows(frame, cid).y
    assert streams.rows(frame, cid).y is first                 # equal rows: the same stream
    steps = _counted(monkeypatch, type(deployed), "_step")
    name = next(c for c in deployed.columns_ if c != "time")
    frame.loc[len(frame) // 2:, name] += 1.0                    # the same object, other rows
    changed = streams.rows(frame, cid).y
    assert len(steps) == len(frame)
    assert not np.array_equal(changed, first)
    np.testing.assert_array_equal(changed, ServedStreams(deployed).rows(frame, cid).y)
