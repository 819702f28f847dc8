"""A healthy coupled pair excluded on a 0.1 K logger (mon82c): the trace, the rule, its bar.

    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82c.py trunnion ROOT LABEL [SEEDS \
        [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82c.py lathe ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82c.py jig ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82c.py table ROOT SHIPPED RULE

bench_mon81's harness (``thermocomp monitor``, MLR fitted on the record's own train split,
``track=false plots=none``, a line per record in ``ROOT/<LABEL>.jsonl``; the code measured is
the tree on ``PYTHONPATH``: ``/work/main/src`` shipped, the branch the rule) on the stranger
machines with a 0.1 K logger: ``trunnion`` (``bench_stranger82b.py``: trunnion82b, its GX20
export), ``lathe`` (``bench_stranger82.py``: lathe82, its GL840 CSV), ``jig`` (bench_mon81's
``jig``: stranger80's jig borer); kinds ``healthy,frozen,jump,drift,dropout`` (each bench's
``faults``); ``table``: bench_mon81's (the bar's parts 1-3 below).

Verdict: REFUSED (part 4: a test file of the monitor fails; parts 1-3 held; below).

Traced (main at d7a6302e, trunnion 8342 healthy, its own init config and mlr; the monitor's
``_update`` wrapped to keep each full-path sample's errors, the fast path's readings recomputed
with the all-in operator).  The rule that fired: the drift judgement
(``Judgement._exclude_by_judgement``), every sensor in, the culprit ``T_RUNDTISCH`` (the C
table), its leave-one-out self-prediction error, mean over ``confirm`` = 2 samples, -0.595 °C at
row 1628 (9.04 h), both samples beyond its warning band 0.576 °C: the band's floor, 3
(``spread_factor``) x its training spread 0.192 °C (99.5th percentile of the windowed
leave-one-out error over the 12 train campaigns; the configured 0.4 below it).  Its partner
``T_WIEGE`` (the trunnion) went with it as blind (its leverage 0.175 with all in, 0.985 once the
table is out; the table's 0.829, 0.997 once the trunnion is out: each the other's only
predictor), its error +0.26 °C within its 0.4 band.  Why healthy data cleared it: the table's
error sat at about -0.46 °C (an offset of this test day beyond training's largest, 0.307 °C of
the same 2-sample statistic over the 12 train campaigns, none beyond the band there) and
flickered -0.35 / -0.59 with ``T_WIEGE`` reading 21.6 / 21.7 °C (``T_RUNDTISCH`` 22.2 still):
the all-in operator's leave-one-out row of the table weighs the trunnion's reading -2.18, so one
0.1 K step of the logger moves the table's error by 0.218 °C (its own reading 0.100, ``T_PINOLE``
0.021, ``T_BETT`` 0.020, ``T_STAENDER_V`` -0.014); the two rows before 1628 with the trunnion at
21.7 crossed.  The band learned from training residuals holds the quantisation only as often as
training's 99.5 % saw it, not its bound: a 1-in-200 flicker on an offset day is an exclusion.

The rule (written before scoring): the learned floor of each judged sensor's band adds the
largest shift of its self-prediction error (every sensor in) that rounding the readings to
their resolution makes, ``(q / 2) · sum_k |(I - M)_jk / (1 - h_j)|``, ``q_k`` sensor ``k``'s
smallest non-zero one-sample step in training (0.1 K on a logger that rounds; about none on a
continuous reading, so the simulated records keep their bands); warning floor ``spread_factor x
spread + that``, alarm floor twice it (``monitor.bands.learned``: ``4 x spread + that``).  On
8342: ``T_RUNDTISCH`` 0.576 -> 0.773 °C, ``T_STAENDER_H`` 0.4 -> 0.43, the others unchanged.
The C (``export/watch.py``) reads the bands the model carries (``warning_c`` / ``alarm_c``): it
follows without a change.

The bar (written before scoring; fresh seeds 8401-8420, none tuned on):
1. Every fresh healthy draw (trunnion 8401-8402, lathe 8403-8404, jig 8405-8406): no exclusion
   event where shipped has none, adaptive RMSE not > 1 % worse than shipped on each target.
2. 8342 (the found case, apart): quiet.
3. Every injected fault (frozen, jump, drift, dropout of each bench's ``faults``, on trunnion
   8401, lathe 8403, jig 8405): the faulted sensor excluded no later than shipped where shipped
   excludes it, adaptive RMSE not > 2 % worse (bench_mon81's ``table``).
4. The monitor test files pass (``tests/apps/test_monitor*.py``, ``tests/shell/test_monitor*.py``).

Scored (2026-12-04, shipped = ``/work/main/src`` at d7a6302e, rule = 7842b580; ``trunnion`` /
``lathe`` / ``jig`` as in the usage, then ``table ROOT shipped rule``).  Adaptive RMSE (µm) per
target, shipped -> rule, and the exclusions (first, h):

| record | kind | shipped exclusions | rule exclusions | adaptive RMSE shipped -> rule |
|---|---|---|---|---|
| trunnion 8342 (found) | healthy | RUNDTISCH + WIEGE 9.044 | none | 5.222 / 2.299 / 2.568 -> fixed's |
| trunnion 8401 | healthy | none | none | 9.790 / 6.385 / 1.444 equal |
| trunnion 8402 | healthy | none | none | 6.999 / 3.098 / 1.354 equal |
| lathe 8403 | healthy | none | none | 1.961 / 3.196 equal |
| lathe 8404 | healthy | none | none | 2.077 / 3.390 equal |
| jig 8405 | healthy | none | none | 4.823 / 5.320 / 2.325 equal |
| jig 8406 | healthy | none | none | 4.334 / 2.844 / 1.986 equal |
| trunnion 8401 | frozen PINOLE | 6.772 | 6.772 | equal |
| trunnion 8401 | jump STAENDER_H | 5.556 | 5.556 | equal |
| trunnion 8401 | drift KUEHLUNG | none (no other predicts it) | none | equal |
| trunnion 8401 | dropout MUTTER_X | 6.667 | 6.667 | equal |
| lathe 8403 | frozen SPINDELKASTEN | none | none | equal |
| lathe 8403 | jump BETT_R | 5.556 | 5.556 | equal |
| lathe 8403 | drift KUEHLMITTEL | REVOLVER 5.056 | REVOLVER 5.283 | 1.869 / 3.338 -> 1.878 / 3.356 |
| lathe 8403 | dropout MUTTER_Z | 6.667 | 6.667 | equal |
| jig 8405 | frozen Pinole | 5.042 | 5.042 | equal |
| jig 8405 | jump Ständer_hinten_oben | 5.828 | 5.828 | equal |
| jig 8405 | drift Hydraulik_Tank | 7.839, 3 out / 2 back | the same | equal |
| jig 8405 | dropout Mutter_X | 6.661 | 6.661 | equal |

Parts 1-3 held: no exclusion on any fresh healthy draw either way, their RMSE equal to the printed
digit; 8342 quiet (adaptive = fixed 5.116 / 1.903 / 2.662: dY 2.299 -> 1.903, dZ 2.568 -> 2.662, the
exclusion's dZ gain was chance); every fault's sensor out at the same sample.  On lathe 8403 the
coolant's drift again takes out the healthy turret (stranger82's 8211 case on a fresh draw), the
rule 14 min later (the turret's band wider), +0.5 % on either target; the coolant never out.
(bench_mon81's ``table`` also flags jig 8405's flapping tank, 3 exclusions both ways, and 8342's
changed healthy RMSE: the found case, apart.)

Part 4 FAILED (the monitor test files with the rule: 2 failed, 138 passed, 4 xfailed; 132 s):
``tests/apps/test_monitor_regime73.py``'s hovering offset (its first test): the Swiss-type lathe's
healthy ``T_toolholder1``, hovering at -0.55 / -0.56 °C in a regime training never held, warned on
main against its 0.539 °C band; its logger's 0.01 K adds 0.021 (band 0.560) and the offset is no
longer said (no event at all).  And ``tests/shell/test_monitor_healthy53.py``'s strict xfail passed
(its healthy column quiet: a gap the rule closes, a strict xfail's XPASS a failure till its mark
goes).  A warning lost within the resolution's own bound is what the rule means to do, but the bar
said the tests pass: REFUSED.  The src change is reverted; the rule is
``benchmarks/mon82c_rule.patch``.

Left: 8342's table / trunnion pair is excluded on main as before.  The warning band (what is
said) and the exclusion band (what is done) share the floor; a resolution bound on the exclusion
only (``exclude_at``'s band, the warning as shipped) would keep regime73's warning and might pass,
not scored.  The lathe's coolant drift still takes the healthy turret out (a fresh draw, 8403).
No failing-on-main test: seeds 8407-8419 went on a synthetic one (test_monitor_frozen_pair77's
field rounded to 0.1 K, trained on 8407-8408 / 8409-8410, 9 healthy draws 8411-8419): no event
on main or with the rule, so it could not fail; not written (those seeds are spent).
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_mon81 as m81  # noqa: E402
from _cli import run_commands  # noqa: E402

KINDS = m81.KINDS
m81.FAULTED.update({
    "trunnion": {"frozen": "T_PINOLE", "jump": "T_STAENDER_H", "drift": "T_KUEHLUNG",
                 "dropout": "T_MUTTER_X"},
    "lathe": {"frozen": "T_SPINDELKASTEN", "jump": "T_BETT_R", "drift": "T_KUEHLMITTEL",
              "dropout": "T_MUTTER_Z"}})


def trunnion(root: str, label: str, seeds: str = "8342,8401-8402", kinds: str = KINDS) -> None:
    """stranger82b's trunnion centre, healthy and faulted (docstring)."""
    m81._stranger(root, label, seeds, kinds, "trunnion", "bench_stranger82b")


def lathe(root: str, label: str, seeds: str = "8403-8404", kinds: str = KINDS) -> None:
    """stranger82's lathe, healthy and faulted (docstring)."""
    m81._stranger(root, label, seeds, kinds, "lathe", "bench_stranger82")


def jig(root: str, label: str, seeds: str = "8405-8406", kinds: str = KINDS) -> None:
    """stranger80's jig borer, healthy and faulted (docstring)."""
    m81._stranger(root, label, seeds, kinds, "jig", "bench_stranger80")


def main(argv: list[str] | None = None) -> int:
    np.seterr(all="ignore")
    return run_commands(__doc__, {"trunnion": trunnion, "lathe": lathe, "jig": jig,
                                  "table": m81.table},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
