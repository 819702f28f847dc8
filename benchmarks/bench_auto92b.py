"""``model=auto``'s guard to MLR off the training pattern, with the pattern built WITHOUT the
ambient: does a pattern that an ambient shift cannot leave keep auto's ambient wins and still fix
its column losers?  (issue 34; stop 92, auto92b, follow-up of bench_auto92).  RESULT: see below.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``; ROOT and WORK as bench_auto92's,
i.e. bench_auto91's ``rows`` already run into WORK)::

    python benchmarks/bench_auto92b.py guard ROOT WORK RECORD ...   # seen records, stored rows
    python benchmarks/bench_auto92b.py rooms RECORD ...             # bench_auto88b's climate rooms
    python benchmarks/bench_auto92b.py trace RECORD                 # one room's rows under ``both``

``guard`` and ``rooms`` are bench_auto92's commands (imported, same records, same figures) with
the probes below in place of its four.  The gate is still
:meth:`thermocomp.apps.deploy.streaming.Envelope.leaves_pattern` of an ``Envelope.from_data``
(``PATTERN_ENERGY`` 0.999, ``tol`` the largest train residual), built on the train inputs
(``T_`` columns less each campaign's first sample) of one of three frames:

* all inputs (bench_auto92's ``pattern`` / ``both``, reproduced for reference);
* ``_noamb``: the inputs less the ambient sensors (``T_amb`` / ``T_amb_*``,
  :func:`thermocomp.core.io.contract.is_ambient`; the columns ``data.roles.ambient`` maps);
* ``_rel``: each other temperature minus the ambient reading (the mean of the ambient sensors),
  the ambient itself dropped.

``pattern*``: the row off that frame's pattern; ``both*``: off it AND outside that frame's
envelope bounds (margin 0.1), the envelope's own clamp condition.  A record without an ambient
sensor has the same gate in all three frames.

``trace``: the climate room's test rows guarded by ``both`` (all inputs), in runs of consecutive
rows: the campaign, the rows, the largest residual off the pattern over ``tol``, the two inputs
carrying most of the squared residual (their share), the inputs beyond the bounds, the referenced
ambient against its train span, and auto's and MLR's sum of squared errors over the run (all
targets).  Then the same rows' fate under ``both_noamb`` / ``both_rel``.

Bar: bench_auto92's, unchanged (written there before any probe): a guard is worth building only
where on the seen records it fixes >= 2 of the 3 seen losers (col5791, col1403, lab5401:
guarded / MLR <= 1.02) AND keeps year6_5411 and every climate room within 2 % of auto (no room
guarded / auto > 1.02) and the rooms' geo mean guarded / auto <= 1.00.  Seen records only, NO
fresh seeds in this stop (fresh 9271-9280 are for the next, if a probe passes here).

Measured
--------
(filled in below after the run)
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto91 as auto91  # noqa: E402
import bench_auto92 as auto92  # noqa: E402
from _cli import run_commands  # noqa: E402

FRAMES = ("", "_noamb", "_rel")
PROBES = tuple(f"{kind}{frame}" for frame in FRAMES for kind in ("pattern", "both"))


def _frame(x: np.ndarray, columns: list[str], frame: str) -> np.ndarray:
    """The inputs ``x`` (order of ``columns``) in ``frame`` (module doc); unchanged without an
    ambient sensor."""
    from thermocomp.core.io.contract import is_ambient

    ambient = np.array([is_ambient(c) for c in columns])
    if frame == "" or not ambient.any():
        return x
    rest = x[:, ~ambient]
    return rest if frame == "_noamb" else rest - x[:, ambient].mean(axis=1, keepdims=True)


def _envelope(x_train: np.ndarray):
    from thermocomp.apps.deploy.streaming import Envelope

    return Envelope.from_data(pd.DataFrame(x_train))


def _off(envelope, x_test: np.ndarray) -> np.ndarray:
    if envelope.basis is None:          # the pattern is the whole space: no row can leave it
        return np.zeros(len(x_test), bool)
    return np.array([envelope.leaves_pattern(row) for row in x_test])


def _gates(x_train: np.ndarray, x_test: np.ndarray, columns: list[str]) -> dict[str, np.ndarray]:
    """Per row of ``x_test``, True where each probe hands the row to MLR."""
    out = {}
    for frame in FRAMES:
        train, test = _frame(x_train, columns, frame), _frame(x_test, columns, frame)
        envelope = _envelope(train)
        off = _off(envelope, test)
        out[f"pattern{frame}"] = off
        out[f"both{frame}"] = off & envelope.outside(test).any(axis=1)
    return out


class _Columns:
    """bench_auto92's loops hand its gate the stacked inputs only; the frames need their column
    names, which each loop passes to ``auto91._inputs`` just before: kept here for the gate."""

    last: list[str] = []

    @classmethod
    def inputs(cls, frame, columns):
        cls.last = list(columns)
        return _INPUTS(frame, columns)


_INPUTS = auto91._inputs


def _with_probes(command):
    @functools.wraps(command)          # run_commands checks the words against its signature
    def run(*words):
        auto91._inputs = _Columns.inputs
        auto92.PROBES, auto92._gates = PROBES, lambda a, b: _gates(a, b, _Columns.last)
        command(*words)
    return run


def _runs(flags: np.ndarray, campaign: np.ndarray) -> list[np.ndarray]:
    """The rows of ``flags`` in runs of consecutive rows of one campaign."""
    rows = np.flatnonzero(flags)
    cuts = np.flatnonzero((np.diff(rows) > 1) | (np.diff(campaign[rows]) != 0)) + 1
    return np.split(rows, cuts) if rows.size else []


def trace(name: str) -> None:
    from thermocomp.core.io.contract import is_ambient

    ds, ids, columns, x_train, series = auto91.room(name)
    x_test = np.vstack([auto91._inputs(ds.campaigns[c], columns) for c in ids])
    campaign = np.concatenate([np.full(len(ds.campaigns[c]), k) for k, c in enumerate(ids)])
    start = np.concatenate([[0], np.cumsum([len(ds.campaigns[c]) for c in ids])])
    gates = _gates(x_train, x_test, columns)
    envelope = _envelope(x_train)
    z = (x_test - envelope.mean) / envelope.scale
    resid = z - z @ envelope.basis @ envelope.basis.T
    ambient = np.array([is_ambient(c) for c in columns])
    amb_train, amb_test = x_train[:, ambient].mean(axis=1), x_test[:, ambient].mean(axis=1)
    beyond = envelope.outside(x_test)
    err = {k: np.zeros(len(x_test)) for k in ("auto", "mlr")}
    for k in err:
        for t in series[k]:
            r = np.concatenate([series[k][t][1][c] for c in ids])
            err[k] += np.where(np.isfinite(r), r, 0.0) ** 2
    print(f"  {name}: {len(x_test)} test rows in {len(ids)} campaigns; pattern rank "
          f"{envelope.basis.shape[1]} of {len(columns)}, tol {envelope.tol:.3g}; train ambient "
          f"(referenced) {amb_train.min():+.2f} .. {amb_train.max():+.2f} K; rows guarded: "
          + ", ".join(f"{p} {int(g.sum())}" for p, g in gates.items()))
    for rows in _runs(gates["both"], campaign):
        share = (resid[rows] ** 2).sum(axis=0)
        share = share / share.sum()
        top = np.argsort(share)[::-1][:2]
        out = [columns[j] for j in np.flatnonzero(beyond[rows].any(axis=0))]
        ratio = np.sqrt((resid[rows] ** 2).sum(axis=1)).max() / envelope.tol
        k = campaign[rows[0]]
        print(f"   {ids[k]} rows {rows[0] - start[k]}-{rows[-1] - start[k]} ({rows.size}): off x{ratio:.2f} "
              f"tol, residual " + " ".join(f"{columns[j]} {share[j]:.2f}" for j in top)
              + f"; beyond {','.join(out)}; ambient {amb_test[rows].min():+.2f} .. {amb_test[rows].max():+.2f}"
              f"; SSE auto {err['auto'][rows].sum():.1f} MLR {err['mlr'][rows].sum():.1f}; kept by "
              f"both_noamb {gates['both_noamb'][rows].mean():.2f}, both_rel {gates['both_rel'][rows].mean():.2f}")
    total = {k: err[k].sum() for k in err}
    both = gates["both"]
    print(f"   all rows SSE auto {total['auto']:.1f}; under both: + {err['mlr'][both].sum() - err['auto'][both].sum():.1f}")


def main(argv: list[str]) -> int:
    commands = {"guard": _with_probes(auto92.guard), "rooms": _with_probes(auto92.rooms), "trace": trace}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
