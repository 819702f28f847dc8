"""A vendor's OPC UA server, not thermocomp's twin (opcua67): for `connect`'s tests and bench.

A umati/MachineTool-like address space of its own: the vendor's namespace URI registered after
three companion specifications' (so its index is 5, not the twin's 2), a machine object with a
folder per sensor holding a ``Temperature`` Float variable (an AnalogItem's: ``EngineeringUnits``
°C and ``EURange`` properties), string and numeric NodeIds, and a ``Compensation`` folder whose
offset nodes are a Float in µm and an Int32 in 0.1 µm.  There is no sample counter, no campaign
sample, no done node, no offset_sample: the running NC program's name (a String) changes with
the campaign, each value carries its SourceTimestamp, and the server's clock
(``ServerStatus/CurrentTime``) is the record's time (epoch + ``time``, a program starting
SETUP_S after the one before: the machine's clock run faster, one row per answer).

The record's rows are published one by one: each sensor's value (with its StatusCode: not
Good, its last value held, over ``bad`` rows; a value within ``deadband`` of the last one
published is not published, as a sensor's deadband does), the program's name, then the clock,
last.  Lockstep: a row waits (at most ``wait_s``) for the client's write to the offset nodes,
then takes the values in them (µm) as the offsets that answer it; the first row waits for a
client to subscribe (small69: a client writes nothing before its first offset; every Write of
offsets is kept, ``Served.writes``).  ``restarts`` stop the server for some rows (the machine
runs on; the address space is kept); with ``renumbered`` (connect68) it comes back as a server
process started anew with another companion specification installed: the namespaces registered
again, the vendor's one index later, the address space built again (the offsets it serves are
the NC's: they hold what was written last).  ``handover=(row, rows)`` (connect68): once ``row``
is answered the client is sent ``stop_signal`` (a service restarted, a host rebooted) and, once
the test says it ended (``stopped``), the next ``rows`` are published with no client (the
machine runs on), the one after them too, then ``handed_over`` is set and it waits for a new
client's answer (small69: before, a write of 0 at its connection came first).  ``refused``
offset nodes are not writable for the session's user (BadUserAccessDenied); with ``users`` a
session needs one of them.  ``clock_set=(row, s)`` (connect71): from that running row on the
server's clock is ``s`` ahead of the machine's (an operator set it forward, the machine ran on);
``machine_at`` maps each time the server's clock showed (s) to the machine's own (the record's,
no clock set: a client's clock driven by it runs at the server's rate, as a real machine's).
After the last row (or ``stop_after`` rows) answered it sends the process ``stop_signal`` (the
user's Ctrl-C or the service manager's SIGTERM: a vendor's server never says it is done).
"""

from __future__ import annotations

import asyncio
import os
import signal
import threading
import time as clock
from dataclasses import dataclass, field
from datetime import datetime, timedelta, timezone

import numpy as np
import pandas as pd
from asyncua import Server, ua
from asyncua.common.callback import CallbackType
from asyncua.crypto.permission_rules import User, UserRole

from thermocomp.apps.machine.nodes import quiet_asyncua
from thermocomp.apps.machine.shelf import standard_shelf_or_none

VENDOR_NS = "http://vendor.example.com/UA/CNC5000/"
COMPANIONS = ("http://opcfoundation.org/UA/DI/", "http://opcfoundation.org/UA/IA/",
              "http://opcfoundation.org/UA/MachineTool/")
EPOCH = datetime(2026, 3, 2, 6, 0, tzinfo=timezone.utc)
CELSIUS = ua.EUInformation(NamespaceUri="http://www.opcfoundation.org/UA/units/un/cefact",
                           UnitId=4408652, DisplayName=ua.LocalizedText("°C"),
                           Description=ua.LocalizedText("degree Celsius"))
# the sensors' nodes: string ids, one numeric (as a vendor's generated address space has them)
SENSORS = {"T_spindle": "s=CNC5000.Spindle.Temperature", "T_bed": "s=CNC5000.Bed.Temperature",
           "T_column": "i=6012", "T_amb": "s=CNC5000.Cabinet.AirTemperature"}
# target -> (node, type, µm per unit)
OFFSETS = {"E_X": ("s=CNC5000.Compensation.OffsetX", ua.VariantType.Float, 1.0),
           "E_Z": ("s=CNC5000.Compensation.OffsetZ_01um", ua.VariantType.Int32, 0.1)}
PROGRAM = "s=CNC5000.Production.ActiveProgram"
SETUP_S = 600.0      # between two programs
RENUMBERING = "http://opcfoundation.org/UA/Machinery/"   # installed before a renumbered restart


def nsu(node: str) -> str:
    """A vendor node as a client names it: by its namespace's URI."""
    return f"nsu={VENDOR_NS};{node}"


def connect_nodes(sensors: dict | None = None, offsets: dict | None = None) -> list[str]:
    """``connect.nodes`` overrides for this server: the vendor's nodes, no twin status node."""
    sensors, offsets = sensors or SENSORS, offsets or OFFSETS
    ins = ",".join(f"{c}:'{nsu(n)}'" for c, n in sensors.items())
    outs = ",".join(f"{t}:'{nsu(n)}'" for t, (n, _, _) in offsets.items())
    return [f"connect.nodes.inputs={{{ins}}}", f"connect.nodes.offsets={{{outs}}}",
            "connect.nodes.sample=null", "connect.nodes.campaign_sample=null",
            "connect.nodes.done=null", "connect.nodes.offset_sample=null",
            "connect.nodes.offset_unit_um={" + ",".join(f"{t}:{u}" for t, (_, _, u) in offsets.items()) + "}",
            f"connect.nodes.campaign='{nsu(PROGRAM)}'", "connect.clock=server"]


class _Users:
    """Anonymous sessions as asyncua's default (the user role), or only ``users``' own."""

    def __init__(self, users: dict | None):
        self.users = users

    def get_user(self, iserver, username=None, password=None, certificate=None):
        if self.users is None or (username in self.users and self.users[username] == password):
            return User(role=UserRole.User, name=username)
        return None


@dataclass
class Served:
    """Per row: the program, the offsets (µm) in the registers when it was answered (NaN: not
    answered, the server down), what each Write brought (node -> VariantType); ``writes``:
    ``(row being served, {target: µm})`` of every Write of offsets, in order."""

    program: list = field(default_factory=list)
    offsets: list = field(default_factory=list)
    answered: list = field(default_factory=list)
    types: dict = field(default_factory=dict)
    writes: list = field(default_factory=list)


class VendorMachine:
    """Serve ``campaigns`` (program name -> rows with ``time`` and the SENSORS' columns)."""

    def __init__(self, campaigns: dict[str, pd.DataFrame], port: int, *, deadband: float = 0.0,
                 bad: dict | None = None, restarts=(), refused=(), wait_s: float = 60.0,
                 stop_after: int | None = None, stop_signal=signal.SIGTERM,
                 stop_pid: int | None = None, sensors: dict | None = None,
                 offsets: dict | None = None, users: dict | None = None,
                 renumbered: bool = False, handover: tuple[int, int] | None = None,
                 clock_set: tuple[int, float] | None = None):
        self.campaigns, self.port, self.deadband = campaigns, port, float(deadband)
        self.sensors, self.offsets = sensors or SENSORS, offsets or OFFSETS
        self.stop_pid = stop_pid        # the client's process (None: this one)
        self.users = users              # {name: password}: no anonymous session (None: anyone)
        # column -> (first, last running row (0-based), StatusCode): the sensor dropped, its last
        # value held with that status (asyncua's server nulls a Bad one's value, not an Uncertain)
        self.bad = bad or {}
        self.restarts = list(restarts)  # (first running row, rows) the server is down
        self.renumbered = renumbered    # a restart registers the namespaces anew, one more first
        self.indices: list[int] = []    # the vendor namespace's index at each start
        self.handover = handover        # (row answered, rows without a client): a client stopped
        self.stopped = threading.Event()        # the test: the client stopped has ended
        self.handed_over = threading.Event()    # the rows without a client are out: start one
        self.refused, self.wait_s = set(refused), float(wait_s)
        self.stop_after, self.stop_signal = stop_after, stop_signal
        self.served = Served()
        self.raised: list = []
        self.closing = threading.Event()     # the test is done with it: end, no signal
        self.listening = threading.Event()   # its endpoint is up: a client started now connects
        self._writes = 0
        self._watchers = 0               # monitored items clients created: a client is there
        self._row = 0                    # the running row being served
        self.clock_set = clock_set       # (row, s): the server's clock set forward from that row
        self.machine_at: dict[float, float] = {}   # the server's clock (s) -> the machine's

    async def _start(self, companions=COMPANIONS, registers=None) -> None:
        server = Server(user_manager=_Users(self.users))
        await server.init(await asyncio.to_thread(standard_shelf_or_none))
        server.set_endpoint(f"opc.tcp://127.0.0.1:{self.port}")
        server.set_server_name("CNC5000 vendor server")
        server.disable_clock()           # its clock is the record's
        for uri in companions:
            await server.register_namespace(uri)
        idx = await server.register_namespace(VENDOR_NS)
        self.indices.append(idx)
        machine = await server.nodes.objects.add_object(idx, "CNC5000")
        monitoring = await machine.add_folder(idx, "Monitoring")
        self.sensor_nodes = {}
        for column, node in self.sensors.items():
            folder = await monitoring.add_folder(idx, column.removeprefix("T_"))
            var = await folder.add_variable(ua.NodeId.from_string(f"ns={idx};{node}"),
                                            "Temperature", ua.Variant(0.0, ua.VariantType.Float))
            await var.add_property(idx, "EngineeringUnits", CELSIUS)
            await var.add_property(idx, "EURange", ua.Range(Low=-20.0, High=120.0))
            self.sensor_nodes[column] = var
        production = await machine.add_folder(idx, "Production")
        self.program = await production.add_variable(ua.NodeId.from_string(f"ns={idx};{PROGRAM}"),
                                                     "ActiveProgram", ua.Variant("", ua.VariantType.String))
        compensation = await machine.add_folder(idx, "Compensation")
        self.offset_nodes = {}
        for target, (node, vt, _) in self.offsets.items():
            var = await compensation.add_variable(ua.NodeId.from_string(f"ns={idx};{node}"),
                                                  f"Offset{target}", ua.Variant(0, vt))
            if registers is not None:    # the NC's register, as it holds it (µm)
                held = registers[list(self.offsets).index(target)] / self.offsets[target][2]
                await var.write_value(ua.Variant(float(held) if vt in (ua.VariantType.Float,
                                                 ua.VariantType.Double) else int(round(held)), vt))
            if target not in self.refused:
                await var.set_writable()
            self.offset_nodes[target] = var
        ids = {v.nodeid: t for t, v in self.offset_nodes.items()}

        def on_write(event, _dispatcher) -> None:
            if not event.is_external:
                return
            wrote = {}
            for wv, code in zip(event.request_params.NodesToWrite, event.response_params):
                if wv.NodeId in ids:
                    target = ids[wv.NodeId]
                    self.served.types[target] = wv.Value.Value.VariantType
                    if code.is_good():
                        wrote[target] = float(wv.Value.Value.Value) * self.offsets[target][2]
            if wrote:                    # Writes that set offsets, not nodes: a handover counts them
                self._writes += 1
                self.served.writes.append((self._row, wrote))

        def on_subscribed(event, _dispatcher) -> None:
            self._watchers += event.is_external

        server.subscribe_server_callback(CallbackType.PostWrite, on_write)
        server.subscribe_server_callback(CallbackType.ItemSubscriptionCreated, on_subscribed)
        self.clock_node = server.get_node(ua.NodeId(ua.ObjectIds.Server_ServerStatus_CurrentTime))
        await server.start()
        self.server = server

    async def _registers(self) -> np.ndarray:
        return np.array([float(await self.offset_nodes[t].read_value()) * self.offsets[t][2]
                         for t in self.offsets])

    async def _publish(self, row: pd.Series, k: int, program: str, last: dict, start: float) -> None:
        machine_s = start + float(row["time"])
        ahead = self.clock_set[1] if self.clock_set and k >= self.clock_set[0] else 0.0
        at = EPOCH + timedelta(seconds=machine_s + ahead)
        self.machine_at[at.timestamp()] = machine_s
        for column, var in self.sensor_nodes.items():
            first, end, code = self.bad.get(column, (-1, -2, None))
            if first <= k <= end:        # the sensor dropped: its last value held, not Good
                dv = ua.DataValue(ua.Variant(last.get(column, 0.0), ua.VariantType.Float),
                                  StatusCode=ua.StatusCode(code),
                                  SourceTimestamp=at, ServerTimestamp=at)
                await var.write_value(dv)
                continue
            v = float(row[column])
            if (column in last and abs(v - last[column]) <= self.deadband
                    and k - 1 not in range(first, end + 1)):
                continue                 # within the deadband: not published
            last[column] = v
            await var.write_value(ua.DataValue(ua.Variant(v, ua.VariantType.Float),
                                               SourceTimestamp=at, ServerTimestamp=at))
        await self.program.write_value(ua.Variant(program, ua.VariantType.String))
        await self.clock_node.write_value(ua.Variant(at, ua.VariantType.DateTime))   # last

    async def serve(self) -> Served:
        quiet_asyncua()
        await self._start()
        self.listening.set()
        down, last, k = None, {}, 0
        starts, at = {}, 0.0    # the machine's clock goes on: a program starts after the one before
        for program, df in self.campaigns.items():
            starts[program] = at - float(df["time"].iloc[0])
            at += float(df["time"].iloc[-1] - df["time"].iloc[0]) + SETUP_S
        deadline = clock.monotonic() + self.wait_s
        while not self._watchers and clock.monotonic() < deadline and not self.closing.is_set():
            await asyncio.sleep(0.01)    # the first row for a client (subscribed), not before
        try:
            for program, df in self.campaigns.items():
                for _, row in df.iterrows():
                    self._row = k
                    out = any(a <= k < a + n for a, n in self.restarts)
                    if out and down is None:
                        kept = await self._registers()      # the NC's, across the restart
                        down = asyncio.create_task(self.server.stop())
                    elif not out and down is not None:
                        await down
                        down = None
                        if self.renumbered:     # a new server process: every value published
                            await self._start((*COMPANIONS, RENUMBERING), kept)
                            last = {}
                        else:
                            await self.server.start()
                    self.served.program.append(program)
                    if out:
                        await asyncio.sleep(0.02)           # the machine runs on
                        self.served.offsets.append(np.full(len(self.offsets), np.nan))
                        self.served.answered.append(False)
                        k += 1
                        continue
                    before = self._writes
                    await self._publish(row, k, program, last, starts[program])
                    if self.handover is not None and k > self.handover[0]:
                        if k <= sum(self.handover):      # no client: the machine runs on
                            self.served.answered.append(False)
                            self.served.offsets.append(np.full(len(self.offsets), np.nan))
                            k += 1
                            continue
                        if k == sum(self.handover) + 1:  # a new client: its answer
                            self.handed_over.set()
                    deadline = clock.monotonic() + self.wait_s
                    while (self._writes <= before and clock.monotonic() < deadline
                           and not self.closing.is_set()):
                        await asyncio.sleep(0.002)
                    self.served.answered.append(self._writes > before)
                    self.served.offsets.append(await self._registers())
                    if self.handover is not None and k == self.handover[0]:
                        os.kill(self.stop_pid or os.getpid(), self.stop_signal)   # stopped
                        while not self.stopped.is_set() and not self.closing.is_set():
                            await asyncio.sleep(0.01)
                    k += 1
                    if self.closing.is_set() or (self.stop_after is not None
                                                 and k >= self.stop_after):
                        break
                else:
                    continue
                break
            if self.served.answered[-1] and not self.closing.is_set():
                os.kill(self.stop_pid or os.getpid(), self.stop_signal)   # the user stops the client
                await asyncio.sleep(1.0)
        finally:
            if down is not None:
                await down
            else:
                await self.server.stop()
        return self.served


def as_published(campaigns: dict[str, pd.DataFrame], deadband: float = 0.0,
                 bad: dict | None = None, sensors: dict | None = None) -> dict[str, pd.DataFrame]:
    """The rows as a client reads them from :class:`VendorMachine`: Float values, a value within
    the deadband of the last one published held, NaN where the sensor is Bad."""
    bad, out, last, k = bad or {}, {}, {}, 0
    for program, df in campaigns.items():
        df = df.copy()
        for i in range(len(df)):
            for column in sensors or SENSORS:
                first, end, _ = bad.get(column, (-1, -2, None))
                v = float(np.float32(df[column].iloc[i]))
                if first <= k <= end:
                    df.loc[df.index[i], column] = np.nan
                    continue
                if not (column in last and abs(float(df[column].iloc[i]) - last[column][0])
                        <= deadband and not first <= k - 1 <= end):
                    last[column] = (float(df[column].iloc[i]), v)
                df.loc[df.index[i], column] = last[column][1]
            k += 1
        out[program] = df
    return out


def served_in_thread(machine: VendorMachine) -> threading.Thread:
    """``machine`` serving in a daemon thread (its own asyncio loop); what it raised in
    ``machine.raised``."""
    def run() -> None:
        try:
            asyncio.run(machine.serve())
        except BaseException as exc:     # said by the test, not lost in the thread
            machine.raised.append(exc)

    thread = threading.Thread(target=run, name="vendor", daemon=True)
    thread.start()
    # a client started before the endpoint listens logs a link_lost first (a loaded CI machine
    # did): the tests count the outages they make, not the server's start-up
    while not machine.listening.wait(0.05) and thread.is_alive():
        pass
    return thread
