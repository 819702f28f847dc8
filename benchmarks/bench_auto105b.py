"""``model=auto``'s blend hedged towards MLR (auto105's nested convex weight) only where the folds
are at least 3 whole campaigns (issue 34; stop 105, auto105b).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the vote code and the rows' src are
that tree's -- main's rows drawn on a copy of 0efa0fc4, the hedge replayed on them)::

    python benchmarks/bench_auto91.py rows ROOT STORE RECORD ...   # the 22-table's rows (main's auto)
    python benchmarks/bench_auto105b.py replay ROOT STORE          # the 22: main / gated hedge
    python benchmarks/bench_auto105b.py seen1 OUT                  # the 10 one-campaign records
    python benchmarks/bench_auto105b.py fl OUT                     # fl_thermal 90/10 replayed
    python benchmarks/bench_auto105b.py authors OUT                # fl_thermal 60/20/20 MAE, run
    python benchmarks/bench_auto105b.py fresh OUT                  # seeds 10030-10034, once (bar)

The rule (``hedge='campaigns'``, ``AutoRegressor._hedged``): auto105's hedge (bench_auto105's
``hedge_weight``: lam by the nested out-of-fold choice, ``lam * W + (1 - lam) * MLR``) where the
folds carry campaign-level evidence -- the record's train part holds >= 2 campaigns (the folds hold
out whole campaigns: ``CAMPAIGN_FOLDS``) and there are >= 3 folds (a nested choice on 2 folds is
one fold's).  Elsewhere W as on main.  How it differs from auto105 (REFUSED): its hedge acted on
any k >= 2 folds, one record's time blocks included; its after-the-fact ``k>=3`` probe still
counted time blocks (col5791, col1514, swiss5454 hedged) and the one-campaign records' blocks
(lr9640 1.121 x main).  Time blocks of one record share its conditions and drift: they do not tell
whether W's edge over MLR holds on another campaign, which is what the weight is for.  Decided on
the seen data (auto105's replay and probes) before any fresh record was drawn.

Whether a record's folds are campaigns is read from its train part (bench_auto_rank's ``setup``:
>= 2 train campaigns), as ``AutoRegressor._scheme`` reads it.

BAR (written and committed before ``replay`` on the redrawn rows, ``seen1``, ``fl``, ``authors``
were run on this rule and before seeds 10030-10034 were simulated; KEPT only if all hold):
(1) SEEN 22 (``replay`` on main 0efa0fc4's rows, redrawn): losers (auto / MLR > 1.0) at most 6 and
    the geometric mean of auto / MLR at most main's on the same rows.
(2) SEEN one-campaign (bench_auto94c's 10 records, own test, main's rows redrawn on 0efa0fc4):
    each record's hedge / main <= 1.01.
(3) fl_thermal: the 90/10 cut's mean RMSE >= 25 % under MLR's; the authors' 60/20/20 split re-run
    with the rule's src (``thermocomp run``): test MAE below the authors' GRU (3.56 / 3.76 / 3.70 /
    3.46 / 4.28) on >= 4 of 5 channels and on the mean.
(4) FRESH 10030-10034 (bench_auto105's :data:`FRESH`, the 22 table's kinds, own test, scored once):
    no record a new loser (main / MLR <= 1 and hedge / MLR > 1), and the geometric mean of
    hedge / MLR at most main's.

Measured (2026-12-07; main = a copy of 0efa0fc4 for every fit, the rule replayed from its stored
arrays; ``OMP_NUM_THREADS=1``, 2 shared cores, load 6-9; CPU user+sys: rows 226.7 s, ``replay``
12.5, ``seen1`` 34.8 (rows) + 4.4, ``fl`` 46.1, ``authors`` 13.5 (this tree's src), ``fresh`` 31.3).
KEPT: all four hold.

(1) SEEN 22 (``replay /tmp/auto105/root /tmp/auto105b/main``; main's rows as 4b70457f's: geo
    0.8257, the same 8 losers): hedged 15 targets of 8 records (year6_5411, year6511, year6512,
    jig_grinder, hmc, mtc_a, mtc_b, grind_b; lam 0.00-0.99), main -> rule: hmc 1.005 -> 0.954, mtc_b
    1.075 -> 0.901, mtc_a 0.704 -> 0.675, year6_5411 0.518 -> 0.537, year6511 0.348 -> 0.367,
    year6512 0.376 -> 0.378, the other 16 within 0.1 % (14 untouched: one train campaign, 2 folds,
    or 1 fold); losers 8 -> 6, geo 0.8257 -> 0.8192: met.  (No bar on it: 2 records > 1 % worse
    than main, year6_5411 1.038, year6511 1.055 -- both still far under MLR.)
(2) SEEN one-campaign (``seen1``): every record 1.000 x main (one train campaign: never hedged);
    geo 0.7654 both: met.
(3) fl_thermal 90/10 (one train record): 2.481 (38.9 % under MLR's 4.060), unchanged: met.  The
    authors' 60/20/20 split re-run with the rule on: MAE 1.170 / 1.411 / 4.078 / 1.399 / 2.529,
    mean 2.117 (GRU 3.752), below the GRU on 4 of 5 and the mean: met (a val split: no hedge).
(4) FRESH 10030-10034 (drawn once, after the bar and the seen results): col10030 0.819, sw10031
    0.558, lab10032 1.227 (one fold), untouched; year6_10033 0.337 -> 0.323 (E_X lam 0), year10034
    0.298 -> 0.297 (E_X lam 0.93); no new loser, geo 0.5626 -> 0.5576: met.

The built key agrees with the replay: ``hedge=campaigns`` fitted on mtc_b and hmc gives the
bench's mixed weights to 4 decimals (mtc_b E_dY lagbank 0.2464, hammerstein 0.4913, mlr 0.2622).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto87b as b87  # noqa: E402
import bench_auto105 as a105  # noqa: E402
from _cli import run_commands  # noqa: E402

MIN_CAMPAIGN_FOLDS = 3           # auto.MIN_HEDGE_FOLDS
AUTHORS = a105.AUTHORS


def _train_campaigns(overrides: list[str]) -> int:
    import bench_auto_rank as rank

    sys.argv[2:] = overrides             # bench_auto_rank simulates when sim= is asked
    return len(rank.setup(overrides)[2])


def _campaigns_of(cache: Path, overrides: dict) -> dict:
    """Per record, the number of train campaigns (cached in ``cache``)."""
    got = json.loads(cache.read_text()) if cache.exists() else {}
    for name, ov in overrides.items():
        if name not in got:
            got[name] = _train_campaigns(ov)
            cache.write_text(json.dumps(got, indent=1))
    return got


def gated_weight(a: dict, kept: dict, campaigns: int) -> float:
    """lam of the rule: auto105's nested weight where the folds are >= 3 whole campaigns, else 1."""
    if campaigns < 2 or np.unique(a["oof_fold"]).size < MIN_CAMPAIGN_FOLDS:
        return 1.0
    return a105.hedge_weight(a, kept)


def replay(root: str, store: str) -> None:
    """Per record of STORE: auto / MLR on the new campaigns, main (the stored W) and the rule."""
    import bench_automore69 as automore

    store_p = Path(store)
    rows = b87._load(store_p)
    camps = _campaigns_of(store_p / "train_campaigns.json",
                          {n: [o.format(root=root) for o in automore.OVERRIDES[n]] for n in rows})
    got, lams = {}, []
    for name, row in rows.items():
        fig = {k: [] for k in ("mlr", "main", "hedge")}
        for t, w in row["weights"].items():
            a = b87._arrays(store_p, name, t)
            if b87._nonzero(b87.choose(a)) != b87._nonzero(w):
                raise SystemExit(f"{name} {t}: stored weights {w}, choose gives {b87.choose(a)}")
            lam = gated_weight(a, w, camps[name])
            if lam < 1.0:
                lams.append(f"{name} {t} {lam:.2f}")
            fig["mlr"].append(b87._new(a, row, a["pred_mlr"]))
            fig["main"].append(b87._new(a, row, b87._deployed(a, w)))
            fig["hedge"].append(b87._new(a, row, b87._deployed(a, a105.mixed(w, lam))))
        got[name] = {k: float(np.mean(fig[k]) / np.mean(fig["mlr"])) for k in ("main", "hedge")}
        g = got[name]
        print(f"{name:12s} train campaigns {camps[name]:2d} folds {np.unique(a['oof_fold']).size}  "
              f"main {g['main']:.3f}  hedge {g['hedge']:.3f} ({g['hedge'] / g['main']:.3f})", flush=True)
    print("targets hedged (lam < 1): " + "; ".join(lams))
    geo = {}
    for k in ("main", "hedge"):
        r = np.array([g[k] for g in got.values()])
        geo[k] = a105._geo(r)
        worse = {n: round(g[k] / g["main"], 3) for n, g in got.items() if g[k] > 1.01 * g["main"]}
        print(f"{k:6s} losers {int((r > 1).sum())} of {r.size} "
              f"({', '.join(n for n, g in got.items() if g[k] > 1)}); geo {geo[k]:.4f}; "
              f"> 1 % worse than main: {worse or 'none'}")
    losers = sum(g["hedge"] > 1 for g in got.values())
    print(f"BAR (1) seen 22: {'met' if losers <= 6 and geo['hedge'] <= geo['main'] else 'NOT met'}")


def _scored(out: Path, names: list[str]) -> list[dict]:
    """Per record of OUT (bench_auto_rank's json + npz): test RMSE mean over targets, MLR / main /
    the rule, and the rule's lams."""
    camps = _campaigns_of(out / "train_campaigns.json",
                          {n: json.loads((out / f"{n}.json").read_text())["overrides"] for n in names})
    rows = []
    for name in names:
        rep = json.loads((out / f"{name}.json").read_text())
        fig, lams = {k: [] for k in ("mlr", "main", "hedge")}, {}
        for t, row in rep["targets"].items():
            with np.load(out / f"{name}.{t}.npz", allow_pickle=True) as z:
                a = {k: z[k] for k in z.files}
            w = {n: float(v) for n, v in row["auto"]["weights"].items()}
            lams[t] = round(gated_weight(a, w, camps[name]), 3)
            y = a["test_y"]

            def dep(ws: dict):
                return sum(v * a[f"test_{n}"] for n, v in ws.items()) if sum(ws.values()) > 0 else 0.0
            fig["mlr"].append(b87._rmse(y - a["test_mlr"]))
            fig["main"].append(b87._rmse(y - dep(w)))
            fig["hedge"].append(b87._rmse(y - dep(a105.mixed(w, lams[t]))))
        rows.append({"record": name, "campaigns": camps[name], "lam": lams,
                     **{k: float(np.mean(v)) for k, v in fig.items()}})
    return rows


def _table(rows: list[dict]) -> None:
    for r in rows:
        print(f"{r['record']:12s} train campaigns {r['campaigns']:2d}  main/MLR {r['main'] / r['mlr']:.3f}  "
              f"hedge/MLR {r['hedge'] / r['mlr']:.3f}  hedge/main {r['hedge'] / r['main']:.3f}  "
              f"lam {r['lam']}")
    print(f"geo main/MLR {a105._geo([r['main'] / r['mlr'] for r in rows]):.4f}  hedge/MLR "
          f"{a105._geo([r['hedge'] / r['mlr'] for r in rows]):.4f}")


def seen1(out: str) -> None:
    """The 10 seen one-campaign records (bench_auto94c's RECORDS, own test): bar (2)."""
    from bench_auto94c import RECORDS as ONE

    out_p = Path(out).resolve()
    for name, ov in ONE.items():
        if not (out_p / f"{name}.json").exists():
            a105._rank(out_p, name, list(ov))
    rows = _scored(out_p, list(ONE))
    _table(rows)
    worst = max(r["hedge"] / r["main"] for r in rows)
    print(f"worst hedge/main {worst:.4f}: BAR (2) {'met' if worst <= 1.01 else 'NOT met'}")


def fl(out: str) -> None:
    """fl_thermal 90/10 (bench_auto105's ``fl9010`` rows): bar (3)'s first half."""
    out_p = Path(out).resolve()
    if not (out_p / "fl9010.json").exists():
        a105._rank(out_p, "fl9010", a105.FL)
    r = _scored(out_p, ["fl9010"])[0]
    print(f"fl_thermal 90/10 mean RMSE: MLR {r['mlr']:.3f} main {r['main']:.3f} "
          f"({1 - r['main'] / r['mlr']:.1%} under MLR) hedge {r['hedge']:.3f} "
          f"({1 - r['hedge'] / r['mlr']:.1%} under MLR; train campaigns {r['campaigns']}, lam {r['lam']}): "
          f"BAR (3a) {'met' if r['hedge'] <= 0.75 * r['mlr'] else 'NOT met'}")


def authors(out: str) -> None:
    """``thermocomp run`` of model=auto on the authors' 60/20/20 split with this tree's src (the
    rule on by default): test MAE per channel against the authors' GRU: bar (3)'s second half."""
    out_p = Path(out).resolve()
    done = subprocess.run([sys.executable, "-m", "thermocomp", "run", *a105.FL60, "model=auto",
                           "track=false", "plots=none", f"out={out_p}"], capture_output=True, text=True,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))
    if done.returncode:
        raise SystemExit(f"run: exit {done.returncode}\n{done.stderr[-2000:]}")
    targets = json.loads((out_p / "metrics.json").read_text())["targets"]
    mae = [targets[t]["test"]["mae"] for t in sorted(targets)]
    beats = sum(m < g for m, g in zip(mae, AUTHORS))
    ok = beats >= 4 and np.mean(mae) < np.mean(AUTHORS)
    print(f"authors' split test MAE {', '.join(f'{m:.3f}' for m in mae)} (mean {np.mean(mae):.3f}; GRU "
          f"{np.mean(AUTHORS):.3f}), below the GRU on {beats} of 5; schemes "
          f"{[targets[t].get('auto', {}).get('reason', '')[-40:] for t in sorted(targets)]}: "
          f"BAR (3b) {'met' if ok else 'NOT met'}")


def fresh(out: str) -> None:
    """Seeds 10030-10034 (bench_auto105's :data:`FRESH`), fitted and scored ONCE: bar (4)."""
    from bench_auto_losses56 import lab_record

    out_p = Path(out).resolve()
    out_p.mkdir(parents=True, exist_ok=True)
    if not (out_p / "lab10032").exists():
        lab_record(out_p / "lab10032", seed=10032)
    for name, ov in a105.FRESH.items():
        if not (out_p / f"{name}.json").exists():
            a105._rank(out_p, name, [o.format(out=out_p) for o in ov])
    rows = _scored(out_p, list(a105.FRESH))
    _table(rows)
    new = [r["record"] for r in rows if r["main"] <= r["mlr"] < r["hedge"]]
    ok = not new and (a105._geo([r["hedge"] / r["mlr"] for r in rows])
                      <= a105._geo([r["main"] / r["mlr"] for r in rows]))
    print(f"new losers {new or 'none'}: BAR (4) {'met' if ok else 'NOT met'}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"replay": lambda root, store: replay(root, store),
                                  "seen1": lambda out: seen1(out), "fl": lambda out: fl(out),
                                  "authors": lambda out: authors(out),
                                  "fresh": lambda out: fresh(out)}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
