"""``model=auto``'s one-fold vote, members that must earn their weight (``one_fold=earned``): the
rule bench_auto93c prototyped (``earned_one``), built in ``vote_weights`` and scored through the
built code (issue 34; stop 93, auto93d).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_auto93d.py seen ROOT OUT     # lab5401 + 9609-9613 (seen), votes vs earned
    python benchmarks/bench_auto93d.py fresh ROOT OUT    # seeds 9629-9633, once (bar)

Both commands write lab5401's generator (bench_auto_losses56's ``lab_record``: ``large_mill_week``
with the seed, a 30 h train week cut into three 10 h runs, a 12 h test run) into ROOT where absent,
and fit ``model=auto`` on each record twice, ``model.estimator.one_fold=votes`` (main's weights)
and ``one_fold=earned`` (the rule, the built default), each test campaign predicted as ``run``
scores it (bench_auto93c's ``trace``: OUT/votes and OUT/earned hold its per-target tables); per
record the mean over targets of the pooled test RMSE over MLR's.  ``seen``: lab5401 (its own test
run Lauf_4) and auto93c's fresh labs 9609-9613, now seen, beside the prototype's figures.

The rule (``vote_weights(..., earned_one=True)``, ``AutoRegressor(one_fold='earned')``): where
the voting rows hold ONE fold (main's one-SE ``fallback`` needs two and cannot act there), each
candidate keeps its vote weight only where its resampled fold ratio (its summed squared error over
MLR's on the fold, over the votes' own resamples of the fold's blocks: ``resampled``, resample x
candidate) has mean + standard deviation below 1; otherwise its weight goes to MLR.  The prototype
(bench_auto93c's ``probe earned_one``) read the fold's ratio + bench_auto91's 500-draw block
bootstrap SE instead: the same blocks, another draw.  A record voting on two or more folds (every
climate room, every record of bench_auto93c's 28 seen but lab5401) is untouched by construction.

BAR (auto93c's, unchanged; written here BEFORE the fresh seeds 9629-9633 were drawn): FRESH
9629-9633 scored ONCE by ``fresh``: (a) no fresh record worse than auto (``one_fold=votes``) by
> 1 %, (b) geo rule / auto over the 5 <= 1.0, (c) the fresh losers (auto / MLR > 1.02) counted
with those the rule brings within 2 % of MLR.  KEPT = (a) and (b) and at least one fresh record
improved by the rule; else REFUSED (src reverted, the diff in ``benchmarks/auto93d_rule.patch``).
Seen (not a gate, a check of the build): lab5401 and 9609-9613 through the built code against the
prototype's 1.024 -> 1.000 (Lauf_4) and 1.093 1.257 1.318 1.248 1.307 -> 1.064 1.267 1.062 1.000
1.005; a difference beyond 0.01 on a record is reported with its cause.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto88b as auto88b  # noqa: E402
import bench_auto93c as auto93c  # noqa: E402
from _cli import run_commands  # noqa: E402

SEEN = (5401, 9609, 9610, 9611, 9612, 9613)
FRESH = range(9629, 9634)           # lab5401's generator drawn again, named before any was drawn
RULES = ("votes", "earned")         # model.estimator.one_fold: main's weights, the rule
PROTOTYPE = {5401: (1.024, 1.000), 9609: (1.093, 1.064), 9610: (1.257, 1.267), 9611: (1.318, 1.062),
             9612: (1.248, 1.000), 9613: (1.307, 1.005)}   # bench_auto93c: auto / MLR, rule / MLR


def _score(root: str, out: str, seeds) -> list[tuple[str, float, float, list]]:
    """Per record ``(name, auto / MLR, rule / MLR, folds per target)``, each fitted under both
    :data:`RULES` (bench_auto93c's ``trace``)."""
    from bench_auto_losses56 import lab_record

    root_path, out_path = Path(root).resolve(), Path(out).resolve()
    names = []
    for s in seeds:
        if not (root_path / f"lab{s}").exists():
            lab_record(root_path / f"lab{s}", seed=s)
        names.append(f"lab{s}")
        for rule in RULES:
            auto88b.RECORDS[f"lab{s}"] = [f"data.path={root_path / f'lab{s}'}",
                                          f"model.estimator.one_fold={rule}"]
            auto93c.trace(str(out_path / rule), f"lab{s}")
    rows = {rule: auto93c._records(out_path / rule / "targets.jsonl") for rule in RULES}
    table = []
    for n in names:
        main, rule = rows["votes"][n], rows["earned"][n]
        assert np.allclose(main["mlr"], rule["mlr"])   # MLR is the same fit under both
        m = float(np.mean(main["mlr"]))
        table.append((n, float(np.mean(main["auto"])) / m, float(np.mean(rule["auto"])) / m,
                      main["folds"]))
    return table


def _print(table, prototype: dict | None = None) -> np.ndarray:
    print("record    auto/MLR  rule/MLR  rule/auto  folds per target" + ("  prototype" if prototype else ""))
    ratios = []
    for n, a, r, folds in table:
        ratios.append(r / a)
        proto = prototype.get(int(n[3:])) if prototype else None
        tail = f"  {proto[0]:.3f} -> {proto[1]:.3f}" if proto else ""
        print(f"{n:9s} {a:8.3f} {r:9.3f} {r / a:10.3f}  {folds}{tail}")
    ratios = np.array(ratios)
    print(f"geo rule / auto over the {len(ratios)}: {np.exp(np.mean(np.log(ratios))):.4f}")
    return ratios


def seen(root: str, out: str) -> None:
    """lab5401 and 9609-9613 (seen) through the built code, beside the prototype's figures."""
    _print(_score(root, out, SEEN), PROTOTYPE)


def fresh(root: str, out: str) -> None:
    """Once, for the bar: :data:`FRESH`, auto under both :data:`RULES`, and the bar's verdict."""
    table = _score(root, out, FRESH)
    ratios = _print(table)
    losers = [n for n, a, *_ in table if a > 1.02]
    fixed = [n for n, a, r, _ in table if a > 1.02 and r <= 1.02]
    worse, improved = int(np.sum(ratios > 1.01)), int(np.sum(ratios < 1.0))
    geo = float(np.exp(np.mean(np.log(ratios))))
    print(f"(a) worse than auto by > 1 %: {worse}; (b) geo {geo:.4f}; (c) losers {losers}, within 2 % "
          f"of MLR by the rule {fixed}; improved {improved}")
    print("bar: " + ("PASSES" if worse == 0 and geo <= 1.0 and improved >= 1 else "FAILS"))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": seen, "fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
