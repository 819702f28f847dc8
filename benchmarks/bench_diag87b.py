"""Diagnose's start lags: where the test campaigns' and the CV's held campaigns' start states lie
against the learned start directions, and whether anything on train alone tells the spurious from
the real ones (stop 87, diag87b; trace only, no rule; issue 34: "diagnose accepts a planted
position effect with 8 train campaigns, accepts nothing on clean data, and never leaves a record's
test error more than 2 % worse").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag87b.py trace ROOT           # every case of CASES
    python benchmarks/bench_diag87b.py trace ROOT CASE      # one case (a key of CASES)

``ROOT``: the folder holding ``lag`` and ``grinder5682`` as bench_remeasure62 writes them (the
grinder case only).  Each case is diagnosed as shipped (every target, ``max_effects=2``, MLR;
SEEN records only), ``Search._family_bar`` wrapped to measure every start lag (learned directions)
that clears the bar for the case's target, in the round it clears; the accepted one is reported.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402

# name -> (how the record is made, target, spurious or real)
CASES = {
    "8457": ("planted:8457", "E_X", "spurious"),
    "8075": ("clean:8075", "E_Y", "spurious"),
    "8178": ("clean:8178", "E_Z", "spurious"),
    "8170": ("clean:8170", "E_X", "spurious"),
    "5682": ("grinder:5682", "E_Zustellung_dY", "spurious"),
    "9046": ("draw:planted:9046:12", "E_X", "spurious"),
    "959": ("memory:planted:959", "E_Y", "real"),
    "8980": ("draw:lag:8980:12", "E_X", "real"),
    "8885": ("planted:8885", "E_Y", "real"),
    "9103": ("draw:planted:9103:12", "E_Y", "real"),
    # beyond the brief's list: the other real start lags diag87's rule lost
    "5687": ("grinder:5687", "E_Zustellung_dY", "real"),
    "climate_drift": ("faults:climate_room:drift", "E_Z", "real"),
    "climate_stuck": ("faults:climate_room:stuck", "E_X", "real"),
}


def _record(how: str, root: str):
    """(dataset, compensator, targets, options, deployed_of) of ``how`` (targets None: all)."""
    kind, *rest = how.split(":")
    if kind == "grinder":
        import bench_diag84
        return bench_diag84._case(f"grinder:{root}:{rest[0]}")
    if kind == "draw":
        import bench_diag76
        import bench_diag86

        from thermocomp.apps.diagnose import SearchOptions
        from thermocomp.core.compensator import Compensator
        from thermocomp.core.models import MLR
        ds = bench_diag86.draw(rest[0], int(rest[1]), int(rest[2]))
        return ds, Compensator(MLR()), None, SearchOptions(max_effects=2), bench_diag76._deployed_stream(ds)
    import bench_diag83b
    return bench_diag83b._case(how)


def _firsts(groups) -> tuple[np.ndarray, np.ndarray]:
    """Each campaign's first row and its name, in order."""
    g = np.asarray(groups, dtype=object)
    first = np.flatnonzero(np.r_[True, g[1:] != g[:-1]])
    return first, g[first]


def _geometry(train: np.ndarray, other: np.ndarray, k: int) -> dict:
    """Where ``other`` start offsets (rows) lie against the ``train`` campaigns' ``k`` learned
    directions: Mahalanobis D2 of their scores (the train scores' covariance), the train's own
    largest D2, the share of each (centred) offset outside the span, each direction's position
    in the train range (0..1 inside)."""
    from thermocomp.apps.diagnose.features import principal_directions

    W = principal_directions(train, np.arange(len(train)), k)
    mean = train.mean(axis=0)
    s_train, s_other = (train - mean) @ W.T, (other - mean) @ W.T
    inv = np.linalg.pinv(np.cov(s_train, rowvar=False, ddof=1).reshape(k, k))
    d2 = np.einsum("ij,jk,ik->i", s_other, inv, s_other)
    own = np.einsum("ij,jk,ik->i", s_train, inv, s_train)
    full = np.sum((other - mean) ** 2, axis=1)
    outside = 1 - np.sum(s_other ** 2, axis=1) / np.where(full > 0, full, np.nan)
    lo, hi = s_train.min(axis=0), s_train.max(axis=0)
    pos = (s_other - lo) / np.where(hi > lo, hi - lo, np.nan)
    sv = np.linalg.svd(train - mean, compute_uv=False)
    beyond = (d2 > own.max()) | np.any((pos < 0) | (pos > 1), axis=1)
    return {"W": W, "d2": d2, "beyond": beyond, "own_max": float(own.max()), "outside": outside, "pos": pos,
            "cond": float(sv[0] / sv[k - 1]) if sv[k - 1] > 0 else np.inf,
            "score_sd": s_train.std(axis=0, ddof=1),
            "captured": float(np.sum(sv[:k] ** 2) / np.sum(sv ** 2))}


def _start_fit(cv, names, effects, effect, fold, W) -> np.ndarray:
    """The start block's coefficients mapped on the sensors (``W' beta``, µm per K of start offset
    at the transient's end): least squares with an intercept on ``fold``'s training rows (None:
    all), its design as the CV builds it (no penalty)."""
    p = cv.problem
    Z = cv.design(names, effects + [effect], fold)
    y = p.y
    ok = p.train_rows(fold) & np.isfinite(y)
    A = np.column_stack([np.ones(ok.sum()), Z[ok]])
    beta = np.linalg.lstsq(A, y[ok], rcond=None)[0]
    return W.T @ beta[-W.shape[0]:]


def _measure(search, ev, current, later) -> dict:
    """Train-side (a rule could use) and test-side (explains only) figures of start lag ``ev``."""
    from dataclasses import replace

    from thermocomp.apps.diagnose.features import initial_offsets

    cv, p, e = search.cv, search.problem, ev.effect
    k = int(e.initial_directions)
    offsets = cv._offsets(e.initial_state)
    first, campaign = _firsts(p.campaigns)
    train = offsets[first]
    test = initial_offsets(later.context, e.initial_state, later.groups)[_firsts(later.groups)[0]]
    deployed = _geometry(train, test, k)
    names = cv.selection(tuple(search.inputs()), None)
    v_all = _start_fit(cv, names, search.effects, e, None, deployed["W"])
    folds = []
    for f in p.fold_ids:
        fitted = np.isin(campaign, np.asarray(p.campaigns)[p.train_rows(f)])
        held = np.isin(campaign, np.asarray(p.campaigns)[p.test_rows(f)]) & ~fitted
        g = _geometry(train[fitted], train[held], k)   # the fold's own directions (CV's)
        folds.append({**g, "v": _start_fit(cv, names, search.effects, e, f, g["W"])})
    neutral = _neutral_cv(cv, names, search.effects, e, train, campaign)
    vs = np.array([x["v"] for x in folds])
    spread = float(np.median(np.linalg.norm(vs - v_all, axis=1)) / np.linalg.norm(v_all))
    cos = vs @ v_all / (np.linalg.norm(vs, axis=1) * np.linalg.norm(v_all))
    plain = cv.run(search.inputs(),
                   search.effects + [replace(e, initial_state=None, initial_directions=None)])
    return {"title": e.title, "k": k, "m": len(e.initial_state), "n": len(train), "gain": ev.gain_pct,
            "plain_gain": 100 * (current.rmse - plain.rmse) / current.rmse,
            "cond": deployed["cond"], "captured": deployed["captured"], "score_sd": deployed["score_sd"],
            "by_direction": np.abs(deployed["W"] @ v_all) * deployed["score_sd"],
            "level_sd": float(np.std(train @ v_all, ddof=1)), "v_norm": float(np.linalg.norm(v_all)),
            "spread": spread, "cos_min": float(cos.min()), "neutral": neutral, "current": current.rmse,
            "cv_d2": np.concatenate([x["d2"] for x in folds]),
            "cv_own": np.array([x["own_max"] for x in folds]),
            "cv_outside": np.concatenate([x["outside"] for x in folds]),
            "cv_cond": np.array([x["cond"] for x in folds]),
            "cv_beyond": np.concatenate([x["beyond"] for x in folds]), "test_beyond": deployed["beyond"],
            "test_d2": deployed["d2"], "test_own": deployed["own_max"], "test_outside": deployed["outside"],
            "test_pos": deployed["pos"], "test_level": test @ v_all, "train_level": train @ v_all}


def _neutral_cv(cv, names, effects, effect, train, campaign) -> tuple[float, float]:
    """CV gains (%) of the start block over the plain lag, least squares (no penalty) in each
    fold: the held campaigns with their own start, and with the fold-train campaigns' mean start
    in its place (the fit unchanged).  What the second keeps is the gain of the fit, not of
    predicting a held campaign's level from its start."""
    from thermocomp.apps.diagnose.features import principal_directions

    p, k = cv.problem, int(effect.initial_directions)
    first, _ = _firsts(p.campaigns)
    t = p.context["time"].to_numpy(float)
    which = np.cumsum(np.isin(np.arange(len(t)), first)) - 1
    decay = 1 - np.exp(-(t - t[first][which]) / effect.tau_s)
    sse = np.zeros(3)
    for f in p.fold_ids:
        Z = cv.design(names, effects + [effect], f)
        tr, te = p.train_rows(f) & p.measured, p.test_rows(f) & p.measured
        fitted = np.isin(campaign, np.asarray(p.campaigns)[p.train_rows(f)])
        W = principal_directions(train[fitted], np.arange(fitted.sum()), k)
        for j, cols in enumerate((slice(None), slice(0, Z.shape[1] - k))):
            A = np.column_stack([np.ones(len(Z)), Z[:, cols]])
            beta = np.linalg.lstsq(A[tr], p.y[tr], rcond=None)[0]
            sse[j] += np.sum((p.y[te] - A[te] @ beta) ** 2)
            if j == 0:
                A[te, -k:] = decay[te, None] * (train[fitted].mean(axis=0) @ W.T)[None, :]
                sse[2] += np.sum((p.y[te] - A[te] @ beta) ** 2)
    full, plain, mean_start = np.sqrt(sse)
    return 100 * (1 - full / plain), 100 * (1 - mean_start / plain)


def _line(name: str, target: str, verdict: str, r: dict) -> str:
    def q(a):
        return f"{np.min(a):.1f}/{np.median(a):.1f}/{np.max(a):.1f}"
    pos = " ".join("[" + ",".join(f"{x:+.2f}" for x in row) + "]" for row in r["test_pos"])
    return (f"{name} {target} ({verdict}, {r['n']} train, {r['m']} sensors, k {r['k']}): {r['title'][:60]}; "
            f"CV g {r['gain']:.1f} %, plain lag {r['plain_gain']:.1f} %\n"
            f"  train: cond {r['cond']:.1f} captured {100 * r['captured']:.1f} %, score sd (K) "
            f"{' '.join(f'{x:.3f}' for x in r['score_sd'])}; folds' cond {q(r['cv_cond'])}\n"
            f"  start level sd {r['level_sd']:.3f} µm, by direction "
            f"{' '.join(f'{x:.3f}' for x in r['by_direction'])}; |v| {r['v_norm']:.3f}, fold "
            f"spread {r['spread']:.2f}, cos min {r['cos_min']:.2f}; level sd / current CV RMSE "
            f"{r['level_sd'] / r['current']:.2f}; least-squares CV g over the plain lag: own start "
            f"{r['neutral'][0]:.1f} %, the fold's mean start {r['neutral'][1]:.1f} %\n"
            f"  CV held: D2 {q(r['cv_d2'])} (fold-train own max {q(r['cv_own'])}), outside span "
            f"{q(100 * r['cv_outside'])} %; beyond the fold-train range {r['cv_beyond'].sum()} of "
            f"{r['cv_beyond'].size}\n"
            f"  test: D2 {' '.join(f'{x:.1f}' for x in r['test_d2'])} (train own max {r['test_own']:.1f}), "
            f"outside span {' '.join(f'{100 * x:.0f}' for x in r['test_outside'])} %, beyond the train range "
            f"{r['test_beyond'].sum()} of {r['test_beyond'].size}, position {pos}\n"
            f"  levels: train {' '.join(f'{x:+.2f}' for x in r['train_level'])} | test "
            f"{' '.join(f'{x:+.2f}' for x in r['test_level'])}")


def trace(root: str, case: str | None = None) -> None:
    """:data:`CASES` (or ``case``) diagnosed as shipped, each cleared start lag of its target
    measured in its round (module doc); the accepted one printed."""
    import thermocomp.apps.diagnose.diagnosis as diagnosis
    from thermocomp.apps.diagnose import diagnose
    from thermocomp.apps.diagnose.search import Search

    for name in [case] if case else list(CASES):
        how, target, verdict = CASES[name]
        ds, comp, targets, options, deployed_of = _record(how, root)
        later, measured = {}, {}
        shipped_stack, shipped_bar = diagnosis.stack, Search._family_bar

        def stack(campaigns, x_cols, y_cols, reference="first_sample"):
            out = shipped_stack(campaigns, x_cols, y_cols, reference)
            if not list(y_cols):
                later["m"] = out        # the test campaigns' temperatures
            return out

        def bar(self, evals, current, target=target):
            shipped_bar(self, evals, current)
            if self.problem.target != target:
                return
            for ev in evals:
                if ev.effect.learns and ev.clears_bar:
                    measured[ev.effect] = _measure(self, ev, current, later["m"])

        diagnosis.stack, Search._family_bar = stack, bar
        try:
            d = diagnose(ds, comp, targets=targets, options=options, deployed_of=deployed_of)
        finally:
            diagnosis.stack, Search._family_bar = shipped_stack, shipped_bar
        j = d.to_json(target)
        accepted = [x.effect for x in d.targets[target].accepted]
        print(f"{name} {target}: accepted {[e.title for e in accepted]}; test {j['before']['test_rmse']:.4f} "
              f"-> {j['after']['test_rmse']:.4f}", flush=True)
        for e in accepted:
            if e in measured:
                print(_line(name, target, verdict, measured[e]), flush=True)
        print(_test_levels(d, target), flush=True)


def _test_levels(d, target: str) -> str:
    """Each test campaign's residual mean / sd before -> after (batch predictions, explains only)
    and the share of the test MSE's change that is in the campaigns' means."""
    parts, mean_change, total_change = [], 0.0, 0.0
    for c in d.predictions["after"]:
        r = {}
        for which in ("before", "after"):
            meas, pred = d.predictions[which][c]
            r[which] = np.asarray(meas[target], float) - np.asarray(pred[target], float)
            r[which] = r[which][np.isfinite(r[which])]
        b, a = r["before"], r["after"]
        parts.append(f"{c} {b.mean():+.2f}/{b.std():.2f} -> {a.mean():+.2f}/{a.std():.2f}")
        mean_change += a.size * (a.mean() ** 2 - b.mean() ** 2)
        total_change += np.sum(a ** 2) - np.sum(b ** 2)
    return (f"  test campaigns' residual mean/sd before -> after: {'; '.join(parts)}; MSE change "
            f"{total_change / sum(len(v[0]) for v in d.predictions['after'].values()):+.3f}, "
            f"{100 * mean_change / total_change:.0f} % of it in the means")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
