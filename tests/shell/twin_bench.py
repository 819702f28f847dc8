"""The twin and its client (`connect`) on loopback, for the tests of the routes to the machine.

The twin runs in a thread of the test's process by default: its own ``thermocomp twin`` process
costs ~6 s of CPU to import the stack and compose (more than the whole stream), and the tests
that look at the offsets, the outages and the faults do not depend on it.  ``process=True``
serves it as a user does (the README's route), for the test that checks the command itself.
"""

from __future__ import annotations

import json
import subprocess
import sys
import threading
from pathlib import Path

from conftest import free_port
from thermocomp.shell.cli import _compose, main

FAST = ["track=false", "plots=none"]


def _served_in_thread(args: list[str]) -> tuple[threading.Thread, list]:
    """`twin` on its composed config in a daemon thread (its asyncio loop there); what it
    raised in the list returned."""
    from thermocomp.shell.stages.twin import twin

    cfg = _compose(args, "twin")
    raised: list = []

    def serve() -> None:
        try:
            twin(cfg)
        except BaseException as exc:     # said by the test, not lost in the thread
            raised.append(exc)

    thread = threading.Thread(target=serve, name="twin", daemon=True)
    thread.start()
    return thread, raised


def twin_and_connect(data: Path, tmp: Path, twin_args=(), connect_args=(), *, speed: float,
                     process: bool = False) -> tuple[dict, dict]:
    """The twin (lockstep at ``speed``) and the client in this process; ``(twin.json,
    connect.json)``, the first checked to be there as soon as the client ends."""
    port = free_port()
    args = [f"data.path={data}", f"out={tmp / 'twin'}", f"twin.port={port}",
            f"twin.speed={speed}", "twin.lockstep=true", *FAST, *twin_args]
    if process:
        server = subprocess.Popen([sys.executable, "-m", "thermocomp", "twin", *args],
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    else:
        thread, raised = _served_in_thread(args)
    twin_json = tmp / "twin" / "twin.json"
    try:
        # connect.give_up_s=120: a twin process imports the stack first, which took over
        # 30 s of wall time on a loaded 2-core machine (connect gave up: exit 2, no defect)
        code = main(["connect", f"data.path={data}", f"out={tmp / 'connect'}", *FAST,
                     f"connect.endpoint=opc.tcp://127.0.0.1:{port}", "connect.retry_s=0.2",
                     "connect.give_up_s=120", *connect_args])
        there = twin_json.is_file()         # what a user reads right after connect
        if process:
            _, err = server.communicate(timeout=120)
        else:
            thread.join(timeout=120)
    finally:
        if process and server.poll() is None:
            server.kill()
    if process:
        assert server.returncode == 0, err
    else:
        assert not thread.is_alive() and not raised, raised
    assert code == 0
    assert there, "twin.json was not written when connect ended"
    return json.loads(twin_json.read_text()), json.loads((tmp / "connect" / "connect.json").read_text())
