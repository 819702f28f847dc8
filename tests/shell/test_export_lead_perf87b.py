"""The conformance pack streams a lead-in shared by campaigns once (perf87b): a test campaign and
the copies it plants faults on start from a copy of the states the lead-in left (and, ci101, the
source's rows before the plant), in the served model and in the numpy model of the code, and the
pack is the one each whole stream gives."""

from __future__ import annotations

import pytest

from test_export import adaptive_mlr
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.deploy.export import pack as pack_module
from thermocomp.apps.deploy.export.pack import conformance_pack


@pytest.fixture(scope="module")
def continued(tmp_path_factory):
    """``(adaptive MLR, its system with the monitor, {test campaign}, {its lead-in})``: the test
    campaign continuing its own rows backwards (ending a sample before its first row where it
    starts: the train campaigns joined jump from one to the next, which the monitor acts on)."""
    deployed, ds, test_ids = adaptive_mlr(tmp_path_factory.mktemp("lead87b") / "data")
    cid = test_ids[0]
    campaign = ds.campaigns[cid].reset_index(drop=True)
    t = campaign["time"].to_numpy(float)
    lead = campaign.iloc[::-1].reset_index(drop=True)
    lead["time"] = t[0] - (t[-1] - t[::-1]) - (t[1] - t[0])
    lead.attrs = dict(campaign.attrs)
    return deployed, state_space(deployed, monitor=True), {cid: ds.campaigns[cid]}, {cid: lead}


def _counted(monkeypatch, cls, name):
    calls = []
    step = getattr(cls, name)

    def counted(self, *args):
        calls.append(1)
        return step(self, *args)

    monkeypatch.setattr(cls, name, counted)
    return calls


def test_the_lead_in_is_streamed_once_and_the_pack_is_the_whole_streams(continued, monkeypatch):
    deployed, ss, campaigns, lead_ins = continued
    served = _counted(monkeypatch, type(deployed), "_step")
    simulated = _counted(monkeypatch, Simulator, "step")
    files, summary = conformance_pack(deployed, ss, campaigns, lead_ins)
    entries = summary["campaigns"]
    lead = len(next(iter(lead_ins.values())))
    rows = len(next(iter(campaigns.values())))
    # (deploy89) the campaign from a cold start too: its own rows, no lead-in to share
    cold = [e for e in entries if "cold_start" in e]
    entries = [e for e in entries if "cold_start" not in e]
    assert [e["lead_in_rows"] for e in cold] == [0]
    assert len(entries) > 2 and {e["lead_in_rows"] for e in entries} == {lead}   # copies planted
    # the lead-in's rows once and, a planted copy being its source up to the plant (from the
    # middle row on, watch.planted), the source's rows before it once (ci101); each campaign's
    # rows after that once (none cut before its stream); the cold start whole
    half = rows // 2
    assert len(served) == lead + half + len(entries) * (rows - half) + rows
    assert len(simulated) == lead + half + sum(e["rows"] - lead - half for e in entries) + rows
    # the whole stream per campaign, as before: the same files to the byte
    before = len(served)
    monkeypatch.setattr(pack_module._Lead, "fits", lambda self, frame: False)
    whole = conformance_pack(deployed, ss, campaigns, lead_ins)
    assert len(served) - before == lead + half + len(entries) * (lead + rows) + rows  # (the prefix)
    assert whole[0] == files and whole[1] == summary
    for e in entries:
        text = files[f"{e['folder']}/rows.csv"]
        assert text.count("\n") == 1 + e["rows"]          # the lead-in's rows in each rows.csv
