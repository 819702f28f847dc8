"""Diagnose's accepted effect adopted in part, by its own cross-validated evidence (stop 95, diag95b;
issue 34: "diagnose ... never leaves a record's test error more than 2 % worse"; bench_diag92's 8
seen rows > 2 % worse than before diagnose, the train-side acceptance rules of diag93b / 94 / 94b /
94c refused or traced).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag95b.py trace ROOT SET [CASES]  # evidence + adoption curve -> ROOT/trace-SET.jsonl
    python benchmarks/bench_diag95b.py table ROOT SET          # trace-SET.jsonl read: factors, test
    python benchmarks/bench_diag95b.py draws ROOT LABEL SET    # SET's draws -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag95b.py compare ROOT SET A B    # two labels' rows of SET: the bar's counts

SET is :data:`SETS`'s: ``seen`` bench_diag92's 70 draws (bench_diag93b's ``seen``), ``fresh`` 9734-9738
(bench_diag92's design: bench_diag86's ``draw``, 12 campaigns, every 3rd test, 8 train; kinds below).
Each draw diagnosed as bench_diag92 (MLR, every target, ``max_effects=2``, test figures as run).
CASES (optional): ``kind:seed,kind:seed`` of SET only.

``trace`` (the code as it is; ``adopt`` of the diagnosed model set by hand, nothing else changed):
every accepted effect (not a sensor removal) read in its round, on the round's own test blocks and
CV units: the CV gain, the Student t of the per-unit MSE gains (``t_units``: the held-out campaigns,
or forward validation blocks) and of the per-block MSE gains (``t_blocks``), the CV-optimal blend
``s* = sum r0 (r0 - r1) / sum (r0 - r1)^2`` of the current CV residual ``r0`` and the candidate's
``r1`` and its jackknife t over the units; then the target's test RMSE with that effect adopted at
0, 0.25, 0.5, 0.75 and 1 (the target's other effects whole), and with every effect at each factor
rule's value.  ``table``: the rows read back, per rule the rows > 2 % worse than before diagnose
and the gain each helpful row keeps.  ``draws`` / ``compare``: bench_diag91's rows (``draws`` of the
rule needs its src: this tree at the bar's commit, or ``git apply benchmarks/diag95b_rule.patch``).

The rule (the brief's James-Stein factor; ``search.adoption``, ``SearchOptions.adopt``, default on)
---------------------------------------------------------------------------------------------------
WHAT is accepted is unchanged; HOW MUCH: with an MLR base (the closed-form CV, shrink on), each
accepted effect enters the deployed model with its coefficients (at the deployed penalty) scaled by
``a = max(0, 1 - 1/t^2)``, ``t`` the Student t of the per-unit CV MSE gains ``d_u = MSE_u - MSE+_u``
over the round's held-out units (8 campaigns here), and the inputs' coefficients refitted to what
the scaled effects leave (``PartialRidgePath.coefficients(alpha, adopted)``, Frisch-Waugh-Lovell);
``AugmentedRegressor(adopt=...)`` carries the factors, written into the diagnosed model's config
(``adopt``, per target).  The search itself (residuals, rounds, the bar) runs on whole effects.
The units, not the test blocks, because the campaigns are the exchangeable units (the module doc of
``search``) and the harms are campaign offsets (bench_diag93b).  Chosen after the ``trace`` of the
SEEN rows below (every factor there was computed on them; none of their constants is read off the
rows: the factor is the brief's formula as written).

The bar (written and committed before the rule's ``draws`` and before any fresh draw)
------------------------------------------------------------------------------------
SEEN (the 70 draws, ``draws seen`` main against the rule, ``compare``), read first; one failing:
REFUSED, src reverted, the rule in ``benchmarks/diag95b_rule.patch``, fresh 9734-9738 UNSPENT.
S1 rows > 2 % worse than before diagnose: fewer than main's 8.  S2 no helpful row (main's test
RMSE < 98 % of before) loses more than 5 points of its reduction (points of ``100 (after / before
- 1)``).  S3 the planted position accepted on each draw main accepts it (27 of 27).  S4 the clean
draws accept what main accepts (the rule cannot change it).  S5 no row more than 2 % worse than
main apart from the ones S2 allows.
FRESH 9734-9738 (clean 9734 / 9735, planted 9736 / 9737, lag 9738), scored once if S1-S5 hold:
F1 rows > 2 % worse than before diagnose not more than main's; F2 no helpful row loses more than 5
points; F3 the position found wherever main finds it; F4 clean draws accept nothing.  KEPT needs
S1-S5, F1-F4 and tests/apps/test_diagnose*.py, tests/test_lint.py passing.
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
from bench_diag92c import _dataset  # noqa: E402
from bench_diag93b import SETS as SETS_93B  # noqa: E402

SETS = {
    "seen": SETS_93B["seen"],
    "fresh": [("clean", 9734), ("clean", 9735), ("planted", 9736), ("planted", 9737), ("lag", 9738)],
}
FACTORS = (0.0, 0.25, 0.5, 0.75, 1.0)


@contextmanager
def _rounds_captured(rounds: list):
    """Each round's family test appends ``(search, evals, current)`` (nothing changed)."""
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


def _t(d: np.ndarray) -> float:
    """Student t of the mean of ``d`` (finite entries)."""
    d = d[np.isfinite(d)]
    if d.size < 2 or d.std(ddof=1) == 0:
        return float("nan")
    return float(d.mean() / (d.std(ddof=1) / np.sqrt(d.size)))


def _blend(problem, r0: np.ndarray, r1: np.ndarray) -> tuple[float, float]:
    """The CV-optimal share ``s*`` of the candidate's change and its jackknife t over the units."""
    ok = problem.validated & np.isfinite(r0) & np.isfinite(r1)
    units = problem.unit_index[ok]
    delta, r = r0[ok] - r1[ok], r0[ok]
    n = int(units.max()) + 1
    num = np.bincount(units, weights=r * delta, minlength=n)
    den = np.bincount(units, weights=delta * delta, minlength=n)
    s = float(num.sum() / den.sum())
    jack = np.array([(num.sum() - num[u]) / (den.sum() - den[u]) for u in range(n) if den[u] > 0])
    se = float(np.sqrt((jack.size - 1) / jack.size * np.sum((jack - jack.mean()) ** 2)))
    return s, (s / se if se > 0 else float("nan"))


def evidence(search, ev, current) -> dict:
    """The accepted ``ev``'s evidence in its round (module doc)."""
    res = ev.result
    s, t_s = _blend(search.problem, current.residual, res.residual)
    return {"effect": ev.effect.title, "n_features": ev.n_features, "gain_pct": ev.gain_pct,
            "p_family": ev.p_family, "blocks": int(current.block_mse.size),
            "units": int(current.unit_mse.size),
            "t_units": _t(current.unit_mse - res.unit_mse),
            "t_blocks": _t(current.block_mse - res.block_mse), "blend": s, "t_blend": t_s,
            "within_pct": ev.gain_pct_within, "rest_pct": ev.gain_pct_within_rest}


def js(t: float) -> float:
    """The positive-part James-Stein factor of an estimate ``t`` standard errors from 0."""
    return float(max(0.0, 1.0 - 1.0 / t ** 2)) if np.isfinite(t) and t != 0 else 0.0


RULES = {
    "t_units": lambda e: js(e["t_units"]),
    "t_blocks": lambda e: js(e["t_blocks"]),
    "blend": lambda e: float(np.clip(e["blend"], 0.0, 1.0)) * js(e["t_blend"]),
    "within": lambda e: (float(np.clip(e["within_pct"] / e["gain_pct"], 0.0, 1.0))
                         if e["within_pct"] is not None and e["gain_pct"] > 0 else 1.0),
}


def _test_rmse(d, ds, target: str, effects: list, adopt: list) -> float:
    """Test RMSE of ``target`` with ``effects`` fitted into the diagnosed draw's base model at the
    deployed penalty, each adopted by its factor in ``adopt``."""
    from thermocomp.apps.diagnose import diagnosis as dg

    base = d.before_model
    model = dg.augment(base, {target: effects}, (), list(base.inputs_),
                       {target: d.cv["shrink_alpha"][target]}, {target: adopt})
    fitted = dg.fit_joined(model, ds, d.cv["train_campaigns"])
    scores, _ = dg.test_scores(fitted, ds, d.cv["test_campaigns"], "simulation", "range", 10)
    return scores[target]["test"]["rmse"]


def trace_draw(kind: str, seed: int) -> dict:
    """One draw: every target's accepted effects, their evidence and adoption curve."""
    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    ds, _ = _dataset(kind, seed)
    rounds: list = []
    with _rounds_captured(rounds):
        d = diagnose(ds, Compensator(MLR()), options=SearchOptions(max_effects=2))
    row = {"case": f"{kind}:{seed}", "targets": {}}
    for target, x in d.targets.items():
        effects = x.search.effects
        if not effects:
            continue
        j = d.to_json(target)
        reads = [evidence(s, ev, cur) for s, evs, cur in rounds if s.problem.target == target
                 for ev in evs if ev.accepted and ev.effect.transform != "remove"]
        whole = _test_rmse(d, ds, target, effects, [1.0] * len(effects))
        curve = [[_test_rmse(d, ds, target, effects, [f if i == k else 1.0 for i in range(len(effects))])
                  for f in FACTORS] for k in range(len(effects))]
        rules = {}
        for name, rule in RULES.items():
            adopt = [rule(e) for e in reads]
            rules[name] = {"adopt": adopt, "test": _test_rmse(d, ds, target, effects, adopt)}
        row["targets"][target] = {"before": j["before"]["test_rmse"], "after": j["after"]["test_rmse"],
                                  "whole": whole, "alpha": d.cv["shrink_alpha"][target],
                                  "effects": reads, "curve": curve, "rules": rules}
    return row


def trace(root: str, name: str, cases: str = "") -> None:
    """SET ``name``'s draws traced (module doc) -> ``ROOT/trace-NAME.jsonl`` and a line per target."""
    chosen = SETS[name] if not cases else [tuple(c.split(":")) for c in cases.split(",")]
    with open(made_folder(root) / f"trace-{name}.jsonl", "a") as out:
        for kind, seed in chosen:
            row = trace_draw(kind, int(seed))
            print(json.dumps(row, default=float), file=out, flush=True)
            for target, v in row["targets"].items():
                change = 100 * (v["after"] / v["before"] - 1)
                print(f"{row['case']:14s} {target} {change:+6.1f} % "
                      + " | ".join(f"{e['effect'][:34]} g {e['gain_pct']:.1f} t_u {e['t_units']:.2f} "
                                   f"t_b {e['t_blocks']:.2f} s* {e['blend']:.2f} t_s {e['t_blend']:.2f} "
                                   f"w {e['within_pct'] or float('nan'):.1f}"
                                   for e in v["effects"])
                      + " | curve " + str([[round(100 * (c / v["before"] - 1), 1) for c in cu]
                                           for cu in v["curve"]])
                      + " | " + " ".join(f"{k} {[round(a, 2) for a in r['adopt']]} "
                                         f"{100 * (r['test'] / v['before'] - 1):+.1f}"
                                         for k, r in v["rules"].items()), flush=True)


def table(root: str, name: str) -> None:
    """``trace-NAME.jsonl`` read back: per rule, rows > 2 % worse than before diagnose, the
    helpful rows' gain kept (points of test RMSE change) and the worst loss of gain."""
    with open(Path(root) / f"trace-{name}.jsonl") as f:
        rows = [json.loads(line) for line in f]
    items = [(r["case"], t, v) for r in rows for t, v in r["targets"].items()]
    for rule in ["main", *RULES]:
        worse, losses = [], []
        for case, t, v in items:
            test = v["whole"] if rule == "main" else v["rules"][rule]["test"]
            main = 100 * (v["whole"] / v["before"] - 1)
            change = 100 * (test / v["before"] - 1)
            if change > 2.0:
                worse.append(f"{case} {t} {change:+.1f}")
            if main < -2.0:
                losses.append((change - main, f"{case} {t} {main:+.1f} -> {change:+.1f}"))
        losses.sort(reverse=True)
        print(f"{rule}: {len(worse)} rows > 2 % worse than before: {worse}")
        print(f"   helpful rows (main < -2 %): {len(losses)}, largest losses of gain (points): "
              f"{[s for _, s in losses[:6]]}")


def draws(root: str, label: str, name: str) -> None:
    """:data:`SETS` ``name`` diagnosed -> ``ROOT/NAME-LABEL.jsonl`` (bench_diag91's rows)."""
    diagnose_cases(root, label, name, SETS[name], _dataset)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "table": table, "draws": draws, "compare": compare},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
