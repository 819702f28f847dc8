"""`thermocomp connect` against a vendor's OPC UA server: what stop 67 left (connect68).

A server process restarted with another companion specification installed registers the
vendor's namespace at another index: the ``nsu=`` ids are resolved again at the new session.
A connect restarted mid-program with ``connect.warm`` (the rows logged since the program's
start): without a ``campaign_sample`` node the log was unread and unsaid.
"""

from __future__ import annotations

import json
import signal
from datetime import timedelta

import numpy as np
import pytest

pytest.importorskip("asyncua")

from conftest import free_port  # noqa: E402
from test_opcua67 import CLIENT, corrections, fitted, programs, run_connect, written_as  # noqa: E402, F401
from thermocomp.shell.cli import main  # noqa: E402
from twin_bench import FAST  # noqa: E402
from vendor_machine import EPOCH, SENSORS, VendorMachine, as_published, connect_nodes, served_in_thread  # noqa: E402


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


STOP, GAP = 19, 4        # P05's row 19 answered, then the client stopped; rows 20-23 with none


def restarted(data, pkl, tmp_path, log_time, stop: int = STOP, gap: int = GAP
              ) -> tuple[VendorMachine, dict, dict]:
    """P05 and P06 served; connect stopped (SIGTERM) once P05's row ``stop`` is answered, ``gap``
    rows pass with no client, a new connect joins at the next with ``connect.warm=<P05's rows 0
    to stop as published>``, their time ``log_time(seconds)``; both connect.json."""
    frames = programs(data)
    machine = VendorMachine(frames, free_port(), handover=(stop, gap))
    log = as_published(frames)["P05.MPF"].iloc[:stop + 1]
    log = log[["time", *SENSORS]].assign(time=log_time(log["time"]))
    log.to_csv(tmp_path / "log.csv", index=False)
    args = ["connect", f"data.path={data}", f"connect.model={pkl}", *FAST, *CLIENT, *connect_nodes(),
            f"connect.endpoint=opc.tcp://127.0.0.1:{machine.port}"]
    thread = served_in_thread(machine)
    try:
        assert main([*args, f"out={tmp_path / 'first'}"]) == 0
        machine.stopped.set()
        assert machine.handed_over.wait(60)
        assert main([*args, f"out={tmp_path / 'second'}", f"connect.warm={tmp_path / 'log.csv'}"]) == 0
    finally:
        machine.closing.set()
        thread.join(timeout=60)
    assert not thread.is_alive() and not machine.raised, machine.raised
    first, second = (json.loads((tmp_path / p / "connect.json").read_text())
                     for p in ("first", "second"))
    return machine, first, second


def stamped(seconds):
    """The server's clock's timestamps (the program starts at the record's epoch)."""
    return [(EPOCH + timedelta(seconds=float(s))).isoformat() for s in seconds]


@pytest.fixture(scope="module")
def stamped_join(fitted, tmp_path_factory):  # noqa: F811
    """``restarted`` with the server's timestamps at the default stop and gap, run once: two
    tests assert on it (what the join streams, what its first Write holds); each reads only."""
    data, pkl = fitted
    return restarted(data, pkl, tmp_path_factory.mktemp("stamped_join"), stamped)


@pytest.mark.parametrize("log_time", [stamped, lambda s: s], ids=["timestamps", "seconds"])
def test_a_connect_restarted_mid_program_is_warmed_on_its_log(fitted, tmp_path, log_time,  # noqa: F811
                                                             request):
    """Before: without a campaign_sample node every client starts a campaign at its first
    sample, connect.warm unread and unsaid (the offsets after the restart from a reset).  Now
    the log's rows are stepped first: with the server's timestamps the offsets are replay's on
    the rows the clients saw (the gap spanned by the time step, as after a link drop); with
    seconds the join follows the log's last row by one period, said."""
    data, pkl = fitted
    machine, first, second = (request.getfixturevalue("stamped_join") if log_time is stamped
                              else restarted(data, pkl, tmp_path, log_time))
    answered = np.array(machine.served.answered)
    assert answered[:STOP + 1].all() and not answered[STOP + 1:STOP + GAP + 1].any()
    assert answered[STOP + GAP + 1:].all()
    assert first["samples"] == STOP + 1 and first["stopped"] == "SIGTERM"
    warmed = [e for e in second["events"] if e["event"] == "warmed"]
    joined = STOP + GAP + 1 if log_time is stamped else STOP + 1      # seconds: one period on
    assert len(warmed) == 1 and f"joined at its sample {joined}" in warmed[0]["detail"]
    assert f"warmed on {STOP + 1} row(s)" in warmed[0]["detail"]
    seen = as_published(programs(data))
    seen["P05.MPF"] = seen["P05.MPF"].drop(index=range(STOP + 1, STOP + GAP + 1))
    if log_time is stamped:
        assert f"place it {(GAP + 1) * 60:g} s after the log's last row" in warmed[0]["detail"]
        assert "joined_mid_campaign" not in [e["event"] for e in second["events"]]
    else:
        assert "one period (60 s) after the log's last row" in warmed[0]["detail"]
        seen["P05.MPF"].loc[STOP + GAP + 1:, "time"] -= GAP * 60.0
    written_as(np.vstack(machine.served.offsets)[answered], corrections(data, pkl, seen))


def test_the_offsets_after_a_warmed_join_move_at_the_guards_rate_over_the_gap(fitted, tmp_path):  # noqa: F811
    """(deploy73) One clock: the offsets' rate limit spans the compensator's own step.  Joined
    14 samples after the first client stopped (early in P05, the spindle heating fast), the
    warmed stream's first step spans the 15 periods no client saw, and its guard lets the
    correction move by its rate over them; the limiter kept a clock of its own, started at the
    joined sample, and allowed one period's change: the offsets lagged replay's guarded
    correction after the join.  Now they are replay's on the rows the clients saw."""
    data, pkl = fitted
    stop, gap = 4, 14
    machine, _, second = restarted(data, pkl, tmp_path, stamped, stop, gap)
    answered = np.array(machine.served.answered)
    assert answered[:stop + 1].all() and answered[stop + gap + 1:].all()
    seen = as_published(programs(data))
    seen["P05.MPF"] = seen["P05.MPF"].drop(index=range(stop + 1, stop + gap + 1))
    written_as(np.vstack(machine.served.offsets)[answered], corrections(data, pkl, seen))


def test_a_connect_started_while_a_program_runs_keeps_the_offsets_until_its_first(stamped_join):
    """(small69) A new connect process wrote the limiter's 0 to the offset nodes at its
    connection, before its first sample: the machine's correction dropped to 0 for up to a
    period (60 s here), then jumped back.  Now its first Write is its first computed offset
    (the one that answers the sample it joins), the registers keeping the first client's last
    offsets until then, said in the event offsets_kept."""
    machine, first, second = stamped_join
    joined = STOP + GAP + 1
    offsets = np.vstack(machine.served.offsets)
    writes = machine.served.writes
    assert max(row for row, _ in writes[:first["writes"]]) == STOP    # the first client's
    after = writes[first["writes"]:]
    assert len(after) == second["writes"] and all(row >= joined for row, _ in after)
    assert np.all(np.array(list(after[0][1].values())) != 0), after[0]     # (it wrote 0, 0)
    np.testing.assert_array_equal(list(after[0][1].values()), offsets[joined])
    kept = [e for e in second["events"] if e["event"] == "offsets_kept"]
    assert len(kept) == 1 and kept[0]["sample"] == -1               # at its connection
    left = ", ".join(f"{t} {v:.3f}" for t, v in zip(("E_X", "E_Z"), offsets[STOP]))
    assert f"(µm: {left})" in kept[0]["detail"], kept[0]["detail"]
