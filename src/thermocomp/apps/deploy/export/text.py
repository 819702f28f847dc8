"""What every generated file says of itself: the provenance banner, the output names."""

from __future__ import annotations

import sys

from ....core.metrics import angular
from ..naming import correction_column


def correction_names(targets) -> list[str]:
    """``E_X`` -> ``C_X``: the corrections the code outputs, as the served model names them."""
    return [correction_column(t) for t in targets]


def ascii_name(name: str) -> str:
    """``name`` in ASCII, each other character escaped as Python writes it (``T_S\\xe4ule``): a
    PLC's or an old compiler's source is read as ASCII, and a contract name takes a lab's letters
    (``Säule [°C]`` -> ``T_Säule``)."""
    return str(name).encode("ascii", "backslashreplace").decode("ascii")


def per_target(laws: dict) -> str:
    """``'E_X lagbank; E_Z blend mlr 0.93 + lagbank 0.07'``: what ``model=auto`` kept per target,
    or an ATI model's intervals (``provenance.laws``)."""
    return "; ".join(f"{ascii_name(t)} {ascii_name(_in_degc(law))}" for t, law in laws.items())


def _in_degc(text: str) -> str:
    """A diagnosed law's ``°C`` (``x (ambient_c0 - 20°C)``) as the banner writes units,
    ``degC``: escaped, it read ``20\\xb0C`` in the code and the export's message."""
    return str(text).replace("°C", " degC").replace("°", " deg")


def time_use(ss) -> str:
    """What reads the time, and the step a bad time is replaced by (the time rule's): a model
    without lags under an adaptive guard reads it too (its rate limit is per second); the banner
    said "not read; period 0 s" of it, the lag period of a model without lags."""
    readers = [who for who, reads in (("the first-order lags", ss.uses_time),
                                      ("the guard's rate limit", ss.guard and any(
                                          r is not None for r in ss.guard_rate or []))) if reads]
    period = ss.time_period or ss.period         # the time rule's step (core.timerule)
    return (f"read by {' and '.join(readers)}" if readers else "not read") + (
        f"; a missing or backward time is the previous + {period:.6g} s, the times after a "
        "backward one counting on from it (a clock started again)" if period else "")


def banner(ss, open_: str, middle: str, close: str) -> str:
    """A comment block: what the code is, where it came from, its inputs, units and bounds."""
    p = ss.provenance
    lines = ["thermocomp compensator, generated code (thermocomp export): do not edit.",
             f"model: {p.get('model', '?')}  source: {p.get('source', '?')}",
             f"run: {p.get('run_id') or '-'}  dataset sha256: {p.get('dataset_hash') or '-'}",
             f"thermocomp {p.get('version', '?')}  exported {p.get('exported', '?')}",
             *([f"per target: {per_target(p['laws'])}"] if p.get("laws") else []),
             "inputs, in order (raw values as measured; T_ in degC, taken relative to a campaign's "
             "first sample where starred):"]
    for j, c in enumerate(ss.inputs):
        ref = "*" if ss.referenced[j] else " "
        bounded = ss.clamp and ss.hi[j] < sys.float_info.max      # a machine state is not
        env = f"[{ss.lo[j]:.6g}, {ss.hi[j]:.6g}]" if bounded else "not clamped"
        lab = p.get("lab_names", {}).get(c)
        held = "  held when missing (a diagnosed effect's signal)" if (ss.held or [0] * (j + 1))[j] else ""
        lines.append(f"  {j}: {ascii_name(c)}{ref} {p.get('units', {}).get(c, '')}  envelope {env}{held}"
                     + (f"  (the lab's {lab!a})" if lab else ""))   # ASCII: a PLC's source
    lines.append(f"time: s, {time_use(ss)}")
    tilts = [t for t in ss.targets if angular(t)]     # (iso67: a tilt's correction in um/m)
    lines.append("outputs: " + ", ".join(map(ascii_name, correction_names(ss.targets)))
                 + " in um" + (f" ({', '.join(map(ascii_name, correction_names(tilts)))} in um/m "
                               "= urad, angular errors)" if tilts else "")
                 + " (the correction: minus the predicted error)")
    for i, t in enumerate(ss.targets if ss.guard else []):
        rate, um = ss.guard_rate[i], "um/m" if angular(t) else "um"
        lines.append(f"guard {ascii_name(t)}: bound [{ss.guard_lo[i]:.6g}, {ss.guard_hi[i]:.6g}] "
                     f"{um}, rate limit " + ("none" if rate is None else (
                         f"over a step or {ss.guard_period:.6g} s, the longer: {rate:.6g} {um}/s")))
    if ss.guard and ss.guard_inputs:
        lines.append("guard bound widens by guard_gain . d on the training pattern, d the inputs' "
                     "distance beyond their training range [guard_in_lo, guard_in_hi]")
    if ss.adapt != "none":
        lines.append(f"adapt: {ss.adapt}, learned from reference measurements of "
                     + ", ".join(map(ascii_name, ss.targets)) + " (tc_reference; ST: ref_valid, ref_error)")
    if p.get("not_in_code"):
        lines.append("not in the code (the served model only): " + "; ".join(p["not_in_code"]))
    body = "\n".join(f"{middle} {line}".rstrip() for line in lines)
    return f"{open_}\n{body}\n{close}"
