"""The twin in lockstep waits for a client slower than its period (a loaded machine's client)."""

import asyncio
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from asyncua import Client, ua

from thermocomp.apps.machine.nodes import NodeMap
from thermocomp.apps.machine.twin import Twin

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from conftest import free_port  # noqa: E402

NODES = NodeMap(namespace="http://thermocomp.org/machine/", input="ns=2;s=M.{column}",
                offset="ns=2;s=C.{target}", offset_sample="ns=2;s=C.Answered",
                sample="ns=2;s=P.Sample", campaign="ns=2;s=P.Campaign",
                campaign_sample="ns=2;s=P.CampaignSample", done="ns=2;s=P.Done")
ROWS, PERIOD_S, CLIENT_S = 12, 0.01, 0.06      # the client answers 6 periods late


async def slow_client(url: str) -> list[int]:
    """Answer every new sample ``CLIENT_S`` after seeing it with offset = the sample number."""
    async with Client(url) as client:
        sample = client.get_node(NODES.sample)
        answered = client.get_node(NODES.offset_sample)
        offset = client.get_node(NODES.offset_id("E_X"))
        done = client.get_node(NODES.done)
        await answered.write_value(ua.Variant(-1, ua.VariantType.Int64))
        seen, last = [], -1
        while not await done.read_value():
            k = int(await sample.read_value())
            if k > last:
                await asyncio.sleep(CLIENT_S)
                await offset.write_value(ua.Variant(float(k), ua.VariantType.Double))
                await answered.write_value(ua.Variant(k, ua.VariantType.Int64))
                seen.append(k)
                last = k
            await asyncio.sleep(0.002)
        return seen


async def serve_and_answer(lockstep: bool):
    df = pd.DataFrame({"T_0": np.linspace(20, 21, ROWS)})
    twin = Twin(NODES, {"K01": df}, ["T_0"], {"K01": np.zeros((ROWS, 1))}, ["E_X"],
                port=free_port(), speed=1 / PERIOD_S, wait_s=5.0, lockstep=lockstep)
    served = asyncio.create_task(twin.serve())
    for _ in range(200):                          # until the server is up (10 s at most)
        try:
            seen = await slow_client(twin.endpoint)
            break
        except (ConnectionError, OSError):
            await asyncio.sleep(0.05)
    return await served, seen


def test_lockstep_waits_for_a_client_slower_than_a_period():
    served, seen = asyncio.run(serve_and_answer(lockstep=True))
    assert seen == list(range(ROWS))              # the client saw every sample
    assert not any(served.stale)
    assert [float(o[0]) for o in served.offsets] == [float(k) for k in range(ROWS)]


def test_without_lockstep_the_clock_runs_on():
    served, seen = asyncio.run(serve_and_answer(lockstep=False))
    assert sum(served.stale) >= ROWS // 2         # the control: the same client is late
    assert len(seen) < ROWS
