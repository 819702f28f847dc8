"""`connect`'s ``clock_gap`` after a sample period change (stop 108, dep108e; issue 34 "deployed as
scored").  dep108b left: on the server-clock route (a vendor's server, ``connect.clock=server``)
``clock_gap`` reads each step of the server's clock against ``connect.period_s`` (the model's
training period): after the logger's period changes (100 s -> 1000 s at col10133's data row 202)
every step is "a stretch without samples (9 counted missed)": 124 events and 1116 samples counted
missed, though the campaign's ``rates.StepWatch`` has said the change once.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep108e.py faults CELLS OUT [CELL ...]     # cells E, G, H; offsets saved
    python benchmarks/bench_dep108e.py compare OUT_BASE OUT_THIS        # cell C

CELLS: bench_audit107's root (read only).  CELL: ``mlr-none`` ``lagbank-none`` by default.  The
feeds and the route are bench_dep108b's (its ``connected``: tests/shell/vendor_machine.py serving
col10133's test rows, lockstep, its clock the record's time, to ``thermocomp connect`` of the
cell's model.pkl); printed per cell and feed: connect's ``clock_gap`` events (the sample before,
the data row where given, the start of the words), ``samples_missed``, its ``time`` events, what
the file reader says of the same rows; the offsets the machine held saved as OUT/<cell>-<feed>.npy.

BAR (written and committed BEFORE any figure below was measured; not to move after):
E. period10 (both cells): ``clock_gap`` events at or after the change (data row 202 on) 124 -> 0;
   the change said once (``time`` events exactly [(period changed, 202)], as the file reader).
G. gap (both cells): connect's gap still said (one ``clock_gap``, its stretch of 6 periods) naming
   data row 301, the row the file reader names ("before data row 301"), and the ``time`` event
   (rows missing, 301) as on BASE; ``samples_missed`` as on BASE.
H. healthy (both cells): no ``clock_gap``, no ``time`` event, 0 missed.
C. every feed, both cells: the offsets the machine held = BASE's (the same bench on 560e4f78's src)
   to 1e-12 um.
The test added fails on 560e4f78, passes here, <= ~2 s CPU (test_opcua67's fixtures).
KEPT where E, G, H, C hold; else REFUSED (src reverted, the rule kept as dep108e_rule.patch).

Harness after the bar (no rule, no figure chosen): the "at or after row 202" count is of the
events whose sample before + 2 >= 202 (the step into data row 202 counts; BASE's run printed it
with + 1: 123 of its 124, all 124 from row 202 on).

Scored once (2026-12-07 ~15:42-15:58 UTC, 2 cores shared, ``nice``; 560e4f78's src and conf
extracted apart, then this tree at 6fe0fa3f, same command, OUT apart; ``compare`` of the two)::

  E  period10, both cells: clock_gap 124 -> 0, samples_missed 1116 -> 0 (325 samples both);
     time events [(period changed, 202)] both, = the file reader's: holds
  G  gap, both cells: one clock_gap, 600 s = 6 periods of 100 s, 5 counted missed, sample before
     299 (BASE the same, no row), now row 301 = the file reader's "before data row 301"; time
     event (rows missing, 301) both; samples_missed 5 both: holds
  H  healthy, both cells: no clock_gap, no time event, 0 missed (both): holds
  C  offsets held, 6 runs x 6 targets (325 to 1441 rows): = BASE's exactly (max 0 um): holds
CPU (user + sys, /usr/bin/time): faults 43.3 + 2.9 s (BASE), 32.8 + 1.8 s (this tree).
Verdict: KEPT.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests"), str(REPO / "tests" / "shell")]
import bench_dep107c  # noqa: E402
import bench_dep108b  # noqa: E402
from _cli import made_folder, run_commands  # noqa: E402

CHANGE_ROW = 202                 # period10: the first data row at 1000 s (bench_audit107.faulted)


def faults(cells: str, out: str, *chosen: str) -> None:
    """Cells E, G, H (module doc); the offsets saved for C."""
    root, scratch = Path(cells).resolve(), made_folder(out)
    data = root / "data" / bench_dep107c.RECORD
    manifest = pd.read_csv(data / "campaigns.csv")
    test_file = manifest.loc[manifest.split == "test", "file"].iloc[0]
    frame = pd.read_csv(data / test_file, dtype=str, keep_default_na=False)
    sensor = next(c for c in frame.columns if c.startswith("T_") and not c.startswith("T_amb"))
    inputs = [c for c in frame.columns if not c.startswith("E_")]
    for name in chosen or bench_dep107c.CELLS:
        model = root / "reports" / bench_dep107c.RECORD / name / "model.pkl"
        for feed in bench_dep108b.FEEDS:
            rows = bench_dep107c.rows_of(frame, feed, sensor).astype(float)
            file_said, _ = bench_dep107c.read_as(rows, scratch / f"{feed}.csv", inputs)
            link, held, _ = bench_dep108b.connected(data, model, rows, scratch / f"connect-{name}-{feed}")
            np.save(scratch / f"{name}-{feed}.npy", held)
            gaps = [e for e in link["events"] if e["event"] == "clock_gap"]
            after = [e for e in gaps if e["sample"] + 2 >= CHANGE_ROW] if feed == "period10" else []
            told = [(e["to"], e["row"]) for e in link["events"] if e["event"] == "time"]
            print(f"{name} [{feed}] {len(rows)} rows: clock_gap {len(gaps)} (period10: at or after "
                  f"row {CHANGE_ROW}: {len(after)}), missed {link['samples_missed']}, samples "
                  f"{link['samples']}; time events {told}; file reader "
                  f"{bench_dep108b._rows_said(file_said)}", flush=True)
            for e in gaps[:2]:
                print(f"    clock_gap sample {e['sample']} row {e.get('row')}: {e['detail'][:160]}",
                      flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"faults": faults, "compare": bench_dep108b.compare}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
