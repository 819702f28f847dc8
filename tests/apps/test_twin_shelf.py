"""The twin's standard address space is built once, shelved, and loaded from the shelf after
(startup52): asyncua built it at every start (~2.5 s CPU) as its own shelf was never found."""

import asyncio
import os
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pandas as pd
from asyncua import Client, ua
from asyncua.server.standard_address_space import standard_address_space

from thermocomp.apps.machine import shelf
from thermocomp.apps.machine.nodes import NodeMap
from thermocomp.apps.machine.twin import Twin

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from conftest import free_port  # noqa: E402

NODES = NodeMap(namespace="http://thermocomp.org/machine/", input="ns=2;s=M.{column}",
                offset="ns=2;s=C.{target}", offset_sample="ns=2;s=C.Answered",
                sample="ns=2;s=P.Sample", campaign="ns=2;s=P.Campaign",
                campaign_sample="ns=2;s=P.CampaignSample", done="ns=2;s=P.Done")


def twin() -> Twin:
    df = pd.DataFrame({"T_0": [20.0]})
    return Twin(NODES, {"K01": df}, ["T_0"], {"K01": np.zeros((1, 1))}, ["E_X"], port=free_port())


async def start_and_stop() -> None:
    t = twin()
    await t._start()
    await t.server.stop()


async def start_and_read() -> tuple[list[str], list[str], float]:
    """What a client sees of a started twin: the namespaces (a standard node), Objects' children,
    and the value of the twin's own offset register."""
    t = twin()
    await t._start()
    try:
        async with Client(t.endpoint) as client:
            namespaces = await client.get_namespace_array()
            children = [(await n.read_browse_name()).Name
                        for n in await client.nodes.objects.get_children()]
            offset = client.get_node(NODES.offset_id("E_X"))
            await offset.write_value(ua.Variant(1.5, ua.VariantType.Double))
            return namespaces, children, await offset.read_value()
    finally:
        await t.server.stop()


def test_twins_build_the_standard_address_space_once_then_load_its_shelf(tmp_path, monkeypatch):
    monkeypatch.setattr(shelf, "shelf_folder", lambda: tmp_path)
    built = []
    fill = standard_address_space.fill_address_space
    monkeypatch.setattr(standard_address_space, "fill_address_space",
                        lambda *a, **k: (built.append(1), fill(*a, **k))[1])
    # a maker killed outright (its pid gone) left a half-made shelf in its temp folder
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True).stdout.strip()
    version = shelf.version_folder().name
    half = tmp_path / f".{version}.tmp-{dead}-x"
    half.mkdir()
    (half / "standard.dat").write_bytes(b"half")

    # two twins at once (xdist, two tests): one builds, the other waits for the whole shelf
    starts = [threading.Thread(target=asyncio.run, args=(start_and_stop(),)) for _ in range(2)]
    for s in starts:
        s.start()
    for s in starts:
        s.join()
    assert len(built) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == [version, f"{version}.lock"]

    namespaces, children, offset = asyncio.run(start_and_read())    # from the shelf
    assert len(built) == 1
    assert namespaces == ["http://opcfoundation.org/UA/", "urn:freeopcua:python:server",
                          NODES.namespace]
    assert {"Server", "Machine"} <= set(children) and offset == 1.5

    # a file of the shelf damaged (its .dat truncated, a disk full, a copy cut short): made
    # anew, whole, before asyncua reads it (it failed the twin's start: BadInternalError)
    # (a stand-in maker copies the shelf as made: a second real build costs ~2.5 s of CPU)
    nodes = tmp_path / version / shelf.NODES
    pristine = shutil.copytree(nodes, tmp_path / "pristine")
    made = []

    def remake(path):
        made.append(path.parent.parent.name)
        shutil.copytree(pristine, path.parent, dirs_exist_ok=True)

    monkeypatch.setattr(shelf, "_make", remake)
    dat = nodes / f"{shelf.SHELF}.dat"
    os.truncate(dat, dat.stat().st_size // 2)
    namespaces, children, offset = asyncio.run(start_and_read())
    assert len(made) == 1 and made[0] != version    # made in a folder of its own, then renamed
    assert {"Server", "Machine"} <= set(children) and offset == 1.5 and len(built) == 1
    assert dat.stat().st_size == (pristine / dat.name).stat().st_size

    # the empty <shelf> asyncua looks for, swept by a temp cleaner (never read, it ages): the
    # shelf is made anew, whole, not rewritten in place by asyncua under the twins reading it
    (nodes / shelf.SHELF).unlink()
    assert shelf.standard_shelf() == nodes / shelf.SHELF
    assert len(made) == 2 and (nodes / shelf.SHELF).is_file() and len(built) == 1
    assert shelf.standard_shelf() == nodes / shelf.SHELF and len(made) == 2   # whole: read


def test_a_twin_starts_where_no_shelf_can_be_made(tmp_path, monkeypatch, caplog):
    """A temp folder the twin cannot write (or a lock held too long): the address space is built
    at this start, as before the shelf, with a warning; the twin serves all the same."""
    monkeypatch.setattr(shelf, "shelf_folder", lambda: tmp_path / "not-a-folder" / "x")
    (tmp_path / "not-a-folder").write_text("a file where the folder would be")
    built = []
    fill = standard_address_space.fill_address_space
    monkeypatch.setattr(standard_address_space, "fill_address_space",
                        lambda *a, **k: (built.append(1), fill(*a, **k))[1])
    namespaces, children, offset = asyncio.run(start_and_read())
    assert built == [1] and offset == 1.5 and {"Server", "Machine"} <= set(children)
    assert "built at this start (no shelf" in caplog.text
