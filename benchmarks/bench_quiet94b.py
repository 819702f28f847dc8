"""The warned air out of the judging fit (stop 94, quiet94b; follow-up of bench_quiet94): on a
one-campaign training the ambient sensors are ``drift_warn_only`` (quiet94: judged and warned,
never excluded, blamed or vetoing).  quiet94 kept them IN the POD operator that judges the
others: where the others lean on a rising air, its departure from the day's co-trend leaked onto
their errors (``bench_quiet94.py leak``: seed 0 a healthy T_0 excluded, seeds 0 / 2 a new thermal
state on healthy data, seed 2 a planted T_3 drift alarmed, never excluded).

THE RULE: the warned air predicts none of the others.  ``monitor.judging_operator``: the
operator of an active set has the warned sensors' COLUMN zero; the others' rows and leverages
are those of the set without them (as when a sensor is excluded), the warned sensors' own rows
and leverages those of the whole set, so their leave-one-out error (``/(1 - h)``) is still the
others' prediction of them: still judged and warned, observable as before.  Every operator the
monitor forms (the active set's, a trial exclusion's, a re-admission's, the bands' sets) goes
through it, and the training spread (``floor_c``) is taken under it.

Usage (from ``benchmarks/``, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_quiet94b.py leak SEEDS [BASE]                          # synthetic
    python benchmarks/bench_quiet94b.py count ROOT SEEDS [HOURS [BASE]]            # healthy
    python benchmarks/bench_quiet94b.py planted ROOT SEEDS [HOURS [RATE [BASE]]]   # drifts

Each compares BASE (``quiet94``, the default: the air warned but in the fit, i.e. main at
a9e5422c; or ``main``: no sensor warned, a9e5422c's flag cleared, bench_quiet94's ``main``)
with ``rule`` (this tree as served).  ``leak``: bench_quiet94's synthetic record (10 sensors of
tests/apps' line and a T_amb warming 0.01 °C / sample; 120 train rows, 360 streamed), healthy and
with T_3 drifting 0.02 °C / sample from row 200: the exclusions, alarms and new states.
``count`` / ``planted``: bench_quiet94's on bench_quiet93's swiss records (ROOT/SEED-<H>h, the
longest of 3 campaigns, ONE training campaign): every exclusion on the healthy record; per
sensor a planted drift of RATE (0.05) °C / 300 s from the first test row, rows to exclusion /
to first flag.

BAR (written and committed BEFORE the fresh seeds 9686-9695 were scored).  KEPT only if all hold:
(1) ``leak 0-3``: on the 4 healthy synthetic records no exclusion of a machine sensor (T_0..T_9)
    and no new thermal state; the planted T_3 drift excluded on seeds 0-3 (quiet94: 2 of 4 on
    seeds 0, 2 missed it);
(2) quiet94's clauses unchanged: 0 healthy exclusions on the FRESH swiss records (9686-9690 at 4
    h, 9691-9695 at 12 h, ``count``); drifts missed (``planted``, never excluded) on them not
    above quiet94's; every T_amb drift quiet94 flags the rule flags; and on the 30 SEEN records
    (9501-9505, 9531-9535, 9556-9560, 4 and 12 h) no healthy exclusion back;
(3) the C follows: C = served to 1e-9 µm on a one-campaign swiss record where main's C excluded
    the air, ``not_in_code`` no longer naming the warned air.
Otherwise REFUSED (src reverted, the rule as benchmarks/quiet94b_rule.patch) or TRACED.

Measured (2026-12-05, this tree)
--------------------------------
(pending)
"""

from __future__ import annotations

import contextlib
import sys
from pathlib import Path
from unittest import mock

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_quiet94 as quiet94  # noqa: E402
from _cli import run_commands  # noqa: E402

@contextlib.contextmanager
def variant(name: str):
    """The tree's monitor as served (``rule``), with the warned air kept in the judging fit
    (``quiet94``: every operator, the fit's and the stream's, with no sensor muted), or with no
    sensor warned either (``main``)."""
    if name == "rule":
        yield
        return
    from thermocomp.apps.deploy.surveillance import SensorMonitor, monitor

    own, fit = monitor.judging_operator, SensorMonitor.from_training.__func__

    def unmuted(pod, subset, mute):
        return own(pod, subset, np.zeros_like(mute))

    def from_training(cls, *args, **kwargs):
        with mock.patch.object(monitor, "judging_operator", unmuted):
            mon = fit(cls, *args, **kwargs)
        mon._operator = lambda subset: unmuted(mon.pod, subset, mon.drift_warn_only)
        if name == "main":
            mon.drift_warn_only[:] = False
        return mon

    with mock.patch.object(SensorMonitor, "from_training", classmethod(from_training)):
        yield


@contextlib.contextmanager
def against(base: str):
    """bench_quiet94's commands with its ``main`` read as BASE and its ``rule`` as the tree's."""
    assert base in ("main", "quiet94"), base
    with mock.patch.object(quiet94, "served", lambda rule: variant("rule" if rule else base)):
        yield


def leak(seeds: str, base: str = "quiet94") -> None:
    """bench_quiet94's ``leak``, BASE against the rule (printed as ``main | rule``)."""
    with against(base):
        quiet94.leak(seeds)


def count(root: str, seeds: str, hours: str = "4,12", base: str = "quiet94") -> None:
    """bench_quiet94's ``count``, BASE against the rule."""
    with against(base):
        quiet94.count(root, seeds, hours)


def planted(root: str, seeds: str, hours: str = "4", rate: str = "0.05",
            base: str = "quiet94") -> None:
    """bench_quiet94's ``planted``, BASE against the rule."""
    with against(base):
        quiet94.planted(root, seeds, hours, rate)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"leak": leak, "count": count, "planted": planted}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
