"""What the simulated machines of the stranger benches share (grinder77, vtl78, jig80, edm81):
each keeps its own network, sensors and kinematics; only the network's conductance matrix is
built one way."""

from __future__ import annotations

import numpy as np


def laplacian(nodes: list[str], links, h_air: np.ndarray) -> np.ndarray:
    """Conductances (W/K) of ``links`` (``(node, node, W/K)``) as a Laplacian over ``nodes``, plus
    each node's conductance to the air ``h_air`` on the diagonal."""
    g = np.diag(h_air.copy())
    for a, b, w in links:
        i, j = nodes.index(a), nodes.index(b)
        g[i, i] += w
        g[j, j] += w
        g[i, j] -= w
        g[j, i] -= w
    return g
