"""CPU time of reading a record from an Excel workbook against reading its CSV export.

Usage::

    python benchmarks/bench_workbook.py [ROWS]     # default: every row of datasets/fl_thermal

Writes the shipped record's first ``ROWS`` rows (23 columns: a time, a state, 5 errors, 16
temperatures) as a workbook (openpyxl) and as CSV in a temporary folder, then reads each with
``read_dataset`` (the data config of ``data=fl_thermal``) in a fresh subprocess, three times, and
prints the best CPU time (user + sys, ``resource.getrusage``) of the read alone, with the
metrics' parity: the same frames from both.
"""

from __future__ import annotations

import csv
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RECORD = ROOT / "datasets" / "fl_thermal" / "spindle_test.csv"
REPEATS = 3
READ = """
import hashlib, resource, sys
from thermocomp.core.io import read_dataset
cfg = {"roles": {"error": ["ch*"], "state": ["spindle*"]}, "test_fraction": 0.1}
before = resource.getrusage(resource.RUSAGE_SELF)
ds, _ = read_dataset(sys.argv[1], cfg)
after = resource.getrusage(resource.RUSAGE_SELF)
cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
digest = hashlib.sha256(b"".join(ds.campaigns[c].to_numpy().tobytes() for c in ds.ids()))
print(cpu, digest.hexdigest()[:12])
"""


def write(folder: Path, rows: int) -> tuple[Path, Path]:
    """The record's first ``rows`` rows as ``lab.xlsx`` and ``lab.csv`` (numbers as floats)."""
    import openpyxl

    with open(RECORD, encoding="utf-8", newline="") as f:
        lines = list(csv.reader(f))[:rows + 1]
    book = openpyxl.Workbook()       # (not write_only: that writes no <dimension>, which Excel
    sheet = book.active              # always writes, and openpyxl then scans the sheet for it)
    sheet.title = "Messung"
    sheet.append(lines[0])
    for line in lines[1:]:
        sheet.append([float(v) for v in line])
    book.save(folder / "lab.xlsx")
    with open(folder / "lab.csv", "w", encoding="utf-8", newline="") as f:
        csv.writer(f).writerows([lines[0], *([repr(float(v)) for v in r] for r in lines[1:])])
    return folder / "lab.xlsx", folder / "lab.csv"


def cpu(path: Path) -> tuple[float, str]:
    """Best CPU seconds of ``REPEATS`` reads of ``path``, each in a fresh process; its digest."""
    env = {"PYTHONPATH": str(ROOT / "src"), "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    runs = [subprocess.run([sys.executable, "-c", READ, str(path)], env=env, check=True,
                           capture_output=True, text=True).stdout.split() for _ in range(REPEATS)]
    return min(float(r[0]) for r in runs), runs[0][1]


def main(rows: int) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        book, export = write(Path(tmp), rows)
        (book_s, book_d), (csv_s, csv_d) = cpu(book), cpu(export)
        print(f"{rows} rows x 23 columns: workbook {book.stat().st_size / 1e6:.2f} MB, CSV "
              f"{export.stat().st_size / 1e6:.2f} MB")
        print(f"read_dataset CPU (best of {REPEATS}): workbook {book_s:.3f} s, CSV {csv_s:.3f} s, "
              f"ratio {book_s / csv_s:.1f}; same frames: {book_d == csv_d}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 11115)
