"""Diagnose's harmful round-1 start lags: the one-standard-error rule on the accepted lag, or the
lag's early transient at test time (stop 93, diag93b; issue 34: "diagnose ... never leaves a
record's test error more than 2 % worse"; bench_diag92's harm rows, diag92c refused).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag93b.py trace ROOT SET        # its start lags -> ROOT/trace-SET.jsonl
    python benchmarks/bench_diag93b.py offsets CASE/TARGET... # the lag's plateau per campaign, train vs test
    python benchmarks/bench_diag93b.py draws ROOT LABEL SET  # SET's draws -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag93b.py compare ROOT SET A B  # two labels' rows of SET: the bar's counts

:data:`SETS`: ``seen`` bench_diag92's ``scan`` draws (= bench_diag92c's ``seen``, 70 draws: bench_diag91b's
``trace`` less few:4004, its ``seen``, the spent fresh 9336-9345 and 9436-9445), ``fresh`` 9546-9555
(clean 9546-9549, planted 9550-9552, lag 9553-9555; bench_diag86's ``draw``, 12 campaigns, every 3rd
test, 8 train: bench_diag92's generator).  Each draw diagnosed with MLR on every target,
``max_effects=2`` (as bench_diag92).  ``trace``: every round whose accepted effect is a lag from the
initial thermal state (a "start lag"), read in the round itself (``Search._family_bar`` wrapped,
nothing changed): (a) the one-standard-error rule -- is "no effect" (the round's current CV) within
one SE of the best rival's mean campaign MSE (ESL 7.10, as ``choose``; and on the test blocks), and
which start lag is the shortest (tau, then fewest regressors) within that band, among all refitted
start lags and among the cleared ones; the test RMSE had each been taken in its place
(bench_diag92's ``_test_rmse``: the effect fitted into the base model with the round's earlier
effects at its CV penalty); (b) the share of the lag's CV SSE gain on held-out rows within one tau
of their campaign's start against the share of those rows, and the test SSE change within one tau
and after it, summed over the test campaigns.  ``offsets``: the diagnosed effects' contribution
per campaign on the plateau (rows past tau), train against test, with the offset the before model
left on each test campaign (not comparable to it: the base is refitted with the effect; read for
the range only).  ``draws`` / ``compare``: bench_diag91's rows (for a rule; not run, below).

Trace (2026-12-05, main 5fe17063's src = this tree's; 2 cores shared; SEEN rows only)
-------------------------------------------------------------------------------------
27 accepted start lags over the 70 seen draws (25 in round 1): 18 help (-25.6 .. -72.0 % on the
target), 9 harm: 8457 E_X +52.5, 9046 E_X +29.0, 8969 E_X +21.7, 8178 E_Z +21.5, 8170 E_X +14.9,
9342 E_X +13.9, 9443 E_Y +13.3, 8075 E_Y +6.6, 9266 E_X +1.5 % (test as run).

(a) The one-SE rule.  "No effect within one SE of the best" holds on NONE of the 27 rows, by
campaigns or by test blocks: the gains are 4-130 SE (harms: 8969 mean campaign MSE 0.476 vs the
best's 0.270 + SE 0.042; 9443 E_Y 1.60 vs 0.49 + 0.074; 8170 0.325 vs 0.199 + 0.023; 9046 1.45 vs
0.191 + 0.010).  The shortest start lag in the band (what-if test change, accepted -> shortest):
the accepted one already on 8969 (+25.0), 9046 (+24.9), 9443 E_Y (+16.5), 8170 (+16.8), 9266
(+2.7); another and worse on 8457 +60.0 -> +72.9, 9342 +14.6 -> +57.3, 8178 +23.0 -> +23.9, 8075
+6.1 -> +6.5: it mends none of the 9.  On the helpful rows it loses 9193 -72.0 -> -57.3, 9269
-51.6 -> -32.7, 8980 -48.8 -> -38.6, 9268 -49.7 -> -38.3, 9345 -53.8 -> -45.7, 9103 E_Y (round 2)
-49.2 -> -42.8, 9444 -40.1 -> -36.7 (gains 9290 -60.0 -> -65.6, 9343 -62.7 -> -64.9, 9288 / 9289
< 1.1 points).  Among the cleared ones only: 2 rows change, both worse (8457 +60.0 -> +72.9, 9345
-53.8 -> -45.7).  Refused as a rule on the seen rows.

(b) The early transient.  The harms' CV gain is NOT in the campaigns' first minutes: within one
tau of the start they gain 0.01-0.18 of their SSE gain on 0.04-0.32 of the rows (less than an even
spread: 8969 0.18 / 0.32, 9443 E_Y 0.07 / 0.16, 9046 0.01 / 0.07, 8170 0.03 / 0.04), and their test
harm lies on the plateau too (test SSE change µm^2, within tau / after: 8969 +22.9 / +79.9, 9443
E_Y -17.9 / +177.8, 9046 +2.9 / +86.3, 8457 +32.5 / +116.9, 9342 0.0 / +65.3, 8170 -2.0 / +63.2,
8178 +0.9 / +57.0, 8075 -5.3 / +21.0).  Past tau the start block is one constant per campaign
(``w'(c(0) - A_0)``): the harm is that offset, not the transient.  The ratio (gain share / row
share) does not separate: harms 0.13-0.75, helpful round-1 lags 0.49-1.30, the real round-2 gains
0.33 (9103 E_Y) and 0.59 (8885 E_Y).  ``offsets``: the test campaigns' plateau lies outside the
train campaigns' range on 9443 E_Y (K03 / K12 -15.8 / -18.9 against [-12.3, -6.1]), 8457 (K06
3.01 against <= 2.96), 8170 (K12 0.97 against <= 0.92), inside on 8969, 9046, 9342, 8178, 8075,
9266 -- and outside on helpful rows as well (9289 E_X K03 / K06 22.8 / 21.3 against <= 21.0; 9443
E_X K03 / K06 / K12 24-25 against <= 20.1): no separation by the offset's range either.

Why no train-side rule can mend most of them (bench_diag92's ``splits``, run here for the rows it
had not: the same lag on 30 random 8 / 4 splits of the 12 campaigns, numpy seed 0, test RMSE
ratio median; the draw's split): 9046 0.586 (1.249), 9342 0.799 (1.146), 8075 0.831 (1.061), 8457
0.918 (1.600), 9266 0.978 (1.027); bench_diag92's 9443 E_Y 0.857, 8969 0.995.  Seven of the nine
harm rows are lags that help or are neutral on most splits: their harm is the fixed split (every
3rd campaign; K06 held out: median ratio 1.91 on 8457, 1.59 on 8178 / 9266, 1.19 on 9046).  Only
the two clean 900 s start lags harm on most splits: 8170 1.123 (> 1.02 in 83 %), 8178 1.042 (57 %).

The bar (written before any fresh run; NOT applied: neither rule passed the seen rows, so none
was built): KEPT only if, FRESH 9546-9555, no (draw, target) row more than 2 % worse than main,
clean accept nothing, the position found wherever main finds it; SEEN: no row more than 2 % worse
than main, the harm rows counted (fewer > 2 % worse than main's 9), docs/diagnose.md's door example
printing the same numbers; tests/*/test_diag*.py pass.  Fresh 9546-9555 UNSPENT.

Verdict: **TRACED** (src as main).  Next: a rule can only aim at the clean draws' short start lags
(8170 / 8178: 900 s, 3 directions: at 300 s samples a plateau from the 4th), whose harm holds over splits;
the other seven need a test of the split itself (more test campaigns), not a train-side rule.
CPU (the bench's own line, user + sys): ``trace seen`` 76.9 s (70 draws, with the what-ifs);
``offsets`` 16.7 s (11 rows); bench_diag92 ``splits`` 4.1-5.7 s a row.
"""

from __future__ import annotations

import json
import sys
from contextlib import contextmanager
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import made_folder, run_commands  # noqa: E402
from bench_diag91 import compare, diagnose_cases  # noqa: E402 (the same rows)
from bench_diag92c import SETS as SETS_92C  # noqa: E402
from bench_diag92c import _dataset  # noqa: E402

SETS = {
    "seen": SETS_92C["seen"],
    "fresh": ([("clean", s) for s in range(9546, 9550)] + [("planted", s) for s in range(9550, 9553)]
              + [("lag", s) for s in range(9553, 9556)]),
}


@contextmanager
def _rounds_captured(rounds: list):
    """Each round's family test appends ``(search, evals, current)`` to ``rounds`` (nothing
    changed: the round's current and candidates on the blocks it tests)."""
    from thermocomp.apps.diagnose import search as search_module

    original = search_module.Search._family_bar

    def captured(self, evals, current):
        original(self, evals, current)
        rounds.append((self, list(evals), current))

    search_module.Search._family_bar = captured
    try:
        yield rounds
    finally:
        search_module.Search._family_bar = original


def _start_lag(ev) -> bool:
    return ev.effect.kind == "dynamics" and bool(ev.effect.initial_state)


def _one_se(mse: np.ndarray) -> float:
    """The top of the one-standard-error band over ``mse``'s units (ESL 7.10, as ``choose``)."""
    return float(mse.mean() + (mse.std(ddof=1) / np.sqrt(mse.size) if mse.size > 1 else 0.0))


def _elapsed(time: np.ndarray, campaigns: np.ndarray) -> np.ndarray:
    """Seconds since each campaign's first row."""
    out = np.empty_like(time)
    for c in np.unique(campaigns):
        m = campaigns == c
        out[m] = time[m] - time[m].min()
    return out


def _early_share(problem, before, after, tau: float) -> tuple[float, float]:
    """Share of the CV SSE gain on held-out rows within ``tau`` of their campaign's start, and
    the share of those rows (what an even gain would give)."""
    ok = problem.validated & np.isfinite(before) & np.isfinite(after)
    early = _elapsed(problem.context["time"].to_numpy(float), np.asarray(problem.campaigns)) < tau
    gain = before ** 2 - after ** 2
    total = float(np.sum(gain[ok]))
    share = float(np.sum(gain[ok & early])) / total if total else float("nan")
    return share, float(np.mean(early[ok]))


def _test_early(ds, d, target: str, tau: float) -> tuple[float, float]:
    """The test campaigns' SSE change (after - before) within ``tau`` of their start, and after."""
    k = list(d.targets).index(target)
    early_sum = late_sum = 0.0
    for c in d.cv["test_campaigns"]:
        t = ds.campaigns[c]["time"].to_numpy(float)
        early = (t - t[0]) < tau
        (mb, pb), (ma, pa) = d.predictions["before"][c], d.predictions["after"][c]
        change = (np.asarray(ma)[:, k] - np.asarray(pa)[:, k]) ** 2 - (np.asarray(mb)[:, k]
                                                                        - np.asarray(pb)[:, k]) ** 2
        early_sum += float(np.nansum(change[early]))
        late_sum += float(np.nansum(change[~early]))
    return early_sum, late_sum


def _read(ds, d, search, evals, current, acc) -> dict:
    """The one-SE reads, the what-ifs and the early shares of one round's accepted start lag."""
    from bench_diag92 import _test_rmse

    target = search.problem.target
    rivals = [ev for ev in evals if not ev.control and ev.effect.transform != "remove"]
    best = max(rivals, key=lambda ev: ev.gain)
    top_unit = _one_se(best.result.unit_mse)
    lags = [ev for ev in rivals if _start_lag(ev) and ev.result.unit_mse.mean() <= top_unit]
    shortest = min(lags, key=lambda ev: (ev.effect.tau_s, ev.n_features), default=None)
    cleared = min([acc] + [ev for ev in lags if ev.clears_bar],
                  key=lambda ev: (ev.effect.tau_s, ev.n_features))
    prior = [ev.effect for ev in d.targets[target].accepted if ev.effect.transform != "remove"]
    prior = prior[:prior.index(acc.effect)]
    whatif = {which: _test_rmse(d, ds, prior + [ev.effect], target, ev.alpha)
              for which, ev in (("accepted", acc), ("shortest", shortest), ("shortest_cleared", cleared))
              if ev is not None}
    early, rows_early = _early_share(search.problem, current.residual, acc.result.residual, acc.effect.tau_s)
    test_early, test_late = _test_early(ds, d, target, acc.effect.tau_s)
    j = d.to_json(target)
    return {"target": target, "effect": acc.effect.title, "tau": acc.effect.tau_s, "gain": acc.gain_pct,
            "within": acc.gain_pct_within, "n_units": int(current.unit_mse.size),
            "n_blocks": int(current.block_mse.size),
            "none_in_band_unit": bool(current.unit_mse.mean() <= top_unit),
            "none_in_band_block": bool(current.block_mse.mean() <= _one_se(best.result.block_mse)),
            "band_unit": (float(current.unit_mse.mean()), float(best.result.unit_mse.mean()), top_unit),
            "best": best.effect.title, "shortest": shortest.effect.title if shortest else None,
            "shortest_cleared": cleared.effect.title, "whatif": whatif,
            "early_share": early, "early_rows": rows_early, "test_early": test_early, "test_late": test_late,
            "accepted_all": [ev.effect.title for ev in d.targets[target].accepted],
            "test_before": j["before"]["test_rmse"],
            "test_change": 100 * (j["after"]["test_rmse"] / j["before"]["test_rmse"] - 1)}


def _print(r: dict) -> None:
    cur, best, top = r["band_unit"]
    same = "=" if r["shortest"] == r["effect"] else (r["shortest"] or "-")[:30]
    print(f"  {r['case']:14s} {r['target']} r{r['round']} {r['effect'][:44]:44s} "
          f"test {r['test_change']:+6.1f} %"
          f" | none in 1-SE: unit {'Y' if r['none_in_band_unit'] else 'n'} ({cur:.3g} vs {best:.3g}"
          f"+{top - best:.2g}) block {'Y' if r['none_in_band_block'] else 'n'} | shortest {same}"
          f" | early share {r['early_share']:.2f} (rows {r['early_rows']:.2f}) test dSSE early"
          f" {r['test_early']:+.2f} late {r['test_late']:+.2f}")
    before = r["test_before"]
    cleared = "=" if r["shortest_cleared"] == r["effect"] else r["shortest_cleared"][:50]
    whatif = ", ".join(f"{k} {100 * (v / before - 1):+.1f}" for k, v in r["whatif"].items())
    print(f"      what-if test (%): {whatif}; shortest cleared {cleared}")


def trace(root: str, name: str) -> None:
    """Every accepted start lag of :data:`SETS` ``name``: the one-SE reads and the early share
    -> ``ROOT/trace-NAME.jsonl`` and a table (module doc)."""
    start_lag_rows(root, name, _read, _print)


def start_lag_rows(root: str, name: str, read, show) -> None:
    """Each round of :data:`SETS` ``name`` whose accepted effect is a start lag: ``read(ds, d,
    search, evals, current, accepted)`` -> a row of ``ROOT/trace-NAME.jsonl``; ``show(row)`` prints
    the rows by test change."""
    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    rows = []
    with open(made_folder(root) / f"trace-{name}.jsonl", "w") as out:
        for kind, seed in SETS[name]:
            ds, _ = _dataset(kind, seed)
            with _rounds_captured([]) as rounds:
                d = diagnose(ds, Compensator(MLR()), options=SearchOptions(max_effects=2))
            step = {}
            for search, evals, current in rounds:
                target = search.problem.target
                step[target] = step.get(target, 0) + 1
                acc = next((ev for ev in evals if ev.accepted), None)
                if acc is None or not _start_lag(acc):
                    continue
                row = {"case": f"{kind}:{seed}", "round": step[target],
                       **read(ds, d, search, evals, current, acc)}
                rows.append(row)
                print(json.dumps(row, default=float), file=out, flush=True)
    for r in sorted(rows, key=lambda r: r["test_change"]):
        show(r)


def offsets(*rows: str) -> None:
    """Each ``CASE/TARGET`` (its accepted effects, bench_diag92's diagnosis): per campaign the
    effects' contribution on the plateau (rows past the first accepted lag's tau) -- train, and
    test with the offset the before model left there (measured - predicted)."""
    from bench_diag92 import _diagnosed, _effect_terms

    for arg in rows:
        case, target = arg.rsplit("/", 1)
        ds, d, _ = _diagnosed(case)
        x, k = d.targets[target], list(d.targets).index(target)
        tau = x.accepted[0].effect.tau_s
        print(f"== {case} {target}: {[ev.effect.title[:50] for ev in x.accepted]}")
        for which in ("train_campaigns", "test_campaigns"):
            _, contribution, groups = _effect_terms(ds, d, target, d.cv[which])
            line = []
            for c in d.cv[which]:
                t = ds.campaigns[c]["time"].to_numpy(float)
                late = (t - t[0]) >= tau
                read = f"{c} {contribution[groups == c][late].mean():+.2f}"
                if which == "test_campaigns":
                    measured, predicted = d.predictions["before"][c]
                    left = np.nanmean((np.asarray(measured)[:, k] - np.asarray(predicted)[:, k])[late])
                    read += f" (left {left:+.2f})"
                line.append(read)
            print(f"  {which[:-10]:5s} plateau contribution: " + ", ".join(line))


def draws(root: str, label: str, name: str) -> None:
    """:data:`SETS` ``name`` diagnosed -> ``ROOT/NAME-LABEL.jsonl`` (bench_diag91's rows)."""
    diagnose_cases(root, label, name, SETS[name], _dataset)


def main(argv: list[str]) -> int:
    commands = {"trace": trace, "offsets": offsets, "draws": draws, "compare": compare}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
