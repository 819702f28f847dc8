"""The ST names every row of a campaign whose first sample had a monitored reading out of range
(st108d, issue 34 "deployed as scored").

dep108 / dep108f (bench_dep108, bench_dep108f) made the C start such a sensor from the monitor's
``first_c`` and reference it late on its return; the ST block (st_watch.py) does neither: on
bench_dep108f's seen ``back`` case (T_amb +30 on rows 0-39) it flags RANGE and refuses rows 0-39,
then says nothing on rows 40-119 while 4.3-8.0 um off the C.

RULE (st_watch.py, no key, no constant): the block's own range test at a campaign's first sample
(any monitored reading measured and beyond ``MON_LO_LIM`` / ``MON_HI_LIM``, whatever rule the row
names first) sets ``mon_rfirst``, kept to the campaign's end; ``mon_unsure`` is TRUE on every row
while it is set.  The numbers (c) and (mon_flag, mon_rule, mon_sensor) are not touched.

BAR (committed before the rule is scored; not moved after).  Tree = this branch's block, BASE =
ab96d05d's (``git archive`` src).  A row is *flagged* where ``mon_flag``, ``mon_unsure`` or
``refused`` is TRUE; *differs* where max |ST - C| > 1e-9 um (C = the JSON mirror ``Simulator``,
equal to the C to 1e-9 um on these cases per dep108 / dep108f).
* S1 on bench_dep108's root (/tmp/dep108/droot, its data), T_amb ``back`` +30 (dep108f's seen
  case) and ``all`` +30 (dep108's): every differing row flagged (BASE: 320 unflagged on ``back``).
* S2 bench_st108b's 8 healthy streams (lr/dl 9964-9967, st108b's root): 0 rows whose
  ``mon_unsure`` differs from BASE (none has a reading out of range at its first sample).
* S3 c and (mon_flag, mon_rule, mon_sensor) identical to BASE on every S1 / S2 row.
* S4 PARSED_DIGEST updated (blark parses), test_export_st97d / test_export.py / the ST modules
  pass; a test (<= ~2 s CPU, test_export_lean107b's room fixture) failing on BASE; one docs line.
* KEPT where S1-S4 hold; else REFUSED.  Porting MON_FIRST_C (numbers agree) only if time is left.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st108d.py score ROOT DATA OUT
"""
