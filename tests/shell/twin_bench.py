"""The twin and its client (`connect`) on loopback, for the tests of the routes to the machine.

The twin runs in a thread of the test's process by default: its own ``thermocomp twin`` process
costs ~6 s of CPU to import the stack and compose (more than the whole stream), and the tests
that look at the offsets, the outages and the faults do not depend on it.  ``process=True``
serves it as a user does (the README's route), for the test that checks the command itself.
"""

from __future__ import annotations

import asyncio
import json
import os
import signal
import subprocess
import sys
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
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


@dataclass
class Handoff:
    """(restart69) A client stopped mid-campaign and a new one joining: once sample ``stop`` is
    answered the client (process ``pid``, None: this one) is sent SIGTERM; once the test says it
    ended (``gone``) the samples up to ``join`` are served with no client (the machine runs on
    with the offsets it holds); at ``join`` the twin says so (``reached``: start the new client)
    and waits (at most ``twin.wait_s``) for its answer; ``at_connection``: what the offset
    registers held when the new client said it is there (``offset_sample`` -1), before that
    answer.  The join sample is the test's, not a matter of a process's start-up."""

    stop: int
    join: int
    pid: int | None = None
    at_connection: list | None = None
    gone: threading.Event = field(default_factory=threading.Event)
    reached: threading.Event = field(default_factory=threading.Event)


@contextmanager
def handing_over(handoff: Handoff):
    """While in it, the twin the ``twin`` stage builds hands over as ``handoff`` says."""
    from thermocomp.apps.machine import twin as module

    class HandingOver(module.Twin):
        async def _wait_answer(self, k, deadline, written, patient):
            h = handoff
            if h.stop < k < h.join:
                return                    # no client: the machine runs on with what it holds
            if k == h.join:
                h.reached.set()
                limit = time.monotonic() + self.wait_s
                while time.monotonic() < limit:
                    answered = int(await self.answered.read_value())
                    if answered == k:
                        break
                    if answered == -1 and h.at_connection is None:
                        h.at_connection = [float(await n.read_value()) for n in self.offset_nodes]
                    await asyncio.sleep(module.POLL_S)
                return
            await super()._wait_answer(k, deadline, written, patient)
            if k == h.stop:
                os.kill(h.pid or os.getpid(), signal.SIGTERM)
                while not h.gone.is_set():
                    await asyncio.sleep(0.01)

    original, module.Twin = module.Twin, HandingOver
    try:
        yield handoff
    finally:
        module.Twin = original


def limiter_step(data: Path, pkl: Path):
    """The largest change per sample (µm per target) `connect` lets reach the machine for the
    model ``pkl`` fitted on ``data``: its correction guard's rate over one sample period."""
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed
    from thermocomp.shell.stages.connect import _guard

    cfg = _compose([f"data.path={data}", f"connect.model={pkl}", *FAST], "connect")
    ds, train_ids = read_streamed(cfg, test=False)[:2]
    deployed = deployable_model(cfg, ds, train_ids, str(pkl), "connect.model")[0]
    guard = _guard(cfg, deployed, ds, train_ids)
    return guard.max_rate_per_s * guard.period_s
