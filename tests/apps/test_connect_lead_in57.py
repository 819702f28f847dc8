"""`connect` names the lead-in of a continuing campaign (deploy57).

The twin serves a test campaign that continues the train record after the train rows, under the
test campaign's name with negative sample numbers; `connect` logged "campaign messung_test from
its sample -2959", a negative sample a user cannot read.  It now says what those samples are.
"""

from __future__ import annotations

import numpy as np

from thermocomp.apps.machine.client import Connection


class _Stream:
    columns_ = ["T_a"]

    def reset(self):
        pass

    def step(self, x, t):
        return np.zeros(1)


class _Limiter:
    def new_campaign(self):
        pass


def _first_event(i: int) -> str:
    conn = Connection(_Stream(), None, "opc.tcp://127.0.0.1:1", _Limiter())
    conn._step("B", [20.0, 0.0], 0, i)
    [event] = [e for e in conn.events if e["event"] == "campaign"]
    return event["detail"]


def test_a_continuing_campaigns_lead_in_is_named():
    assert _first_event(-2959) == ("campaign B from its sample -2959 (2959 sample(s) of the "
                                   "campaign(s) it continues first, unscored)")
    assert _first_event(0) == "campaign B from its sample 0"
