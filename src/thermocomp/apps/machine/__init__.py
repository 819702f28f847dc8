"""To the machine over OPC UA: a virtual machine tool (:mod:`.twin`) serving a dataset's test
campaigns, and the client (:mod:`.client`) that runs a deployed compensator against one.

:mod:`.nodes` (the node ids both sides use) and :mod:`.offsets` (what may be written to the
machine) are pure; the two others need ``asyncua`` (the ``machine`` extra).
"""

from .nodes import NodeMap
from .offsets import OffsetLimiter

__all__ = ["NodeMap", "OffsetLimiter"]
