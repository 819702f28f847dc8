"""A stepped error's culprit out in the exported C (cmon86, issue 34): the code's monitor
excludes the culprit of a self-prediction error stepped past the alarm band as the served
monitor does (its ``_check_stepped``), where before it flagged ``STEPPED`` and the conformance
pack was cut there.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon86.py compare [ROOT] [SPEC]

``ROOT`` (default ``/tmp/cmon86-bench``); ``SPEC`` (default :data:`SPEC`: bench_cmon85's 50
campaigns, seeds 8841-8850, and as many fresh ones drawn with this task's seeds 8996-9005, none
tuned on).  The records, the faults and the model as bench_cmon84 draws them (``_records``).
``compare``: bench_cmon85's (its ``measured``) with "before" the export without ``stepped`` (the
code as on main, which flags a stepped error): per campaign the rows where the compiled C equals
the served corrections (every target within 1e-9 µm, over the rows the C takes), the largest
|C - served| over them, the first flag, the pack's rows and ``tc_step``'s largest and summed CPU
time of a sample.

Traced (s8841 drift, bench_cmon85's record; the code on main): the drifting ``T_front1`` reads
beyond its range at row 1121 and is excluded for it (``OFF_RANGE``).  Its drift had pulled the
others' predictions: with it out ``T_right1``'s self-prediction error steps by -2.83 °C in that
sample, past its alarm band.  The served ``_check_stepped`` takes ``T_right1`` out as a second
sensor (its culprit: the largest step times ``sqrt(1 - h)``), a drift-like exclusion (its wait
doubled, no field following it), back after a window within half its warning band (row 1249).  The
C flagged ``STEPPED`` and kept ``T_right1`` in: from row 1122 on its corrections part from the
served ones by 9-75 µm.  What the C lacked: the stepped culprit's exclusion, and (with one out)
the operator of the set with two out, which cmon85's solve holds.

The rule (the code's; the served monitor unchanged): each judged sensor whose error steps past
its alarm band in one sample (``|e| >= alarm`` and ``|e - e_prev| >= alarm``) is fired on (not
calm, not due back, its dropout mark cleared); the culprit (the largest ``|e - e_prev|
sqrt(1 - h)``) out as a drift exclusion is (its wait a window doubled per exclusion, but no field
to follow), beside one out already as the second (the set solved, cmon85); a third, or one the
code does not hold out, flagged as before.  Work: the check is O(n) per sample; an exclusion adds
one solve of the set's operator (bench_cmon85's bound).

Bar (written before scoring): over bench_cmon85's 50 campaigns and the 50 fresh ones, the
campaigns flagged go down; no campaign that was C = served on every row before loses it; every
changed campaign's largest |C - served| over the rows the C takes <= 1e-9 µm; the largest
``tc_step`` CPU time of a sample over all campaigns now / before <= 3; the export compiles with
-Werror (the bench's build, ``_ccode.built``) and tests/shell/test_export*.py pass; a test that
fails on main (tests/shell/test_export_cmon86.py: the stepped culprit followed by the C).

Scored (2026-12-04, ``compare`` on this branch's sources at its first commit, "before" the same
export without ``stepped``; run as five processes over the SPEC's parts under a load of 13 on the
two shared cores; the process that ran bench_cmon85's strangers went on into the fresh ones,
scored again by another, and was stopped there): 100 campaigns (50 of bench_cmon85's, 50 fresh).
The column's drift records of s8841-s8844 were traced while the
rule was written (s8841); the fresh ones were not looked at before scoring.  Before -> now, the
changed campaigns (rows C = served, every target within 1e-9 µm; max abs(C - served); the first
flag; the pack's rows; ``tc_step``'s largest CPU time of a sample, µs):

| campaign (T_front1) | rows C = served | max abs(C - served), µm | first flag | pack rows | worst, µs |
|---|---|---|---|---|---|
| column s8841 drift | 1313 -> 1441 | 75 -> 8.2e-13 | STEPPED 1121 -> none | 1120 -> 1441 | 11.2 -> 19.9 |
| column s8842 drift | 1335 -> 1441 | 30 -> 1.2e-12 | STEPPED 1130 -> none | 1129 -> 1441 | 8.3 -> 20.7 |
| column s8843 drift | 1331 -> 1441 | 44 -> 9.4e-13 | STEPPED 1106 -> none | 1105 -> 1441 | 8.8 -> 19.1 |
| column s8844 drift | 1284 -> 1441 | 78 -> 3.5e-12 | STEPPED 1098 -> none | 1097 -> 1441 | 12.9 -> 20.9 |
| column s8996 drift | 1310 -> 1441 | 37 -> 1.4e-12 | STEPPED 1083 -> none | 1082 -> 1441 | 8.3 -> 19.8 |
| column s8998 drift | 1363 -> 1441 | 17 -> 6.3e-13 | STEPPED 1157 -> none | 1156 -> 1441 | 12.5 -> 21.7 |
| column s8999 drift | 1276 -> 1441 | 34 -> 2.2e-12 | STEPPED 1088 -> none | 1087 -> 1441 | 11.3 -> 20.8 |

Every other campaign the same rows, gaps, flags and pack rows.  Over the 100: rows C = served
200725 -> 201600 of 201600; C = served on every row of 93 -> 100 campaigns, none
lost; campaigns flagged 7 -> 0; the pack keeps 199289 -> 201600 rows; the changed
campaigns' largest abs(C - served) 3.5e-12 µm.  Work: the largest ``tc_step`` CPU time of a
sample over all 100 23.9 -> 24.5 µs (1.02x); per campaign the ratio now /
before of its largest 1.02 at the median (0.59 - 1.49 where nothing changed: the timer's
noise), 2.49x at most (a drift campaign: the samples that solve the set with two out); summed
378.3 -> 378.5 ms.  The export compiles with -Werror (every build above);
tests/shell/test_export*.py pass (418 + 220, with test_docs / test_imports / test_benchmarks_cli);
tests/shell/test_export_cmon86.py fails on main (the mirror flags ``STEPPED`` at row 1121).

Verdict: KEPT (every clause of the bar met).

Tried after, not kept: a jump of a sensor while one is out, re-referenced and out as the second
(``benchmarks/cmon86_jump.patch``, a ``second_jump`` key).  On test_export_cmon80's three-sensor
record the planted jump of ``T_a`` beside ``T_b``'s reading beyond its range then leaves one
sensor in: the mirror re-admits both at row 33, where the served monitor keeps them out, and
parts from it by 4.1-15 µm with no flag (C = served lost, unflagged): the code's re-admission of
two out with one sensor left in differs from the served one (not traced further; cmon85's second
out may reach it too).  Not scored; reverted.  Left: that re-admission, a third sensor out, a second
one out for a jump, a dropout or its range, and a sensor no other predicts as the second out.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import made_folder, run_commands, seed_list  # noqa: E402

SPEC = ("column:8841-8844,trunnion:8845-8846,lathe:8847-8848,jig:8849-8850,"
        "column:8996-8999,trunnion:9000-9001,lathe:9002-9003,jig:9004-9005")


def _before(ss):
    """``ss`` as exported before cmon86 (no ``stepped``: a stepped error flagged)."""
    import dataclasses

    return dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items() if k != "stepped"})


def compare(root: str = "/tmp/cmon86-bench", spec: str = SPEC) -> None:
    """Before / now per campaign (bench_cmon85's ``measured``, before: :func:`_before`)."""
    import tempfile

    from bench_cmon84 import _records
    from bench_cmon85 import measured

    folder = made_folder(root)
    t0 = time.process_time()
    for part in spec.split(","):
        name, seeds = part.split(":")
        for seed in seed_list(seeds):
            for deployed, tests, label in _records(folder, name, seed):
                with tempfile.TemporaryDirectory(prefix="cmon86-") as tmp:
                    print("\n".join(measured(deployed, tests, label, Path(tmp), _before)),
                          flush=True)
    print(f"bench process CPU {time.process_time() - t0:.1f} s", flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"compare": compare}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
