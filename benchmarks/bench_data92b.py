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

Scored (2026-12-05, fresh seeds 9531-9535, each ``write`` once on this tree, copies of the same
files scored by main 8cd822b4's src and conf; ``score`` (mlr) and ``bad`` of fix/data92b fb4552fe
src, unchanged since; no seed drawn before; the bar above unchanged after)
---------------------------------------------------------------------------------------------
Records 55-61 rows at 300 s from 21:30:00 (past midnight), 3 targets, the last quarter held out.

==========  ==========================================  =============================================
file        main 8cd822b4 (5 of 5 seeds alike)          fix/data92b (5 of 5 seeds alike)
==========  ==========================================  =============================================
contract    accepted, C = contract 0 µm                 as main, every printed figure equal (0 µm)
rawclock    init exit 2 at data row 1 ("a time of day   accepted with NO key: init says "'Uhrzeit'
            without its date"); the two keys it names   h:mm:ss, its header a time of day ... read
            typed (data.time=of_day data.roles.time=    as data.time='of_day'" and writes ``time:
            'Uhrzeit'): accepted, C = contract 0 µm     of_day``; run = plain replay (<= 8.9e-15 µm),
                                                        replay = C (<= 2.5e-14 µm), C(rawclock) =
                                                        C(contract) 0 µm on every row; every figure
                                                        = main's with the two keys typed (0 µm)
rawpair     accepted (Datum + Uhrzeit one timestamp),   as main, every figure equal (0 µm), no
            C = contract 0 µm                           of_day key written
rawzeit     accepted (Zeit [s]), C = contract 0 µm      as main, every figure equal (0 µm)
bad 25:10   exit 2, data row 1 (the clock refused as    exit 2, column 'time' (header 'Uhrzeit'),
(row 20)    a time of day without its date)             data row 21: "time decreases from 90600 s
                                                        (row 20) to 83400 s" (init's one rule, an
                                                        hour past 23 in the file: data.time=elapsed)
bad 21.75   exit 2, column 'Uhrzeit', data row 20       as main (the same words)
(row 20)    (the decimal mark is ambiguous)
==========  ==========================================  =============================================

Test RMSE (µm, run, E_X E_Y E_Z): 9531 0.345 1.075 0.888; 9532 0.531 0.758 1.669; 9533 0.746
0.577 1.062 (replay as deployed 0.768 1.941 1.676: the monitor and the guard, as main's).

Against the BAR: (a) 5 of 5; (b) 10 of 10 (rawpair, rawzeit) as main to the printed digit; (c)
10 of 10 refused exit 2 naming file / column / row (the 25:10 one at its next row, naming row 20:
``init``'s rule reads a file whose ``h:mm:ss`` passes 23 h as elapsed, kept as it is, so the
clock's step back after it is what is refused; read without ``init`` the file reader says
"'25:10:00' is no time of day (data.time=of_day)" at row 20, the test); (d)
tests/shell/test_clock_header92b.py, 7 of 8 fail on 8cd822b4 (the eighth a guard of the date
pair).  KEPT.  CPU: one set look-up per header; ``score`` ~4 min per seed (4 files, mlr).
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
