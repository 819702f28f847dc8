r"""Contiguous time blocks about as long as a residual takes to forget itself.

The units a test or a bootstrap can treat as near-independent when the held-out
campaigns or folds are too few to be the units themselves: the diagnosis's
acceptance test (:mod:`thermocomp.apps.diagnose.search`) and ``model=auto``'s votes
with few validation folds (:func:`thermocomp.core.models.blend.vote_weights`) cut
them alike.

**Why blocks.**  Cross-validation holds out whole campaigns (or forward
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
records (they pass with blocks of 7-13 samples; it is refused from ~16); so the diagnosis's bar
also asks such a gain to reach ``min_gain_pct`` in its ``1 - alpha`` lower bound
(:meth:`~thermocomp.apps.diagnose.search.Search._clears`; ``benchmarks/bench_diagnose_few.py``).

**Whose residual.**  The length is the *current* residual's, although it holds the slow effect
being tested.  Lengths from what is left once a candidate is fitted were measured and rejected
(``benchmarks/bench_diagnose_memory.py``): the residual with the right effect fitted keeps its
memory longer, not shorter (14 of 15 planted position effects; seed 515: 71 samples against 67;
removing the position's dwells leaves the slow misfit of the static model), only wrong
candidates' residuals forget fast (an ambient interval: 6); blocks as long as each candidate's
own gain takes to forget accepted 8 of 24 clean records (test error up to 80 % worse; stop 41,
before the within-campaign, margin and saturation checks).  Since diag91b the search re-cuts a
round's blocks in the ``campaigns`` scheme as long as its candidates' gains take to forget, the
longest over the round, where that is shorter than the residual's, unless a gain is mostly one
number per campaign (:func:`between_campaign_share` over :data:`BETWEEN_CAMPAIGNS`)
(:meth:`~thermocomp.apps.diagnose.search.Search._recut_on_gains`, ``benchmarks/bench_diag91b.py``;
in forward chaining it took a lag that made the spindle record's ch4 26 % worse, bench_diag91).
With one or more of 8 campaigns against a real effect (seeds 515, 737, 1514), no campaign-level statistic
(exact sign flips, t, bootstrap-t) reaches ``alpha`` even before the family-wise correction.

**One block per campaign** is also what a residual made of campaign offsets gives: with
``reference=first_sample`` the probe noise of a campaign's first sample shifts its whole error
(clean 8-campaign data: over half the CV error in the campaigns' means).  The campaigns' gains
are then the whole evidence, and a candidate with as many regressors as a fold has training
campaigns can match their offsets by chance in every fold alike; the diagnosis refuses it
(:meth:`~thermocomp.apps.diagnose.search.Search.saturates`,
``benchmarks/bench_diagnose_saturated.py``).
"""

from __future__ import annotations

import numpy as np

DECORRELATED = 0.2        # autocorrelation at which two samples count as near-independent
BETWEEN_CAMPAIGNS = 0.4   # share of a gain's variance in its campaigns' means: campaign-sized units


def decorrelation_length(residual, campaigns, scored, span=None) -> int:
    """Samples until the residual's autocorrelation within campaigns first falls to
    :data:`DECORRELATED` (the longest scored run when it never does).

    ``span``: the rows a run stretches over (default ``scored``): an error measured on 1 row in
    N (a probe cycle) is scored on its measured rows only, which are never contiguous; its runs
    are the stretches of ``span`` and its lags are counted in *measured* samples, the series at
    its own spacing (the only one whose autocorrelation can be estimated)."""
    r = np.asarray(residual, float)
    ok = np.asarray(scored, bool) & np.isfinite(r)
    runs = _runs(np.asarray(campaigns, dtype=object), ok, span)
    if not runs:
        return 1
    centred = r - r[ok].mean()
    var = float(np.mean(centred[ok] ** 2))
    longest = max(len(run) for run in runs)
    if var <= 0.0:
        return 1
    series = [centred[run] for run in runs]     # copied once, not at every lag
    for lag in range(1, longest):
        num = cnt = 0.0
        for x in series:
            if len(x) > lag:
                num += float(x[:-lag] @ x[lag:])
                cnt += len(x) - lag
        if num / cnt / var <= DECORRELATED:       # cnt > 0: lag < the longest run
            return lag
    return longest


def between_campaign_share(values, campaigns, scored) -> float:
    """Share of ``values``' variance (over the ``scored`` rows) that lies between the campaigns'
    means: the intraclass share of a one-way decomposition (0: every campaign alike on average,
    1: one number per campaign).

    A design effect: where a per-sample gain is mostly a per-campaign constant, its blocks
    within a campaign share that constant whatever their autocorrelation says (a candidate
    matching the campaigns' offsets, clean seed 4004 of ``benchmarks/bench_diag91.py``), and the
    effective number of units is the number of campaigns."""
    x = np.asarray(values, float)
    ok = np.asarray(scored, bool) & np.isfinite(x)
    if ok.sum() < 2:
        return 1.0
    x = x[ok]
    _, group = np.unique(np.asarray(campaigns, dtype=object)[ok].astype(str), return_inverse=True)
    counts = np.bincount(group)
    means = np.bincount(group, weights=x) / counts
    total = float(np.sum((x - x.mean()) ** 2))
    if total <= 0.0:
        return 0.0
    return float(np.sum(counts * (means - x.mean()) ** 2) / total)


def _runs(campaigns: np.ndarray, ok: np.ndarray, span=None) -> list[np.ndarray]:
    """Row indices of each contiguous scored stretch of one campaign (``span``: the rows of
    each contiguous stretch of ``span`` that are ``ok``; stretches without one dropped)."""
    if span is None:
        span = ok
    idx = np.flatnonzero(np.asarray(span, bool) | ok)
    if idx.size == 0:
        return []
    breaks = np.flatnonzero((np.diff(idx) != 1) | (campaigns[idx[1:]] != campaigns[idx[:-1]])) + 1
    runs = (run[ok[run]] for run in np.split(idx, breaks))
    return [run for run in runs if run.size]


def cut_blocks(unit_index: np.ndarray, campaigns, length: int, timeline: bool = False,
               scored=None) -> np.ndarray:
    """Test block of each row (-1: not scored): every contiguous scored stretch of one campaign
    (``timeline``: of the campaigns taken as one time line, as forward validation blocks run
    on into the next campaign) cut into ``len // length`` near-equal blocks (at least one).
    Neighbouring units shorter than ``length`` (time blocks of one record) thus share a test
    block: they are not independent of each other.

    ``scored``: the rows with an error to score (default: every row of a unit).  A stretch is
    then one of the units' rows, and ``length`` counts its scored rows (an error measured on 1
    row in N: :func:`decorrelation_length` with ``span``), so that no block is left without
    one; the unscored rows get -1."""
    unit_index = np.asarray(unit_index)
    out = np.full(unit_index.shape, -1)
    span = unit_index >= 0
    ok = span if scored is None else span & np.asarray(scored, bool)
    key = np.zeros(len(unit_index)) if timeline else np.asarray(campaigns, dtype=object)
    n = 0
    for run in _runs(key, ok, span):
        k = max(1, len(run) // max(int(length), 1))
        for part in np.array_split(run, k):
            out[part] = n
            n += 1
    return out
