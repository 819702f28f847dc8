"""``model=auto``'s guard to MLR off the training pattern, judged on the part of the inputs the
AMBIENT does not explain: does a row count as new only where the machine's sensors depart from
their ambient-driven response learned on train (an internal source never seen), not where the
ambient itself has left its span (a colder room the response explains)?  (issue 34; stop 93,
auto93, follow-up of bench_auto92 / 92b / 92c).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``; ROOT and WORK as bench_auto92's,
i.e. bench_auto91's ``rows`` already run into WORK)::

    python benchmarks/bench_auto93.py guard ROOT WORK RECORD ...   # seen records, stored rows
    python benchmarks/bench_auto93.py rooms RECORD ...             # bench_auto88b's climate rooms
    python benchmarks/bench_auto93.py fresh                        # seeds 9271-9280, once (bar)

``guard`` and ``rooms`` are bench_auto92's commands (imported, same records, same figures) with
the probes below in place of its four; the gate now also sees each campaign's frame (its
``time`` column), not only the stacked inputs.

The ambient-driven response (learned on the train campaigns alone, nothing from the test): per
campaign, the ambient input ``u`` (the mean of the ambient sensors,
:func:`thermocomp.core.io.contract.is_ambient`, less the campaign's first sample, as every input
is referenced) and its first-order low-passes at ``TAUS_S`` (900 / 3600 / 14400 s, monb92's state
filters, not tuned here; each started at 0, the referenced start); every other input regressed on
those four features by least squares without intercept over all train rows (a linear filter from
the ambient to each sensor: a colder room, the negative of a warmer one, is explained by the
same filter).  The sensors' DEPARTURE is each non-ambient input less that response.  The pattern
gate is bench_auto92's (:meth:`thermocomp.apps.deploy.streaming.Envelope.leaves_pattern`,
``PATTERN_ENERGY`` 0.999, ``tol`` the largest TRAIN residual; margin ``promote.envelope.margin``
0.1), built on the train departures instead of the raw inputs.  A record without an ambient
sensor has departure = inputs (the probes equal bench_auto92's there).

* ``pattern`` / ``both``: bench_auto92's, reference (raw inputs; ``both`` = off the pattern AND
  beyond the bounds on any input);
* ``dyn``: the row's departure off the departures' pattern;
* ``dyn_both``: ``dyn`` AND the departure beyond the departures' bounds;
* ``both_dyn``: ``both`` AND ``dyn`` (bench_auto92's envelope condition, excusing rows whose
  departure from the ambient response stays on the train pattern).

Choice (seen records only): the rule is the probe that meets the bar below on the seen records;
where several do, the one guarding the fewest rows.  No threshold is chosen: ``tol`` and the
margin are the envelope's own.

Bar (written here BEFORE any probe of this bench ran; bench_auto92b's, with the brief's wording):
on the SEEN records -- the 10 of bench_auto92's ``guard`` (col5791, col1403, lab5401, year6_5411,
col1514, col6512, swiss303, swiss5454, year6511, mill1514) and its 13 climate rooms (cr9079,
cr9182, cr9248, cr9244, cr9181, cr9183, cr9245, cr9031, cr9076, cr9081, cr9083, cr9088, cr9089) --
(a) the rooms not worse: geo mean guarded / auto <= 1.002 and no record of the 23 worse than
auto by > 1 % (rooms: guarded / auto <= 1.01; the guard records: guarded / MLR <= 1.01 x auto /
MLR); (b) losers fixed counted (guarded / MLR <= 1.02 among col5791, col1403, col1514, col6512,
lab5401), at least 1 of the 3 bench_auto92 bar losers (col5791, col1403, lab5401).  A probe
passing (a) and (b) on the seen records is scored ONCE on fresh seeds 9271-9280 by ``fresh``
(bench_auto92's fresh block's generators, stated: 9271-9275 climate rooms, bench_auto88's
``sim=climate_room`` at bench_auto87's SMALL size as bench_auto88b's FRESH; 9276-9280 column
records, bench_remeasure62's ``sim=column_moving_source``, each scored on its OWN test campaigns
as a room is), with the same (a): no fresh record worse than auto by > 1 %, geo guarded / auto
<= 1.002 over the 10, and the fresh records where auto loses to MLR counted with those the guard
brings within 2 % of MLR.  Otherwise no fresh seed is drawn.
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto87 as auto87  # noqa: E402
import bench_auto88b as auto88b  # noqa: E402
import bench_auto91 as auto91  # noqa: E402
import bench_auto92 as auto92  # noqa: E402
import bench_auto92b as auto92b  # noqa: E402
import bench_auto92c as auto92c  # noqa: E402
from _cli import run_commands  # noqa: E402

TAUS_S = (900.0, 3600.0, 14400.0)
FRESH = {**{f"cr{s}": ["sim=climate_room", f"seed={s}", *auto87.SMALL] for s in range(9271, 9276)},
         **{f"col{s}": ["sim=column_moving_source", f"seed={s}"] for s in range(9276, 9281)}}
PROBES = ("pattern", "both", "dyn", "dyn_both", "both_dyn")


class _Frames:
    """bench_auto92's loops hand its gate the stacked inputs only; the ambient response needs each
    campaign's time line, so every frame ``auto91._inputs`` is asked for is kept here, in order
    (the train campaigns first, then the test ones), until the gate takes them."""

    seen: list = []

    @classmethod
    def inputs(cls, frame, columns):
        cls.seen.append(frame)
        return auto92b._Columns.inputs(frame, columns)

    @classmethod
    def take(cls, n_train: int, n_test: int) -> tuple[list, list]:
        frames, cls.seen = cls.seen, []
        sizes = np.cumsum([len(f) for f in frames])
        cut = int(np.searchsorted(sizes, n_train)) + 1
        assert sizes[cut - 1] == n_train and sizes[-1] == n_train + n_test, "frames out of step"
        return frames[:cut], frames[cut:]


def _ambient_features(frame, ambient_columns: list[str]) -> np.ndarray:
    """The referenced ambient and its low-passes at :data:`TAUS_S` (rows x 4)."""
    u = frame[ambient_columns].to_numpy(float).mean(axis=1)
    u = u - u[0]
    t = frame["time"].to_numpy(float)
    dt = np.diff(t, prepend=t[0])
    out = [u]
    for tau in TAUS_S:
        alpha = 1.0 - np.exp(-dt / tau)
        y = np.zeros_like(u)
        for k in range(1, len(u)):          # causal: a filter the stream could run
            y[k] = y[k - 1] + alpha[k] * (u[k] - y[k - 1])
        out.append(y)
    return np.column_stack(out)


def departures(train_frames, test_frames, x_train, x_test, columns) -> tuple[np.ndarray, np.ndarray]:
    """``(train, test)`` departures of the non-ambient inputs from their ambient-driven response
    learned on the train rows (module doc); the inputs unchanged without an ambient sensor."""
    from thermocomp.core.io.contract import is_ambient

    ambient = np.array([is_ambient(c) for c in columns])
    if not ambient.any():
        return x_train, x_test
    names = [c for c, a in zip(columns, ambient) if a]
    f_train = np.vstack([_ambient_features(f, names) for f in train_frames])
    f_test = np.vstack([_ambient_features(f, names) for f in test_frames])
    coef, *_ = np.linalg.lstsq(f_train, x_train[:, ~ambient], rcond=None)
    return x_train[:, ~ambient] - f_train @ coef, x_test[:, ~ambient] - f_test @ coef


def _gates(x_train: np.ndarray, x_test: np.ndarray, columns: list[str]) -> dict[str, np.ndarray]:
    """Per row of ``x_test``, True where each probe hands the row to MLR."""
    from thermocomp.apps.deploy.streaming import Envelope

    train_frames, test_frames = _Frames.take(len(x_train), len(x_test))
    raw = Envelope.from_data(pd.DataFrame(x_train), margin=auto92c._margin())
    off = auto92b._off(raw, x_test)
    both = off & raw.outside(x_test).any(axis=1)
    d_train, d_test = departures(train_frames, test_frames, x_train, x_test, columns)
    dyn_env = Envelope.from_data(pd.DataFrame(d_train), margin=auto92c._margin())
    dyn = auto92b._off(dyn_env, d_test)
    rank = None if dyn_env.basis is None else dyn_env.basis.shape[1]
    print(f"   departures: {d_train.shape[1]} inputs, rank {rank}, tol {dyn_env.tol:.3g}", flush=True)
    return {"pattern": off, "both": both, "dyn": dyn,
            "dyn_both": dyn & dyn_env.outside(d_test).any(axis=1), "both_dyn": both & dyn}


def _with_probes(command):
    @functools.wraps(command)          # run_commands checks the words against its signature
    def run(*words):
        auto91._inputs = _Frames.inputs
        auto92.PROBES, auto92._gates = PROBES, lambda a, b: _gates(a, b, auto92b._Columns.last)
        command(*words)
    return run


def fresh() -> None:
    """``rooms`` on :data:`FRESH` (each record's own test campaigns), once, for the bar."""
    auto88b.RECORDS.update(FRESH)
    _with_probes(auto92.rooms)(*FRESH)


def main(argv: list[str]) -> int:
    commands = {"guard": _with_probes(auto92.guard), "rooms": _with_probes(auto92.rooms), "fresh": fresh}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
