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

Measured (2026-12-07; ``agree`` on mon105c's ROOT, its models fitted once by main's src; this
branch's src; 11 records 42.8 + 1.4 s CPU, the C builds included).  max |served - mirror| /
max |served - C| over the campaign (µm), rows where the mirror reads a held value::

    cr9763  T_amb 0 / 2.1e-14, 49 held    T_headstock 2.8e-14 / 3.4e-14, 0
    sw9776  T_amb 0 / 2.8e-14, 50 held    T_headstock 0 / 2.8e-14, 0
    lr9376  T_head_left 0 / 1.6e-13, 0
    spent and fresh (sw9815 cr9816 lr9817 sw9818 cr9819 cr10038 sw10039 lr10040; 14 cases):
            all <= 1.0e-13; held rows 43-50 on each record's ambient or first sensor (lr9817
            T_spindle_rear 49, lr10040 T_head_right 43), 0 on cr9819 (its past moved) and on
            every T_headstock

D1 met (worst 1.6e-13 µm; the pack's K09.freeze.T_b: test_export_inputs_product62 and
test_export_atiprod65 pass, 7 cases each: D2).  D3: the 45 test_export_* modules importing watch
105 passed; 29 more exercising the pack / Simulator 213 passed (test_export's PARSED_DIGEST
unchanged: the ST is not touched).  D4: healthy frames 0 flagged rows on the cr / sw records; lr9376
(35 rows), lr9817 (58) and lr10040 (13) flag rows (sensors excluded and re-admitted on the
healthy frame) on ecd7ec36's src alike (each measured on both): the bar's wording missed them; the
change adds none.  D5: the ST holds no stand-in: it reads the frozen reading as read (the held
value) and flags the freeze where its judgement ends (st98), unchanged.  The C's state:
sizeof(tc_state) 8,656 -> 22,080 bytes with 12 monitored sensors (cr9763, sw9776), 10,144 ->
25,632 with 14 (lr9376): 128 rows x (8 NM + 8) + 8 NM + 12 (and padding); an export without
``spread`` keeps one row.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402


def _three(deployed, ss, binary: Path, frame: pd.DataFrame) -> tuple[float, float, str, int]:
    """``(max |served - mirror|, max |served - C|, rows the mirror flags and their kinds, rows
    held)`` over ``frame`` (µm; held: a row where the mirror reads a sensor at its held value)."""
    from _ccode import streamed
    from bench_cmon92 import Stepped

    from thermocomp.apps.deploy.export.watch import FLAG_KINDS

    run, served, mirror, flagged, held, bits = Stepped(deployed, ss), [], [], 0, 0, 0
    for c, want, flags, *_ in run.rows(frame):
        w = run.sim.watch
        served.append(want)
        mirror.append(c)
        flagged, bits = flagged + bool(flags), bits | flags
        if hasattr(w, "hold_to"):      # (a tree before mon105d: never held)
            held += bool((w.froze & ~w._active() & (w.off == 0) & (w.now <= w.hold_to)).any())
    served, mirror = np.array(served), np.array(mirror)
    code = streamed(binary, frame[["time", *ss.inputs]])
    assert code.shape == served.shape, (code.shape, served.shape)
    return (float(np.max(np.abs(served - mirror))), float(np.max(np.abs(served - code))),
            f"{flagged} (bits {[k for k, b in FLAG_KINDS if bits & b]})", held)


def agree(root: str, *records: str) -> None:
    """The ``agree`` rows (module doc)."""
    from _ccode import built
    from bench_cmon92 import faulted_cell, made, planted
    from bench_mon97 import FRESH as SPENT
    from bench_mon97 import SEEN
    from bench_mon105c import FRESH, frozen_sensors

    from thermocomp.apps.deploy.export import exported_files

    base = Path(root).resolve()
    for record in records:
        made(base, record, "mlr", {**SEEN, **SPENT, **FRESH})
        deployed, ss, frame, lead, start, cid = faulted_cell(base, record, "mlr-none")
        with tempfile.TemporaryDirectory(prefix="mon105d-") as tmp:
            binary = built(Path(tmp), exported_files(deployed, "c"))
            m, c, flagged, held = _three(deployed, ss, binary, frame)
            print(f"{record} campaign {cid} healthy: |served-mirror| {m:.3g} |served-C| {c:.3g} µm, "
                  f"mirror flagged rows {flagged}, held rows {held}", flush=True)
            for sensor in frozen_sensors(deployed.monitor):
                whole = pd.concat([frame.iloc[:start], planted(frame, start, (sensor,), "freeze")])
                m, c, flagged, held = _three(deployed, ss, binary, whole)
                print(f"  {sensor:<18} |served-mirror| {m:.3g} |served-C| {c:.3g} µm, "
                      f"mirror flagged rows {flagged}, held rows {held}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"agree": agree}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))

