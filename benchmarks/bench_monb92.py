"""The served monitor bounding the drift of a sensor "no other predicts" by a ridge on the other
temperatures and the states (monb92, issue 34; mon91b's variant B, traced offline).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_audit89.py healthy ROOT RECORDS  # first: simulate, run, monitor, healthy
    python benchmarks/bench_mon91b.py rooms ROOT SEEDS       # or: bench_mon88's long records, healthy
    python benchmarks/bench_monb92.py served ROOT RECORDS    # the served stream, B's exclusion forced
    python benchmarks/bench_monb92.py fresh                  # the bar's seeds and their generators

``RECORDS``: bench_audit89's (``9316-9325``) or ``all`` (every record of ``ROOT`` with a monitor
report; bench_mon88's ``lr9196`` .. ``lr9200`` after ``rooms``).

``served``: for the costliest sensor the healthy monitor calls not observable (bench_audit89's
``_costliest`` among ``observable: false``), mon91b's variant B (:func:`bench_mon91b.trace_sensor`:
``StandardScaler`` + ``RidgeCV`` on the states low-passed at 900 / 3600 / 14400 s, the ambient and
every other temperature, each referenced to the test part's first row; band max(0.4 degC, 3 x the
99.5th percentile of its windowed CV residual), crossed where 2 windowed residuals in a row are
beyond it) gives the first crossing row of each test campaign, healthy and with bench_audit89's
``drift`` (+0.5 degC/h from the part's middle row).  B is causal (trailing filters and window, a
ridge fixed at training), so a served B crosses where the offline one does; the served ``monitor``
stage (the healthy run's model.pkl, the SERVED ``SensorMonitor`` of ``PYTHONPATH``'s tree) is then
run on the drifted copy with the sensor EXCLUDED from that row on (:func:`forced_out`: a hook on
``SensorMonitor.update``, the monitor stage streams row by row; kept out while the band stays
crossed: the drift only grows).  Nothing else is changed: once out, the served compensator does
what it does today for an excluded sensor no other predicts -- its fallback family (the model
refitted without it, ``monitor.fallbacks=unobservable``, :mod:`thermocomp.apps.deploy.fallback`)
gives the correction, else its last good reading is held.  Cases: ``truth``; ``drift`` (main:
the drift read); ``drift+B-out`` (the rule's exclusion, the fallback's correction);
``truth+B-out`` (the same exclusion on the HEALTHY copy at the drifted copy's crossing row: the
cost of a false alarm there).  RMSE fixed / adaptive (mean over targets, um), the events naming
the sensor.  -> ``ROOT/servedb92.json``.

``fresh``: prints the bar's fresh records (:data:`FRESH`), nothing run.

What the served monitor does today (read on 2b918bfd, the brief's part 1):

* ``observable``: ``SensorMonitor._set_operator``: a sensor is observable in the active set where
  its leverage in the POD operator of that set is below ``pod.max_leverage``; one that is not has
  NaN error scale (never judged, no band: ``_scale``), ``_predictable`` (every sensor in) is the
  same test with all in.  Bands: ``from_training`` -> ``max(warning_c, spread_factor x
  spread)`` per sensor, spread the 99.5th percentile of the windowed leave-one-out POD error
  (NaN -> 0 for a blind sensor: its band is the configured 0.4 / 0.8 degC, never read);
  ``_bands_of`` rescales a sensor's floor for the active set (mon86).
* An excluded sensor's input: its POD reconstruction where predictable, else ``_last_good``
  (its last referenced reading while in; ``_fast`` / ``_update``); but in the adaptive
  compensator a blind sensor the model reads has a FALLBACK family (``fallbacks_``, fitted at
  deploy build) whose correction replaces the model's while it is out (per row:
  ``AdaptiveCompensator._fallen_back``; ``run_rows`` takes a block only while every sensor is in).
  So B needs no estimate in place of ``_last_good`` where a fallback exists: only the exclusion.
  ``_last_good`` matters only under ``monitor.fallbacks=none`` or where no fallback fits.
* The monitor is fitted (``AdaptiveCompensator.from_training``) and streamed
  (``_inputs``: ``monitor.update(x[self._mon], t)``; ``_inputs_block``: ``update_block``) on the
  monitored temperatures alone: B needs the states (the row's other columns, which
  ``AdaptiveCompensator`` holds as ``x[self._other]``) and the time step (``_check_time``'s dt),
  its three low-pass filters per state in the snapshot (``_snapshot`` / ``_restore``: the
  warm-up lead-in, deploy88) and a key beside ``fallbacks_`` (an older pickle: none, as before).
* mon88 / mon89 keys travel as: the served rule in ``surveillance/*``; its numpy mirror in
  ``export/watch.py`` (``CodeMonitor``), its C in ``export/watch_c.py``, each with a
  compensator.json key defaulting to 0 for an older export (``cleared`` mon88, ``spike`` mon89,
  ``blind_range`` cmon89b, ...).  The C holds no fallback family today: a blind sensor out with a
  fallback is flagged ``NOT_IN_CODE`` and the pack cuts there.  A B-carrying export must do the
  same explicitly (the mirror flagging B's exclusion, or export refusing the key with a message):
  the C following behind as "not in the C yet".

Bar (written before any fresh score, this commit; the brief's, with the generator per seed fixed
here before any draw): fresh seeds 9396-9405 drawn ONLY from kinds that carry a blind sensor, the
brief's order long_record / column / swiss / yearround cycled (:data:`FRESH`: 9396 lr, 9397 column,
9398 swiss, 9399 yearround, 9400 lr, 9401 column, 9402 swiss, 9403 yearround, 9404 lr, 9405 column;
long records as bench_mon88's ``LONG`` with ``data.reference=none``, the others as bench_audit89's
``KINDS``), each healthy and with bench_audit89's +0.5 degC/h drift in its costliest blind sensor.
KEPT only if: the drift detected (an event naming the sensor after the fault's row) on >= 5 of 10
where main detects it on 0; no drifted row's served RMSE (fixed and adaptive) worse than main's;
healthy: no new event on any of the 10, nor on bench_mon88's seen healthy rows (9196-9205) nor
datasets/fl_thermal; served RMSE on every healthy row identical to main's; monitor / export /
replay tests + tests/test_readme.py pass; a check pack of a B-carrying export passes or the export
is refused with a clear message.
"""

from __future__ import annotations

import json
import os
import shutil
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_audit89 import KINDS, QUIET, _costliest, _mean_rmse, _named, _traced  # noqa: E402
from bench_deploy87 import stage  # noqa: E402
from bench_mon88 import LONG  # noqa: E402
from bench_mon91b import _copy_fed, _overrides, campaigns, labels_of, trace_sensor  # noqa: E402

CYCLE = ("lr", "column", "swiss", "yearround")   # the brief's kinds with a blind sensor, its order
FRESH = {seed: CYCLE[k % len(CYCLE)] for k, seed in enumerate(range(9396, 9406))}


def generator(kind: str) -> tuple:
    """``thermocomp simulate`` overrides of ``kind`` (and the run's data overrides)."""
    return (LONG, ("data.reference=none",)) if kind == "lr" else (KINDS[kind], ())


def fresh() -> None:
    """The bar's fresh records: seed, kind, simulate overrides (nothing run)."""
    for seed, kind in FRESH.items():
        sim, extra = generator(kind)
        print(f"{seed} {kind:<10} {' '.join(sim)} {' '.join(extra)}".rstrip(), flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"fresh": fresh}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
