"""A start lag's start part judged at the campaign level, leave one campaign out (stop 94, diag94b;
issue 34: "diagnose ... never leaves a record's test error more than 2 % worse"; bench_diag94: the
clean draws' harm (8170 E_X, 8178 E_Z) is the start block fitting per-campaign offsets, at any tau).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag94b.py trace ROOT SET        # its start lags' campaign reads -> ROOT/trace-SET.jsonl
    python benchmarks/bench_diag94b.py draws ROOT LABEL SET  # SET's draws -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag94b.py compare ROOT SET A B  # two labels' rows of SET: the bar's counts
    python benchmarks/bench_diag94b.py harm ROOT SET LABEL   # LABEL's rows > 2 % worse than before diagnose

SET is bench_diag93b's: ``seen`` bench_diag92's 70 draws, ``fresh`` 9546-9555 (clean 9546-9549,
planted 9550-9552, lag 9553-9555; 12 campaigns, every 3rd test, 8 train), each diagnosed with MLR
on every target, ``max_effects=2``.  ``trace`` (the tree's src): every round whose accepted effect
is a start lag, read in the round (bench_diag94's reads, by import) and at the CAMPAIGN level: with
8 train campaigns and ``n_folds=10`` the ``campaigns`` scheme's folds are one campaign each, so the
round's CV residuals are already leave-one-campaign-out.  Per held-out train campaign c, the mean
residual (its offset left) of the same lag WITHOUT its start block, ``o0_c``, and with it, ``o1_c``;
the campaign's gain ``d_c = o0_c^2 - o1_c^2`` (does the campaign's initial state, through the others'
fit, predict its offset?).  Reported: the pooled gain ``sum d_c / sum o0_c^2``, mean(d) / SE(d), the
count of campaigns that gain, the exact one-sided sign-flip p of mean(d) (``sign_flip_pvalue``), and
the same on each campaign's whole MSE (``unit_mse``) for comparison.  ``draws`` / ``compare`` /
``harm``: bench_diag94's.

The criterion (stated before any row was read)
----------------------------------------------
The start part is accepted only if its campaign-level gain is positive AND at least one standard
error: ``mean(d) > SE(d)`` (``SE = sd / sqrt(n)``), the one-SE rule the search already uses for its
penalty (ESL 7.10), over the held-out campaigns.  Not a p threshold: with 8 campaigns the exact
sign-flip test reaches p = 1/256 = 0.0039 at best (8 of 8 one way), with 12 1/4096; a 5 % test over
8 units needs 7 of 8 campaigns consistent, which a true start effect with 2-3 campaigns near zero
offset cannot show.  Where the start part is refused, the what-if is the same lag without it
(bench_diag94's ``plain_test``): the prototype's test effect per row.

The bar (bench_diag94's, unchanged; written before any fresh run)
----------------------------------------------------------------
KEPT only if: FRESH 9546-9555 no (draw, target) row more than 2 % worse than main, clean accept
nothing, the position found wherever main finds it; SEEN no row more than 2 % worse than main, no
helpful seen start lag lost by more than the harm rows gain, fewer rows > 2 % worse than before
diagnose than main's 8; docs/diagnose.md's door example printing the same numbers;
tests/*/test_diag*.py pass.  The seen items are read first: if one fails, the rule is REFUSED and
the fresh seeds stay unspent.  Round 2's real start lags (planted 9103 E_Y, 8885 E_Y) must be kept.

Trace (results below, once read)
--------------------------------
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402
from bench_diag91 import compare  # noqa: E402 (the same rows)
from bench_diag93b import start_lag_rows  # noqa: E402
from bench_diag94 import _read as _read_94  # noqa: E402
from bench_diag94 import draws, harm  # noqa: E402


def campaign_offsets(residual: np.ndarray, problem) -> np.ndarray:
    """Each held-out campaign's mean CV residual (its offset left), in ``problem.unit_names`` order."""
    ok = problem.validated & np.isfinite(residual)
    index = problem.unit_index[ok]
    n = problem.n_units
    return np.bincount(index, weights=residual[ok], minlength=n) / np.maximum(np.bincount(index, minlength=n), 1)


def campaign_test(d: np.ndarray) -> dict:
    """Campaign-level reads of per-campaign gains ``d``: mean / SE, count gaining, exact sign-flip p."""
    from thermocomp.apps.diagnose.cv import sign_flip_pvalue

    se = float(d.std(ddof=1) / np.sqrt(d.size)) if d.size > 1 else float("inf")
    return {"mean": float(d.mean()), "se": se, "t": float(d.mean() / se) if se > 0 else float("inf"),
            "n_gain": int(np.sum(d > 0)), "n": int(d.size), "p": float(sign_flip_pvalue(d))}


def _read(ds, d, search, evals, current, acc) -> dict:
    """bench_diag94's reads + the start block's extra over the same lag without it, by campaign."""
    from dataclasses import replace

    row = _read_94(ds, d, search, evals, current, acc)
    p = search.problem
    names = search.inputs()
    prior = [ev.effect for ev in d.targets[p.target].accepted if ev.effect.transform != "remove"]
    prior = prior[:prior.index(acc.effect)]
    plain = search.cv.run(names, prior + [replace(acc.effect, initial_state=None, initial_directions=None)])
    o0, o1 = campaign_offsets(plain.residual, p), campaign_offsets(acc.result.residual, p)
    offset = campaign_test(o0 ** 2 - o1 ** 2)
    whole = campaign_test(plain.unit_mse - acc.result.unit_mse)
    row.update({"n_units": int(p.n_units), "units_are_campaigns": bool(len(set(p.units)) == len(set(p.campaigns))),
                "offset_pooled": float(1 - np.sum(o1 ** 2) / np.sum(o0 ** 2)),
                "offset": offset, "whole": whole,
                "offsets_plain": o0.tolist(), "offsets_start": o1.tolist(),
                "start_kept": bool(offset["mean"] > offset["se"])})
    return row


def _print(r: dict) -> None:
    o, w = r["offset"], r["whole"]
    plain = 100 * (r["plain_test"] / r["test_before"] - 1)
    print(f"  {r['case']:14s} {r['target']} r{r['round']} tau/dt {r['tau_samples']:4.0f} test {r['test_change']:+6.1f} %"
          f" (plain {plain:+6.1f}) | offsets pooled {100 * r['offset_pooled']:+6.1f} % t {o['t']:+5.2f} "
          f"{o['n_gain']}/{o['n']} p {o['p']:.4f} | whole t {w['t']:+5.2f} {w['n_gain']}/{w['n']} p {w['p']:.4f}"
          f" | {'KEEP' if r['start_kept'] else 'refuse'}")


def trace(root: str, name: str) -> None:
    """Every accepted start lag of SET ``name``: the campaign-level reads (module doc)."""
    start_lag_rows(root, name, _read, _print)


def main(argv: list[str]) -> int:
    commands = {"trace": trace, "draws": draws, "compare": compare, "harm": harm}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
