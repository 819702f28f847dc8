"""`thermocomp export`: a deployed compensator as coefficients and code a CNC runs (pure core).

:func:`exported_files` turns a deployed compensator into ``{file name: text}``:

* ``json`` -- ``compensator.json``, the state-space arrays (:mod:`.statespace`);
* ``c`` -- ``compensator.h``, ``compensator.c`` and the CSV driver ``stream.c`` (:mod:`.c`);
* ``st`` -- ``compensator.st``, an IEC 61131-3 function block (:mod:`.st`).

Of an adaptive compensator the time rule and the correction guard are in the code, and the
reference update of ``adapt.method`` (:mod:`.output`); a Hammerstein model's static powers too,
and a diagnosed model's lags, products, squares, (exportrest60) lags' initial-state transients
and (export62) a state times the inputs' rises as derived inputs
(:func:`.derived.derived_inputs`), its ambient steps as laws of the initial
ambient, a lag bank's lag of its lag as a cascade, around a plain or an ATI model; (exportrest62)
an ATI model whose ambient is the manifest's (given at a campaign's start), and ``arx_rf``, its
ARX a law and its forest flat arrays the code walks (:mod:`.forest`); (lstmexport62) ``lstm``,
its skip path a law and its network's weights arrays the code steps per sample, in double
(:mod:`.recurrent`), plain or a ``model=auto`` blend member; (exportati63) both within an ATI
model, each interval's forest or network counting in its interval, and arx_rf under a diagnosed
model's effects; (exportlstm64) lstm under a diagnosed model with any of those effects, its
network reading the features the code computes for them (:func:`.recurrent.net_reads`);
(exportprod65) a state times the inputs' rises around an ATI model too; (diag107b) the lean level
laws (``ambient_scaled``, ``ambient_mean``) as the ambient law's block (:mod:`.derived`).
Every format also writes ``compensator.json``, the arrays the code was generated from.  Only the
families of :data:`~.laws.LINEAR_FAMILIES` export, and what ``model=auto`` keeps of them (one, or
a blend) and the ATI wrapper of them (:mod:`.laws`); any other model is refused
(:class:`~.errors.NotExportable`) with one line naming them.
"""

from __future__ import annotations

import json

from .errors import NotExportable
from .laws import EXPORTED_FAMILIES
from .left_out import not_in_code, with_st_fallbacks
from .statespace import FORMATS, LINEAR_FAMILIES, Simulator, StateSpace, state_space

__all__ = ["FORMATS", "LINEAR_FAMILIES", "NotExportable", "Simulator", "StateSpace", "check_exportable",
           "exported_files", "not_in_code", "state_space"]


def _check_format(fmt: str) -> None:
    if fmt not in FORMATS:
        raise NotExportable(f"export.format={fmt!r}: one of {', '.join(FORMATS)}")
    if fmt == "onnx":
        raise NotExportable("export.format=onnx: no ONNX export is implemented yet; the families "
                            f"{EXPORTED_FAMILIES} export to json, c and st")


def check_exportable(compensator, fmt: str) -> None:
    """:class:`NotExportable` for what keeps a fitted ``compensator`` from exporting as ``fmt``
    however it is deployed (the format, the family, the denoiser, the columns it reads): the
    checks of :func:`exported_files` on its plain stream without an envelope, so that a model
    is refused before its envelope and guard are derived from data.  One that cannot stream at
    all is left to its deployment, which says so."""
    from ..streaming import StreamingCompensator

    _check_format(fmt)
    try:
        stream = StreamingCompensator(compensator)
    except ValueError:
        return
    state_space(stream, known_ambient=False)


def exported_files(deployed, fmt: str, provenance: dict | None = None,
                   monitor: bool = True) -> dict[str, str]:
    """``{file name: text}`` of format ``fmt`` for the ``deployed`` stream or adaptive
    compensator (its plain stream, correction guard and reference update; the C, unless not
    ``monitor``, its sensor monitor's slice: :mod:`.watch`)."""
    _check_format(fmt)
    ss = state_space(deployed, provenance, monitor=monitor and fmt == "c")
    # (st93) the ST block's monitor: its detection, as outputs; (st103b) with the fallback
    # models' laws beside the model's, served while the block holds their sensor out
    watch = {}
    if fmt == "st" and monitor:
        from .watch import monitor_fields

        watch = monitor_fields(deployed, list(ss.inputs)).get("monitor", {})
        with_st_fallbacks(ss, deployed, watch)
    files = {"compensator.json": json.dumps(ss.to_dict(), indent=1) + "\n"}
    if fmt == "c":
        from . import c
        from .driver import DRIVER

        files.update({"compensator.h": c.header(ss), "compensator.c": c.source(ss),
                      "stream.c": DRIVER})
    elif fmt == "st":
        from . import st

        files["compensator.st"] = st.function_block(ss, watch)
    return files
