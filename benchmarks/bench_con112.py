"""An early period change on ``connect``'s server route (stop 112, con112).  sec111 left: a feed
whose period changes within a campaign's first 10 steps (while ``rates.StepWatch`` learns the
period) made connect, on the server's clock, say a ``clock_gap`` and count samples missed at each
long step, read against ``connect.period_s``, where the file reader says no stretch (or a period
change).  The bar: benchmarks/con112_bar.md.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_con112.py said OUT.json        # the bar's feeds, both routes -> OUT
    python benchmarks/bench_con112.py fresh OUT.json       # C4: the feeds of seed 10266 -> OUT
    python benchmarks/bench_con112.py cells BASE.json THIS.json   # cells C1-C4 of two trees' OUT

``said``: 325 rows of 100 s, then r x 100 s from the step into data row j + 1 (j = 2..9, r = 0.5,
2, 3: cell C2); healthy, jittery healthy (+-10 / 20 / 25 % of the period per timestamp, 300
campaigns of 60 rows each, con111's seed 10217) and bench_con111's feeds (which hold
bench_con109's): cell C3.  Each fed to an offline ``Connection`` (bench_con109's ``_connected``:
the client's ``_sample``/``_step``, no server) on the server's clock and on a ``time`` node,
``connect.period_s`` the feed's shorter period; per feed and route the events (kind, data row
named, data row being read) and the samples counted missed, with the file reader's words: its
stretches without rows (``timestamps.row_gaps``, each data row and samples missed), said where it says no
period change (``values.py``, ``stdin.py``), and its period change.

The rule measured (REFUSED, not in src): benchmarks/con112_rule.patch, applied to 277c06b1 in a
worktree (``git apply``) whose src is then put on PYTHONPATH.

SCORED (2026-12-08 ~01:40 UTC, 2 cores shared; BASE 277c06b1's src in a detached worktree, the
rule 2961d118's src; ``said`` CPU (user + sys) 6.7 s BASE, 7.5 s the rule)::

  C1/C2 (24 feeds x 2 routes): BASE fails 24 (server: 2x and 3x at every step, a `clock_gap` at
     each long step until the period is learned, 124 clock_gaps, 168 missed where the file reader
     counts 15; 0.5x at steps 7-9; node: 0.5x at steps 2-6, the watch's).  The rule fails 6:
     server 0.5x step 6 (BASE's at-once said it; 5 of 10 learned steps long: the learned median
     75 s, not the file's 50 s), node 0.5x steps 2-6 (as BASE); 10 clock_gaps, 10 missed.
  C3: healthy, 900 jittery (+-10/20/25 %), con109's and con111's gap feeds identical to BASE
     (33 clock_gaps said one row later, owed to the watch); con111's 9 early-change feeds
     (server) differ from BASE: its clock_gaps there are the fault (7 now = the file reader).
  C4 seed 10266 (p 105.513 s, step 3, x3; drawn and scored once): the rule = the file reader
     (nothing, 0 missed), BASE 8 clock_gaps / 16 missed; the healthy feed nothing on both.
  Through a real asyncua server (test_opcua67's vendor machine, P05 changed): x3 from step 3
     BASE 8 clock_gaps / 16 missed, the rule none / 0; x2 from step 8 BASE 3 / 3, the rule 0 / 0
     (period changed at data row 12 on both = the file reader); x0.5 from step 4 (period_s 30)
     BASE 13 / 13 (10 on the healthy P06), the rule 3 / 3 (= the file reader's stretches).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_con109 import _connected, _file_said  # noqa: E402
from bench_con111 import _change  # noqa: E402
from bench_con111 import feeds as con111_feeds  # noqa: E402

SEED, FRESH_SEED = 10217, 10266
LEARNED_AT = 11       # the data row read when the watch has learned the period (its 10 steps)


def _truth(times: np.ndarray) -> dict:
    """The file reader's words of ``times``: stretches ``[[data row, samples missed]]`` and the data
    rows of its period changes."""
    from thermocomp.core.io.timestamps import row_gaps
    from thermocomp.core.timerule import median_step

    period, steps = median_step(times), np.diff(times)
    changes = [r for k, r in _file_said(times) if k == "period changed"]
    # (as values.py and stdin.py read a record: its stretches said only where no period change is)
    gaps = [] if changes else [[int(g) + 2, int(round(steps[g] / period)) - 1] for g in row_gaps(times)]
    return {"gaps": gaps, "period": changes}


def _feeds() -> dict[str, tuple[str, np.ndarray, float]]:
    """``{name: (cell, times, connect.period_s)}``: the bar's feeds but the fresh ones."""
    out = {f"early change step {j} x{r:g}": ("C2", _change(100.0, 325, j, r * 100.0), min(1, r) * 100)
           for j in range(2, 10) for r in (0.5, 2.0, 3.0)}
    out.update({"healthy 100": ("C3", np.arange(325) * 100.0, 100.0),
                "healthy 37": ("C3", np.arange(200) * 37.0, 37.0)})
    out.update({f"con111 {k}": ("C3", t, float(np.median(np.diff(t[:11]))))
                for k, (_, t) in con111_feeds().items()})
    rng = np.random.default_rng(SEED)
    for a in (0.1, 0.2, 0.25):
        for i in range(300):
            t = np.sort(np.arange(60) * 100.0 + rng.uniform(-a, a, 60) * 100.0)
            out[f"jitter {a:g} {i}"] = ("C3", t, 100.0)
    return out


def _fresh() -> dict[str, tuple[str, np.ndarray, float]]:
    """C4's feeds, drawn from seed 10266 in the bar's order: p, j, r."""
    rng = np.random.default_rng(FRESH_SEED)
    p = float(rng.uniform(20, 200))
    j = int(rng.integers(2, 10))
    r = float(rng.choice([0.5, 2.0, 3.0]))
    print(f"fresh: period {p:.6g} s, step {j}, x{r:g}", flush=True)
    return {f"fresh change step {j} x{r:g} of {p:.4g} s": ("C2", _change(p, 325, j, r * p), min(1, r) * p),
            f"fresh healthy {p:.4g} s": ("C3", np.arange(325) * p, p)}


def _said(feeds: dict, out: str) -> None:
    found = {}
    for name, (cell, times, period) in feeds.items():
        routes = {route: _connected(times, period, route) for route in ("server", "node")}
        found[name] = {"cell": cell, "file": _truth(times),
                       **{r: {"said": s, "missed": m} for r, (s, m) in routes.items()}}
    Path(out).write_text(json.dumps(found, indent=1))
    print(f"{len(found)} feeds written to {out}", flush=True)


def said(out: str) -> None:
    """The bar's feeds (module doc) -> OUT."""
    _said(_feeds(), out)


def fresh(out: str) -> None:
    """C4's feeds (seed 10266) -> OUT."""
    _said(_fresh(), out)


def _c2(route: str, mine: dict, file: dict) -> tuple[bool, str]:
    """C2 of one route: the file reader's stretches named at their rows, said at most one row late
    or when the period is learned; missed (server) its sum; period changes at its rows."""
    gaps = [(row, read) for kind, row, read in mine["said"] if kind in ("clock_gap", "rows missing")]
    changes = [row for kind, row, _ in mine["said"] if kind == "period changed"]
    named, want = sorted({row for row, _ in gaps}), [g[0] for g in file["gaps"]]
    timely = all(read <= row + 1 or (row <= LEARNED_AT and read == LEARNED_AT) for row, read in gaps)
    missed = mine["missed"] == sum(m for _, m in file["gaps"]) if route == "server" else True
    ok = named == want and timely and missed and changes == file["period"]
    return ok, (f"stretches {gaps} (file {want}), missed {mine['missed']} (file "
                f"{sum(m for _, m in file['gaps'])}), period changed {changes} (file {file['period']})")


def cells(base: str, this: str) -> None:
    """C1-C4 of the bar, per feed: THIS against the file reader and BASE (module doc)."""
    b, t = (json.loads(Path(p).read_text()) for p in (base, this))
    failed, later, jitter_said = {"C2": [], "C3": []}, 0, {"base": 0, "this": 0}
    for name, f in t.items():
        for route in ("server", "node"):
            mine, old = f[route], b[name][route]
            if f["cell"] == "C2":
                ok, note = _c2(route, mine, f["file"])
                base_ok, base_note = _c2(route, old, f["file"])
                print(f"{name} [C2] {route}: {'ok' if ok else 'FAIL'}; {note}\n    BASE "
                      f"{'ok' if base_ok else 'FAIL'}: {base_note}", flush=True)
            else:
                # (kind, row named) as a set of words (a clock_gap owed comes after the watch's
                # `time` of the same row); the row being read later only for a clock_gap
                now, was = sorted(map(tuple, mine["said"])), sorted(map(tuple, old["said"]))
                ok = (sorted(e[:2] for e in now) == sorted(e[:2] for e in was)
                      and mine["missed"] == old["missed"]
                      and all(e[0] == "clock_gap" or e in was for e in now))
                later += sum(e not in was for e in now)
                if name.startswith("jitter"):
                    jitter_said["this"] += len(mine["said"])
                    jitter_said["base"] += len(old["said"])
                if not ok or not name.startswith("jitter"):
                    print(f"{name} [C3] {route}: {'ok' if ok else 'FAIL'}; said {mine['said']} "
                          f"missed {mine['missed']} (BASE {old['said']} missed {old['missed']})",
                          flush=True)
            if not ok:
                failed[f["cell"]].append(f"{name} ({route})")
    print(f"jitter: events said BASE {jitter_said['base']}, here {jitter_said['this']}; C3 events "
          f"said later than BASE (clock_gap owed to the watch) {later}", flush=True)
    for cell, names in failed.items():
        print(f"{cell} failed {len(names)}: {names[:40]}{' ...' if len(names) > 40 else ''}", flush=True)
    print(f"feeds {len(t)}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"said": said, "fresh": fresh, "cells": cells}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
