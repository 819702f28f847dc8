"""The last two seen rows diagnose leaves > 2 % worse after diag100 (planted 9342 E_X +13.9 %,
lag 9443 E_Y +13.3 %), traced on the TRAIN reads of their accepted effect, and the start lag's
within / pooled bound raised from 2/3 to 0.93: REFUSED (fresh lag 9959 E_Y's real start lag reads
0.70; ``benchmarks/diag101_rule.patch``) (stop 101, diag101; issue 34: "diagnose ... never leaves a
record's test error more than 2 % worse"; bench_diag100's seen draws and reads).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag101.py trace ROOT SET     # accepted effects' reads -> ROOT/trace-SET.jsonl
    python benchmarks/bench_diag101.py draws ROOT LABEL SET   # SET's draws -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag101.py default ROOT LABEL     # make run's -> ROOT/default-LABEL.jsonl
    python benchmarks/bench_diag101.py bar ROOT MAIN RULE     # the bar below on two labels' rows

:data:`SETS`: ``seen`` bench_diag92's 70 draws (bench_diag100's), ``harms`` the two of them left
> 2 % worse (planted 9342, lag 9443), ``default`` make run's scenario (bench_diag98's), ``fresh``
9956-9960 (clean 9956-9957, planted 9958, lag 9959-9960: bench_diag100's kinds, the lag kind twice,
where a real start lag can be lost).  ``trace`` is bench_diag100's (reads of each accepted effect in
its round: gain, p, campaigns gaining, means share, within / pooled, extrapolation); ``draws`` /
``default`` bench_diag91's / bench_diag98's rows.  MAIN = 5586e97a's src (``git archive``; its
diagnose package equals diag100's 06ec96fb, so bench_diag100's ``rule`` rows are main's seen and
default rows).

The trace (2026-12-06, 5586e97a; bench_diag100's ``table ROOT seen,default`` and ``spent``)
-----------------------------------------------------------------------------------------
Each of the two rows takes ONE effect, a round-1 start lag on 8 train campaigns, gaining in all 8::

  row (test %)            effect (tau, dirs)        gain  p       p_fam   b   camps top1 means w/p  out gout
  planted:9342 E_X +13.9  T_bearing_f1 1800 s (2)   45.1  5.0e-05 5.0e-05 21  8/8  0.34 0.60 0.82  3  0.52
  lag:9443 E_Y     +13.3  T_bearing_f3 3600 s (3)   42.9  5.0e-05 3.5e-04 19  8/8  0.33 0.45 0.90  5  0.45

Against the helpful start lags (``table``): gain, p_fam, camps, top1, late campaigns, outside /
gout overlap as in bench_diag100; only within / pooled (w/p) separates the ROUND-1 start lags on 8
train campaigns: harms 0.28-0.90 (these two the highest, 0.825 / 0.897), helpful real lags 0.963
(spent lag 9838 E_X) .. 1.302 over 14 seen + 6 spent (9343 0.980, 9444 0.981, 9839 0.980, 9840
0.991, 9345 0.994).  Helpful start lags under the bound: round 2 after a position effect (8885
0.27, 9103 0.42, spent 9810 0.60, 9836 0.59: diag100 refuses them already), spent planted 9811 E_X
0.46 (refused by diag100), spent lag 9813 E_Y (T_motor2 14400 s, -2.2 %) 0.699: the one a higher
bound newly refuses (outside the bar).  make run's E_Y reads 0.76 on 16 campaigns, where the means
are resolved and the bound is not asked.  The effects are fast sensors' lags (tau 1800 / 3600 s;
the real ones 7200-14400 s), but tau is the simulator's design, no general read: not used.

The rule (``search.START_WITHIN_SHARE`` 2/3 -> 0.93; diag100's clause in ``Search._within_checks``,
no key): the bound between the highest harm (0.897) and the lowest helpful round-1 lag (0.963),
READ OFF the seen and spent rows, 0.033 from each: the fresh draws judge it.

The bar (committed BEFORE the fresh seeds 9956-9960 are drawn; the rule judged on it as is)
-----------------------------------------------------------------------------------------
A row is (draw, target), its change diagnose's own, 100 (after / before - 1) % as run.
G1 seen (70 draws, 210 rows): rows > 2 % worse 2 (main) -> <= 1 (rule), and no row > 2 % worse
under the rule that main has <= 2 %.  G2 the 44 rows main helps (change < 0): the rule's mean gain
>= 47 %; make run's scenario (seed 0) E_Y: the rule's change within 1 point of main's (-25.3 %).
G3 FRESH 9956-9960 (15 rows), scored ONCE after this bar: the rule's rows > 2 % worse <= main's,
and its mean change <= main's + 1 point.  G4 tests/apps/test_diagnose_few.py passes with the rule
(the planted position effect with 8 train campaigns accepted).  All: KEPT (src, a test failing on
5586e97a, docs/diagnose.md); else REFUSED (``benchmarks/diag101_rule.patch``, src reverted).

Measured (2026-12-06; MAIN = 5586e97a's src, RULE = 49ea75f5's; nice, 2 cores shared, load ~20)
-----------------------------------------------------------------------------------------------
The bar at 49ea75f5 (19:05 UTC); then the seen / default / harms rule runs (19:05-19:10), fresh main
(19:07-19:08) and fresh rule (19:12-19:13), scored once; bar and rule unchanged.  MAIN's seen and
default rows are bench_diag100's ``rule`` rows (06ec96fb; the diagnose package unchanged since).
CPU: ``draws seen`` rule 84.6 s (5.5 min wall); ``default`` rule 8.0 s; ``trace harms`` rule 5.2 s;
``draws fresh`` main 8.3 s, rule 7.6 s; ``trace fresh`` with MAIN's src 7.9 s (after the score).

``bar /tmp/diag101/rows main rule``::

  seen lag:9443 E_Y: +13.3 -> -0.5 %
  seen planted:9342 E_X: +13.9 -> +19.4 %
  fresh lag:9959 E_X: -1.8 -> +0.0 %
  fresh lag:9959 E_Y: -37.1 -> +0.0 %
  G1 seen rows > 2 % worse 2 -> 1 [('planted:9342', 'E_X')] (<= 1, none new): met
  G2 seen helpful rows' mean gain (44 rows) 49.37 -> 49.37 (>= 47): met
  G2 make run's E_Y -25.3 -> -25.3 % (within 1 point): met
  G3 fresh rows > 2 % worse 0 [] -> 0 []: met
  G3 fresh mean change (15 rows) -7.17 -> -4.57 %: FAILS

G4 ``pytest -n 0 tests/apps/test_diagnose_few.py`` with the rule: 17 passed (met).  The bar FAILS
on G3: **REFUSED**.  ``trace harms`` (rule): 9443 E_Y takes T_motor1's 7200 s start lag (w/p 1.02,
test -0.5 %); 9342 E_X takes T_amb's 7200 s start lag (w/p 0.98, gain 43.2 %, 8/8 campaigns) and
goes +13.9 -> +19.4 %: the bound moves the harm to the next start lag, which reads like a real one.
``trace fresh`` (MAIN's src, after the score, explains only): lag 9959 E_Y's real T_motor1 14400 s
start lag, round 1, gain 55.8 %, 8/8 campaigns, reads w/p 0.70 (means 0.75), E_X's T_amb 14400 s
0.87 (-1.8 %); the lowest helpful round-1 read was 0.963 on the seen and spent lag draws.  No bound
on within / pooled separates: harms 0.28-0.98 (with 9342's second choice), real round-1 lags
0.46-1.30.  The rule and its test (test_diagnose_startshare100's ~0.84 candidate refused where
unresolved; fails on 5586e97a, 4 passed with the rule) are ``benchmarks/diag101_rule.patch``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402
from bench_diag100 import SETS as SETS_100  # noqa: E402

SETS = {"seen": SETS_100["seen"], "default": SETS_100["default"],
        "harms": [("planted", 9342), ("lag", 9443)],
        "fresh": ([("clean", s) for s in (9956, 9957)] + [("planted", 9958)]
                  + [("lag", s) for s in (9959, 9960)])}


def trace(root: str, name: str) -> None:
    """bench_diag100's trace of :data:`SETS` ``name`` -> ``ROOT/trace-NAME.jsonl``."""
    import bench_diag100

    bench_diag100.trace(root, name, SETS[name])


def draws(root: str, label: str, name: str) -> None:
    """:data:`SETS` ``name`` diagnosed -> ``ROOT/NAME-LABEL.jsonl`` (bench_diag91's rows)."""
    from bench_diag91 import diagnose_cases
    from bench_diag92c import _dataset as draw_12

    diagnose_cases(root, label, name, SETS[name], draw_12)


def bar(root: str, main: str, rule: str) -> None:
    """The bar (module doc) on ``ROOT/{seen,fresh,default}-{MAIN,RULE}.jsonl``; G4 is a pytest run."""
    from bench_diag98 import _changes, fresh_items, print_moved, seen_worse

    seen, _ = seen_worse(root, main, rule)
    worse = {n: {k for k, v in seen[n].items() if v > 2.0} for n in seen}
    items = [(f"G1 seen rows > 2 % worse {len(worse[main])} -> {len(worse[rule])} {sorted(worse[rule])} "
              f"(<= 1, none new)", len(worse[rule]) <= 1 and worse[rule] <= worse[main])]
    helpful = [k for k, v in seen[main].items() if v < 0]
    g = {n: -float(np.mean([seen[n][k] for k in helpful])) for n in seen}
    items.append((f"G2 seen helpful rows' mean gain ({len(helpful)} rows) {g[main]:.2f} -> {g[rule]:.2f} "
                  f"(>= 47)", g[rule] >= 47.0))
    dflt = {n: _changes(root, "default", n)[("default:0", "E_Y")] for n in (main, rule)}
    items.append((f"G2 make run's E_Y {dflt[main]:+.1f} -> {dflt[rule]:+.1f} % (within 1 point)",
                  abs(dflt[rule] - dflt[main]) <= 1.0))
    print_moved("seen", seen[main], seen[rule])
    items += [(f"G3 {text[4:]}", ok) for text, ok in fresh_items(root, main, rule, 5)]
    for text, ok in items:
        print(f"  {text}: {'met' if ok else 'FAILS'}")
    print(f"  bar ({len(items)} of 5 items read here; G4 is tests/apps/test_diagnose_few.py): "
          f"{'HOLDS' if len(items) == 5 and all(ok for _, ok in items) else 'FAILS or incomplete'}")


def main(argv: list[str]) -> int:
    from bench_diag98 import default

    return run_commands(__doc__, {"trace": trace, "draws": draws, "default": default, "bar": bar},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
