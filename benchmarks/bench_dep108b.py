"""`connect` (OPC UA) says a sample period that changes and a stretch without rows as the file
reader does (stop 108, dep108b; issue 34 "deployed as scored").  dep107c made the C, the served
model and stdin read the rows' time with ``rates.StepWatch``; ``connect`` said neither (its
``clock_gap`` reads the server's clock against ``connect.period_s``: a period change is a gap at
every sample after it, and on a ``time`` node, the twin's, nothing at all).  Second gap (dep107b's
"named, not mended"): without a time column a stray blank line restarted the stream.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep108b.py faults CELLS OUT [CELL ...]     # cells P, G, H
    python benchmarks/bench_dep108b.py said OUT                         # what a faults OUT said
    python benchmarks/bench_dep108b.py compare OUT_BASE OUT_THIS        # corrections, both trees
    python benchmarks/bench_dep108b.py blank OUT                        # cell B

CELLS: bench_audit107's root (``data/col10133``, ``reports/col10133/<cell>/model.pkl``; read
only).  CELL: ``mlr-none`` ``lagbank-none`` by default.  Per CELL and feed (bench_dep107c's
``healthy``, ``period10`` (100 s rows, 1000 s from data row 202) and ``gap`` (data rows 301-305
left out, a step of 6 periods); ``comma`` is not a feed of connect: an OPC UA node holds a number):
the test file's rows served by tests/shell/vendor_machine.py (a vendor's server, lockstep, its
clock the record's time, offsets as Double nodes) to ``thermocomp connect`` of the cell's
model.pkl (``connect.clock=server``); what connect says of the rows' time (its log's warnings,
connect.json's events) beside what the file reader says of the same rows (``read_dataset``), and
the offsets the machine held at each row saved as OUT/<cell>-<feed>.npy.

BAR (written and committed BEFORE any figure below was measured; not to move after):
P. period10 (both cells): connect says the period change (100 s -> 1000 s) naming the campaign's
   data row 202, the row the file reader names, in a warning and a connect.json event (``time``,
   ``to: period changed``); on BASE it says no period change.
G. gap: connect says the stretch without rows (6 periods of 100 s) naming data row 301, the row
   the file reader names ("before data row 301"), warning and event (``rows missing``).
H. healthy (both cells): no period nor rows-missing word from connect (no false alarm).
C. every feed, both cells: the offsets the machine held = BASE's (same bench on 0dd05741's src) to
   1e-12 um (the watch says; it changes no correction).
B. blank: a stream without a time column (``data.sample_period_s``) with a stray blank line among
   its rows: the file reader, stdin (``monitor.input=-``) and stream.c read it alike, as the data
   contract (docs/data-format.md) says of a file: the blank line left out, said, the rows after it
   one period on, no new campaign; the corrections of stdin and the C then = those of the same
   rows without the blank line (to 1e-9 um).  On BASE at least one reader restarts there.
Each mend: a test failing on 0dd05741, passing here; the tests added cost <= 3 s CPU in all.
KEPT where P, G, H, C (and B, or B traced as a separate verdict) hold; else REFUSED.

Harness after the bar (no rule, no figure chosen): connect's warnings are read from its run's
thermocomp.log (``said`` re-reads a faults OUT; the run's logging replaces a handler the bench
adds); B's file reader reads the rows with their E_ columns (it refuses a record without one).

Scored once (2026-12-07 ~14:34-14:40 UTC, 2 cores shared, ``nice``; this tree d14558d2's src, then
the same command on 0dd05741's src and conf, OUT apart; ``said`` and ``compare`` of the two)::

  P  period10, both cells: the file reader "line 203 (data row 202): the sample period changes
     from 100 s to 1000 s"; connect "time: campaign P1.MPF, column 'time', data row 202 of those
     read: the sample period changes from 100 s to 1000 s here ..." and one event (to: period
     changed, row 202) (base: none; both also 124 clock_gap events, 1116 samples counted missed):
     holds
  G  gap, both cells: the file reader "(steps of 6 sample periods of 100 s ...) before line 302
     (data row 301)"; connect "data row 301 of those read: 6 sample periods of 100 s without rows
     before this one" and an event (rows missing, row 301) (base: none; 1 clock_gap both): holds
  H  healthy, both cells: no time event, no warning: holds
  C  offsets held, 6 runs x 6 targets (325 to 1441 rows): = base's exactly (max 0 um): holds
  B  the file reader "line 451 (data row 450): a blank line under it is left out ..." (both
     trees); stdin now "<stdin>, data row 450: a blank line under it is left out ..." (base:
     nothing), its frames = those without the blank line (both); stream.c "line 452: a blank
     line: left out, no time column: the rows from line 453 read one period after the row above
     it ...", corrections = without it, 0 um, both cells (base: "a new campaign starts at line
     453", mlr 281 um, lagbank 262 um off): holds
CPU (user + sys, /usr/bin/time): faults 42.9 + 2.2 s (this tree), 43.3 + 1.9 s (base); blank
3.3 + 0.8 s (this), 3.6 + 0.6 s (base).  Verdict: KEPT.
"""

from __future__ import annotations

import json
import logging
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests"), str(REPO / "tests" / "shell")]
import bench_dep107c  # noqa: E402
from _cli import made_folder, run_commands  # noqa: E402

FEEDS = ("healthy", "period10", "gap")
BLANK_AFTER = 450                # B: the stray blank line under data row 450


def _rows_said(lines: list[str]) -> list[tuple[str, int]]:
    """``(period changed | rows missing, data row)`` of what a reader said."""
    out = []
    for ln in lines:
        kind = ("period changed" if "period changes" in ln else "rows missing"
                if "without rows" in ln else None)
        row = re.search(r"data row (\d+)", ln)
        if kind and row:
            out.append((kind, int(row.group(1))))
    return out


def connected(data: Path, model: Path, rows: pd.DataFrame, out: Path) -> tuple[dict, np.ndarray, list]:
    """``rows`` served by the vendor's server to ``thermocomp connect`` of ``model``: its
    connect.json, the offsets the machine held at each row, the warnings it logged."""
    from asyncua import ua

    from conftest import free_port
    from thermocomp.shell.cli import main as cli
    from vendor_machine import VendorMachine, connect_nodes, served_in_thread

    sensors = {c: f"s=CNC5000.{c}" for c in rows.columns if c != "time" and not c.startswith("E_")}
    offsets = {t: (f"s=CNC5000.Offset.{t}", ua.VariantType.Double, 1.0)
               for t in rows.columns if t.startswith("E_")}
    machine = VendorMachine({"P1.MPF": rows}, free_port(), sensors=sensors, offsets=offsets)
    thread = served_in_thread(machine)
    try:
        code = cli(["connect", f"data.path={data}", f"out={out}", "track=false", "plots=none",
                     f"connect.model={model}", f"connect.endpoint=opc.tcp://127.0.0.1:{machine.port}",
                     "connect.retry_s=0.4", "connect.give_up_s=60", "connect.hold_s=600",
                     *connect_nodes(sensors, offsets)])
    finally:
        machine.closing.set()
        thread.join(timeout=60)
    assert code == 0 and not machine.raised, (code, machine.raised)
    return json.loads((out / "connect.json").read_text()), np.vstack(machine.served.offsets), warned(out)


def warned(out: Path) -> list[str]:
    """The warnings of connect's log (its ``thermocomp.log``: the run's logging replaces a
    handler the bench would add)."""
    log = (out / "thermocomp.log").read_text(errors="replace").splitlines()
    return [ln.split(": ", 1)[1] for ln in log if " WARNING " in ln and ": " in ln]


def said(out: str) -> None:
    """What connect said of the rows' time in a ``faults`` OUT already run (its logs, events)."""
    for run in sorted(Path(out).glob("connect-*")):
        events = json.loads((run / "connect.json").read_text())["events"]
        print(f"{run.name}: events {[(e['to'], e['row']) for e in events if e['event'] == 'time']}; "
              f"warnings {_rows_said([ln for ln in warned(run) if ln.startswith('time: ')])}", flush=True)


def faults(cells: str, out: str, *chosen: str) -> None:
    """Cells P, G, H (module doc); the offsets saved for C."""
    root, scratch = Path(cells).resolve(), made_folder(out)
    data = root / "data" / bench_dep107c.RECORD
    manifest = pd.read_csv(data / "campaigns.csv")
    test_file = manifest.loc[manifest.split == "test", "file"].iloc[0]
    frame = pd.read_csv(data / test_file, dtype=str, keep_default_na=False)
    sensor = next(c for c in frame.columns if c.startswith("T_") and not c.startswith("T_amb"))
    inputs = [c for c in frame.columns if not c.startswith("E_")]
    for name in chosen or bench_dep107c.CELLS:
        model = root / "reports" / bench_dep107c.RECORD / name / "model.pkl"
        for feed in FEEDS:
            rows = bench_dep107c.rows_of(frame, feed, sensor).astype(float)
            file_said, _ = bench_dep107c.read_as(rows, scratch / f"{feed}.csv", inputs)
            link, held, logged = connected(data, model, rows, scratch / f"connect-{name}-{feed}")
            np.save(scratch / f"{name}-{feed}.npy", held)
            events = [e for e in link["events"] if e["event"] == "time"]
            said = [ln for ln in logged if ln.startswith("time: ")]
            gaps = [e for e in link["events"] if e["event"] == "clock_gap"]
            print(f"{name} [{feed}] {len(rows)} rows: file reader {_rows_said(file_said)}; connect "
                  f"events {[(e['to'], e['row']) for e in events]}, warnings {_rows_said(said)}; "
                  f"samples {link['samples']}, missed {link['samples_missed']}, clock_gap events "
                  f"{len(gaps)}; offsets {held.shape}", flush=True)
            for ln in said[:2]:
                print(f"    connect said: {ln[:230]}", flush=True)
            for ln in file_said[:1]:
                print(f"    file reader said: {ln[:230]}", flush=True)


def compare(base: str, this: str) -> None:
    """Cell C: max |offsets here - BASE's| per cell and feed."""
    for path in sorted(Path(this).glob("*.npy")):
        b, t = np.load(Path(base) / path.name), np.load(path)
        same = b.shape == t.shape and np.array_equal(np.isnan(b), np.isnan(t))
        diff = float(np.nanmax(np.abs(b - t))) if same else float("nan")
        print(f"{path.stem}: shape {t.shape} (base {b.shape}), NaN alike {same}, "
              f"max |this - base| {diff:.3g} um", flush=True)


def blank(out: str, cells: str = "/tmp/a107/root") -> None:
    """Cell B: col10133's test rows without their time column, a blank line under data row
    :data:`BLANK_AFTER`: the file reader, stdin and this tree's stream.c (built beside each
    cell's compensator.c) against the same rows without it."""
    from thermocomp.core.io import ReadOptions, read_dataset
    from thermocomp.core.io.stdin import stream_campaigns

    root, scratch = Path(cells).resolve(), made_folder(out)
    data = root / "data" / bench_dep107c.RECORD
    frame = pd.read_csv(data / "test_cycle.csv")
    inputs = [c for c in frame.columns if not c.startswith("E_") and c != "time"]
    lines = frame.drop(columns="time").to_csv(index=False).splitlines()     # (E_: the file reader's)
    whole = "\n".join(lines) + "\n"
    stray = "\n".join([*lines[:BLANK_AFTER + 1], "", *lines[BLANK_AFTER + 1:]]) + "\n"
    (scratch / "stray.csv").write_text(stray)
    for name, read in (("file reader", lambda: read_dataset(scratch / "stray.csv", {"sample_period_s": 100})),
                       ("stdin", lambda: stream_campaigns(stray, inputs, ReadOptions.from_cfg(
                           {"sample_period_s": 100})))):
        handler = bench_dep107c.Said()
        logging.getLogger("thermocomp").addHandler(handler)
        try:
            got = read()
        finally:
            logging.getLogger("thermocomp").removeHandler(handler)
        parts = got[0] if name == "stdin" else got[0].campaigns
        print(f"B {name}: campaigns {[(k, len(v)) for k, v in parts.items()]}; said "
              f"{[ln[:200] for ln in handler.lines if 'blank' in ln]}", flush=True)
        if name == "stdin":
            alone, _ = stream_campaigns(whole, inputs, ReadOptions.from_cfg({"sample_period_s": 100}))
            print(f"B stdin frames = those without the blank line: "
                  f"{list(parts) == list(alone) and all(parts[k].equals(alone[k]) for k in alone)}")
    for name in bench_dep107c.CELLS:
        stream = bench_dep107c.built(root / "reports" / bench_dep107c.RECORD / f"{name}-c", scratch / name)
        fed = [subprocess.run([str(stream)], input=t.encode(), capture_output=True) for t in (whole, stray)]
        ys = [bench_dep107c.corrections(f.stdout) for f in fed]
        said = [ln for ln in fed[1].stderr.decode().splitlines() if "blank" in ln]
        print(f"B C {name}: exit {fed[1].returncode}, rows {len(ys[0])} / {len(ys[1])}, max |blank - "
              f"without| {float(np.abs(ys[0] - ys[1]).max()):.3g} um; said {[ln[:200] for ln in said]}",
              flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"faults": faults, "said": said, "compare": compare, "blank": blank}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
