r"""The units of the acceptance test, and the rows where the CV does not extrapolate.

**Test blocks.**  Cross-validation holds out whole campaigns (or forward
blocks), but a sign-flip test over 8 campaigns has 256 outcomes: its smallest
one-sided p is 1/256, and family-wise over a round's candidates no effect,
however strong, reaches ``alpha = 0.01``.  The gains are therefore tested on
contiguous time blocks *within* the held-out units, each as long as the
current model's CV residual takes to forget itself: the first lag at which
its autocorrelation (pooled within campaigns, around the overall mean, so a
campaign-wide offset keeps the blocks of that campaign long) falls to
:data:`DECORRELATED`.  Neighbouring blocks are then near-independent and
their gains as likely positive as negative under the null.  A residual that
never forgets within a campaign (a slow drift) gives one block per unit, the
campaign test as before.  Units that follow each other on one time line
(forward validation blocks, time blocks of a single campaign) shorter than the
decorrelation length share test blocks of that length (on a measured spindle record, 16 validation blocks of
312 samples against a decorrelation of 715 were tested as 16 units, and a lag
that raised two probes' test error by a third passed).  The smallest p the
design can reach is reported (``min_p``).  Blocks of one campaign still share that campaign's
gain, which no autocorrelation at the first lags shows (clean data at the noise floor:
609 one-sample blocks, a lag of the inputs at p 0.00045 that raised the test error 8 %), and no
block length tied to the residual separates that case from the planted effects of 8-campaign
records (they pass with blocks of 7-13 samples; it is refused from ~16); so the bar also asks
such a gain to reach ``min_gain_pct`` in its ``1 - alpha`` lower bound
(:meth:`~.search.Search._clears`; ``benchmarks/bench_diagnose_few.py``).

The length is the *current* residual's, although it holds the slow effect being tested.  Lengths
from what is left once a candidate is fitted were measured and rejected
(``benchmarks/bench_diagnose_memory.py``): the residual with the right effect fitted keeps its
memory longer, not shorter (14 of 15 planted position effects; seed 515: 71 samples against 67;
removing the position's dwells leaves the slow misfit of the static model), only wrong
candidates' residuals forget fast (an ambient interval: 6); blocks as long as each candidate's
own gain takes to forget accepted 8 of 24 clean records (test error up to 80 % worse).  With one
or more of 8 campaigns against a real effect (seeds 515, 737, 1514), no campaign-level statistic
(exact sign flips, t, bootstrap-t) reaches ``alpha`` even before the family-wise correction.

One block per campaign is also what a residual made of campaign offsets gives: with
``reference=first_sample`` the probe noise of a campaign's first sample shifts its whole error
(clean 8-campaign data: over half the CV error in the campaigns' means).  The campaigns' gains
are then the whole evidence, and a candidate with as many regressors as a fold has training
campaigns can match their offsets by chance in every fold alike; it is refused
(:meth:`~.search.Search.saturates`, ``benchmarks/bench_diagnose_saturated.py``).

**Rows within the train range.**  A held-out campaign whose inputs leave the
range of the campaigns the fold trained on is an extrapolation: there a
model with fewer sensors can look far better (a measured lathe: four healthy
sensors "faulty", CV 21.8 -> 11.4 µm, test error 12.6 -> 13.4 µm).  A row is
within range when its leverage in the fold's training design (centred inputs)
is at most the largest leverage of a training row -- inside the ellipsoid
that holds the training data, the classical check for hidden extrapolation
(Montgomery, Peck & Vining, *Introduction to Linear Regression Analysis*,
3.8; :func:`~thermocomp.core.model_selection.extrapolation.within_range`, which
``model=auto`` shares).  The bar asks a change's gain to hold on those rows too.
"""

from __future__ import annotations

# the rule lives in core: model=auto's votes with few folds cut the same blocks
from ...core.model_selection.blocks import DECORRELATED, cut_blocks, decorrelation_length

__all__ = ["DECORRELATED", "cut_blocks", "decorrelation_length"]
