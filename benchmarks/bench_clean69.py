"""Clean fresh seed 6953's lag from the initial state, accepted by the shipped diagnose: the harm
measured on new campaigns, traced, and one rule measured against a bar written before it was
scored (issue 34 item 4; stop 69, clean69).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_clean69.py moretest CASE ...    # own test and 24 new campaigns
    python benchmarks/bench_clean69.py trace CASE ...       # the accepted lag's CV residual, per campaign
    python benchmarks/bench_clean69.py campaigns CASE ...   # every candidate's within gain, less the best
    python benchmarks/bench_clean69.py fresh ROOT           # bench_planted69's fresh -> ROOT/fresh.jsonl
    python benchmarks/bench_clean69.py compare BASE NEW     # the bar's counts of two trees

CASE: ``bench_diagnose_memory``'s (``clean:SEED`` / ``planted:SEED``); ``campaigns`` also
``LAGROOT::machine:NAME[::OVERRIDE...]``.  ``moretest``: bench_moretest68's ``few_again`` draws
(the same machine, the record's own clean law) of the fresh seeds ``NEW_SEEDS`` (12 campaigns each,
all test), scored as bench_moretest68's rows.  BASE / NEW: roots holding ``moretest.jsonl``
(``bench_moretest68.py rows /tmp/moretest68-root ROOT``, all groups) and ``fresh.jsonl``.

Is the harm real (``moretest clean:6953``, main f8a12479, before the rule)
-------------------------------------------------------------------------
Accepted: the 1 h lag of the inputs from the initial thermal state (2 directions, 12 regressors).
Test RMSE (µm) before -> after: own 4 campaigns 0.5969 -> 0.6998 (+17.2 %); 24 new campaigns
(seeds 6981, 6982) 0.6884 -> 0.8063 (+17.1 %, 90 % resampled interval [+7.1, +25.5], per draw
+14.3 / +20.6; 16 campaigns > 2 % worse, 3 better).  Real.  On the new campaigns the harm is all in
their means: each campaign's mean error squared (row-weighted) 0.269 -> 0.437 µm², the error
about the means 0.1876 -> 0.1888 (most means pushed further the way they already were:
N1_K01 +0.73 -> +1.09, N1_K07 -0.95 -> -1.24, N2_K12 +0.58 -> +1.05 µm).

Why it clears (``trace clean:6953``, ``campaigns clean:6953``, the same code)
---------------------------------------------------------------------------
14 ranked blocks of ~30 samples over the 8 train campaigns; the lag gains 12.9 % of the CV RMSE
(family-wise p 0.0011, margin p 0.0043).  Its CV MSE split: the held-out campaigns' means
0.0917 -> 0.0479 µm², within them 0.2360 -> 0.2008 (within gain 7.7 % of the RMSE, so
initlag67 / within67's check, >= 5 %, passes).  It is not the start transient: the first hour of
each campaign gains nothing (0.0400 -> 0.0413 µm² of the pooled within MSE; K01's first hour
0.132 -> 0.405), the rest does (1-3 h 0.0739 -> 0.0625, after 3 h 0.1221 -> 0.0970).  And it is
one campaign's: K11 (the longest, 7.8 h, the largest within error 0.370 µm²) falls to 0.192 and
carries 86 % of the pooled within gain; without K11 the within gain is 1.5 %; 5 of 8 campaigns
gain within at all.  K11's 3 blocks are the 3 largest block gains (0.586 -> 0.293, 0.368 -> 0.243,
0.325 -> 0.145), so the signed ranks and the margin count that one campaign three times.  The
same round's single-input lags from the initial state (q 3-4, 7-10 % in CV, 3.4-4.6 % within)
have 102-124 % of their within gain in K11.

The within gain less the campaign gaining most there, on the candidates of >= 5 % CV gain that
clear with the shipped code, of the cases traced (``campaigns`` clean:6953 clean:6757 clean:4004
planted:4002 planted:4012 planted:4004 planted:626 planted:6941 planted:6945, grinder-nocoolant
5687 and 5682; w: within %, r: without the best campaign %)::

  clean 6953   inputs' 1 h lag + init (12)  w 7.7  r 1.5   (K11 86 %)   accepted, +17 % new
  planted 4002 T_motor1 1 h lag + init      w 33.6 r 32.8  (second effect)
  planted 4012 inputs' 4 h lag + init (13)  w 29.9 r 25.7  (second effect)
  planted 4004 inputs x ambient (10)        w 12.9 r 9.8   626: 17.8 / 12.7; 6941: 28.4 / 19.3
  planted 6945 T_box1 30 min lag + init     w 22.2 r 24.6
  the planted banks and products            w 43-69 r 39-67
  grinder-nocoolant 5687 (helpful lag)      w 12.5 r 11.6; 5682: 8.1 / 7.7
  (not clearing: clean 4004's 2 h lags 10.0-11.3 / 8.5-10.2, saturating; 6757's 900 s lags 2.2 / 1.7)

The rule (written here before it was scored)
--------------------------------------------
``withinrest``: in the ``campaigns`` scheme a candidate (every kind within67 asks: not the
control, not a sensor fault) clears only if, besides the shipped bar, its within-campaign gain
(within67's: the pooled CV residual less each held-out unit's own mean) reaches ``min_gain_pct``
also with the held-out unit whose within error falls most left out (``Search._within_gain``,
``less_best``; reported as ``cv_rmse_gain_pct_within_rest``).  A within gain one campaign carries
is one unit's evidence, however many test blocks it spans.  Nothing else changes: the forward
scheme (lagwithin68's campaigns there are 1-3 pieces of one time line), the family-wise p, the
margin, saturation, ``choose``, the deployed penalty.

The bar (the task's; adopt only if all hold, else src reverted, this bench kept, REFUSED)
------------------------------------------------------------------------------------------
Against the shipped code (diagnose's src as 3d65c78c, unchanged to f8a12479: its rows
/tmp/planted69-base, bench_planted69's shipped run):

1. Clean 6953 accepts nothing.
2. bench_moretest68's 133 rows (all six groups): planted found (``S_pos_Y`` accepted first) stays
   19 of 23; clean + null accepting something 0 of 44; no row > 2 % worse than before diagnose
   on the new campaigns with its 90 % resampled interval above +2 %; no row's test RMSE after on
   the new campaigns more than 2 % above the shipped row's.
3. Fresh 6941-6960 (bench_planted69's ``fresh``): planted found stays 8 of 10, clean accepting
   0 of 10.

CPU (user + sys) reported, not in the bar.

Scored (2026-12-01; the rule 898fefc7, its rows /tmp/clean69-rule; ``compare`` against
/tmp/planted69-base)
------------------------------------------------------------------------------------
1. Clean 6953 accepts nothing (``moretest clean:6953``): own test 0.5969 µm, its before
   (shipped 0.6998); 24 new campaigns 0.6884, their before (shipped 0.8063).  Held.
2. bench_moretest68's 133 rows: every row identical to the shipped one (accepted effects, own test
   and new campaigns' after): planted found 19 of 23 (missed 515, 737, 1514, 4001), clean + null
   accepting 0 of 44, > 2 % worse on the new campaigns 1 (the jig's E_DISP_Y +3.9 %, its interval
   not above +2 %), with the interval above +2 % 0; rows > 2 % above the shipped after 0; the
   control never accepted.  Held.
3. Fresh 6941-6960: one row differs, clean 6953 (0.6998 -> 0.5969 µm, -14.7 %, its before);
   planted found 8 of 10 (missed 6946, 6950), clean accepting 1 -> 0 of 10; no row > 2 % above
   shipped.  Held.

**Adopted** (1-3 hold).  Before the commit the rule was run once on 6953 alone (the figure of 1).
CPU (user + sys, /usr/bin/time): the 133 rows 352.3 s (rule; the rows' own 351 s against 399 s
in planted69's shipped run, another time and load: not a measured speed-up), fresh 22.2 s (19.1
s the rows' own, shipped 19.5 s).  Run after, outside the bar: pde66's four copies (``bench_pde66.py
write`` + ``diagnose``, /tmp/clean69-pde, 53 s CPU) identical to planted69's shipped run (every
target's accepted effects and test RMSE after; E_Y 3.2711 / 3.3808 µm on the planted copies).
"""

from __future__ import annotations

import resource
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402

NEW_SEEDS = (6981, 6982)


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def moretest(cases: list[str]) -> None:
    """Each case diagnosed as its row (E_Y, ``max_effects=2``) with the new campaigns added as test
    campaigns: own test and new campaigns before -> after, the 90 % resampled interval of the new
    ones' pooled change, each draw's change, campaigns > 2 % worse / better."""
    import bench_diagnose_memory as memory
    from bench_moretest68 import _change, few_again, resampled, targets_of, with_new

    from thermocomp.apps.diagnose import SearchOptions, diagnose

    for case in cases:
        start = _cpu()
        ds, comp, targets, _ = memory.dataset(case)
        full = with_new(ds, [few_again(case, s) for s in NEW_SEEDS])
        d = diagnose(full, comp, targets=targets, options=SearchOptions(max_effects=2))
        for t, o in targets_of(d, ds.ids("test"), [12] * len(NEW_SEEDS)).items():
            (ob, oa), (nb, na) = o["own"]["rmse"], o["new"]["rmse"]
            per = np.array(o["new"]["per_campaign"], float)
            lo, hi = resampled(per)
            draws = [_change(per[12 * k:12 * (k + 1)]) for k in range(len(NEW_SEEDS))]
            print(f"{case} {t}: accepted {o['accepted']}\n  own {o['own']['campaigns']}: {ob:.4f} -> "
                  f"{oa:.4f} ({100 * (oa / ob - 1):+.1f} %) | new {o['new']['campaigns']}: {nb:.4f} -> "
                  f"{na:.4f} ({100 * (na / nb - 1):+.1f} %) [90 %: {lo:+.1f}, {hi:+.1f}] per draw "
                  f"{', '.join(f'{x:+.1f}' for x in draws)}; worse {o['new']['worse']} better "
                  f"{o['new']['better']}; CPU {_cpu() - start:.1f} s", flush=True)


ACCEPTED = "3600s) of the model inputs, from the initial thermal state (2"     # 6953's lag


def trace(cases: list[str], label: str = ACCEPTED) -> None:
    """Round 1 of each case's E_Y: for each candidate whose label holds ``label``, per held-out
    campaign its CV residual's mean and the MSE about it, before / after, on the first hour, the
    next two and the rest of the campaign; per test block its MSE before / after."""
    import bench_diagnose_memory as memory

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.apps.diagnose import search as S

    shipped, seen = S.Search._evaluate, []

    def evaluate(self, effect, current, r2, faults=None):
        ev = shipped(self, effect, current, r2, faults)
        if label in effect.label and not seen:
            seen.append((self.problem, current, ev))
        return ev

    S.Search._evaluate = evaluate
    try:
        for case in cases:
            seen.clear()
            ds, comp, targets, _ = memory.dataset(case)
            diagnose(ds, comp, targets=targets, options=SearchOptions(max_effects=1))
            p, cur, ev = seen[0]
            print(f"== {case}: {ev.effect.label} q {ev.n_features} g {ev.gain_pct:.1f} within "
                  f"{ev.gain_pct_within} p {ev.p_value:.4f} pf {ev.p_family} pm {ev.p_margin:.4f} "
                  f"alpha {ev.alpha}; context {list(p.context.columns)[:8]}")
            _trace_parts(p, cur.residual, ev.result.residual, cur.block_mse, ev.result.block_mse)
    finally:
        S.Search._evaluate = shipped


def _trace_parts(p, r0, r1, b0, b1) -> None:
    ok = p.validated & np.isfinite(r0) & np.isfinite(r1)
    camp = np.asarray(p.campaigns, dtype=object)
    t = np.asarray(p.context["time"], float) if "time" in p.context else np.arange(len(r0), dtype=float)
    tot = {"means": [0.0, 0.0], "within": [0.0, 0.0], "0-1h": [0.0, 0.0], "1-3h": [0.0, 0.0],
           "3h-": [0.0, 0.0]}
    for c in dict.fromkeys(camp[ok]):
        rows = ok & (camp == c)
        since = t[rows] - t[camp == c][0]
        line = [f"  {c}: n {rows.sum()} ({since[-1] / 3600:.1f} h)"]
        for k, r in enumerate((r0[rows], r1[rows])):
            m = r.mean()
            w = r - m
            tot["means"][k] += rows.sum() * m * m
            tot["within"][k] += w @ w
            parts = []
            for name, sel in (("0-1h", since < 3600), ("1-3h", (since >= 3600) & (since < 10800)),
                              ("3h-", since >= 10800)):
                tot[name][k] += w[sel] @ w[sel]
                parts.append(f"{name} {np.mean(w[sel] ** 2) if sel.any() else np.nan:.3f}")
            line.append(f"{'before' if k == 0 else 'after'} mean {m:+.3f} within {np.mean(w ** 2):.3f} "
                        f"({', '.join(parts)})")
        print(" | ".join(line))
    N = ok.sum()
    print("  pooled (MSE µm², / all rows): " + "; ".join(f"{k} {a / N:.4f} -> {b / N:.4f}"
                                                         for k, (a, b) in tot.items()))
    blocks = p.block_index
    print("  blocks (campaign, MSE before -> after): " + ", ".join(
        f"{camp[np.argmax(blocks == i)]} {x:.3f}->{y:.3f}" for i, (x, y) in enumerate(zip(b0, b1))))



def _unit_within(p, r0, r1):
    """Per held-out campaign: its CV residual's sum of squares about its own mean, before and
    after (``campaigns`` scheme: the units are the campaigns)."""
    ok = p.validated & np.isfinite(r0) & np.isfinite(r1)
    u, n = p.unit_index[ok], p.n_units
    c = np.maximum(np.bincount(u, minlength=n), 1)
    out = []
    for r in (r0[ok], r1[ok]):
        w = r - (np.bincount(u, weights=r, minlength=n) / c)[u]
        out.append(np.bincount(u, weights=w * w, minlength=n))
    return out


def campaigns(cases: list[str]) -> None:
    """Every candidate of ``cases`` (bench_diagnose_memory's, or
    ``ROOT::machine:NAME[::OVERRIDE...]``, ROOT a ``bench_remeasure62.py write`` root's ``lag``)
    that gains >= 5 % in CV, each round: its within-campaign gain pooled, without the campaign
    that gains most within, and that campaign's share of the pooled within gain; whether it
    clears."""
    import bench_diagnose_memory as memory
    import bench_diagnose_refnoise57 as refnoise

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.apps.diagnose import search as S

    shipped = S.Search._family_bar

    def bar(self, evals, current):
        shipped(self, evals, current)
        p = self.problem
        if p.scheme != "campaigns":
            return
        for ev in evals:
            if ev.control or ev.effect.transform == "remove" or ev.gain_pct < 5.0:
                continue
            s0, s1 = _unit_within(p, current.residual, ev.result.residual)
            best = int(np.argmax(s0 - s1))
            rest = np.arange(s0.size) != best
            g = 100.0 * (1.0 - np.sqrt(s1.sum() / s0.sum()))
            g1 = 100.0 * (1.0 - np.sqrt(s1[rest].sum() / s0[rest].sum()))
            share = (s0 - s1) / max(s0.sum() - s1.sum(), 1e-300)
            print(f"  {p.target} {ev.effect.kind[:8]:8s} {str(ev.effect.column)[:14]:14s} "
                  f"{ev.effect.label[:60]:60s} q {ev.n_features:2d} g {ev.gain_pct:5.1f} within "
                  f"{g:5.1f} w/o best {g1:5.1f} ({p.unit_names[best]}, share {share[best]:.2f}); "
                  f"campaigns gaining within {int((s1 < s0).sum())}/{s0.size}; clears {ev.clears_bar}",
                  flush=True)

    S.Search._family_bar = bar
    try:
        for case in cases:
            print(f"== {case}", flush=True)
            if "::" in case:
                root, name, *extra = case.split("::")
                ds, comp, options = refnoise.composed(Path(root), name.split(":", 1)[1], *extra)
                d = diagnose(ds, comp, None, "simulation", options)
            else:
                ds, comp, targets, _ = memory.dataset(case)
                d = diagnose(ds, comp, targets=targets, options=SearchOptions(max_effects=2))
            for t in d.targets:
                j = d.to_json(t)
                print(f"{t}: test {j['before']['test_rmse']:.4f} -> {j['after']['test_rmse']:.4f}; "
                      f"accepted {[e['transform'][:50] for e in j['effects'] if e['accepted']]}",
                      flush=True)
    finally:
        S.Search._family_bar = shipped


def fresh(root: Path) -> None:
    """bench_planted69's fresh rows (planted 6941-6950, clean 6951-6960) -> ROOT/fresh.jsonl."""
    import bench_planted69 as planted69

    planted69.fresh(root)


def compare(base: Path, new: Path) -> None:
    """Bar 2 (the moretest rows, the control checked) and bar 3 (the fresh rows), as
    bench_planted69's."""
    from bench_planted69 import fresh_bar, moretest_bar

    print("== 2. bench_moretest68's rows")
    moretest_bar(base, new)
    print("== 3. fresh rows")
    fresh_bar(base, new)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "moretest": lambda *cases: moretest(list(cases)),
        "trace": lambda *cases: trace(list(cases)),
        "campaigns": lambda *cases: campaigns(list(cases)),
        "fresh": lambda root, *_: fresh(Path(root).resolve()),
        "compare": lambda base, new, *_: compare(Path(base).resolve(), Path(new).resolve()),
    }, argv)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
