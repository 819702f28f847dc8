"""diag91b's rule (diagnose's test blocks re-cut by the candidates' gains' decorrelation, ``campaigns``
scheme only, a between-campaign guard) on records it was not tuned on: faults58's climate room and
bench_diag88's grinders (stop 91, diag91c; issue 34: "... accepts nothing on clean data, and never
leaves a record's test error more than 2 % worse"; bench_diag91b's "left").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag91c.py write ROOT               # the grinder records -> ROOT
    python benchmarks/bench_diag91c.py rows ROOT LABEL          # every record -> ROOT/rows-LABEL.jsonl
    python benchmarks/bench_diag91c.py compare ROOT A B         # two labels' rows: the bar's counts

``write``: bench_new_machines56's grinder (its seed; ``init`` with its test share, whose config the
grinders are read with) and the grinders 5687 / 5682 (bench_diag88's) under ``ROOT``.  ``rows``:
every record of :data:`RECORDS` diagnosed with MLR on every target -- the climate room
(bench_diagnose_faults58's ``climate_room``, sim seed 5820, 43 campaigns, 39 train, clean and each
planted fault, ``max_effects=1`` as faults58) and the grinders (``grinder-nocoolant``'s config as
bench_diag88 / refnoise57 read them, 12 runs, test share 0.25) -- per target: test RMSE before ->
after, what is accepted, each round's test blocks, whether the control ever clears.  ``compare``:
per label the controls clearing and the rows more than 2 % worse than their before; then every
(record, target) row whose after differs between A and B, with the change against A.

The comparison: A = main BEFORE diag91b (10918742's ``src`` and ``conf``, ``git archive`` under
/tmp/diag91c/before), B = this branch's base 6d1f04a4 (diag91b merged).  Seen records only (no fresh
seed: the brief's).

The bar (written here BEFORE the first run of either tree on these records)
---------------------------------------------------------------------------
TRACED-clean (no src change) if all hold:

1. No (record, target) row's test RMSE (after) more than 2 % above A's after.
2. No acceptance new in B on a record whose new acceptance is a harm: on ``climate_room:clean``
   (no planted fault; its start lags are the simulator's real transient, bench_diag88) and on
   grinder 5682 (its start lag a harm in bench_diag83b / 88) nothing accepted in B that A does not
   accept, unless its row is not worse than A's (item 1 then carries it).
3. No control clears in B where it does not in A.

Else: the rows that break it, and a concrete defect of the rule named from them (a src change only if
the defect is plain and its fix general, with a test failing on 6d1f04a4).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import made_folder, run_commands  # noqa: E402

CLIMATE_ROOM = [f"climate_room:{kind}" for kind in ("clean", "drift", "offset", "stuck", "contact")]
GRINDERS = [5687, 5682]
RECORDS = [*CLIMATE_ROOM, *(f"grinder:{seed}" for seed in GRINDERS)]


def write(root: str) -> None:
    """The grinder ``init`` config (bench_new_machines56's) and the grinders 5687 / 5682."""
    import bench_new_machines56 as nm56

    folder = made_folder(root)
    nm = folder / "lag" / "nm56"
    if not (nm / "init-grinder").exists():
        nm56.write_grinder(nm / "grinder", nm56.SEEDS["grinder"])
        status, *_ = nm56.thermocomp("init", str(nm / "grinder"), *nm56.INIT_ARGS["grinder"],
                                     f"out={nm}/init-grinder")
        assert status == 0
    for seed in GRINDERS:
        if not (folder / f"grinder{seed}").exists():
            nm56.write_grinder(folder / f"grinder{seed}", seed)


def _record(case: str, root: Path):
    """(dataset, compensator, options) of a :data:`RECORDS` entry."""
    if case.startswith("grinder:"):
        from bench_diagnose_refnoise57 import composed
        return composed(root / "lag", "grinder-nocoolant", f"data.path={root}/grinder{case[8:]}")
    from bench_diagnose_faults58 import case_data
    ds, comp, options, _ = case_data(case, root)
    return ds, comp, options


def rows(root: str, label: str) -> None:
    """:data:`RECORDS` diagnosed (module doc) -> ``ROOT/rows-LABEL.jsonl``."""
    from cpu import cpu_seconds

    from thermocomp.apps.diagnose import diagnose

    folder = made_folder(root)
    with open(folder / f"rows-{label}.jsonl", "w") as out:
        for case in RECORDS:
            ds, comp, options = _record(case, folder)
            t0 = cpu_seconds()
            d = diagnose(ds, comp, None, "simulation", options)
            row = {"case": case, "cpu_s": round(cpu_seconds() - t0, 1), "targets": {}}
            for t, x in d.targets.items():
                j = d.to_json(t)
                row["targets"][t] = {
                    "before": j["before"]["test_rmse"], "after": j["after"]["test_rmse"],
                    "accepted": [e.effect.title for e in x.accepted],
                    "excluded": j["excluded_inputs"],
                    "blocks": [r.test_blocks for r in x.search.rounds],
                    "control": bool(j["control_ever_clears_bar"])}
            print(json.dumps(row, ensure_ascii=False, default=float), file=out, flush=True)
            print(f"  {case} {label} ({row['cpu_s']} s): " + " | ".join(
                f"{t} {v['blocks']} {v['before']:.4f} -> {v['after']:.4f} "
                f"{[a[:40] for a in v['accepted']]}{' CONTROL' if v['control'] else ''}"
                for t, v in row["targets"].items()), flush=True)


def _rows(path: Path) -> dict:
    with open(path) as f:
        return {r["case"]: r for r in map(json.loads, f)}


def compare(root: str, a: str, b: str) -> None:
    """The bar's counts of labels ``a`` and ``b``, then every row whose after differs."""
    rs = {n: _rows(Path(root) / f"rows-{n}.jsonl") for n in (a, b)}
    for n, r in rs.items():
        control = [f"{c} {t}" for c, x in r.items() for t, v in x["targets"].items() if v["control"]]
        worse = [f"{c} {t} {100 * (v['after'] / v['before'] - 1):+.1f} %" for c, x in r.items()
                 for t, v in x["targets"].items() if v["after"] > 1.02 * v["before"]]
        print(f"{n}: control clears {control}; > 2 % over before {worse}; "
              f"diagnose CPU {sum(x['cpu_s'] for x in r.values()):.1f} s")
    worse = 0
    for c, x in rs[a].items():
        for t, v in x["targets"].items():
            w = rs[b][c]["targets"][t]
            if (v["accepted"], v["after"], v["blocks"]) != (w["accepted"], w["after"], w["blocks"]):
                change = 100 * (w["after"] / v["after"] - 1)
                worse += change > 2.0
                print(f"  {c} {t}: before {v['before']:.4f}; {a} {v['after']:.4f} {v['blocks']} "
                      f"{[s[:44] for s in v['accepted']]} | {b} {w['after']:.4f} {w['blocks']} "
                      f"{[s[:44] for s in w['accepted']]} ({change:+.1f} %)")
    print(f"rows more than 2 % worse in {b} than in {a}: {worse}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "rows": rows, "compare": compare}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
