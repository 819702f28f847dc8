"""What dep107 left at the deployed seams (stop 107, dep107b; issue 34).

Three seams dep107 (bench_dep107.py) named and left:
1. ``stream.c --state`` with a time-of-day clock (TC_DAY_SECONDS): the days added so far
   (``day_added``) are not in the state file.  A stream cut after midnight and restarted from its
   state against the uninterrupted stream and the served session.
2. a stray blank line within a run: stream.c restarts a campaign there (said), served's stdin
   (``monitor.input=-``) and replay's file read ignore it (dep107: 28.6 / 32.6 um off after it).
   One rule for the three readers, from the data contract (docs/data-format.md,
   docs/to-the-machine.md's rows).
3. connect's offset rate limiter on a plain model, where served and the C apply none (dep107:
   10131 rows 998-1000, 0.316 um): on how many rows it binds on the lab records.

BAR (committed before anything new is run; not to move after):
  B1. item 1: on day-clock records (tests/shell/test_export_day_seconds91's: seconds of day, runs
      across a pause over midnight; h:mm:ss, one run over midnight) the C cut by ``--state`` at
      every data row after midnight against the C uninterrupted: max |difference| (um) over the
      rows after the cut; and against the served session.  A difference > 1e-9 um is a break:
      mended (a failing cheap test, the mend; old state files refused or read as today).
  B2. item 2: one rule for the three readers, decided from the data contract; after it the C and
      served's stdin agree on the 10118 / 10131 cases (a stray blank line at data row 450, and
      ``thermocomp rows``' two campaigns) to <= 1e-9 um, and replay reads the file as they do (or
      the part that cannot agree named with the reason and a measured number).
  B3. item 3: the rows on which connect's limiter binds (plain model) on lab 10118, 10131, 10132,
      counted; the decision (a named machine-side safety in the docs, or removed) from the docs'
      account of the limiter.
  B4. neighbours (dep107's 73 modules: stdin, monitor.input=-, connect) pass; ruff clean.
  Seeds: none new (10118, 10131, 10132 seen: dep107's roots in /tmp/dep107/roots reused).
  Verdict: KEPT where B1-B4 hold with a src change; TRACED where nothing breaks.
"""
