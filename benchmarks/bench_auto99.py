"""auto hands a lag-family target to MLR while its inputs have been beyond the fit region for a
while: a SUSTAINED excursion, not a sample (issue 34; stop 99, auto99; the "next" of bench_auto98b).

TRACED on SEEN: no form of the state separates the column losers from the records where the lag
families win beyond the region; no rule built in src, fresh 9795-9804 NOT drawn (they stay fresh).

The state: per target whose kept model's heaviest member is a lag family (``lagbank`` /
``hammerstein``), an exponentially weighted share of the recent samples whose inputs lie beyond
the final fit's input region (``lev``: bench_auto98b's, :func:`within_range`'s leverage check),
``e_t = e_{t-1} + (b_t - e_{t-1}) / W``, 0 at each stream's start (a campaign that restarts the
stream); the prediction is MLR's while ``e_t >= s``, else the blend's.  ``latch``: once handed
over, MLR's to the stream's end; ``grow``: the window grows from the stream's start to W (a stream
that starts beyond is seen at once; a campaign that continues its predecessor starts full-grown).
Causal and one or two numbers of state per target (the C could carry it).  In simulation the blend
and MLR run free on every row, so the hand-over changes no state: the trace over stored rows IS
the rule's output (bench_auto98b's ``rule`` showed it to the digit for the per-sample form).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_auto99.py rows22 ROOT MAIN_WORK OUT RECORD ...   # the 22-table rows
    python benchmarks/bench_auto99.py rows ROOT OUT RECORD ...       # own-test records (one-campaign, fl)
    python benchmarks/bench_auto99.py oof22 ROOT MAIN_WORK OUT FORMS RECORD ...   # the final refit's OOF
    python benchmarks/bench_auto99.py sustain OUT FORMS RECORD ...   # FORMS "W:s,W:s:latch:grow" -> table

``rows22``: bench_auto98b's ``trace22`` (MAIN_WORK = main's stored rows ``/tmp/auto96/seen``, ROOT
``/tmp/auto96/root``; bench_auto96 says how to rebuild both), each row's y (the new campaigns'
scored rows, else NaN), the blend, MLR, the lev flag, the campaign (OUT/RECORD.npz).  ``rows``:
bench_auto98b's ``trace`` fit (``model=auto`` and MLR on the train part, the record's own test; a
test that continues the train part continues its stream: its state starts at 0, full-grown).
``oof22``: the final refit's out-of-fold rows (main's stored ``oof_*``, auto's own folds rebuilt
and checked against ``oof_y``): a fold's rows beyond the region of its fit rows, the excursion
state over them, the blend's and MLR's squared error there (does the train data's own structure
say MLR wins in an excursion?).  ``sustain``: per form the figure (bench_auto96's: mean over
targets of auto's RMSE / mean of MLR's) main -> rule (rule / main, rows handed), the geometric
mean, losers, records > 1 % worse.

BAR (bench_auto98b's clauses, written here before any FRESH seed is simulated; W, s and the form
chosen on SEEN only; KEPT only if all hold, on by default only with the state carried into the
exported C / ST so that deployed = scored, else a key off by default):
(1) SEEN 22-table (``rows22`` + ``sustain`` against main's stored rows /tmp/auto96/seen): losers
    (auto / MLR > 1.0) fewer than main's 8, no record's rule / main > 1.01.  The 10 seen
    one-campaign records (bench_auto95's SEEN, ``rows``): no record's rule / main > 1.01.
(2) fl_thermal 90/10 (``rows ... fl_thermal``): mean RMSE over ch1..ch5 <= 2.506 µm (2.481 + 1 %).
(3) FRESH 9795-9804 (bench_auto98's FRESH), scored ONCE with ``rows``: losers no more than main's,
    the geometric mean of auto / MLR not above main's.
Fresh seeds are drawn only if (1) and (2) hold for one form; else TRACED / REFUSED on the seen gate.

Measured (SEEN; 2026-12-06, 4fafc59a, nice, ``OMP_NUM_THREADS=1``, load 6-17 on 2 cores)::

  22-table, auto / MLR: main 0.8264 geo, 8 losers (col5791 1.258, col1403 1.311, ...: reproduced)
  the ceiling (every lag target's whole new-campaign prediction MLR's, beyond or not): col1403
  0.976, hmc / mtc_b 1.000 (every target a lag one: auto = MLR), col5791 1.013 (its loss sits in
  non-lag targets too); hmc and mtc_b are hardly ever beyond (1 of 26144 / 677 of 23040 rows), so
  an excursion rule can mend col1403 alone: losers 8 -> 7 at best, and only with ~all of col1403's
  rows handed over (64 % beyond, and its in-region rows lose as well)
  form (W:s)           geo     losers  > 1 % worse  col1403  col5791  tsc_a2 x main  mtc_b x main
  1:1 (per sample)     0.8101  8       1            1.050    1.012    1.069          1.006
  100:0.5              0.8126  8       1            1.066    1.016    1.056          0.998
  300:0.5              0.8138  8       0            1.137    1.032    1.000          0.999
  300:0.3              0.8112  8       1            1.028    1.013    1.070          0.994
  30:0.5:latch         0.8084  7       2            0.975    1.013    1.110          1.040
  50:0.7:latch         0.8106  7       2            0.988    1.013    1.101          1.010 (> 1.01)
  75:0.6:latch         0.8106  7       1            0.987    1.013    1.101          1.010 (<= 1.01)
  100:0.5:latch        0.8105  7       1            0.987    1.013    1.101          1.010 (<= 1.01)
  150:0.7:latch        0.8140  8       0            1.141    1.036    1.000          0.992
  300:0.5:latch:grow   0.8212  8       1 (swiss303 1.599 x main: its campaigns start beyond, latched whole)
  grid W 30/50/75/100/150/200 x s 0.5-0.95, latched (36 forms): col1403 < 1 in 11, where W*s <~ 70
  rows (30: s <= 0.9, 50: <= 0.7, 75: <= 0.6, 100: 0.5), and each of the 11 hands tsc_a2's
  mid-campaign excursion (its campaign 2 from row 419, 10 % of its rows) to MLR: tsc_a2 >= 1.100 x
  main; tsc_a2 is spared (<= 1.01) in 13 forms (50:0.95, 75/100: >= 0.9, 150/200: >= 0.7), where
  col1403 is >= 1.141

  one-campaign 10 (``rows``): every sustained form (300:0.5, latched 30-100) hands 0 rows:
  geo 0.7657 = main, none worse (the per-sample 1:1: lr9643 1.173, lr9211 1.172 x main);
  300:0.5:latch:grow: sw9696 1.767 x main.  fl_thermal 90/10: 2.481 -> 2.481 µm (0 rows beyond)

  oof22 (the train data's own structure; SSE blend | MLR on the OOF rows in the state 100:0.5):
  col1403 E_Y 152 rows 7.85e3 | 4.70e4, E_Y_mid 636 | 3.05e3; col5791 E_Z_mid 1.23e3 | 1.22e3;
  iso_b E_Z 3005 rows 2.55e5 | 9.72e5; tsc_a2, mtc_b, mtc_a, grind_b, year6*: 0 rows in excursion
  (per sample, 1:1: the blend wins beyond on every lag record with rows beyond but mtc_b E_dX / E_dZ,
  103 rows; hmc, swiss303: none beyond)

What separates the column losers is the unseen source of the NEW campaigns (55-76 % of their rows
beyond; col1403's from the first 1-33 rows of each campaign, col5791's 1-85), not anything the
train part shows: on col1403's
own out-of-fold excursions the blend's squared error is 1/6 of MLR's, so a gate judged on the final
refit's OOF rows never hands col over, and a state fast enough to hand col1403 over (latched within
~70 rows) also takes tsc_a2's excursion (its beyond rows: auto 0.532 vs MLR 9.94 µm on E_dZ1,
bench_auto98b) and mtc_b's.  Clause (1) fails for every form, so no rule was built and the fresh
seeds stay unspent.

CPU (nice, ``OMP_NUM_THREADS=1``): ``rows22`` 22 records 20.0 s, ``rows`` 10 + fl_thermal 67.7 s,
``oof22`` 11 records 11.9 s, ``sustain`` 2.6-3.7 s per grid; ~20 min wall.
"""

import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
os.environ.setdefault("OMP_NUM_THREADS", "1")
from _cli import run_commands  # noqa: E402

LAG = ("lagbank", "hammerstein")


def excursion(flag: np.ndarray, campaign: np.ndarray, window: float, warm=None,
              grow: bool = False) -> np.ndarray:
    """The causal state: the exponentially weighted share (time constant ``window`` samples) of the
    rows ``flag``ged beyond, restarted at 0 where ``campaign`` changes (a stream's start).

    ``grow``: the window grows from the stream's start to ``window`` samples (the running share of
    the rows since the start, then the weighted one), so a stream that starts beyond is seen at
    once; a campaign that continues its predecessor (``warm`` on its rows) starts full-grown, its
    state 0 (its predecessor's end lies inside the region it was fitted on)."""
    warm = np.zeros(len(flag), bool) if warm is None else warm
    out = np.empty(len(flag))
    e, n = 0.0, 0
    for i, (b, c) in enumerate(zip(flag, campaign)):
        if i == 0 or c != campaign[i - 1]:
            e, n = 0.0, (window if warm[i] else 0)
        n += 1
        e += (float(b) - e) / (min(n, window) if grow else window)
        out[i] = e
    return out


def _save(out: str, name: str, targets: dict) -> None:
    arrays = {f"{t}.{k}": v for t, c in targets.items() for k, v in c.items()}
    np.savez_compressed(Path(out, f"{name}.npz"), **arrays)
    print(name, "; ".join(f"{t} lag={bool(c['lag'])} lev {int(c['lev'][np.isfinite(c['y'])].sum())}/"
                          f"{int(np.isfinite(c['y']).sum())}" for t, c in targets.items()), flush=True)


def _lag_kept(weights: dict) -> bool:
    return max(weights, key=weights.get) in LAG and max(weights.values()) > 0   # not a zero kept


def rows22(root: str, main_work: str, out: str, *records: str) -> None:
    from bench_auto91 import stored_targets
    from bench_auto98b import beyond, framed

    from thermocomp.core.continuation import predecessors

    work = Path(main_work).resolve()
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        _, _, full, ids, comp, m_fit, m_all = framed(root, work, name)
        continuing = predecessors(full)
        targets = {}
        for t, w, a, y_new, new, _ in stored_targets(work, name):
            X = m_all.X[comp.selected_[t]].to_numpy()
            assert len(X) == len(y_new), (name, t, len(X), len(y_new))
            lev = beyond(m_fit.X[comp.selected_[t]].to_numpy(), X)["lev"]
            test = {k[5:]: a[k] for k in a.files if k.startswith("pred_") and k != "pred_auto"}
            targets[t] = {"y": np.where(new, y_new, np.nan), "blend": sum(v * test[n] for n, v in w.items()),
                          "mlr": test["mlr"], "lev": lev, "campaign": a["campaign"],
                          "warm": np.array([ids[k] in continuing for k in a["campaign"]]),
                          "lag": np.array(_lag_kept(w))}
        _save(out, name, targets)


def rows(root: str, out: str, *records: str) -> None:
    from bench_auto98 import _with_root
    from bench_auto98b import beyond, fitted

    from thermocomp.core.continuation import predecessors

    _with_root(root, records)
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        auto, ds, train, meas, pred, base = fitted(root, name)
        ids = ds.ids("test")
        m_fit = auto.stacked(train)
        parts = {c: auto.stacked({c: ds.campaigns[c]}) for c in ids}
        targets = {}
        for t, est in auto.estimators_.items():
            cols = auto.selected_[t]
            X = np.vstack([parts[c].X[cols].to_numpy() for c in ids])
            campaign = np.concatenate([np.full(len(parts[c].X), k) for k, c in enumerate(ids)])
            warm = np.concatenate([np.full(len(parts[c].X), c in predecessors(ds)) for c in ids])
            assert len(X) == len(meas[t]), (name, t, len(X), len(meas[t]))
            targets[t] = {"y": meas[t], "blend": pred[t], "mlr": base[t], "campaign": campaign, "warm": warm,
                          "lev": beyond(m_fit.X[cols].to_numpy(), X)["lev"],
                          "lag": np.array(_lag_kept(dict(est.weights_)))}
        _save(out, name, targets)


def oof22(root: str, main_work: str, out: str, forms: str, *records: str) -> None:
    """The final refit's out-of-fold rows (main's stored ``oof_*``; auto's own folds rebuilt,
    checked against ``oof_y``): per lag target, a fold's scored rows beyond the region of its fit
    rows and, per form, those in a sustained excursion (a fold's rows of one campaign as one
    stream): the blend's and MLR's squared error on them (does MLR win where the train data's own
    excursions are?).  OUT/oof.RECORD.json."""
    import json

    from bench_auto91 import stored_targets
    from bench_auto98b import framed

    from thermocomp.core.model_selection.extrapolation import within_range
    from thermocomp.shell.builders import build_compensator

    work = Path(main_work).resolve()
    Path(out).mkdir(parents=True, exist_ok=True)
    forms = [_form(f) for f in forms.split(",")]
    for name in records:
        cfg, ds, _, _, comp, m_fit, _ = framed(root, work, name)
        folds, groups = _folds(build_compensator(cfg, ds=ds).estimator, m_fit)
        rep = {}
        for t, w, a, _, _, members in stored_targets(work, name):
            if not _lag_kept(w):
                continue
            X, y_all = m_fit.X[comp.selected_[t]].to_numpy(), m_fit.Y[t].to_numpy()
            scored = [score & np.isfinite(y_all) for _, score in folds]
            y = np.concatenate([y_all[s] for s in scored])
            assert np.allclose(y, a["oof_y"], equal_nan=True), (name, t, len(y), len(a["oof_y"]))
            lev = np.concatenate([~within_range(X, fit, s)[s] for (fit, _), s in zip(folds, scored)])
            stream = np.concatenate([k * 10_000 + groups[s] for k, s in enumerate(scored)])
            blend = sum(v * members[n] for n, v in w.items())
            c = {"lev": lev, "campaign": stream, "warm": np.zeros(len(y), bool), "lag": True, "y": y}
            cell = {"n": len(y), "beyond": int(lev.sum()),
                    "sse": [float(np.sum((y - blend) ** 2)), float(np.sum((y - members["mlr"]) ** 2))]}
            for form in forms:
                rows = handed(c, *form)
                cell[_said(form)] = [int(rows.sum()), float(np.sum((y - blend)[rows] ** 2)),
                                     float(np.sum((y - members["mlr"])[rows] ** 2))]
            rep[t] = cell
        Path(out, f"oof.{name}.json").write_text(json.dumps(rep, indent=1))
        print(name, "; ".join(f"{t} beyond {c['beyond']}/{c['n']} " + " ".join(
            f"{k} {v[0]} b|m {v[1]:.3g}|{v[2]:.3g}" for k, v in c.items()
            if isinstance(v, list) and k != "sse")
            for t, c in rep.items()) or "no lag target", flush=True)


def _folds(auto, m) -> tuple[list, np.ndarray]:
    """``([(fit, score) row masks], campaign code per row)``: the folds ``auto`` (the configured
    AutoRegressor) validates on over the stacked train rows ``m``, as its ``fit`` builds them."""
    from thermocomp.core.context import groups_of
    from thermocomp.core.models.auto import BLOCKS_ONE, FORWARD_ONE, _scheme

    groups = groups_of(m.context)
    auto.scheme_ = _scheme(auto.scheme, groups)
    if auto.scheme_ == FORWARD_ONE:
        auto.scheme_ = BLOCKS_ONE.get(auto.one_record, FORWARD_ONE)
    codes = (np.zeros(len(m.X), int) if groups is None
             else np.unique(groups.astype(str), return_inverse=True)[1])
    return [(fit, score) for fit, _, score in auto._folds(groups, len(m.X))], codes


def _load(out: str, name: str) -> dict:
    a = np.load(Path(out, f"{name}.npz"))
    targets = {}
    for key in a.files:
        t, k = key.rsplit(".", 1)
        targets.setdefault(t, {})[k] = a[key]
    return targets


def _rmse(y, p) -> float:
    keep = np.isfinite(y) & np.isfinite(p)
    return float(np.sqrt(np.mean((y[keep] - p[keep]) ** 2)))


def handed(c: dict, window: float, share: float, latch: bool = False, grow: bool = False) -> np.ndarray:
    """The rows of target ``c`` handed to MLR: a lag-family target in a sustained excursion
    (``latch``: from the first such row to its stream's end; ``grow``: :func:`excursion`'s)."""
    if not c["lag"]:
        return np.zeros(len(c["y"]), bool)
    rows = excursion(c["lev"], c["campaign"], window, c["warm"], grow) >= share
    if latch:
        for k in np.unique(c["campaign"]):
            mine = np.flatnonzero(c["campaign"] == k)
            rows[mine] = np.maximum.accumulate(rows[mine])
    return rows


def figures(out: str, name: str, forms: list) -> dict:
    """bench_auto96's figure of ``name``: main, then per form (figure, rows handed over)."""
    targets = _load(out, name)
    mlr = np.mean([_rmse(c["y"], c["mlr"]) for c in targets.values()])
    fig = {"main": np.mean([_rmse(c["y"], c["blend"]) for c in targets.values()]) / mlr}
    for form in forms:
        rule, rows_handed = [], 0
        for c in targets.values():
            swap = handed(c, *form)
            rule.append(_rmse(c["y"], np.where(swap, c["mlr"], c["blend"])))
            rows_handed += int((swap & np.isfinite(c["y"])).sum())
        fig[form] = (np.mean(rule) / mlr, rows_handed)
    return fig


def _form(text: str) -> tuple:
    """``W:s[:latch][:grow]`` -> ``(W, s, latch, grow)``."""
    parts = text.split(":")
    return float(parts[0]), float(parts[1]), "latch" in parts[2:], "grow" in parts[2:]


def _said(form: tuple) -> str:
    return f"{form[0]:g}:{form[1]:g}" + (":latch" if form[2] else "") + (":grow" if form[3] else "")


def sustain(out: str, forms: str, *records: str) -> None:
    from bench_auto96 import _geo

    forms = [_form(f) for f in forms.split(",")]
    figs = {name: figures(out, name, forms) for name in records}
    for name, fig in figs.items():
        print(f"{name:11s} main {fig['main']:.3f} " + " ".join(
            f"{_said(k)} {v:.3f} ({v / fig['main']:.3f}, {n})"
            for k, (v, n) in ((k, f) for k, f in fig.items() if k != "main")), flush=True)
    main = [f["main"] for f in figs.values()]
    for form in forms:
        rule = [f[form][0] for f in figs.values()]
        ratio = np.divide(rule, main)
        worst = list(figs)[int(np.argmax(ratio))]
        print(f"{len(main)} records, {_said(form)}: geo main {_geo(main):.4f} rule "
              f"{_geo(rule):.4f}; losers {sum(v > 1 for v in main)} -> {sum(v > 1 for v in rule)}; "
              f"> 1 % worse {int(np.sum(ratio > 1.01))}; worst {worst} {ratio.max():.3f}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"rows22": rows22, "rows": rows, "oof22": oof22, "sustain": sustain}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
