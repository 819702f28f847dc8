"""A deployed compensator restarted mid-campaign (restart58).

A new process holds no stream: the served model started a session it did not hold from a reset
at the block's first row, and ``connect`` a campaign it first saw at its sample 1234 from a reset
there, without a word; a model of changes from a campaign's first sample then misses the warm-up
before the restart (a lag bank on a Swiss lathe's 8 h run: E_X RMSE 26 um after the restart
against 1.3 uninterrupted).  Both now say so, and the served model resumes exactly when the rows
logged since the campaign's start are resent with ``reset``.
"""

from __future__ import annotations

import copy
import logging

import numpy as np
import pandas as pd
import pytest

from conftest import offline_connection
from test_deploy import ARStub, campaigns
from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.deploy.pyfunc import CompensatorModel
from thermocomp.core.compensator import Compensator


class _Said(logging.Handler):
    """The warnings of one logger, whatever the ``thermocomp`` logger's propagation."""

    def __init__(self, name: str):
        super().__init__(logging.WARNING)
        self.lines: list[str] = []
        self.logger = logging.getLogger(name)

    def emit(self, record):
        self.lines.append(record.getMessage())

    def __enter__(self):
        self.logger.addHandler(self)
        return self.lines

    def __exit__(self, *exc):
        self.logger.removeHandler(self)


@pytest.fixture(scope="module")
def deployed():
    camps = campaigns(0)
    train = {c: camps[c] for c in list(camps)[:4]}
    comp = Compensator(ARStub()).fit(train)          # a model with memory: the state matters
    return StreamingCompensator.from_training(comp, train), camps["K05"]


def _server(deployed) -> CompensatorModel:
    """A freshly started server: a new process, no session held."""
    model = CompensatorModel(copy.deepcopy(deployed))
    model.load_context(None)
    return model


def test_a_restarted_server_says_it_does_not_hold_the_session(deployed):
    streaming, campaign = deployed
    half = len(campaign) // 2
    before, after = campaign.iloc[:half], campaign.iloc[half:]
    first = _server(streaming)
    with _Said("thermocomp.apps.deploy.pyfunc") as said:
        first.predict(None, before, {"session": "machine-7", "reset": True})
        whole = pd.concat([first.predict(None, after, {"session": "machine-7"})])
    assert said == []                       # a session started with reset, then held: no word
    restarted = _server(streaming)
    with _Said("thermocomp.apps.deploy.pyfunc") as said:
        cold = restarted.predict(None, after, {"session": "machine-7"})
    assert len(said) == 1 and "'machine-7' is not held by this server" in said[0]
    assert "resend its rows since the campaign's start with reset=true" in said[0]
    assert np.abs(cold["C_Z"].to_numpy() - whole["C_Z"].to_numpy()).max() > 0.1
    # the resume the warning names: the logged rows since the start, with reset, answers as
    # the uninterrupted stream did
    again = _server(streaming)
    with _Said("thermocomp.apps.deploy.pyfunc") as said:
        resumed = again.predict(None, campaign, {"session": "machine-7", "reset": True})
    assert said == []
    np.testing.assert_allclose(resumed.iloc[half:].to_numpy(float), whole.to_numpy(float),
                               atol=1e-12)


@pytest.mark.parametrize("first_sample, said", [(0, False), (-40, False), (1234, True)])
def test_connect_says_it_joined_a_campaign_mid_way(first_sample, said):
    conn = offline_connection()
    with _Said("thermocomp.apps.machine.client") as lines:
        conn._step("B", [20.0, 0.0], 0, first_sample)
        conn._step("B", [20.0, 60.0], 1, first_sample + 1)   # later samples: no more word
    assert bool(lines) is said and len(lines) <= 1
    joined = [e for e in conn.events if e["event"] == "joined_mid_campaign"]
    assert bool(joined) is said
    if said:
        assert "campaign B joined at its sample 1234, not its first" in lines[0]


class _Model:
    def __init__(self, reference: str):
        self.reference = reference


@pytest.mark.parametrize("reference, said", [("first_sample", True), ("none", False)])
def test_a_cut_test_campaign_not_carried_over_is_said(reference, said):
    """A test campaign that continues another (a logger's file rotated) streamed by a model of
    changes from each campaign's first sample starts from a reset: ``replay``, ``monitor``,
    ``promote`` and ``serve`` said nothing (the read had said ``its state is carried over``)."""
    from thermocomp.core.continuation import lead_ins
    from thermocomp.core.io.contract import Dataset

    whole = campaigns(0)["K05"]
    half = len(whole) // 2
    parts = {"A": whole.iloc[:half].reset_index(drop=True),
             "B": whole.iloc[half:].reset_index(drop=True)}
    manifest = pd.DataFrame({"file": ["A.csv", "B.csv"], "split": ["test", "test"],
                             "continues": ["", "A"]}, index=pd.Index(["A", "B"], name="campaign"))
    with _Said("thermocomp") as lines:
        leads = lead_ins(_Model(reference), Dataset(manifest, parts, name="cut"), ["A", "B"])
    assert (list(leads) == ["B"]) is (not said)
    words = [s for s in lines if "B continues A, but the model reads" in s]
    assert bool(words) is said
    if said:
        assert "fit with data.reference=none" in words[0]


def test_connect_restarted_resumes_on_the_rows_logged_before(deployed):
    """``connect.warm``: the rows logged since the campaign's start are stepped before the first
    sample a restarted client joins; it then corrects as the client that never stopped."""
    streaming, campaign = deployed
    cols = list(streaming.columns_)
    rows = campaign[cols + (["time"] if "time" not in cols else [])]
    half = len(rows) // 2

    def stepped(first: int, warm=None) -> np.ndarray:
        stream = copy.deepcopy(streaming)
        conn = offline_connection(stream, warm=warm)
        return np.array([conn._step("K05", list(map(float, r)), k, k)
                         for k, r in enumerate(rows.to_numpy()) if k >= first]), conn

    whole, _ = stepped(0)
    with _Said("thermocomp.apps.machine.client") as lines:
        resumed, conn = stepped(half, warm=campaign.iloc[:half])
    assert lines == [] and [e["event"] for e in conn.events][-1] == "warmed"
    np.testing.assert_allclose(resumed, whole[half:], atol=1e-12)
    cold, _ = stepped(half)
    assert np.abs(cold - whole[half:]).max() > 0.1


def test_a_serving_process_logs_its_warnings_as_thermocomp_does(deployed, monkeypatch, capsys):
    # a fresh serving process has no thermocomp handler: the warning was a bare stderr line
    # (Python's last resort), not "[thermocomp] warning: ..." (lead58)
    root = logging.getLogger("thermocomp")
    monkeypatch.setattr(root, "handlers", [])
    monkeypatch.setattr(root, "propagate", True)
    streaming, campaign = deployed
    _server(streaming).predict(None, campaign.iloc[10:], {"session": "machine-9"})
    err = capsys.readouterr().err
    assert "[thermocomp] warning: " in err and "'machine-9' is not held by this server" in err
