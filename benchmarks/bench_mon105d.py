"""mon105c's held value for a frozen sensor in the exported code too: the mirror
(:class:`~thermocomp.apps.deploy.export.watch.CodeMonitor`) and the C (``watch_c``) read a
sensor out for a freeze by its run alone at its held value while the rate fitted to its own
readings over the ``EXCURSION_TAU_S`` before its run projects a drift within the stand-in's
training spread, as the served ``SensorMonitor`` does since mon105c (issue 34; stop 105, mon105d).

What the code carries: ``spread`` (floor_c / SPREAD_FACTOR per sensor) in compensator.json's
monitor (an export before it: 0, the stand-in, as before); the last ``TREND_ROWS`` referenced
rows and their times in the monitor's state (``tc_state``, so the ``--state`` file); at the
freeze exclusion the time until which the held value is read (``hold_to``); the model reads
``last`` (the held reading) instead of the stand-in while froze, not off, and now <= hold_to.
The monitor's time is the time rule's ``now`` (the served monitor's raw time, the same but for a
missing or restarted time).

Usage (``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_mon105d.py agree ROOT RECORD [RECORD ...]

``agree``: per record (made into ROOT as bench_mon105c's, the same ``mlr-none`` cells) and per
bench_mon105c's frozen sensor (bench_cmon92's ``planted`` freeze from a quarter in), the served
corrections, the mirror's (``Simulator``) and the C's (compiled, the whole campaign streamed),
and the largest |served - mirror| and |served - C| over the campaign (µm); and the mirror's
flags over the healthy frame.

BAR (written and committed BEFORE the mirror / C were changed or measured; mon105c's served
numbers stand and are not re-scored)
---
D1. served = mirror = C within 1e-9 µm on every row of mon105c's frozen cases (cr9763 T_amb,
    T_headstock; sw9776 T_amb, T_headstock; lr9376 T_head_left) and on the export check pack's
    planted freeze (K09.freeze.T_b followed to its end: no part where served holds).
D2. tests/shell/test_export_inputs_product62.py and test_export_atiprod65.py: 7 checked cases
    again (pass).
D3. every tests/shell/test_export_* module that imports watch / watch_c passes (a state size or
    the ST's PARSED_DIGEST updated only with the reason said).
D4. healthy frames: 0 flags from the code's monitor (mirror) on the records above.
D5. the ST: said whether it serves the stand-in or the held value; if the stand-in, not_in_code
    / docs say so.
KEPT if D1-D5 hold; else TRACED / REFUSED as the brief says. The C's state growth (bytes) reported.
"""
