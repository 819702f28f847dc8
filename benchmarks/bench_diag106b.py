"""A sensor removal judged on a bound, not on a point estimate 8 campaigns cannot carry (stop 106,
diag106b; issue 34: "``diagnose`` ... never leaves a record's test error more than 2 % worse").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag106b.py seen ROOT            # 10076 (diag106's draw) -> ROOT/rows.jsonl
    python benchmarks/bench_diag106b.py fresh ROOT           # 10082-10086 + clean twins -> ROOT/rows.jsonl
    python benchmarks/bench_diag106b.py table ROOT           # bench_diag106's table of ROOT's rows
    python benchmarks/bench_diag106b.py units ROOT CASE ...  # faults58 CASEs: each removal's units
    python benchmarks/bench_diagfault72.py faults ROOT STEM  # bar item 2 (faults58's 36 cases)
    python benchmarks/bench_diag75.py removal ROOT 7442      # bar item 3 (tcm74 7442)
    python benchmarks/bench_diagfault72.py record WORK STEM "90/10 mlr" "60/20/20 mlr" \\
        "60/20/20 hammerstein E_ch4"                         # bar item 5 (fl_thermal, the docs' rows)
    python benchmarks/bench_diagfault72.py score WORK ROOT SHIPPED NEW  # items 2 and 5 counted

The rule is ``diag106b_rule.patch`` (``git apply`` it to measure it; src is the shipped one).
``units``: bench_diagnose_faults58's CASEs (data under ROOT, bench_fault70 ``write``), every removal
the health step weighed: pooled CV gain, the rule's p (computed here, on any src) and each held-out
unit's RMSE change.  ``seen`` / ``fresh``: bench_diag106's ``audit`` (the user's commands:
simulate, diagnose at the defaults, the rerun, replay; test RMSE as diagnose scores it, deployed)
on :data:`KINDS`.

The harm (diag106, 1707a192): fresh 10076 (year-round VMC, ``sensor_drift`` on ``T_box1`` in the
later campaigns, train and test) -- diagnose excludes ``T_box1`` and ``E_Z`` goes 4.565 -> 5.430 um
(+18.9 %).  ``E_Z`` reads ``T_box1`` (MLR coefficient -2.15 um/K).  The removal's non-inferiority
(``search.Search._evaluate``: no target >= ``min_gain_pct`` worse in CV) passed on its pooled point
estimate (5.00 -> 4.89 um) while the 8 held-out campaigns' changes ran -38 ... +39 % (K07 +39 %,
K08 +14 %); on test 3 of 4 campaigns got 35-72 % worse.

The rule ``notworse`` (form and level chosen before any scoring; no constant fitted on 10076)
---------------------------------------------------------------------------------------------
A removal's non-inferiority is a TEST, not a point estimate: on every target, besides the shipped
clauses (jump ratio >= ``fault_ratio``; pooled and in-range CV not ``min_gain_pct`` worse), the
held-out units' MSEs (``CVResult.unit_mse``: the campaigns; forward, the validation blocks) must
show at ``alpha`` that the removal costs less than ``min_gain_pct``: the one-sided sign-flip p of
``e_k = (1 + m)^2 MSE_k - MSE+_k`` (m = ``min_gain_pct`` / 100; mean <= 0 under "worse by m or
more") <= ``alpha`` -- the margin test the effects pass (``margin_pvalue``), the margin on the cost
side (``search.not_worse_pvalue``).  Level: the project's ``alpha`` (0.01), the one the effects
use; no new key.  Where the units cannot reach ``alpha`` (fewer than 7: smallest p 2^-n > alpha)
the level is their smallest p: every unit within the margin.  Every target must pass (an
intersection-union test: no multiplicity correction).  How it differs from the refused rules:
diag75 ``onealpha`` asked a GAIN at p <= alpha on some target (superiority, margin 0); fault70
EARN asked a 5 % gain.  This asks no gain: a removal the model already discounts (each unit
changed by less than the margin) passes at the design's smallest p.

Kinds of the fresh draws (chosen before drawing; bench_diag106's): 10082, 10084, 10086
``vmc_drift_later`` (10076's kind), 10083, 10085 ``vmc_jump_some`` (10077's kind); each with its
clean twin; 8 train campaigns each.

BAR (all must hold, else REFUSED: src reverted, this bench and ``diag106b_rule.patch`` kept):

1. seen 10076: ``E_Z`` no longer > 2 % worse (diagnose's after vs before, deployed).
2. bench_diagnose_faults58's 36 cases (bench_diagfault72 ``faults``, shipped = ``git archive`` of
   1707a192): every planted fault the shipped code excludes still excluded; no healthy sensor
   removed that shipped keeps.
3. tcm74 7442: the healthy ``T_Hydraulik`` kept.
4. tests/apps/test_diagnose*.py and tests/**/test_diagnose* pass.
5. fl_thermal, the docs' diagnose rows ("90/10 mlr", "60/20/20 mlr", "60/20/20 hammerstein
   E_ch4"): no channel's after > 2 % worse than shipped's after.
6. fresh 10082-10086 (scored once, after this bar is committed): no (draw, target) > 2 % worse
   (after vs before); the clean twins accept nothing (no effect, no sensor excluded).

Scored (2026-12-07; shipped = ``git archive`` of 1707a192, the rule = it + ``diag106b_rule.patch``;
nice, ``OMP_NUM_THREADS=1``, 2 cores under load 6-13; CPU user + sys by ``/usr/bin/time``)
---------------------------------------------------------------------------------------------
1. **Met.** seen 10076: ``T_box1`` kept (the rule's p 0.133 / 0.160 / 0.129 on E_X / E_Y / E_Z),
   ``E_Z`` 4.565 -> 4.565 um (shipped 5.430); E_X / E_Y 0.676 / 1.470 unchanged (shipped 0.626 /
   1.497).  16.0 s.
2. **FAILS.** faults58's 36 cases (shipped 142.6 s, rule 139.5 s): planted faults excluded 10 -> 8
   of 16, in one unit 5 -> 4 of 16; healthy removals 17 -> 14 (twin lathe clean / offset /
   drift1 keep ``T_Chuck_hydraulics``), none new.  Lost, ``units`` (rule's p; units' RMSE change
   without the sensor, + worse)::

     climate_room:drift T_headstock   E_Z pooled -1.35 %, p 0.017: 39 units -15 ... +13 %
                                      (kept: test E_X / E_Z 0.317 / 0.326 -> 0.315 / 0.310)
     swiss_lathe_door:contact1 T_nc_spindle_motor  E_X pooled +13.95 %, p 0.127: 16 units, two
                                      -36 / -58 %, six +6 ... +21 %  (kept: E_X 1.019 -> 1.233 um)
     twin_lathe:drift T_Sub_bearing   E_Z2 pooled +59.4 %, p 0.025: 16 units, two +203 / +214 %,
                                      the rest -93 ... +28 %  (kept: E_Z2 0.331 -> 1.107 um)

   A broken sensor costs where it is healthy and read, and gains where it is broken: the same
   spread as 10076's (-38 ... +39 %), with the opposite test outcome on two of three.  The
   per-unit spread does not tell a removal that hurts the test from one that saves it.
3. **FAILS (as shipped).** tcm74 7442: ``T_Hydraulik`` excluded by both (rule: p 2^-16 on all
   three targets, all 16 forward units within the margin); deployed 1.428 / 0.389 / 1.720 ->
   1.485 / 0.435 / 1.786 um, as run no worse -- clamp74's envelope, which no CV bound sees.
4. Met: tests/apps/test_diagnose*.py, tests/shell/test_diagnose*.py, test_sensor_faults,
   test_sim_effects, test_auto_diagnosed* with the rule (and its test): 211 passed (76.4 s CPU).
5. Met: fl_thermal "90/10 mlr", "60/20/20 mlr", "60/20/20 hammerstein E_ch4": every channel the
   same as shipped to the digit (T_t16 / T_t5 nominated, kept by both; 43.8 s).
6. Met, vacuously: fresh 10082-10086 and twins (86.1 s): nothing accepted or excluded on any of 30
   (draw, target), none worse; no sensor was nominated (planted jump ratios 1.57-2.36 < 3), so the
   rule never acted: shipped's rows are the same by construction (not run).

**REFUSED** (items 2 and 3): src unchanged, the rule and its test in ``diag106b_rule.patch``.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag106 as d106  # noqa: E402
from _cli import run_commands  # noqa: E402

SEEN = "10076"
FRESH = "10082-10086"
KINDS = {10082: d106.KINDS[10076], 10083: d106.KINDS[10077], 10084: d106.KINDS[10076],
         10085: d106.KINDS[10077], 10086: d106.KINDS[10076]}


def audit(root: str, seeds: str) -> None:
    d106.KINDS.update(KINDS)
    d106.audit(root, seeds)


def units(root: str, *cases: str) -> None:
    """Each faults58 CASE's health step: every removal, its pooled CV gain, the rule's p and its
    held-out units' RMSE change (%, + worse without the sensor)."""
    import bench_diagnose_faults58 as f58
    import numpy as np

    import thermocomp.apps.diagnose.diagnosis as dg
    from thermocomp.apps.diagnose import diagnose
    from thermocomp.apps.diagnose.cv import sign_flip_pvalues

    shipped = dg.sensor_health

    def traced(searches, options=None, start=None):
        out = shipped(searches, options=options, start=start)
        m = 1.0 + options.min_gain_pct / 100.0
        for t, rnd in out[2].items():
            for ev in (rnd.evaluated if rnd else []):
                b, a = out[3][t].unit_mse, ev.result.unit_mse
                p = float(sign_flip_pvalues([m * m * b - a], seed=options.seed)[0])
                change = 100.0 * (np.sqrt(a / b) - 1.0)
                print(f"{case} {t} {ev.effect.column}: pooled {ev.gain_pct:+.2f} %, rule's p {p:.4g}, "
                      f"units {np.round(change[np.isfinite(change)]).astype(int).tolist()}, "
                      f"excluded {ev.accepted}")
        return out

    dg.sensor_health = traced
    try:
        for case in cases:
            ds, comp, options, _ = f58.case_data(case, Path(root))
            diagnose(ds, comp, None, "simulation", options)
    finally:
        dg.sensor_health = shipped


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": lambda root: audit(root, SEEN),
                                  "fresh": lambda root: audit(root, FRESH),
                                  "table": d106.table, "units": units}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
