"""The C holds a reading beyond its range of a sensor no other predicts as the second out, as
served does: a drifting ambient leaving its range while a blind sensor is out as explaining
(issue 34; stop 98, mon98b; mon98's "main defect found").

mon98 found on main, fresh dl9845 (bench_mon98 ``cases``, its ambient case: a +1 K/h drift of
``T_amb`` from a quarter into the first test campaign): max|C - served| 10.6 µm over 208 rows.

TRACE (seen dl9845, rebuilt with bench_mon98 into /tmp/mon98b; /tmp/mon98b ``trace.py``, served
and the export's numpy mirror stepped together).  At drift row 369 the blind ``T_table`` (no other
predicts it; nor ``T_amb``) goes out "as explaining" the others' errors (``BLIND_OUT``), in the
code too.  At row 872 ``T_amb`` reads 29.81 °C, beyond its range [10.6, 19.8] ± 10 °C.  Served
(``SensorMonitor._update``): the range is an instant fault, ``T_amb`` out (read as missing, held
at its last good reading), and in the same sample's re-admission ``T_table`` back: "the others
within their warning bands with it in for 427 samples" (``Readmission._pass_once_back``, the
rule for one out as explaining: its return is vouched for by the others' bands, and with the
drifting ``T_amb`` out they pass).  No special clause: the general re-admission, judged in the
set without ``T_amb``.  The code (``CodeMonitor._beyond``, C ``mon_beyond``): with one out, a
range reading is held as the second only for a sensor the others predict (cmon89
``_second_kind``); ``T_amb`` is blind, so ``RANGE`` is flagged "not in the code" and the sample
passes the monitor by: ``T_table`` stays out, ``T_amb`` in, on every later row (C ``RANGE`` each).

RULE (mirror ``CodeMonitor._second_kind`` / ``_beyond``, C ``mon_second_kind`` / ``mon_beyond``
with ``mon_second_range``; compensator.json ``monitor.second_range`` = 1, absent: 0, flagged as
before).  A sensor no other predicts that the code holds out for a range reading (cmon89b
``ranges``) is held as the second out too (cmon89's path for a blind jump: the field rebuilt
without both, ``min_active`` left in, the set's operator solved), read as missing while it stays
beyond, its return judged by its leak (``_leak_passes``) as the first's is.  The re-admission of
the first in the same sample is the code's existing ``_returning``: one mechanism, the served
one.  The ST block lags: it flags the reading (``OFF_RANGE``) and holds no re-admission
(corrected after the fresh run: the bar's draft said ``RANGE``; the bar unchanged).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_mon98b.py cases ROOT RECORD [RECORD ...]   # healthy + two drifts

``cases``: bench_mon98's ``cases`` on :data:`FRESH` (or dl9845, bench_mon98's), each record
simulated into ``ROOT/data`` and ``run model=mlr`` into ``ROOT/reports`` once: per record the
healthy frame, then a +1 K/h drift on the first predicted non-ambient sensor and on ``T_amb``;
per case max|C - served| (µm, C = the export's numpy mirror) and the rows where the mirror's
sensors out or new thermal state differ from served's.

Records.  SEEN: dl9845 (mon98's fresh, spent), the other benches' tr9828 / sw9776 / cr9763 /
lr9376.  FRESH (never simulated before this bar's commit): dl9870, dl9871 (bench_cmon91's dl9377
generator: a 5-day drift record of the kind of dl9845), sw9872 (bench_mon97's Swiss lathe: its
ambient drift takes a partner out before its range, mon98's sw9841).

BAR (written and committed BEFORE any of 9870-9872 is simulated; scored once; main = da1272c3's
src via ``git archive``, the rule this branch's; the fresh records simulated and run once by main's
tree, the root then copied for the rule: the rule changes the export only)
---
B1. seen dl9845, ambient case: max|C - served| <= 1e-9 µm on every row and 0 rows mirror !=
    served (main: 10.6 µm, 208 rows).
B2. fresh dl9870, dl9871, sw9872, every case (healthy, drift, ambient): on the rule max|C -
    served| <= 1e-9 µm, 0 rows apart; where main is apart, it was flagged (a ``RANGE``).
B3. healthy frames: served events and the mirror's flags line for line as main's.
B4. bench_mon98 ``cases`` on its seen tr9828 / sw9776 / cr9763 / lr9376, bench_dep98 ``back`` and
    bench_kelvin97 ``faults`` on tr9828: every line as main's (CPU lines aside).
B5. tests/shell/test_export_mon98b.py: the compiled C = served on every row with a range reading
    of a blind sensor as the second out; fails on da1272c3.
KEPT if B1-B5 hold; else REFUSED (benchmarks/mon98b_rule.patch, src as da1272c3).

Seen (before the bar; dl9845 rebuilt by da1272c3's tree into one ROOT, copied for the rule;
21.6-23.7 s CPU each): ambient case max|C - served| 10.6 µm, 208 rows apart -> 6.39e-14 µm, 0 rows;
its healthy frame and drift case as main's line for line (3.2e-14 µm, 0 rows).

Scored (fresh 9870-9872, once, after the bar's commit 8f429640; the rule unchanged since; main =
``git archive da1272c3``, the records simulated and run by it, the ROOT copied for the rule; CPU
50.5 s main, 45.9 + 8.9 s rule, 2026-12-06 10:23-10:31 UTC under a load of 10-12 on 2 cores)::

    record  case     main: max|C - served|, rows apart   rule             served: T_amb out / first out
    dl9870  healthy  0 µm, 0                              the same         (14 events, the generator's)
    dl9870  drift    2.84e-14, 0                          the same
    dl9870  ambient  2.97 µm, 243 rows                    2.84e-14, 0      837 (range) / T_bed_left at 3
    dl9871  healthy  2.84e-14, 0                          the same         (14 events)
    dl9871  drift    2.84e-14, 0                          the same
    dl9871  ambient  2.97 µm, 125 rows                    1.07e-14, 0      955 (range) / T_zdrive at 687
    sw9872  healthy  0 µm, 0                              the same         (0 events)
    sw9872  drift    2.38e-13, 0                          the same
    sw9872  ambient  1.46e-13, 0                          the same         751 / T_nc_cabinet at 26

On main the C names ``T_amb`` at the served row of both dl parts (its ``RANGE`` flag: the rule
path for a blind range with one out), so each parting was flagged, not silent.  Every served
line (events, rows named, RMSE) is the same on both trees: the rule changes the export only.
B1 MET (above).  B2 MET (every fresh case 0 rows apart, <= 2.4e-13 µm on the rule).  B3 MET
(healthy lines identical).  B4 MET: bench_mon98 ``cases`` on tr9828 / sw9776 / cr9763 / lr9376
(53.4 / 53.0 s CPU), bench_dep98 ``back`` tr9828 (11.1 / 11.1 s), bench_kelvin97 ``faults``
(49.4 / 49.7 s): every line the same, main and rule.  B5 MET: test_export_mon98b's compiled-C
case fails on da1272c3 (``RANGE`` flagged from the fault's row 721), passes on the rule.
Beside the bar: on da1272c3 bench_mon98's seen tr9828 drift line is no longer its docstring's
(16d3b58d: new state at 148, C = served): served takes ``T_coolant_return`` out at 130 and the C
parts from served by up to 19.9 µm over 6743 rows, on main and rule alike (not this rule's).
Its cause is restart98 (8cd3b84a; 289e984a, 9f59f14f and 16d3b58d give the old line): W3 is no
longer warmed on W2 (0 lead-in rows, 20160 before).  Traced on the rule's tree (/tmp/mon98b
``tr.py``): the same defect as dl9845's with a sensor the others predict: ``T_coolant_return``
(blind) out as explaining at 130, ``T_ram`` beyond its range at 817; served takes ``T_ram`` out and
``T_coolant_return`` back, the C flags ``RANGE`` at 817 (its first parting, 6.77 µm: flagged, not
silent) and keeps ``T_coolant_return`` out.  This rule does not reach it (the C flags ``RANGE``
there on the rule too: not traced why); next: the first's return judged before the refusal.

VERDICT: KEPT (B1-B5 met).  The ST block lags (flags ``OFF_RANGE``, holds no re-admission).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_cmon91 import FRESH as CMON91  # noqa: E402
from bench_mon97 import SW  # noqa: E402
from bench_mon98 import FRESH as MON98  # noqa: E402


def _dl(seed: int) -> list[str]:
    """bench_cmon91's dl9377 generator with ``seed``."""
    return [f"seed={seed}" if w.startswith("seed=") else w for w in CMON91["dl9377"]]


FRESH = {"dl9870": _dl(9870), "dl9871": _dl(9871), "sw9872": [*SW, "seed=9872"]}


def cases(root: str, *records: str) -> None:
    """bench_mon98's ``cases`` on :data:`FRESH` and dl9845 (module doc)."""
    from bench_mon98 import cases as mon98_cases

    mon98_cases(root, *records, generators={"dl9845": MON98["dl9845"], **FRESH})


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cases": cases}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
