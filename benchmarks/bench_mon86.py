"""A band for the set a sensor is judged in (mon86, issue 34): fl_thermal's healthy ``T_t14``,
back once the drifting ``T_t12`` is out, warns 15 times against a band trained on the whole set.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_mon86.py trace [CASE]
    python benchmarks/bench_mon86.py column ROOT LABEL [SEEDS [KINDS]]
    python benchmarks/bench_mon86.py ctable ROOT MAIN RULE
    python benchmarks/bench_mon86.py ccode [ROOT] [SEED] [KIND]
    python benchmarks/bench_mon86.py trunnion ROOT LABEL [SEEDS [KINDS]]
    python benchmarks/bench_mon86.py lathe ROOT LABEL [SEEDS [KINDS]]
    python benchmarks/bench_mon86.py jig ROOT LABEL [SEEDS [KINDS]]
    python benchmarks/bench_mon86.py table ROOT MAIN RULE

``trace``: tests/apps/test_monitor_new_state48.py's case (bench_mon85b's ``trace``; ``CASE``
``drift``: ``T_t12`` drifting 1 K/h from sample 10243, ``clean``: the record as measured), served:
every event after the train part, ``T_t14``'s warning episodes (ok -> warning or alarm) after
its last return, the samples it spends out of ok then, and its bands in the whole set and in the
set without ``T_t12``.  The rest: bench_mon84's commands (its docstring), by default on
``/tmp/mon86-bench`` and this task's fresh seeds: ``column`` 8986-8990, ``trunnion`` 8991-8992,
``lathe`` 8993-8994, ``jig`` 8995.

Traced (2026-12-04, main 14a3bd50).  The bands are set once, in ``from_training``: the configured
band or ``SPREAD_FACTOR`` (3) x the sensor's training spread, whichever is larger, the spread the
99.5th percentile of its windowed leave-one-out error with every sensor in.  Every judgement
(``_judge``: a band left when the last ``confirm`` = 2 errors are all beyond it; ``_set_states``
turns that into a ``warning`` event) compares the error in the *active* set against that
whole-set band.  On the drift case ``T_t14`` is out 10294-10498 and back at 10498 (mon85b), in
the set without ``T_t12`` (``T_t14``'s leverage 0.502 -> 0.725) to the end: training's own
spread of ``T_t14`` there is 0.166 °C (0.112 with every sensor in), so 3x it is 0.499 > the
0.400 band it is judged against; its error on the record, as on the clean one, has median
``|E|`` 0.333 and 90th percentile 0.402: it warns 15 times (bench_mon85b).

The rule (written and committed before scoring).  A sensor's bands are those of the set it is
judged in: ``max(configured, SPREAD_FACTOR x its training spread in that set)`` (the alarm band
twice that floor, ``learned_bands`` alike: its floor 4x the spread), never narrower than its
whole-set band.  Its spread in a set ``S`` is its whole-set spread x ``g_S``, ``g_S = sqrt(a_S' C
a_S / a_F' C a_F)`` (at least 1; 1 for the whole set ``F`` and where no other sensor predicts it):
``a`` its row of the leave-one-out error map ``(e_j - M_S[j]) / (1 - h_j)`` (the error is linear
in the referenced readings, and so is its trailing window mean), ``C`` the second moment of
training's windowed referenced snapshots (``n x n``, fitted once with the bands).  So the ratio
of the windowed error's RMS in ``S`` to its RMS in ``F``: no refit, no training data kept, per
change of the active set ``O(n^3)`` from the operator the monitor computes anyway.  On the trace
the RMS ratio of ``T_t14`` is 0.0721 / 0.0484 = 1.490 against its 99.5th-percentile ratio 0.166 /
0.112 = 1.486.  Served: the active set's bands judge (levels, the fast path, the stepped error,
the freeze's moved field, the culprit and explaining checks, the messages); a re-admission trial
is judged against the trial set's bands; ``warning_c`` / ``alarm_c`` stay the whole set's (what
reports show).  Numpy mirror (``export/watch.py``) and C (``watch_c.py``) alike, from the
exported ``floor`` and ``moment``; an export without them judges as before.

Bar (written before scoring; "main": ``git archive 14a3bd50`` sources, alternated with the rule's
``git archive``; REFUSED if any part fails: the source reverted, the rule kept as
``benchmarks/mon86_rule.patch``):
1. ``trace drift``: ``T_t14``'s warning episodes after its return fewer than main's; ``T_t14``
   back and ``T_t12`` out at main's samples, no new thermal state.  ``trace clean``: nothing out
   and every event after the train part main's (no warning it had not).
2. s8703, s8546, s8613 healthy: every E_* served RMSE no more than main's; s8774 frozen:
   ``T_front1`` first out no later than main's.
3. Fresh column_moving_source 8986-8990, healthy and frozen / jump / drift / dropout: no served
   E_* RMSE more than 2 % above main's; ``T_front1`` first out no more than 2 samples after main's.
4. Trunnion 8991-8992, lathe 8993-8994, jig 8995, healthy: no exclusion or new thermal state main
   does not have.
5. ``ccode`` (rule) on s8774 frozen, s8703 healthy and fresh 8986 drift: C = served to 1e-9 µm.
6. tests/apps/test_monitor*.py, tests/shell/test_monitor*.py, tests/shell/test_export*.py pass.

Scored, the first rule (2026-12-04; main ``git archive 14a3bd50``, the rule served only: the
mirror and the C not yet written, part 1 first)
------------------------------------------------------------------------------------------------
1. ``trace drift``: main ``T_t14`` out 10294, ``T_t12`` out 10498 (lone fault, ``E`` +0.93),
   ``T_t14`` back at 10498, then 15 warning episodes and 36 samples out of ok to the end.  The
   rule: ``T_t14`` out 10294 as main, and ``T_t12``'s bands in the set without ``T_t14`` widen
   0.453 -> 0.644 (alarm 0.906 -> 1.29, the band that excludes while ``T_t14`` is out by its
   error): ``T_t12`` reaches it at 10617, when ``T_t15`` and ``T_t8`` (their bands 0.400, 0.580)
   are out of theirs, and ``_drift_vetoed`` (``new_state_others`` = 2 others out) refuses it on
   every sample to the end.  ``T_t12`` never out (main: 10498), ``T_t14`` never back; out at the
   end ``T_t14``.  ``trace clean``: nothing out, no event after the train part, both.  Fails.

Verdict on the first rule: REFUSED at part 1 (the rest not scored): the source reverted, the rule
kept as ``benchmarks/mon86_rule.patch`` (served only).  The band of the set works both ways: the
coupled partner of a sensor taken out is predicted worse in training too, so a drift of that
partner is held to the looser band; where the sensor out is a culprit taken within its band
(mon85b's ``_hid``: the monitor's guess, not a fault seen), that is the drift it hid, hidden
further.  ``T_t14``'s own band in the set without ``T_t12``: 0.400 -> 0.500 (alarm 1.001).

The second rule (written and committed before scoring it; the bar above, parts 1-6, unchanged).
The first rule, but the set that sets the bands counts a culprit out within its own band
(``_hid``) as in: the active set and every ``_hid`` sensor.  It is out on the monitor's guess (it
passed its own band; the field pulled round it by another's error) and due back as soon as that
one is out (mon85b), so it loosens no band meanwhile; a sensor out for its own error beyond the
band, or an instant fault (dropout, range, jump, freeze), leaves the set it is judged without.
Served, numpy mirror (``hid``) and C (``mon_hid``) alike.

Scored, the second rule (2026-12-04; "main": ``git archive 14a3bd50`` sources, "rule": this branch
at c0590a05 (``git archive``), per seed main's run then the rule's; E_* test RMSE in µm, served
adaptive)
------------------------------------------------------------------------------------------------
1. ``trace drift``: every event to 10498 as main's (``T_t14`` out 10294, ``T_t12`` out 10498 as
   the lone fault, ``E`` +0.93, ``T_t14`` back at 10498: "within ±0.5 °C", main's "±0.4"), no new
   thermal state, out at the end ``T_t12`` both.  After its return ``T_t14``: main 15 warning
   episodes and 36 samples out of ok, the rule 0 and 0 (its band in the set without ``T_t12``
   0.400 -> 0.500, alarm 0.800 -> 1.001); no other event after 10498 either way.  ``trace
   clean``: nothing out, no event after the train part, both.  Holds.
2. s8703 / s8546 / s8613 healthy and s8774 frozen: every line of the two jsonl equal (RMSE to 4
   decimals, the spans out, the events; s8703 E_Y 15.275, s8546 16.489, s8613 12.352 both);
   ``T_front1`` first out 726 -> 726.  Holds.
3. Fresh 8986-8990, healthy and the four faults (25 records): every line equal; ``T_front1`` first
   out at the same row (frozen 732 / 728 / 752 / 732 / 725, drift 1174 / 1153 / 1255 / 1295 /
   1159, jump and dropout 721).  Holds.
4. Trunnion 8991-8992, lathe 8993-8994, jig 8995, healthy (``table /tmp/mon86-str main rule``):
   the two jsonl byte-identical, no event on any either way.  Holds.
5. ``ccode`` (rule): s8774 frozen, s8703 healthy and 8986 drift, C = served to 2.84e-13 µm, the
   code flags nothing.  Holds.  The branch is taken there: with ``T_front1`` out (s8774 frozen,
   rows 726-1441) the set's bands are wider than the whole set's for some sensor (on s8774 and
   s8703 the sets without 12 and 11 of the 20 sensors widen one, ``T_front1``'s among them; on
   8986 11, not ``T_front1``'s), and the column records are main's line for line: the wider
   bands changed no decision there.  Also the deployed fl_thermal with ``T_t12`` frozen from row
   240: 682 of its 1112 rows judged with a wider band for some sensor, C = served to 3.9e-13 µm,
   nothing flagged (tests/shell/test_export_mon86.py).
6. tests/apps/test_monitor*.py, tests/shell/test_monitor*.py, tests/shell/test_export*.py with the
   rule: 417 passed, 1 failed, 4 xfailed (main's four known gaps), 273.9 s user + 14.9 s sys
   CPU.  The failure: test_monitor_lab57's empty logger row asserted each re-admission message
   names the sensor's whole-set warning band; ``T_guidebush``, back at 9600 s while others of
   the dropout were still out, now names its band in the set it came back in, 1.01 °C against
   0.925.  Main and the rule on that record (the test's own stream): every event at the same
   time, the same RMSE (E_X 1.298 fixed / 1.303 adaptive, E_Y 0.921 / 0.924); that message's
   figure the only difference.  The test now asserts the figure is at least the whole-set band
   (the half band before mon85b's dropout rule still fails it): 14 passed.  Holds with that
   message changed, by the rule's design.

CPU (user + sys of the bench process): ``column`` on the 9 seeds 29.1 s main (making the
records), 24.5 s rule; ``ccode`` 2.3-2.5 s each; ``trace clean`` 1.2 / 1.3 / 1.3 s main and 1.2 /
1.3 / 1.2 s rule (alternated): the moment (``n x n``, fitted once) costs nothing measurable; the
stranger runs 4.0-4.8 s main (making the records), 0.0 rule (their work in their ``thermocomp
monitor`` subprocesses, not counted).

Verdict: KEPT (parts 1-5 held; part 6 with the one message figure above, the test updated).
The rule quiets the healthy ``T_t14`` after its return (15 warning episodes -> 0) and changed
no decision on the 29 column and 5 stranger records.  What it does not do: the hypothetical sets
of the judgement (``_resolves``, ``_explaining``, ``_lone_fault``: the active set less one) are
judged with the active set's bands, not their own; ``_hotter`` and the out-of-range leak
(``_leak_passes``) keep the whole set's; on the exported records the wider bands are computed
(C = served) but changed no decision, so the C's ``mon_bands`` is shown equal where it is
inert; the RMS ratio stands in for the 99.5th percentile's (1.490 against 1.486 on the trace).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_mon84 as m84  # noqa: E402
import bench_mon85b as m85b  # noqa: E402
from _cli import run_commands  # noqa: E402

ROOT = "/tmp/mon86-bench"


def _bands(mon, subset: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The warning and alarm bands of ``subset`` (the rule's, where the tree has it)."""
    if hasattr(mon, "_bands_of"):
        return mon._bands_of(subset)
    return mon.warning_c, mon.alarm_c


def trace(case: str = "drift") -> None:
    from thermocomp.apps.deploy.surveillance import SensorMonitor

    names, x = m85b._fl(case)
    cut, t14, t12 = 10003, names.index("T_t14"), names.index("T_t12")
    mon = SensorMonitor.from_training(None, names, {"train": x[:cut]})
    back, episodes, off = None, 0, 0
    for i, row in enumerate(x):
        events = mon.update(row, 15.0 * i)[1]
        for e in events if i >= cut else []:
            if e["sensor"] != "T_t14" or e["to"] == "excluded" or e["from"] == "excluded":
                print(f"{i}: {e['sensor']} {e['from']} -> {e['to']}: {e['reason'][:120]}")
            if e["sensor"] == "T_t14" and e["from"] == "excluded":
                back, episodes, off = i, 0, 0
            elif e["sensor"] == "T_t14" and back is not None and e["from"] == "ok":
                episodes += 1
        if back is not None and mon._active[t14]:
            off += int(mon.states[t14] > 0)
    print(f"T_t14 last back at {back}: {episodes} warning episodes, {off} samples out of ok after")
    for label, s in (("whole set", np.ones(len(names), bool)),
                     ("without T_t12", np.arange(len(names)) != t12)):
        w, a = _bands(mon, s)
        print(f"T_t14 bands, {label}: warning {w[t14]:.3f}, alarm {a[t14]:.3f}")
    print("out at the end:", mon.excluded, "; new thermal state:", mon.new_state_)


def column(root: str, label: str, seeds: str = "8986-8990", kinds: str = m84.KINDS) -> None:
    m84.column(root, label, seeds, kinds)


def ctable(root: str, main: str, rule: str) -> None:
    m84.ctable(root, main, rule)


def ccode(root: str = ROOT, seed: str = "8774", kind: str = "frozen") -> None:
    m84.ccode(root, seed, kind)


def trunnion(root: str, label: str, seeds: str = "8991-8992", kinds: str = m84.KINDS) -> None:
    m84.trunnion(root, label, seeds, kinds)


def lathe(root: str, label: str, seeds: str = "8993-8994", kinds: str = m84.KINDS) -> None:
    m84.lathe(root, label, seeds, kinds)


def jig(root: str, label: str, seeds: str = "8995", kinds: str = m84.KINDS) -> None:
    m84.jig(root, label, seeds, kinds)


def table(root: str, main: str, rule: str) -> None:
    m84.table(root, main, rule)


def main(argv: list[str] | None = None) -> int:
    np.seterr(all="ignore")
    return run_commands(__doc__, {"trace": trace, "column": column, "ctable": ctable,
                                  "ccode": ccode, "trunnion": trunnion, "lathe": lathe,
                                  "jig": jig, "table": table},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
