"""The node ids of the virtual machine's address space, from ``connect.nodes`` (pure).

Patterns hold ``{column}`` (a temperature, state or ``time`` input) or ``{target}`` (a
compensation offset); the status nodes are plain ids.  The twin serves these nodes, the
client reads and writes them: one mapping for both (``conf/connect/default.yaml`` is a
umati-style example).  (opcua67) A vendor's server is none of that: ``inputs`` and ``offsets``
name a node per column or target (over the patterns), any id may name its namespace by its URI
(``nsu=<uri>;s=...``, resolved against the server's namespace array at each connection, as its
index is the server's to choose), and the status nodes may be absent (None): see
:class:`NodeMap`.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from dataclasses import dataclass, field

STATUS = ("sample", "campaign", "campaign_sample", "done", "offset_sample")
NSU = "nsu="


class NodesUnknown(ValueError):
    """A node id the server does not know (or a namespace URI it does not hold)."""


def resolve_id(node_id: str, namespaces: list[str]) -> str:
    """``nsu=<uri>;<id>`` as ``ns=<index of uri in the server's namespaces>;<id>``; any other
    id as it is."""
    if not node_id.startswith(NSU):
        return node_id
    uri, sep, rest = node_id[len(NSU):].partition(";")
    if not sep or not rest:
        raise NodesUnknown(f"{node_id}: nsu=<namespace URI>;<identifier> (s=, i=, g= or b=)")
    if uri not in namespaces:
        raise NodesUnknown(f"{node_id}: the server has no namespace {uri!r} (its namespaces: "
                           f"{', '.join(namespaces)})")
    return f"ns={namespaces.index(uri)};{rest}"


@dataclass(frozen=True)
class NodeMap:
    """Node id patterns and the namespace they live in.

    ``sample`` (Int64): the running sample number, written last when a sample is published;
    ``campaign`` (String) and ``campaign_sample`` (Int64): where that sample is;
    ``done`` (Boolean): the campaigns are over; ``offset_sample`` (Int64, written by the client):
    the sample the offsets it last wrote answer; ``reference`` (Double per target, with
    ``{target}``): the error measured at the sample (a reference measurement), NaN on the others.

    (opcua67) Each status node may be None, the server has none: without ``sample`` the client
    samples on its clock (``connect.clock``, every ``connect.period_s``), without ``campaign``
    one campaign runs from the first sample (``campaign_sample``: counted from there), without
    ``done`` it runs until stopped (SIGINT/SIGTERM), without ``offset_sample`` the offsets are
    written alone.  ``inputs`` / ``offsets``: a node per column / target, over the patterns;
    ``offset_unit_um``: µm per unit of the offset nodes (0.1: an Int32 in 0.1 µm), one for all
    or per target (``{E_Z: 0.1}``, 1 for a target not named).
    """

    namespace: str
    input: str
    offset: str
    sample: str | None
    campaign: str | None
    campaign_sample: str | None
    done: str | None
    offset_sample: str | None
    reference: str = "ns=2;s=Machine.Measurement.{target}"
    inputs: Mapping = field(default_factory=dict)
    offsets: Mapping = field(default_factory=dict)
    offset_unit_um: float | Mapping = 1.0

    @classmethod
    def from_config(cls, nodes: Mapping) -> "NodeMap":
        def given(k):
            v = nodes.get(k)
            return None if v is None else str(v)

        optional = {"reference": str(nodes["reference"])} if "reference" in nodes else {}
        for k in ("inputs", "offsets"):
            if nodes.get(k):
                optional[k] = {str(c): str(n) for c, n in nodes[k].items()}
        unit = nodes.get("offset_unit_um")
        if isinstance(unit, Mapping):
            optional["offset_unit_um"] = {str(t): float(u) for t, u in unit.items()}
        elif unit is not None:
            optional["offset_unit_um"] = float(unit)
        return cls(**{k: str(nodes[k]) for k in ("namespace", "input", "offset")},
                   **{k: given(k) for k in STATUS}, **optional)

    def missing(self) -> list[str]:
        """The status nodes the server does not have (None)."""
        return [k for k in STATUS if getattr(self, k) is None]

    def input_id(self, column: str) -> str:
        return self.inputs.get(column) or self.input.format(column=column)

    def unit_um(self, target: str) -> float:
        """µm per unit of ``target``'s offset node."""
        u = self.offset_unit_um
        return float(u.get(target, 1.0)) if isinstance(u, Mapping) else float(u)

    def offset_id(self, target: str) -> str:
        return self.offsets.get(target) or self.offset.format(target=target)

    def reference_id(self, target: str) -> str:
        return self.reference.format(target=target)


def quiet_asyncua() -> None:
    """asyncua logs a dropped link as a traceback and revised settings as warnings; the link's
    events are the client's own (``connect.json``), so only its errors that end a run show."""
    logging.getLogger("asyncua").setLevel(logging.CRITICAL)
