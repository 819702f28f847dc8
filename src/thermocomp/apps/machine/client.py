"""The OPC UA client that runs a deployed compensator against a machine (``thermocomp connect``).

It subscribes to the ``sample`` and ``done`` nodes; on each new sample it reads the inputs and
where the sample is in one Read (the twin writes ``sample`` last), resets the compensator when
the campaign changes, steps it and writes the offsets (through :class:`~.offsets.OffsetLimiter`)
with ``offset_sample``.  A value that is not a number streams as NaN: the compensator handles
it as ``monitor`` does (the adaptive one reconstructs or holds).  Without a fresh sample the
offsets are held, then decay; a lost link or server is reconnected every ``retry_s`` until
``give_up_s`` pass without one.  It ends when ``done`` turns true.  With ``adapt`` (an
:class:`~thermocomp.apps.deploy.adapt.Adaptation` without a schedule: the machine says when) the
``reference`` nodes are read with the inputs; a finite one is a reference measurement of that
sample, learned from after its own correction is given, as ``replay`` learns.
"""

from __future__ import annotations

import asyncio
import logging
import math
import time as clock

import numpy as np
import pandas as pd
from asyncua import Client, ua

from ...core.context import TIME
from .nodes import NodeMap, quiet_asyncua
from .offsets import OffsetLimiter

log = logging.getLogger(__name__)
LINK_ERRORS = (ConnectionError, OSError, asyncio.TimeoutError, ua.UaError)


class LinkLost(RuntimeError):
    """No server answered for ``give_up_s`` seconds."""


def number(value) -> float:
    """A node's value as a float: anything that is not a finite-able number is NaN."""
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def joined_mid_campaign(cid: str, i: int) -> str:
    """What a client that first sees campaign ``cid`` at its sample ``i > 0`` is told: it was
    started (or restarted: a new process keeps no stream) after the campaign began, and streams
    from a reset there.  Measured (restart58): a lag bank on a Swiss lathe's 8 h run, connect
    restarted 5 h in, E_X RMSE 27.2 um after the restart against 1.4 uninterrupted."""
    return (f"campaign {cid} joined at its sample {i}, not its first (connect started or "
            "restarted mid-campaign: no stream state survives a restart): the stream starts from "
            "a reset here, so a model of changes from a campaign's first sample misses the "
            "warm-up before it; connect.warm=<the rows logged since the campaign's start> "
            "resumes it (docs/to-the-machine.md)")


def warm_times(warm) -> str:
    """``'<first> to <last> s'`` of a ``connect.warm`` log's times, or that it has none."""
    if TIME not in warm.columns:
        return "no time"
    t = warm[TIME].to_numpy(float)
    return f"{np.nanmin(t):g} to {np.nanmax(t):g} s"


class _Changes:
    """Subscription handler: queues the new values of ``sample`` / ``done``."""

    def __init__(self, queue: asyncio.Queue):
        self.queue = queue

    def datachange_notification(self, node, val, data):
        self.queue.put_nowait(val)


class Connection:
    """Run ``deployed`` (the adaptive or the plain streaming compensator) against ``endpoint``."""

    def __init__(self, deployed, nodes: NodeMap, endpoint: str, limiter: OffsetLimiter, *,
                 retry_s: float = 1.0, give_up_s: float = 60.0, timeout_s: float = 4.0,
                 adapt=None, warm=None):
        self.deployed, self.map, self.endpoint, self.limiter = deployed, nodes, endpoint, limiter
        self.adapt = adapt
        self.warm = warm             # rows logged since the running campaign's start (a restart)
        self.retry_s, self.give_up_s, self.timeout_s = retry_s, give_up_s, timeout_s
        self.events: list[dict] = []
        self.written: list[np.ndarray] = []      # every offset vector written
        self.samples = 0
        self._last, self._campaign = -1, None
        self._connected = False
        self._stale = False          # the offsets are decaying for want of fresh samples
        self.missed = 0              # samples the server published that this client never saw
        self._start = clock.monotonic()

    def _event(self, kind: str, detail: str, level: int = logging.INFO, **extra) -> None:
        e = {"wall_s": round(clock.monotonic() - self._start, 3), "sample": self._last,
             "event": kind, "detail": detail, **extra}
        self.events.append(e)
        log.log(level, "%s: %s", kind, detail)

    async def run(self) -> None:
        """Until the server says the campaigns are done."""
        quiet_asyncua()
        lost_at = None
        while True:
            try:
                if await self._session():
                    return
            except LINK_ERRORS as exc:
                if self._connected or lost_at is None:    # once per outage, not per attempt
                    reason = " ".join(str(exc).split())[:120] or type(exc).__name__
                    self._event("link_lost", f"{type(exc).__name__}: {reason}")
            now = clock.monotonic()
            if self._connected or lost_at is None:    # the clock runs from the last good link
                lost_at = now
            if now - lost_at > self.give_up_s:
                raise LinkLost(f"no OPC UA server at {self.endpoint} for {self.give_up_s:g} s")
            await asyncio.sleep(self.retry_s)

    async def _session(self) -> bool:
        """One connection; True when the campaigns are done."""
        self._connected = False
        client = Client(self.endpoint, timeout=self.timeout_s, watchdog_intervall=self.retry_s)
        await client.connect()
        try:
            self._connected = True
            self._event("connected", self.endpoint)
            get = client.get_node
            m, cols = self.map, self.deployed.columns_
            reads = cols + ([TIME] if TIME not in cols else [])
            refs = [m.reference_id(t) for t in self.deployed.targets_] if self.adapt else []
            inputs = [get(n) for n in [*map(m.input_id, reads), *refs]]
            status = [get(m.campaign), get(m.campaign_sample), get(m.sample), get(m.done)]
            offsets = [get(m.offset_id(t)) for t in self.deployed.targets_]
            answered = get(m.offset_sample)
            queue: asyncio.Queue = asyncio.Queue()
            period_ms = max(1.0, 250.0 * self.retry_s / 10)
            sub = await client.create_subscription(period_ms, _Changes(queue))
            await sub.subscribe_data_change([status[2], status[3]])
            now = clock.monotonic
            await self._write(client, offsets, (answered, self._last), self.limiter.stale(now()))
            while True:
                try:
                    await asyncio.wait_for(queue.get(), timeout=self.retry_s / 4)
                except asyncio.TimeoutError:
                    await client.check_connection()
                    if self.limiter.decaying(now()) and not self._stale:
                        self._stale = True
                        self._event("stale", f"no fresh sample for {self.limiter.hold_s:g} s: "
                                             "offsets decaying")
                    await self._write(client, offsets, None, self.limiter.stale(now()))
                    continue
                values = await client.read_values(inputs + status)
                row, (cid, i, k, done) = values[:len(inputs)], values[len(inputs):]
                if done:
                    self._event("done", "the server says the campaigns are done")
                    return True
                k = int(k) if k is not None else -1
                if k > self._last:
                    y = self._step(str(cid), [number(v) for v in row], k, int(i))
                    await self._write(client, offsets, (answered, k), self.limiter.fresh(y, now()))
        finally:
            try:     # a dead link would keep the goodbye waiting for the request timeout
                await asyncio.wait_for(client.disconnect(), self.retry_s)
            except Exception:            # the link is gone already
                client.disconnect_socket()

    def _step(self, cid: str, row: list[float], k: int, i: int) -> np.ndarray:
        d = self.deployed
        if cid != self._campaign:
            d.reset()
            if self.adapt is not None:
                self.adapt.start()      # what was learned is kept: the same machine
            self.limiter.new_campaign()
            self._campaign = cid
            # a campaign that continues others comes after their rows (twin: its samples < 0)
            ahead = (f" ({-i} sample(s) of the campaign(s) it continues first, unscored)"
                     if i < 0 else "")
            self._event("campaign", f"campaign {cid} from its sample {i}{ahead}")
            if i > 0 and self.warm is not None:
                self._warm(cid, i, row)
            elif i > 0:
                self._event("joined_mid_campaign", joined_mid_campaign(cid, i), logging.WARNING)
            self.warm = None         # the rows before a restart belong to its campaign only
        elif k > self._last + 1:
            self.missed += k - self._last - 1      # counted; an event when the inputs went stale
        if self._stale:
            self._event("fresh", f"samples again ({self.missed} not seen so far)")
            self._stale = False
        self._last = k
        x = np.asarray(row[:len(d.columns_)], float)
        reads = len(d.columns_) + (TIME not in d.columns_)
        t = row[d.columns_.index(TIME)] if TIME in d.columns_ else row[reads - 1]
        y = d.step(x, t)
        if self.adapt is not None:      # the correction first, then what its reference teaches
            measured = np.asarray(row[reads:], float)[None]
            y = self.adapt.correct(np.asarray(y, float)[None], np.array([t]), measured)[0]
        for e in getattr(d, "last_events_", []):
            self._event("compensator", e.get("reason", ""), sensor=e.get("sensor"))
        self.samples += 1
        return y

    def _warm(self, cid: str, i: int, row: list[float]) -> None:
        """Step the rows logged before the joined sample (``connect.warm``: those with an earlier
        time, all without one), unscored and unwritten, so that the stream goes on from the
        state they leave, as if it had not restarted (the samples missed while no client ran
        are spanned by the time rule's step, as after a link drop)."""
        d, warm = self.deployed, self.warm
        reads = len(d.columns_) + (TIME not in d.columns_)
        t = row[d.columns_.index(TIME)] if TIME in d.columns_ else row[reads - 1]
        logged = len(warm)
        if TIME in warm.columns and math.isfinite(t):
            warm = warm[warm[TIME].to_numpy(float) < t]
        if not len(warm):
            # nothing to warm on (a log on another clock, another campaign's, an empty one):
            # said as the restart it is, not as a warm-up of 0 rows
            first = (f" (its {logged} row(s) are at times from {warm_times(self.warm)}, not "
                     f"before this sample's {t:g} s)" if logged else " (it holds no row)")
            self._event("joined_mid_campaign", joined_mid_campaign(cid, i) + ". connect.warm "
                        f"has no row logged before this sample{first}", logging.WARNING)
            return
        warm = warm.reset_index(drop=True)
        predicted = d.predict(warm)
        if self.adapt is not None:
            # the log's measured errors are the references the client had learned from before
            # the restart (as a served session resent from its start relearns them): without
            # them what adapt had learned was lost at a restart, warmed or not
            targets = list(d.targets_)
            measured = np.column_stack([pd.to_numeric(warm[t], errors="coerce").to_numpy(float)
                                        if t in warm.columns else np.full(len(warm), np.nan)
                                        for t in targets])
            times = warm[TIME].to_numpy(float) if TIME in warm.columns else np.full(len(warm), np.nan)
            self.adapt.correct(predicted[targets].to_numpy(float), times, measured)
        self._event("warmed", f"campaign {cid} joined at its sample {i}: the stream warmed on "
                              f"{len(warm)} row(s) logged before it (connect.warm), unscored")

    async def _write(self, client, offsets, answered, values: np.ndarray) -> None:
        """The offsets, then (``answered``: ``(node, sample)``) the sample they answer: one Write,
        applied in order."""
        nodes = list(offsets)
        data = [ua.Variant(float(v), ua.VariantType.Double) for v in values]
        if answered is not None:
            nodes.append(answered[0])
            data.append(ua.Variant(answered[1], ua.VariantType.Int64))
        await client.write_values(nodes, data)
        self.written.append(np.array(values, float))
