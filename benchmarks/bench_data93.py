"""Data in, as a stranger (stop 93, data93): a time-of-day header over DECIMAL HOURS (``Hora``
21.5, 21.5833 ...), and rows missing from a time of day without its date that may hide a day.

Usage (from ``benchmarks/``, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_data93.py write ROOT SEED            # the exports of SEED
    python benchmarks/bench_data93.py score ROOT SEED [FAMILIES [FILES]]  # init -> run -> C
    python benchmarks/bench_data93.py bad ROOT SEED              # hours no time of day; a gap

``write``: bench_data92b's ``write`` (``contract.csv``, ``rawclock.csv`` -- a dateless ``h:mm:ss``
under ``Uhrzeit`` from 21:30:00, past midnight --, ``rawpair.csv``, ``rawzeit.csv``) and, from
``rawclock.csv``'s lines, ``rawhora.csv`` (the clock as decimal hours under ``Hora``, every digit
of the float, decimal commas: 21,5, 21,583333333333332 ... 0,0 ...) and ``rawhora4.csv`` (4
decimals, as a lab's sheet rounds them: 21,5833).
``score``: bench_data92's ``score`` (init on the file alone, NO key typed; a refusal's key typed
once; ``run data.test_fraction=0.25``, plain replay, replay as deployed, ``export.format=c`` with
its check pack, the compiled C fed the RAW file) of ``contract``, ``rawclock``, ``rawhora``,
``rawhora4`` by default (mlr): per target the test RMSE of each, and max |C(file) - C(contract)|.
``bad``: ``init`` on (a) ``rawhora.csv`` with data row 20 ``25,25`` (no hour of a day); (b) the
record's decimal hours from 00:00:00 (all within [0, 1]: the hour after midnight, or a day as
Excel's fraction of it); (c) ``rawclock.csv`` and ``rawhora.csv`` with data rows 16-20 cut out (a
30 min gap, 6 sample periods: as well a day and 30 min); (d) bench_data92's ``served`` lagbank
session's 30 min pause between blocks: exit status, the refusal's file / column / row, and
whether the gap is said to hide a day.

What is detectable (said in docs/own-data.md): a time of day without its date cannot see a whole
day lost between two rows one sample period apart -- the rows look continuous.  What can be seen
is a gap in the rows' count against the clock (a step of 1.5 periods or more): under 100 periods
it was said as a logger's outage only; it now says "as well a day longer".  A day lost at the
same clock time (a step of 0) is a duplicate time, refused as before.

BAR (written before the fresh seeds 9556-9560 were drawn; dev seed 4242 only before)
------------------------------------------------------------------------------------
KEPT where, on 5 of 5 fresh seeds (mlr): (a) ``rawhora`` is accepted with NO key, init saying
decimal hours and writing ``units: {Hora: h}`` and ``time: of_day``, its run = plain replay,
replay = C to 1e-6 µm per target, and its C = C(contract) to 1e-6 µm on every row, its run =
the contract file's run to 1e-6 µm per target (main: refused at midnight); ``rawhora4`` accepted
so, or refused exit 2 at its row (its 4 decimals are 0.18 s off the clock: its figures reported,
not held to 1e-6); (b) ``contract`` and ``rawclock`` as main 5fe17063 to 1e-6 µm in every printed
figure (no case main accepts changes; ``rawpair``/``rawzeit`` scored on main and here where the
deadline allows, else said not scored); (c) ``bad`` (a) refused exit 2 naming file, column and
data row 20; (b) refused exit 2 naming both keys (``h`` and ``d``); (c) both gaps said "as well a
day longer" (main: an outage only); (d) the served 30 min pause warned of (main: not); (e)
tests/shell/test_decimal_hours93.py fail on 5fe17063 and pass here.  Any accepted case of main's
read otherwise, or a value no time of day accepted, refuses the rule.

Scored: (below, after the fresh seeds)
"""

from __future__ import annotations

import sys
from pathlib import Path

import pandas as pd
from _cli import run_commands
from bench_data88 import START, _cli, _refusal
from bench_data92 import score as score_files
from bench_data92 import served
from bench_data92b import write as write_raw

FILES = "contract,rawclock,rawhora,rawhora4"
CUT = range(16, 21)          # data rows cut out for ``bad``'s gap (6 sample periods)


def _hours(clock: str, digits: int | None) -> str:
    """``h:mm:ss`` as decimal hours with a decimal comma (``digits``: rounded; None: every one)."""
    h, m, s = (int(p) for p in clock.split(":"))
    value = h + m / 60 + s / 3600
    return (repr(value) if digits is None else f"{value:.{digits}f}").replace(".", ",")


def _lines(base: Path, name: str) -> list[str]:
    return (base / name).read_bytes().decode("utf-8").removeprefix("\ufeff").split("\r\n")


def _save(path: Path, lines: list[str]) -> None:
    path.write_bytes(("\ufeff" + "\r\n".join(lines)).encode("utf-8"))


def _as_hours(lines: list[str], digits: int | None, shift: float = 0.0) -> list[str]:
    """``rawclock.csv``'s lines, the clock as decimal hours under ``Hora`` (``shift`` s later)."""
    head, *body = lines
    out = ["Hora" + head[head.index(";"):]]
    for line in body:
        if not line:
            out.append(line)
            continue
        clock, rest = line.split(";", 1)
        t = (pd.Timestamp(f"2027-01-01 {clock}") + pd.Timedelta(seconds=shift)).strftime("%H:%M:%S")
        out.append(f"{_hours(t, digits)};{rest}")
    return out


def write(root: str, seed: str) -> None:
    """bench_data92b's exports of ``seed``, ``rawhora.csv`` and ``rawhora4.csv``."""
    write_raw(root, seed)
    base = Path(root) / seed
    clock = _lines(base, "rawclock.csv")
    _save(base / "rawhora.csv", _as_hours(clock, None))
    _save(base / "rawhora4.csv", _as_hours(clock, 4))
    print(f"wrote {base}: rawhora.csv, rawhora4.csv (from {START:%H:%M:%S})")


def score(root: str, seed: str, families: str = "mlr", files: str = FILES) -> None:
    """bench_data92's score of the files, no key typed (module docstring)."""
    score_files(root, seed, families, files)


def _init(base: Path, label: str, lines: list[str]) -> str:
    path = base / f"bad-{label}.csv"
    _save(path, lines)
    done = _cli("init", str(path), f"out={base / f'bad-{label}-init'}")
    day = [ln for ln in done.stderr.splitlines() if "a day longer" in ln]
    return (f"exit {done.returncode}: " + (_refusal(done)[:400] if done.returncode else
                                            "accepted") + f"; said to hide a day: {len(day)}")


def bad(root: str, seed: str) -> None:
    """Hours no time of day, hours within the first hour, a gap; a served pause (docstring)."""
    base = Path(root) / seed
    hora, clock = _lines(base, "rawhora.csv"), _lines(base, "rawclock.csv")
    broken = list(hora)
    broken[20] = "25,25" + broken[20][broken[20].index(";"):]          # data row 20
    midnight = 86400.0 - (START - START.normalize()).total_seconds()
    cases = {"hour25": broken,
             "firsthour": _as_hours(clock[:13], None, shift=midnight),    # 00:00 .. 00:55
             "gapclock": [ln for i, ln in enumerate(clock) if i not in CUT],
             "gaphora": [ln for i, ln in enumerate(hora) if i not in CUT]}
    for label, lines in cases.items():
        print(f"seed {seed} bad {label}: {_init(base, label, lines)}")
    served(root, seed)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "score": score, "bad": bad}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
