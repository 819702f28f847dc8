"""`connect` names the lead-in of a continuing campaign (deploy57).

The twin serves a test campaign that continues the train record after the train rows, under the
test campaign's name with negative sample numbers; `connect` logged "campaign messung_test from
its sample -2959", a negative sample a user cannot read.  It now says what those samples are.
"""

from __future__ import annotations

from conftest import offline_connection


def _first_event(i: int) -> str:
    conn = offline_connection()
    conn._step("B", [20.0, 0.0], 0, i)
    [event] = [e for e in conn.events if e["event"] == "campaign"]
    return event["detail"]


def test_a_continuing_campaigns_lead_in_is_named():
    assert _first_event(-2959) == ("campaign B from its sample -2959 (2959 sample(s) of the "
                                   "campaign(s) it continues first, unscored)")
    assert _first_event(0) == "campaign B from its sample 0"
