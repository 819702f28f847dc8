"""``model=auto`` where its folds cannot hold out what the test holds out: one train campaign,
new test campaigns -> MLR kept (issue 34, acceptance "model=auto better than MLR on each
record"; stop 82, auto82b).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_auto82b.py splits ROOT WORK [RECORD ...]  # the splits -> WORK/splits.jsonl
    python benchmarks/bench_automore69.py rows ROOT WORK22            # the 22 records' rows (bench_auto80's)
    python benchmarks/bench_auto82b.py fresh ROOT WORK                # this stop's fresh records -> WORK
    python benchmarks/bench_auto82b.py screen SPLITS OLD22 OLDFRESH   # the rule on stored rows: the bar
    python benchmarks/bench_auto82b.py bar SPLITS OLD22 NEW22 OLDFRESH NEWFRESH   # the code's rows

``splits``: per record (bench_automore69's 22, bench_auto82's 6 fresh, this stop's fresh, and
``fl_thermal``'s 90/10 and 60/20/20 cuts) what the rule reads, from the split alone: the train
campaigns, how many records they are once the runs that continue one another are joined
(``continuation.predecessors``), whether a test campaign continues a train one, the val split,
``holdout_scheme``.  ``fresh``: bench_automore69's instrument (auto and each candidate alone fitted
once on the record's train campaigns; scored on its own test and on 3 new campaigns of its
machine, seeds 8311-8313) on records drawn from this stop's seeds: the column
(``column_moving_source``, 8301-8302), the Swiss lathe (``swiss_lathe_door``, 8303-8304: where
auto's dynamic families win most over MLR, swiss303 0.57 x MLR), the lab mill (bench_automore69's
``lab_mill``, 8305) and the mill week (``large_mill_week`` 120 s, 8306).  All train on one
campaign and are tested on new ones.  The other simulators' machines were not used: the
simulators' machines do not depend on the seed, so these are the 22's machines drawn again (the
volumetric mill has one train week too, but no ``data`` config for auto's targets; not tried).
Nothing here reads a test campaign to choose: it is only scored.

The rule (written and committed before anything was scored)
-----------------------------------------------------------
Auto's folds hold out what the test holds out (``holdout_scheme``).  Where the train split is ONE
record (one campaign, or runs that continue one another: the folds are blocks of that one run)
and no test campaign continues it (new campaigns: another day, another programme), no fold sees a
new campaign's conditions (its start state, its weather, its programme), so the folds' evidence
for a dynamic or nonlinear family over MLR is not evidence for the test: MLR is kept (the one-SE
rule's simplest model; the zero rule then runs on it).  Where the test continues the train record
(``fl_thermal``'s 90/10 and 60/20/20 cuts) or the train split is >= 2 records, or a val split
scores the candidates: unchanged.  The screen (``screen``) takes the stored rows and gives a record
where the rule fires MLR's squared errors on every target (the code would also run the zero rule
on MLR: not in the screen).

The bar (written before scoring; fails -> no src, or the src reverted and kept as
``benchmarks/auto82b_rule.patch``; this docstring says REFUSED with the numbers)
------------------------------------------------------------------------------------------------
Record figure = mean over targets of the pooled test RMSE (bench_automore69's); OLD = the shipped
rows (/tmp/auto80/new: this base's auto, checked equal by bench_auto82), NEW = the rule's.

1. the 22 records' new campaigns: the count where auto is worse than MLR drops by >= 3 (8 -> <= 5);
2. the geometric mean over the 22 of auto / MLR on the new campaigns rises by <= 2 % (relative);
3. the count within 10 % of the best single family on the new campaigns falls by <= 1;
4. ``fl_thermal`` 90/10 and 60/20/20: the rule does not fire (a test that continues the train
   record; with the code: auto's weights and test RMSE unchanged);
5. >= 4 fresh records of this stop's seeds (one train campaign, new test campaigns): the count
   where auto is worse than MLR on their new campaigns not higher than shipped's.

Ordering, said plainly: ``screen`` ran once on this file's bar before its first commit (42a9d16a;
the bar's text is as it was when it ran), and the fresh draws started before that commit.

Scored (2026-12-04; OLD = /tmp/auto80/new and the shipped src on the fresh records, NEW = this
tree's rule, ``model.estimator.unseen_campaigns=mlr``; 2 shared cores, load 8-11, every record
once, ``OMP_NUM_THREADS=1``): **KEPT by the bar as written**, NOT MERGED (below), with a cost
the bar does not weigh (below: the fresh records' wins)
----------------------------------------------------------------------------------------------
``splits``: the rule fires on 9 of the 22 (col5791, col1403, col1514, col6511, col6512, swiss303,
swiss5454, mill1514, twin_lathe: one train campaign, new test campaigns) and on all 12 fresh
records (auto82's 6, this stop's 6); not on lab5401 (3 train campaigns, auto82 said one: its folds
are one ``blocked forward`` fold of campaigns), nor on the 12 others (4-16 train campaigns), nor
on ``fl_thermal`` (both cuts: ``spindle_test_test`` continues the train record).  The code
reproduces the screen on the 9 to the digit (MLR kept on every target, the zero rule firing on
none); of the 13 others lab5401, tsc_a2 and iso_a were run again as controls (auto's squared
errors equal OLD's on every campaign), the other 10 keep OLD's rows (the rule needs one train
record).

1. holds: worse than MLR on the new campaigns 8 -> 4 (col5791 1.258, col1403 1.311, col1514 1.019,
   col6512 1.004 -> 1.000; left: lab5401 1.070, hmc 1.005, iso_a 1.083, mtc_b 1.075).
2. holds: geometric mean auto / MLR over the 22 0.8264 -> 0.8311 (x1.0056).
3. holds: within 10 % of the best single family 15 -> 15 (col5791, col1403 in; swiss303 1.000 ->
   1.758, twin_lathe 1.075 -> 1.104 out).
4. holds: ``fl_thermal`` 90/10 auto 2.4810 -> 2.4810 µm (MLR 4.060), 60/20/20 RMSE mean 2.6133
   -> 2.6133, weights unchanged on all five channels (the stage sets ``folds``: the test
   continues the train record; 60/20/20 is a val split besides).  Auto 90/10 CPU 35.7 / 32.8 s
   (load 8-11; the rule adds no work where it does not fire).
5. holds: this stop's 6 fresh records worse than MLR on the new campaigns 1 -> 0 (own test 1 -> 0).

What the bar does not weigh (measured, the same rows): better than MLR on the new campaigns 13 ->
9 of the 22 (swiss303 0.569, swiss5454 0.950, twin_lathe 0.973, col6511 0.996 -> 1.000 x MLR).
On the fresh records (auto / MLR on their 3 new campaigns, shipped -> rule): col8301 0.838,
col8302 0.922, swiss8303 0.477, swiss8304 0.570 -> 1.000; labmill8305 1.000 = 1.000; mill8306
1.010 -> 1.000; geometric mean 0.772 -> 1.000, within 10 % of the best single family 5 -> 2 of 6
(auto82's fresh, screened: col8131 1.211, col8132 1.041, col8134 1.006 -> 1.000, col8133 0.745,
labmill8136 0.977 -> 1.000).  On one train record the folds were right on 4 of this stop's 6
fresh records and on the Swiss lathes by 43-52 %: the hypothesis (their evidence is not evidence
for new campaigns) holds on the column's unseen source Q3 and fails on the Swiss lathe and the
column's other draws.  Item 5 counts losses only, which the rule removes by construction; a
bar on the fresh records' geometric mean or wins would have refused it.  The helper's
recommendation: do not merge as the default without the parent weighing that cost.

**Not merged (the lead, after scoring)**: the bar was mis-written (it counted losses only), and by
issue 34's own words a tie with MLR is not "better than MLR" either: the rule turns 4 losses into
ties at the price of 4 wins on the 22 and 4 of 6 fresh records (geometric mean 0.772 -> 1.000), a
user with one train record and new campaigns would lose the Swiss lathe's 43-52 %.  src, conf,
docs and the test reverted; the rule in ``benchmarks/auto82b_rule.patch``.  An opt-in key was
weighed and left out: a user who knows the new campaigns leave the train conditions can ask for
``model=mlr`` itself.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_auto82 as auto82  # noqa: E402
import bench_automore69 as automore  # noqa: E402
import bench_remeasure62 as remeasure  # noqa: E402
from _cli import made_folder, run_commands  # noqa: E402

FRESH = {"col8301": ("column", ["sim=column_moving_source", "seed=8301"]),
         "col8302": ("column", ["sim=column_moving_source", "seed=8302"]),
         "swiss8303": ("swiss", ["sim=swiss_lathe_door", "seed=8303"]),
         "swiss8304": ("swiss", ["sim=swiss_lathe_door", "seed=8304"]),
         "labmill8305": ("lab_mill", [*automore.LAB_MILL, "seed=8305"]),
         "mill8306": ("mill", [*remeasure.MILL, "seed=8306"])}
FRESH_NEW = [8311, 8312, 8313]        # the new campaigns of each fresh record's machine
FL = {"fl9010": ["data=fl_thermal"],
      "fl602020": ["data=fl_thermal", "data.split_order=[train,test,val]", "data.test_fraction=0.2",
                   "data.val_fraction=0.2"]}
DROP, GEO_RISE, BEST_FALL, NEAR_BEST = 3, 1.02, 1, 1.1


def _overrides() -> dict:
    return {**{n: automore.OVERRIDES[n] for n in automore.OF},
            **{n: o for n, o in auto82.FRESH.items()}, **{n: o for n, (_, o) in FRESH.items()}, **FL}


def splits(root: Path, work: Path, names: list[str]) -> None:
    """Each record's split as the rule reads it -> WORK/splits.jsonl."""
    import bench_auto_rank as rank

    from thermocomp.core.continuation import predecessors
    from thermocomp.core.scoring.evaluation import holdout_scheme

    known = _overrides()
    os.environ.setdefault("OUT", str(work / "rank"))
    for name in names or list(known):
        overrides = [o.format(root=root) for o in known[name]]
        sys.argv = [sys.argv[0], "splits", *overrides]   # bench_auto_rank simulates when sim= is asked
        with contextlib.redirect_stdout(io.StringIO()):
            _, ds, _ = rank.setup(overrides)
        links, train, test = predecessors(ds), ds.ids("train"), ds.ids("test")
        joined = sum(c in train and p in train for c, p in links.items())
        row = {"record": name, "train": len(train), "train_records": len(train) - joined,
               "test": len(test), "val": len(ds.ids("val")), "scheme": holdout_scheme(ds),
               "test_continues": sorted(c for c, p in links.items() if c in test and p in train)}
        print(json.dumps(row), flush=True)
        with (work / "splits.jsonl").open("a", encoding="utf-8") as f:
            f.write(json.dumps(row) + "\n")


def fires(split: dict) -> bool:
    """The rule, on the split alone: one train record, no test campaign continuing it, no val."""
    return split["train_records"] == 1 and not split["test_continues"] and not split["val"]


def fresh(root: Path, work: Path) -> None:
    """This stop's fresh records through bench_automore69's ``rows`` (this tree's code)."""
    for name, (machine, overrides) in FRESH.items():
        automore.OVERRIDES[name], automore.OF[name] = overrides, machine
        automore.MACHINES[machine] = (*automore.MACHINES[machine][:2], FRESH_NEW)
    automore.rows(root, work, list(FRESH))


def _split_rows(path: Path) -> dict:
    return {r["record"]: r for r in remeasure._read(path)}


def _screened(row: dict, split: dict) -> dict:
    """The stored row with auto's squared errors MLR's where the rule fires."""
    if not fires(split):
        return row
    return {**row, "squares": {**row["squares"], "auto": row["squares"]["mlr"]}}


def _summaries(work: Path, names=None) -> dict:
    rows = {r["record"]: r for r in remeasure._read(work / "automore.jsonl")}
    return {n: r for n, r in rows.items() if names is None or n in names}


def verdict(sp: dict, old22: dict, new22: dict, oldf: dict, newf: dict, fl_ok: bool, fl_line: str) -> None:
    """Print the per-record table and the bar's five items (rows: bench_automore69's)."""
    a = {n: automore.summary(r) for n, r in old22.items()}
    b = {n: automore.summary(r) for n, r in new22.items() if n in a}
    lines = ["record        train rec cont fires | auto/MLR own old -> new | new old -> new | "
             "auto/best new old -> new"]

    def row(n, s, t):
        p = sp[n]
        return (f"{n:12s}  {p['train']:5d} {p['train_records']:3d} {len(p['test_continues']):4d} "
                f"{'YES' if fires(p) else '-':5s} |  {s['to_mlr'][0]:6.3f} -> {t['to_mlr'][0]:6.3f}      "
                f"| {s['to_mlr'][1]:6.3f} -> {t['to_mlr'][1]:6.3f} | {s['to_best'][1]:6.3f} -> "
                f"{t['to_best'][1]:6.3f}")

    lines += [row(n, a[n], b[n]) for n in b]
    worse = [sum(s["to_mlr"][1] > 1 for s in x.values()) for x in (a, b)]
    geo = [float(np.exp(np.mean([np.log(s["to_mlr"][1]) for s in x.values()]))) for x in (a, b)]
    near = [sum(s["to_best"][1] <= NEAR_BEST for s in x.values()) for x in (a, b)]
    ok = [worse[0] - worse[1] >= DROP, geo[1] <= GEO_RISE * geo[0], near[0] - near[1] <= BEST_FALL, fl_ok]
    fa = {n: automore.summary(r) for n, r in oldf.items()}
    fb = {n: automore.summary(r) for n, r in newf.items() if n in fa}
    lines += ["", "fresh:"] + [row(n, fa[n], fb[n]) for n in fb]
    fw = [sum(s["to_mlr"][1] > 1 for s in x.values()) for x in (fa, fb)]
    fo = [sum(s["to_mlr"][0] > 1 for s in x.values()) for x in (fa, fb)]
    fired = [n for n in fb if fires(sp[n])]
    ok.append(len(fired) >= 4 and fw[1] <= fw[0])
    say = ["holds" if k else "FAILS" for k in ok]
    lines += ["", f"1 worse than MLR on the new campaigns {worse[0]} -> {worse[1]} (" + ", ".join(
        n for n, s in b.items() if s["to_mlr"][1] > 1) + f"): {say[0]}",
        f"2 geometric mean auto/MLR new {geo[0]:.4f} -> {geo[1]:.4f} (x{geo[1] / geo[0]:.4f}): {say[1]}",
        f"3 within 10 % of the best single family new {near[0]} -> {near[1]}: {say[2]}",
        f"4 fl_thermal: {fl_line}: {say[3]}",
        f"5 fresh ({len(fb)} records, the rule fires on {len(fired)}) worse than MLR new {fw[0]} -> "
        f"{fw[1]} (own test {fo[0]} -> {fo[1]}): {say[4]}",
        "VERDICT: " + ("KEPT" if all(ok) else "REFUSED")]
    print(remeasure._wrapped(lines, 150))


def _fl_split(sp: dict) -> tuple[bool, str]:
    on = [n for n in FL if n in sp and fires(sp[n])]
    return (not on and all(n in sp for n in FL),
            "the rule fires on " + (", ".join(on) or "neither cut") + " (test continues the train record: "
            + ", ".join(f"{n} {sp[n]['test_continues']}" for n in FL if n in sp) + ")")


def screen(splits_path: Path, old22: Path, oldf: Path) -> None:
    sp = _split_rows(splits_path)
    o22, of = _summaries(old22, sp), _summaries(oldf, sp)
    verdict(sp, o22, {n: _screened(r, sp[n]) for n, r in o22.items()}, of,
            {n: _screened(r, sp[n]) for n, r in of.items()}, *_fl_split(sp))


def bar(splits_path: Path, old22: Path, new22: Path, oldf: Path, newf: Path) -> None:
    """The code's rows; a record of the 22 not run again where the rule does not fire keeps OLD's
    row (its code path unchanged: the rule needs one train record), said."""
    sp = _split_rows(splits_path)
    o22, n22 = _summaries(old22, sp), _summaries(new22, sp)
    kept = [n for n in o22 if n not in n22 and not fires(sp[n])]
    missing = [n for n in o22 if n not in n22 and fires(sp[n])]
    if missing:
        raise SystemExit(f"the rule fires on {missing}: their rows must be run again")
    print(f"not run again (the rule does not fire, OLD's rows): {', '.join(kept) or 'none'}")
    same = [n for n in n22 if not fires(sp[n]) and n22[n]["squares"]["auto"] == o22[n]["squares"]["auto"]]
    print(f"run again where the rule does not fire, auto's squared errors equal OLD's: {', '.join(same)}")
    fl = "; " + _fl_moved(old22, new22) if (new22 / "fl.jsonl").exists() else ""
    ok, line = _fl_split(sp)
    verdict(sp, o22, {**{n: o22[n] for n in kept}, **n22}, _summaries(oldf, sp), _summaries(newf, sp),
            ok, line + fl)


def _fl_moved(old: Path, new: Path) -> str:
    """``fl_thermal``'s runs (bench_auto80's ``fl``): auto's weights and test RMSE, OLD against NEW."""
    def runs(work):
        return {r["run"]: r for r in map(json.loads, (work / "fl.jsonl").read_text().splitlines())}

    o, n = runs(old), runs(new)
    said = []
    for name in ("auto9010", "auto602020"):
        if name in o and name in n:
            same = o[name]["rmse"] == n[name]["rmse"] and all(
                o[name]["auto"][t]["weights"] == n[name]["auto"][t]["weights"] for t in o[name]["auto"])
            said.append(f"{name} RMSE mean {np.mean(list(o[name]['rmse'].values())):.4f} -> "
                        f"{np.mean(list(n[name]['rmse'].values())):.4f} ({'unchanged' if same else 'MOVED'})")
    return ", ".join(said)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "splits": lambda root, work, *names: splits(Path(root).resolve(), made_folder(work), list(names)),
        "fresh": lambda root, work: fresh(Path(root).resolve(), made_folder(work)),
        "screen": lambda s, old22, oldf: screen(Path(s), Path(old22), Path(oldf)),
        "bar": lambda s, old22, new22, oldf, newf: bar(Path(s), Path(old22), Path(new22), Path(oldf),
                                                       Path(newf)),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
