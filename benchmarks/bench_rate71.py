"""The correction guard's rate limit on a stream faster than the training rows (rate71).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_rate71.py served ROOT [family]

``ROOT``: a folder ``benchmarks/bench_faults71.py write ROOT`` wrote (its ``lathe_a``, ``init-lathe_a``
and ``out/lathe_a-<family>-plain`` are read; ``tc`` is made there).  ``lathe_a`` (bench_twolog70,
seed 7043) has two loggers: the DAQ's temperatures every 60 s, the probes every 300 s; ``run``
trains on the joined 300 s rows.  The served model (adaptive, as promote registers it, and the plain
stream) is fed the test run's temperature file as written (1441 rows at 60 s) and the same file
cut to every 5th row (289 rows at 300 s, the probes' instants less 7 s); printed per family: the
adaptive form's guard events, the rows it changed and by how much against the plain stream; the
plain stream's largest change per second over one 60 s step and over 300 s spans, against the
guard's limit; the two cadences' corrections at their shared instants; each against the probes.

Found by faults71: the served lag bank on the 60 s file gives 88 guard events (``rate_limited`` /
``free``), 51 of 1441 rows changed, by 3.02 µm at most.

Trace (measured before any change, 2026-12-02, at 2ee78b3a)
-----------------------------------------------------------
The guard learns its rate per second from the training rows, ``(1 + rate_margin)`` x the largest
``|dy| / dt`` between consecutive 300 s rows of the measured errors and the model's corrections
(lag bank: 0.0867 / 0.0607 µm/s for E_dX / E_dY), and applies it as ``rate * dt``, ``dt`` the
stream's step (60 s: 5.2 / 3.6 µm).  The plain 60 s stream moves at most 0.137 / 0.092 µm/s over
one 60 s step (1.58 / 1.52 x the limit) but at most 0.048 / 0.032 µm/s over any 300 s span (0.56
/ 0.52 x): within training's rate at training's resolution.  A correction's sample-to-sample
jitter (sensor noise through the model's gains) does not shrink with the step: a rate learnt from
300 s steps divides it by 300, the stream's by 60.  That is the unit mismatch: the rate is known
per training period, not within one.  MLR's corrections are the same at both cadences (0 µm at the
shared instants); the lag bank's are NOT: its lags are in time, ``a = exp(-dt / tau)``, but their
discretisation holds each input over the step before it (:func:`first_order_lags`), which makes
``L[x] - x`` on a ramp ``r * dt * a / (1 - a)`` (tau = 300 s: 175 s of lag at 300 s steps, 271 s at
60 s): the 60 s answer is up to 10.2 / 6.7 µm (RMS 3.0 / 2.0) off the 300 s one at the same
instants, and against the probes RMSE 3.39 / 2.26 µm at 60 s vs 1.85 / 1.41 at 300 s (MLR 2.16 /
1.45 at both).  The second is the model's own behaviour on a cadence it was not trained on: no
guard rule changes it (documented, docs/to-the-machine.md).

Rule (one, committed before scoring)
------------------------------------
The guard's rate limit over a step of ``dt`` seconds is ``rate * max(dt, period)``, ``period`` the
training sample period (``CorrectionGuard.period_s``, the exported ``guard_period``): a step shorter
than a training period may move as far as one training period allows, since training's rows say
nothing finer.  A step of the training period, longer, or without time is limited as before.  The
same rule in the guard (:mod:`thermocomp.apps.deploy.guard`: ``step``, ``step_block``), the exported
code's Simulator, the C and the ST (the check pack compares them).

Bar (all three, else REFUSED and the src change reverted)
---------------------------------------------------------
1. ``served`` here: the lag bank's adaptive form on lathe_a's healthy 60 s file: 0 guard events
   (was 88), 0 rows changed against the plain stream; MLR 0 as before.
2. ``benchmarks/bench_deploy_faults.py``: its adaptive column not weaker: every printed figure
   of every fault x model identical to the code before (its records are at the training cadence;
   the cases with a substituted time, ``dup_time``, ``swap``, ``dup_row``, are the ones that can
   move), run on the code before and after on fresh roots.
3. ``benchmarks/bench_monitor_healthy.py --jobs 1``: ``results.json`` identical (healthy and
   faulted, every record x model, guard events included) on the code before and after.

Measured (2026-12-02, 2 shared cores, load 2-8; the code before: 2ee78b3a; after: the rule)
-----------------------------------------------------------------------------------------
1. ``served``: lag bank 88 guard events, 51 of 1441 rows changed, max 3.024 µm -> 0, 0, 0.000;
   MLR 0 -> 0.  Everything else printed unchanged (the plain stream has no guard): the 60 s vs 300 s
   answers and the RMSEs against the probes above.  4.0 s CPU per family.
2. ``bench_deploy_faults.py``: its whole output identical to the byte (diff empty), every fault x
   model x form; 9.3 s CPU each.
3. ``bench_monitor_healthy.py --jobs 1`` on fresh roots: ``results.json`` byte-identical (22 record
   x model pairs, healthy and faulted) and its printed tables likewise; 818 s CPU before, 870 s after.
All three met: the rule is kept.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]

import bench_faults71 as faults71  # noqa: E402
import lab_matrix  # noqa: E402
from _cli import run_commands  # noqa: E402

NAME = "lathe_a"


def probes_at(root: Path, stride: int) -> tuple[np.ndarray, np.ndarray]:
    """``(rows of the 60 s file 7 s before each probe sample, whose index is a multiple of
    stride, the probes' errors there, referenced to the first)``."""
    disp = pd.read_csv(root / NAME / "production_disp.csv", sep=";", decimal=",")
    t = pd.to_datetime(disp.iloc[:, 0], format="%d.%m.%Y %H:%M:%S").to_numpy()
    temp = pd.read_csv(root / NAME / "production_temp.csv", parse_dates=["Time"])
    rows = np.searchsorted(temp["Time"].to_numpy(), t) - 1
    ok = (rows >= 0) & (rows % stride == 0)
    errors = disp.iloc[:, 1:].to_numpy(float)[ok]
    return rows[ok], errors - errors[0]


def served(root: Path, family: str = "lagbank") -> None:
    lab_matrix.project(root)
    adaptive = faults71.deployed_model(root, NAME, family)
    plain = faults71.deployed_model(root, NAME, family, "false")
    lines = faults71._lines(root, NAME)
    every5 = [lines[0]] + lines[1::5]
    c60, _, events = faults71.served(adaptive, faults71.client_body(NAME, lines))
    p60 = faults71.served(plain, faults71.client_body(NAME, lines))[0]
    p300 = faults71.served(plain, faults71.client_body(NAME, every5))[0]
    guard = adaptive.guard
    d = np.abs(c60 - p60)
    print(f"{family}: guard rate {np.round(guard.max_rate_per_s, 4)} µm/s, period {guard.period_s:g} s")
    print(f"  60 s adaptive: {events} guard events, {int((d > 1e-9).any(axis=1).sum())} of "
          f"{len(c60)} rows changed, max {d.max():.3f} µm")
    step = np.abs(np.diff(p60, axis=0)).max(axis=0) / 60
    span = np.abs(p60[5:] - p60[:-5]).max(axis=0) / 300
    print(f"  plain 60 s: max µm/s over a 60 s step {np.round(step, 4)} "
          f"({np.round(step / guard.max_rate_per_s, 2)} x the limit), over 300 s spans "
          f"{np.round(span, 4)} ({np.round(span / guard.max_rate_per_s, 2)} x)")
    shared = p60[::5][:len(p300)] - p300
    print(f"  60 s vs 300 s at shared instants: max {np.round(np.abs(shared).max(axis=0), 3)}, "
          f"RMS {np.round(np.sqrt(np.mean(shared ** 2, axis=0)), 3)} µm")
    rows, errors = probes_at(root, 5)
    keep = rows // 5 < len(p300)
    for label, c in (("300 s", p300[rows[keep] // 5]), ("60 s", p60[rows[keep]])):
        rmse = np.sqrt(np.mean((errors[keep] + c) ** 2, axis=0))
        print(f"  plain {label} vs the probes ({keep.sum()} rows): RMSE {np.round(rmse, 3)} µm")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "served": lambda root, family="lagbank": served(Path(root).resolve(), family),
    }, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
