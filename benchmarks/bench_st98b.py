"""The Structured Text block names a freeze after its own earlier flag (st98b, issue 34; st98's
``ended`` cases: 42 seen frozen sensors of lr9790 / dl9791 / dl9794 the C names FREEZE where the
block's judgement had ended at its own earlier JUMP / STEP_OUT, ``mon_lost``, and stayed silent).

The rule (st_watch.py ``BLOCK``; no key, on with ``MON_STEP_JUDGE``): the C's two run rules,
written once for every path -- per monitored sensor ``mon_fpast`` (its run of equal in-range
readings ``mon_frun`` past ``MON_DITHER_RUN``, or, one no other predicts, past
``MON_BLIND_RUN``) and ``mon_fnew`` (the run's first sample past them).  st98's path (field
whole, none held) reads ``mon_fpast`` with the field's rule (``MON_SEEN_RUN`` and the others'
prediction moved by ``MON_WARN``), as before.  After the block's judgement ended
(``mon_lost``) and no rule named the sample, the first sensor with ``mon_fnew`` that the block
does not hold re-referenced out (``mon_out``) is flagged ``FREEZE`` (``BLIND`` where the C does
not hold it out, ``MON_FREEZE_HELD``), once a run.  The field's rule is not judged there (it
needs the set the C judges, which the block does not follow).  This is
benchmarks/st98_after_lost.patch made one mechanism with st98's path (the patch wrote the run
rules a second time, and fired twice a run for a sensor no other predicts with both runs finite).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the block measured is that tree's;
BASE is 289e984a's st_watch.py ``OUTPUTS`` / ``BLOCK``, bench_st97d's ``base_block``)::

    python benchmarks/bench_st98b.py cases ROOT RECORD [RECORD ...]

``cases``: per record (:data:`FRESH`, or any of bench_st98's; made into ``ROOT`` by bench_cmon92's
``made``, each once) its first test campaign's fed frame (bench_cmon92's ``faulted_cell``), the
block, the BASE block and the C's numpy mirror stepped together.  ``healthy``: the whole frame,
``diff rows`` (``c``, ``n_clamped``, ``refused``, ``mon_flag``, ``mon_rule`` or ``mon_sensor``
differing from BASE's, bit for bit) and the block's FREEZE rows.  ``after``: a first fault the
block flags -- bench_cmon92's spike (+5 C for 10 rows, then back) on the first monitored sensor
the others predict (``A``), planted 20 rows before the onset -- then from the onset each other
monitored sensor frozen in turn (bench_cmon92's ``planted`` freeze, 60 rows held, 60 past), from
the state at the onset (``mon_lost`` there said).  Per case: the C's first FREEZE / BLIND (row
from the onset, rule, sensor), the block's first FREEZE / BLIND and BASE's; the class ``agree``
(the same row, rule and sensor), ``mismatch`` (a C FREEZE / BLIND not so named), ``false`` (a
block FREEZE / BLIND with no C one at or before its row), ``none`` (neither); ``diff rows``
(outputs differing from BASE's) on rows other than the block's FREEZE / BLIND row.

Records.  SEEN (spent): lr9790, dl9791, dl9794 (bench_st97d's; the 42 ``ended``), bench_st98's
SEEN / FRESH.  FRESH (never simulated before this bar): lr9865, dl9866, cr9867, lr9868, dl9869
(bench_st97b's generators, cmon91's kinds, with these seeds).

Seen, traced before the bar (this tree's block; copies of st98's records in /tmp/st98b/seen):
``bench_st98.py cases`` lr9790 / dl9791: 14 + 14 of st98's ``ended`` cases now ``agree`` (FREEZE
at the C's row 10-11), healthy diff rows 0 (dl9794 still running at the bar's commit).
This bench's ``cases`` on lr9790 (T_head_left spiked at 3653, lost at onset): 13 agree, diff
rows 0 (23.6 s CPU).  lr9132 (tests/shell/test_export_st94.py's fixture), its first sensor the
others predict spiked 20 rows before START, then its first dithered sensor the others predict
frozen: the C names FREEZE
at row 10 by the field's rule (``seen_run`` 3, the prediction moved), the block at row 11 by
the run rule (``dither_run`` 10): a ``mismatch`` the rule cannot reach (the field's rule after
the block's judgement ended needs the C's set).  The test uses a sensor no other predicts.

BAR (written and committed BEFORE any of 9865-9869 was simulated; scored once, this tree's block)
---
1. After the block's own flag, every fresh record: every ``after`` case whose C names a FREEZE
   or BLIND is named by the block at that row with that rule and sensor (``agree``);
   ``mismatch`` 0; ``false`` 0; ``diff rows`` 0 on the rows other than the named one.
   ``mon_lost`` TRUE at every record's onset (the spike flagged first), else the record is
   reported as not testing the rule.
2. Healthy, every fresh record: 0 diff rows against BASE over the whole fed frame; no block
   FREEZE row.
3. The existing tables elsewhere unchanged: ``bench_st98.py cases`` on its sw9853 and cr9854
   (now seen) prints its docstring's lines (healthy diff 0 against its 16d3b58d, 12 agree each);
   on bench_st97d's lr9790 / dl9791 / dl9794 the 42 ``ended`` cases become ``agree`` (FREEZE at
   the C's row), healthy diff rows 0; ``bench_st97d.py cases`` on lr9790 / dl9791 / dl9794
   prints its a/m/o/n (2/4/0/14, 3/7/3/7, 1/4/0/11) with 0 diff rows and 0 mon_stop rows.
KEPT if 1-3 hold (with a test failing on 289e984a, PARSED_DIGEST, docs); REFUSED otherwise
(benchmarks/st98b_rule.patch, src as on 289e984a).

Scored (2026-12-06, 2 cores shared by up to 8 helpers, load 10-11; the bar and the rule unchanged
since their commit f232b458, the fresh records simulated after it by this bench, ``cases
/tmp/st98b/fresh lr9865 cr9867 lr9868`` and ``... dl9866 dl9869`` in two processes, once; 48.9 +
80.8 s CPU, the making included)::

    record  test  rows (lead-in)  healthy diff rows  spiked (row)          after cases  diff rows
    lr9865  R1b   4321 (3457)     0                  T_head_left (3653)    13 agree     0
    dl9866  R1b   7200 (5760)     0                  T_head_left (6100)    13 agree     0
    cr9867  C10   205 (0)         0                  T_amb (31)            11 agree     0
    lr9868  R1b   4321 (3457)     0                  T_head_left (3653)    13 agree     0
    dl9869  R1b   7200 (5760)     0                  T_head_right (6100)   13 agree     0

1 MET: 63 of 63 cases agree (the C's FREEZE, every one held, named at its row and sensor: row 11
from the onset on 56, row 10 on 7), mismatch 0, false 0, diff rows besides the
named 0; ``mon_lost`` TRUE at every onset.  BASE: no FREEZE in any case.  2 MET: 0 diff rows on
the five healthy frames, no block FREEZE row.  3 MET: ``bench_st98.py cases`` sw9853 / cr9854
(10.6 s CPU): its 28 lines identical to st98's scoring run (12 agree each, healthy diff 0);
lr9790 / dl9791 / dl9794 (51.7 s CPU): the 42 ``ended`` now 42 ``agree`` (FREEZE at the C's row
10-11), healthy diff rows 0; ``bench_st97d.py cases`` on them (48.8 s CPU): 2/4/0/14, 3/7/3/7,
1/4/0/11 (a/m/o/n), 0 diff rows, 0 mon_stop rows.  VERDICT: KEPT.

Not reached (seen, before the bar): a sensor the others predict that the C names frozen by the
field's rule before its run passes (lr9132's dithered case: C row 10, block row 11); on the five
fresh records no C freeze came by that rule in these cases.
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st98  # noqa: E402
from _cli import run_commands  # noqa: E402

BASE = "289e984a"
LEAD = 20                  # rows before the onset the spike starts (back 10 rows before it)


def generators() -> dict:
    """Every record's simulate words: :data:`FRESH` and bench_st98's."""
    from bench_st97b import CMON91_FRESH

    fresh = {f"{record[:2]}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
             for (record, words), seed in zip(CMON91_FRESH.items(), range(9865, 9870))}
    return {**bench_st98.generators(), **fresh}


def _freezes(rows) -> dict:
    """``rows`` (:meth:`bench_st98.Three.rows`'s): the C's, the block's and BASE's first FREEZE /
    BLIND (row, rule, sensor), and the rows differing from BASE's other than the block's."""
    from thermocomp.apps.deploy.export.watch import BLIND, FREEZE

    out = {"c": None, "st": None, "base": None, "rows": 0}
    for i, ((_, _, (flag, rule, sensor), (bits, crule, csensor), _), (differs, b)) in enumerate(rows):
        st_named = flag and rule in (FREEZE, BLIND)
        if out["c"] is None and bits and crule in (FREEZE, BLIND):
            out["c"] = (i, crule, csensor)
        if out["st"] is None and st_named:
            out["st"] = (i, rule, sensor)
        if out["base"] is None and b[0] and b[1] in (FREEZE, BLIND):
            out["base"] = (i, b[1], b[2])
        out["rows"] += differs and not st_named
    return out


def cases(root: str, *records: str) -> None:
    """The ``cases`` lines (module doc)."""
    from bench_cmon92 import SPIKE_C, SPIKE_ROWS, planted

    from thermocomp.apps.deploy.export.watch import FREEZE

    base_root = Path(root).resolve()
    for record in records:
        made = bench_st98.cell(base_root, record, generators(), BASE)
        ss, frame, lead, start, cid, names, block, base = made
        three = bench_st98.Three(ss, block, base)
        healthy = list(three.rows(frame))
        st_freeze = [i for i, (got, _) in enumerate(healthy) if got[2][1] == FREEZE]
        spiked = names[list(ss.monitor["predictable"]).index(True)]
        head = frame.iloc[:start].copy()
        col = head.columns.get_loc(spiked)
        head.iloc[start - LEAD:start - LEAD + SPIKE_ROWS, col] += SPIKE_C
        three = bench_st98.Three(ss, block, base)
        list(three.rows(head))
        lost = bool(three.fb.vars["mon_lost"])
        print(f"{record} {cid}: {len(frame)} fed rows ({lead} lead-in), onset {start}; healthy: diff rows "
              f"{sum(d for _, (d, _) in healthy)}, ST FREEZE rows {st_freeze or '-'}; after: {spiked} "
              f"spiked at {start - LEAD}, block lost at onset {lost}", flush=True)
        tally, rows = {}, 0
        for sensor in [n for n in names if n != spiked]:
            run = copy.deepcopy(three)
            got = _freezes(list(run.rows(planted(frame, start, (sensor,), "freeze"))))
            kind = bench_st98._kind(got)    # (never other: the C's first FREEZE / BLIND)
            tally[kind] = tally.get(kind, 0) + 1
            rows += got["rows"]
            print(f"  frozen {sensor:<20} C {bench_st98._said(got['c'], names):<28} ST "
                  f"{bench_st98._said(got['st'], names):<28} BASE {bench_st98._said(got['base'], names):<28} "
                  f"{kind:<8} diff rows {got['rows']}", flush=True)
        print(f"  {record} after: {tally}; diff rows besides the named {rows}", flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"cases": cases}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
