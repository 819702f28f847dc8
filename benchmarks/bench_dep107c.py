"""The C and the served model say what the file reader says of the same rows (stop 107,
dep107c; issue 34 "deployed as scored").  audit107 (bench_audit107, cell F on col10133) left:
(1) a logger set to another sample rate mid-stream (100 s rows, then 1000 s from data row 202):
``replay`` (the file reader) and ``monitor.input=-`` warn naming the row, ``stream.c`` and the
served model say nothing, though their corrections match replay's; (2) the C's refusal of
``22,61`` (a decimal comma in a ','-separated stream) suggests a missing-value mark; (3) one more
such gap, chosen here: a stretch without rows (a gateway's outage: the file reader's
``rates.said_if_rows_missing``, "N stretch(es) without rows ... before line L").

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep107c.py faults CELLS OUT [PORT] [CELL ...]   # cells P, D, G, H

PORT: also serve the cell's model.pkl there (bench_audit107's HTTP route; '' none).
CELLS: bench_audit107's root (``data/col10133``, ``reports/col10133/<cell>`` and ``<cell>-c``,
made by its ``models`` command; read only).  OUT: scratch.  CELL: ``mlr-none`` ``lagbank-none``
by default.  Per CELL, the test file of col10133 (1441 rows at 100 s) as written (``healthy``)
and faulted by bench_audit107.faulted (``period10``, ``comma``) and here (``gap``: data rows
301-305 left out, a stretch of 6 periods): fed to (a) the cell's ``stream`` as audit107 built it
(570d5a78's stream.c: the base) and (b) this tree's ``stream.c`` (export.driver.DRIVER) built by
tests/cbuild.py beside the cell's compensator.c/.h, both ``--flags``; and to the served model in
process (pyfunc.CompensatorModel around the registered version the cell's C was exported from,
the code ``serve`` runs) as one
block and as blocks of 50 rows in one session; per route: exit / status, what it says (stderr
lines, log warnings, events) and max |correction - base| over the rows; the served corrections
saved as OUT/served-<cell>-<fault>-<block>.npy (to compare two trees' runs).

BAR (written and committed BEFORE any of the figures below was measured; not to move after):
P. period10 (both cells): this tree's C says on stderr the period change, naming line 203 (data
   row 202, as the file reader names it) and both periods (100 s, 1000 s); the served model says
   it in a warning (session, the row of its block) and, for the adaptive model, an event of that
   row (``sensor`` time); served as one block and as blocks of 50 alike.  The C's stdout (--flags
   included: no new column) = the base's byte for byte; served corrections = BASE's served to
   1e-9 um; |served - C| <= 1e-9 um (audit107: 1.4e-13).
D. comma: the C exit 2 naming line 202 and input T_front1 and a decimal comma (not a
   missing-value mark); stdin exit 2 naming row 201, T_front1 and a decimal comma; the served
   400 naming row 201 and T_front1 (JSON: a number is sent as a number).
G. gap: the file reader says the stretch (replay of the rows); the C and the served model say it
   naming its row and its length in periods (or, where they say it already on BASE, traced); the
   corrections unchanged as in P.
H. healthy (both cells): no period nor gap line said by the C or served (no false alarm), the C's
   stdout = the base's byte for byte.
Each mend: a test failing on 1e995de3, passing here, <= ~3 s CPU (tests/cbuild.py for the C).
KEPT where P, D, G, H hold; else REFUSED (src reverted, the rule kept as
benchmarks/dep107c_rule.patch).

Harness after the bar (no rule, no figure chosen): the served model also by HTTP (``PORT``:
bench_audit107's route, ``thermocomp serve`` of the cell's model.pkl, its faults' first 220 rows)
for D's 400 (the in-process predict takes no JSON: not run for ``comma``); what the file reader
and stdin say of each fault's rows (``read_dataset`` of them written, ``stream_campaigns``).

Scored once (2026-12-07 ~12:15 UTC, 2 cores shared, ``nice``; this tree 1a71d75d's src, then the
same command on 1e995de3's src, OUT apart; the served corrections compared file by file)::

  P  mlr-none, lagbank-none: the C says "line 203: the sample period changes from 100 s to 1000 s
     here ..." (base: nothing); stdout = base byte for byte (--flags); served (in process, one
     block and blocks of 50; HTTP) warns "session 'm1', column 'time', data row 202 of the block"
     (blocks of 50: "data row 2", the same row), one event time -> period changed at 21000 s
     (base: nothing); served corrections = 1e995de3's served exactly (np.array_equal, 12 arrays);
     |served - C| 2.27e-13 / 1.99e-13 um (HTTP 1.42e-13, as audit107): holds
  D  the C exit 2 "line 202: input T_front1: '22,61' is no number: a decimal comma? ..." (base:
     "a mark for a value not measured?"); stdin "data row 201: ... '22,61' is not a number: a
     decimal comma? set data.decimal=','" (base: no hint); HTTP 400 "column 'T_front1', data row
     201 of the block: value '22,61' is not a number (float64; send numbers as JSON numbers ...)"
     (unchanged): holds
  G  the file reader "1 stretch(es) without rows (steps of 6 sample periods of 100 s ... before
     line 302 (data row 301))"; the C "line 302: 6 sample periods of 100 s without rows before
     this one ..."; served "data row 301 of the block" (blocks of 50: "data row 1"), event time ->
     rows missing at 30500 s; stdin now the file reader's words, "before data row 301" (base: the
     C, served and stdin said nothing); corrections as in P: holds
  H  healthy: no period or gap line from the C, served, stdin or the file reader; stdout = base
     byte for byte: holds
CPU (user + sys, /usr/bin/time of the bench, both cells, its waited children in): 22.5 +
2.9 s with HTTP (this tree), 12.0 + 0.6 s without (1e995de3).  Verdict: KEPT.
"""

from __future__ import annotations

import io
import logging
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE), str(REPO / "tests")]
import bench_audit107  # noqa: E402
from _cli import made_folder, run_commands  # noqa: E402

RECORD = "col10133"
CELLS = ("mlr-none", "lagbank-none")
GAP_ROWS = range(300, 305)        # data rows 301-305 (0-based 300-304) left out
BLOCK = 50
FAULTS = ("healthy", "period10", "comma", "gap")


def rows_of(frame: pd.DataFrame, fault: str, sensor: str) -> pd.DataFrame:
    """The test file's cells with ``fault`` (module doc)."""
    if fault == "healthy":
        return frame
    if fault == "gap":
        return frame.drop(index=list(GAP_ROWS)).reset_index(drop=True)
    return bench_audit107.faulted(frame, fault, sensor, 100.0)


def built(cell_c: Path, out: Path) -> Path:
    """This tree's stream.c beside the cell's compensator.c/.h in ``out``, built (tests/cbuild.py)."""
    from cbuild import compiled
    from thermocomp.apps.deploy.export.driver import DRIVER

    out.mkdir(parents=True, exist_ok=True)
    for name in ("compensator.c", "compensator.h"):
        shutil.copy(cell_c / name, out / name)
    (out / "stream.c").write_text(DRIVER)
    return compiled(out)


def fed(stream: Path, rows: pd.DataFrame) -> tuple[int, str, bytes]:
    done = subprocess.run([str(stream), "--flags"], input=rows.to_csv(index=False).encode(),
                          capture_output=True)
    return done.returncode, done.stderr.decode(errors="replace"), done.stdout


def corrections(stdout: bytes) -> np.ndarray:
    got = pd.read_csv(io.BytesIO(stdout)) if stdout.strip() else pd.DataFrame()
    return got.filter(like="C_").to_numpy(float)


class Said(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.lines: list[str] = []

    def emit(self, record):
        self.lines.append(record.getMessage())


def served(model: Path, rows: pd.DataFrame, block: int | None) -> tuple[str, np.ndarray, list, list]:
    """The served model (the pyfunc serve runs) on ``rows`` as one block or blocks of ``block``."""
    from mlflow.exceptions import MlflowException

    from thermocomp.apps.deploy.pyfunc import CompensatorModel, load_deployed

    served_model = CompensatorModel(load_deployed(str(model), folder=model))
    inputs = [c for c in rows.columns if not c.startswith("E_")]
    frame = rows[inputs].copy()
    handler = Said()
    logger = logging.getLogger("thermocomp")
    logger.addHandler(handler)
    outs, status = [], "200"
    try:
        starts = range(0, len(frame), block or len(frame))
        for k, start in enumerate(starts):
            part = frame.iloc[start:start + (block or len(frame))].reset_index(drop=True)
            try:
                outs.append(served_model.predict(None, part, {"session": "m1", "reset": k == 0}))
            except MlflowException as exc:
                status = f"400: {exc.message[:300]}"
                break
    finally:
        logger.removeHandler(handler)
    out = pd.concat(outs, ignore_index=True) if outs else pd.DataFrame()
    events = [e for e in out.get("events", []) if e not in (None, "", "[]")]
    said = [ln for ln in handler.lines if "not held by this server" not in ln]
    return status, out.filter(like="C_").to_numpy(float), said, [e for e in events if '"sensor": "time"' in e]


def read_as(rows: pd.DataFrame, path: Path, inputs: list[str]) -> tuple[list[str], list[str]]:
    """What the file reader (read_dataset of ``rows`` written to ``path``) and the stdin reader
    (stdin.stream_campaigns, ``monitor.input=-``'s) say of ``rows``: warnings, or the refusal."""
    from thermocomp.core.io import read_dataset
    from thermocomp.core.io.options import ReadOptions
    from thermocomp.core.io.stdin import stream_campaigns

    rows.to_csv(path, index=False)
    said = []
    for read in (lambda: read_dataset(path), lambda: stream_campaigns(path.read_text(), inputs,
                                                                      ReadOptions.from_cfg({}))):
        handler = Said()
        logging.getLogger("thermocomp").addHandler(handler)
        try:
            read()
        except ValueError as exc:
            handler.lines.append(f"REFUSED: {exc}")
        finally:
            logging.getLogger("thermocomp").removeHandler(handler)
        said.append([ln[:260] for ln in handler.lines if "period" in ln or "rows" in ln or "REFUSED" in ln])
    return said[0], said[1]


def http(name: str, cell: Path, data: Path, frame: pd.DataFrame, sensor: str, stream: Path, port: str,
         scratch: Path) -> None:
    """bench_audit107's served route (``thermocomp serve`` of the cell's model.pkl on PORT, its
    faults' first 220 rows by HTTP, against this tree's C), and what the server said of time."""
    answers = {f: pd.read_csv(io.BytesIO(fed(stream, bench_audit107.faulted(frame, f, sensor, 100.0))[2]))
               for f in bench_audit107.FAULTS}
    inputs = [c for c in frame.columns if not c.startswith("E_")]
    folder = made_folder(scratch / f"{name}-http")
    bench_audit107._served(cell / "model.pkl", data, frame, inputs, sensor, 100.0, int(port), folder, answers)
    said = [ln[:300] for ln in (folder / "serve.err").read_text(errors="replace").splitlines()
            if "column 'time'" in ln]
    print(f"  server said of time: {said}", flush=True)


def registered(root: Path, cell_c: Path) -> Path:
    """The pyfunc folder of the registered version the cell's C was exported from (its log's
    ``export.model=models:/<name>/<version>``, the store's source of that version)."""
    import re
    import sqlite3

    name, version = re.search(r"export\.model=models:/([^/\s]+)/(\d+)",
                              (cell_c / "thermocomp.log").read_text()).groups()
    with sqlite3.connect(f"file:{root / 'mlruns' / 'mlflow.db'}?mode=ro", uri=True) as db:
        source, = db.execute("select source from model_versions where name = ? and version = ?",
                             (name, int(version))).fetchone()
    return root / "mlruns" / "thermocomp" / "models" / source.split("/")[-1] / "artifacts"


def faults(cells: str, out: str, port: str = "", *chosen: str) -> None:
    """Cells P, D, G, H (module doc)."""
    root, scratch = Path(cells).resolve(), made_folder(out)
    data = root / "data" / RECORD
    manifest = pd.read_csv(data / "campaigns.csv")
    test_file = manifest.loc[manifest.split == "test", "file"].iloc[0]
    frame = pd.read_csv(data / test_file, dtype=str, keep_default_na=False)
    sensor = next(c for c in frame.columns if c.startswith("T_") and not c.startswith("T_amb"))
    for name in chosen or CELLS:
        cell = root / "reports" / RECORD / name
        base_stream = cell.parent / f"{name}-c" / "stream"
        stream = built(cell.parent / f"{name}-c", scratch / name)
        model = registered(root, cell.parent / f"{name}-c")
        print(f"{name}: sensor {sensor}; base {base_stream}; this tree's {stream}; served {model}",
              flush=True)
        if port:
            http(name, cell, data, frame, sensor, stream, port, scratch)
        for fault in FAULTS:
            rows = rows_of(frame, fault, sensor)
            if name == (chosen or CELLS)[0]:
                file_said, stdin_said = read_as(rows, scratch / f"{fault}.csv",
                                                [c for c in frame.columns if not c.startswith("E_")])
                print(f"  [{fault}] the file reader says {file_said}; stdin says {stdin_said}", flush=True)
            (b_rc, b_err, b_out), (rc, err, got) = fed(base_stream, rows), fed(stream, rows)
            c_base, c_this = corrections(b_out), corrections(got)
            said = [ln for ln in err.splitlines() if "monitor:" not in ln]
            b_said = [ln for ln in b_err.splitlines() if "monitor:" not in ln]
            print(f"  C [{fault}] base exit {b_rc} ({len(c_base)} rows), this exit {rc} ({len(c_this)} rows);"
                  " "
                  f"stdout = base byte for byte: {got == b_out}; base says {b_said}; this says {said}",
                  flush=True)
            for block in (None, BLOCK) if fault != "comma" else ():   # (a JSON number: HTTP's)
                status, c_served, logged, events = served(model, rows, block)
                np.save(scratch / f"served-{name}-{fault}-{block or 0}.npy", c_served)
                n = min(len(c_served), len(c_this))
                diff = float(np.abs(c_served[:n] - c_this[:n]).max()) if n else float("nan")
                print(f"    served [{fault}] {'one block' if block is None else f'blocks of {block}'}: "
                      f"{status}, {len(c_served)} rows, max|served - C| {diff:.3g} um over {n}; "
                      f"warnings {logged}; time events {events[:3]}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"faults": faults}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
