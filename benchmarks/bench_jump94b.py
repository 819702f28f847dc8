"""A blind sensor's level shift caught by two windows, built (jump94b, issue 34; follow-up of
``bench_jump94.py``, whose prototype ``settled`` passed its bar but was not built).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's
monitor as built -- main's src, or this branch's with the rule)::

    python benchmarks/bench_jump94b.py fl ROOT                      # fl_thermal planted / healthy
    python benchmarks/bench_jump94b.py flbar MAIN_ROOT RULE_ROOT    # clause (c)
    python benchmarks/bench_jump94b.py trace ROOT RECORDS           # bench_step93's trace
    python benchmarks/bench_jump94b.py healthy ROOT RECORDS         # bench_step93's healthy
    python benchmarks/bench_jump94b.py steps MAIN_ROOT RULE_ROOT    # clause (a) / (d)
    python benchmarks/bench_jump94b.py events MAIN_ROOT RULE_ROOT   # clause (b) / (d)

``fl``: bench_jump94's ``fl`` with the tree's own monitor (its RULE ``main``: the tree as it is)
-> ``ROOT/fl-main.json``; ``flbar``: bench_jump94's clause (c), MAIN_ROOT's file (main's src)
against RULE_ROOT's (this branch's).  ``trace`` / ``healthy``: bench_step93b's (the tree's own
monitor) -> ``ROOT/trace-main.json`` / ``ROOT/healthy-main.json``; ``RECORDS`` as there
(``lr9699,...,cr9708``).  ``steps``: the planted cells of MAIN_ROOT against RULE_ROOT under
bench_jump94's clause (a) (mean d NOT above main's, to 4 decimals -- bench_step93b's ``steps``
asks strictly below -- and no cell past main's d + log(1.02)); ``events``: bench_step93b's.

The rule as built (``src/thermocomp/apps/deploy/surveillance/settled.py``; the numpy mirror
``CodeMonitor._settled``, the C ``mon_settled`` / ``TC_MON_SETTLED``): bench_jump94's prototype,
one change found on main's suites before any fresh seed: the ring holds each sample's row of the
monitor's window (the reading on its reference, NaN beyond its range: no measurement), not the
raw reading less the reference.  With the raw reading, tests/apps/test_monitor_leak81.py failed:
a nut out of range at +13 K for 150 samples, back on its true reading, read its return as a
settled -13 K step and was re-referenced by it.  The served monitor keeps a ring of the last
``2 window - 1`` rows per sensor in its state (``_settle``, ``_settle_age``: samples since the
sensor's reference moved); the fast block stops before a row on which the rule fires.  The ST
does not hold the rule (st_watch's docstring says so: the ST holds no exclusion nor
reconstruction either).  No key: the rule is on wherever a sensor no other predicts has a finite
training separation (bench_jump94's bar decides; a pickled monitor from before has none).

BAR: bench_jump94's, unchanged (written there before its fresh seeds; quoted), scored ONCE on
FRESH lr9699-9703, cr9704-9708 (bench_bar91b's ten-seed cycle ``commands_on(9699)``: five long
records, five climate rooms), main = 51493fa9's src (``git archive``), the rule = this branch:
(a) fresh planted steps (``trace``, every monitored sensor, k in 0.5 / 1 / 2 / 2.9 x its
    training step): no cell with d_rule > d_main + log(1.02), mean d not above main's (4 dp);
(b) fresh healthy (``healthy``): 0 new sensor events, d not above main's on any record;
(c) fl_thermal (seen): the healthy record quiet (0 sensor events, Σ² = main's to 0.01 µm²); of
    the 15 T_t16 cells, every step of |size| >= 2 degC caught at every onset, no cell with d past
    main's + log(1.02), mean d below main's;
(d) seen simulated (``trace`` / ``healthy`` on bench_step93b's seen records, and 9661-9665 now
    seen): as (a) and (b).
KEPT only if all four hold, with src (served + numpy mirror + C), tests failing on main and
docs; else REFUSED (``benchmarks/jump94b_rule.patch``).  Bench_bar91b's ``score`` / ``table``
rows are not part of bench_jump94's bar (it says why: a rule for a noisy blind sensor): not run.

Measured (2026-12-05)
---
(filled in below after the runs)
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_jump94 as jump94  # noqa: E402
import bench_step93b as step93b  # noqa: E402
from _cli import run_commands  # noqa: E402


def fl(root: str) -> None:
    """bench_jump94's ``fl`` of the tree's own monitor -> ``ROOT/fl-main.json``."""
    jump94.fl(root, "main")


def flbar(main_root: str, rule_root: str) -> None:
    """Clause (c): MAIN_ROOT's ``fl-main.json`` against RULE_ROOT's, bench_jump94's ``flbar``."""
    both = Path(rule_root) / "flbar"
    both.mkdir(parents=True, exist_ok=True)
    for src, name in ((main_root, "fl-main.json"), (rule_root, "fl-settled.json")):
        (both / name).write_text((Path(src) / "fl-main.json").read_text())
    jump94.flbar(str(both))


def trace(root: str, labels: str) -> None:
    """bench_step93b's ``trace`` of the tree's own monitor -> ``ROOT/trace-main.json``."""
    step93b.trace(root, labels)


def healthy(root: str, labels: str) -> None:
    """bench_step93b's ``healthy`` of the tree's own monitor -> ``ROOT/healthy-main.json``."""
    step93b.healthy(root, labels)


def steps(main_root: str, rule_root: str) -> None:
    """Clause (a): the planted cells, mean d not above main's, none past main's d + log(1.02)."""
    a, b = (json.loads((Path(r) / "trace-main.json").read_text()) for r in (main_root, rule_root))
    rows = [(rec, name, ca, cb) for rec in a for name in a[rec]
            for ca, cb in zip(a[rec][name], b[rec][name])]
    da, db = np.array([r[2]["d"] for r in rows]), np.array([r[3]["d"] for r in rows])
    far = [r for r, x, y in zip(rows, da, db) if y > x + np.log(1.02)]
    print(f"{len(rows)} cells: mean d {da.mean():.4f} -> {db.mean():.4f}; detected "
          f"{sum(r[2]['detected'] for r in rows)} -> {sum(r[3]['detected'] for r in rows)}; "
          f"cells past main's d + log(1.02): {len(far)}")
    for rec, name, ca, cb in rows:
        if abs(cb["d"] - ca["d"]) > 1e-6:
            print(f"  {rec} {name} {ca['k']:g}x ({ca['size']:.3g} degC): d x 100 {100 * ca['d']:.2f}"
                  f" -> {100 * cb['d']:.2f}; detected {ca['detected']} -> {cb['detected']}")
    for rec, name, ca, cb in far:
        print(f"  PAST: {rec} {name} {ca['k']:g}x d x 100 {100 * ca['d']:.2f} -> {100 * cb['d']:.2f}")
    print(f"(a) {'MET' if round(db.mean(), 4) <= round(da.mean(), 4) and not far else 'FAILS'}")


def events(main_root: str, rule_root: str) -> None:
    """Clause (b): bench_step93b's ``events`` (the true records' sensor events and d)."""
    step93b.events(main_root, rule_root)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"fl": fl, "flbar": flbar, "trace": trace, "healthy": healthy,
                                  "steps": steps, "events": events}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
