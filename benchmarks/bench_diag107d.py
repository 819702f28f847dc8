"""Why diagnose misses the planted lag and hydraulic effects on fresh climate rooms (stop 107,
diag107d; issue 34: "find the residual, trace it to an effect the model lacks").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag107d.py trace DATA TRUTH_COLUMN [TARGET]
    python benchmarks/bench_diag107d.py draws ROOT SEEDS LABEL   # bench_diag107's draws -> rows-LABEL
    python benchmarks/bench_diag107d.py bar ROOT BASE RULE       # the bar's D1-D5 on two labels' rows
    python benchmarks/bench_diag107d.py seen BASE RULE           # D6: bench_diag107c's ``seen``

``trace``: DATA (a bench_diag107 / bench_diag107c climate draw) diagnosed on TARGET (E_X) as
shipped; then, on the shipped search's round 1: every candidate reading TRUTH_COLUMN (the planted
effect's sensor or signal) with its screen rank among the round's candidates, whether the
shortlist took it, and its CV gain and p; the per-campaign gains (share of each held-out
campaign's CV MSE) of the round's best and of the truth's best candidate; then the same search
started from the lean level law taken (``ambient_scaled``, the room's law as diag107 reads it):
where the planted effect ranks and whether it clears there.  Explains only: the test split is not
read, the conditional search is no rule.
``draws`` / ``bar``: bench_diag107's (``thermocomp diagnose`` as a user runs it, MLR, every
target; planted and clean twin of each seed) on :data:`KINDS`.

The trace (2026-12-07, 02d5ff8f's src; diag107c's fresh draws, now seen; ``trace``, 2.8-3.6 s CPU
each).  Round 1 of E_X, every draw: 8 test blocks (one per campaign: the residual is mostly the
campaigns' levels), design floor p 1/256; held-out campaign gains in % of their MSE::

  10158 lag    ambient_scaled 54.0 % p .035 (-35 +77 -16 +36 +37 +86 +90 +91); mean law 53.0 % p .008
               p_fam .031; the truth's T_nc_spindle_motor lags screen #20 / #23 of 180 (not shortlisted;
               alone 19.0 % p .035, C01 -101 %); T_headstock 7200 s 24.2 % p_fam .023
  10161 lag    mean law 43.6 % p .039 (C04 -55, C06 -4); the truth's sensor lags #94.. of 310 (start
               lags, alone -0.4 %); the 28.76 C regime 39.7 % p_fam .0078 but 12 regressors: saturates
  10160 hydr.  ambient_scaled 41.2 % p .023 (C02 -128, C08 -3); S_hydraulic_temp_C 14400 s lag is
               shortlisted (#12) but gains 24.8 % p .059, within the campaigns 3.7 %

The family, sensor and tau are on offer; the level law (beta 0.015 /K on X, MLR holds none) fills
the residual.  The law loses in a held-out campaign where the planted effect still runs, and the
effect's gain is buried under the campaigns' offsets: neither clears alone.  Taken the law
(``ambient_scaled``), the next round clears the planted effect at once: 10158 T_nc_spindle_motor
14400 s 60.4 % (19 ranked blocks, p_fam 1e-4); 10161 T_nc_spindle_motor 14400 s start lag 65.3 %
(p_fam .0039); 10160 S_hydraulic_temp_C raw 56.0 % (p_fam .0039).  The PAIR against round 1's model
gains 74-86 % with every held-out campaign +50 .. +100 % (p_fam .0039 over the pairs); the
control's pair p .039 / .039 / .074.  Clean twins (10158 / 10161 / 10160): best pair p_fam .106 /
.566 / .109.  Test (read only to explain): 10158 level + T_nc_spindle_motor 14400 s 3.300 -> 0.975;
10160 level + S_hyd raw 3.177 -> 1.186.  Not the one-SE rule, a rival, the shortlist, tau or the
soaked-start gate (10161's start lags are there and clear once the law is in): the MASKING of two
effects, each < alpha alone on 8 campaigns.

Refused rules this differs from: diag106c (a cleared candidate admitted beyond a saturated rival on
the rival's residual, the rival not taken -- here the effect does not clear alone, and the law IS
taken, tested with it as one candidate); bench_diag88c rule 1 (a saturated rival dropped from the
band); diag106e (lean laws offered everywhere: diag107's gate stays, the pair is tried only where
the lean laws are offered).  diag107 took the lean law where it cleared alone (10126).

The rule (src: ``Search._level_pair``, ``Search._round``; no key, no constant)
-----------------------------------------------------------------------------
Where a round takes nothing and a lean level law gained: the lean law of most CV gain is taken
provisionally, the next round runs as any round (its own bar), and its eligible effect (``choose``'s
order) is taken WITH the law only if the pair clears against the round's model as one candidate:
held-out campaigns' gains as shares of their MSE (``_family_bar``'s one-block-per-unit statistic),
sign flips family-wise over every pair of that round (max-T) at ``alpha``, gain >= ``min_gain_pct``.
Else the law is dropped and the search stops as before.  Needs room for two effects.

BAR (committed before any of 10173-10177 is simulated; not moved after).  BASE = 02d5ff8f's src
(``git archive``), RULE = this branch's src.  Row = (draw, target), test RMSE as diagnose scores it.
* D1 seen 10158 / 10160 / 10161 PLANTED: found with RULE (bench_diag106e's E1), and no row of these 3
  draws and their clean twins with RULE's after more than 2 % above BASE's after.
* D2 fresh 10173-10177 PLANTED: found with RULE on MORE draws than with BASE.
* D3 fresh CLEAN twins: nothing accepted but the level law (diag107's E2), no sensor excluded.
* D4 the control accepted nowhere, and clears on no row where it does not with BASE.
* D5 no fresh row (20: planted and clean) with RULE's after more than 2 % above BASE's after.
* D6 bench_diag88 ``seen`` (33 rows) and bench_remeasure62 ``diagnose`` (139): none more than 2 %
  above BASE's after.  BASE rows: diag107c's RULE rows (9f388e38's src; to 02d5ff8f only deploy /
  export and core/io's rate messages changed, which these benches' valid data do not reach).
* D7 the diagnose test modules (tests/**/test_diag*.py and the importers of search / candidates /
  features) pass; ruff; test_benchmarks_cli -k diag107d.
All: KEPT; else REFUSED (src reverted, ``benchmarks/diag107d_rule.patch``).

Fresh kinds (chosen before drawing; bench_diag107c's order, 8 train / 4 test runs): 10173, 10176
``hidden_source`` (E_X); 10174, 10177 ``lag_node`` (E_X); 10175 ``axis_position`` (E_Z).

Scored (2026-12-07, once; bar at d5648504; BASE = 02d5ff8f's src + conf, RULE = d5648504's src, both
``git archive``; ROOT /tmp/diag107d; 2 shared cores, load 6-9; CPU user + sys, ``/usr/bin/time``)
-------------------------------------------------------------------------------------------------
``draws ROOT 10158,10160,10161,10173-10177``: BASE 124.0 s (simulating the 10 fresh draws), RULE
94.5 s; diagnose alone 105.3 / 94.4 s.  The rows that differ (test RMSE µm; the other 27 identical)::

  10158 lag   E_X  3.305 -> BASE 3.305 (nothing) / RULE 1.955  least-squares law + T_nc_z1_drive 7200 s
  10160 hydr. E_X  3.177 -> 3.177 / 1.060  least-squares law + S_hydraulic_temp_C raw + its 900 s lag
  10161 lag   E_X  3.298 -> 3.298 / 0.820  mean law + T_nc_z1_drive 7200 s start lag (2 directions)
  10173 hydr. E_X  3.968 -> 3.968 / 0.920  least-squares law + S_hydraulic_temp_C raw
  10176 hydr. E_X  2.248 -> 2.248 / 1.141  least-squares law + S_hydraulic_temp_C 900 s lag

D1 met (the 3 seen planted found; none of their 12 rows worse).  D2 met: found BASE 3 (10174, 10175,
10177) -> RULE 5 of 5.  D3 met (clean twins: nothing).  D4 met (the control accepted nowhere, clears
nowhere).  D5 met (no fresh row worse; 2 of 20 better by 49-77 %).  D6 met: bench_diag88 ``seen`` 33
rows (RULE 34.8 s) and bench_remeasure62 ``diagnose`` 139 (RULE 308.4 s) all identical to BASE (no
row there has a round that takes nothing after a lean law gained and a pair that clears).  D7 met:
the 66 modules (diag107c's 44 and neighbours, every test module naming the diagnose app, the new
test) 904 passed, 1 failed: test_lab_sweep57's dvc launcher, which fails alike on BASE (the
worktree has no .venv: environment); 359.4 s CPU; test_benchmarks_cli -k diag107d 2 passed, ruff
clean.  The new test_diagnose_pair107d fails on 02d5ff8f and adds 0.2-0.5 s CPU (run less
collect-only, 3 pairs).  **KEPT.**
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag107 as d107  # noqa: E402
import bench_diag107c as d107c  # noqa: E402
from _cli import run_commands  # noqa: E402

HIDDEN, LAG = d107.HIDDEN, d107.LAG
KINDS = {
    10173: ("climate_hydraulic", HIDDEN, (None, None, "E_X")),
    10174: ("climate_lag", LAG, ("dynamics", None, "E_X")),
    10175: ("climate_position", ["sim.generator.effects=[axis_position]"], (None, "S_pos_Z", "E_Z")),
    10176: ("climate_hydraulic", HIDDEN, (None, None, "E_X")),
    10177: ("climate_lag", LAG, ("dynamics", None, "E_X")),
    10158: d107c.KINDS[10158], 10160: d107c.KINDS[10160], 10161: d107c.KINDS[10161],   # seen (D1)
}
SEEN = (10158, 10160, 10161)


def _num(v) -> float:
    return float("nan") if v is None else float(v)


def _round_lines(search, current, effects_title: str) -> None:
    """One round of ``search`` from ``current`` (its effects as set): every shortlisted candidate."""
    from thermocomp.apps.diagnose import search as sm

    p = search.problem
    if p.recut_test_blocks(current.residual):
        current = search.cv._result(current.prediction, current.alpha)
    names = search.cv.selection(search.inputs(), None)
    cands = sm.candidates(p, names, set(search.excluded), search.effects, search.options.candidates,
                          search._read_columns())
    search.start_lags_screened = sum(sm._start_lag(e) for e in cands)
    if not search._bank_untestable(len(names)):
        cands = [e for e in cands if e.over is None and e.transform not in sm.LEAN_LEVEL]
    ok = p.validated
    Z = np.column_stack([np.ones(len(p.y)), search.cv.design(names, search.effects)])[ok]
    Q = sm._orthonormal(Z)
    r_perp = current.residual[ok] - Q @ (Q.T @ current.residual[ok])
    scored = [(e, sm.screen_r2(Q, r_perp, search.cv.features(e, names)[ok])[0]) for e in cands]
    short = search._shortlist(scored)
    evals = [search._evaluate(e, current, r2) for e, r2 in short]
    current = search._recut_on_gains(evals, current)
    search._family_bar(evals, current)
    print(f"  [{effects_title}] cv {current.rmse:.4f}, {p.n_blocks_tested} test blocks, "
          f"{len(cands)} candidates, shortlist {len(short)}")
    for ev in sorted(evals, key=lambda ev: -ev.gain):
        share = (current.block_mse - ev.result.block_mse) / np.maximum(current.block_mse, 1e-300)
        cells = " ".join(f"{100 * s:+.0f}" for s in share) if len(share) <= 12 else f"{len(share)} blocks"
        print(f"    {ev.effect.title[:70]:70s} gain {ev.gain_pct:6.1f} p {ev.p_value:.4f} "
              f"p_fam {_num(getattr(ev, 'p_family', None)):.4f} within "
              f"{_num(getattr(ev, 'gain_pct_within', None)):5.1f} {'CLEARS' if ev.clears_bar else ''}"
              f" | {cells}")
    return scored, short, current, evals


def _pairs(search, first, evals) -> None:
    """Each round-2 candidate taken WITH the level law, against round 1's model: the pair's CV gain,
    its held-out campaigns' gains (shares of their MSE, clipped as ``_family_bar``), their sign-flip
    p alone and family-wise over the pairs (the control's pair alone)."""
    from thermocomp.apps.diagnose.cv import sign_flip_maxt, sign_flip_pvalues

    family = [ev for ev in evals if not ev.control]
    share = lambda ev: np.clip(1 - ev.result.unit_mse / first.unit_mse, -1, 1)  # noqa: E731
    D = np.array([share(ev) for ev in family])
    pf = sign_flip_maxt(D, seed=search.options.seed)
    p1 = sign_flip_pvalues(D, seed=search.options.seed)
    print(f"  pairs (level law + candidate) against round 1's model, {len(first.unit_mse)} campaigns:")
    for ev, a, b, d in sorted(zip(family, p1, pf, D), key=lambda z: -z[0].gain)[:6]:
        gain = 100 * (1 - ev.result.rmse / first.rmse)
        print(f"    + {ev.effect.title[:60]:60s} gain {gain:5.1f} p {a:.4f} p_fam {b:.4f} | "
              + " ".join(f"{100 * x:+.0f}" for x in d))
    for ev in evals:
        if ev.control:
            d = share(ev)
            gain = 100 * (1 - ev.result.rmse / first.rmse)
            print(f"    + the control {ev.effect.title[:40]}: gain {gain:.1f} "
                  f"p {sign_flip_pvalues(d[None], seed=search.options.seed)[0]:.4f} | "
                  + " ".join(f"{100 * x:+.0f}" for x in d))


def trace(data: str, truth: str, target: str = "E_X") -> None:
    """DATA's ``target``: the shipped search, the truth's candidates, the search from the level law."""
    from bench_diag105 import _searches

    from thermocomp.apps.diagnose import diagnose
    from thermocomp.apps.diagnose.features import Effect
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.io.read import read_dataset
    from thermocomp.core.models import MLR

    ds, comp, store = read_dataset(data)[0], Compensator(MLR()), {}
    with _searches(store):
        d = diagnose(ds, comp, targets=[target])
    x, search = d.targets[target], store[target]
    print(f"{Path(data).name} {target}: shipped accepted {[e.title for e in x.search.effects]}")
    search.effects = []
    first = search.cv.run(search.inputs(), [])
    scored, short, current, _ = _round_lines(search, first, "round 1 as shipped")
    rank = sorted(scored, key=lambda s: -s[1])
    mine = [(i + 1, e, r2) for i, (e, r2) in enumerate(rank) if e.column == truth]
    print(f"  the truth's column {truth}: {len(mine)} candidates of {len(rank)}; best screen ranks "
          + ", ".join(f"#{i} {e.title[:48]} r2 {r2:.3f}{' (short)' if any(e is s[0] for s in short) else ''}"
                      for i, e, r2 in mine[:4]))
    for i, e, r2 in mine[:2]:
        ev = search._evaluate(e, current, r2)
        share = (current.block_mse - ev.result.block_mse) / np.maximum(current.block_mse, 1e-300)
        print(f"    evaluated alone: {e.title[:60]} gain {ev.gain_pct:.1f} p {ev.p_value:.4f} | "
              + " ".join(f"{100 * s:+.0f}" for s in share[:12]))
    lean = Effect("ambient_interval", "ambient_scaled")
    search.effects = [lean]
    start = search.cv.run(search.inputs(), [lean])
    evals = _round_lines(search, start, "round 2 after ambient_scaled taken")[3]
    _pairs(search, first, evals)
    search.effects = []
    # explains only: the test split is read after the search
    from bench_diag107c import _per_campaign

    short = [ev for ev in evals if not ev.control and ev.n_features == 1]
    best = sorted(short, key=lambda ev: -ev.gain)[:1] + [ev for ev in short if ev.effect.column == truth][:1]
    print(f"  test RMSE (um): before {_per_campaign(comp, ds, target, [], None)[0]:.3f}, the level law alone "
          f"{_per_campaign(comp, ds, target, [lean], None)[0]:.3f}")
    for ev in [ev for i, ev in enumerate(best) if all(ev is not b for b in best[:i])]:
        rmse, cells, _ = _per_campaign(comp, ds, target, [lean, ev.effect], None)
        print(f"    level law + {ev.effect.title[:60]}: {rmse:.3f} | {cells}")


def draws(root: str, seeds: str, label: str) -> None:
    """Each seed's PLANTED then CLEAN draw diagnosed by this tree -> ROOT/rows-LABEL.jsonl."""
    d107.KINDS = KINDS
    d107.draws(root, seeds, label)


def bar(root: str, base: str, rule: str) -> None:
    """D1-D5 on ROOT/rows-BASE.jsonl and ROOT/rows-RULE.jsonl (every row that differs first)."""
    import json

    def load(label):
        lines = (Path(root) / f"rows-{label}.jsonl").read_text().splitlines()
        return {r["case"]: r for r in map(json.loads, lines)}

    b, r = load(base), load(rule)
    for case in r:
        for t, v in r[case]["targets"].items():
            w = b[case]["targets"][t]
            titles = [a["title"][:60] for a in v["accepted"]], [a["title"][:60] for a in w["accepted"]]
            if titles[0] != titles[1] or v["after"] != w["after"]:
                print(f"  {case} {t}: before {v['before']:.4f}; BASE {w['after']:.4f} {titles[1]}; "
                      f"RULE {v['after']:.4f} {titles[0]} ({100 * (v['after'] / w['after'] - 1):+.1f} %)")
    seen = [c for c in r if r[c]["seed"] in SEEN]
    fresh = [c for c in r if r[c]["seed"] not in SEEN]

    def worse(cases):
        return [(c, t, round(100 * (v["after"] / b[c]["targets"][t]["after"] - 1), 1)) for c in cases
                for t, v in r[c]["targets"].items() if v["after"] > 1.02 * b[c]["targets"][t]["after"]]

    found = {lab: [c for c in fresh if not r[c]["clean"] and rows[c]["found"]]
             for lab, rows in ((base, b), (rule, r))}
    seen_missed = [c for c in seen if not r[c]["clean"] and not r[c]["found"]]
    clean_taking = [(c, t, [a["title"][:50] for a in v["accepted"]]) for c in fresh if r[c]["clean"]
                    for t, v in r[c]["targets"].items()
                    if v["excluded"] or any(a["kind"] != "ambient_interval" for a in v["accepted"])]
    taken = [(c, t) for c in r for t, v in r[c]["targets"].items()
             if any(d107.CONTROL_WORDS in a["title"] for a in v["accepted"])]
    new = [(c, t) for c in r for t, v in r[c]["targets"].items()
           if v["control_clears"] and not b[c]["targets"][t]["control_clears"]]
    items = [(f"D1 seen planted missed with RULE {seen_missed}; seen rows > 2 % above BASE {worse(seen)}",
              bool(seen) and not seen_missed and not worse(seen)),
             (f"D2 fresh planted found BASE {len(found[base])} {found[base]} RULE {len(found[rule])} "
              f"{found[rule]}", len(found[rule]) > len(found[base])),
             (f"D3 clean twins taking more than the level law {clean_taking}", not clean_taking),
             (f"D4 control accepted {taken}, clears with RULE only {new}", not taken and not new),
             (f"D5 fresh rows > 2 % above BASE's after {worse(fresh)}", not worse(fresh))]
    for text, ok in items:
        print(f"  {text}: {'met' if ok else 'FAILS'}")
    cpu = {lab: round(sum(x["diagnose_cpu_s"] for x in rows.values()), 1)
           for lab, rows in ((base, b), (rule, r))}
    print(f"  diagnose CPU s (children, user + sys): {cpu}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "draws": draws, "bar": bar, "seen": d107c.seen}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
