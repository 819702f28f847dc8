"""diag103's forward-within bound (``search.START_FORWARD_WITHIN_PCT`` = 28) scored where it bites --
fresh start lags reading 28-40 forward within -- and train-only reads that might tell lag 9443 E_Y's
harm (+13.3 %, its T_bearing_f3 3600 s start lag reads 33.3) from the real start lags of its kind
(stop 105, diag105; issue 34: "diagnose ... never leaves a record's test error more than 2 % worse").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag105.py band ROOT BOUND SET     # SET diagnosed with the bound at BOUND
    python benchmarks/bench_diag105.py fresh ROOT BOUND        # FRESH in order until the stop rule
    python benchmarks/bench_diag105.py fresh ROOT BOUND LIKE   # the fresh cases bound LIKE's run drew
    python benchmarks/bench_diag105.py score ROOT SET           # the band table: bound 28 vs 40 vs 0
    python benchmarks/bench_diag105.py trace ROOT SET           # part (2)'s reads -> ROOT/trace-SET.jsonl
    python benchmarks/bench_diag105.py table ROOT SETS          # SETS comma-separated: harms vs helpful
    python benchmarks/bench_diag105.py whatif ROOT SET          # each start lag weighed, taken: test %
    python benchmarks/bench_diag105.py forward ROOT SET         # cleared start lags' forward per campaign
    python benchmarks/bench_diag105.py draws ROOT LABEL SET     # SET's rows -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag105.py default ROOT LABEL       # make run's -> ROOT/default-LABEL.jsonl
    python benchmarks/bench_diag105.py bar ROOT MAIN RULE       # B1-B4 on two labels' rows

``band`` / ``fresh`` write ``ROOT/SET-bBOUND.jsonl`` (bench_diag91's rows) and
``ROOT/decisions-SET-bBOUND.jsonl`` (bench_diag103b's decisions: per target the rounds in which a
start lag reached the forward clause, each with its forward-within read, CV gain, cleared,
accepted), the src's ``START_FORWARD_WITHIN_PCT`` set to BOUND for the run (main's src otherwise;
BOUND 0 = no forward clause, 40 = the band refused).

Part (1): the bound in its band (procedure fixed BEFORE any fresh seed is drawn)
------------------------------------------------------------------------------
Draws: bench_diag103b's kinds and scenario (bench_diag86's ``draw``, 12 campaigns, every 3rd test,
8 train; MLR on every target, ``max_effects=2``), kinds in the order lag, lag, planted repeated:
:data:`FRESH` = 10025-10029, then (only if needed) 9476-9480.  A BAND READ is a start lag that
reached the clause (bound 28's run) reading 28 <= forward within < 40.  Stop rule: draw all of
10025-10029; if they hold fewer than :data:`ENOUGH` (3) band reads, go on through 9476-9480 one
draw at a time until 3 (at most those 5); 9481-9485 are never drawn here: they are kept for
scoring any rule part (2) builds.  Each drawn case is diagnosed three times: bound 28 (main),
40 (the band refused) and 0 (no forward clause).  Score per row (draw, target) whose bound-28
decisions hold a band read: the row's test change (100 (after / before - 1) %) at 28 vs at 40; a
band read ACCEPTED at 28 is HELPFUL if the row at 28 is better than at 40 by more than 0.5 points,
HARMFUL if worse by more than 0.5 (a row > 2 % worse at 28 counts as the bound's harm), NEUTRAL
otherwise.  The same for reads < 28 refused (28 vs 0): the bound's other side.  This is a trace
(TRACED table): the bound is not moved on these numbers.

Part (2): a rule, and its bar (committed BEFORE the scored seeds 9481-9485 are drawn)
-----------------------------------------------------------------------------------
Traced before the bar (seen / spent only; ``trace``, ``whatif``, ``forward``; numbers in the
report): none of the new single-lag reads separates 9443 E_Y's T_bearing_f3 from spent 9959 E_Y's
T_motor1 (-37.1 %): last train campaign alone 40.7 / 38.4 (pooled / within) vs 19.1 / 19.6; the
residual-on-change slope positive in 8 / 8 campaigns for both (min 0.83 vs 0.76); within gain by
quarter of the campaigns' time 43.9 29.0 33.1 38.3 vs 45.6 33.8 23.0 40.9.  What does separate is
the CHOICE among 9443 E_Y's cleared rivals: T_motor2 / T_motor1 (forward within 42.0 / 41.1) beat
the taken T_bearing_f3 (33.3) forward within in each of the 4 later train campaigns (16.3 30.7
60.0 43.5 vs 4.8 29.1 48.7 38.4), and taken alone they leave the test -0.9 / -0.5 %.  Offline over
the 29 seen + spent round-1 start-lag choices, such an every-campaign better rival exists in 5:
9443 E_Y (+13.3 -> -0.9), 9933 E_X (-38.2 -> -57.0), 9840 E_X (-59.3 -> -64.1), 9814 E_X (-56.9
-> -53.7), 9839 E_X (-59.4 -> -54.9); the others (9959 E_Y / E_X among them) keep their choice.

RULE (``search.forward_first``, no key): where :func:`choose`'s first is a start lag read forward
(diag103's clause), an eligible start lag whose forward within SSE is lower in EVERY later train
campaign goes first (of several, the best forward read).  It refuses nothing and has no constant:
unlike diag101's within / pooled bound and diag103's forward bound it ranks, it does not bar.

MAIN = 4b70457f's src (``git archive``), RULE = this branch's.  A row is (draw, target), its change
100 (after / before - 1) % of the test RMSE as run.
B1 seen (bench_diag92's 70 draws, 210 rows): rows > 2 % worse 1 (main) -> 0 (rule), none new.
B2 every seen row main helps by more than 2 % (change < -2) stays < -2 under the rule; those rows'
mean gain under the rule >= main's - 1 point; make run's E_Y within 1 point of main's (-25.3 %);
the 12 spent draws: rows > 2 % worse no more than main's.
B3 the seen clean draws accept nothing under the rule (as main).
B4 SCORED once after this bar, :data:`SCORED` 9481-9485 (kinds lag, planted, lag, clean, lag, chosen
before drawing): the rule's rows > 2 % worse <= main's, its mean change <= main's + 1 point, the
clean draw accepts nothing.  (The rule may not move a scored row: said if so.)
B5 tests/apps/test_diagnose_few.py, test_diagnose_startshare100.py and the modules that import
search pass with the rule.
KEPT if B1-B5 hold (src, a test failing on 4b70457f, docs/diagnose.md); else REFUSED
(``benchmarks/diag105_rule.patch``, src reverted).

Measured (2026-12-07; nice, 2 cores shared, load 11-21; MAIN = 4b70457f's src by ``git archive``)
------------------------------------------------------------------------------------------------
Part (1), ``fresh ROOT 28`` (13.4 s CPU), ``fresh ROOT 40 28`` (14.0), ``fresh ROOT 0 28`` (15.1):
10025-10029 held 2 band reads, so 9476-9478 were drawn (9478 brought 7): 8 draws, 24 rows, 9 band
reads.  ``score ROOT fresh``: bound 28 and 40 give the same 24 rows (every band read was a cleared
rival behind a start lag read 42.8-70.6; none accepted); bound 0 moves one row, 10025 E_Y +0.0 ->
+1.1 % (T_motor1 36 s start lag at 22.2).  ``whatif ROOT fresh`` (17.7 s; each start lag that
reached the clause, taken alone in its round, the test read here only) -- the band reads: 10028 E_X
31.7 / 33.5 -> -20.5 / -27.3 %; 9478 E_X 37.3 / 33.4 / 34.6 -> -49.6 / -53.7 / -38.3; 9478 E_Y 35.0
/ 37.8 / 32.1 / 31.5 -> -32.2 / -29.5 / -27.3 / -19.6: 9 of 9 helpful, 0 harmful.  Below 28: 10025
E_Y's two (22.2 / 22.0) +1.1 % each.  NOTE: ``whatif ROOT fresh`` walked all of :data:`FRESH` and so
also drew 9479 (planted: no start lag reached the clause) and 9480 (lag: 6 E_X reads 47.9-68.1, none
in the band) outside the stop rule: spent, counted in no table here.  Seen / spent, ``whatif``
(start 33.6 s, spent 23.4 s; ``forward`` 27.5 / 18.1 s, ``trace`` 30.6 / 18.5 s), the band:
seen 6 helpful (9443 E_X 38.8, 9193 E_X 39.8 / 38.1, 9290
E_X 35.1 / 34.7, 9445 E_X 37.3: -31.5 .. -67.7 %), 4 harmful (9443 E_Y's four, 32.0-37.5: +4.1 ..
+13.3); spent 3 helpful + 1 neutral (9959's four), 2 harmful (9838 E_Z 38.6 / 38.8: +28.5 / +24.7,
not taken: E_Z accepted nothing).  Harmful start lags also read above 40 (9932 E_Z 41.8-59.1, +12.1
.. +16.6 %; 9838 E_Z 40.6 / 42.9; 9933 E_X T_amb 46.7, +13.3), all kept out by other checks.  So the
bound at 28 did not bite on the fresh draws, everything they read in 28-40 would have helped, and
only 9443 E_Y puts harms in the band; the forward read does not separate harm from help in general.

Part (2), ``bar /tmp/diag105/bar main rule`` (``draws`` seen main / rule 87.1 / 87.5 s CPU, run
side by side; spent 17.2 / 17.0; default 7.6 / 7.6; scored 8.5 / 8.4; user + sys, ``/usr/bin/time``)::

  seen lag:9443 E_Y: +13.3 -> -0.9 %
  spent lag:9839 E_X: -59.4 -> -54.9 %
  spent lag:9840 E_X: -59.3 -> -64.1 %
  spent lag:9933 E_X: -38.2 -> -57.0 %
  scored lag:9481 E_X: -36.1 -> -31.7 %
  B1 seen rows > 2 % worse 1 [('lag:9443', 'E_Y')] -> 0 [] (0, none new): met
  B2 seen rows main helps (44): lost []; mean gain 49.37 -> 49.37 (>= main - 1): met
  B2 make run's E_Y -25.3 -> -25.3 % (within 1 point): met
  B2 spent rows > 2 % worse [] -> []: met
  B3 seen clean rows accepting 0 -> 0: met
  B4 scored rows > 2 % worse [] -> []: met
  B4 scored mean change (15 rows) -14.01 -> -13.71 %: met
  B4 scored clean rows accepting 0 -> 0: met
  B1-B4 (8 of 8 items): HOLD

The one scored row the rule moved went the wrong way by 4.4 points (9481 E_X T_box2 -> T_box1
1440 s, still helpful): of the 5 rows moved in all (seen, spent, scored) 3 gained (9443 E_Y 14.2
points, 9933 18.8, 9840 4.8) and 2 lost 4.4-4.5 points (9839, 9481).  Verdict: KEPT.
"""

from __future__ import annotations

import json
import sys
from contextlib import contextmanager
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import numpy as np  # noqa: E402
from _cli import made_folder, run_commands  # noqa: E402
from bench_diag103 import SETS as SETS_103  # noqa: E402

_KINDS = ["lag", "lag", "planted"] * 4
FRESH = list(zip(_KINDS, range(10025, 10030))) + list(zip(_KINDS[5:], range(9476, 9481)))
FIRST = 5                      # 10025-10029: always drawn
ENOUGH = 3                     # band reads that stop the draws after FIRST
BAND = (28.0, 40.0)
SCORED = [("lag", 9481), ("planted", 9482), ("lag", 9483), ("clean", 9484), ("lag", 9485)]
SETS = {"seen": SETS_103["seen"], "scored": SCORED, "harms": SETS_103["harms"], "start": SETS_103["start"],
        "spent": SETS_103["spent"], "default": SETS_103["default"], "fresh": FRESH, "drawn": FRESH[:8]}


@contextmanager
def _bound(value: float):
    from thermocomp.apps.diagnose import search as search_module

    was = search_module.START_FORWARD_WITHIN_PCT
    search_module.START_FORWARD_WITHIN_PCT = float(value)
    try:
        yield
    finally:
        search_module.START_FORWARD_WITHIN_PCT = was


def _band_reads(dec: dict) -> int:
    return sum(BAND[0] <= lag["forward_within"] < BAND[1] for rounds in dec.values() for r in rounds
               for lag in r["lags"])


def band(root: str, bound: str, name: str, cases=None) -> None:
    """:data:`SETS` ``name`` (or ``cases``) diagnosed with the bound at ``bound``."""
    from bench_diag103b import _diagnosed

    with _bound(float(bound)):
        _diagnosed(root, f"b{bound}", name, SETS[name] if cases is None else cases)


def fresh(root: str, bound: str, like: str = "") -> None:
    """:data:`FRESH` by the stop rule (module doc), or the cases bound ``like``'s run drew."""
    from bench_diag103b import decisions

    if like:
        rows = open(Path(root) / f"fresh-b{like}.jsonl")
        cases = [json.loads(line)["case"].split(":") for line in rows]
        band(root, bound, "fresh", [(k, int(s)) for k, s in cases])
        return
    found = [0]

    def until_enough():
        for i, case in enumerate(FRESH):
            if i >= FIRST and found[0] >= ENOUGH:
                return
            yield case

    import bench_diag91

    keep_cases = bench_diag91.diagnose_cases

    def counting(root_, label, name, cases, dataset, reference="first_sample", keep=None):
        def keep2(case, ds, d):
            found[0] += _band_reads(decisions(d))
            if keep is not None:
                keep(case, ds, d)
        return keep_cases(root_, label, name, cases, dataset, reference, keep2)

    bench_diag91.diagnose_cases = counting
    try:
        band(root, bound, "fresh", until_enough())
    finally:
        bench_diag91.diagnose_cases = keep_cases
    print(f"  band reads ({BAND[0]:.0f}-{BAND[1]:.0f}): {found[0]} (enough {ENOUGH})")


def _verdict(delta: float) -> str:
    return "HELPFUL" if delta < -0.5 else "HARMFUL" if delta > 0.5 else "neutral"


def score(root: str, name: str) -> None:
    """The band table (module doc) of ``ROOT/{NAME,decisions-NAME}-b{28,40,0}.jsonl``."""
    from bench_diag98 import _changes

    ch = {b: _changes(root, name, f"b{b}") for b in ("28", "40", "0")}
    dec = [json.loads(line) for line in open(Path(root) / f"decisions-{name}-b28.jsonl")]
    tally: dict = {}
    for row in dec:
        for t, rounds in row["decisions"].items():
            key = (row["case"], t)
            c28, c40, c0 = (ch[b][key] for b in ("28", "40", "0"))
            for r in rounds:
                for lag in r["lags"]:
                    fw = lag["forward_within"]
                    side = "band" if BAND[0] <= fw < BAND[1] else "below" if fw < BAND[0] else "above"
                    other = c40 if side == "band" else c0 if side == "below" else c28
                    v = _verdict(c28 - other) if lag["accepted"] or side == "below" else "-"
                    tally.setdefault((side, v), []).append(key)
                    print(f"  {key[0]:14s} {t} r{r['round']} {lag['effect'][:40]:40s} fwd {fw:6.1f} gain "
                          f"{lag['gain']:5.1f}{' clears' if lag['clears'] else ''}"
                          f"{' *' if lag['accepted'] else ''}"
                          f" | test % b28 {c28:+6.1f} b40 {c40:+6.1f} b0 {c0:+6.1f} | {side} {v}")
    every = {b: sorted(k for k, v in ch[b].items() if v > 2.0) for b in ch}
    print(f"  rows {len(ch['28'])}; rows > 2 % worse: " + "; ".join(f"b{b} {every[b]}" for b in ch))
    for (side, v), keys in sorted(tally.items()):
        print(f"  {side:5s} {v:8s} {len(keys)} {sorted(set(keys))}")


# -- part (2): train-only reads of the accepted start lags (trace; nothing changed) -----------------
def _last_within(search, ev, current) -> dict:
    """The last train campaign alone, scored by the fit on the campaigns before it: the gain (%) of
    ``ev`` (at its penalty) over the current model (at its own), pooled and within."""
    from bench_diag103 import _chronological, _pct, _sse

    p = search.problem
    camps = _chronological(p)
    labels = np.asarray(p.campaigns, dtype=object)
    train, test = np.isin(labels, camps[:-1]), (labels == camps[-1]) & p.validated
    b = _sse(search, list(search.effects), current.alpha, train, test)
    a = _sse(search, list(search.effects) + [ev.effect], ev.alpha, train, test)
    return {"last_pooled": _pct(b[0], a[0]), "last_within": _pct(b[1], a[1])}


def _per_campaign(search, ev, current) -> dict:
    """Per held-out campaign (CV): the slope of the current model's residual on the candidate's
    change of the prediction, both less their campaign means (1: the change fits the residual's
    shape in that campaign, <= 0: against it), and the within gain in each quarter of the
    campaigns' time (every campaign's rows cut in 4; residuals less the campaign's mean)."""
    p = search.problem
    ok = p.validated & np.isfinite(current.residual) & np.isfinite(ev.result.residual)
    labels = np.asarray(p.campaigns, dtype=object)
    slopes, q0, q1 = [], np.zeros(4), np.zeros(4)
    cells = 0
    for c in dict.fromkeys(labels[ok].tolist()):
        m = ok & (labels == c)
        r0, r1 = current.residual[m], ev.result.residual[m]
        d = r0 - r1                       # the candidate's change of the prediction
        r0c, r1c, dc = r0 - r0.mean(), r1 - r1.mean(), d - d.mean()
        slopes.append(float(r0c @ dc / (dc @ dc)) if dc @ dc > 0 else float("nan"))
        quarter = np.minimum((4 * np.arange(r0.size)) // r0.size, 3)
        for k in range(4):
            s0, s1 = np.sum(r0c[quarter == k] ** 2), np.sum(r1c[quarter == k] ** 2)
            q0[k] += s0
            q1[k] += s1
            cells += int(s1 < s0)
    s = np.array(slopes)
    quarters = [100 * (1 - np.sqrt(q1[k] / q0[k])) if q0[k] > 0 else float("nan") for k in range(4)]
    return {"slope_pos": int(np.sum(s > 0)), "slope_n": int(s.size), "slope_min": float(np.nanmin(s)),
            "slope_med": float(np.nanmedian(s)), "quarters": quarters, "cells_gain": cells,
            "cells": 4 * int(s.size)}


def _reads2(search, ev, current) -> dict:
    from bench_diag103 import chained

    r = {"gain": ev.gain_pct, "effect": ev.effect.title, "round": len(search.effects) + 1,
         "target": search.problem.target, "resolved": search._means_resolved(),
         "fwd_within_src": getattr(ev, "gain_pct_forward_within", None)}
    r.update(chained(search, ev, current), **_last_within(search, ev, current),
             **_per_campaign(search, ev, current))
    r.pop("fwd_sse", None)
    return r


def trace(root: str, name: str) -> None:
    """The cleared start lags' part-(2) reads on :data:`SETS` ``name``, the accepted ones marked,
    with their target's test change as run (bench_diag103's trace; explains only)."""
    from bench_diag103 import trace as trace_103

    trace_103(root, name, sets=SETS, read=_reads2, line=_line2)


def _line2(r: dict) -> str:
    f = lambda v, s: "  -" if v is None or not np.isfinite(v) else format(v, s)  # noqa: E731
    return (f"  {r['case']:13s} {r['target']} r{r['round']} {'*' if r['accepted'] else ' '} "
            f"{r['effect'][:34]:34s} test {r['test']:+6.1f} gain {f(r['gain'], '5.1f')} fwdw "
            f"{f(r['fwd_within'], '5.1f')} | last p {f(r['last_pooled'], '6.1f')} w "
            f"{f(r['last_within'], '6.1f')}"
            f" | slope+ {r['slope_pos']}/{r['slope_n']} min {f(r['slope_min'], '5.2f')} med "
            f"{f(r['slope_med'], '4.2f')} | q " + " ".join(f(q, '5.1f') for q in r["quarters"])
            + f" cells {r['cells_gain']}/{r['cells']}")


def table(root: str, names: str) -> None:
    """The accepted start lags' part-(2) reads of the sets ``names`` (comma-separated): harms
    (> 2 % worse) first, then the helpful ones."""
    rows = [json.loads(line) for n in names.split(",") for line in open(Path(root) / f"trace-{n}.jsonl")]
    acc = [r for r in rows if r["accepted"]]
    for title, part in (("harms (> 2 % worse)", [r for r in acc if r["test"] > 2.0]),
                        ("helpful (test < 0)", [r for r in acc if r["test"] < 0]),
                        ("others accepted", [r for r in acc if 0 <= r["test"] <= 2.0])):
        print(f"{title}: {len(part)}")
        for r in sorted(part, key=lambda r: (r["case"], r["target"], r["round"])):
            print(_line2(r))


def _taken(ds, comp, search, x, r, ev, target) -> float:
    """The test RMSE of the model with the effects accepted before round ``r`` and ``ev`` on
    ``target``, its penalty chosen as diagnose chooses the final one (``Search._deployed``), fitted
    as diagnose fits its "after"."""
    from thermocomp.apps.diagnose.diagnosis import augment, test_scores
    from thermocomp.core.continuation import fit_joined
    from thermocomp.core.scoring.evaluation import require_split
    from thermocomp.core.scoring.results import TargetResult

    effects = [a.effect for a in x.accepted[:r.step - 1]] + [ev.effect]
    kept, search.effects = search.effects, effects
    try:
        alpha = search._deployed(ev.result).alpha
    finally:
        search.effects = kept
    model = augment(comp, {target: effects}, alphas={target: alpha})
    fitted = fit_joined(model, ds, require_split(ds, "train"))
    scores, _ = test_scores(fitted, ds, require_split(ds, "test"), "simulation", "range", 200)
    return float(TargetResult(scores[target]).test.rmse)


@contextmanager
def _searches(store: dict):
    """Each target's :class:`~thermocomp.apps.diagnose.search.Search` -> ``store`` as it runs."""
    from thermocomp.apps.diagnose import search as search_module

    original = search_module.Search.run

    def wrapped(self, *args, **kwargs):
        store[self.problem.target] = self
        return original(self, *args, **kwargs)

    search_module.Search.run = wrapped
    try:
        yield store
    finally:
        search_module.Search.run = original


def whatif(root: str, name: str) -> None:
    """Every start lag of :data:`SETS` ``name`` that reached the forward clause (or was accepted),
    with the test change (%) its target would have had had it been taken in its round -> ``ROOT/
    whatif-NAME.jsonl`` (explains only: the test split is read here, never by diagnose)."""
    from bench_diag98 import _dataset
    from bench_diag103 import _start_lag

    from thermocomp.apps.diagnose import diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    with open(made_folder(root) / f"whatif-{name}.jsonl", "w") as out:
        for kind, seed in SETS[name]:
            ds, options = _dataset(kind, seed)
            comp, searches = Compensator(MLR()), {}
            with _searches(searches):
                d = diagnose(ds, comp, options=options)
            for t, x in d.targets.items():
                j = d.to_json(t)
                before, after = j["before"]["test_rmse"], j["after"]["test_rmse"]
                for r in x.search.rounds:
                    for ev in r.evaluated:
                        fw = getattr(ev, "gain_pct_forward_within", None)
                        if not _start_lag(ev.effect) or (fw is None and not ev.accepted):
                            continue
                        rmse = _taken(ds, comp, searches[t], x.search, r, ev, t)
                        row = {"case": f"{kind}:{seed}", "target": t, "round": r.step,
                               "effect": ev.effect.title, "forward_within": fw, "gain": ev.gain_pct,
                               "clears": bool(ev.clears_bar), "accepted": bool(ev.accepted),
                               "taken_pct": 100 * (rmse / before - 1), "row_pct": 100 * (after / before - 1)}
                        print(json.dumps(row, default=float), file=out, flush=True)
                        print(f"  {row['case']:14s} {t} r{r.step} {'*' if ev.accepted else ' '} "
                              f"{row['effect'][:40]:40s} fwd {'   -' if fw is None else format(fw, '5.1f')}"
                              f" gain {ev.gain_pct:5.1f}{' clears' if ev.clears_bar else '       '} | taken "
                              f"{row['taken_pct']:+6.1f} % (row as run {row['row_pct']:+6.1f})", flush=True)


def _per_campaign_forward(search, ev, current) -> dict:
    """``ev``'s forward within gain (%) in each later train campaign (bench_diag103's read split)."""
    base = search.cv.forward_within(search.inputs(), search.effects, current.alpha)
    after = search.cv.forward_within(search.inputs(), search.effects + [ev.effect], ev.alpha)
    return {"effect": ev.effect.title, "target": search.problem.target, "round": len(search.effects) + 1,
            "forward_within": ev.gain_pct_forward_within,
            "per_campaign": (100 * (1 - np.sqrt(after / base))).tolist()}


def forward(root: str, name: str) -> None:
    """Every start lag of :data:`SETS` ``name`` that cleared the forward clause: its forward within
    gain per later train campaign, the accepted one marked, main's choice (``forward_first`` off)
    -> ``ROOT/forward-NAME.jsonl`` (explains only)."""
    from bench_diag98 import _dataset
    from bench_diag100 import _rounds_read
    from bench_diag103 import _start_lag

    from thermocomp.apps.diagnose import diagnose
    from thermocomp.apps.diagnose import search as search_module
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    kept = getattr(search_module, "forward_first", None)
    search_module.forward_first = lambda eligible: eligible
    try:
        with open(made_folder(root) / f"forward-{name}.jsonl", "w") as out:
            for kind, seed in SETS[name]:
                ds, options = _dataset(kind, seed)
                store: dict = {}
                with _rounds_read(store, _per_campaign_forward,
                                  lambda e: _start_lag(e)):
                    d = diagnose(ds, Compensator(MLR()), options=options)
                accepted = {id(ev) for x in d.targets.values() for ev in x.accepted}
                for key, (ev, r) in store.items():
                    if r["forward_within"] is None:
                        continue
                    r = dict(r, case=f"{kind}:{seed}", accepted=key in accepted)
                    print(json.dumps(r, default=float), file=out, flush=True)
                    print(f"  {r['case']:14s} {r['target']} r{r['round']} {'*' if r['accepted'] else ' '} "
                          f"{r['effect'][:40]:40s} fwd {r['forward_within']:5.1f} per campaign "
                          + " ".join(f"{g:6.1f}" for g in r["per_campaign"]), flush=True)
    finally:
        if kept is not None:
            search_module.forward_first = kept


def draws(root: str, label: str, name: str) -> None:
    """:data:`SETS` ``name`` diagnosed -> ``ROOT/NAME-LABEL.jsonl`` (bench_diag91's rows)."""
    from bench_diag91 import diagnose_cases
    from bench_diag92c import _dataset as draw_12

    diagnose_cases(root, label, name, SETS[name], draw_12)


def _accepting_clean(root: str, name: str, label: str) -> int:
    from bench_diag91 import _rows

    rows = _rows(Path(root) / f"{name}-{label}.jsonl")
    return sum(bool(v["accepted"]) for c, r in rows.items() if c.startswith("clean:")
               for v in r["targets"].values())


def bar(root: str, main: str, rule: str) -> None:
    """B1-B4 (module doc) on ``ROOT/{seen,spent,default,scored}-{MAIN,RULE}.jsonl``."""
    from bench_diag98 import _changes, print_moved

    items = []
    seen = {n: _changes(root, "seen", n) for n in (main, rule)}
    worse = {n: {k for k, v in seen[n].items() if v > 2.0} for n in seen}
    items.append((f"B1 seen rows > 2 % worse {len(worse[main])} {sorted(worse[main])} -> {len(worse[rule])} "
                  f"{sorted(worse[rule])} (0, none new)", not worse[rule]))
    helpful = [k for k, v in seen[main].items() if v < -2.0]
    lost = [k for k in helpful if seen[rule][k] >= -2.0]
    g = {n: -float(np.mean([seen[n][k] for k in helpful])) for n in seen}
    items.append((f"B2 seen rows main helps ({len(helpful)}): lost {lost}; mean gain {g[main]:.2f} -> "
                  f"{g[rule]:.2f} (>= main - 1)", not lost and g[rule] >= g[main] - 1.0))
    dflt = {n: _changes(root, "default", n)[("default:0", "E_Y")] for n in (main, rule)}
    items.append((f"B2 make run's E_Y {dflt[main]:+.1f} -> {dflt[rule]:+.1f} % (within 1 point)",
                  abs(dflt[rule] - dflt[main]) <= 1.0))
    spent = {n: _changes(root, "spent", n) for n in (main, rule)}
    sw = {n: sorted(k for k, v in spent[n].items() if v > 2.0) for n in spent}
    items.append((f"B2 spent rows > 2 % worse {sw[main]} -> {sw[rule]}", len(sw[rule]) <= len(sw[main])))
    clean = {n: _accepting_clean(root, "seen", n) for n in (main, rule)}
    items.append((f"B3 seen clean rows accepting {clean[main]} -> {clean[rule]}", clean[rule] == 0))
    print_moved("seen", seen[main], seen[rule])
    print_moved("spent", spent[main], spent[rule])
    if (Path(root) / f"scored-{rule}.jsonl").exists():
        sc = {n: _changes(root, "scored", n) for n in (main, rule)}
        print_moved("scored", sc[main], sc[rule])
        w = {n: sorted(k for k, v in sc[n].items() if v > 2.0) for n in sc}
        m = {n: float(np.mean(list(sc[n].values()))) for n in sc}
        c = {n: _accepting_clean(root, "scored", n) for n in (main, rule)}
        items += [(f"B4 scored rows > 2 % worse {w[main]} -> {w[rule]}", len(w[rule]) <= len(w[main])),
                  (f"B4 scored mean change ({len(sc[main])} rows) {m[main]:+.2f} -> {m[rule]:+.2f} %",
                   m[rule] <= m[main] + 1.0),
                  (f"B4 scored clean rows accepting {c[main]} -> {c[rule]}", c[rule] == 0)]
    for text, ok in items:
        print(f"  {text}: {'met' if ok else 'FAILS'}")
    held = len(items) == 8 and all(ok for _, ok in items)
    print(f"  B1-B4 ({len(items)} of 8 items): {'HOLD' if held else 'FAIL or incomplete'}")


def main(argv: list[str]) -> int:
    from bench_diag98 import default

    commands = {"band": band, "fresh": fresh, "score": score, "trace": trace, "table": table,
                "whatif": whatif, "forward": forward, "draws": draws, "default": default, "bar": bar}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
