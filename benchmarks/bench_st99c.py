"""Why the ST block misses the C's ``BLIND_OUT`` of T_spindle_front on lr9896 (st99c, issue 34).

st99b (bench_st99b.py, traced after its score) found on lr9896 (bench_cmon91's lr generator, seed
9896): test_export_st96's bump (+6 °C over 20 rows, held 30, down over 20) of T_spindle_front
from the campaign's onset (row 3673) taken out by the C as a ``BLIND_OUT`` at row 3686, back at
3741, while the block (st_watch.py) and main stay silent.

No rule here: a trace (the verdict TRACED).  ``trace`` steps the block, the BASE block (90cf3c74's
st_watch.py, bench_st97d's ``base_block``) and the C's numpy mirror together over a record's first
test campaign's fed frame (bench_cmon92's ``faulted_cell``, its lead-in with it), the C's drift
path logged (:class:`Logged`), and prints:

* ``stop``: the row the block's ``BLIND_OUT`` judgement ends for the campaign (``mon_stop``;
  ``mon_blind_lost`` TRUE from there) and what the C did on that row: its drift judgement with
  every sensor in reached the band and no sensor no other predicts explained it (``_explaining``
  None), then its lone fault (``_lone_fault``: sensor, resolves), ``_others`` against
  ``new_state_others`` (a veto: nothing excluded, the C's state unchanged), a new thermal state
  declared (``_declare``), a ``DRIFT_OUT`` (``_exclude``);
* ``after``: the C's drift outcomes on the healthy frame from the stop on (veto / new state /
  DRIFT_OUT / BLIND_OUT rows), the block silent on each (it judges no drift there);
* ``planted``: each sensor no other predicts (``predictable`` false) bumped as
  tests/shell/test_export_st96.py bumps (``bumped``, +6 °C) from the onset, from the state there:
  the C's first ``BLIND_OUT`` (row, sensor) to the bump's end + 30 rows and the block's (row; ``-``:
  silent), whether the block had stopped before the onset.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st99c.py trace ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (each once); RECORD any of
bench_st99b's (seen: lr9893 ... dl9897, st98's) or :data:`FRESH` (lr9904 dl9905 cr9906: bench_cmon91's
lr / dl / cr generators on seeds 9904-9906).

BAR (the brief's, for a rule: lr9896 ST = C on the BLIND_OUT; fresh 9904-9906: the ST names >= 90 %
of the C's BLIND_OUTs, false 0, healthy diff rows 0; st99b / st98 / st97d lines unchanged).  No rule
is built (below: the mend is not small), so the bar is not scored; the fresh lines are main's
share, measured once after this docstring's commit, the baseline for a next rule.

Measured (2026-12-06, 2 cores shared by up to 8 helpers; this tree's block = 90cf3c74's, diff rows
0 on every frame).  Fresh, once, after this docstring's bar (commit 2ed6d191; ``trace
/tmp/st99c/fresh lr9904 dl9905 cr9906``, 31.8 s CPU, the making included; the stop line's warning
count and the "C's first" note were added after it, on seen records only): no stop on any;
the C's BLIND_OUT in 3 planted cases, all dl9905 (6134 T_spindle_front, 6132 T_motor, 6129
T_spindle_front for T_table's bump), the block naming each on the same row and sensor (3 of 3,
main; the brief's fresh clause is met by main, the records cannot tell a rule from it).

Seen (``trace /tmp/st99c/seen lr9896 lr9893 dl9894 cr9895 dl9897``, 58.0 s CPU; ``trace
/tmp/st99c/st97d lr9823 dl9821``, 25.5 s; copies of st99b's and st97d's records)::

    record  stop (0-based row), the C there          warned  C BLIND_OUT planted   ST names
    lr9896  1867: veto (lone T_head_left, 2 others)   3       3                     0
    lr9823  379: new thermal state                    3       2                     0
    dl9821  4543: new thermal state                   1       0                     -
    lr9893  never                                     -       3                     3
    dl9894  never                                     -       3                     2
    dl9897  never                                     -       3                     3
    cr9895  never                                     -       0                     -

(warned: judged sensors at their warning band on the stop's row; ``new_state_others`` 2.)  Of 14
seen BLIND_OUTs the block names 8, each on the C's row and sensor.  The 6 missed: 4 after the
stop alone (lr9896 T_spindle_front and T_motor at 3686; lr9823 T_spindle_front 3690, T_table
3684); 2 after the C's JUMP of the bumped T_table (lr9896 3681, dl9894 6131), the C's BLIND_OUT
following its BACK (3698, 6142): the block's ``mon_lost`` TRUE there (dl9894: it names the JUMP
at 6131 and its judgement ends, st94b's documented end), another class than lr9896's.

The place.  lr9896: the C's drift judgement (watch.py ``_drift``) with every sensor in reaches
the band at 1867 (T_head_left), no blind sensor explaining it; its lone fault T_head_left
resolves, and 2 other judged sensors are beyond their warning band (``_others`` >=
``new_state_others``, watch.py line 1367): the veto, nothing excluded, ``novel`` False, no sensor
out.  The block (st_watch.py ``BLOCK``, the ``mb = MON_BLINDS`` branch, line 862: ``mon_reach AND
mon_take_set < 0``) cannot tell that veto from the C's new thermal state or ``DRIFT_OUT`` and sets
``mon_blind_lost`` (st96's rule, st97d's ``mon_stop``); line 853 (``mon_judge := ... NOT
mon_blind_lost``) never judges a BLIND_OUT again that campaign.  The C judges on: a new state at
2900 (ended 2910), STEP_OUT / BACK at 2702 / 2714 and 3248 / 3259 (the block names each STEP_OUT),
then the BLIND_OUT at 3686.

Not mended (TRACED).  Following the C past that row needs its outcome: veto (state unchanged),
new thermal state (no drift exclusion until a window with every judged sensor within its warning
band, ``_follow_field``) or ``DRIFT_OUT``.  Telling them apart is ``_lone_fault`` / ``_resolves``
(an operator with each judged sensor out) and ``_hovers`` (the field's memory): not small.  A
narrower next rule: where at least ``new_state_others`` + 1 judged sensors are at their warning
band (lr9896 3, lr9823 3; not dl9821's 1), no ``DRIFT_OUT`` can follow whatever the culprit, only
a veto or a new state: the block could pause to a window with none at its warning band (the C's
end of a new state) and judge on; a reach in the pause still ends it.  That moves st97d's
``mon_stop`` rows (lr9823 380) by design: a next stop's own bar.
"""

from __future__ import annotations

import contextlib
import copy
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st98  # noqa: E402
import bench_st99b  # noqa: E402
from _cli import run_commands  # noqa: E402

BASE = "90cf3c74"
DRIFT_PATH = ("_explaining", "_lone_fault", "_others", "_declare", "_exclude", "_blind_out")


def generators() -> dict:
    """Every record's simulate words: :data:`FRESH` and bench_st99b's."""
    return {**bench_st99b.generators(), **FRESH}


def _fresh() -> dict:
    from bench_st97b import CMON91_FRESH

    return {f"{record[:2]}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
            for (record, words), seed in zip(list(CMON91_FRESH.items())[:3], range(9904, 9907))}


FRESH = _fresh()     # lr9904, dl9905, cr9906 (chosen before any was simulated)


@contextlib.contextmanager
def Logged(log: list):
    """The C mirror's drift path (:data:`DRIFT_PATH`, CodeMonitor methods) appending ``(name,
    result)`` to ``log`` while in the block (class-level: deep copies log too)."""
    from thermocomp.apps.deploy.export.watch import CodeMonitor

    saved = {name: CodeMonitor.__dict__[name] for name in DRIFT_PATH}

    def logged(name, f):
        def call(*a, **k):
            got = f(*a, **k)
            log.append((name, got))
            return got
        return call
    for name, f in saved.items():     # (a staticmethod kept one: ``_others``)
        plain = f.__func__ if isinstance(f, staticmethod) else f
        setattr(CodeMonitor, name, staticmethod(logged(name, plain)) if plain is not f else logged(name, f))
    try:
        yield log
    finally:
        for name, f in saved.items():
            setattr(CodeMonitor, name, f)


def _outcome(log: list, names) -> str:
    """What the C's drift path did on a row, from its ``log``."""
    said = dict(log)
    if "_blind_out" in said:
        return "BLIND_OUT"
    if "_declare" in said:
        return "new state"
    if said.get("_exclude"):
        return "DRIFT_OUT"
    if "_lone_fault" in said:
        j, resolves = said["_lone_fault"]
        tail = f", {said['_others']} others >= new_state_others" if "_others" in said else ""
        return f"veto (lone {names[j] if j >= 0 else '-'}, resolves {resolves}{tail})"
    return "none"


def _warned(watch) -> tuple[int, int]:
    """The judged sensors at their warning band on the C's row (its ``_judge``), and
    ``new_state_others``: at least one more than it, the C's ``_others`` veto holds whatever its
    culprit, no ``DRIFT_OUT`` (a veto or a new thermal state only)."""
    from thermocomp.apps.deploy.export.watch import WARNING

    level, _ = watch._judge()
    return int((watch._judging() & (level >= WARNING)).sum()), int(watch.a["new_state_others"])


def trace(root: str, *records: str) -> None:
    """The ``trace`` lines (module doc)."""
    from test_export_st96 import bumped
    from thermocomp.apps.deploy.export.watch import BLIND_OUT, RULES

    base_root = Path(root).resolve()
    for record in records:
        made = bench_st98.cell(base_root, record, generators(), BASE)
        ss, frame, lead, start, cid, names, block, base = made
        frame = frame.reset_index(drop=True)
        log: list = []
        with Logged(log):
            three = bench_st98.Three(ss, block, base)
            stop, after, at_start, diff = None, {}, None, 0
            for i, (_, (differs, _)) in enumerate(three.rows(frame)):
                diff += differs
                v = three.fb.vars
                if v["mon_stop"]:
                    stop = (i, int(v["mon_stop_row"]), _outcome(log, names), *_warned(three.sim.watch))
                elif stop and any(name == "_explaining" for name, _ in log):    # (a drift judgement)
                    kind = _outcome(log, names).split(" (")[0]
                    after.setdefault(kind, []).append(i)
                at_start = copy.deepcopy(three) if i == start - 1 else at_start
                log.clear()
            print(f"{record} {cid}: {len(frame)} fed rows ({lead} lead-in), onset {start}, diff rows {diff}",
                  flush=True)
            said = "row %d (mon_stop_row %d), the C: %s; at their warning band %d (new_state_others %d)"
            print(f"  stop: {said % stop if stop else 'never'}")
            print("  after: " + ("; ".join(f"{k} {len(r)} (first {r[0]})" for k, r in after.items()) or "-"))
            lost = bool(at_start.fb.vars["mon_blind_lost"]) if at_start else None
            for sensor in [n for n, p in zip(names, ss.monitor["predictable"]) if not p]:
                df, end = bumped(frame, sensor, start)
                three, c, st, first, lost_at = copy.deepcopy(at_start), None, None, None, None
                for i, ((_, _, (flag, rule, k), (_, crule, ck), _), _) in enumerate(
                        three.rows(df.iloc[start:end + 31]), start):
                    first = first or ((i, RULES[crule]) if crule else None)
                    if c is None and crule == BLIND_OUT:
                        c, lost_at = (i, names[ck]), bool(three.fb.vars["mon_lost"])
                    st = st or ((i, names[k]) if flag and rule == BLIND_OUT else None)
                    log.clear()
                after_other = c and first != (c[0], "BLIND_OUT")     # (the C's first event another)
                before = f", the C's first {first}, ST mon_lost {lost_at}" if after_other else ""
                print(f"  planted {sensor} +6 C: C BLIND_OUT {c or '-'}, ST {st or '-'} "
                      f"(stopped before: {lost}{before})", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
