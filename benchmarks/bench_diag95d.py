"""Start lags only on initial-state directions the train campaigns span beyond the sensors' noise
(stop 95, diag95d; issue 34: "diagnose ... never leaves a record's test error more than 2 % worse";
bench_diag92's 8 seen rows > 2 % worse than before diagnose; bench_diag95 ``directions``: the harm
start lags' CV gain comes from the initial state's 2nd / 3rd principal directions, which span 0.05-0.25 K
over the train campaigns against 2.1-4.7 K on the first).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag95d.py draws ROOT LABEL SET    # SET's draws -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag95d.py compare ROOT SET A B    # two labels' rows of SET: the bar's counts
    python benchmarks/bench_diag95d.py harm ROOT SET LABEL     # LABEL's rows > 2 % worse than before diagnose

``draws`` of the rule needs its src: ``git apply benchmarks/diag95d_rule.patch`` if the rule is not in
the tree; main's rows: ``draws ROOT main seen`` on main's src (674a868c).

SET is bench_diag93b's: ``seen`` bench_diag92's 70 draws, ``fresh`` 9546-9555 (bench_diag86's
``draw``, 12 campaigns, every 3rd test, 8 train), each diagnosed with MLR on every target,
``max_effects=2`` (bench_diag94's runner; rows as bench_diag91's).

The rule (``features.spanned_directions``, used by ``candidates``; no key)
-------------------------------------------------------------------------
The start lags (``initial_state`` + ``initial_directions`` k, options (2, 3)) are offered with k capped
at the number of LEADING principal directions of the train campaigns' initial distances
``c_j(0) - A_0`` that the campaigns span beyond the temperature sensors' own noise; none spanned: no
start lag.  Direction ``w`` is spanned when the s.d. of the campaigns' scores on it exceeds
``3 sigma_w``, ``sigma_w`` the noise of one reading projected on ``w``: the robust s.d. (1.4826 MAD)
of the train rows' first differences (within campaigns) of those sensors projected on ``w``, over
``sqrt(2)`` (a difference carries two readings' noise), floored at the projected resolution
``sqrt(sum w_j^2 q_j^2 / 12)`` (``q_j`` the sensor's smallest step).  Why: a direction the campaigns
spread over no more than the noise of the readings that place them carries no transferable effect; its
CV gain fits 8 campaign offsets (bench_diag95).  The factor 3 is the usual three-sigma, stated before
any run of the rule, not tuned on a harm row (the first probe, below, reads seen rows only).

The bar (committed before the fresh seeds 9546-9555 are drawn; the brief's)
--------------------------------------------------------------------------
KEPT only if all hold.  SEEN (bench_diag92's 70 draws; main's rows ``draws seen main`` on 674a868c's
src): (1) rows > 2 % worse than before diagnose 8 -> <= 2; (2) planted position found >= 27 draws and
on each its target's gain within 2 points of main's; (3) clean draws accept nothing main does not; (4)
no row that main helps (after < before) loses more than 5 points of gain (100 (after - before) /
before).  FRESH 9546-9555, scored once after the bar: reported against main (same counts), not tuned
on.  If the seen gate fails: REFUSED, the patch saved as ``benchmarks/diag95d_rule.patch``, src
reverted, 9546-9555 left undrawn.

First probe (seen rows only, before the rule's run; scratch script): s.d. of the campaign scores on
directions 1 / 2 / 3 against sigma_w (MAD): clean 8170 E_X 0.752 / 0.048 / 0.042 K against 0.107 /
0.038 / 0.049; planted 8969 E_X 0.723 / 0.071 / 0.055 against 0.102 / 0.047 / 0.038; lag 9443 E_Y
1.079 / 0.078 / 0.042 against 0.093 / 0.052 / 0.036; the HELPFUL lag 9269 E_X 0.898 / 0.073 / 0.039
against 0.089 / 0.048 / 0.031, 9195 E_X 1.425 / 0.057 / 0.042 against 0.098 / 0.054 / 0.044.  Only the
first direction is spanned (ratio 7-15; the 2nd 1.1-1.5) on harm and helpful rows alike: the rule
caps every start lag at 1 direction, which bench_diag95 ``directions`` measured to keep the helpful
(9269 -52.5, 9445 -44.4, 9195 -37.6 %) and to still harm 8457 (+52.6), 9342 (+22.9), 8178 (+11.9),
8170 (+7.5 %) where the search picks the same lag.
Measured (2026-12-06, main 674a868c's src against it + the rule; 2 cores shared; SEEN rows only)
----------------------------------------------------------------------------------------------
``draws seen main`` 78.3 s process CPU (diagnose 51.1 s); ``draws seen rule`` 70.7 s (diagnose 42.6 s).
Accepted start lags over the 70 draws: main 27 (16 of 2 directions, 11 of 3), the rule 16 (all of 1).
(1) rows > 2 % worse than before diagnose 8 -> 2 (met): mended clean 8170 E_X, 8178 E_Z, 8075 E_Y,
planted 8969 / 9046 E_X, lag 9443 E_Y (their start lags refused or cut to 1 direction; 9046 0.8451 ->
0.5960, before 0.6551); left planted 8457 E_X +52.5 -> +44.9 %, 9342 E_X +13.9 -> +22.1 % (both a
1-direction start lag, as ``directions`` foresaw).  (2) FAILS: planted position found 27 -> 26
(planted:8966 E_Y lost its S_pos_Y x T_box1 interaction, gain -56.8 -> 0 %: with fewer start
candidates its round-1 p went 5.0e-5 -> 9.8e-4, p_fam 1.0e-4 -> 7.3e-3, and it did not clear);
gains moved > 2 points on 8885 E_Y (-71.0 -> -67.3 %), 9103 E_Y (-49.2 -> -25.7: its 2nd effect, a
T_motor2 lag, gone), 9256 E_Y (-42.3 -> -48.6).  (3) met: clean draws accept nothing (main: 8075, 8170,
8178).  (4) FAILS: 8 helpful rows lose > 5 points of gain: planted 8966 E_Y -56.8 -> 0.0, 9103 E_Y
-49.2 -> -25.7; lag 9193 E_X -62.5 -> 0.0, 9194 -51.2 -> -37.7, 9269 -56.5 -> -15.5, 9270 -41.7 ->
-23.3, 9290 -58.0 -> -32.6, 9345 -53.0 -> -43.5 (main: a T_box1 start lag on each; the rule: none on
9193, another sensor's lag on 9194 / 9269 / 9270 / 9290, T_box1's weaker on 9345); 15 rows more than 2 %
worse than main's, 11 more than 2 % better.

Verdict: **REFUSED**.  Clauses (1) and (3) met, (2) and (4) not; the rule (src + its 2 tests) is
``benchmarks/diag95d_rule.patch``, src is main's, the fresh seeds 9546-9555 stay UNDRAWN.  The
2nd direction is no more spanned beyond the sensors' noise on the helpful T_box1 rows (spread / noise
1.1-1.5) than on the harm rows, yet there it carries their gain: the span of a direction against the
noise does not tell a transferable start effect from 8 fitted offsets.  Next: none along the
directions' size; the harm is in the first error sample's reference (bench_diag95), a rule of the
data's frame with its own bar.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402
from bench_diag95c import compare, draws, harm  # noqa: E402 (its runner and rows: the same sets)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"draws": draws, "compare": compare, "harm": harm}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
