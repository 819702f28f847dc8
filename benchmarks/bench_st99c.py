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

Seen, traced (2026-12-06, this tree = 90cf3c74's block; ``trace /tmp/st99c/seen lr9896``): the
block's judgement stops at lead-in row 1867 (``mon_stop_row`` 1868), where the C's drift judgement
with every sensor in reaches the band (T_head_left), no blind sensor explaining it: lone fault
T_head_left, resolves, 2 others beyond their warning band >= ``new_state_others`` 2: the C's veto,
nothing excluded, ``novel`` False, no sensor out, its state as before.  The block ends its
``BLIND_OUT`` judgement there for the campaign (st96's "a drift judgement it cannot follow",
st97d's ``mon_stop``) and never judges again; the C judges on: a new thermal state at 2900 (flags
72), its end, then at 3686 the ``BLIND_OUT`` of the bumped T_spindle_front the block cannot name.
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


def trace(root: str, *records: str) -> None:
    """The ``trace`` lines (module doc)."""
    from test_export_st96 import bumped
    from thermocomp.apps.deploy.export.watch import BLIND_OUT

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
                    stop = (i, int(v["mon_stop_row"]), _outcome(log, names))
                elif stop and any(name == "_explaining" for name, _ in log):    # (a drift judgement)
                    kind = _outcome(log, names).split(" (")[0]
                    after.setdefault(kind, []).append(i)
                at_start = copy.deepcopy(three) if i == start - 1 else at_start
                log.clear()
            print(f"{record} {cid}: {len(frame)} fed rows ({lead} lead-in), onset {start}, diff rows {diff}",
                  flush=True)
            print(f"  stop: {'row %d (mon_stop_row %d), the C: %s' % stop if stop else 'never'}")
            print("  after: " + ("; ".join(f"{k} {len(r)} (first {r[0]})" for k, r in after.items()) or "-"))
            lost = bool(at_start.fb.vars["mon_blind_lost"]) if at_start else None
            for sensor in [n for n, p in zip(names, ss.monitor["predictable"]) if not p]:
                df, end = bumped(frame, sensor, start)
                three, c, st = copy.deepcopy(at_start), None, None
                for i, ((_, _, (flag, rule, k), (_, crule, ck), _), _) in enumerate(
                        three.rows(df.iloc[start:end + 31]), start):
                    c = c or ((i, names[ck]) if crule == BLIND_OUT else None)
                    st = st or ((i, names[k]) if flag and rule == BLIND_OUT else None)
                    log.clear()
                print(f"  planted {sensor} +6 C: C BLIND_OUT {c or '-'}, ST {st or '-'} "
                      f"(stopped before: {lost})", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
