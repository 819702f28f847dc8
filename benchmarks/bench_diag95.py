"""Does diagnose's CV score a start lag as ``run`` scores the test?  (stop 95, diag95; issue 34:
"diagnose ... never leaves a record's test error more than 2 % worse"; bench_diag94b: on clean
8170 E_X the accepted start lag gains on all 8 train campaigns held out one at a time, yet the test
error rises +14.9 %; bench_diag93b: the same lag harms the test on ~80 % of random 8 / 4 splits).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag95.py paths CASE/TARGET...   # the test split through the CV's path
    python benchmarks/bench_diag95.py loco CASE/TARGET...    # all 12 campaigns held out one at a time
    python benchmarks/bench_diag95.py rivals CASE/TARGET...  # the start lag's round: every rival's test
    python benchmarks/bench_diag95.py directions CASE/TARGET...  # the start lag with 0-3 directions
    python benchmarks/bench_diag95.py reference CASE/TARGET...   # the probe's noise in the first sample
    python benchmarks/bench_diag95.py quiet ROOT SET         # SET with that what-if -> ROOT/SET-quiet.jsonl
    python benchmarks/bench_diag95.py draws ROOT LABEL SET   # SET as drawn -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag95.py compare ROOT SET A B   # two labels' rows of SET: the bar's counts
    python benchmarks/bench_diag95.py harm ROOT SET LABEL    # LABEL's rows > 2 % worse than before diagnose

CASE is ``kind:seed`` (bench_diag86's ``draw``, 12 campaigns, every 3rd test, 8 train; as
bench_diag92 draws and diagnoses them: MLR on every target, ``max_effects=2``).  ``paths``: the
train split stacked as the search stacks it and the test campaigns after it, one
:class:`~thermocomp.apps.diagnose.cv.Problem` over both whose only fold is the test split (train
rows fold -1: always trained on), the search's own
:class:`~thermocomp.apps.diagnose.cv.CrossValidator` building the design (its features, lags and
initial-state transient, the directions learned on the fold's train rows) and its
:class:`~thermocomp.apps.diagnose.shrink.PartialRidgePath` fitting it at the diagnosed model's
penalty; per test campaign its RMSE before -> after on that path, against ``run``'s test
(``diagnosis.test_scores``' predictions) and the largest difference of the two residuals.
``loco``: the accepted effect held fixed (sensor, tau, directions, penalty), every one of the 12
campaigns held out once and predicted by the model fitted on the other 11 (the same path): each
campaign's gain ``1 - RMSE_after / RMSE_before``, its split, programme, spindle speed, ambient,
length, the offset the model without the effect leaves it (mean residual) and the start block's
mean contribution there; then the same on the 8 train campaigns alone (the search's folds).

The question and what counts as a defect
----------------------------------------
If the CV computed something the test does not (reference frame, first sample or not; one-step
against simulation; the start block's state from measured data; an offset removed per campaign;
directions or denoising learned on all train campaigns), the test split scored through the CV's
path would differ from ``run``'s test of the same fitted model.  Defect: a residual difference
above 1e-9 µm on any test campaign (stated with the first probe, a scratch copy of ``paths``, run
on 8 harm rows; no rule was built, so no bar was scored and the fresh seeds 9546-9555 stay UNSPENT).
``reference`` and ``quiet`` change the DATA (a what-if of where the offsets come from), not src.

Measured (2026-12-06, main 34af1fcb's src = this tree's; 2 cores shared; SEEN rows only)
---------------------------------------------------------------------------------------
``paths`` (8 harm rows: clean 8170 E_X, 8178 E_Z, 8075 E_Y; planted 8969, 8457, 9046, 9342 E_X; lag
9443 E_Y; 3 helpful: lag 9269, 9445, 9195 E_X): the CV's path and ``run``'s test agree on all 44
test campaigns, before and after, to <= 2.8e-13 µm (8170: K03 0.5685 -> 0.7916, K06 0.9089 ->
0.6237, K09 0.6909 -> 0.5980, K12 0.9615 -> 1.2944 on both; split 0.7968 -> 0.9158, +14.9 %); the
train folds on that path equal the search's own CV of the accepted effect to <= 7.1e-15 (``rivals``).
Same frame (first sample), same simulation-mode design, same initial state read, same learned
directions.  NOT a defect: the CV scores the test split exactly as ``run`` does.

``loco`` (the accepted effect fixed, sensor / tau / directions / penalty): held out one at a time
from the 8 train campaigns, 8170's lag gains on 8/8 (mean +19.0 %); from all 12 it gains on 5/12 --
on 4/8 of the SAME train campaigns (mean -3.1 %) and 1/4 test (-26.8 %).  With the 4 test
campaigns in the fit, the train campaigns' own gain goes (mean gain of the 8 train campaigns, 8
held out -> 12 held out): 8178 +21.0 -> +3.2 %, 8969 +18.6 -> +0.9, 8457 +30.6 -> +4.5, 9046 +55.5 ->
+40.4, 8075 +41.1 -> +22.8, 9443 +38.6 -> +24.4, 9342 +39.6 -> +26.2; the helpful lags keep it: 9269
+44.7 -> +48.3, 9445 +36.9 -> +30.2, 9195 +48.3 -> +49.2.  The 8/8 is a relation of these 8
campaigns, not of the machine: the contradiction with bench_diag93b's random splits goes.

``rivals``: every start lag shares one initial state (every field temperature, candidates.py; only
the lag, tau and 2 or 3 directions differ), so past tau they are one per-campaign regressor.  8170
round 1: all 8 start lags (T_box1 / T_box2 / T_nose / T_bearing_f3 / T_motor2 / the inputs, 900-3600
s) CV +21.8 .. +22.5 %, 8/8 campaigns gaining, test +15.9 .. +17.1 %.  Over the 8 harm rows' rounds:
47 of 59 start lags gain on all 8 train campaigns, 57 of 59 leave the test > 2 % worse; the 3
helpful rows: 5 of 22 gain on all 8, none worse.  ``directions``: the 2nd / 3rd directions carry the
harm's CV gain (8969 1 -> 2 directions -0.2 -> +26.4 %, test -0.1 -> +23.7 %; 9443 +6.8 -> +36.8 %,
test -11.9 -> +3.4 %; 8170 +3.9 -> +22.4 % at 3, test +7.5 -> +16.8 %) -- over the train campaigns
they span 0.05-0.25 K against 2.1-4.7 K on the first (``paths``); one direction still harms 8457 (+52.6 %),
9342 (+22.9), 8178 (+11.9), 8170 (+7.5) and keeps the helpful (9269 -52.5, 9445 -44.4, 9195 -37.6).

What differs between 8170's train and test campaigns: not the programme (constant / run-stop /
steps, 2000-6000 rpm in both), not the ambient (test 6.8-28.4 °C inside train 4.6-32.7), hardly
the initial state (first direction inside the train range but K12 -4.02 K against [-3.56,
-1.34]).  It is the error probe's noise in the campaign's FIRST sample: ``data.reference=
first_sample`` zeroes the error there, so that sample's noise (probe 0.4 µm s.d., 0.1 µm quantum)
is a constant offset of the whole campaign.  ``reference``: the offsets the model leaves (12 held
out) correlate with -E(0) at 0.956 (8170), 0.882 (8178), 0.958 (8075) on the clean draws (the
clean law is exactly linear in the rises: nothing else is left), 0.57-0.90 planted, -0.22 on 9443
(its lag); E(0) s.d. 0.29-0.45 µm.  8170: train E(0) mean -0.30, test +0.35 µm (test all > 0),
so the model fitted on train leaves every test campaign -0.47 .. -0.87 µm; the start block moves
K03 / K12 +0.25 / +0.37 (the wrong way).  The 8 train offsets' s.d. 0.351 against the residual's
white noise 0.415: no campaign-level signal beyond the reference's noise, and the start block fits
8 noise draws.  What-if (the first error sample replaced by the value at t0 of a line over the
first 4 samples, train and test alike; then diagnosed): 8170 +14.9 % -> nothing accepted; 8178
+21.5 -> nothing; 8969 +21.7 -> nothing; 8457 +52.5 -> nothing; 8075 +6.6 -> nothing; 9266 +1.5 ->
nothing; 9046 +29.0 -> -1.1 %; 9342 +13.9 -> -8.7; 9443 +13.3 -> -23.3 (another start lag); the
helpful keep theirs: 9269 -56.5 -> -51.3, 9445 -41.9 -> -41.7, 9195 -45.5 -> -49.2, 8885 E_Y -71.0
-> -72.6, 9103 E_Y -49.2 -> -49.0.  The test's "before" moves with the data (8170 0.7968 ->
0.7298; 8178 E_Z 0.6377 -> 1.1755: a line over 4 samples of 300 s bends where E_Z rises fast).
``quiet seen`` against ``draws seen main`` (bench_diag92's 70 draws, the what-if on all of them):
rows > 2 % worse than before diagnose 8 -> 0 (each against its own data's "before"); the position
found on 27 -> 28 draws (+ planted:9048); clean draws still accept two 900 s start lags, harmless
(9189 E_Y +1.0 %, 9283 E_Y +0.2 %: 4 samples shrink the reference's noise, they do not remove it);
the control clears on planted:9191 E_X and lag:9343 E_Y (main: lag:9343 E_Z), deciding nothing.
Not a rule: the line moves every score (clean draws' E_Z before +30 .. +260 %, where the error
rises fast in its first 4 samples), so main's and the what-if's "after" do not compare (74 rows
differ > 2 %); it shows where the harm comes from.  diagnose CPU 48.1 s (main) / 46.8 s.

Verdict: **TRACED** (src as main).  The CV and the test score alike; the start lag's 8/8 is 8
campaign offsets that are the probe's noise in each campaign's first sample, which the first-sample
frame spreads over the campaign; the 4 test campaigns carry 4 new noise draws.  Next: the error's
reference read off more than one noisy sample (a rule of the data's frame: every score moves, its
own bar), or diagnose weighing the train campaigns' offsets against the noise floor the reference
puts there (8170: offsets s.d. 0.351 µm, the residual's white noise 0.415 µm).
CPU (the bench's own line, user + sys): ``paths`` 14.4 s (11 rows), ``loco`` 16.4 s (12 rows),
``rivals`` 15.9 s (11), ``directions`` 14.3 s (11), ``reference`` 29.3 s (13) + 4.4 s (8170);
``draws seen main`` 74.1 s, ``quiet seen`` 71.8 s (70 draws each).
"""

from __future__ import annotations

import sys
from contextlib import contextmanager
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402
from bench_diag91 import compare  # noqa: E402 (the same rows)
from bench_diag94 import draws, harm  # noqa: E402


@contextmanager
def _folds(fold_of_row: np.ndarray):
    """:class:`~thermocomp.apps.diagnose.cv.Problem`'s ``campaigns`` scheme with the folds given
    (one per row; -1: trained on by every fold, never scored), the rest of its set-up as built."""
    from thermocomp.apps.diagnose import cv as cv_module

    class Given:
        def __init__(self, n_folds):
            pass

        def fold_index(self, units):
            return fold_of_row

    original = cv_module.LeaveCampaignsOut
    cv_module.LeaveCampaignsOut = Given
    try:
        yield
    finally:
        cv_module.LeaveCampaignsOut = original


def _stacked(ds, d, target: str):
    """(Matrices, label) of the train campaigns as the search stacks them, the test ones after."""
    from thermocomp.apps.diagnose.diagnosis import _in_frame
    from thermocomp.core.continuation import fit_campaigns
    from thermocomp.core.frame import stack

    before = d.before_model
    train_ids, test_ids = d.cv["train_campaigns"], d.cv["test_campaigns"]
    train = fit_campaigns(ds, {c: ds.campaigns[c] for c in train_ids}, train_ids, before.reference)
    m = stack({**train, **{c: ds.campaigns[c] for c in test_ids}}, before.inputs_, before.targets_,
              before.reference)
    return m, _in_frame(before, m)[target]


def _validator(search, m, y, folds: np.ndarray):
    """The search's CrossValidator over the rows of ``m`` with ``folds``."""
    from thermocomp.apps.diagnose.cv import CrossValidator, Problem

    p0 = search.problem
    with _folds(folds):
        p = Problem(m.X, y, m.context, m.groups, np.asarray(m.groups), p0.target, p0.mode,
                    p0.reference, p0.n_folds, "campaigns")
    return CrossValidator(p, search.cv.estimator, search.cv.selector, search.cv.shrink)


def _held_out(cv, inputs, effects, alpha: float) -> np.ndarray:
    """Each fold's rows predicted by the design fitted on the fold's train rows at ``alpha``."""
    from thermocomp.apps.diagnose.shrink import PartialRidgePath

    p = cv.problem
    pred = np.full(len(p.y), np.nan)
    for k in p.fold_ids:
        names = cv.selection(tuple(inputs), k)
        Z = cv.design(names, effects, k)
        tr, te = p.train_rows(k) & p.measured, p.test_rows(k)
        path = PartialRidgePath(Z[tr], p.y[tr], len(names), True)
        pred[te] = path.predict(Z[te], np.array([alpha]))[:, 0]
    return pred


def _states(d, m, y, groups, test, effects, preds) -> None:
    """Each start block's initial state ``w'(c(0) - A_0)`` (K; directions learned on the train
    campaigns) by campaign, train then test; for a test campaign the offset the model without the
    effect leaves it (mean residual) and the effect's mean change of the correction there."""
    from thermocomp.apps.diagnose.features import initial_offsets, principal_directions

    for e in (e for e in effects if e.initial_state):
        offsets = initial_offsets(m.context, e.initial_state, groups)
        k = e.initial_directions or len(e.initial_state)
        w = principal_directions(offsets[~test], groups[~test], k) if e.initial_directions else np.eye(k)
        first = {c: w @ offsets[np.argmax(groups == c)] for c in dict.fromkeys(groups.tolist())}
        train = np.array([v for c, v in first.items() if not test[np.argmax(groups == c)]])
        lo, hi = train.min(axis=0), train.max(axis=0)
        print(f"  {e.column} start block, w'(c(0) - A0) by direction, train range "
              + ", ".join(f"[{a:+.2f}, {b:+.2f}]" for a, b in zip(lo, hi)))
        for c, v in first.items():
            on = groups == c
            where = "test " if test[on][0] else "train"
            extra = ""
            if test[on][0]:
                off = float(np.nanmean(y[on] - preds["before"][on]))
                change = float(np.nanmean(preds["after"][on] - preds["before"][on]))
                outside = int(np.sum((v < lo) | (v > hi)))
                extra = (f"; offset left {off:+.3f}, the effect's mean change {change:+.3f}, "
                         f"{outside} direction(s) outside the train range")
            print(f"    {c} {where} " + " ".join(f"{x:+6.2f}" for x in v) + extra)


def _change(after: float, before: float) -> str:
    return f"{100 * (after / before - 1):+.1f} %"


def _count(gains: np.ndarray) -> str:
    """How many of ``gains`` are positive, and their mean (%)."""
    return f"{int(np.sum(gains > 0))}/{gains.size} (mean {100 * gains.mean():+.1f} %)"


def _rmse(r: np.ndarray) -> float:
    return float(np.sqrt(np.nanmean(r ** 2)))


def _case(arg: str):
    from bench_diag92 import _diagnosed

    case, target = arg.rsplit("/", 1)
    ds, d, found = _diagnosed(case)
    x = d.targets[target]
    effects, alpha = x.search.effects, float(x.search.alpha or 0.0)
    print(f"== {case} {target}: {[e.title for e in effects]}, penalty {alpha:.3g}")
    return ds, d, found[target], target, effects, alpha


def _with_test_fold(arg: str):
    """``_case(arg)`` and the rows the search stacks with the test campaigns after them: (case...,
    m, y, groups, test rows, the search's validator whose one fold is the test split)."""
    case = _case(arg)
    ds, d, search, target = case[:4]
    m, y = _stacked(ds, d, target)
    groups = np.asarray(m.groups)
    test = np.isin(groups, list(d.cv["test_campaigns"]))
    return (*case, m, y, groups, test, _validator(search, m, y, np.where(test, 0, -1)))


def paths(*rows: str) -> None:
    """Each ``CASE/TARGET``: the test campaigns through the CV's path against run's (module doc)."""
    for arg in rows:
        ds, d, search, target, effects, alpha, m, y, groups, test, cv = _with_test_fold(arg)
        k = list(d.targets).index(target)
        same = np.allclose(m.X.to_numpy(float)[~test], search.problem.X.to_numpy(float), equal_nan=True) \
            and np.allclose(y[~test], search.problem.y, equal_nan=True)
        print(f"  train rows as the search's: {same}")
        preds = {"before": _held_out(cv, search.inputs(), [], 0.0),
                 "after": _held_out(cv, search.inputs(), effects, alpha)}
        worst = 0.0
        for c in d.cv["test_campaigns"]:
            on = groups == c
            read = {}
            for which, pred in preds.items():
                meas, run_pred = d.predictions[which][c]
                run_r = np.asarray(meas, float)[:, k] - np.asarray(run_pred, float)[:, k]
                cv_r = y[on] - pred[on]
                gap = float(np.nanmax(np.abs(run_r - cv_r)))
                worst = max(worst, gap)
                read[which] = (_rmse(cv_r), _rmse(run_r), gap)
            (cb, rb, gb), (ca, ra, ga) = read["before"], read["after"]
            print(f"  {c}: CV's path {cb:.4f} -> {ca:.4f} ({100 * (ca / cb - 1):+6.1f} %), run's "
                  f"{rb:.4f} -> {ra:.4f}; max |residual difference| {gb:.1e} / {ga:.1e}")
        _states(d, m, y, groups, test, effects, preds)
        before, after = (_rmse((y - preds[w])[test]) for w in ("before", "after"))
        j = d.to_json(target)
        print(f"  test split on the CV's path {before:.4f} -> {after:.4f} ({_change(after, before)}), "
              f"run's {j['before']['test_rmse']:.4f} -> {j['after']['test_rmse']:.4f}; largest "
              f"difference {worst:.1e} µm: {'DEFECT' if worst > 1e-9 else 'the paths agree'}")


def loco(*rows: str) -> None:
    """Each ``CASE/TARGET``: the accepted effect fixed, every campaign held out (module doc)."""
    for arg in rows:
        ds, d, search, target, effects, alpha = _case(arg)
        m, y = _stacked(ds, d, target)
        groups = np.asarray(m.groups)
        ids = list(dict.fromkeys(groups.tolist()))
        test_ids = set(d.cv["test_campaigns"])
        man = ds.manifest
        for label, scored in (("all 12", ids), ("train 8", [c for c in ids if c not in test_ids])):
            keep = np.isin(groups, scored)
            fold = np.array([scored.index(g) if g in scored else -2 for g in groups])
            cv = _validator(search, _rows(m, keep), y[keep], fold[keep])
            before = _held_out(cv, search.inputs(), [], 0.0)
            after = _held_out(cv, search.inputs(), effects, alpha)
            g = groups[keep]
            gains = {}
            print(f"  {label} campaigns, each held out, fitted on the rest:")
            for c in scored:
                on = g == c
                b, a = _rmse(y[keep][on] - before[on]), _rmse(y[keep][on] - after[on])
                gains[c] = 1 - a / b
                off = float(np.nanmean(y[keep][on] - before[on]))
                contribution = float(np.nanmean(after[on] - before[on]))
                r = man.loc[c]
                print(f"    {c} {'test ' if c in test_ids else 'train'} {r['programme']:8s} "
                      f"{r['spindle_rpm']:5.0f} rpm {r['ambient_c']:5.1f} °C {r['duration_h']:4.1f} h: "
                      f"{b:.4f} -> {a:.4f} ({100 * gains[c]:+6.1f} %), offset left {off:+.3f}, "
                      f"the effect's mean change {contribution:+.3f}")
            v = np.array(list(gains.values()))
            tr = np.array([gains[c] for c in scored if c not in test_ids])
            te = np.array([gains[c] for c in scored if c in test_ids])
            tail = f", test campaigns {_count(te)}" if te.size else ""
            print(f"    gain in {int(np.sum(v > 0))}/{v.size}; train campaigns {_count(tr)}{tail}")


def rivals(*rows: str) -> None:
    """Each ``CASE/TARGET``: every candidate of the round that took the first start lag, its
    held-out train campaigns gaining (the search's CV) and its test change on the same path."""
    from bench_diag92 import _rounds

    for arg in rows:
        ds, d, search, target, _, _, m, y, groups, test, cv = _with_test_fold(arg)
        x = d.targets[target]
        for rnd, current in _rounds(x):
            if rnd.accepted is None or not rnd.accepted.effect.initial_state:
                continue
            prior = [ev.effect for ev in x.accepted if ev.effect.transform != "remove"]
            prior = prior[:prior.index(rnd.accepted.effect)]
            base = _rmse((y - _held_out(cv, search.inputs(), prior, 0.0 if not prior else
                                        float(current.alpha or 0.0)))[test])
            same = float(np.nanmax(np.abs(_held_out(search.cv, search.inputs(), prior + [rnd.accepted.effect],
                                                    float(rnd.accepted.alpha or 0.0))
                                          - rnd.accepted.result.prediction)))
            print(f"  round {rnd.step} ({len(rnd.evaluated)} evaluated, {rnd.n_candidates} screened); the "
                  f"accepted one's train folds on this path against the search's CV: max |difference| "
                  f"{same:.1e}; test without the round's effect {base:.4f}")
            counts = []
            for ev in sorted((e for e in rnd.evaluated if not e.control), key=lambda e: -e.gain):
                gaining = int(np.sum(ev.result.unit_mse < current.unit_mse))
                after = _rmse((y - _held_out(cv, search.inputs(), prior + [ev.effect],
                                             float(ev.alpha or 0.0)))[test])
                start = bool(ev.effect.initial_state)
                counts.append((start, gaining, after / base - 1))
                mark = "*" if ev.accepted else " "
                print(f"    {mark} {ev.effect.title[:62]:62s} CV {ev.gain_pct:5.1f} %, "
                      f"{gaining}/{current.unit_mse.size} train campaigns gain held out, clears "
                      f"{str(ev.clears_bar):5s}; test {100 * (after / base - 1):+6.1f} %")
            starts = [c for c in counts if c[0]]
            n = current.unit_mse.size
            print(f"    start lags: {len(starts)}, {sum(g == n for _, g, _ in starts)} gain on all {n} "
                  f"train campaigns, test worse > 2 % on {sum(t > 0.02 for _, _, t in starts)}")


def directions(*rows: str) -> None:
    """Each ``CASE/TARGET``: its first start lag with 1, 2 and 3 initial directions (and none),
    the penalty the search's CV picks (least error, train only): CV gain, train campaigns gaining
    held out, test change on the same path."""
    from dataclasses import replace

    from bench_diag92 import _rounds

    for arg in rows:
        ds, d, search, target, _, _, m, y, _, test, cv = _with_test_fold(arg)
        x = d.targets[target]
        rnd, current = next((r, c) for r, c in _rounds(x)
                            if r.accepted is not None and r.accepted.effect.initial_state)
        prior = [ev.effect for ev in x.accepted if ev.effect.transform != "remove"]
        prior = prior[:prior.index(rnd.accepted.effect)]
        base = _rmse((y - _held_out(cv, search.inputs(), prior, float(current.alpha or 0.0)))[test])
        e = rnd.accepted.effect
        for k in (None, 1, 2, 3):
            variant = replace(e, initial_state=e.initial_state if k else None, initial_directions=k)
            res = search.cv.run(search.inputs(), prior + [variant])
            gaining = int(np.sum(res.unit_mse < current.unit_mse))
            pred = _held_out(cv, search.inputs(), prior + [variant], float(res.alpha or 0.0))
            after = _rmse((y - pred)[test])
            print(f"  {k or 0} direction(s){' (taken)' if k == e.initial_directions else '        '}: CV "
                  f"{100 * (1 - res.rmse / current.rmse):5.1f} %, {gaining}/{current.unit_mse.size} train "
                  f"campaigns gain, penalty {res.alpha or 0.0:.3g}; test {100 * (after / base - 1):+6.1f} %")


FIRST = 4    # samples of the line whose value at a campaign's start replaces its first error sample


def _quiet_reference(ds):
    """``ds`` with each campaign's first sample of every error replaced by the value at its start of
    the least-squares line over its first :data:`FIRST` samples: the first-sample reference read
    off less of the probe's noise (a what-if of the data, not a rule)."""
    out = {}
    for c, df in ds.campaigns.items():
        df = df.copy()
        t = df["time"].to_numpy(float)[:FIRST]
        for col in (k for k in df.columns if k.startswith("E_")):
            e = df[col].to_numpy(float)[:FIRST]
            ok = np.isfinite(e)
            if ok.sum() >= 2 and np.isfinite(e[0]):
                slope, level = np.polyfit(t[ok] - t[0], e[ok], 1)
                df.loc[df.index[0], col] = level
        out[c] = df
    ds.campaigns.clear()
    ds.campaigns.update(out)
    return ds


def reference(*rows: str) -> None:
    """Each ``CASE/TARGET``: the probe noise in the reference -- each campaign's first error sample
    against the offset the model leaves it, and the diagnosis re-run with the first sample replaced
    (:func:`_quiet_reference`): accepted effects and test change."""
    from bench_diag86 import draw

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    for arg in rows:
        ds, d, search, target, effects, alpha = _case(arg)
        m, y = _stacked(ds, d, target)
        g = np.asarray(m.groups)
        ids = list(dict.fromkeys(g.tolist()))
        cv = _validator(search, m, y, np.array([ids.index(c) for c in g]))
        before = _held_out(cv, search.inputs(), [], 0.0)
        offset = np.array([np.nanmean((y - before)[g == c]) for c in ids])
        e0 = np.array([float(ds.campaigns[c][target].iloc[0]) for c in ids])
        n_train = len(d.cv["train_campaigns"])
        steps = np.concatenate([np.diff((y - before)[g == c]) for c in ids[:n_train]])
        noise = np.nanstd(steps) / np.sqrt(2)      # white noise: a step's sd is sqrt(2) of it
        train, test = e0[:n_train], e0[n_train:]
        print(f"  first error sample E(0), train {' '.join(f'{v:+.1f}' for v in train)} (mean "
              f"{train.mean():+.2f}), test {' '.join(f'{v:+.1f}' for v in test)} (mean {test.mean():+.2f}); "
              f"corr(offset left, -E(0)) over the 12 held out {np.corrcoef(offset, -e0)[0, 1]:.3f}; train "
              f"offsets sd {offset[:n_train].std(ddof=1):.3f} against the residual's white noise {noise:.3f}")
        kind, seed = arg.rsplit("/", 1)[0].split(":")
        quiet = _quiet_reference(draw(kind, int(seed), 12))
        q = diagnose(quiet, Compensator(MLR()), options=SearchOptions(max_effects=2))
        j, jq = d.to_json(target), q.to_json(target)
        for label, js, taken in (("as drawn", j, effects),
                                 (f"E(0) from the line over the first {FIRST}", jq,
                                  q.targets[target].search.effects)):
            b, a = js["before"]["test_rmse"], js["after"]["test_rmse"]
            print(f"  {label}: {[e.title[:70] for e in taken]} test {b:.4f} -> {a:.4f} ({_change(a, b)})")


def quiet(root: str, name: str) -> None:
    """bench_diag93b's SET ``name`` drawn with :func:`_quiet_reference` and diagnosed ->
    ``ROOT/NAME-quiet.jsonl`` (bench_diag91's rows; ``draws ROOT main NAME`` for main's)."""
    from bench_diag86 import draw
    from bench_diag91 import diagnose_cases
    from bench_diag93b import SETS

    diagnose_cases(root, "quiet", name, SETS[name],
                   lambda kind, seed: (_quiet_reference(draw(kind, seed, 12)), None))


def _rows(m, keep: np.ndarray):
    """``m`` (frame.Matrices) restricted to the rows ``keep``."""
    from dataclasses import replace

    return replace(m, X=m.X.loc[keep].reset_index(drop=True), Y=m.Y.loc[keep].reset_index(drop=True),
                   groups=np.asarray(m.groups)[keep], time=np.asarray(m.time)[keep],
                   context=m.context.loc[keep].reset_index(drop=True))


def main(argv: list[str]) -> int:
    commands = {"paths": paths, "loco": loco, "rivals": rivals, "directions": directions,
                "reference": reference, "quiet": quiet, "draws": draws, "compare": compare,
                "harm": harm}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
