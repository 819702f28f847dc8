"""Files whose errors start again at zero: a restart, not a continuation (restart98).

A lab that zeroes its displacement probes before each run (a dial gauge or a capacitive probe
set to 0) writes files whose every error starts at 0, whatever the machine's state; where their
times abut, :func:`~thermocomp.core.continuation.predecessors` links them by time and
``data.reference=auto`` would read the later file as continuing the earlier one (its state
carried over, the errors absolute).  trunnion63 simulates each week so (ham98: E_Z -1.9 µm at
W2's end, +0.1 at W3's first row; hammerstein 1.900 µm warm against 0.383 in each file's own
frame).  A record of one logger that runs on (lr9211 E_Z +12.66 -> +13.35) is not one.

A link is read as a restart where every error of the later campaign starts (its first measured
value ``f``) within :data:`NEAR` steps of 0, and starting at 0 explains those first values
:data:`ODDS` times better than running on from the predecessor's last measured values ``l``
(Gaussian step noise: ``sum((f - l)**2 / s**2) - sum(f**2 / s**2) > 2 ln ODDS`` over the errors),
a jump the record's own steps cannot explain.  An error's step ``s`` is its step noise where the
two files meet: the larger median of ``|diff|`` over the last :data:`EDGE` measured values
before and the first :data:`EDGE` after.  Only the files' own first and last rows are read; no
test split.  Seen (restart98): trunnion63's six junctions 8.0-64 (every ``|f| <= 1.0 s``), lr9211
and fl_thermal's cuts below 0 (``|f|`` 39 s and 1.7-275 s).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from .io.contract import Dataset, role

# ``ds.meta`` key: {campaign: why} of the links ``data.reference=auto`` read as restarts;
# :func:`~thermocomp.core.continuation.predecessors` leaves them out (every stage agrees)
RESTARTED = "restarted"


# measured values each side of a junction whose steps give an error's step noise there
EDGE = 10
# a zeroed probe's first reading lies within this many steps of 0
NEAR = 2.0
# how much better "starts at 0" must explain the first values than "runs on" (likelihood ratio)
ODDS = 20.0


def _measured(values) -> np.ndarray:
    x = np.asarray(values, float)
    return x[np.isfinite(x)]


def _step(before: np.ndarray, after: np.ndarray) -> float:
    """An error's step noise where ``before`` ends and ``after`` begins (0: none read)."""
    sides = [np.abs(np.diff(x)) for x in (before[-EDGE:], after[:EDGE]) if x.size > 1]
    step = max((float(np.median(d)) for d in sides), default=0.0)
    if step > 0:
        return step
    steps = np.abs(np.diff(np.concatenate([before, after])))   # (quantised and still: its resolution)
    steps = steps[steps > 0]
    return float(steps.min()) if steps.size else 0.0


def restart_jump(before, after) -> tuple | None:
    """``(log-odds, error, its last value before, its first after)`` (the error that jumps
    most, in steps) where the campaign ``after`` restarts after ``before`` (frames), None where
    it may continue it (the module's rule)."""
    errors = [c for c in after.columns if role(c) == "E" and c in before.columns]
    terms = []
    for col in errors:
        a, b = _measured(before[col]), _measured(after[col])
        step = _step(a, b) if a.size and b.size else 0.0
        if step <= 0 or abs(b[0]) > NEAR * step:
            return None          # (not measured in one, or starts away from 0: it may run on)
        terms.append((col, a[-1], b[0], (b[0] - a[-1]) / step, b[0] / step))
    odds = 0.5 * sum(j ** 2 - f ** 2 for *_, j, f in terms)
    if not terms or odds <= np.log(ODDS):
        return None
    col, last, first, *_ = max(terms, key=lambda t: abs(t[3]))
    return odds, col, float(last), float(first)


def restarts(ds: Dataset, links: Mapping[str, str]) -> dict[str, str]:
    """``{campaign: why}`` of the ``links`` (campaign -> the one it continues) read as restarts
    (:func:`restart_jump`), said: "W3 restarts after W2: ..."."""
    out = {}
    for cid, prev in links.items():
        before, after = ds.campaigns.get(prev), ds.campaigns.get(cid)
        if before is None or after is None or not len(before) or not len(after):
            continue
        jump = restart_jump(before, after)
        if jump:
            odds, col, last, first = jump
            out[cid] = (f"{cid} restarts after {prev}: every error starts at 0 ({col} "
                        f"{last:+.3g} -> {first:+.3g}; {np.exp(min(odds, 700.0)):.3g}:1 against "
                        f"running on), no state carried over")
    return out
