"""`thermocomp export`: a deployed compensator as coefficients and code a CNC runs (pure core).

:func:`exported_files` turns a deployed compensator into ``{file name: text}``:

* ``json`` -- ``compensator.json``, the state-space arrays (:mod:`.statespace`);
* ``c`` -- ``compensator.h``, ``compensator.c`` and the CSV driver ``stream.c`` (:mod:`.c`);
* ``st`` -- ``compensator.st``, an IEC 61131-3 function block (:mod:`.st`).

Of an adaptive compensator the time rule and the correction guard are in the code, and the
reference update of ``adapt.method`` (:mod:`.output`); a Hammerstein model's static powers too.
Every format also writes ``compensator.json``, the arrays the code was generated from.  Only the
families of :data:`~.statespace.LINEAR_FAMILIES` export; any other model is refused
(:class:`~.errors.NotExportable`) with one line naming them.
"""

from __future__ import annotations

import json

from .errors import NotExportable
from .output import not_in_code
from .statespace import FORMATS, LINEAR_FAMILIES, Simulator, StateSpace, state_space

__all__ = ["FORMATS", "LINEAR_FAMILIES", "NotExportable", "Simulator", "StateSpace", "exported_files",
           "not_in_code", "state_space"]


def exported_files(deployed, fmt: str, provenance: dict | None = None) -> dict[str, str]:
    """``{file name: text}`` of format ``fmt`` for the ``deployed`` stream or adaptive
    compensator (its plain stream, correction guard and reference update)."""
    if fmt not in FORMATS:
        raise NotExportable(f"export.format={fmt!r}: one of {', '.join(FORMATS)}")
    if fmt == "onnx":
        raise NotExportable("export.format=onnx: no ONNX export is implemented yet; the linear "
                            f"families ({', '.join(LINEAR_FAMILIES)}) export to json, c and st")
    ss = state_space(deployed, provenance)
    files = {"compensator.json": json.dumps(ss.to_dict(), indent=1) + "\n"}
    if fmt == "c":
        from . import c

        files.update({"compensator.h": c.header(ss), "compensator.c": c.source(ss),
                      "stream.c": c.DRIVER})
    elif fmt == "st":
        from . import st

        files["compensator.st"] = st.function_block(ss)
    return files
