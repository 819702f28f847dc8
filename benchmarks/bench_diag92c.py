"""A start lag accepted only where its gain holds within the campaigns (stop 92, diag92c; issue 34:
"diagnose ... never leaves a record's test error more than 2 % worse"; bench_diag92's trace).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag92c.py draws ROOT LABEL SET   # SET's draws -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag92c.py compare ROOT SET A B   # two labels' rows of SET: the bar's counts
    python benchmarks/bench_diag92c.py split CASE...          # each cleared start lag's two parts' p

``draws`` / ``compare``: bench_diag91b's (bench_diag91's ``diagnose_cases`` / ``compare``) on
:data:`SETS`: ``seen`` bench_diag92's ``scan`` draws (bench_diag91b's ``trace`` less few:4004, its
``seen``, the spent fresh 9336-9345 and 9436-9445), ``fresh`` the unspent seeds 9476-9485 (clean
9476-9479, planted 9480-9482, lag 9483-9485; bench_diag86's ``draw``, 12 campaigns, every 3rd test,
8 train).  ``split``: needs the rule's src (``git apply benchmarks/diag92c_rule.patch``): each
CASE (``kind:seed``) diagnosed as ``draws`` does; per target the test before -> after and every
start lag of a round with a family-wise p <= 0.01 and a within-rest gain >= 5 % (main's other
checks): its CV gain, within gain, the within part's p, the means part's p, and whether it clears.

The rule (``Search._split_clears``, asked of every lag from the initial state in the ``campaigns``
scheme, after main's checks)
-----------------------------------------------------------------------------------------------
A start lag's CV gain is split in two: WITHIN the held-out campaigns (each one's residual less its
mean) and in the campaigns' MEANS.  It clears only if one part holds on its own by the test of its
resolution: the within part by the test blocks (sign flips of the blocks' within MSE gains, ``p <=
alpha`` and, on blocks finer than the campaigns, the margin's p <= alpha: a within gain of
``min_gain_pct`` with confidence), or the means part by the campaigns (each campaign's gain in its
squared mean as a share of its MSE, clipped to [-1, 1], sign flips by campaign, exact: p >= 1/256
with 8).  Both are main's own tests (``_flip_pvalues``, ``sign_flip_pvalues``); no threshold was
read off the seen rows (``alpha`` and ``min_gain_pct`` are the options').  Decided from the
mechanism and checked on bench_diag92's trace rows before the bar (probe, this tree):
planted:8969 E_X's T_bearing_f1 7200 s lag: within p 1e-4 but its margin fails, means p 0.0156 ->
refused, E_X stays 0.8041 (main 0.9789); planted:8885 E_Y's round-2 T_motor1 lag: within p 0.02,
means p 1/128 (all 8 campaigns) -> kept (E_Y 1.4571 as main); lag:9289 / 9443 E_X's T_box1 lags
(within p 5e-5) kept; lag:9443 E_Y's T_bearing_f3 lag (within 38.5 %, p 5e-5) kept: its harm is
the split (bench_diag92), which no train-side rule sees.

The bar (written BEFORE any run of either tree on the fresh seeds 9476-9485; all must hold, else
REFUSED: src reverted, this bench and ``diag92c_rule.patch`` kept)
-----------------------------------------------------------------------------------------------
1. FRESH 9476-9485 (clean 9476-9479, planted 9480-9482, lag 9483-9485): no (draw, target) row
   more than 2 % worse than main.
2. FRESH clean 9476-9479 accept nothing on any target.
3. FRESH planted 9480-9482: the position found wherever main finds it.
4. SEEN (``seen``): the harm rows planted:8969 E_X and lag:9443 E_Y no longer > 2 % worse than
   before the diagnosis, or said why not; no seen row more than 2 % worse than main.
5. tests/*/test_diag*.py pass (three parts, ``-n 2``).

Scored (2026-12-05, 2 cores shared; main = 2b918bfd's src (``git archive`` under /tmp/diag92c/main),
rule = this branch's src before the revert (= main + ``diag92c_rule.patch``); ``seen`` once per
tree, main first)
-------------------------------------------------------------------------------------------------
``seen`` (70 draws, 210 rows): position found on 27 draws in both; clean draws accepting the same
(8075 / 8170 / 8178, main's spurious start lags); the control clears on lag:9343 E_Z in both (as
bench_diag92 read, deciding nothing).  Three rows differ (test RMSE µm, before; main | rule)::

  planted:8969 E_X  0.8041; 0.9789 T_bearing_f1 7200 s +init | 0.8041 nothing          -17.9 %
  planted:9103 E_Y  2.9079; 1.4766 position + T_motor2 3600 s +init | 2.1593 position  +46.2 %
  planted:9266 E_X  0.6664; 0.6764 T_nose 14400 s +init | 0.6758 T_box1 14400 s +init  -0.1 %

``split`` (rule's src) on the rows: 9103 E_Y's round-2 T_motor2 start lag (CV gain 43.4 %, within
18.0 %, round 2 on 8 blocks, one per campaign) reads within p 0.078 and means p 0.0156 (7 of 8
campaigns): refused, and the test error it took from main's 1.4766 back to 2.1593.  The other
seen harms clear BOTH parts, so the rule keeps them: 8457 E_X (T_amb 7200 s: within 16.5 %, p
0.0039; means p 0.0156), 9046 E_X (within 40.9 %, p 5e-5; means 1/256), 9342 E_X (37.2 %, 5.5e-4;
2/256), 8170 E_X (6.5 %, 2e-4; 1/256), 8178 E_Z (11.1 %, 0.0039; 2/256), 8075 E_Y (14.1 %, 0.002;
1/256), 9443 E_Y (38.5 %, 5e-5; 2/256: bench_diag92's split, which no train-side rule sees).  Only
8969 E_X's lag fails both (within p 1e-4 but its 5 % margin not; means 0.0156).  The harms' means
part is as consistent over the 8 held-out train campaigns as a real effect's: the campaigns' test
cannot tell them apart either (bench_diag92: they gain in 7-8 of 8).  CPU (diagnose, ``seen``):
46.1 s main, 50.0 s rule.

Bar: 4 fails (9103 E_Y +46.2 % against main; and 7 of the 8 seen harm rows kept, 9443 E_Y
said why); so the rule is REFUSED without scoring the fresh seeds: 9476-9485 are UNSPENT.  The
test (tests/apps/test_diagnose_start_lag92c.py, in the patch: 8969 E_X refused and 8885 E_Y's
round-2 lag kept) failed on 2b918bfd (main takes 8969's lag) and passed on the rule; items 1-3 and
5 were not run.

**REFUSED** (src as on main; the rule and its test in ``benchmarks/diag92c_rule.patch``).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402
from bench_diag91 import compare, diagnose_cases  # noqa: E402 (the same rows)
from bench_diag91b import SETS as SETS_91B  # noqa: E402
from bench_diag92 import FRESH_SPENT  # noqa: E402

SETS = {
    "seen": [c for c in SETS_91B["trace"] if c[0] != "few"] + SETS_91B["seen"] + FRESH_SPENT
            + SETS_91B["fresh"],
    "fresh": ([("clean", s) for s in range(9476, 9480)] + [("planted", s) for s in range(9480, 9483)]
              + [("lag", s) for s in range(9483, 9486)]),
}


def _dataset(kind: str, seed: int):
    from bench_diag86 import draw

    return draw(kind, seed, 12), None


def draws(root: str, label: str, name: str) -> None:
    """:data:`SETS` ``name`` diagnosed -> ``ROOT/NAME-LABEL.jsonl`` (bench_diag91's rows)."""
    diagnose_cases(root, label, name, SETS[name], _dataset)


def split(*cases: str) -> None:
    """Each start lag's two parts (module doc; the rule's src)."""
    from bench_diag92 import _diagnosed, _rounds

    for case in cases:
        _, d, _ = _diagnosed(case)
        for target, x in d.targets.items():
            j = d.to_json(target)
            print(f"{case} {target}: test {j['before']['test_rmse']:.4f} -> {j['after']['test_rmse']:.4f} "
                  f"{[ev.effect.title[:40] for ev in x.accepted]}")
            for rnd, _ in _rounds(x):
                for ev in sorted(rnd.evaluated, key=lambda e: -e.gain):
                    if (getattr(ev, "p_within", None) is not None and (ev.gain_pct_within_rest or 0) >= 5
                            and (ev.p_family or 1) <= 0.01):
                        mark = "*" if ev.accepted else " "
                        print(f"  round {rnd.step} {mark} {ev.effect.title[:50]:50s} gain {ev.gain_pct:5.1f} "
                              f"within {ev.gain_pct_within:5.1f} p_within {ev.p_within:.2g} "
                              f"p_means {ev.p_between:.3g} clears {ev.clears_bar}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"draws": draws, "compare": compare, "split": split}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
