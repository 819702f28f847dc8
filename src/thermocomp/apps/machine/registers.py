"""An offset as a machine's register holds it (opcua67; its own module since opcleft67): in the
offset node's own DataType and unit (``offset_unit_um``), a Float the value rounded to float32,
an integer the nearest count, refused beyond the integer type's range (pure: no server)."""

from __future__ import annotations

import numpy as np
from asyncua import ua

FLOATS = (ua.VariantType.Double, ua.VariantType.Float)
INT_RANGE = {ua.VariantType.SByte: (-2 ** 7, 2 ** 7 - 1), ua.VariantType.Int16: (-2 ** 15, 2 ** 15 - 1),
             ua.VariantType.Int32: (-2 ** 31, 2 ** 31 - 1), ua.VariantType.Int64: (-2 ** 63, 2 ** 63 - 1)}
WRITABLE = (*FLOATS, *INT_RANGE)


class WriteRefused(RuntimeError):
    """The server refused to write an offset (its StatusCode, the node), or an offset is beyond
    its integer node's range."""


def as_registers(values, units, types, targets, node_ids) -> tuple[list, np.ndarray]:
    """``(variants to write, what the registers then hold in µm)`` of the offsets ``values`` (µm)
    in their nodes' ``types`` and ``units`` (µm per unit); WriteRefused naming the target, its
    node (``node_ids``), the offset and the range where an integer node cannot hold it (none of
    them is then written: one Write)."""
    values, units = np.asarray(values, float), np.asarray(units, float)
    counts = [v / u if vt in FLOATS else float(np.rint(v / u))
              for v, u, vt in zip(values, units, types)]
    for t, n, v, u, c, vt in zip(targets, node_ids, values, units, counts, types):
        if vt in INT_RANGE and not INT_RANGE[vt][0] <= c <= INT_RANGE[vt][1]:
            lo, hi = INT_RANGE[vt]
            raise WriteRefused(f"offset {t} ({n}): {v:.6g} µm is {c:.0f} counts of {u:g} µm "
                               f"(offset_unit_um), beyond its {vt.name}'s {lo} to {hi} "
                               f"({lo * u:.6g} to {hi * u:.6g} µm)")
    data = [ua.Variant(c if vt in FLOATS else int(c), vt) for c, vt in zip(counts, types)]
    held = np.array([float(np.float32(c)) if vt == ua.VariantType.Float else c
                     for c, vt in zip(counts, types)]) * units
    return data, held
