"""`thermocomp connect` against a vendor's OPC UA server: what stop 67 left (connect68).

A server process restarted with another companion specification installed registers the
vendor's namespace at another index: the ``nsu=`` ids are resolved again at the new session.
"""

from __future__ import annotations

import signal

import numpy as np
import pytest

pytest.importorskip("asyncua")

from conftest import free_port  # noqa: E402
from test_opcua67 import corrections, fitted, programs, run_connect, written_as  # noqa: E402, F401
from vendor_machine import VendorMachine, as_published  # noqa: E402


def test_a_restart_that_renumbers_the_vendor_namespace_is_followed(fitted, tmp_path):  # noqa: F811
    """The server down for 5 samples mid-program, back with the vendor's namespace at index 6
    (was 5) and its address space built anew: the client resolves its ids again and streams on
    from its state across the gap, the offsets replay's on the rows it saw."""
    data, pkl = fitted
    frames = programs(data)
    machine = VendorMachine(frames, free_port(), restarts=[(20, 5)], renumbered=True,
                            stop_signal=signal.SIGINT)
    code, link = run_connect(data, pkl, tmp_path, machine)
    assert machine.indices == [5, 6]
    assert code == 0 and link["stopped"] == "SIGINT"
    events = [e["event"] for e in link["events"]]
    assert events.count("connected") == 2 and events.count("link_lost") == 1
    assert "input_status" not in events
    assert link["samples_missed"] == 5 and events.count("campaign") == 2
    seen = as_published(frames)
    seen["P05.MPF"] = seen["P05.MPF"].drop(index=range(20, 25))
    answered = np.array(machine.served.answered)
    assert not answered[20:25].any() and answered[25:].all()
    written_as(np.vstack(machine.served.offsets)[answered], corrections(data, pkl, seen))
