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


def lagged_readings(temps: np.ndarray, ambient: dict[str, np.ndarray], sensors, nodes: list[str],
                    step_s: float, noise: float, decimals: int, rng: np.random.Generator) -> np.ndarray:
    """Each sensor's reading (jig80, edm81): its truth -- an ``ambient`` series by name, or a weighted
    sum of ``temps``' nodes -- through a first-order lag of its time constant (s), plus white noise of
    ``noise`` K, rounded to ``decimals``.  ``sensors``: ``(name, where, lag_s)``.  (grinder77 and
    vtl78 write the same lag as an explicit recursion, whose last bits differ: their recorded
    figures were measured with it.)"""
    from scipy.signal import lfilter
    out = np.empty((temps.shape[0], len(sensors)))
    for j, (_, where, lag) in enumerate(sensors):
        if isinstance(where, str):
            truth = ambient[where]
        else:
            truth = sum(wt * temps[:, nodes.index(n)] for n, wt in where.items())
        a = 1.0 - np.exp(-step_s / lag)
        read, _ = lfilter([a], [1.0, a - 1.0], truth, zi=[(1.0 - a) * truth[0]])
        out[:, j] = np.round(read + noise * rng.standard_normal(truth.size), decimals)
    return out
