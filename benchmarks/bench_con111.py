"""A stretch without rows within a campaign's first 10 steps, said by ``connect``'s watch (stop 111,
con111).  con109 left: ``connect`` says such a stretch on the server's clock at once
(``clock_gap``, read against ``connect.period_s``), the file reader says it (its median period),
but the watch (``rates.StepWatch``, the ``time`` event) says nothing there: it learns the period
from the campaign's first 10 steps and read none of them.  The bar: benchmarks/con111_bar.md.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_con111.py said OUT.json          # every feed, both routes -> OUT.json
    python benchmarks/bench_con111.py cells BASE.json THIS.json   # cells G1-G3 of two trees' OUT
    python benchmarks/bench_con111.py jitter               # (after the bar) jittery healthy clocks

``said``: the feeds of the bar (the seen grid of gaps, bench_con109's, early period changes, the
fresh ones of seed 10217) fed to an offline ``Connection`` (bench_con109's ``_connected``: the
client's ``_sample``/``_step``, no server) on the server's clock and on a ``time`` node; per feed
and route the events (kind, data row named, data row being read), the samples counted missed, and
the file reader's words of the same rows.  ``cells`` scores them.

``jitter`` (harness after the bar, beside G2): 2000 healthy campaigns of 60 rows at 100 s per
jitter, each timestamp off by up to +-10 ... 30 % of the period (uniform; seed 10217, its own
generator): the stretches said in data rows <= 11 by the watch (``rates.StepWatch``, connect's
and the served model's rule) and by the file reader (``timestamps.row_gaps``), by both or by one.

SCORED (2026-12-07 ~22:50-22:55 UTC, 2 cores shared; BASE = 1a0fc91a's src in a detached worktree,
this tree d3761a2d's src; the script and tests the same)::

  G1 seen grid (32 feeds x 2 routes): `time` "rows missing" at the file reader's row (3..10), said
     while the row after it is read; BASE said none; missed as BASE (server 2..5, node 0).
  G2 con109's healthy / period feeds and 16 early period changes: events and missed = BASE's.
  G3 fresh (seed 10217: a 4-period gap into step 3, a change to 111 s from step 7): G1 / G2 hold.
  57 feeds, 114 feed-routes, failed 0.  CPU of ``said``: BASE 2.75 s, here 2.90 s (process).
  jitter (+-10 / 20 / 25 / 30 %): said by the watch only 0 / 1 / 5 / 46 of 2000 campaigns each
  (BASE 0 / 0 / 0 / 0); by the file reader only 0 / 0 / 29 / 319 (BASE 0 / 0 / 31 / 357).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_con109 import _connected, _feeds, _file_said  # noqa: E402

SEED = 10217


def _gap(period: float, rows: int, step: int, periods: int) -> np.ndarray:
    """Rows every ``period`` s, the step into data row ``step + 1`` ``periods`` periods long."""
    t = np.arange(rows) * period
    t[step:] += (periods - 1) * period
    return t


def _change(period: float, rows: int, step: int, to: float) -> np.ndarray:
    """Rows every ``period`` s, then every ``to`` s from the step into data row ``step + 1``."""
    t = np.arange(rows) * period
    t[step:] = t[step - 1] + to * np.arange(1, rows - step + 1)
    return t


def feeds() -> dict[str, tuple[str, np.ndarray]]:
    """``{name: (cell, times)}``: the bar's feeds (cell ``G1``: a gap; ``G2``: none)."""
    out = {f"seen gap step {j} x{m}": ("G1", _gap(100.0, 325, j, m))
           for j in range(2, 10) for m in range(3, 7)}
    out.update({f"con109 {k}": ("G1" if "gap" in k else "G2", t) for k, t in _feeds().items()})
    out.update({f"early change step {j} to {to:g}": ("G2", _change(100.0, 325, j, to))
                for j in range(2, 10) for to in (1000.0, 300.0)})
    rng = np.random.default_rng(SEED)
    j, m, c = (int(rng.integers(lo, hi)) for lo, hi in ((2, 10), (3, 7), (2, 10)))
    out[f"fresh gap step {j} x{m}"] = ("G1", _gap(37.0, 200, j, m))
    out[f"fresh change step {c} to 111"] = ("G2", _change(37.0, 200, c, 111.0))
    out["fresh healthy 37"] = ("G2", np.arange(200) * 37.0)
    return out


def said(out: str) -> None:
    """Each feed's events and missed count, both routes, with the file reader's words (to OUT)."""
    found = {}
    for name, (cell, times) in feeds().items():
        period = float(np.median(np.diff(times[:11])))
        routes = {route: _connected(times, period, route) for route in ("server", "node")}
        found[name] = {"cell": cell, "file": _file_said(times),
                       **{r: {"said": s, "missed": m} for r, (s, m) in routes.items()}}
    Path(out).write_text(json.dumps(found, indent=1))
    print(f"{len(found)} feeds written to {out}", flush=True)


def _time_said(events: list) -> list:
    return [e for e in events if e[0] in ("rows missing", "period changed")]


def cells(base: str, this: str) -> None:
    """G1-G3 of the bar, per feed: THIS against the file reader and BASE."""
    b, t = (json.loads(Path(p).read_text()) for p in (base, this))
    failed = []
    for name, f in t.items():
        file, verdicts = [tuple(x) for x in f["file"]], []
        for route in ("server", "node"):
            mine, old = f[route], b[name][route]
            gaps = [e for e in mine["said"] if e[0] == "rows missing"]
            if f["cell"] == "G1":
                ok = ([(e[0], e[1]) for e in gaps] == file and all(e[2] == e[1] + 1 for e in gaps)
                      and mine["missed"] == old["missed"])
                note = f"rows missing {[(e[1], e[2]) for e in gaps]} (BASE {_time_said(old['said'])})"
            else:
                ok = ([tuple(e) for e in mine["said"]] == [tuple(e) for e in old["said"]]
                      and mine["missed"] == old["missed"] and not gaps)
                note = f"said {_time_said(mine['said'])} (BASE {_time_said(old['said'])})"
            verdicts.append(ok)
            print(f"{name} [{f['cell']}] {route}: {'ok' if ok else 'FAIL'}; file {file}; {note}; "
                  f"missed {mine['missed']} (BASE {old['missed']})", flush=True)
        if not all(verdicts):
            failed.append(name)
    print(f"feeds {len(t)}, failed {len(failed)}: {failed}", flush=True)


def jitter() -> None:
    """Jittery healthy clocks (module doc): early stretches said by the watch and the file reader."""
    from thermocomp.core.io.rates import StepWatch
    from thermocomp.core.io.timestamps import row_gaps

    rng = np.random.default_rng(SEED)
    for a in (0.1, 0.2, 0.25, 0.3):
        both = watch_only = file_only = 0
        for _ in range(2000):
            t = np.sort(np.arange(60) * 100.0 + rng.uniform(-a, a, 60) * 100.0)
            w = StepWatch(hour_steps=False)
            said = {f[1] + 1 for r, s in enumerate(t) for f in w.read(float(s), r) if f[0] == "gap"}
            watch = {r for r in said if r <= 11}
            file = {int(g) + 2 for g in row_gaps(t) if g + 2 <= 11}
            both, watch_only, file_only = (both + len(watch & file), watch_only + len(watch - file),
                                           file_only + len(file - watch))
        print(f"jitter +-{a:.0%}: early stretches said by both {both}, by the watch only "
              f"{watch_only}, by the file reader only {file_only}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"said": said, "cells": cells, "jitter": jitter}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
