"""A fast ramp of a sensor no other predicts is not a settled step (settle95, issue 34; follow-up
of ``bench_jump94b.py``, whose ``settled`` rule re-references a blind sensor whose last window
lies wholly off the window before by more than 3 x its largest training separation).
KEPT: the bar below (committed in f1f17de0 before the fresh seeds) met on fresh lr9739-9743 /
cr9744-9748, scored once, and on the seen cells; served, numpy mirror and C alike.  Fault (2)
(fl_thermal's +1 degC T_t16 at mid-test) TRACED, not mended: not a warming trend (below).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's
monitor as built -- main's src, or this branch's with the rule)::

    python benchmarks/bench_settle95.py ramp                        # the seen ramp (fault 1)
    python benchmarks/bench_settle95.py fl ROOT                      # fl_thermal planted / healthy
    python benchmarks/bench_settle95.py flbar MAIN_ROOT RULE_ROOT    # clause (c)
    python benchmarks/bench_settle95.py trace ROOT RECORDS           # bench_step93's trace
    python benchmarks/bench_settle95.py healthy ROOT RECORDS         # bench_step93's healthy
    python benchmarks/bench_settle95.py steps MAIN_ROOT RULE_ROOT    # clause (a) / (d)
    python benchmarks/bench_settle95.py events MAIN_ROOT RULE_ROOT   # clause (b) / (d)

``ramp``: tests/shell/test_export_cmon82c's machine and ramp (``T_u``, no other sensor predicts
it, ramps down 0.8 degC a row from row 41 for 20 rows and back as fast; adaptive MLR, no
fallback), streamed by the tree's served monitor: ``T_u``'s events, and at every sample where
its windows part past the limit, the separation, the windows' median difference, the larger of
their median absolute deviations and their ratio.  The other commands are bench_jump94b's (the
tree's own monitor; use separate ROOTs for ``trace`` and ``healthy``: each makes its ROOT anew).
Main's src for MAIN_ROOT: ``git archive 34af1fcb src conf | tar -x -C /tmp/main``, then
``PYTHONPATH=/tmp/main/src`` (``trace`` / ``healthy`` link the tree's ``conf/`` in).

Trace on SEEN records, before the rule (main = 34af1fcb):
Fault (1), ``ramp``: main re-references ``T_u`` at row 63 by -9.77 degC (out since row 58 for
explaining ``T_b``'s band) and at row 80 by +8.81 degC: separations 1.02 / 1.01 degC past the
limit 0.995 degC (3 x 0.33), the windows' median difference over their larger median absolute
deviation (MAD) 9.77 / 2.34 = 4.2 and 8.81 / 2.41 = 3.7 (a straight ramp over ``w`` samples:
median difference ``w`` x its rate, each window's MAD ``w / 4`` x it: ratio 4).
fl_thermal's planted ``T_t16`` cells at the sample main fires (onset + 9): the ratio is 11.1 /
21.3 / 31.5 / 52.0 / 29.8 at 240 (+1 / +2 / +3 / +5 / -3 degC), 13.2-32.2 at 556, 8.5-45.9 at
900: the smallest of the 14 caught cells 8.5 (+1 degC at 900).  In T_t16's training part the
ratio reaches 11.6 where the windows do not part past the limit (the separation decides there).
Fault (2), the +1 degC at 556 main misses: NOT warming.  T_t16's least-squares trend over the 200
samples around it is -0.001 degC a sample (flat); the windows' separation is 0.354 degC against
the limit 0.362 (3 x 0.121): the noise of the two windows' extremes (spreads 0.68 / 0.64 degC,
the widest of the three onsets), the median difference 1.086.  Removing a common trend does not
reach it; a statistic that reads medians (not extremes) would, but it changes the limit's
training statistic (every blind sensor's limit, the C's constants): not tried in this stop.

The rule (``src/thermocomp/apps/deploy/surveillance/settled.py``: ``steadiness``, ``STEADY``;
numpy mirror ``CodeMonitor._settled``, C ``mon_settled`` with ``MON_SETTLE_STEADY``, exported
as ``settle_steady``; an export before it has none: 0, the rule as before): main's, and also the
windows' median difference past ``STEADY`` = 6 x the larger of their MADs.  6 sits between a
straight ramp's 4 (analytic; 3.4-4.2 on the seen ramp) and the smallest seen caught fl cell's
8.5, chosen on those seen numbers only.  No key.  The rule can only fire where main fires: it
cannot catch more, only fewer.

BAR (committed before the fresh seeds were simulated; fresh = lr9739-9743, cr9744-9748,
bench_bar91b's ten-seed cycle ``commands_on(9739)``, drawn true; main = 34af1fcb's src):
(r) seen ramp (``ramp``): ``T_u`` never re-referenced (main: twice, -9.77 / +8.81 degC); the
    numpy mirror and the compiled C (gcc -Werror) give the served corrections on every row
    (tests/shell/test_monitor_settled95.py);
(a) fresh planted steps (``trace``): no cell with d_rule > d_main + log(1.02), mean d not above
    main's (4 dp), detected not below main's;
(b) fresh healthy (``healthy``): 0 new sensor events, d not above main's on any record;
(c) fl_thermal (seen): the healthy record quiet (0 sensor events, Σ² = main's 83.90 to 0.01
    µm²); main's 14 caught T_t16 cells still caught, no cell with d past main's + log(1.02);
(d) seen simulated (``trace`` on lr9699-9703 / cr9704-9708, jump94b's fresh, now seen, whose 9
    moved cells are blind steps main's rule catches; ``healthy`` on bench_step93b's 15 seen
    records): as (a) and (b).
KEPT only if all hold, with src (served + mirror + C), tests failing on 34af1fcb and docs; else
REFUSED (``benchmarks/settle95_rule.patch``).  Fault (2) is TRACED above, not in the bar.

Measured (2026-12-06; main = 34af1fcb's src and conf under /tmp, the rule = this branch at
f1f17de0; under a load of ~6-10 on 2 cores)
---
(r) ``ramp``: main re-references ``T_u`` at row 63 (-9.77 degC) and row 80 (+8.81), re-admitted
    at row 68; the rule: three samples part past the limit (ratios 4.18, 3.42, 3.66), none
    re-referenced; ``T_u`` out at row 58 for its leak, back at row 75, its reference unmoved.
    tests/shell/test_monitor_settled95.py: mirror and compiled C = served on every row: MET.
(c) ``fl`` / ``flbar`` (seen): every one of the 16 lines equal to main's (Σ², d, events):
    healthy 83.90 = 83.90 µm², 0 sensor events; the 14 caught cells caught at +9 as main's;
    mean d x 100 3.39 = 3.39; 0 cells past main's d + log(1.02); +1 degC at 556 missed by both.
    (``flbar`` prints "(c) FAILS": bench_jump94's (c) asked mean d strictly below main's; this
    bar's (c) asks the 14 still caught and none past: MET.)
(d) seen ``trace lr9699-9703,cr9704-9708``: 520 cells, every cell equal to main's (mean d 0.1586
    = 0.1586, detected 175 = 175, 0 past); ``healthy`` on bench_step93b's 15 seen records:
    events and d as main's on every one (column9316's 188, lr9430's 3), 0 new: MET.
Fresh, scored once (lr9739-9743, cr9744-9748):
(a) ``trace``: 520 cells, every cell equal to main's: mean d 0.1487 = 0.1487, detected 164 =
    164, 0 cells past main's d + log(1.02): MET.
(b) ``healthy`` / ``events``: the 10 true records 0 sensor events under both, d 0 on both: MET.
CPU: fresh trace main 146.7 s, rule 192.0 s; healthy 10.3 / 11.3 s; seen trace 154.5 / 199.9 s,
healthy 15.7 / 18.9 s; ``ramp`` 2 s; fl 16 monitor runs ~3 s each.  The rule left every simulated
and fl cell as main's (it can only withhold main's re-references); its one measured effect is
the ramp of (r).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_jump94b as jump94b  # noqa: E402
from _cli import run_commands  # noqa: E402


def ramp() -> None:
    """The seen ramp (module doc): ``T_u``'s events and the two windows' statistics."""
    import tempfile
    sys.path[:0] = [str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
    from test_export_cmon82c import _deployed, _machine, _served_moves
    from thermocomp.apps.deploy.surveillance import settled
    judge = settled.Settled._settled

    def watched(self, x, time, events):
        cols = self._settle_cols
        if self._ref is not None and len(cols):
            rows = np.vstack([self._settle[:, cols], x[cols] - self._ref[cols]])
            sep = settled.separation(rows, self.window)[0]
            med = np.median(rows[self.window:], 0) - np.median(rows[:self.window], 0)
            mad = [np.median(np.abs(r - np.median(r, 0)), 0)
                   for r in (rows[:self.window], rows[self.window:])]
            for k in np.flatnonzero(sep > self._settle_lim[cols]):
                spread = max(mad[0][k], mad[1][k])
                print(f"  t {time:7.0f} s  {self.names[cols[k]]}: separation {sep[k]:.3f} "
                      f"(limit {self._settle_lim[cols[k]]:.3f}), median difference {med[k]:+.3f}, "
                      f"larger MAD {spread:.3f}, ratio {abs(med[k]) / spread:.2f}")
        judge(self, x, time, events)

    settled.Settled._settled = watched
    with tempfile.TemporaryDirectory() as tmp:
        deployed, frame = _deployed(_machine(Path(tmp) / "data"), "none")
        for row, to, why in _served_moves(deployed, frame):
            print(f"row {row}: T_u {to}: {why[:90]}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"ramp": ramp, "fl": jump94b.fl, "flbar": jump94b.flbar,
                                  "trace": jump94b.trace, "healthy": jump94b.healthy,
                                  "steps": jump94b.steps, "events": jump94b.events},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
