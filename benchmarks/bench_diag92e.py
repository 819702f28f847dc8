"""Are diag92d's acceptances earned at the campaigns' resolution? (stop 92, diag92e; issue 34:
"diagnose accepts a planted position effect with 8 train campaigns"; bench_diag92d's caveat).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag92e.py trace [ROW...]   # ROW ``KIND:SEED:TARGET``; none: :data:`ROWS`

``trace``: each ROW's draw (bench_diag91b's ``_dataset``: bench_diag86's ``draw``, 12 campaigns,
every 3rd test, 8 train; ``few:4004`` test_diagnose_few's clean draw, E_Y only) diagnosed as
bench_diag91b / bench_diag92d run it (MLR, ``max_effects=2``, every target).  Per round of ROW's
target: the test blocks, the train campaigns they lie in (``m``) and the smallest p a campaign
design can give (``1/2^m``); the accepted candidate (or, where none is, the one of least p_fam)
with its p, p_margin and p_fam as run, and the same three with a CAMPAIGN-AWARE null: every
sign pattern flips all blocks of one campaign together (exact over the ``2^m`` patterns), the
round's statistics unchanged (a candidate's own p of its blocks' MSE gains; the family-wise
max-T of ``Search._family_bar``'s D, signed ranks over finer blocks, over the same family and
the same patterns).  ``survives``: p_fam with campaign flips <= alpha (0.01).  The code that
computes the p-values is the tree's own (``cv.sign_flip_maxt`` / ``search._flip_pvalues``), with
its sign patterns replaced by the campaign patterns; on a round with one block per campaign
the campaign-aware p's equal the run's (a check of the trace).

:data:`ROWS`: every (draw, target) where diag92d changed the result (bench_diag92d: trace
8969 E_Y; seen 9103 E_Y, 9150 E_Y, lag:9195 E_Y, clean:8170 E_X; fresh 9491 E_X, lag:9493 E_Y;
few:4004 E_Y, 8 -> 43 blocks, nothing taken) and, for comparison, three rows main (2b918bfd)
already accepted on more than 8 blocks (bench_diag91b's 8966 E_Y, 8968 E_Y, lag:9289 E_X).

No rule: a trace, no src change, no fresh seed spent, no bar.

Traced (2026-12-05, ``trace`` on this branch = 8281b37a's src, diag92d's rule in; main = 2b918bfd's
src, ``git archive`` under /tmp/diag92e/main, on the four rows it differs in round 1 or 2)
---------------------------------------------------------------------------------------------------
Per accepted round: blocks, then p_fam as run -> p_fam with campaign flips (8 train campaigns in
every row: the floor is 1/256 = 0.0039; p_fam <= 0.01 needs at most one other pattern of 255 to
reach the observed max-T).  Rounds on 8 blocks (one per campaign) read the same p both ways
(8969 r2 0.0078, 9493 r2 0.0195, 9289 r2 0.875: the check holds).

diag92d's changed rows (the rule's acceptances, test RMSE before -> after as run)::

  row               round: taken (blocks)              p_fam run -> campaigns  at 0.01
  planted:8969 E_Y  r1 position (14)                   0.0070 -> 0.0391        NO
                    r2 T_motor1 7200 s lag (8)         0.0078 -> 0.0078        yes   5.0569 -> 2.5898
  planted:9103 E_Y  r1 position (50; main's too)       0.0060 -> 0.1484        NO
                    r2 T_motor2 3600 s lag (13)        0.0009 -> 0.0117        NO    (main on 8: 0.0039)
  planted:9150 E_Y  r1 position (58; main's too)       0.0000 -> 0.0039        yes
                    r2 T_motor1 7200 s lag (13)        0.0087 -> 0.0312        NO    (main on 8: 0.0195)
  lag:9195 E_Y      r1 T_motor2 7200 s lag (14)        0.0056 -> 0.0156        NO    (main on 8: 0.0547)
  clean:8170 E_X    r1 T_box1 1800 s lag (573)         0.0000 -> 0.0039        yes   (clean: a start lag)
  planted:9491 E_X  r1 T_bearing_f3 900 s lag (203)    0.0000 -> 0.1523        NO
  lag:9493 E_Y      r1 T_motor1 7200 s lag (550)       0.0000 -> 0.3594        NO    (+1.5 % test)
  few:4004 E_Y      r1 nothing (43); least p_fam: the offset lag, 0.0000 -> 0.0078 (refused by the
                    other gates, saturating; it would pass the campaign null alone)

Main's own acceptances on more than 8 blocks (bench_diag91b's; the same on both trees)::

  planted:8966 E_Y  r1 position (53)                   0.0001 -> 0.0391        NO
  planted:8968 E_Y  r1 position (27)                   0.0002 -> 0.0078        yes
  lag:9289 E_X      r1 T_box1 14400 s lag (37)         0.0000 -> 0.0156        NO

Own p (a candidate alone, campaign flips) of the NO rows: 8969 r1 0.0078, 9103 r1 0.0156, r2
0.0039, 9150 r2 0.0078, 9195 0.0078, 9491 0.0234, 9493 0.0938; 8966 0.0078, 9289 0.0117: 5 of
9 reach alpha alone and fail by the family (the max-T over the round's family).

Verdict: TRACED, no rule.  The rule's acceptances do NOT hold at the campaigns' resolution: of
the 7 fine-block rounds whose pick differs from main's, 1 survives (clean 8170's start lag,
0.0039) and 6 do not (0.0117 .. 0.359); 8969's position, the rule's case, reads 0.039 (main's
one-block-per-campaign shares read 0.0117), and its round 2 (8 blocks, 0.0078) follows it.
The gap is not diag92d's alone: 2 of main's 3 fine-block acceptances (8966's position
0.039, 9289's lag 0.0156) and 9103's position (50 blocks) fail it too; 8968's and 9150's
positions pass (0.0078, 0.0039).  A fine-block acceptance rests on the blocks within a campaign
being independent units; with 8 train campaigns a campaign-level null reaches 0.01 family-wise
only where at most one of the 255 other patterns reaches the observed max-T, i.e. the gain's
sign is shared by (nearly) every campaign: a position carried by few campaigns (8969: K05) does
not get there.  CPU of ``trace`` (all rows): 16 s.
"""

from __future__ import annotations

import sys
from contextlib import contextmanager
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402
from bench_diag89c import capture_families  # noqa: E402
from bench_diag91b import _dataset  # noqa: E402 (the same draws)

ALPHA = 0.01
ROWS = ["planted:8969:E_Y", "planted:9103:E_Y", "planted:9150:E_Y", "lag:9195:E_Y", "clean:8170:E_X",
        "planted:9491:E_X", "lag:9493:E_Y", "few:4004:E_Y",
        "planted:8966:E_Y", "planted:8968:E_Y", "lag:9289:E_X"]


@contextmanager
def campaign_flips(block_campaign: np.ndarray):
    """Within the block, the sign-flip tests of :mod:`thermocomp.apps.diagnose.cv` flip whole
    campaigns: ``block_campaign[i]`` is block ``i``'s campaign (0 .. m-1); every one of the
    ``2^m`` patterns is enumerated (exact, whatever the number of blocks)."""
    from thermocomp.apps.diagnose import cv

    m = int(block_campaign.max()) + 1
    expanded = cv._sign_patterns(m)[:, block_campaign]      # patterns x blocks
    saved = cv._sign_chunks, cv.EXACT_UNITS
    cv._sign_chunks = lambda n, *_: iter([expanded])
    cv.EXACT_UNITS = block_campaign.size                     # p = hits / 2^m, the identity in
    try:
        yield m
    finally:
        cv._sign_chunks, cv.EXACT_UNITS = saved


def _block_campaign(problem) -> np.ndarray:
    """Each test block's train campaign (its CV unit), numbered 0 .. m-1."""
    ok = problem.validated
    blocks, units = problem.block_index[ok], problem.unit_index[ok]
    out = np.full(problem.n_blocks_tested, -1)
    out[blocks] = units
    if (out < 0).any() or any(np.unique(units[blocks == b]).size > 1 for b in range(out.size)):
        raise RuntimeError("a test block spans no campaign or two")
    return np.unique(out, return_inverse=True)[1]


def _record_campaign_p() -> None:
    """Wrap ``Search._family_bar`` (over bench_diag89c's capture of its D, ranks or clipped
    shares): after it, each family member gets ``campaign_p`` / ``campaign_p_margin`` /
    ``campaign_p_family`` (the round's statistics, campaign patterns) and ``campaign_m`` (the
    round's campaigns)."""
    from thermocomp.apps.diagnose import cv, search

    rounds: list = []
    capture_families(rounds)
    captured = search.Search._family_bar

    def family_bar(self, evals, current):
        tested = len(rounds)
        captured(self, evals, current)
        if len(rounds) == tested:        # no family-wise test this round
            return
        _, family, D = rounds[-1]
        with campaign_flips(_block_campaign(self.problem)) as m:
            p_family = cv.sign_flip_maxt(D)
            for ev, pf in zip(family, p_family):
                ev.campaign_p, ev.campaign_p_margin = search._flip_pvalues(
                    current.block_mse, ev.result.block_mse, self.options.min_gain_pct)
                ev.campaign_p_family, ev.campaign_m = float(pf), m

    search.Search._family_bar = family_bar


def _fmt(x) -> str:
    return "-" if x is None else f"{x:.4f}"


def trace(*rows: str) -> None:
    """Each ROW's rounds: the accepted candidate's p's as run and with campaign flips (module doc)."""
    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    _record_campaign_p()
    for row in rows or ROWS:
        kind, seed, target = row.split(":")
        ds, targets = _dataset(kind, int(seed))
        d = diagnose(ds, Compensator(MLR()), targets=targets, options=SearchOptions(max_effects=2))
        j = d.to_json(target)
        print(f"{row}: test {j['before']['test_rmse']:.4f} -> {j['after']['test_rmse']:.4f}", flush=True)
        for k, rnd in enumerate(d.targets[target].search.rounds, 1):
            family = [ev for ev in rnd.evaluated if getattr(ev, "campaign_m", None)]
            if not family:
                continue
            ev = rnd.accepted or min(family, key=lambda e: e.p_family)
            m = ev.campaign_m
            print(f"  round {k}: {rnd.test_blocks} blocks in {m} campaigns (floor 1/2^{m} = "
                  f"{2.0 ** -m:.4f}); {'ACCEPTED' if rnd.accepted else 'least p_fam, not taken'} "
                  f"{ev.effect.title[:60]}\n"
                  f"    as run:         p {_fmt(ev.p_value)} p_margin {_fmt(ev.p_margin)} "
                  f"p_fam {_fmt(ev.p_family)}\n"
                  f"    campaign flips: p {_fmt(ev.campaign_p)} p_margin {_fmt(ev.campaign_p_margin)} "
                  f"p_fam {_fmt(ev.campaign_p_family)} -> "
                  f"{'survives' if ev.campaign_p_family <= ALPHA else 'does NOT survive'} at {ALPHA}",
                  flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
