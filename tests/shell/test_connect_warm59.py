"""``connect.warm`` with no row before the joined sample says the restart (deploy59).

restart58's ``connect.warm=<log>`` steps the rows logged before the sample a restarted client
joins.  A log with none before it (kept on another clock, another campaign's, empty) stepped
nothing and said ``warmed ... on 0 row(s)`` at info level, with the ``joined_mid_campaign``
warning left out: the restart went on unwarmed, the operator told it was resumed.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest

from conftest import offline_connection
from test_deploy import ARStub, campaigns
from test_restart58 import _Said
from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.core.compensator import Compensator


@pytest.fixture(scope="module")
def deployed():
    """A model with memory (test_restart58's), and a test campaign."""
    camps = campaigns(0)
    train = {c: camps[c] for c in list(camps)[:4]}
    return StreamingCompensator.from_training(Compensator(ARStub()).fit(train), train), camps["K05"]


@pytest.mark.parametrize("shift_s, kept", [(150000.0, 0), (0.0, None)],
                         ids=["another-clock", "the-campaigns-log"])
def test_a_warm_log_with_no_row_before_the_join_is_said_as_the_restart(deployed, shift_s, kept):
    streaming, campaign = deployed
    cols = list(streaming.columns_)
    rows = campaign[cols + (["time"] if "time" not in cols else [])]
    half = len(rows) // 2
    log = campaign.iloc[:half].assign(time=campaign["time"].iloc[:half] + shift_s)
    conn = offline_connection(copy.deepcopy(streaming), warm=log)
    with _Said("thermocomp.apps.machine.client") as lines:
        conn._step("K05", list(map(float, rows.to_numpy()[half])), half, half)
    events = [e["event"] for e in conn.events]
    if kept == 0:
        assert events[-1] == "joined_mid_campaign" and "warmed" not in events
        assert len(lines) == 1 and "connect.warm has no row logged before this sample" in lines[0]
        assert f"from {log['time'].min():g} to {log['time'].max():g} s" in lines[0]
    else:
        assert events[-1] == "warmed" and lines == []


def test_a_warmed_restart_relearns_the_references_in_the_log(deployed):
    """With ``adapt`` (a probe every few samples), what the bias had learned before the restart
    was lost: the warm-up stepped the stream only.  The log's measured errors, the references the
    client had taken, are relearned as a served session resent from its start relearns them."""
    from thermocomp.apps.deploy.adapt import Adaptation, ReferenceAdapter

    streaming, campaign = deployed
    cols, targets = list(streaming.columns_), list(streaming.targets_)
    probed = campaign.copy()
    off = np.arange(len(probed)) % 7 != 6                     # a reference every 7th sample
    probed.loc[off, targets] = np.nan
    probed[targets] += 3.0                                    # an offset the bias learns
    rows = probed[cols + ["time"] + targets].to_numpy(float)
    half = len(rows) // 2

    def stepped(first: int, warm=None) -> np.ndarray:
        conn = offline_connection(copy.deepcopy(streaming), warm=warm,
                                  adapt=Adaptation(ReferenceAdapter(len(targets), "bias")))
        return np.array([conn._step("K05", list(r), k, k) for k, r in enumerate(rows) if k >= first])

    whole = stepped(0)
    resumed = stepped(half, warm=probed.iloc[:half])
    np.testing.assert_allclose(resumed, whole[half:], atol=1e-9)
