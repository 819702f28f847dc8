"""``model.diagnosed`` on the records it was never measured on: on by default or not (issue 34;
stop 100, autodiag100; follow-up of ``bench_autodiag99b.py`` / ``bench_effects99.py``, KEPT behind
the key, default false).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the tree measured)::

    python benchmarks/bench_autodiag100.py seen22 ROOT MAIN_WORK OUT RECORD ...   # the 22-table
    python benchmarks/bench_autodiag100.py ways ROOT OUT RECORD ...               # own test split
    python benchmarks/bench_autodiag100.py table OUT RECORD ...                   # the bar's figures

Both commands fit ``model=auto`` per record as ``run`` fits it (``bench_auto_rank.setup``, the
fits, seeds and splits of ``bench_auto98``), once with ``model.diagnosed=false`` (main's default)
and once with ``model.diagnosed=true`` (``shell.builders.build_compensator`` runs diagnose's
search on the train split; a target where it accepts an effect gets the ``diagnosed``
candidate).  Where the search accepts nothing on any target the key-on candidates are main's
per target (``ForTargets`` leaves the candidate out), so auto is main's by construction: the
key-on fit is not repeated, its cost is the search's plus the key-off fit's.  CPU is this
process's user + sys (``time.process_time``) of build + fit, key on first (it pays the process's
first imports).  Everything a record gives goes to
``OUT/RECORD.json`` (a record already there is not refitted).

``seen22`` (ROOT as bench_auto96's, MAIN_WORK = ``/tmp/auto96/seen``, main's stored rows of
bench_automore69): the 22-table's records, scored in simulation mode on their 12-16 NEW campaigns
(``bench_auto98.with_new_campaigns``); the key-off fit's votes are checked against the stored ones
(``reproduced``) and its RMSE against the stored auto's.  The record figure is bench_auto96's: the
mean over targets of auto's pooled RMSE over the mean of MLR's (stored MLR).  ``ways``: a record
of bench_auto98's :data:`~bench_auto98.RECORDS` (bench_auto95's ten one-campaign SEEN records,
``fl_thermal`` 90/10, the FRESH kinds), of bench_automore69's table (its own test split: iso_a,
mtc_a) or ``mt<seed>`` (bench_autodiag99's, ``ROOT/data/mt<seed>``), scored on its own test; the
record figure is the mean over targets of the RMSE (on / off: the ratio of those means).

BAR (written and committed before the FRESH seeds 9795-9799 are simulated; the default turns to
true only if all four hold):

* A1 (seen: the 22-table, bench_auto95's ten one-campaign records, iso_a / mtc_a on their own test,
  fl_thermal 90/10, mt9888): on every record key-on / key-off record figure <= 1.02 (no record made
  more than 2 % worse), and the geometric mean of on / off over those records <= 1.0.
* A2 (22-table): losers, auto / MLR > 1.0 with the key on, not more than 8 (main's 8: col5791
  1.258, col1403 1.311, col1514 1.019, col6512 1.004, lab5401 1.070, hmc 1.005, iso_a 1.083,
  mtc_b 1.075).
* A3 (22-table): CPU of build + fit summed over the 22 records, key on <= 1.5 x key off.
* A4 (FRESH 9795-9799: lr9795-9797, sw9798-9799, bench_auto98's FRESH kinds), scored ONCE with
  ``ways``: A1's clauses on them (each on / off <= 1.02, their geometric mean <= 1.0).
The FRESH seeds are simulated only if A1-A3 hold on the seen records (else they stay fresh).
All four: ``model.diagnosed`` defaults to true (conf, docs/cli.md, the tests that compose auto);
``make run``'s E_X / E_Y / E_Z must not move by more than 1 %.  Else TRACED, with the table: which
record fails which clause, what was accepted there, and its effect on the test.
"""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
os.environ.setdefault("OMP_NUM_THREADS", "1")
from _cli import run_commands  # noqa: E402

LOSERS = {"col5791": 1.258, "col1403": 1.311, "col1514": 1.019, "col6512": 1.004, "lab5401": 1.070,
          "hmc": 1.005, "iso_a": 1.083, "mtc_b": 1.075}     # main's 22-table losers (bench_auto98)


def _fit_both(cfg, ds, train) -> tuple:
    """``(key off, key on, report)``: auto fitted with ``model.diagnosed`` false and true (key on
    is key off where nothing is accepted: module doc); the report holds the CPU seconds, the
    effects accepted per target and the votes."""
    from omegaconf import open_dict

    from thermocomp.shell.builders import build_compensator

    rep = {}
    with open_dict(cfg):          # key on first: it pays the process's first imports (against it)
        cfg.model.diagnosed = True
    t0 = time.process_time()
    built = build_compensator(cfg, ds=ds)
    rep["cpu_search"] = time.process_time() - t0
    with open_dict(cfg):
        cfg.model.diagnosed = False
    diagnosed = built.estimator.candidates["diagnosed"]
    rep["accepted"] = {t: [e["effect"] for e in a["accepted"]] for t, a in (diagnosed.about or {}).items()}
    rep["alpha"] = {t: a["alpha"] for t, a in (diagnosed.about or {}).items()}
    on = None
    if diagnosed.by_target:
        t0 = time.process_time()
        on = built.fit(train)
        rep["cpu_fit_on"] = time.process_time() - t0
    t0 = time.process_time()
    off = build_compensator(cfg, ds=ds).fit(train)
    rep["cpu_off"] = time.process_time() - t0
    if on is None:
        on, rep["cpu_fit_on"] = off, rep["cpu_off"]
    rep["cpu_on"] = rep["cpu_search"] + rep["cpu_fit_on"]
    rep["weights_off"] = {t: e.weights_ for t, e in off.estimators_.items()}
    rep["weights_on"] = {t: e.weights_ for t, e in on.estimators_.items()}
    return off, on, rep


def _rmse(y, p) -> float:
    keep = np.isfinite(y) & np.isfinite(p)
    return float(np.sqrt(np.mean((y[keep] - p[keep]) ** 2)))


def _predicted(comp, ds, ids) -> dict:
    """``{target: prediction}`` of ``comp`` over the campaigns ``ids`` in simulation, concatenated."""
    from thermocomp.core.scoring.evaluation import split_residuals

    _, _, series = split_residuals(comp, ds, ids, "simulation")
    return {t: np.concatenate([y[c] - r[c] for c in ids]) for t, (y, r) in series.items()}


def _say(name: str, rep: dict) -> None:
    cells = {t: {k: round(v, 4) for k, v in c.items() if isinstance(v, float)}
             for t, c in rep["targets"].items()}
    print(f"{name}: accepted {rep['accepted']}; cpu off {rep['cpu_off']:.1f} s, on {rep['cpu_on']:.1f} s "
          f"(search {rep['cpu_search']:.1f}); {cells}", flush=True)


def seen22(root: str, main_work: str, out: str, *records: str) -> None:
    """The 22-table records (module doc): OUT/RECORD.json."""
    from bench_auto91 import stored_targets
    from bench_auto98 import with_new_campaigns

    work = Path(main_work).resolve()
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        path = Path(out, f"{name}.json")
        if path.exists():
            continue
        cfg, ds, train, full, ids = with_new_campaigns(root, work, name)
        off, on, rep = _fit_both(cfg, ds, train)
        p_off = _predicted(off, full, ids)
        p_on = p_off if on is off else _predicted(on, full, ids)
        rep["targets"] = {}
        for t, w, a, y_new, new, _ in stored_targets(work, name):
            test = {k[5:]: a[k] for k in a.files if k.startswith("pred_") and k != "pred_auto"}
            stored = sum(v * test[n][new] for n, v in w.items())
            same = set(w) == {n for n, v in rep["weights_off"][t].items() if v > 0} and all(
                abs(rep["weights_off"][t].get(n, 0.0) - v) < 1e-9 for n, v in w.items())
            rep["targets"][t] = {"mlr": _rmse(y_new[new], test["mlr"][new]),
                                 "stored": _rmse(y_new[new], stored), "reproduced": same,
                                 "off": _rmse(y_new[new], p_off[t][new]),
                                 "on": _rmse(y_new[new], p_on[t][new])}
        path.write_text(json.dumps(rep, indent=1, default=float))
        _say(name, rep)


def _setup(root: str, name: str):
    """``(cfg, dataset, train)`` of a ``ways`` record (module doc)."""
    import bench_auto96
    import bench_auto_rank as rank
    from bench_auto98 import _with_root
    from bench_autodiag99 import _overrides

    if name.startswith("mt"):
        overrides = _overrides(root, name)
        sys.argv[2:] = overrides
        return rank.setup(overrides)
    _with_root(root, [name])
    return bench_auto96._setup(name, root)


def ways(root: str, out: str, *records: str) -> None:
    """Records scored on their own test split (module doc): OUT/RECORD.json."""
    Path(out).mkdir(parents=True, exist_ok=True)
    for name in records:
        path = Path(out, f"{name}.json")
        if path.exists():
            continue
        cfg, ds, train = _setup(root, name)
        off, on, rep = _fit_both(cfg, ds, train)
        ids = ds.ids("test")
        y = _measured(off, ds, ids)
        p_off = _predicted(off, ds, ids)
        p_on = p_off if on is off else _predicted(on, ds, ids)
        rep["targets"] = {t: {"off": _rmse(y[t], p_off[t]), "on": _rmse(y[t], p_on[t])} for t in y}
        path.write_text(json.dumps(rep, indent=1, default=float))
        _say(name, rep)


def _measured(comp, ds, ids) -> dict:
    from thermocomp.core.scoring.evaluation import split_residuals

    _, _, series = split_residuals(comp, ds, ids, "simulation")
    return {t: np.concatenate([y[c] for c in ids]) for t, (y, _) in series.items()}


def _geo(v) -> float:
    return float(np.exp(np.mean(np.log(v))))


def table(out: str, *records: str) -> None:
    """Per record: key on / off (record figure), auto / MLR both ways where the 22-table's stored
    MLR is there, CPU; then the geometric mean, the losers and the CPU sums (module doc)."""
    ratios, losers_off, losers_on, cpu_off, cpu_on = [], [], [], 0.0, 0.0
    for name in records:
        rep = json.loads(Path(out, f"{name}.json").read_text())
        cells = list(rep["targets"].values())
        off, on = np.mean([c["off"] for c in cells]), np.mean([c["on"] for c in cells])
        ratios.append(on / off)
        line = f"{name:11s} on/off {on / off:.4f}  mean RMSE {off:.4g} -> {on:.4g}"
        if "mlr" in cells[0]:
            mlr, stored = np.mean([c["mlr"] for c in cells]), np.mean([c["stored"] for c in cells])
            losers_off.append(off / mlr > 1)
            losers_on.append(on / mlr > 1)
            cpu_off += rep["cpu_off"]
            cpu_on += rep["cpu_on"]
            line += (f"  auto/MLR stored {stored / mlr:.3f} off {off / mlr:.3f} on {on / mlr:.3f}"
                     f"  reproduced {all(c['reproduced'] for c in cells)}")
        worst = max(c["on"] / c["off"] for c in cells)
        accepted = {t: a for t, a in rep["accepted"].items() if a}
        print(f"{line}  worst target {worst:.3f}  cpu {rep['cpu_off']:.1f} -> {rep['cpu_on']:.1f} s"
              f"  accepted {accepted or 'nothing'}")
    print(f"{len(ratios)} records: geo on/off {_geo(ratios):.4f}, worst {max(ratios):.4f}, "
          f"> 2 % worse {sum(r > 1.02 for r in ratios)}")
    if losers_on:
        print(f"22-table part: losers off {sum(losers_off)} on {sum(losers_on)}; CPU off {cpu_off:.1f} s "
              f"on {cpu_on:.1f} s ({cpu_on / cpu_off:.2f} x)")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen22": seen22, "ways": ways, "table": table}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
