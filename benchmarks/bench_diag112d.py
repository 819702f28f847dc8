"""diag112's v2 refit-null surrogate scored unchanged (stop 112, diag112d).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag112d.py planted ROOT LABEL MODEL SEED...   # climate draws, model=MODEL

``planted`` is bench_diag112's, with the draws this one scores: bench_diag111's N2 planted draws
(their kinds from bench_diag107/107d/108) and the fresh 10278-10280 (kinds named before drawing);
MODEL ``lstm`` runs the tests' small LSTM.  bench_diag112's ``family`` and ``first MODEL`` give V3/V4.
``git apply benchmarks/diag112d_rule.patch`` (= diag112_rule.patch, v2 unchanged) in a scratch tree to
measure the rule.  REFUSED: it never took more than BASE but took less on 7 of the 30 (draw, target)
where BASE took something (model=arx, N2 but 10122): 10160 E_Z, 10161 E_X, 10175 E_Z, 10181 E_X+E_Z,
10183 E_Z, 10185 E_X, mostly the level law or a law pair BASE's refits pass at .01 (10160 E_Z: v2
refit p .02, test 6.813 kept vs BASE 3.149); fresh 10279 E_Z with arx_rf likewise (6.354 vs 1.874).
It was 3-5x cheaper (family, lstm, planted).  The bar: ``benchmarks/diag112d_bar.md``;
the figures: the diag112d report.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag107 as d107  # noqa: E402
import bench_diag107d as d107d  # noqa: E402
import bench_diag108 as d108  # noqa: E402
import bench_diag112 as d112  # noqa: E402
from _cli import run_commands  # noqa: E402

FRESH = {10278: ["sim.generator.effects=[axis_position]"], 10279: ["sim.generator.effects=[hidden_source]"],
         10280: ["++sim.generator.clean=true"]}
N2 = {s: k[1] for s, k in {**d107.KINDS, **d107d.KINDS, **d108.KINDS}.items()}
LSTM = ["model=lstm", "model.estimator.max_epochs=2", "model.estimator.hidden_size=4",
        "model.estimator.chunk=16"]


def planted(root: str, label: str, model: str, *seeds: str) -> None:
    """bench_diag112 ``planted`` over the N2 and fresh draws."""
    d112.FRESH.update({**N2, **FRESH})
    d112.MODEL_WORDS["lstm"] = LSTM
    d112.planted(root, label, model, *seeds)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"planted": planted}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
