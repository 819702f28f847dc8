"""Diagnose's family-wise acceptance by a hierarchical null: blocks nested in campaigns (stop 93,
diag93; issue 34: "an acceptance test whose resolution suits the number of units ... report the
smallest p the design can reach"; bench_diag92e's "the choice is stated, not made").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag93.py draws ROOT LABEL SET [NULL]  # SET's draws -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag93.py compare ROOT SET A B         # two labels' rows: the bar's counts
    python benchmarks/bench_diag93.py trace [ROW...]               # per round, the p's of every null
    python benchmarks/bench_diag93.py door ROOT [NULL]             # docs/diagnose.md's door example
    python benchmarks/bench_diag93.py reach                        # each null's smallest p, 8 campaigns
    python benchmarks/bench_diag93.py cli NULL ARGS...             # thermocomp ARGS under NULL

``draws`` / ``compare``: bench_diag91b's (12 campaigns, every 3rd test, 8 train; MLR,
``max_effects=2``, every target; ``few:4004`` E_Y only) with diagnose's family-wise p taken from
null NULL (default ``cluster``; ``blocks`` is main's, bit for bit: its rows equal a plain run of
5fe17063 on every set), on :data:`SETS`: ``trace`` / ``seen`` bench_diag91b's, ``seen92d`` bench_diag92d's
fresh 9486-9495 (spent), ``fresh`` the unspent 9476-9485 (bench_diag92's generator: clean
9476-9479, planted 9480-9482, lag 9483-9485; NOT run).  ``trace``: per row and round the members
that clear with main's p or the cluster's, each with its family-wise p under all four nulls.
``door``: the page's two commands under NULL, the table it prints.  ``reach``: each null's floor.
``cli NULL ARGS``: ``thermocomp ARGS`` under NULL (what ``door`` runs).

The nulls (the round's D unchanged: signed ranks of the test blocks' MSE gains over finer blocks,
shares of each block's MSE with one block per campaign; ``Search._family_bar``)
---------------------------------------------------------------------------------------------
``blocks``: main's, sign flips of the test blocks (exact to 16, else 20000 draws).
``campaigns``: bench_diag92e's, a campaign's blocks flipped together, exact over 2^m (8
campaigns: floor 1/256 = 0.0039).  ``cluster`` (THE RULE, the brief's first design): each
member's mean block gain over its CR1 cluster-robust standard error, campaigns the clusters
(Cameron & Miller 2015, section VI.C: t with m - 1 = 7 degrees of freedom), the family jointly by
the multivariate t (Hothorn, Bretz & Westfall 2008) with the correlation of the members' cluster
sums, 20000 draws, Westfall & Young's step-down max-T as main's.  Smallest p with 8 campaigns:
5e-5 family-wise (1/20001 of the draws; ``reach``), none for a member alone (continuous t_7).
``means``: the same t on the campaigns' mean block gains (every campaign alike; a check on
CR1's weighting of long campaigns).  The rule as src (cv.cluster_maxt, Problem.block_units,
search's _family_bar in the campaigns scheme; forward kept main's) is
``benchmarks/diag93_rule.patch``; this bench carries its own copy (the same numbers).

Traced (2026-12-05, on 5fe17063's src, seen rows only; no bar written, fresh 9476-9485 UNSPENT)
---------------------------------------------------------------------------------------------
Test RMSE (µm) before -> after; every (draw, target) where ``cluster`` differs from main::

  trace:  position found 3 -> 3 (8966 out, 8969 in); clean, control: as main
    planted:8969 E_Y  5.0569 main nothing [8]           | cluster 2.9372 position + T_bearing_f1 lag  -41.9 %
    planted:8966 E_Y  5.0569 main 1.6397 position [45]  | cluster 3.7935 nothing                     +131.4 %
    lag:9288 E_X      1.1694 main 0.8135 T_box2 lag     | cluster 1.1694 nothing                      +43.8 %
    lag:9289 E_X      2.1815 main 1.0737 T_box1 lag     | cluster 2.1815 nothing                     +103.2 %
  seen (44 draws): position found 19 -> 8; clean 8075 / 8170 / 8178 accept main's start lags in
  both (E_Y +6.6 %, E_X +14.9 %, E_Z +21.5 % against before); no control clears; 15 rows differ,
  13 more than 2 % worse than main: 12 position rows lost (9047 +151.6 %, 9101 +130.1, 9102 +325.4,
  9103 +96.9, 9190 +144.2, 9191 +198.4, 9192 +69.8, 9231 +184.5, 9232 +115.7, 9257 +31.9, 9265
  +18.4, 8457 +131.2) and lag:9269 E_X (main's T_box1 14400 s lag lost, a T_bearing_r 900 s one
  taken: 0.7263 -> 1.4357, +97.7 %); better: 9150 E_Y -31.1 % (round 2's T_motor1 lag), 9266 E_X -0.1 %.
  seen92d (9486-9495): position 3 -> 2 (9491 E_Y 2.2321 -> 5.1145, +129.1 %); clean nothing, no control.
  door (docs/diagnose.md, 16 train campaigns): the page's table to the digit (E_X 0.75 -> 0.75, E_Y
  6.25 -> 2.85, E_Z 6.25 -> 1.02; the same effects), in the src rule and in this bench.
  ``means``: the same picture (seen: position 19 -> 8, 9190 in and 9049 out; 13 rows > 2 % worse).

Round 1's family-wise p of the member main takes, by null (``trace``; 8 campaigns every row)::

  row (blocks)          member                    blocks   campaigns  cluster  means   main / cluster
  8969 E_Y (8)          position (T_box1/T_amb)   0.0117   0.0117     0.0030   0.0030  -  / takes
  8885 E_Y (13)         position                  0.0018   0.0039     0.0017   0.0012  takes / takes
  8968 E_Y (17)         position                  0.0004   0.0195     0.0061   0.0079  takes / takes
  9049 E_Y (51)         position                  0.0000   0.0078     0.0059   0.0101  takes / takes
  9150 E_Y (58)         position                  0.0000   0.0039     0.0004   0.0004  takes / takes
  9190 E_Y (30)         position                  0.0001   0.0078     0.0109   0.0076  takes / -
  9047 E_Y (65)         position                  0.0000   0.0352     0.0131   0.0128  takes / -
  9231 E_Y (73)         position                  0.0000   0.0352     0.0290   0.0208  takes / -
  9257 E_Y (64)         position                  0.0000   0.0117     0.0336   0.0193  takes / -
  9102 E_Y (89)         position                  0.0000   0.0117     0.0407   0.0399  takes / -
  9101 E_Y (71)         position                  0.0000   0.0234     0.0418   0.0559  takes / -
  9192 E_Y (53)         position                  0.0000   0.0234     0.0613   0.0271  takes / -
  9232 E_Y (76)         position                  0.0001   0.0586     0.1127   0.0822  takes / -
  9103 E_Y (50)         position                  0.0060   0.1484     0.1582   0.0516  takes / -
  9191 E_Y (103)        position                  0.0005   0.0820     0.2035   0.2689  takes / -
  8457 E_Y (101)        position                  0.0000   0.1680     0.2054   0.1657  takes / -
  8966 E_Y (45)         position (T_box1)         0.0022   0.0977     0.0242   0.0668  takes / -
  9289 E_X (30)         T_box1 14400 s lag        0.0001   0.0156     0.0149   0.0259  takes / -
  9288 E_X (19)         T_box2 14400 s lag        0.0044   0.0430     0.0431   0.0219  takes / -
  harms main takes, start lags (test error before -> main's after):
  8969 E_X (24)         T_bearing_f1 7200 s lag   0.0000   0.0039     0.0012   0.0016  takes / takes  +21.7 %
  8170 E_X (21)         T_nose 900 s lag          0.0000   0.0039     0.0005   0.0007  takes / takes  +14.9 %
  8075 E_Y (11)         3600 s lags (top four)    0.0015   0.0078     .0018-21 0.0017  takes / takes   +6.6 %
  8178 E_Z (8)          T_bearing_f3 900 s lag    0.0078   0.0078     0.0029   0.0029  takes / takes  +21.5 %
  4004 E_Y (8)          offset lag (saturates)    0.0039   0.0039     0.0002   0.0002  -  / -  (other gates)

Why (read off the table): a campaign-level test rewards a gain that is STEADY across the 8
campaigns, and on these records that is the wrong property.  The planted position's gain is as
uneven across campaigns as the campaigns' use of the Y axis (a campaign that barely moves it
gains little; 8969's K05 carries most), so its cluster t stays small and the family's max-T
(t_7 tails) refuses it on 11 of the 19 seen draws where block flips take it (and 9265's raw
S_pos_Y); where every campaign gains alike -- the start lags that fit the campaigns' offsets
(diag92, diag92c: they gain "steadily in every held-out campaign") -- the t is large and the
harms clear at 0.0005-0.003, as under main.  The only row it wins (8969 E_Y) is a round of one
block per campaign, where the t's continuous tail goes below campaign flips' 3/256; the same
reach lets 8178 E_Z's other start lags clear (0.0050 against 0.0117).  Weighting the campaigns
alike (``means``) changes nothing of this.  So a hierarchical null is not the way to the
issue's acceptance with 8 campaigns: it keeps every harm and loses most finds.  The choice
between blocks as units and campaign-level evidence, measured: campaign-level evidence (flips
or cluster t) cannot carry the planted position with 8 campaigns on most draws.

Verdict: TRACED.  The rule failed its seen rows (13 seen rows more than 2 % worse than main, the
position 19 -> 8), so no bar was written and the fresh seeds 9476-9485 were not run.  CPU
(``seen``, diagnose only, src rule against main): 31.7 / 31.2 s.

"""

from __future__ import annotations

import subprocess
import sys
from contextlib import contextmanager
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402
from bench_diag91 import compare, diagnose_cases  # noqa: E402 (the same rows)
from bench_diag91b import SETS as SEEN_SETS  # noqa: E402
from bench_diag91b import _dataset  # noqa: E402
from bench_diag92d import SETS as SETS_92D  # noqa: E402
from bench_diag92e import ROWS as ROWS_92E  # noqa: E402
from bench_diag92e import campaign_flips  # noqa: E402

RESAMPLES = 20000        # the multivariate-t draws (cv.RESAMPLES: the sign flips' Monte Carlo count)
NULLS = ("blocks", "campaigns", "cluster", "means")
TRACE_ROWS = [*ROWS_92E, *(f"planted:{s}:E_Y" for s in (8885, 9047, 9049, 9101, 9102, 9190, 9191, 9192, 9231,
                                                           9232, 9257, 9265, 8457)),
              "planted:8969:E_X", "lag:9288:E_X", "lag:9269:E_X", "clean:8075:E_Y", "clean:8178:E_Z"]
SETS = {"trace": SEEN_SETS["trace"], "seen": SEEN_SETS["seen"], "seen92d": SETS_92D["fresh"],
        "fresh": ([("clean", s) for s in range(9476, 9480)] + [("planted", s) for s in range(9480, 9483)]
                  + [("lag", s) for s in range(9483, 9486)])}


def cluster_t(D, clusters, equal: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Each row's mean block gain of ``D`` (candidates x blocks) over its cluster-robust standard
    error, the blocks nested in ``clusters`` (each block's campaign), and the rows' centred cluster
    sums (candidates x campaigns: the means' covariance is their Gram matrix up to a factor).

    The CR1 sandwich (Cameron & Miller 2015, "A practitioner's guide to cluster-robust
    inference", eq. 11, section VI.C): a campaign's blocks correlated in any way, campaigns
    independent; with one block per campaign the one-sample t.  ``equal``: every campaign
    weighted alike instead (the one-sample t of the campaigns' mean block gains)."""
    D = np.nan_to_num(np.atleast_2d(np.asarray(D, dtype=float)))
    groups = np.unique(np.asarray(clusters), return_inverse=True)[1]
    m, n = int(groups.max()) + 1, D.shape[1]
    if equal:
        means = np.stack([np.bincount(groups, weights=d, minlength=m) for d in D]) / np.bincount(groups)
        u = means - means.mean(axis=1, keepdims=True)
        return means.mean(axis=1) / np.maximum(np.sqrt((u ** 2).sum(axis=1) / (m * (m - 1))), 1e-300), u
    u = np.stack([np.bincount(groups, weights=d - d.mean(), minlength=m) for d in D])
    se = np.sqrt(m / (m - 1) * (u ** 2).sum(axis=1)) / n
    return D.mean(axis=1) / np.maximum(se, 1e-300), u


def cluster_maxt(D, clusters, equal: bool = False, seed: int = 0) -> np.ndarray:
    """Family-wise one-sided p's of every row's :func:`cluster_t`: Student's t with ``m - 1``
    degrees of freedom for ``m`` campaigns, jointly the multivariate t of Hothorn, Bretz &
    Westfall (2008) with the correlation of the rows' cluster sums, :data:`RESAMPLES` draws,
    through Westfall & Young's step-down max-T (as ``cv.sign_flip_maxt``, its null drawn, not
    flipped).  Smallest p: 1 / (RESAMPLES + 1) = 5e-5 whatever ``m`` (>= 2)."""
    observed, u = cluster_t(D, clusters, equal)
    m = u.shape[1]
    if m < 2:
        return np.ones(observed.size)
    rng = np.random.default_rng(seed)
    loadings = u / np.maximum(np.linalg.norm(u, axis=1, keepdims=True), 1e-300)     # corr = L L'
    draws = (rng.standard_normal((RESAMPLES, m)) @ loadings.T
             / np.sqrt(rng.chisquare(m - 1, (RESAMPLES, 1)) / (m - 1)))
    order = np.argsort(-observed)
    bar = observed[order] - 1e-9 * np.maximum(np.abs(observed[order]), 1.0)
    tail_max = np.maximum.accumulate(draws[:, order][:, ::-1], axis=1)[:, ::-1]
    p = (1 + (tail_max >= bar).sum(axis=0)) / (RESAMPLES + 1)
    out = np.empty(observed.size)
    out[order] = np.maximum.accumulate(p)
    return out


def block_campaigns(problem) -> np.ndarray:
    """Each test block's CV unit (its campaign), 0 .. m-1 (bench_diag92e's check: none spans two)."""
    from bench_diag92e import _block_campaign

    return _block_campaign(problem)


@contextmanager
def null(name: str):
    """Within the block, ``Search._family_bar`` takes its family-wise p from null ``name`` of
    :data:`NULLS` in the ``campaigns`` scheme (forward chaining keeps main's): ``blocks`` main's
    (sign flips of the test blocks), ``campaigns`` bench_diag92e's (a campaign's blocks flipped
    together, exact over 2^m), ``cluster`` :func:`cluster_maxt` (CR1), ``means`` the same with
    every campaign alike.  Every family member gets ``p_nulls`` (its p under each null),
    ``n_campaigns`` and ``clears_main`` (every check with main's p)."""
    from thermocomp.apps.diagnose import cv, search

    family_bar = search.Search._family_bar

    def recorded(self, evals, current):
        members = [ev for ev in evals if not ev.control and ev.effect.transform != "remove"]

        def every_null(D, **kw):
            flips = cv.sign_flip_maxt(D, **kw)
            if self.problem.forward:
                return flips
            clusters = block_campaigns(self.problem)
            with campaign_flips(clusters):
                campaign = cv.sign_flip_maxt(D)
            ps = dict(zip(NULLS, (flips, campaign, cluster_maxt(D, clusters),
                                  cluster_maxt(D, clusters, equal=True))))
            for k, ev in enumerate(members):
                ev.p_nulls = {n: float(v[k]) for n, v in ps.items()}
                ev.n_campaigns = int(clusters.max()) + 1
            return ps[name]

        search.sign_flip_maxt = every_null
        try:
            family_bar(self, evals, current)
        finally:
            search.sign_flip_maxt = cv.sign_flip_maxt
        least = self.options.min_gain_pct
        for ev in members:
            if hasattr(ev, "p_nulls"):
                ev.clears_main = (self._clears(ev.gain_pct, ev.p_nulls["blocks"], ev.gain_pct_in_range,
                                               ev.p_margin, ev.n_features)
                                  and getattr(ev, "gain_pct_within", least) >= least
                                  and getattr(ev, "gain_pct_within_rest", least) >= least)

    search.Search._family_bar = recorded
    try:
        yield
    finally:
        search.Search._family_bar = family_bar


def draws(root: str, label: str, name: str, null_name: str = "cluster") -> None:
    """:data:`SETS` ``name`` diagnosed under null ``null_name`` -> ``ROOT/NAME-LABEL.jsonl``."""
    with null(null_name):
        diagnose_cases(root, label, name, SETS[name], _dataset)


def trace(*rows: str) -> None:
    """Each ROW (``KIND:SEED:TARGET``; none: :data:`TRACE_ROWS`) diagnosed as ``draws`` runs it
    (the ``cluster`` null): per round its blocks and campaigns, then the members that clear every
    check with main's p or with the cluster t's (where none does, the one of least p as main runs),
    each with its family-wise p under every null of :data:`NULLS`."""
    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    for row in rows or TRACE_ROWS:
        kind, seed, target = row.split(":")
        ds, targets = _dataset(kind, int(seed))
        with null("cluster"):
            d = diagnose(ds, Compensator(MLR()), targets=targets, options=SearchOptions(max_effects=2))
        j = d.to_json(target)
        print(f"{row}: test {j['before']['test_rmse']:.4f} -> {j['after']['test_rmse']:.4f}", flush=True)
        for k, rnd in enumerate(d.targets[target].search.rounds, 1):
            family = [ev for ev in rnd.evaluated if hasattr(ev, "p_nulls")]
            if not family:
                continue
            shown = [ev for ev in family if ev.clears_main or ev.clears_bar] or [
                min(family, key=lambda e: e.p_nulls["blocks"])]
            print(f"  round {k}: {rnd.test_blocks} blocks in {family[0].n_campaigns} campaigns; taken: "
                  f"{rnd.accepted.effect.title[:50] if rnd.accepted else 'nothing'}")
            for ev in sorted(shown, key=lambda e: e.p_nulls["blocks"])[:4]:
                ps = " ".join(f"{n} {ev.p_nulls[n]:.4f}" for n in NULLS)
                print(f"    {ev.effect.title[:44]:44s} {ev.gain_pct:5.1f} % | p_fam {ps} | clears "
                      f"main {'Y' if ev.clears_main else '-'} cluster {'Y' if ev.clears_bar else '-'}",
                      flush=True)


def door(root: str, null_name: str = "cluster") -> None:
    """docs/diagnose.md's door example (its two commands; data and report under ROOT), diagnosed
    under null ``null_name``: the table it prints."""
    root = Path(root)
    run = [sys.executable, __file__, "cli", null_name]
    subprocess.run([*run, "simulate", "sim.generator.effects=[door]", f"data.path={root / 'raw'}"],
                   check=True, capture_output=True, cwd=HERE.parent)
    out = subprocess.run([*run, "diagnose", f"data.path={root / 'raw'}", f"out={root / 'report'}"],
                         check=True, capture_output=True, text=True, cwd=HERE.parent).stdout
    print("\n".join(line for line in out.splitlines() if line.startswith(("target", "E_", "acceptance"))))


def cli(null_name: str, *argv: str) -> None:
    """``thermocomp ARGV`` with diagnose's family-wise p from null ``null_name`` (``door``'s)."""
    from thermocomp.shell.cli import main as thermocomp

    with null(null_name):
        code = thermocomp(list(argv))
    if code:
        raise SystemExit(code)


def reach() -> None:
    """The smallest family-wise p of each null with 8 campaigns, a family of 8 that all gain in
    every campaign (one block each, gains of spread 1 to 1.5, each member a multiple)."""
    from thermocomp.apps.diagnose import cv

    D = np.linspace(1.0, 1.5, 8)[None, :] * np.linspace(1.0, 2.0, 8)[:, None]
    campaigns = np.arange(8)
    with campaign_flips(campaigns):
        flips = cv.sign_flip_maxt(D).min()
    print(f"8 campaigns, one block each: campaign flips {flips:.2g} (1/2^8), cluster t "
          f"{cluster_maxt(D, campaigns).min():.2g} (1/(R+1), R = {RESAMPLES} draws)")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"draws": draws, "compare": compare, "trace": trace, "door": door,
                                  "cli": cli, "reach": reach}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
