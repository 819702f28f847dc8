"""A healthy column record the monitor must stay quiet on (mon86b, issue 34):
tests/shell/test_monitor_healthy53.py's strict xfail, traced on mon86's bands.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_mon86b.py trace [ROOT]
    python benchmarks/bench_mon86b.py fl [CASE]
    python benchmarks/bench_mon86b.py column ROOT LABEL [SEEDS [KINDS]]
    python benchmarks/bench_mon86b.py ctable ROOT MAIN RULE
    python benchmarks/bench_mon86b.py ccode [ROOT] [SEED] [KIND]
    python benchmarks/bench_mon86b.py trunnion ROOT LABEL [SEEDS [KINDS]]
    python benchmarks/bench_mon86b.py lathe ROOT LABEL [SEEDS [KINDS]]
    python benchmarks/bench_mon86b.py jig ROOT LABEL [SEEDS [KINDS]]
    python benchmarks/bench_mon86b.py table ROOT MAIN RULE

``trace``: the healthy53 record (column_moving_source seed 5305 without its new source, 30 h of
training, 20 h of test; made once under ``ROOT``, default ``/tmp/mon86b-bench``) through
``thermocomp monitor`` in this process: at each call of the served ``_lone_fault`` paper 002's
culprit, the pick, every judged sensor out of band (its last errors against its band, its
leverage, ``|E|(1 - h)`` and the standardised ``|E| sqrt(1 - h)``) and, for the four largest
``|E|(1 - h)``, who is out of the active set's band and of the trial set's own band (mon86's
``_bands_of``) with it out; then the record's events and served RMSE.  ``fl``: bench_mon86's
``trace`` (fl_thermal, ``drift`` or ``clean``).  The rest: bench_mon84's commands (its docstring)
on this task's fresh seeds: ``column`` 9061-9065, ``trunnion`` 9066-9067, ``lathe`` 9068-9069,
``jig`` 9070.

Traced (2026-12-04, main 6fa0d518, ``trace``).  One event, at t = 63100 s of ``test_cycle``:
``T_right3`` excluded ("drift: self-prediction error -0.17 °C"), back at 64200 s ("within ±0.4
°C for 11 samples"); E_X 0.731 fixed -> 0.776 adaptive µm (E_Y 6.072 -> 6.106, E_Z 1.349 ->
1.345).  The check: ``_lone_fault``'s first one, ``_resolves(j, out)`` of paper 002's culprit.
Every sensor in, the set's bands are the whole set's.  Out of band one sensor, ``T_left1``: its
last two errors -0.4068 / -0.4149 °C against its 0.4052 warning band (the smaller 0.4 % over),
leverage 0.786, ``|E|(1 - h)`` 0.088, standardised 0.190, the largest of all.  Paper 002's culprit
``j`` = ``T_right3``: ``|E|(1 - h)`` 0.111 (the largest), its error -0.165 °C within its 0.400
band, standardised 0.135.  With ``T_right3`` out, ``T_left1``'s mean error is within 0.405 and it
stays judged: the exclusion "explains the bands" and is taken at once.  Without ``T_right4``
(0.092) the same holds; without ``T_left1`` itself its coupled ``T_left3`` goes unjudged (mon84b
refuses that); without ``T_right1`` ``T_left1`` stays out (-0.406 against 0.405).  In every one
of these trial sets nobody is out of the trial set's own (mon86) bands either: the bands of the
one-more-out checks (mon86's "what remains") are not what excludes here.  The gap is the
other one the task names: a healthy sensor excluded for another's error.  ``T_right3`` is within
its band at 41 % of it, and the likelihood ratio's single fault (the largest standardised
residual, mon84) is ``T_left1``, out of band; ``_lone_fault`` asks that only where ``j`` fails
to explain the bands or hides one out of them (mon85), not where ``j`` explains them by pulling
the field round the sensor that is out.

The rule (written and committed before scoring).  In ``_lone_fault``, a culprit within its own
band whose exclusion explains the bands is not taken where the likelier single fault (the largest
standardised residual of the judged sensors) is out of band: then that one, if its own exclusion
explains them (mon84/mon84b's test, unchanged), else no exclusion yet and no new thermal state
declared (sensor -1: the judgement waits for the next sample).  Unchanged: ``j`` out of band,
``j`` within band where the likelier fault is within band too, every path where ``j`` did not
explain the bands.  Served (``judgement.py``), numpy mirror (``export/watch.py``) and C
(``watch_c.py``) alike.

Bar (written before scoring; "main": ``git archive 6fa0d518`` sources, alternated with the rule's
``git archive``; REFUSED if any part fails or is unscored by 17:50 UTC: the source reverted, the
rule kept as ``benchmarks/mon86b_rule.patch``):
1. ``trace``: no event on the healthy53 record, every served adaptive RMSE = fixed (the strict
   xfail removed, the test passing).
2. ``column`` s8703 / s8546 / s8613 healthy: every E_* served RMSE no more than main's; s8774
   frozen: ``T_front1`` first out no later than main's.
3. Fresh column_moving_source 9061-9065, healthy and frozen / jump / drift / dropout: no served
   E_* RMSE more than 2 % above main's; ``T_front1`` first out no more than 2 samples after main.
4. Trunnion 9066-9067, lathe 9068-9069, jig 9070, healthy: no event main does not have.
5. ``fl clean``: nothing out, no event after the train part; ``fl drift``: ``T_t12`` out at 10498
   as main.
6. ``ccode`` (rule) on s8774 frozen, s8703 healthy and 9061 drift: C = served to 1e-9 µm.
7. tests/apps/test_monitor*.py, tests/shell/test_monitor*.py, tests/shell/test_export*.py pass.

Scored (2026-12-04; "main": ``git archive 6fa0d518`` sources, "rule": ``git archive dc79707f``,
per seed main's run then the rule's; E_* test RMSE in µm, served adaptive)
------------------------------------------------------------------------------------------------
1. ``trace``: the rule waits at t = 63100 s (culprit ``T_right3`` -> "none yet"): nothing
   excluded, every served adaptive RMSE = fixed (E_X 0.776 -> 0.731, E_Y 6.106 -> 6.072, E_Z
   1.345 -> 1.349, as fixed).  But ``T_left1`` is then seen out of its band: one warning episode,
   ``ok -> warning`` at 63100 s (-0.41 °C, the smaller 0.4068 against 0.4052) and back at 63200 s
   (0.343): 2 events (main: 2, the exclusion and the re-admission).  The test's ``events == []``
   still fails.  Fails.
2. s8703 / s8546 / s8613 healthy: every E_* equal to 3 decimals (s8703 E_Y 15.275, s8546 16.489,
   s8613 12.352 both); s8774 frozen ``T_front1`` first out 726 -> 726.  Holds.  Where the rule
   acts: s8703 frozen and drift, ``T_right4`` (main out 731-732 as a culprit within band) stays
   in (frozen E_Z 8.855 -> 8.856, drift E_X 32.578 -> 32.577, the rest equal).
3. Fresh 9061-9065, healthy and the four faults (25 records): no E_* more than 2 % above main's
   (the largest change s9062 healthy E_Z 9.448 -> 9.449); ``T_front1`` first out at main's row on
   every one (+0: frozen 739 / 743 / 725 / 725 / 724, drift 1263 / 1084 / 1253 / 1287 / 1156,
   jump and dropout 721).  The rule acts on s9062 healthy and frozen: ``T_right4`` out 731-733 ->
   732-733 (one row later).  Holds.
4. Trunnion 9066-9067, lathe 9068-9069, jig 9070, healthy (``table /tmp/mon86b-str main
   rule``): the two jsonl byte-identical, no event on any either way.  Holds.
5. ``fl clean``: nothing out, no event after the train part; ``fl drift``: the output line for
   line main's (``T_t14`` out 10294, ``T_t12`` out 10498, ``T_t14`` back at 10498).  Holds.
6. ``ccode`` (rule): s8774 frozen 2.84e-13, s8703 healthy 2.84e-13, 9061 drift 2.84e-13 µm, and
   where the rule acts s9062 healthy 2.84e-13, s9062 frozen 3.69e-13, s8703 frozen 3.69e-13 µm;
   the code flags nothing on any.  Holds.
7. tests/apps/test_monitor*.py, tests/shell/test_monitor*.py, tests/shell/test_export*.py with
   the rule: 416 passed, 3 failed, 4 xfailed (main's four known gaps; healthy53's still xfail).
   tests/shell/test_export_mon85b.py: its record (fl_thermal, ``T_t12`` 1 K/h and ``T_t14`` 2.7
   K/h from row 240) needs the healthy ``T_t15`` taken out within its band as a culprit; the rule
   refuses that pick (the likelier fault out of band), so the branch the test covers is not
   reached.  On that record (served, rows 1-based): main ``T_t15`` out 306-316 and 317-323, then
   a new thermal state at 323 and no drift out to the end; the rule ``T_t14`` out at 313,
   ``T_t12`` out at 576, no new thermal state; served RMSE E_ch1..5 main 28.17 / 26.04 / 62.75 /
   62.35 / 17.45, rule 21.09 / 20.22 / 59.87 / 56.85 / 21.77 (fixed 28.26 / 26.29 / 62.77 /
   62.38 / 17.43: E_ch5 25 % worse than main's).  tests/apps/test_monitor_regime73.py, two: the
   Swiss lathe's healthy ``T_toolholder1`` hovering past its band (mon73's regime) is now
   excluded at 29100 s: main's pick was a culprit within its band, held by the regime check
   (``_excursion_hovers``, asked only of a culprit within band or within rounding); the rule
   hands the pick to ``T_toolholder1`` itself, out of band, whose exclusion explains the bands,
   and the regime check no longer holds it; with 1 K/h on ``T_nc_x1_drive`` ``T_toolholder1`` goes
   out first (3.9 h before the onset).  A healthy sensor excluded: the very harm the rule was to
   mend.  Fails.

CPU (user + sys of the bench process): ``column`` per seed 3.7-4.3 s main (making the records),
3.2-3.8 s rule; ``trace`` 2.5 s; ``ccode`` 2.6-2.7 s each; ``fl`` 1.3 (clean) / 1.6 (drift) s
either tree; the stranger runs 3.5-8.6 s main (making the records), 0.0 rule.

Verdict: REFUSED (part 1 fails: the healthy53 record still raises an event, a warning instead of an
exclusion; part 7 fails: a lathe's hovering healthy offset excluded, test_export_mon85b's case no
longer reaching its branch).  The source reverted, the rule kept as
``benchmarks/mon86b_rule.patch`` (served, numpy mirror and C).  What it showed: the trace's gap is
real and the rule mends that exclusion (no healthy sensor out, served RMSE = fixed on healthy53; 45
column, 5 stranger and the fl_thermal records main's or within a row; C = served where it acts),
but handing the pick to the likelier fault out of band bypasses the regime check that holds a
hovering offset (regime73): a next rule must keep that check for the sensor it hands the pick to
(or wait, never hand over).  What remains, for the lead to decide before a next rule: (a) whether a
warning that is true by the band (``T_left1`` 0.4068 against 0.4052 for 2 samples, 100 s, nothing
excluded, nothing corrected differently) breaks "quiet on healthy records": if not, the rule with
healthy53's test asserting no exclusion and RMSE = fixed; if so, the band itself (a short
training's 99.5th percentile) is the gap, and mon53/54/58/64's band changes were refused; (b)
test_export_mon85b needs another record that takes a culprit within its band out (one the rule lets
stand: the likelier fault within band too), and its two-drift record, where the rule takes both
drifts out (``T_t14`` 313, ``T_t12`` 576) instead of main's new thermal state, scored on its own
(E_ch1-4 better, E_ch5 17.45 -> 21.77 µm).
"""

from __future__ import annotations

import functools
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

import bench_mon84 as m84  # noqa: E402
import bench_mon86 as m86  # noqa: E402
from _cli import run_commands  # noqa: E402

ROOT = "/tmp/mon86b-bench"
SIM = ("sim=column_moving_source", "seed=5305", "sim.generator.q3=false",
       "sim.generator.train_hours=30", "sim.generator.test_hours=20")


def _said(mon, j, k, z, level, err) -> list[str]:
    """The lone-fault call's evidence (docstring)."""
    n, out = mon.names, np.flatnonzero(mon._judged & (level >= 1))
    lines = [f"paper 002's culprit {n[j]} (|E|(1-h) {z[j]:.3f}, error {err[j]:+.3f}, band "
             f"{mon._warn[j]:.3f}, standardised {abs(err[j]) * mon._std[j]:.3f}) -> "
             f"{n[k] if k >= 0 else 'none yet'}"]
    for i in out:
        last = mon._err[mon._recent[mon._pos, :mon.confirm], i]
        lines.append(f"  out of band {n[i]}: last {', '.join(f'{e:+.4f}' for e in last)} band "
                     f"{mon._warn[i]:.4f} h {mon._lev[i]:.3f} |E|(1-h) {z[i]:.3f} standardised "
                     f"{abs(err[i]) * mon._std[i]:.3f}")
    rows = mon._hist[mon._recent[mon._pos, :mon.confirm]]
    X = np.where(np.isfinite(rows), rows, 0.0)
    for c in np.argsort(-z)[:4]:
        trial = mon._active.copy()
        trial[c] = False
        M, lev = mon._operator(trial)
        judged = np.flatnonzero(trial & (lev < mon.pod.max_leverage))
        E = ((X[:, judged] - X[:, trial] @ M[judged].T) / (1 - lev[judged])).mean(axis=0)
        own = mon._bands_of(trial, M, lev[trial])[0]
        lines.append(f"  without {n[c]}: out of the active band "
                     f"{[n[i] for i, e in zip(judged, E) if abs(e) >= mon._warn[i]]}, of its own "
                     f"set's {[n[i] for i, e in zip(judged, E) if abs(e) >= own[i]]}; unjudged "
                     f"{[n[i] for i in np.flatnonzero(trial) if i not in judged]}")
    return lines


def trace(root: str = ROOT) -> None:
    from conftest import FAST, thermocomp
    from thermocomp.apps.deploy.surveillance.judgement import Judgement

    data, out = Path(root) / "column53", Path(root) / "trace-mon"
    if not (data / "campaigns.csv").exists():
        thermocomp("simulate", *SIM, f"data.path={data}", *FAST)
    picks, log = Judgement._lone_fault, []

    def lone(self, j, z, level, err):
        k, resolves = picks(self, j, z, level, err)
        log.extend(_said(self, j, k, z, level, err))
        return k, resolves

    Judgement._lone_fault = lone
    try:
        thermocomp("monitor", f"data.path={data}", "sim=column_moving_source", f"out={out}", *FAST)
    finally:
        Judgement._lone_fault = picks
    say = functools.partial(print, flush=True)
    for line in log:
        say(line)
    report = json.loads((out / "monitor.json").read_text())
    for e in report["events"]:
        say(f"event {e['time']:.0f}: {e['sensor']} {e['from']} -> {e['to']}: {e['reason'][:100]}")
    say("served E_* RMSE fixed -> adaptive: " + ", ".join(
        f"{t} {r['rmse_fixed']:.3f} -> {r['rmse_adaptive']:.3f}"
        for t, r in report["targets"].items()))


def fl(case: str = "drift") -> None:
    m86.trace(case)


def column(root: str, label: str, seeds: str = "9061-9065", kinds: str = m84.KINDS) -> None:
    m84.column(root, label, seeds, kinds)


def ctable(root: str, main: str, rule: str) -> None:
    m84.ctable(root, main, rule)


def ccode(root: str = ROOT, seed: str = "8774", kind: str = "frozen") -> None:
    m84.ccode(root, seed, kind)


def trunnion(root: str, label: str, seeds: str = "9066-9067", kinds: str = m84.KINDS) -> None:
    m84.trunnion(root, label, seeds, kinds)


def lathe(root: str, label: str, seeds: str = "9068-9069", kinds: str = m84.KINDS) -> None:
    m84.lathe(root, label, seeds, kinds)


def jig(root: str, label: str, seeds: str = "9070", kinds: str = m84.KINDS) -> None:
    m84.jig(root, label, seeds, kinds)


def table(root: str, main: str, rule: str) -> None:
    m84.table(root, main, rule)


def main(argv: list[str] | None = None) -> int:
    np.seterr(all="ignore")
    return run_commands(__doc__, {"trace": trace, "fl": fl, "column": column, "ctable": ctable,
                                  "ccode": ccode, "trunnion": trunnion, "lathe": lathe,
                                  "jig": jig, "table": table},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
