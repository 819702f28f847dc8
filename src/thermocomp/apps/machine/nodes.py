"""The node ids of the virtual machine's address space, from ``connect.nodes`` (pure).

Patterns hold ``{column}`` (a temperature, state or ``time`` input) or ``{target}`` (a
compensation offset); the status nodes are plain ids.  The twin serves these nodes, the
client reads and writes them: one mapping for both (``conf/connect/umati.yaml`` is a
umati-style example).
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from dataclasses import dataclass

STATUS = ("sample", "campaign", "campaign_sample", "done", "offset_sample")


@dataclass(frozen=True)
class NodeMap:
    """Node id patterns and the namespace they live in.

    ``sample`` (Int64): the running sample number, written last when a sample is published;
    ``campaign`` (String) and ``campaign_sample`` (Int64): where that sample is;
    ``done`` (Boolean): the campaigns are over; ``offset_sample`` (Int64, written by the client):
    the sample the offsets it last wrote answer; ``reference`` (Double per target, with
    ``{target}``): the error measured at the sample (a reference measurement), NaN on the others.
    """

    namespace: str
    input: str
    offset: str
    sample: str
    campaign: str
    campaign_sample: str
    done: str
    offset_sample: str
    reference: str = "ns=2;s=Machine.Measurement.{target}"

    @classmethod
    def from_config(cls, nodes: Mapping) -> "NodeMap":
        keys = ("namespace", "input", "offset", *STATUS)
        optional = {"reference": str(nodes["reference"])} if "reference" in nodes else {}
        return cls(**{k: str(nodes[k]) for k in keys}, **optional)

    def input_id(self, column: str) -> str:
        return self.input.format(column=column)

    def offset_id(self, target: str) -> str:
        return self.offset.format(target=target)

    def reference_id(self, target: str) -> str:
        return self.reference.format(target=target)


def quiet_asyncua() -> None:
    """asyncua logs a dropped link as a traceback and revised settings as warnings; the link's
    events are the client's own (``connect.json``), so only its errors that end a run show."""
    logging.getLogger("asyncua").setLevel(logging.CRITICAL)
