"""The ambient-interval wrapper (``ati=cmeans``) at a test campaign whose initial ambient lies
outside the train campaigns' span: is the interval's extrapolated ambient law the loss of
``model=auto`` on cr9245 (issue 34; stop 90, lead90).  TRACED (no rule kept)

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ati90.py sweep DATA WORK RECORD ...   # -> WORK/<variant>/<record>/
    python benchmarks/bench_ati90.py table DATA WORK               # per target and per campaign

``sweep``: each climate room of bench_auto88b's :data:`RECORDS` (simulated into DATA where absent)
run four ways, ``model=mlr``: ``main`` (``ati=cmeans`` as shipped), ``clip`` (the same, each
campaign's initial ambient ``A0`` clipped at predict to its interval's train campaigns' ambient
range, ``intervals_[m]['ambient_min' / 'ambient_max']``: the rule traced, applied here by
:func:`clipped`, a patch of ``ATIRegressor.predict`` in this process only; the elbow's folds
predict through it too), ``pooled`` (``ati.estimator.n_intervals=1``: one model with the ambient
interaction) and ``mlr`` (no wrapper).  ``table``: test RMSE per (record, target) of each,
clip / main, and for every test campaign whose ``A0`` lies outside the train span, its own RMSE
under main, clip and pooled.

Why: auto89 traced cr9245's loss (auto 2.482 vs MLR 1.922 µm; E_Z keeps ``ati`` 0.52 in a blend
losing 4.045 vs 2.693) to test campaign C10 at 20.2 °C, below every train campaign (23.4-31.5
°C): ``ati=cmeans`` takes the ambient interaction ``x (A0 - 20 °C)`` (conf/ati/cmeans.yaml), a
law linear in the ambient, extrapolated there.  The question: does holding ``A0`` to the span
the law was fitted on (or the pooled model) serve such campaigns better, whatever the record?

Bar (written before the sweep, seen records only; no fresh seeds drawn): keep a rule only if
no (record, target) of the 32 seen rooms is more than 2 % worse than main and cr9245 is better.

Trace (2026-12-05, ca338ef6 + nothing in src; 2 cores, ``OMP_NUM_THREADS=1``; ``sweep
/tmp/auto89/data /tmp/lead90/sweep <the 32 rooms of /tmp/auto89/data>``, 3.5 s per run)
---------------------------------------------------------------------------------------------
* cr9245, ``ati=cmeans``: E_X 0.919 -> 0.693, E_Z 6.394 -> 4.651 µm clipped (C10 at 20.2 °C
  held to 23.4 °C): the extrapolated law is part of the loss, not all of it (MLR E_Z 2.693).
* The 64 (record, target) rows: clip / main geometric mean 0.977; 11 rows more than 2 % better,
  11 more than 2 % worse (cr9184 E_Z 0.855 -> 1.073, +25.5 %; cr9248 E_Z 0.896 -> 1.086, +21.3 %;
  cr9089 E_X 0.518 -> 0.612, +18.1 %; cr9250 E_X +14.2 %; cr9249 E_Z +11.5 %; cr9081 E_X +9.3 %)
  beside the wins (cr9088 E_Z 5.514 -> 2.634, cr9078 E_X 0.932 -> 0.646, cr9245, cr9248 E_X
  0.817 -> 0.611, cr9085 E_Z -17 %).  Every changed row but cr9086 E_Z (+0.9 %, through the
  elbow's folds) has a test campaign outside the train span; on those records clipping is as
  often wrong as right: the ambient law the room generator draws does go on past the span on
  some (the interval's slope right there), not on others.  Bar failed: REFUSED as a rule; src
  unchanged (the patch is :func:`clipped`, here).
* The elbow keeps one interval on nearly every room: ``pooled`` (``n_intervals=1``) = main on 63
  of 64 rows (cr9245 too: no interval model extrapolates there, the ONE law's ambient slope
  does); per out-of-span test campaign (40 campaign-targets), pooled / main geo 0.989 (2 better,
  1 worse: cr9088 E_Z C11 7.963 -> 2.546, cr9089 E_Z C10 1.677 -> 1.093, C12 0.657 -> 2.037);
  clip / main geo 0.930, 17 better, 16 worse (cr9245 C10 E_Z 9.690 -> 6.561, cr9078 C11 E_X 1.421
  -> 0.827; cr9184 C12 E_Z 1.050 -> 1.561, cr9248 C12 E_Z 0.862 -> 1.496).  ``ati=cmeans`` beats
  plain MLR by far on these rooms (cr9248 E_Z 0.896 vs 3.557): the ambient law is worth its
  extrapolation more often than not; held at the span it loses as often as it gains.

Left: no train-side signal says where an ambient law extrapolates; the next probe is the
ambient law's own evidence (its slope's standard error against the distance to the span:
widen the band with the distance), scored the same way.
"""

from __future__ import annotations

import json
import sys
from contextlib import contextmanager, nullcontext
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto88b as auto88b  # noqa: E402
from _cli import run_commands  # noqa: E402

VARIANTS = {"main": ["ati=cmeans"], "clip": ["ati=cmeans"],
            "pooled": ["ati=cmeans", "ati.estimator.n_intervals=1"], "mlr": []}


@contextmanager
def clipped():
    """``ATIRegressor.predict`` with each row's ``ambient_c0`` clipped to its interval's train
    campaigns' ambient range (the rule traced), restored after."""
    from thermocomp.core.context import AMBIENT_C0
    from thermocomp.core.models import ati

    plain = ati.ATIRegressor.predict

    def predict(self, X, context=None):
        if context is None or AMBIENT_C0 not in context or not self.campaign_ambient_:
            return plain(self, X, context)
        a0 = np.asarray(context[AMBIENT_C0], float).copy()
        which = self._row_intervals(len(a0), context)
        for m, interval in enumerate(self.intervals_):
            a0[which == m] = np.clip(a0[which == m], interval["ambient_min"],
                                     interval["ambient_max"])
        context = context.copy()
        context[AMBIENT_C0] = a0
        return plain(self, X, context)

    ati.ATIRegressor.predict = predict
    try:
        yield
    finally:
        ati.ATIRegressor.predict = plain


def sweep(data: str, work: str, *records: str) -> None:
    from thermocomp.shell.cli import main

    for record in records:
        path = auto88b.auto88._data(Path(data).resolve(), record)
        for variant, overrides in VARIANTS.items():
            out = Path(work).resolve() / variant / record
            if (out / "metrics.json").exists():
                continue
            args = ["run", f"data.path={path}", "model=mlr", *overrides, "plots=none",
                    f"out={out}"]
            with clipped() if variant == "clip" else nullcontext():
                assert main(args) == 0, (variant, record)
            print(variant, record, flush=True)


def _test(work: Path, variant: str, record: str) -> dict:
    return json.loads((work / variant / record / "metrics.json").read_text())["targets"]


def table(data: str, work: str) -> None:
    work = Path(work)
    rows, campaigns = [], []
    for record in sorted(p.name for p in (work / "clip").iterdir()):
        manifest = pd.read_csv(Path(data) / record / "campaigns.csv")
        train = manifest[manifest.split == "train"].ambient_c
        outside = manifest[(manifest.split == "test") & ~manifest.ambient_c.between(
            train.min(), train.max())]
        scores = {v: _test(work, v, record) for v in VARIANTS}
        for target in scores["main"]:
            rmse = {v: scores[v][target]["test"]["rmse"] for v in VARIANTS}
            rows.append({"record": record, "target": target, **rmse,
                         "clip/main": rmse["clip"] / rmse["main"],
                         "span": f"{train.min():.1f}-{train.max():.1f}"})
            for _, c in outside.iterrows():
                per = {v: scores[v][target]["test"]["per_campaign"][c.campaign]["rmse"]
                       for v in ("main", "clip", "pooled")}
                campaigns.append({"record": record, "target": target, "campaign": c.campaign,
                                  "A0": c.ambient_c, **per})
    frame, per = pd.DataFrame(rows), pd.DataFrame(campaigns)
    with pd.option_context("display.width", 200, "display.max_rows", 500):
        print(frame.to_string(index=False, float_format=lambda v: f"{v:.3f}"))
        print(per.to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    ratio = frame["clip/main"]
    print(f"clip/main geo {np.exp(np.log(ratio).mean()):.3f}; rows > 2 % worse "
          f"{int((ratio > 1.02).sum())}, > 2 % better {int((ratio < 0.98).sum())} of {len(ratio)}")
    for v in ("clip", "pooled"):
        r = per[v] / per["main"]
        print(f"out-of-span test campaigns ({len(per)} campaign-targets): {v}/main geo "
              f"{np.exp(np.log(r).mean()):.3f}, better {int((r < 0.98).sum())}, worse "
              f"{int((r > 1.02).sum())}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"sweep": sweep, "table": table}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
