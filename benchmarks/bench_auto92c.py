"""``model=auto``'s guard to MLR off the training pattern, acting only where the row's AMBIENT stays
inside the train ambient span: does excusing an ambient excursion (not a new heat source) keep
auto's cooling-room win on cr9182 and still fix its column losers?  (issue 34; stop 92, auto92c,
follow-up of bench_auto92 / bench_auto92b).  RESULT: see "Scored" below.

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

Bar: bench_auto92's, unchanged, written here BEFORE any ``_inamb`` number was computed: a guard
is worth building only where on the seen records it fixes >= 2 of the 3 seen losers (col5791,
col1403, lab5401: guarded / MLR <= 1.02) AND keeps year6_5411 and every climate room within 2 %
of auto (year6_5411 guarded / MLR <= 1.02 x its auto / MLR, no room guarded / auto > 1.02) and the
13 rooms' geo mean guarded / auto <= 1.00.  A probe passing that on the seen records earns a
fresh score on seeds 9271-9280 in the NEXT stop; no fresh seed is drawn here.
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

PROBES = ("pattern", "both", "pattern_inamb", "both_inamb")


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
    print(f"   {int(ambient.sum())} ambient of {len(columns)} inputs; rows with ambient out of span "
          f"{1 - in_span.mean():.2f}", flush=True)
    return {"pattern": off, "both": both, "pattern_inamb": off & in_span, "both_inamb": both & in_span}


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
