"""Why the C keeps a blind explainer out when a PREDICTED sensor leaves its range beside it
(issue 34; stop 98, mon98c; mon98b's finding on main: tr9828's drift line since restart98).

mon98b (bench_mon98b) found on main: bench_mon98's seen tr9828 drift case (a +1 K/h drift of
``T_ram``, trunnion63, mlr, from a quarter into test campaign W3, no lead-in since restart98)
has C != served from row 817 on.  Measured again here on a4724a2a (``cases ROOT tr9828``, CPU
24.9 s): max|C - served| 22.7 µm, rows mirror != served 6743 (every row from 817 to the end of
the 7560), the served RMSE over the drift 2.3982 µm (healthy 1.0979); the healthy frame and the
ambient case C = served (0 and 1.8e-15 µm, 0 rows).

TRACE (seen tr9828 only, served and the export's numpy mirror stepped together; ``trace``).
At drift row 130 the blind ``T_coolant_return`` (no other predicts it) goes out as explaining
the others' errors, in served and in the code alike (C = served to row 816, <= 1.4e-14 µm).  At
row 817 ``T_ram`` reads 34.85 °C, beyond its range [17.8, 24.8] ± 10 °C.  Served, in that one
sample: ``T_ram`` out (out of range), then by the ordinary re-admission ``T_coolant_return``
back ("the others within their warning bands with it in for 687 samples", readmission.py
``_why_back``'s explainer path): one out again, ``T_ram``.  The code (``CodeMonitor._beyond``):
with one out, a range reading is held as the second only where ``_second_kind(j, OFF_RANGE)``;
``T_ram`` is predicted (``ported``), so mon98b's blind clause is not the one that refuses: it is
cmon89's ``rebuilds``: 8 sensors active, 8 - 1 = 7 < ``min_active`` 8 (served's ``r_ + 1``),
the field cannot be rebuilt without both.  ``RANGE`` is flagged "not in the code", the sample
passes the monitor by, and ``T_coolant_return`` never comes back: served out ``T_ram``, C out
``T_coolant_return`` (C flags ``RANGE T_ram`` each row; |C - served| 2.02, 3.17, 4.78 µm at rows
817-819, growing with the drift).  The operator of the set without both exists (solved), and
``solve`` is on, ``out2`` free: only the count stops it.

WHY NOT MENDED (TRACED).  mon98b's rule reaches dl9845 because there the set without both still
holds ``min_active``; here it does not, so no widening of ``_second_kind`` holds ``T_ram`` as the
second: the code would have to judge the first's return BEFORE it refuses the range (take
``T_ram`` out as the only one where ``_returning`` lets ``T_coolant_return`` back in the set
without ``T_ram``, a swap of ``out``), in the mirror (``_beyond`` / ``_step``'s order) and in the
C (``mon_beyond`` / ``mon_second_kind`` and the re-admission after it), with its own json key.
Served itself passes through a set of 7 for that sample (exclude, then re-admit): the code's
judgement of the set in between is the part to build and prove.  Not small within the stop's
deadline, so no rule was built and no bar scored.  The BAR for that rule (from the brief, not
run): tr9828 drift C = served <= 1e-9 µm every row; bench_mon98b's dl9845 / dl9870 / dl9871
lines, bench_mon98's other seen lines, bench_kelvin97 ``faults``, bench_dep98 ``back tr9828``
unchanged; healthy 0 rows apart.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_mon98c.py trace ROOT [FROM TO]   # tr9828's drift, rows FROM..TO-1

``trace``: tr9828 (bench_mon98's SEEN) simulated into ``ROOT/data`` and ``run model=mlr`` into
``ROOT/reports`` once (bench_mon98's ``cases`` builds the same ROOT); its drift case stepped from
the campaign's start (CPU 7.0 s on a4724a2a, ROOT built), and per drift row in FROM..TO-1
(default 815..820): served's sensors out and events, the code's out / out2, its rule and sensor,
|C - served| (µm); at a range reading while one is out, why ``_second_kind`` refuses it (active
count against ``min_active``).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_audit97 import TRUNNION  # noqa: E402


def _why_refused(watch, names, rng) -> str:
    """At a range reading with one out: ``_second_kind``'s count (active - 1 against min_active)."""
    from thermocomp.apps.deploy.export.watch import OFF_RANGE

    j = int(np.argmax(rng))
    return (f"range {names[j]} with {names[watch.out]} out: ported {bool(watch.ported[j])}, "
            f"active {int(watch._active().sum())} - 1 vs min_active {int(watch.a['min_active'])}, "
            f"second kind {watch._second_kind(j, OFF_RANGE)}")


def trace(root: str, start_row: str = "815", stop_row: str = "820") -> None:
    """The ``trace`` rows (module doc)."""
    from bench_cmon92 import Stepped, faulted_cell, made
    from bench_mon98 import SEEN, _drifts

    from thermocomp.apps.deploy.export.watch import RULES

    os.environ["THERMOCOMP_TARGETS"] = TRUNNION[0].split("=", 1)[1]
    base = Path(root).resolve()
    made(base, "tr9828", "mlr", SEEN)
    deployed, ss, frame, _lead, start, _cid = faulted_cell(base, "tr9828", "mlr-none")
    mon, names = deployed.monitor, list(deployed.monitor.names)
    sensor, part = _drifts(frame, start, names, mon._predictable)["drift"]
    full = pd.concat([frame.iloc[:start], part])
    lo, hi = start + int(start_row), start + int(stop_row)
    run = Stepped(deployed, ss)
    lo_lim, hi_lim = run.sim.watch.a["lo_lim"], run.sim.watch.a["hi_lim"]
    print(f"tr9828 drift of {sensor} from row {start}; rows {start_row}..{int(stop_row) - 1}")
    for i, (c, want, *_) in enumerate(run.rows(full.iloc[:hi])):
        w = run.sim.watch
        if i < lo:
            continue
        x = full[ss.inputs].to_numpy(float)[i][w.idx]
        rng = (x < lo_lim) | (x > hi_lim)
        said = [(e.get("sensor"), e.get("to")) for e in deployed.last_events_]
        print(f"  {i - start}: served out {[names[k] for k in np.flatnonzero(~mon._active)]} "
              f"{said}; C out {[names[k] for k in (w.out, w.out2) if k >= 0]} rule "
              f"{RULES[w.rule]} {names[w.sensor] if w.sensor >= 0 else '-'}; |C - served| "
              f"{np.max(np.abs(c - want)):.3g} µm")
        if rng.any() and w.out >= 0:
            print(f"    {_why_refused(w, names, rng)} (after the row)")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
