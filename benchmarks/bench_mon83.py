"""A healthy coupled pair excluded on a 0.1 K logger, third try (mon83): the trace, the rule, its bar.

    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon83.py trunnion ROOT LABEL [SEEDS \
        [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon83.py lathe ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon83.py jig ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon83.py table ROOT SHIPPED RULE

bench_mon82c's harness (``thermocomp monitor``, MLR fitted on the record's own train split,
``track=false plots=none``, a line per record in ``ROOT/<LABEL>.jsonl``; the code measured is
the tree on ``PYTHONPATH``: ``/work/main/src`` shipped, the branch the rule) on the stranger
machines with a 0.1 K logger: ``trunnion`` (``bench_stranger82b.py``: trunnion82b, 8342 the found
case), ``lathe`` (``bench_stranger82.py``: lathe82), ``jig`` (``bench_stranger80.py``: jig80);
kinds ``healthy,frozen,jump,drift,dropout`` (each bench's ``faults``).  ``table``: the two labels
side by side (bench_mon81's), then each faulted sensor's first exclusion, rule minus shipped in
minutes.

Verdict: the first rule REFUSED (part 3), the second KEPT (below).

Reproduced (2026-12-04, main at b79207b5, ``trunnion ROOT main 8342 healthy``, 15.3 s CPU with
the record's write): ``T_RUNDTISCH`` and ``T_WIEGE`` excluded at 9.044 h (row 1628, 20 s
samples), adaptive RMSE dX / dY / dZ 5.222 / 2.299 / 2.568 µm against fixed 5.116 / 1.903 /
2.662.  The table's error (every sensor in) over the 22 rows to 1629: two levels, -0.34 ... -0.37
with ``T_WIEGE`` at 21.6 °C and -0.56 ... -0.59 at 21.7 (``T_RUNDTISCH`` 22.2 throughout); the
last two -0.590 / -0.584 against its band 0.576 (the smallest over 2 samples beyond it on rows
1628 and 1652 only of 1800; the largest smallest-of-3 0.573).  Its rounding bound, mon82c's
``(q / 2) · sum_k |(I - M)_jk| / (1 - h_j)`` (q = 0.1 K on every sensor): 0.196 °C (``T_WIEGE``
0.083, ``T_BETT`` 0.061, ``T_STAENDER_V`` / ``_H`` 0.069).  The excursion memory
(``Excursion._excursion_hovers``, mon73) at the exclusion: the table's error -0.587 °C is 0.53 of
its rise 1.10 °C; 30 min ago (the memory) -0.431 of 1.022, 0.42: grown 1.26x < 1.5, it *hovers*
-- a regime by the shipped test, but the culprit is out of its own band, where that test is not
asked (``level[j] < WARNING`` only).

The rule (written and committed before scoring).  mon82c / mon82d widened a band by the rounding
bound and so delayed every drift crossing it by up to the bound (the column's source, jig 8445's
tank).  Here nothing widens: the drift judgement's culprit ``j`` (``Judgement.
_exclude_by_judgement``, after the new-state veto) is held -- nothing excluded, as for mon73's
culprit within its band -- where both (a) its smallest error over the last ``confirm`` samples is
beyond the band that excludes (warning, or alarm while one is out) by less than its rounding
bound ``rounding_c`` (mon82c's ``(q / 2) · sum_k |(I - M)_jk| / (1 - h_j)``, ``q_k`` sensor
``k``'s smallest non-zero step in training, every sensor in; fitted by ``from_training``, 0 on a
continuous reading and on a monitor pickled before), a crossing the loggers' last digit can make
alone, and (b) the excursion hovers by mon73's test (``_excursion_hovers``: every judged sensor
out of band no larger a share of its rise than 30 min ago, within 1.5x), a regime.  A drift that
grows its share, or passes the band by more than the bound, is excluded at the same sample as
shipped; a continuous reading (bound about 0) is never held.  The warnings are as shipped (an
offset is still said).  ``_explaining`` (a sensor no other predicts, the tank) is not touched.
The exported monitor (``export/watch.py``, its C ``watch_c.py``) follows: the bound travels as
``rounding`` (an export before it: zeros, as shipped), C = numpy mirror = served.

The bar (written before scoring; fresh seeds 8511-8516, none tuned on; REFUSED if any part fails,
the src reverted and kept as ``benchmarks/mon83_rule.patch``):
1. 8342 (the found case, apart): no exclusion, adaptive RMSE = fixed on every target (warnings
   are allowed and counted).
2. Every fresh healthy draw (trunnion 8511-8512, lathe 8513-8514, jig 8515-8516), with the rule:
   no exclusion, adaptive RMSE equal to fixed on every target.
3. Every injected fault (frozen, jump, drift, dropout of each bench's ``faults``, on trunnion
   8511, lathe 8513, jig 8515): the faulted sensor excluded no later than shipped where shipped
   excludes it (each delay in minutes, ``table``; none later), no sensor excluded more often than
   shipped, adaptive RMSE not > 2 % worse than shipped (bench_mon81's ``table`` checks).
4. ``tests/shell/test_monitor*.py``, ``tests/apps/test_monitor*.py`` and
   ``tests/shell/test_export*.py`` pass, the exported C following the rule (C = served).

Scored (2026-12-04, shipped = ``/work/main/src`` at b79207b5, rule = 1343c021 + its export port;
ROOT /tmp/mon83, labels ``shipped`` / ``rule``; healthy on every seed, the faults on 8511 / 8513
/ 8515): **REFUSED** (part 3).  Adaptive RMSE (µm) per target, shipped -> rule, the exclusions
(first, h):

| record | kind | shipped exclusions | rule exclusions | adaptive RMSE shipped -> rule |
|---|---|---|---|---|
| trunnion 8342 (found) | healthy | RUNDTISCH + WIEGE 9.044 | none | 5.222 / 2.299 / 2.568 -> fixed |
| trunnion 8511 | healthy | none | none | 9.449 / 6.341 / 2.679 = fixed |
| trunnion 8512 | healthy | none | none | 7.373 / 4.055 / 1.288 = fixed |
| lathe 8513 | healthy | none | none | 2.177 / 6.263 = fixed |
| lathe 8514 | healthy | none | none | 1.864 / 4.325 = fixed |
| jig 8515 | healthy | none | none | 4.886 / 5.393 / 5.547 = fixed |
| jig 8516 | healthy | none | none | 6.317 / 4.075 / 6.889 = fixed |
| trunnion 8511 | frozen PINOLE | 6.061 | 6.061 (+0 min) | equal |
| trunnion 8511 | jump STAENDER_H | 5.556 | 5.556 (+0 min) | equal |
| trunnion 8511 | drift KUEHLUNG | none (no other predicts it) | none | equal |
| trunnion 8511 | dropout MUTTER_X | 6.667 | 6.667 (+0 min) | equal |
| lathe 8513 | frozen SPINDELKASTEN | none | none | equal |
| lathe 8513 | jump BETT_R | 5.556 | 5.556 (+0 min) | equal |
| lathe 8513 | drift KUEHLMITTEL | REVOLVER 6.394 | REVOLVER 6.772 | 4.426 / 7.075 -> 4.592 / 7.102 |
| lathe 8513 | dropout MUTTER_Z | 6.667 | 6.667 (+0 min) | equal |
| jig 8515 | frozen Pinole | 5.058 | 5.058 (+0 min) | equal |
| jig 8515 | jump Ständer_hinten_oben | 5.828 | 5.828 (+0 min) | equal |
| jig 8515 | drift Hydraulik_Tank | 7.797, 3 out / 2 back | the same (+0 min) | equal |
| jig 8515 | dropout Mutter_X | 6.661 | 6.661 (+0 min) | equal |

Part 1 held: 8342 has no exclusion, adaptive = fixed 5.116 / 1.903 / 2.662 (dY 2.299 -> 1.903;
dZ 2.568 -> 2.662, the false exclusion's dZ gain chance as in mon82c); 4 events left, the table's
two warnings at 9.044 / 9.178 h and their returns (25 shipped).  Part 2 held (no event either
way, RMSE = fixed to the printed digit).  Part 3 FAILED on lathe 8513's coolant drift: the
coolant (no other predicts it) is never out; its leak takes the healthy turret out, 22.7 min
later with the rule (6.394 -> 6.772 h), and that false exclusion had helped dX: 4.426 -> 4.592
(+3.8 % > 2 %; dZ +0.4 %).  Traced (main, the all-in operator): the turret's error climbed a
staircase -0.42 -> -0.445 -> -0.475 -> -0.55 ... -0.577 over the 60 samples (20 min) before
6.394 h, past its band 0.559 by less than its bound 0.088, and its share of its rise grew less
than 1.5x in the 30-min memory: mon73's share test called a growing leak a hover.  Every fault's
own sensor went out at the same sample (+0 min each); jig 8515's tank flaps 3x both ways
(bench_mon81's table flags it on both).  The export port (numpy mirror + C) passed
``test_export_cmon80/82/82b/82c`` and ``test_export_monitor76`` (15 passed); part 4 not run
further.  The src change (served + export) is reverted; it is ``benchmarks/mon83_rule.patch``.

The second rule (written and committed before scoring; tuned on 8342 and lathe 8513's drift, seen
above): the first, and (c) the error of the field's memory (the excursion rule's, 30 min, of the
culprit, every sensor in) beyond its band less its rounding bound already, on the side of its
error now: an offset that has stood within the logger's last digit of the band, not one a leak
carries there.  On the two tuning records: 8342's table, memory -0.431 against 0.576 - 0.196 =
0.380, held (no exclusion, adaptive = fixed); lathe 8513's turret, memory -0.400 against 0.559 -
0.088 = 0.471, out at 6.394 h as shipped (dX 4.426).  Served (``Judgement._within_rounding``),
numpy mirror and C alike.

Its bar (written before scoring; fresh seeds 8517-8522, none tuned on; REFUSED if any part fails):
parts 1-4 as above with trunnion 8517-8518, lathe 8519-8520, jig 8521-8522 healthy and the
faults on 8517 / 8519 / 8521 (ROOT /tmp/mon83, labels ``shipped2`` / ``rule2``); and 5. on the
first rule's records (8511-8516, seen; labels ``shipped`` / ``rule2``) the same checks.

Scored (2026-12-04, shipped = ``/work/main/src`` at b79207b5, rule = 3917940d; each machine's
records shipped then rule, the fresh first, then the seen): **KEPT**.
1. 8342: no exclusion (RUNDTISCH + WIEGE at 9.044 h shipped), adaptive = fixed 5.116 / 1.903 /
   2.662 µm (shipped 5.222 / 2.299 / 2.568); 4 events, the table's warnings at 9.044 / 9.178 h and
   their returns (25 shipped).  Held.
2. Fresh healthy: trunnion 8517 (8.060 / 4.640 / 1.154) and 8518 (9.132 / 2.852 / 3.303), lathe
   8519 (3.404 / 7.220) and 8520 (1.085 / 4.615), jig 8521 (6.083 / 2.314 / 1.732) and 8522
   (6.906 / 3.430 / 1.573): no event either way, adaptive = fixed to the printed digit.  Held.
3. Fresh faults, the faulted sensor's first exclusion shipped -> rule: trunnion 8517 frozen
   PINOLE 7.133 -> 7.133 h (+0 min), jump STAENDER_H 5.556 (+0), dropout MUTTER_X 6.667 (+0),
   drift KUEHLUNG never out either way (no other predicts it); lathe 8519 jump BETT_R 5.556 (+0),
   dropout MUTTER_Z 6.667 (+0), frozen SPINDELKASTEN and drift KUEHLMITTEL never out either way
   (the coolant's leak takes the healthy turret out at 5.167 h both ways); jig 8521 frozen Pinole
   5.042 (+0), jump Ständer_hinten_oben 5.828 (+0), drift Hydraulik_Tank 7.714 (+0), dropout
   Mutter_X 6.661 (+0).  Every exclusion count and every adaptive RMSE equal.  Held.
4. ``tests/shell/test_monitor*.py`` + ``tests/apps/test_monitor*.py``: 141 passed, 4 xfailed
   (the strict xfails still fail: healthy53's column is no rounding case); ``tests/shell/
   test_export*.py``: 239 passed (C compiled with the rule); the new
   ``tests/apps/test_monitor_rounding83.py`` (5: the bound; a healthy offset the last digit flips
   across the band warned, not excluded, where the judgement before excludes it; a drift from a
   clean field out at the same sample; the code's numpy mirror = served on both, bound or none).
   And the C on the found case: ``thermocomp run`` (mlr) then ``thermocomp export
   export.format=c monitor.adaptive=true`` of 8342 (``compensator.json``'s ``monitor.rounding``
   0.196 on the table, 0.083 the trunnion, 0.061-0.069 the bed and columns, 0 elsewhere),
   compiled ``cc -Wall -Wextra -Werror``: ``check/check.sh`` passed its 6 campaigns (1800 rows
   each, none cut, largest |C - served| 2.9e-14 µm), the own test campaign with no monitor
   message (the table held, as served).  Held.
5. Seen records (8511-8516) under the second rule: every exclusion and RMSE as shipped, lathe
   8513's turret out at 6.394 h as shipped (dX 4.426); bench_mon81's table flags only what it
   flags on shipped too (jig 8515's tank out 3x both ways) and 8342's change.  Held.

What it does not do: the rule fired on no fresh record (all 24 equal to shipped); its one effect
measured is 8342's.  A drift starting from an offset that stood within the bound of its band for
30 min waits until it passes the band by the bound or outgrows the memory's share (at most bound
/ rate: 0.196 °C on 8342's table, 12 min at 1 K/h); not met on the records above.  Lathe 8513 /
8519's coolant drift still takes the healthy turret out (shipped's behaviour, untouched).
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_mon81 as m81  # noqa: E402
import bench_mon82c as m82c  # noqa: E402
from _cli import run_commands  # noqa: E402

KINDS = m82c.KINDS


def trunnion(root: str, label: str, seeds: str = "8342,8511-8512", kinds: str = KINDS) -> None:
    """stranger82b's trunnion centre, healthy and faulted (docstring)."""
    m82c.trunnion(root, label, seeds, kinds)


def lathe(root: str, label: str, seeds: str = "8513-8514", kinds: str = KINDS) -> None:
    """stranger82's lathe, healthy and faulted (docstring)."""
    m82c.lathe(root, label, seeds, kinds)


def jig(root: str, label: str, seeds: str = "8515-8516", kinds: str = KINDS) -> None:
    """stranger80's jig borer, healthy and faulted (docstring)."""
    m82c.jig(root, label, seeds, kinds)


def table(root: str, shipped: str, rule: str) -> None:
    """bench_mon81's side by side, then each faulted sensor's first exclusion (min, rule - shipped)."""
    m81.table(root, shipped, rule)
    rows = {}
    for label in (shipped, rule):
        for line in (Path(root) / f"{label}.jsonl").read_text().splitlines():
            r = json.loads(line)
            rows.setdefault((r["record"], r["kind"]), {})[label] = r
    for (record, kind), two in sorted(rows.items()):
        if kind == "healthy" or len(two) < 2:
            continue
        first = [min((s[two[x]["sensor"]][2] for s in two[x]["sensors"].values()
                      if two[x]["sensor"] in s), default=None) for x in (shipped, rule)]
        said = "never out either way" if first == [None, None] else (
            f"{first[0]} h -> {first[1]} h" + (f", {60 * (first[1] - first[0]):+.1f} min"
                                             if None not in first else ""))
        print(f"{record:12s} {kind:8s} {two[shipped]['sensor']}: {said}")


def main(argv: list[str] | None = None) -> int:
    np.seterr(all="ignore")
    return run_commands(__doc__, {"trunnion": trunnion, "lathe": lathe, "jig": jig,
                                  "table": table},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
