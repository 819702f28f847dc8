"""diag91b's rule (diagnose's test blocks re-cut by the candidates' gains' decorrelation, ``campaigns``
scheme only, a between-campaign guard) on records it was not tuned on: faults58's climate room and
bench_diag88's grinders (stop 91, diag91c; issue 34: "... accepts nothing on clean data, and never
leaves a record's test error more than 2 % worse"; bench_diag91b's "left").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag91c.py write ROOT               # the grinder records -> ROOT
    python benchmarks/bench_diag91c.py rows ROOT LABEL          # every record -> ROOT/rows-LABEL.jsonl
    python benchmarks/bench_diag91c.py compare ROOT A B         # two labels' rows: the bar's counts
    python benchmarks/bench_diag91c.py trace ROOT CASE...       # per round: blocks, the best rivals' p

``write``: bench_new_machines56's grinder (its seed; ``init`` with its test share, whose config the
grinders are read with) and the grinders 5687 / 5682 (bench_diag88's) under ``ROOT``.  ``rows``:
every record of :data:`RECORDS` diagnosed with MLR on every target -- the climate room
(bench_diagnose_faults58's ``climate_room``, sim seed 5820, 43 campaigns, 39 train, clean and each
planted fault, ``max_effects=1`` as faults58) and the grinders (``grinder-nocoolant``'s config as
bench_diag88 / refnoise57 read them, 12 runs, test share 0.25) -- per target: test RMSE before ->
after, what is accepted, each round's test blocks, whether the control ever clears.  ``compare``
(bench_diag91's): per label the controls clearing; then every (record, target) row whose accepted
effects or after differ between A and B, with the change against A.  ``trace``:
each step > 0 round of the CASEs (:data:`RECORDS` names): its test blocks, the three rivals of
largest CV gain (gain %, family-wise p, clears) and the control's p; with B's src also the family's
largest between-campaign share of the gains (the guard's number).

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

Scored (2026-12-05, 2 cores shared with other helpers; A then B, ``rows`` after the bar above was
committed (222e234c), run twice per tree, identical rows; CPU of the diagnoses 26.3 / 25.2 s A,
28.6 / 29.4 s B)
--------------------------------------------------------------------------------------------------
Test RMSE (as run), before -> after, every (record, target) row: IDENTICAL in A and B -- the same
effects accepted, the same after::

  record                 target           before  after   accepted (A and B)
  climate_room:clean     E_X / E_Z        0.2854 / 0.2913 unchanged, nothing
  climate_room:drift     E_X              0.3154  0.3174  T_headstock removed
                         E_Z              0.3721  0.3262  T_headstock removed + inputs 900 s lag +init
  climate_room:offset    E_X              0.3603  0.3612  T_toolholder1 removed
                         E_Z              0.3761  0.3715  T_toolholder1 removed
  climate_room:stuck     E_X              0.5990  0.5146  T_nc_x1_drive removed + inputs 900 s lag +init
                         E_Z              0.5273  0.4779  T_nc_x1_drive removed + T_nc_tool_motor 900 s lag
  climate_room:contact   E_X              0.3174  0.3174  T_headstock removed
                         E_Z              0.3866  0.3262  T_headstock removed + inputs 900 s lag +init
  grinder:5687           dY               0.5433  0.4306  T_Ständer_Bohrung 900 s lag (real, bench_diag88)
                         dZ               0.3867  0.3867  nothing
  grinder:5682           dY               0.7395  0.7943  T_Ständer_vorn 900 s lag (+7.4 %: A's own harm)
                         dZ               0.5600  0.5600  nothing

No control clears in either tree.  Where the blocks differ (the test blocks of the rounds after the
health step; ``trace``)::

  climate_room:stuck E_X  39 -> 137 blocks (587 -> 131 samples): the same three lags clear, p_fam
                          < 1e-4 in both; control p 0.842 -> 0.957
  climate_room:stuck E_Z  39 -> 230 blocks (587 -> 83): the same three clear, p_fam <= 3e-4 in A,
                          < 1e-4 in B; control p 0.938 -> 1.000
  grinder:5682 dY round 2 9 -> 328 blocks (644 -> 24 samples; largest share 0.097): nothing clears in
                          either, but the two S_Schleifleistung lags (CV gain 1.4 / 1.2 %) read p_fam
                          0.9004 -> 0.0012 / 0.0001, refused by the bar's 5 % gain floor
                          (``min_gain_pct``) and margin, not by their p
  every other round: the residual's blocks (one per campaign / run) in both trees.

The guard (share > 0.4): fires on grinder 5682's and 5687's round 1 (largest member share 0.419 /
0.525), nowhere on the climate room (0.25-0.39).  It decides nothing here: with the guard off
(``BETWEEN_CAMPAIGNS`` patched to 1.01, B's src; ``trace`` of grinder 5682 / 5687 and
climate_room:clean only) the grinders' round-1 lengths (665 / 1082 samples) still cut their 9 runs
of 480-1200 samples into 9 blocks, every round's blocks and p as with the guard.

Bar: 1 holds (0 rows more than 2 % over A's after; every after identical); 2 holds (no acceptance new
in B on any record); 3 holds (no control clears in either).  **TRACED-clean**: no src change.

What it shows beyond the bar: on a short-run record (the grinder's 9 train runs) a round whose
candidates' gains decorrelate in ~24 samples is tested on 328 ranked blocks, and 1.2-1.4 % CV gains
read a family-wise p of 1e-4; the bar's gain floor and margin carry the refusal there, not the p.
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
            row = {"case": case, "cpu_s": round(cpu_seconds() - t0, 1), "found": None, "targets": {}}
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


def compare(root: str, a: str, b: str) -> None:
    """bench_diag91's compare of the ``rows`` of labels ``a`` and ``b`` (no position is planted
    here: its "found" counts are empty)."""
    import bench_diag91
    bench_diag91.compare(root, "rows", a, b)


def trace(root: str, *cases: str) -> None:
    """Per round of ``cases``: test blocks, the best rivals' evidence (module doc)."""
    import numpy as np

    from thermocomp.apps.diagnose import diagnose
    from thermocomp.apps.diagnose.search import Search

    try:
        from thermocomp.core.model_selection.blocks import between_campaign_share
    except ImportError:   # A's src: no guard
        between_campaign_share = None
    original = Search._family_bar

    def traced(self, evals, current):
        original(self, evals, current)
        p = self.problem
        family = [ev for ev in evals if not ev.control and ev.effect.transform != "remove"]
        if not family:
            return
        share = "" if between_campaign_share is None else " largest share {:.3f};".format(max(
            between_campaign_share(current.residual ** 2 - ev.result.residual ** 2, p.campaigns,
                                   p.validated) for ev in family))
        control = next((ev for ev in evals if ev.control), None)
        best = sorted(family, key=lambda ev: -ev.gain)[:3]
        print(f"    {p.target}: {p.n_blocks_tested} blocks ({p.block_samples} samples);{share} "
              + "; ".join(f"{ev.effect.title[:44]} {ev.gain_pct:.1f} % p_fam {ev.p_family:.4f}"
                          f"{' CLEARS' if ev.clears_bar else ''}" for ev in best)
              + (f"; control p {control.p_value:.3f}" if control else ""), flush=True)
        assert np.isfinite(current.block_mse).all()

    Search._family_bar = traced
    folder = Path(root).resolve()
    for case in cases:
        print(f"  {case}", flush=True)
        ds, comp, options = _record(case, folder)
        diagnose(ds, comp, None, "simulation", options)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"write": write, "rows": rows, "compare": compare,
                                    "trace": trace}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
