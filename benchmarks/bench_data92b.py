"""Data in, as a stranger (stop 92, data92b): a lab's time-of-day column found by its header, in
the languages labs write (``Uhrzeit``, ``Heure``, ``Hora``, ``Ora``, ``時刻``, ``time of day``).

Usage (from ``benchmarks/``, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_data92b.py write ROOT SEED            # the exports of SEED
    python benchmarks/bench_data92b.py score ROOT SEED [FAMILIES]  # init -> run -> replay -> C
    python benchmarks/bench_data92b.py bad ROOT SEED               # a cell no time of day

``write``: bench_data92's ``write`` (``contract.csv``, ``raw.csv``, ``rawclock.csv``: the dateless
``h:mm:ss`` under ``Uhrzeit`` from 21:30:00, past midnight) and two more raw exports of the same
rows: ``rawpair.csv`` (``Datum;Uhrzeit``, the date and the time of day in two columns) and
``rawzeit.csv`` (``Zeit``, the seconds elapsed since the first row, numbers).
``score``: bench_data92's ``score`` of ``contract``, ``rawclock``, ``rawpair``, ``rawzeit`` with
NO key typed (init on the file alone; a refusal's key typed once as bench_data92 does): per target
the test RMSE of run, plain replay, replay as deployed and the exported C fed the RAW file, and
max |C(file) - C(contract.csv)| over every row.
``bad``: ``rawclock.csv`` with one cell of the clock no time of day (row 20: ``25:10:00``, and
apart ``21.75``): ``init`` on it, the exit status and the refusal's file / column / row.

BAR (written before the fresh seeds 9531-9535 were scored; none drawn before; mlr only, the
deadline: lagbank's C reads the same time)
--------------------------------------------------------------------------------------------
KEPT where, on 5 of 5 seeds: (a) ``rawclock`` is accepted with no key, init writing
``data.time: of_day`` and saying so, and its run = plain replay, replay = C to 1e-6 µm per target
and C(rawclock) = C(contract) to 1e-6 µm on every row; (b) ``rawpair`` and ``rawzeit`` read as on
main 8cd822b4 (accepted there: every printed figure equal to 1e-6 µm, C(file) = C(contract) as
there; refused there: refused here at the same row, exit 2); (c) ``bad`` refused exit 2 naming the
file, the column and the row (main: refused too, the cell or the column); (d) tests failing on
8cd822b4 pass here.  Any case main accepts read otherwise here, or a value no time of day
accepted, refuses the rule.

Scored: see the bottom of this docstring (written after the fresh seeds only).
"""

from __future__ import annotations

import sys
from pathlib import Path

import pandas as pd
from _cli import run_commands
from bench_data88 import START, _cli, _refusal
from bench_data92 import score as score_files
from bench_data92 import write as write_raw

FILES = "contract,rawclock,rawpair,rawzeit"


def write(root: str, seed: str) -> None:
    """bench_data92's exports of ``seed``, ``rawpair.csv`` and ``rawzeit.csv`` (module docstring):
    ``rawclock.csv``'s lines, its ``Uhrzeit`` beside its date or in place of the seconds."""
    write_raw(root, seed)
    base = Path(root) / seed
    rows = pd.read_csv(base / "contract.csv")
    head, *body = (base / "rawclock.csv").read_bytes().decode("utf-8").removeprefix(
        "\ufeff").split("\r\n")[:len(rows) + 1]
    stamps = [START + pd.Timedelta(seconds=float(t)) for t in rows["time"]]
    since = [repr(float(t - rows["time"].iloc[0])).replace(".", ",") for t in rows["time"]]
    for name, lines in (("rawpair.csv", [f"Datum;{head}", *(f"{s:%d.%m.%Y};{line}" for s, line
                                                             in zip(stamps, body))]),
                        ("rawzeit.csv", [f"Zeit [s];{head.partition(';')[2]}",
                                         *(f"{z};{line.partition(';')[2]}" for z, line
                                           in zip(since, body))])):
        (base / name).write_bytes(("\ufeff" + "".join(f"{ln}\r\n" for ln in lines)).encode())
    print(f"wrote {base}: rawpair.csv, rawzeit.csv ({len(rows)} rows)")


def score(root: str, seed: str, families: str = "mlr") -> None:
    """bench_data92's score of the four files, no key typed (module docstring)."""
    score_files(root, seed, families, FILES)


def bad(root: str, seed: str) -> None:
    """``rawclock.csv`` with one cell no time of day, through ``init`` (module docstring)."""
    base = Path(root) / seed
    lines = (base / "rawclock.csv").read_bytes().decode("utf-8").split("\r\n")
    for label, cell in (("hour25", "25:10:00"), ("decimal", "21.75")):
        broken = list(lines)
        broken[20] = cell + broken[20][broken[20].index(";"):]       # data row 20
        path = base / f"bad-{label}.csv"
        path.write_bytes("\r\n".join(broken).encode("utf-8"))
        done = _cli("init", str(path), f"out={base / f'bad-{label}-init'}")
        print(f"seed {seed} bad {label} ({cell!r} at data row 20): exit {done.returncode}: "
              f"{_refusal(done)[:300] if done.returncode else 'accepted'}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "score": score, "bad": bad}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
