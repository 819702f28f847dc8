"""Plain JSON data from results that hold NumPy values and NaN (JSON has no NaN).

Core and shell both import this module; it depends on NumPy only.
"""

from __future__ import annotations

import numpy as np


def json_safe(obj):
    """A copy of ``obj`` that :func:`json.dumps` writes with ``allow_nan=False``.

    Recursively: NaN and ±inf become ``None``; NumPy scalars become Python
    scalars; NumPy arrays, tuples and lists become lists; dict keys that are
    NumPy scalars become Python ones.  Other objects are returned unchanged.

    Parameters
    ----------
    obj : object
        A scalar, or nested dicts / lists / tuples / arrays of them.

    Returns
    -------
    object
        ``float(obj)`` for a finite float (``None`` otherwise), and so on.
    """
    if isinstance(obj, dict):
        return {_key(k): json_safe(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple, np.ndarray)):
        return [json_safe(v) for v in obj]
    if isinstance(obj, (float, np.floating)):
        return float(obj) if np.isfinite(obj) else None
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def _key(k):
    return k.item() if isinstance(k, np.generic) else k
