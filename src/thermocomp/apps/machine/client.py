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

(opcua67) A vendor's server has none of the twin's status nodes (:class:`~.nodes.NodeMap`): the
client then subscribes to the server's clock (``ServerStatus/CurrentTime``, ``clock="server"``)
and takes a sample each time it has gone ``period_s`` on, the stream's time that clock's seconds
since the campaign's first sample (not the inputs' SourceTimestamps: a sensor in its deadband
keeps an old one while time goes on); a campaign node of any type (an NC program's name) starts
a campaign when it changes, else one runs from the first sample; without ``done`` it runs until
SIGINT / SIGTERM (main thread), which end it cleanly.  Node ids may name their namespace by its
URI (resolved at each connection); every node is checked to be there first (NodesRefused, naming
each).  An input whose StatusCode is not Good is NaN (``input_status`` events).  Offsets are
written in each node's own DataType and unit; a refused write is WriteRefused.  A held offset
is not written again.  (small69) A new process writes no offset before its first computed one:
the registers keep what they hold (an earlier client's last offsets; event ``offsets_kept``);
(restart69) joining a campaign mid-way it moves them at the rate limit, not in one jump.
(connect68) Without ``campaign_sample``, ``connect.warm``'s rows are the first sample's
campaign's, placed on the server's clock by their timestamps (:meth:`Connection._joined`).
(connect71) The server's clock set while the machine ran is told from a pause by the client's
own clock (:mod:`.clockset`): the stream's time goes on as the client's did (``clock_set``; its
server times, deploy73, let ``data.clock_sets`` undo it in the machine's log).
"""

from __future__ import annotations

import asyncio
import logging
import math
import signal
import threading
import time as clock
from collections import deque
from contextlib import contextmanager, suppress
from dataclasses import dataclass
from datetime import datetime, timezone

import numpy as np
import pandas as pd
from asyncua import Client, ua

from ...core.context import TIME
from ...core.io.clocksets import after
from ...core.io.rates import (
    FOUND,
    GAP_PERIODS,
    LEARNING_GAP,
    PAUSE_PERIODS,
    SAID_AT_MOST,
    SETTLED,
    StepWatch,
    found_words,
)
from ...core.io.stdin import CLOCK_SETS, LAST_READ, TIME_ORIGIN
from ..deploy.streaming import OutOfEnvelopeError
from .clockset import OwnClock
from .nodes import NodeMap, NodesUnknown, quiet_asyncua, resolve_id
from .offsets import OffsetLimiter
from .registers import WRITABLE, WriteRefused, as_registers

log = logging.getLogger(__name__)
LINK_ERRORS = (ConnectionError, OSError, asyncio.TimeoutError, ua.UaError)
CLOCKS = ("node", "server")
CURRENT_TIME = "i=2258"     # Server_ServerStatus_CurrentTime: every OPC UA server's clock
NO_CAMPAIGN = "connect"     # the one campaign of a server without a campaign node
DONE = "done"
UNKNOWN = (ua.StatusCodes.BadNodeIdUnknown, ua.StatusCodes.BadNodeIdInvalid)
REFUSED = (ua.StatusCodes.BadUserAccessDenied, ua.StatusCodes.BadIdentityTokenRejected,
           ua.StatusCodes.BadIdentityTokenInvalid, ua.StatusCodes.BadSecurityPolicyRejected)
WRITE_REFUSED = (ua.StatusCodes.BadUserAccessDenied, ua.StatusCodes.BadNotWritable,
                 ua.StatusCodes.BadTypeMismatch, ua.StatusCodes.BadOutOfRange,
                 ua.StatusCodes.BadWriteNotSupported, *UNKNOWN)


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
    """Subscription handler: queues the new values of ``sample`` / ``done`` (or the clock's)."""

    def __init__(self, queue: asyncio.Queue):
        self.queue = queue

    def datachange_notification(self, node, val, data):
        self.queue.put_nowait(val)


class NodesRefused(RuntimeError):
    """``connect.nodes`` names nodes the server does not have, or offset nodes of a type the
    client cannot write (said in one message, every one of them)."""


class SessionRefused(RuntimeError):
    """The server refused the session's identity (no use retrying it)."""


@dataclass
class _Plan:
    """One session's nodes (their ids resolved against the server's namespaces)."""

    inputs: list            # the columns' nodes, then time's (clock node), then the references'
    labels: list            # what each input node is (a column, time, reference <target>)
    status: dict            # campaign / campaign_sample / sample / done: those the server has
    clock: object | None    # clock server: the server's CurrentTime
    offsets: list
    types: list             # the VariantType each offset node takes
    answered: object | None  # offset_sample, if the server has it
    watched: list           # what a new sample is told by (subscribed)
    registers: np.ndarray   # what the offset nodes held at the start (µm)


class Connection:
    """Run ``deployed`` (the adaptive or the plain streaming compensator) against ``endpoint``.

    ``clock`` (opcua67): where a sample's time comes from, ``node`` (the ``time`` input's node:
    the twin's) or ``server`` (the server's ``ServerStatus/CurrentTime``, read with the inputs:
    the machine's own clock, which goes on while a sensor sits in its deadband); without a
    ``sample`` node a sample is taken each time that clock has gone ``period_s`` on."""

    def __init__(self, deployed, nodes: NodeMap, endpoint: str, limiter: OffsetLimiter, *,
                 retry_s: float = 1.0, give_up_s: float = 60.0, timeout_s: float = 4.0,
                 adapt=None, warm=None, clock: str = "node", period_s: float | None = None,
                 user: tuple[str, str] | None = None):
        self.deployed, self.map, self.endpoint, self.limiter = deployed, nodes, endpoint, limiter
        self.adapt = adapt
        self.warm = warm             # rows logged since the running campaign's start (a restart)
        self.retry_s, self.give_up_s, self.timeout_s = retry_s, give_up_s, timeout_s
        if clock not in CLOCKS:
            raise ValueError(f"clock={clock!r}: one of {', '.join(CLOCKS)}")
        self.clock, self.period_s = clock, period_s
        self.user = user             # (name, password) of the session, None: anonymous
        if nodes is not None and nodes.sample is None and not (period_s and period_s > 0):
            raise ValueError("without a sample node the client samples every period_s: > 0")
        self.events: list[dict] = []
        self.written: list[np.ndarray] = []      # every offset vector written (µm, as written)
        self.samples = 0
        self._last, self._campaign = -1, None
        self._connected = False
        self._stale = False          # the offsets are decaying for want of fresh samples
        self.missed = 0              # samples the server published that this client never saw
        self.refused = 0             # samples the compensator refused (a plain one's dropout)
        self._refusing = False       # the last sample was refused (said once per run of them)
        self._start = clock_now()
        self._at = None              # the clock (s) of the last sample taken (no sample node)
        self._t0 = 0.0               # the clock (s) at the running campaign's first sample
        self._i = -1                 # the running campaign's sample (no campaign_sample node)
        self._quality: dict[str, str] = {}      # input -> Good / Uncertain / Bad, as last read
        self._held = None            # the offsets last written (a held one is not written again)
        self._kept = None            # what the offset nodes held at the first connection (µm)
        self._time = math.nan        # the last sample's time on the compensator's clock
        self._step_s = math.nan      # its step from the sample before (NaN: a campaign's first)
        self.stopped = None          # the signal that stopped the client, if one did
        self._placed = ""            # how connect.warm's log was placed on the server's clock
        self.own = OwnClock(period_s)    # the client's clock against the server's (connect71)
        # (dep106b) data.runs_at_pauses' step (the model's pause_s_, stream.c's TC_PAUSE_S): a
        # longer one starts a campaign from a reset, as the record's read, the C and serve do
        self.pause_s = float(getattr(deployed, "pause_s_", 0.0) or 0.0)
        self._paused = None          # the pause (s) the next step starts a campaign after
        # (dep108b) the running campaign's time read as the file reader reads it (rates.StepWatch:
        # the served model's and stream.c's rule), the rows read in it and the last ones' times
        self._watch, self._rows, self._recent = self._new_watch(), 0, deque(maxlen=SETTLED + 2)
        # (dep108e) the long steps of the server's clock the watch has yet to call a gap (the next
        # step short again) or part of a new period: {their data row: (the sample before, its s,
        # its steps, the period they count, what the client's clock told of it then)}; (con112)
        # while it learns the period, all of them
        self._owed: dict[int, tuple[int, float, int, float, str]] = {}
        self._passed = False         # (con112) a sample passed over since the last taken (too soon)

    def _event(self, kind: str, detail: str, level: int = logging.INFO, **extra) -> None:
        e = {"wall_s": round(clock_now() - self._start, 3), "sample": self._last,
             "event": kind, "detail": detail, **extra}
        self.events.append(e)
        log.log(level, "%s: %s", kind, detail)

    async def run(self) -> None:
        """Until the server says the campaigns are done, or SIGINT / SIGTERM (main thread: the
        session ends, ``stopped``; the offsets written last stay on the machine)."""
        quiet_asyncua()
        stop = asyncio.Event()
        with _stop_on_signals(stop, self):
            lost_at = None
            while True:
                session = asyncio.ensure_future(self._session())
                halt = asyncio.ensure_future(stop.wait())
                await asyncio.wait({session, halt}, return_when=asyncio.FIRST_COMPLETED)
                halt.cancel()
                if stop.is_set():
                    session.cancel()
                    try:
                        await session
                    except (asyncio.CancelledError, *LINK_ERRORS):
                        pass
                    self._event("stopped", f"{self.stopped}: the client ends; {self._left()}")
                    return
                try:
                    if session.result():
                        return
                except LINK_ERRORS as exc:
                    if self._connected or lost_at is None:    # once per outage, not per attempt
                        reason = " ".join(str(exc).split())[:120] or type(exc).__name__
                        self._event("link_lost", f"{type(exc).__name__}: {reason}")
                now = clock_now()
                if self._connected or lost_at is None:    # the clock runs from the last good link
                    lost_at = now
                if now - lost_at > self.give_up_s:
                    raise LinkLost(f"no OPC UA server at {self.endpoint} for {self.give_up_s:g} s")
                with suppress(TimeoutError):
                    async with asyncio.timeout(self.retry_s):
                        await stop.wait()

    async def _plan(self, client) -> _Plan:
        """The session's nodes: ids resolved (``nsu=``), each checked to be there, the offset
        nodes' types read; NodesRefused naming every one that is not."""
        m, d = self.map, self.deployed
        names = await client.get_namespace_array()
        bad: list[str] = []

        def node(label: str, text: str):
            try:
                return client.get_node(resolve_id(text, names))
            except (NodesUnknown, ValueError, ua.UaError) as exc:
                bad.append(f"{label} ({text}): {exc}")
                return None

        cols = list(d.columns_)
        labels = cols + ([TIME] if TIME not in cols else [])
        inputs = [node(c, m.input_id(c)) if c != TIME or self.clock == "node" else None
                  for c in labels]
        if self.adapt:
            labels += [f"reference {t}" for t in d.targets_]
            inputs += [node(f"reference {t}", m.reference_id(t)) for t in d.targets_]
        status = {k: node(k, getattr(m, k)) for k in ("campaign", "campaign_sample", "sample", "done")
                  if getattr(m, k) is not None}
        offsets = [node(f"offset {t}", m.offset_id(t)) for t in d.targets_]
        answered = node("offset_sample", m.offset_sample) if m.offset_sample is not None else None
        clock = client.get_node(CURRENT_TIME) if self.clock == "server" else None
        if bad:
            raise NodesRefused("; ".join(bad))
        named = [(lab, n) for lab, n in zip(labels, inputs) if n is not None]
        named += [(k, n) for k, n in status.items()] + [
            (f"offset {t}", n) for t, n in zip(d.targets_, offsets)]
        named += [("offset_sample", answered)] if answered is not None else []
        values = await client.read_attributes([n for _, n in named], ua.AttributeIds.Value)
        bad = [f"{lab} ({n.nodeid.to_string()}): {v.StatusCode.name}" for (lab, n), v in
               zip(named, values) if v.StatusCode is not None and v.StatusCode.value in UNKNOWN]
        if bad:
            raise NodesRefused("the server has no node " + "; ".join(bad))
        at = len(named) - len(offsets) - (answered is not None)
        registers = np.array([number(v.Value.Value if v.Value is not None else None)
                              * m.unit_um(t) for t, v in zip(d.targets_, values[at:])])
        types = []
        for t, n in zip(d.targets_, offsets):
            vt = await n.read_data_type_as_variant_type()
            if vt not in WRITABLE:
                bad.append(f"offset {t} ({n.nodeid.to_string()}): {vt.name}, not a signed "
                           "integer or a floating-point number")
            types.append(vt)
        if bad:
            raise NodesRefused("; ".join(bad))
        time_at = labels.index(TIME)
        watched = ([status["sample"]] + ([status["done"]] if "done" in status else [])
                   if "sample" in status else [clock if clock is not None else inputs[time_at]])
        return _Plan(inputs, labels, status, clock, offsets, types, answered, watched, registers)

    async def _session(self) -> bool:
        """One connection; True when the campaigns are done."""
        self._connected = False
        client = Client(self.endpoint, timeout=self.timeout_s, watchdog_intervall=self.retry_s)
        if self.user is not None:
            client.set_user(self.user[0])
            client.set_password(self.user[1])
        try:
            await client.connect()
        except ua.UaStatusCodeError as exc:
            if exc.code not in REFUSED:          # a server starting, a link down: retried
                raise
            client.disconnect_socket()
            who = f"user {self.user[0]!r}" if self.user is not None else "an anonymous session"
            raise SessionRefused(f"the server refused {who}: {ua.StatusCode(exc.code).name}"
                                 + ("" if self.user is not None else
                                    " (connect.user and THERMOCOMP_OPCUA_PASSWORD: its user)"))
        try:
            self._connected = True
            self._event("connected", self.endpoint)
            plan = await self._plan(client)
            queue: asyncio.Queue = asyncio.Queue()
            period_ms = max(1.0, 250.0 * self.retry_s / 10)
            sub = await client.create_subscription(period_ms, _Changes(queue))
            await sub.subscribe_data_change(plan.watched)
            now = clock_now
            if not self.limiter.started:
                await self._keep(client, plan)
            elif self._held is None or not np.array_equal(plan.registers, self._held):
                # a server that came back without what was written last (its registers lost):
                # written again; else they hold it (a restart keeping them)
                self._held = None
                await self._write(client, plan, self._last, self.limiter.stale(now()))
            reads = [n for n in plan.inputs if n is not None] + list(plan.status.values())
            reads += [plan.clock] if plan.clock is not None else []
            while True:
                # asyncio.timeout, not wait_for: 3.11's wait_for returns the item when run()'s
                # cancel comes as it arrives (cpython #86296): SIGTERM was then lost until done
                try:
                    async with asyncio.timeout(self.retry_s / 4):
                        await queue.get()
                except TimeoutError:
                    await client.check_connection()
                    if self.limiter.decaying(now()) and not self._stale:
                        self._stale = True
                        self._event("stale", f"no fresh sample for {self.limiter.hold_s:g} s: "
                                             "offsets decaying")
                    if self.limiter.started:        # (before its first: the machine's are kept)
                        await self._write(client, plan, None, self.limiter.stale(now()))
                    continue
                got = await client.read_attributes(reads, ua.AttributeIds.Value)
                sample = self._sample(plan, got)
                if sample == DONE:
                    self._event("done", "the server says the campaigns are done")
                    return True
                if sample is not None:
                    cid, row, k, i = sample
                    y = self._step(cid, row, k, i)
                    # a refused sample (None) answered with the offsets held, as tc_step gives
                    # the last corrections again (then decaying, as with no fresh sample)
                    await self._write(client, plan, k, self.limiter.stale(now()) if y is None
                                      else self.limiter.fresh(y, now(), self._step_s))
        finally:
            try:     # a dead link would keep the goodbye waiting for the request timeout
                async with asyncio.timeout(self.retry_s):
                    await client.disconnect()
            except Exception:            # the link is gone already
                client.disconnect_socket()

    def _sample(self, plan: _Plan, got: list):
        """``(campaign, row, k, i)`` of a new sample in one Read's values, DONE, or None (nothing
        new).  An input whose StatusCode is not Good is NaN (a dropped sensor: its held value is
        not a reading); each change of an input's quality is an event."""
        live = [lab for lab, n in zip(plan.labels, plan.inputs) if n is not None]
        n = len(live)
        given = dict(zip(live, got[:n]))
        status = dict(zip(plan.status, got[n:n + len(plan.status)]))
        value = {k: v.Value.Value if v.Value is not None else None for k, v in status.items()}
        if value.get("done"):
            return DONE
        row = [self._reading(lab, given[lab]) if lab in given else math.nan for lab in plan.labels]
        if plan.clock is not None:
            at, now = seconds(got[-1]), own_clock()
            if at is None:
                return None
        else:
            at, now = row[plan.labels.index(TIME)], None
        cid = str(value["campaign"]) if "campaign" in value else NO_CAMPAIGN
        new = cid != self._campaign
        told = (self._clock_set(at, now) if plan.clock is not None and self._at is not None
                and not new else None)
        if told is None and plan.clock is not None and self._at is not None and at < self._at:
            # the server's clock set back (NTP, a reset clock), not told: time goes on a period
            self._event("clock_back", f"the server's clock went back {self._at - at:g} s: the "
                        "stream's time goes on from its last sample"
                        + (f" ({self.own.why_not()})" if self.own.why_not() else ""),
                        logging.WARNING)
            self._t0 -= self._at - at + self.period_s
            self._at = at - self.period_s
        if (self.pause_s and not new and self._at is not None and math.isfinite(at)
                and at - self._at > self.pause_s):
            self._paused, new = at - self._at, True      # (dep106b) a campaign from here
        period = self._clock_period()
        steps = (1 if self._at is None or new or not period
                 else max(1, round((at - self._at) / period)))
        if "sample" in value:
            k = int(value["sample"]) if value["sample"] is not None else -1
            if k <= self._last:
                return None
        else:       # a sample each time the clock has gone a period on (or a campaign starts)
            if not math.isfinite(at) or (not new and self._at is not None
                                         and at - self._at < self.period_s * (1 - 1e-6)):
                # (the clock gone on, not a period: a sample passed over; not the same clock read again)
                self._passed = self._passed or (self._at is not None and math.isfinite(at) and at > self._at)
                return None
            if plan.clock is not None and not new and self._at is not None:
                steps = self._clock_gap(at - self._at, steps)
            self._passed = False
            k = self._last + steps
        if new:
            self._t0, self._i = at, -1
            if self.warm is not None and "campaign_sample" not in value:
                self._t0, self._i = self._joined(at, plan.clock is not None)
        self._i = (int(value["campaign_sample"]) if "campaign_sample" in value and self._paused is None
                   else self._i + steps)
        if now is not None:
            self.own.taken(None if new or told is not None or self._at is None else at - self._at,
                           now)
        self._at = at
        if plan.clock is not None:          # the stream's time: s since the campaign's start
            row[plan.labels.index(TIME)] = at - self._t0
        return cid, row, k, self._i

    def _joined(self, at: float, server_clock: bool) -> tuple[float, int]:
        """(connect68) Where the first sample of a client given ``connect.warm`` sits in the
        campaign the log holds, without a ``campaign_sample`` node (a vendor's server): ``(the
        clock at the campaign's start, the sample before the joined one)``.  On the server's
        clock the log's timestamps place it (their first is the campaign's start: the samples no
        client saw are spanned by the time step, as after a link drop); a log of seconds tells
        nothing of the server's clock: the join follows the log's last row by one period, as
        ``run`` joins a campaign to the one it continues (a served ``continues`` alike).  On a
        ``time`` node the campaign's own seconds place it as they are."""
        warm, period = self.warm, self.period_s or 1.0
        times = warm[TIME].to_numpy(float) if TIME in warm.columns else np.arange(len(warm)) * period
        last = float(np.nanmax(times)) if len(warm) and np.isfinite(times).any() else -period
        origin = warm.attrs.get(TIME_ORIGIN)
        if not server_clock:
            t0, self._placed = 0.0, ""
        elif origin is not None:
            t0 = origin.timestamp() + self._sets_before(at)
            self._placed = (f" (the log's timestamps place it {at - t0 - last:g} s after the "
                            "log's last row)")
        else:
            t0 = at - last - period
            self._placed = (f" (the log's time is seconds, not the server's clock: this sample "
                            f"placed one period ({period:g} s) after the log's last row; the time "
                            "no client saw is not known: a log with timestamps spans it)")
        periods = (at - t0) / period
        return t0, (max(1, round(periods)) if math.isfinite(periods) else 1) - 1

    def _sets_before(self, at: float) -> float:
        """(deploy74) The seconds ``data.clock_sets`` moves the joined sample (``at``, the
        server's clock) back by: the sets undone in the log before its last row and those
        between it and ``at``, the sample read as the log's next row (:func:`.clocksets.after`),
        so that its time continues the log's as ``replay`` of the whole log reads it; 0 without."""
        warm = self.warm
        last = warm.attrs.get(LAST_READ)
        if not warm.attrs.get(CLOCK_SETS) or last is None:
            return 0.0
        moved = last - warm.attrs[TIME_ORIGIN].timestamp() - float(warm[TIME].dropna().iloc[-1])
        return moved + after(last, at, warm.attrs[CLOCK_SETS])

    def _clock_set(self, at: float, now: float) -> float | None:
        """(connect71) The seconds the server's clock was set by since the last sample, told by
        the client's own clock (:meth:`~.clockset.OwnClock.set_by`), or None.  Set, the stream's
        time and the server's clock at the last sample move with it: the model's time goes on as
        the client's clock did, the next sample a period after the last on it, the guard's rate
        over that time (a pause, kept, goes on by the server's step)."""
        step = self.own.set_by(at - self._at, now)
        if step is None:
            return None
        went = now - self.own.at
        self._event("clock_set", f"the server's clock went {at - self._at:g} s since the last "
                    f"sample while the client's went on {went:g} s: set "
                    f"{'forward' if step > 0 else 'back'} {abs(step):g} s (an operator, DST, NTP) "
                    "while the machine ran: the stream's time goes on as the client's clock did",
                    logging.WARNING, step_s=step, from_utc=utc(self._at), at_utc=utc(at))
        self._t0 += step
        self._at += step
        return step

    def _new_watch(self) -> StepWatch:
        """A campaign's watch; (dep108e) on the server's clock (UTC: no daylight saving time) a
        step of an hour and a period is a stretch without samples, as ``clock_gap`` said it."""
        return StepWatch(hour_steps=self.clock != "server")

    def _clock_period(self) -> float | None:
        """(dep108e) The period a step of the stream's time is read against: the one the
        campaign's watch has settled on (its first steps', the new one after a period change),
        ``connect.period_s`` before it has one."""
        return self._watch.period if math.isfinite(self._watch.period) else self.period_s

    def _clock_gap(self, gap: float, steps: int) -> int:
        """(opcleft67) A step of the server's clock of :data:`~...core.io.rates.GAP_PERIODS`
        periods or more since the last sample is kept in the stream's time, as ``replay`` and
        ``run`` read the same step in a file's ``time`` (the lag bank steps over it), and said
        (``clock_gap``) as the file reader says it: up to :data:`~...core.io.timestamps.PAUSE_PERIODS`
        periods a stretch without samples (a link or the server down: counted missed), beyond
        them a pause (the machine off, or its clock set forward: no sample was published that
        the client did not see, none counted).  The samples the step spans (``steps``), or 1.
        (dep108e) The periods are the watch's (:meth:`_clock_period`); once it has one, a
        stretch is the watch's: said and counted when the next step is short again (its
        ``gap``), not where the steps go on long (a new period, said once as a ``time`` event;
        before, every step after a change was a gap of the old period's).  (con112) So too while
        the watch learns the period (:meth:`_learned`, :meth:`_first_step`), but for a step over
        a sample passed over: before, each step of a period changed in the first steps was a gap
        of ``connect.period_s``'s, its samples counted missed, where the file reader and the
        ``time`` node said none."""
        period = self._clock_period()
        if gap < GAP_PERIODS * period:
            return steps
        paused = gap > PAUSE_PERIODS * period
        # (con112) while a period is learned, a step over a sample passed over (it came within a
        # period: a jittery clock) tells no period: said at once, as before
        if not paused and (math.isfinite(self._watch.period) or not self._passed):
            self._owed[self._rows] = (self._last, gap, steps, period, self.own.why_not())
            return 1
        self._said_gap(gap, steps, period, paused, self._last, self._rows + 1)
        return 1 if paused else steps

    def _said_gap(self, gap: float, steps: int, period: float, paused: bool, before: int,
                  row: int, why_not: str | None = None) -> None:
        """The ``clock_gap`` event of a step of ``gap`` s (``steps`` periods of ``period`` s)
        after sample ``before``, the first sample after it the campaign's data ``row``;
        ``why_not``: what the client's clock told of the step when it came (None: now)."""
        if why_not is None:             # '': the client's clock went on as much (connect71)
            why_not = self.own.why_not()
        what = (f"more than {PAUSE_PERIODS} periods: a pause (the machine off?) or its clock set "
                "forward, no sample counted missed" if paused and why_not else
                f"more than {PAUSE_PERIODS} periods: a pause (the client's clock went on as much: "
                "the machine off, not its clock set), no sample counted missed" if paused else
                f"a stretch without samples ({steps - 1} counted missed)")
        what += f" ({why_not})" if why_not else ""
        self._event("clock_gap", f"the server's clock went on {gap:g} s ({gap / period:.4g} "
                    f"periods of {period:g} s) since the last sample, {what}: the stream's "
                    "time keeps the step, as replay reads a file's (a lag model steps over it)",
                    logging.WARNING, sample=before, row=row)

    def _reading(self, label: str, dv) -> float:
        """A node's value as a number; NaN unless its StatusCode is Good."""
        code = dv.StatusCode if dv.StatusCode is not None else ua.StatusCode()
        quality = "Good" if code.is_good() else "Uncertain" if code.is_uncertain() else "Bad"
        if self._quality.get(label, "Good") != quality:
            self._event("input_status", f"{label}: {code.name}" + (
                " (read as missing)" if quality != "Good" else " (read again)"),
                logging.WARNING if quality != "Good" else logging.INFO, input=label)
        self._quality[label] = quality
        if quality != "Good":
            return math.nan
        return number(dv.Value.Value if dv.Value is not None else None)

    def _step(self, cid: str, row: list[float], k: int, i: int) -> np.ndarray | None:
        d = self.deployed
        if cid != self._campaign or self._paused is not None:
            if self._paused is not None:
                self._event("pause", f"the time paused {self._paused / 3600:.3g} h, more than "
                            f"{self.pause_s:g} s (data.runs_at_pauses): a campaign from a reset "
                            "here, as the record's read, stream.c (TC_PAUSE_S) and serve start one",
                            logging.WARNING, pause_s=self._paused)
                self._paused = None
            d.reset()
            if self.adapt is not None:
                self.adapt.start()      # what was learned is kept: the same machine
            # joined mid-way (i > 0) by a new process: rate-limited from what the machine holds
            self.limiter.new_campaign(self._kept if i > 0 and not self.limiter.started else None)
            self._campaign, self._time = cid, math.nan
            self._short_campaign()
            self._watch, self._rows, self._owed = self._new_watch(), 0, {}
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
        self._watched(cid, t)
        before = self._clock_time(self._time)
        try:
            y = d.step(x, t)
        except OutOfEnvelopeError as exc:
            # (dep107) a plain stream refuses a missing value (or, policy=refuse, an input out of
            # its envelope): the sample is not taken, nothing remembered changes, as the served
            # model refuses the row and the C's tc_step the sample; it ended the client
            if not self._refusing:
                self._event("refused", f"{exc}: the offsets held, the sample not taken (as serve "
                            "and the C's tc_step refuse it)", logging.WARNING)
            self._refusing = True
            self.refused += 1
            return None
        if self._refusing:
            self._event("taken", f"samples taken again ({self.refused} refused so far)")
        self._refusing = False
        if self.adapt is not None:      # the correction first, then what its reference teaches
            measured = np.asarray(row[reads:], float)[None]
            y = self.adapt.correct(np.asarray(y, float)[None], np.array([t]), measured)[0]
        for e in getattr(d, "last_events_", []):
            self._event("compensator", e.get("reason", ""), sensor=e.get("sensor"))
        self.samples += 1
        # (deploy73) the offsets' rate over the compensator's own step (one clock, the guard's)
        now = self._clock_time(t)
        self._step_s, self._time = now - before, now
        return y

    def _watched(self, cid: str, t: float) -> None:
        """(dep108b) The sample's time ``t`` (the stream's, s) read on by the campaign's watch
        (:class:`~...core.io.rates.StepWatch`): a sample period that changes and a stretch without
        rows said as the file reader says them of the machine's log, naming the campaign's data
        row (the samples read in it, 1-based; not the campaign's sample, which counts periods of
        the server's clock); an event ``time`` each (its ``to`` the served model's), a warning
        the first :data:`~...core.io.rates.SAID_AT_MOST` of each kind.  The offsets as they are.
        It said neither (a period change, on the server's clock: a ``clock_gap`` at every sample
        after it; on a ``time`` node nothing).  (dep108e) On the server's clock its finding of a
        gap is the one a ``clock_gap`` waits for once the watch has a period (:meth:`_clock_gap`)."""
        self._recent.append((self._rows, t))
        learning = not math.isfinite(self._watch.period)
        for kind, at, was, now in self._watch.read(float(t), self._rows):
            said = self._watch.said[kind] = self._watch.said.get(kind, 0) + 1
            when = dict(self._recent).get(at, t)
            self._event("time", f"campaign {cid}, column {TIME!r}, data row {at + 1} of those read: "
                        f"{found_words(kind, was, now)}; the offsets go on"
                        + (" (no more said)" if said == SAID_AT_MOST else ""),
                        logging.WARNING if said <= SAID_AT_MOST else logging.DEBUG,
                        sensor=TIME, to=FOUND[kind], time=when, row=at + 1)
            if kind == "gap" and at in self._owed:
                self._gap_owed(at)
        if learning and math.isfinite(self._watch.period):
            self._learned()
        elif learning and self._rows == 2 and 1 in self._owed and len(self._watch.steps) == 2:
            self._first_step()
        if math.isfinite(self._watch.period):   # (dep108e) read on as a new period's: not owed
            self._owed = {r: owed for r, owed in self._owed.items() if r >= self._rows}
        self._rows += 1

    def _learned(self) -> None:
        """(con112) The period just learned: the long steps still owed from the learning are read
        against it, as the file reader reads a campaign's steps against their median.  A run of
        them up to this step is the new period's first steps (this one stays owed: the watch's gap
        waiting for the next); an earlier one long at the learned period is a stretch without
        samples, said and counted now."""
        period, run = self._watch.period, self._rows
        while run in self._owed and self._watch.is_long(self._owed[run][1], period):
            run -= 1
        self._owed = {r: owed for r, owed in self._owed.items() if r <= run or r == self._rows}
        for row in sorted(r for r in self._owed if r < self._rows):
            if self._watch.is_long(self._owed[row][1], period):
                self._gap_owed(row, period)

    def _first_step(self) -> None:
        """(con112) The campaign's first step owed (the watch's stretches while it learns are the
        steps after the first): a stretch where the second is short, :data:`LEARNING_GAP` times
        or more below it, its samples counted at the second's period, said now (one sample on)."""
        second = self._watch.steps[-1][1]
        if self._owed[1][1] >= LEARNING_GAP * second and self._watch.is_long(self._owed[1][1], second):
            self._gap_owed(1, second)

    def _short_campaign(self) -> None:
        """(con112) A campaign over before its period was learned: the long steps still owed read
        against the median of its steps, as the file reader reads a short campaign's."""
        steps = [s for _, s in self._watch.steps]
        if self._owed and not math.isfinite(self._watch.period) and steps:
            period = float(np.median(steps))
            for row in sorted(r for r, owed in self._owed.items() if self._watch.is_long(owed[1], period)):
                self._gap_owed(row, period)

    def _gap_owed(self, row: int, period: float | None = None) -> None:
        """(dep108e) The long step into data row ``row`` the watch calls a gap: said (``clock_gap``,
        the sample before it and the data row after it, as the file reader names it) and its
        samples counted missed; the samples' count goes on from the server's clock, as when it was
        said at once.  ``period``: the one its samples count (None: the one it was owed at)."""
        before, gap, steps, owed_at, why_not = self._owed.pop(row)
        if period is None:
            period = owed_at
        else:
            steps = max(1, round(gap / period))
        self._said_gap(gap, steps, period, False, before, row + 1, why_not)
        self.missed += steps - 1
        self._last += steps - 1

    def _clock_time(self, given: float) -> float:
        """The last sample's time on the compensator's clock (its time rule's: the adaptive's,
        a plain lag stream's); a plain stream of a static law keeps none: the time ``given``."""
        t = getattr(self.deployed, "clock_time_", None)
        return given if t is None else float(t)

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
                              f"{len(warm)} row(s) logged before it (connect.warm), unscored"
                              + self._placed)

    async def _keep(self, client, plan: _Plan) -> None:
        """(small69) No offset computed yet (a new process, started while a program runs): the
        offset nodes keep what they hold until the first computed offset, said (``offsets_kept``);
        ``offset_sample`` (the twin's) gets -1, no sample answered, which tells it a client is
        there.  Before, the limiter's 0 was written here: the machine's correction dropped to 0
        until the first sample (up to a sample period), then jumped back."""
        self._kept = plan.registers
        self._event("offsets_kept", f"the offsets the machine holds are kept until the first one "
                                    f"computed, not zeroed (µm: {self._um(plan.registers)})")
        if plan.answered is not None:
            await _written(client, [plan.answered], [ua.Variant(self._last, ua.VariantType.Int64)])

    def _um(self, offsets) -> str:
        return ", ".join(f"{t} {v:.3f}" for t, v in zip(self.deployed.targets_, offsets))

    def _left(self) -> str:
        """What stays on the machine when the client ends (it does not zero the offsets)."""
        if self._held is None and self._kept is not None:
            return f"it wrote no offset: those the machine held stay (µm: {self._um(self._kept)})"
        last = self._held if self._held is not None else self.limiter.offset
        return f"the offsets it wrote last stay on the machine (µm: {self._um(last)})"

    async def _write(self, client, plan: _Plan, answered, values: np.ndarray) -> None:
        """The offsets, then (``answered``: the sample they answer, with an ``offset_sample`` node)
        that sample: one Write, applied in order.  Each offset in its node's type and unit
        (``offset_unit_um``; an integer node takes the nearest count); what was written, in µm,
        is kept.  A held offset is not written again; a refused write is WriteRefused."""
        unit = [self.map.unit_um(t) for t in self.deployed.targets_]
        data, held = as_registers(values, unit, plan.types, self.deployed.targets_,
                                  [n.nodeid.to_string() for n in plan.offsets])
        if answered is None and self._held is not None and np.array_equal(held, self._held):
            return                   # held: the machine holds it already
        nodes = list(plan.offsets)
        if answered is not None and plan.answered is not None:
            nodes.append(plan.answered)
            data.append(ua.Variant(answered, ua.VariantType.Int64))
        await _written(client, nodes, data)
        self._held = held
        self.written.append(held)


async def _written(client, nodes: list, data: list) -> None:
    """One Write of ``data`` to ``nodes``; a refused one is WriteRefused (no use retrying),
    another failure (a server going down) a UaStatusCodeError, retried as a lost link."""
    codes = await client.write_values(nodes, data, raise_on_partial_error=False)
    failed = [(n, c) for n, c in zip(nodes, codes) if not c.is_good()]
    refused = [(n, c) for n, c in failed if c.value in WRITE_REFUSED]
    if refused:
        raise WriteRefused("; ".join(f"{n.nodeid.to_string()}: {c.name}" for n, c in refused))
    if failed:
        raise ua.UaStatusCodeError(failed[0][1].value)


def clock_now() -> float:
    return clock.monotonic()


def own_clock() -> float:
    """(connect71) The client's clock a step of the server's is timed by: monotonic, going on
    while the client's host is suspended (CLOCK_BOOTTIME where there is one: a suspended host is
    not the server's clock set forward)."""
    boot = getattr(clock, "CLOCK_BOOTTIME", None)
    return clock.clock_gettime(boot) if boot is not None else clock.monotonic()


def utc(s: float) -> str:
    """The server's clock ``s`` (s since the epoch) as an ISO 8601 time in UTC: where a
    ``clock_set`` event finds its rows in the machine's log (``data.clock_sets``, deploy73)."""
    return datetime.fromtimestamp(s, timezone.utc).isoformat()


def seconds(dv) -> float | None:
    """A DateTime node's value (the server's clock) in s, None when it has none."""
    v = dv.Value.Value if dv is not None and dv.Value is not None else None
    if not isinstance(v, datetime):
        return None
    return (v if v.tzinfo else v.replace(tzinfo=timezone.utc)).timestamp()


@contextmanager
def _stop_on_signals(stop: asyncio.Event, link: Connection):
    """SIGINT and SIGTERM set ``stop`` (``link.stopped`` names it) while the client runs in the
    main thread; the handlers before come back after."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    loop = asyncio.get_running_loop()
    signals = (signal.SIGINT, signal.SIGTERM)
    before = {s: signal.getsignal(s) for s in signals}

    def handle(s):
        link.stopped = signal.Signals(s).name
        stop.set()

    for s in signals:
        loop.add_signal_handler(s, handle, s)
    try:
        yield
    finally:
        for s in signals:
            loop.remove_signal_handler(s)
            signal.signal(s, before[s])
