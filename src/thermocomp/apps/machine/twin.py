"""A virtual machine tool over OPC UA: a dataset's test campaigns served sample by sample.

Each sample its inputs are written to their nodes, then ``campaign``, ``campaign_sample`` and
last ``sample``; one period (``1/speed`` s) later the offsets the client wrote are read (the
correction the machine applies while that sample holds).  The machine's error at the sample,
compensated, is its measured error minus that offset; a sample whose offsets do not answer it
(``offset_sample``) is stale.  A campaign that continues others (``lead_ins``) is served
after them under its own name (``campaign_sample`` < 0 there, unscored): the client's stream
is warmed on them as ``replay`` warms it.  The first sample waits for a client (at most ``wait_s``).
``references`` (per campaign, rows x targets, NaN where none) are the reference measurements
of the error the machine takes (a probe touch): published on the ``reference`` nodes with the
sample they belong to (NaN on the others), for a client that learns from them (``adapt``).
``drops`` stop the input nodes (the sensor link down: the client sees stale inputs) and
``restarts`` stop the server (its address space, the offset registers, kept), for a number of
samples each, while the machine runs on with the offsets it holds.
``lockstep``: the next sample comes as soon as the client answered this one: a bench that runs at
the client's pace, not the clock's.  A sample waits at most ``wait_s`` for its answer while the
client keeps answering (a loaded machine's client may take longer than a period); after a sample
it left unanswered, at most one period (a client gone does not stall the bench), stale as without it.
"""

from __future__ import annotations

import asyncio
import logging
import time as clock
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from asyncua import Server, ua

from .nodes import NodeMap, quiet_asyncua
from .shelf import standard_shelf_or_none

log = logging.getLogger(__name__)
NO_CLIENT = -2      # offset_sample until a client writes (it writes -1 when it connects)
POLL_S = 0.002      # lockstep: how often the twin looks for the client's answer


@dataclass
class Outage:
    """``samples`` samples from the running sample ``at`` (0-based, over all campaigns)."""

    at: int
    samples: int

    def covers(self, k: int) -> bool:
        return self.at <= k < self.at + self.samples


@dataclass
class Served:
    """Per sample: the offsets the machine held and whether they answered it."""

    offsets: list = field(default_factory=list)
    stale: list = field(default_factory=list)


class Twin:
    """Serve ``campaigns`` (inputs in ``columns``, errors ``errors`` per campaign, n × targets)."""

    def __init__(self, nodes: NodeMap, campaigns: dict[str, pd.DataFrame], columns: list[str],
                 errors: dict[str, np.ndarray], targets: list[str], *, host: str = "127.0.0.1",
                 port: int = 4840, speed: float = 1.0, drops=(), restarts=(), wait_s: float = 0.0,
                 lead_ins: dict[str, pd.DataFrame] | None = None,
                 references: dict[str, np.ndarray] | None = None, lockstep: bool = False):
        self.map, self.campaigns, self.columns = nodes, campaigns, list(columns)
        self.lead_ins = lead_ins or {}
        self.references = references or {}
        self.errors, self.targets = errors, list(targets)
        self.endpoint = f"opc.tcp://{host}:{port}"
        self.period = 1.0 / float(speed)
        self.drops, self.restarts = list(drops), list(restarts)
        self.wait_s = float(wait_s)
        self.lockstep = bool(lockstep)
        self.held = np.zeros(len(self.targets))     # the machine's offset registers
        self.stopping = None                         # the task stopping the server, while down
        self.server = None

    async def _start(self) -> None:
        server = Server()
        await server.init(await asyncio.to_thread(standard_shelf_or_none))   # not built at each start
        server.set_endpoint(self.endpoint)
        server.set_server_name("thermocomp twin")
        idx = await server.register_namespace(self.map.namespace)
        folder = await server.nodes.objects.add_folder(idx, "Machine")

        async def add(node_id: str, name: str, value, variant, writable=False):
            var = await folder.add_variable(ua.NodeId.from_string(node_id), name,
                                            ua.Variant(value, variant))
            if writable:
                await var.set_writable()
            return var

        self.inputs = [await add(self.map.input_id(c), c, float("nan"), ua.VariantType.Double)
                       for c in self.columns]
        self.reference_nodes = [await add(self.map.reference_id(t), f"reference {t}", float("nan"),
                                          ua.VariantType.Double) for t in self.targets]
        self.offset_nodes = [await add(self.map.offset_id(t), f"offset {t}", float(v),
                                       ua.VariantType.Double, True)
                             for t, v in zip(self.targets, self.held)]
        m = self.map
        self.answered = await add(m.offset_sample, "offset_sample", NO_CLIENT, ua.VariantType.Int64,
                                  True)
        self.sample = await add(m.sample, "sample", -1, ua.VariantType.Int64)
        self.campaign = await add(m.campaign, "campaign", "", ua.VariantType.String)
        self.campaign_sample = await add(m.campaign_sample, "campaign_sample", -1,
                                         ua.VariantType.Int64)
        self.done = await add(m.done, "done", False, ua.VariantType.Boolean)
        await server.start()
        self.server = server

    async def _read_offsets(self, k: int) -> bool:
        """Take the offsets the client wrote into the registers; True when they answer ``k``."""
        values = [await n.read_value() for n in self.offset_nodes]
        self.held = np.array([float(v) if v is not None else np.nan for v in values])
        return int(await self.answered.read_value()) == k

    async def _wait_answer(self, k: int, deadline: float, written: bool, patient: bool) -> None:
        """Until ``deadline``; in lockstep (sample ``k`` written) until the client answered it, at
        most ``wait_s`` when ``patient`` (it answered the sample before), else until ``deadline``."""
        if self.lockstep and written:
            limit = max(deadline, clock.monotonic() + self.wait_s) if patient else deadline
            while clock.monotonic() < limit:
                if int(await self.answered.read_value()) == k:
                    return
                await asyncio.sleep(POLL_S)
        await asyncio.sleep(max(0.0, deadline - clock.monotonic()))

    async def serve(self, finished=None) -> Served:
        """Serve every campaign at ``speed`` samples per second; the per-sample record.

        ``finished(served)`` is called before ``done`` turns true: what it writes (``twin.json``)
        is there when the client ends."""
        quiet_asyncua()
        await self._start()
        waited = clock.monotonic()
        while (clock.monotonic() - waited < self.wait_s
               and await self.answered.read_value() == NO_CLIENT):
            await asyncio.sleep(0.05)      # the first sample for the client, not before it came
        served, k, answered = Served(), 0, True
        start = clock.monotonic()
        try:
            for cid, df in self.campaigns.items():
                lead = self.lead_ins.get(cid)
                first = -len(lead) if lead is not None else 0     # the lead-in: negative samples
                X = df[self.columns].to_numpy(float)
                refs = self.references.get(cid)
                none = np.full(len(self.targets), np.nan)
                if lead is not None:
                    X = np.vstack([lead[self.columns].to_numpy(float), X])
                for i in range(first, len(df)):
                    down = any(r.covers(k) for r in self.restarts)
                    if down and self.stopping is None:
                        log.info("server stopped at sample %d", k)   # the machine runs on
                        self.stopping = asyncio.create_task(self.server.stop())
                    elif not down and self.stopping is not None:
                        log.info("server started again at sample %d", k)
                        await self.stopping
                        self.stopping = None
                        await self.server.start()    # the address space (registers) kept
                    written = not down and not any(d.covers(k) for d in self.drops)
                    if written:
                        for node, v in zip(self.inputs, X[i - first]):
                            await node.write_value(ua.Variant(float(v), ua.VariantType.Double))
                        measured = refs[i] if refs is not None and i >= 0 else none
                        for node, v in zip(self.reference_nodes, measured):
                            await node.write_value(ua.Variant(float(v), ua.VariantType.Double))
                        await self.campaign.write_value(ua.Variant(cid, ua.VariantType.String))
                        await self.campaign_sample.write_value(ua.Variant(i, ua.VariantType.Int64))
                        await self.sample.write_value(ua.Variant(k, ua.VariantType.Int64))
                    await self._wait_answer(k, start + (k + 1) * self.period, written, answered)
                    if self.lockstep:            # the next period from now, not from the schedule
                        start = clock.monotonic() - (k + 1) * self.period
                    answered = await self._read_offsets(k) and not down
                    if i >= 0:                   # the lead-in warms the client, unscored
                        served.offsets.append(self.held.copy())
                        served.stale.append(not answered)
                    k += 1
            if self.stopping is not None:
                await self.stopping
                self.stopping = None
                await self.server.start()
            if finished is not None:
                finished(served)
            await self.done.write_value(ua.Variant(True, ua.VariantType.Boolean))
            await asyncio.sleep(max(0.5, 5 * self.period))      # the client reads it and leaves
        finally:
            if self.stopping is None:
                await self.server.stop()
        return served


def twin_report(served: Served, errors: dict[str, np.ndarray], targets: list[str]) -> dict:
    """``targets.<t>``: RMS and peak of the error compensated with the offsets the machine held,
    RMS uncompensated, stale samples (``twin.json``, CLI.md)."""
    e = np.vstack(list(errors.values())) if errors else np.empty((0, len(targets)))
    off = np.vstack(served.offsets) if served.offsets else np.empty((0, len(targets)))
    stale = np.asarray(served.stale, dtype=bool)

    def rms(r):
        ok = np.isfinite(r)
        return float(np.sqrt(np.mean(r[ok] ** 2))) if ok.any() else None

    out = {}
    for j, t in enumerate(targets):
        comp = e[:, j] - np.where(np.isfinite(off[:, j]), off[:, j], 0.0)
        ok = np.isfinite(comp)
        out[t] = {"rms_compensated": rms(comp), "rms_uncompensated": rms(e[:, j]),
                  "peak_compensated": float(np.max(np.abs(comp[ok]))) if ok.any() else None,
                  "stale_samples": int(stale.sum()),
                  "max_abs_offset": float(np.nanmax(np.abs(off[:, j]))) if len(off) else 0.0,
                  "offsets_finite": bool(np.all(np.isfinite(off[:, j])))}
    return {"targets": out, "n_samples": int(len(e)),
            "offsets": {t: [float(v) for v in off[:, j]] for j, t in enumerate(targets)}}
