"""``model=auto``'s guard to MLR off the training pattern, acting only where the row's AMBIENT stays
inside the train ambient span: does excusing an ambient excursion (not a new heat source) keep
auto's cooling-room win on cr9182 and still fix its column losers?  (issue 34; stop 92, auto92c,
follow-up of bench_auto92 / bench_auto92b).  TRACED (no rule; src as on main)

Usage (from the repository root; ``PYTHONPATH=<tree>/src``; ROOT and WORK as bench_auto92's,
i.e. bench_auto91's ``rows`` already run into WORK)::

    python benchmarks/bench_auto92c.py guard ROOT WORK RECORD ...   # seen records, stored rows
    python benchmarks/bench_auto92c.py rooms RECORD ...             # bench_auto88b's climate rooms

``guard`` and ``rooms`` are bench_auto92's commands (imported through bench_auto92b's hook, same
records, same figures) with the probes below in place of its four.  The pattern gate is
bench_auto92's: :meth:`thermocomp.apps.deploy.streaming.Envelope.leaves_pattern` of an
``Envelope.from_data`` on the train inputs (``T_`` columns less each campaign's first sample, all
inputs), ``PATTERN_ENERGY`` 0.999, ``tol`` the largest train residual.  New here, the AMBIENT
SPAN: a test row's ambient is in span when every ambient input
(:func:`thermocomp.core.io.contract.is_ambient`) lies within that envelope's own bounds, i.e. the
train ambient range widened on each side by ``promote.envelope.margin`` (read from
``conf/promote/default.yaml``, 0.1; not tuned).  Nothing is taken from the test part.

* ``pattern`` / ``both``: bench_auto92's (reference; ``both`` = off the pattern AND beyond the
  bounds on any input);
* ``pattern_inamb``: off the pattern AND the ambient in span;
* ``both_inamb``: ``both`` AND the ambient in span.

A record without an ambient sensor has every row in span (the ``_inamb`` probes equal their
references there).

Trace only (added AFTER the ``_inamb`` scores below, to see which rows carry what; not a rule and
not scored against the bar, since a direction chosen from these records would be fitted to them):
``both_above`` / ``both_below``: ``both``'s rows whose ambient is above / below the span.

Bar: bench_auto92's, unchanged, written here BEFORE any ``_inamb`` number was computed: a guard
is worth building only where on the seen records it fixes >= 2 of the 3 seen losers (col5791,
col1403, lab5401: guarded / MLR <= 1.02) AND keeps year6_5411 and every climate room within 2 %
of auto (year6_5411 guarded / MLR <= 1.02 x its auto / MLR, no room guarded / auto > 1.02) and the
13 rooms' geo mean guarded / auto <= 1.00.  A probe passing that on the seen records earns a
fresh score on seeds 9271-9280 in the NEXT stop; no fresh seed is drawn here.

Scored (2026-12-05, this tree = main 8281b37a, src as 2b918bfd; WORK = /tmp/auto92c/seen, a copy of
auto92's rows, ROOT = /tmp/auto92c/root)
------------------------------------------------------------------------------------------------
``guard /tmp/auto92c/root /tmp/auto92c/seen col5791 col1403 lab5401 year6_5411 col1514 col6512
swiss303 swiss5454 year6511 mill1514`` (6 s CPU) and ``rooms cr9079 cr9182 cr9248 cr9244 cr9181
cr9183 cr9245 cr9031 cr9076 cr9081 cr9083 cr9088 cr9089`` (32 s CPU); 2 shared cores, nice,
``OMP_NUM_THREADS=1``.  ``pattern`` / ``both`` reproduce bench_auto92 to the digit.

Seen records, new campaigns: auto / MLR -> guarded / MLR (share of rows guarded)::

              auto    pattern       both          pattern_inamb  both_inamb    both_above   both_below
  col5791     1.258   0.999 (0.41)  1.004 (0.32)  1.041 (0.33)   1.045 (0.24)  1.240 (0.08) 1.258 (0)
  col1403     1.311   1.111 (0.47)  1.130 (0.32)  1.218 (0.39)   1.234 (0.24)  1.225 (0.08) 1.311 (0)
  lab5401     1.070   1.063 (0.10)  1.070 (0)     1.063 (0.10)   1.070 (0)     1.070 (0)    1.070 (0)
  year6_5411  0.518   0.655 (0.03)  0.518 (0)     0.655 (0.03)   0.518 (0)     0.518 (0)    0.518 (0)
  col1514     1.019   1.006         1.011         1.004          1.010         1.021        1.019
  col6512     1.004   1.000         1.000         1.001          1.001         1.004        1.004
  swiss303 / swiss5454 / year6511 / mill1514: unchanged (within 0.001) under all six.

Test rows (own + new) with the ambient out of span: the four columns 0.14-0.15, every one ABOVE
it (a hotter season); swiss303 / swiss5454 0.03 / 0.02 below, year6511 0.01 above (none of them
guarded by any probe); lab5401 / mill1514 / year6_5411 none.

Climate rooms (own test campaigns), guarded / auto::

              pattern  both   pattern_inamb  both_inamb  both_above  both_below
  cr9079      1.352    1.000  1.352          1.000
  cr9182      1.057    1.054  1.003          1.000       1.000       1.054
  cr9248      1.084    1.000  1.084          1.000
  cr9245      1.008    1.007  1.009          1.008       1.000       0.998
  cr9183 1.003 / 1.003 (pattern / pattern_inamb), cr9076 / 9081 1.001 / 1.004 under both pattern
  probes, cr9244 / 9181 / 9031 / 9083 / 9088 / 9089 none guarded (1.000)
  geo mean    1.036    1.005  1.031          1.001

(Test rows with the ambient out of span: cr9182 0.25, cr9245 0.30, all BELOW it (cooling);
every other room none.)

Against the bar (unchanged, written before scoring): ``both_inamb`` keeps what ``both`` lost on
cr9182 (x1.054 -> x1.000) and every room within 2 % (worst cr9245 x1.008; geo 1.0006, printed
1.001, i.e. just over the <= 1.00 line) and year6_5411 (0.518), BUT it fixes NONE of the three
losers (col5791 1.045, col1403 1.234, lab5401 1.070): excusing the ambient excursion also excuses
the hotter-season rows that carried the last part of col5791's fix (``both`` 1.004 -> 1.045).
``pattern_inamb`` fails as ``pattern`` did (year6_5411 0.655, cr9079 x1.352, geo 1.031) and fixes
none (col5791 1.041).  No probe passes, so no rule was built and fresh seeds 9271-9280 were NOT
drawn.

Trace (``both_above`` / ``both_below``, added after the scores above): the ambient excursions go
OPPOSITE ways on the two sides: every out-of-span row on the columns is above the span (hotter
season) and needs the guard (col5791 needs both the in-span 0.24 and the above-span 0.08 of its
rows handed to MLR to reach 1.004; either alone leaves 1.045 / 1.240), every one on cr9182 is
below (a cooling room) and must not be guarded (``both_below`` x1.054 is all of ``both``'s
loss) -- though on cr9245, also cooling, guarding its below-span rows helps a little (x0.998).
A rule "guard above the span, excuse below" would separate col5791 from cr9182, but it would be
chosen from exactly them (two records, one of each; cr9245 already disagrees), and a cooling
room is not physically more benign than a warming one: not built.

Verdict: TRACED.  An ambient excursion is not, on these records, the mark of a harmless row: the
column losers' fix needs rows whose ambient left the span, the cooling room's loss is rows whose
ambient left it.  Left: what separates col5791's above-span rows from cr9182's below-span rows
other than the sign (e.g. whether the machine's own sensors' residual off the pattern is
explained by the ambient's lag response learned on train, i.e. a pattern in the ambient-driven
dynamics rather than the static inputs), or a pattern built on train rows that cover both
ambient directions (a room with cooling in its train campaigns).
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto91 as auto91  # noqa: E402
import bench_auto92 as auto92  # noqa: E402
import bench_auto92b as auto92b  # noqa: E402
from _cli import run_commands  # noqa: E402

PROBES = ("pattern", "both", "pattern_inamb", "both_inamb", "both_above", "both_below")


@functools.cache
def _margin() -> float:
    """``promote.envelope.margin``: the margin a promoted model's envelope is built with."""
    from omegaconf import OmegaConf

    return float(OmegaConf.load(HERE.parent / "conf" / "promote" / "default.yaml").envelope.margin)


def _gates(x_train: np.ndarray, x_test: np.ndarray, columns: list[str]) -> dict[str, np.ndarray]:
    """Per row of ``x_test``, True where each probe hands the row to MLR."""
    import pandas as pd

    from thermocomp.apps.deploy.streaming import Envelope
    from thermocomp.core.io.contract import is_ambient

    envelope = Envelope.from_data(pd.DataFrame(x_train), margin=_margin())
    off = auto92b._off(envelope, x_test)
    beyond = envelope.outside(x_test)
    ambient = np.array([is_ambient(c) for c in columns])
    # the ambient's own excursion is a change of room, not a new source inside the machine
    in_span = ~beyond[:, ambient].any(axis=1)
    both = off & beyond.any(axis=1)
    above = (x_test[:, ambient] > envelope.hi[ambient]).any(axis=1)
    below = (x_test[:, ambient] < envelope.lo[ambient]).any(axis=1)
    print(f"   {int(ambient.sum())} ambient of {len(columns)} inputs; test rows with the ambient above "
          f"its span {above.mean():.2f}, below {below.mean():.2f}", flush=True)
    return {"pattern": off, "both": both, "pattern_inamb": off & in_span, "both_inamb": both & in_span,
            "both_above": both & above, "both_below": both & below}


def _with_probes(command):
    @functools.wraps(command)          # run_commands checks the words against its signature
    def run(*words):
        auto91._inputs = auto92b._Columns.inputs
        auto92.PROBES, auto92._gates = PROBES, lambda a, b: _gates(a, b, auto92b._Columns.last)
        command(*words)
    return run


def main(argv: list[str]) -> int:
    commands = {"guard": _with_probes(auto92.guard), "rooms": _with_probes(auto92.rooms)}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
