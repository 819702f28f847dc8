"""Issue 34's "on records you do not have" scoreboard re-measured at 70341ac8 (stop 107, acc107):
``model=auto`` against MLR and the best single family, and ``diagnose``'s acceptance line.
Measuring only: no rule, no src change.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_acc107.py rows ROOT WORK [RECORD ...]  # bench_automore69's rows + reasons
    python benchmarks/bench_acc107.py table WORK                   # its table, and against 2026-12-01
    python benchmarks/bench_acc107.py fresh ROOT OUT               # seeds 10144-10151, own test, ONCE
    python benchmarks/bench_acc107.py diag OUT                     # seeds 10152-10155, diagnose, ONCE

ROOT as bench_automore69's docstring builds it (``bench_remeasure62.py write ROOT``,
``bench_automore69.py write ROOT``, the strangers' ``write`` + ``init`` into ROOT/labs).

``rows``: bench_automore69's ``rows`` unchanged (the same 22 records, the same overrides, the new
campaigns of seeds 6911-6940), each row also keeping every target's ``reason_`` and ``scheme_`` of
the fitted auto (where the campaign hedge, auto105b, moved the weights it says "hedged towards MLR
by the nested weight LAM").  ``table``: bench_automore69's table, then each record's auto / MLR
and auto / best single family, own | new, beside the 2026-12-01 table (:data:`OLD`, stop 69 at
3d65c78c, copied from bench_automore69's docstring) and the hedge's lam per target.

``fresh``: eight records of the 22 table's kinds, named here before any was drawn (:data:`FRESH`),
each with its kind's own train / test split; auto and every candidate it validated alone fitted
on the train part exactly as bench_automore69's ``record_row`` fits them (no new campaigns), scored
on the own test: auto / MLR, auto / the best single family (after the fact), record means over the
targets of the pooled test RMSE (bench_automore69's figure).

``diag``: bench_diag86's draws (the year-round VMC, 12 campaigns, every 3rd by date test: 8
train), ``planted`` (``axis_position`` on Y) 10152, 10153 and ``clean`` (``sim.generator.clean``)
10154, 10155 -- the clean kind of the same generator, not the same seeds -- diagnosed as
bench_diag86's ``fresh`` does (MLR, every target, ``max_effects=2``, test figures as deployed):
per target the accepted effects with their family-wise p, the smallest p its starting design can
reach (``cv.designs[target].min_p``, and the record's ``cv.min_p``), test RMSE before -> after.

What counts (written and committed before ``rows``, ``fresh`` and ``diag`` were run; issue 34's
line read as it stands, nothing moved after the numbers):
  A. auto better than MLR on each fresh record: auto / MLR < 1 on all 8 of 10144-10151 (own test).
  B. within 10 % of the best single family on most: auto / best <= 1.10 on at least 5 of 8.
  C. diagnose accepts the planted position effect (an ``interaction`` on ``S_pos_Y`` for E_Y) on
     both 8-train planted draws 10152, 10153.
  D. diagnose accepts nothing on any target of the clean draws 10154, 10155.
  E. no (draw, target) of 10152-10155 with its test RMSE after more than 2 % above before.
The 22 table is re-measured and reported as it comes (no bar on it: its records are seen).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_automore69 as automore  # noqa: E402
import bench_remeasure62 as remeasure  # noqa: E402
from _cli import made_folder, run_commands  # noqa: E402

# the 2026-12-01 table (bench_automore69's docstring, 3d65c78c): auto / MLR own, new; auto / best
# single family own, new
OLD = {"swiss303": (0.56, 0.57, 1.00, 1.00), "swiss5454": (0.93, 0.95, 1.50, 1.54),
       "year6_5411": (0.68, 0.52, 1.53, 1.40), "year6511": (0.37, 0.35, 1.08, 0.92),
       "year6512": (0.47, 0.38, 1.26, 0.91), "lab5401": (1.02, 1.07, 1.04, 1.07),
       "mill1514": (1.01, 1.01, 1.01, 1.01), "col5791": (1.32, 1.33, 1.32, 1.33),
       "col1403": (1.27, 1.31, 1.27, 1.31), "col1514": (1.03, 1.02, 1.14, 1.21),
       "col6511": (1.05, 1.04, 1.05, 1.04), "col6512": (1.02, 1.01, 1.02, 1.01),
       "twin_lathe": (0.96, 0.97, 0.96, 1.07), "jig_grinder": (0.97, 0.94, 1.03, 0.99),
       "hmc": (1.62, 1.01, 1.66, 1.15), "tsc_a2": (0.32, 0.38, 1.05, 1.04),
       "iso_a": (0.95, 0.96, 1.42, 0.97), "iso_b": (0.56, 0.87, 0.96, 1.00),
       "mtc_a": (0.62, 0.70, 0.92, 0.95), "mtc_b": (1.12, 1.07, 1.12, 1.08),
       "grind_a": (0.98, 0.94, 1.00, 0.95), "grind_b": (0.99, 0.99, 1.00, 1.00)}

# named before drawing: the 22 table's kinds, each its kind's own train / test split
FRESH = {"col10144": ["sim=column_moving_source", "seed=10144"],
         "sw10145": ["sim=swiss_lathe_door", "seed=10145"],
         "mill10146": [*remeasure.MILL, "seed=10146"],
         "lab10147": ["data.path={out}/lab10147"],                 # lab5401's kind (lab_record)
         "year6_10148": ["sim=yearround_spindle", "sim.generator.n_campaigns=6", "seed=10148"],
         "year10149": ["sim=yearround_spindle", "seed=10149"],
         "grind10150": ["data.path={out}/grind10150"],             # grind_a's kind (14 runs)
         "jig10151": ["hydra.searchpath=[file://{root}/nm60/init-jig_grinder/conf]", "data=jig_grinder",
                      "data.path={out}/jig10151"]}                 # jig_grinder's kind, its init config
DIAG = [("planted", 10152, 12), ("planted", 10153, 12), ("clean", 10154, 12), ("clean", 10155, 12)]


def _with_reasons(record_row):
    """``record_row`` whose row also keeps the fitted auto's ``reason_`` / ``scheme_`` per target."""
    import thermocomp.shell.builders as builders

    def row(root: Path, work: Path, name: str) -> dict:
        built, shipped = [], builders.build_compensator

        def remember(*args, **kwargs):
            built.append(shipped(*args, **kwargs))
            return built[-1]

        builders.build_compensator = remember
        try:
            out = record_row(root, work, name)
        finally:
            builders.build_compensator = shipped
        auto = built[0]
        out["reasons"] = {t: e.reason_ for t, e in auto.estimators_.items()}
        out["schemes"] = {t: e.scheme_ for t, e in auto.estimators_.items()}
        return out
    return row


def rows(root: str, work: str, *names: str) -> None:
    automore.record_row = _with_reasons(automore.record_row)
    automore.rows(Path(root).resolve(), Path(work).resolve(), list(names) or list(automore.OF))


def _lam(reason: str) -> str:
    """The hedge's weight in ``reason`` ('-' where auto was not hedged)."""
    key = "hedged towards MLR by the nested weight "
    return reason.split(key)[1].split()[0] if key in reason else "-"


def table(work: str) -> None:
    automore.table([Path(work).resolve()])
    got = {r["record"]: r for r in remeasure._read(Path(work).resolve() / "automore.jsonl")}
    print("\nrecord       auto/MLR own | new (2026-12-01)      auto/best own | new (2026-12-01)  hedge lam")
    now_counts = np.zeros(4, int)
    for name, row in got.items():
        s = automore.summary(row)
        now = (s["to_mlr"][0], s["to_mlr"][1], s["to_best"][0], s["to_best"][1])
        now_counts += [now[0] < 1, now[1] < 1, now[2] <= 1.1, now[3] <= 1.1]
        old = OLD.get(name, (np.nan,) * 4)
        lams = ", ".join(f"{t} {_lam(r)}" for t, r in row.get("reasons", {}).items() if _lam(r) != "-")
        moved = "  *" if any(abs(round(a, 2) - b) > 0.005 for a, b in zip(now, old)) else ""
        print(f"{name:12s} {now[0]:5.2f} | {now[1]:5.2f} ({old[0]:.2f} | {old[1]:.2f})    "
              f"{now[2]:5.2f} | {now[3]:5.2f} ({old[2]:.2f} | {old[3]:.2f})  {lams or '-'}{moved}")
    old_counts = [sum(o[0] < 1 for o in OLD.values()), sum(o[1] < 1 for o in OLD.values()),
                  sum(o[2] <= 1.1 for o in OLD.values()), sum(o[3] <= 1.1 for o in OLD.values())]
    print(f"{len(got)} records; better than MLR own / new, within 10 % of the best own / new: "
          f"{' / '.join(map(str, now_counts))} (2026-12-01: {' / '.join(map(str, old_counts))})")


def _fresh_record(out: Path, name: str) -> None:
    """The written records of :data:`FRESH` (lab5401's, grind_a's and jig_grinder's writers)."""
    folder = out / name
    if folder.exists():
        return
    seed = int(name[-5:])
    if name.startswith("lab"):
        from bench_auto_losses56 import lab_record
        lab_record(folder, seed=seed)
    elif name.startswith("grind"):
        import bench_zerofew67 as zerofew
        zerofew.grind_record(folder, automore.GRIND_RUNS, automore.GRINDS["grind_a"], seed)
    elif name.startswith("jig"):
        import bench_new_machines60 as nm60
        nm60.write_jig_grinder(folder, seed)


def _own_figures(row: dict) -> dict:
    """auto / MLR and auto / the best single family on the own test (record means)."""
    models, _, own = automore._arrays(row, row["own"])
    r = automore.record_rmse(own)
    families = [k for k, m in enumerate(models) if m != "auto"]
    best = families[int(np.argmin(r[families]))]
    ia, im = models.index("auto"), models.index("mlr")
    return {"record": row["record"], "own_n": len(row["own"]), "auto": r[ia], "mlr": r[im],
            "best": models[best], "best_rmse": r[best], "to_mlr": r[ia] / r[im], "to_best": r[ia] / r[best]}


def fresh(root: str, out: str) -> None:
    """:data:`FRESH` fitted and scored ONCE on their own test (rows -> OUT/fresh.jsonl)."""
    out_p = made_folder(out)
    path = out_p / "fresh.jsonl"
    done = {r["record"] for r in remeasure._read(path)}
    automore.draws = lambda *_: []             # no new campaigns: the own test only
    record_row = _with_reasons(automore.record_row)
    for name, ov in FRESH.items():
        automore.OVERRIDES[name] = [o.format(out=out_p, root="{root}") for o in ov]
        automore.OF[name] = name
        if name not in done:
            _fresh_record(out_p, name)
            remeasure.measure(path, [("fresh", record_row(Path(root).resolve(), out_p, name))])
    figs = [_own_figures(r) for r in remeasure._read(path)]
    for f in figs:
        print(f"{f['record']:12s} own {f['own_n']}: MLR {f['mlr']:.4g} auto {f['auto']:.4g} best "
              f"{f['best']} {f['best_rmse']:.4g}; auto/MLR {f['to_mlr']:.3f}, auto/best {f['to_best']:.3f}")
    a = sum(f["to_mlr"] < 1 for f in figs)
    b = sum(f["to_best"] <= 1.1 for f in figs)
    print(f"A. better than MLR on {a} of {len(figs)}: {'met' if a == len(figs) else 'NOT met'}; "
          f"B. within 10 % of the best on {b} of {len(figs)}: {'met' if b >= 5 else 'NOT met'}; "
          f"geo auto/MLR {np.exp(np.mean(np.log([f['to_mlr'] for f in figs]))):.4f}")


def diag(out: str) -> None:
    """:data:`DIAG` diagnosed ONCE (bench_diag86's ``fresh``), with each design's reach."""
    from bench_diag76 import _deployed_stream
    from bench_diag86 import draw
    from cpu import cpu_seconds

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    path = made_folder(out) / "diag.jsonl"
    done = {r["case"]: r for r in remeasure._read(path)}
    for kind, seed, n in DIAG:
        if f"{kind}:{seed}" in done:
            continue
        ds = draw(kind, seed, n)
        t0 = cpu_seconds()
        d = diagnose(ds, Compensator(MLR()), options=SearchOptions(max_effects=2),
                     deployed_of=_deployed_stream(ds))
        js = {t: d.to_json(t) for t in d.targets}
        row = {"case": f"{kind}:{seed}", "train": len(ds.ids("train")), "cpu_s": round(cpu_seconds() - t0, 1),
               "min_p": js[d.primary]["cv"]["min_p"], "scheme": js[d.primary]["cv"]["scheme"],
               "targets": {t: {"before": j["before"]["test_rmse"], "after": j["after"]["test_rmse"],
                               "min_p": j["cv"]["designs"][t]["min_p"],
                               "test_blocks": j["cv"]["designs"][t]["test_blocks"],
                               "control_clears": j["control_ever_clears_bar"],
                               "accepted": [{"effect": e.effect.title, "p_family": e.p_family,
                                             "gain_pct": e.gain_pct} for e in d.targets[t].accepted]}
                           for t, j in js.items()}}
        with path.open("a") as f:
            f.write(json.dumps(row, ensure_ascii=False, default=float) + "\n")
        done[row["case"]] = row
    found, clean, worse = [], [], []
    for case, r in done.items():
        print(f"{case} ({r['train']} train, {r['scheme']}, record min p {r['min_p']:.2g}, "
              f"CPU {r['cpu_s']} s)")
        for t, v in r["targets"].items():
            acc = "; ".join(f"{a['effect']} (p_fam {a['p_family']:.2g}, {a['gain_pct']:.1f} %)"
                            for a in v["accepted"]) or "nothing"
            print(f"  {t}: {v['test_blocks']} test blocks, min p {v['min_p']:.2g}; test {v['before']:.4f} -> "
                  f"{v['after']:.4f} ({100 * (v['after'] / v['before'] - 1):+.1f} %); {acc}"
                  + ("; control clears" if v["control_clears"] else ""))
            if v["after"] > 1.02 * v["before"]:
                worse.append(f"{case} {t}")
        if case.startswith("planted"):
            found.append(any(a["effect"].startswith("interaction:S_pos_Y")
                             for a in r["targets"]["E_Y"]["accepted"]))
        else:
            clean += [f"{case} {t}" for t, v in r["targets"].items() if v["accepted"]]
    print(f"C. planted position found {sum(found)} of {len(found)}: {'met' if all(found) else 'NOT met'}; "
          f"D. clean accepting {clean or 'nothing'}: {'met' if not clean else 'NOT met'}; "
          f"E. > 2 % worse {worse or 'none'}: {'met' if not worse else 'NOT met'}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"rows": rows, "table": table, "fresh": fresh, "diag": diag},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
