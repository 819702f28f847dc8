"""Deployed = scored at the seams no bench checked yet (stop 107, dep107; issue 34).

Four seams (the brief's):
1. ``stream.c --state``: the state saved after a refused row (a bad value / a row written again /
   a time set back) read back by a fresh process goes on as the uninterrupted stream does, and as
   the served session does after the same row;
2. ``connect`` (OPC UA) with a plain model (``monitor.adaptive=false``) fed a missing value (a
   bad-status node, NaN): what it answers against served and the C;
3. a chained file's first row read as a jump (pt10044: W3 fed after W2, ``data.reference`` none):
   the jump or a new campaign, decided from the data contract (docs/data-format.md);
4. a blank line mid-file: ``stream.c`` restarts a campaign there; do served (``monitor.input=-``)
   and ``replay`` read the same file the same way?

BAR (written and committed BEFORE any seed of 10130-10132 is built; not to move after):
  B1. every seam answered with a measured number: |C - served| (and |C cut by --state - C
      uninterrupted|) in um for 1, 2, 4; |replay - run| (the test RMSE, um) and |C - served| for 3.
  B2. every break found is mended (a failing cheap test in the module of the code it concerns,
      the mend, the test passing; a refusal with file / column / row and exit 2 where refusing
      is the right mend) or named as left, with the reason.
  B3. the seeds, kinds chosen now: 10130 a portal mill's weekly files (bench_audit98's PORTAL,
      ``seed=10130``, as pt10044; seam 3), 10131 and 10132 a lab's export as bench_audit106's
      cell L writes it (``write_export``, as dep106b's 10118; seams 1, 2, 4).  Scored once.
  Verdict: KEPT where B1 and B2 hold with a src change; TRACED where nothing breaks.
"""
