"""CPU of a twin start (``Twin._start``: the OPC UA server with the twin's nodes), first and after.

Usage::

    python benchmarks/bench_twin_start.py [starts]      # default 3, in this one process

Run it twice: the first run of an asyncua/Python pair makes the standard address space's shelf
(:mod:`thermocomp.apps.machine.shelf`), the runs after load it.  Measured on the shared 2-core
machine (load 2-4), CPU (user + sys of this process, its threads included), main 39b980b ->
fix/startup52::

    start                              main (built at every start)   fix/startup52
    first ever (makes the shelf)       2.26-2.50 s                   5.48 s (once per version)
    first of a process, shelf there    2.26-2.50 s                   0.30 s
    later ones in the process          2.29-3.16 s                   0.14-0.16 s

tests/shell/test_twin.py, tests/apps/test_twin_lockstep.py and tests/shell/test_machine_routes.py
together (pytest, /usr/bin/time user+sys): 45.6 -> 35.6 s.  A client walking the standard nodes
(Objects and Types, 3 levels, 1880 nodes: the same ones either way) pays the lazy loading:
1.35-1.47 -> 1.89-1.94 s; thermocomp's client reads its nodes by id and browses none.
"""

from __future__ import annotations

import asyncio
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from cpu import cpu_seconds  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from conftest import free_port  # noqa: E402
from thermocomp.apps.machine.nodes import NodeMap  # noqa: E402
from thermocomp.apps.machine.twin import Twin  # noqa: E402

NODES = NodeMap(namespace="http://thermocomp.org/machine/", input="ns=2;s=M.{column}",
                offset="ns=2;s=C.{target}", offset_sample="ns=2;s=C.Answered",
                sample="ns=2;s=P.Sample", campaign="ns=2;s=P.Campaign",
                campaign_sample="ns=2;s=P.CampaignSample", done="ns=2;s=P.Done")


cpu = cpu_seconds


async def start() -> float:
    twin = Twin(NODES, {"K01": pd.DataFrame({"T_0": [20.0]})}, ["T_0"], {"K01": np.zeros((1, 1))},
                ["E_X"], port=free_port())
    before = cpu()
    await twin._start()
    spent = cpu() - before
    await twin.server.stop()
    return spent


if __name__ == "__main__":
    for i in range(int(sys.argv[1]) if len(sys.argv) > 1 else 3):
        print(f"start {i}: {asyncio.run(start()):.3f} s CPU")
