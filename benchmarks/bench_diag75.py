"""The closed loop's two open items of stop 74 (issue 34 item 4; stop 75, diag75): why planted 4001
is missed, and why a sensor is excluded at a removal p of 0.04-0.08 when effects need 0.01.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag75.py trace SEED           # a planted VMC seed: round 1 of E_Y with oracles
    python benchmarks/bench_diag75.py fresh ROOT           # fresh seeds -> ROOT/fresh.jsonl
    python benchmarks/bench_diag75.py removal ROOT SEED    # tcm74's record: the health step's evidence

``trace``: bench_diagnose_memory's ``planted:SEED`` (the few-campaign year-round VMC, 8 train
campaigns, a position x column-tilt effect on E_Y), round 1 of E_Y with two oracles beside the
search's candidates: ``S_truth`` (the planted term itself, as the simulator adds it, offered as a
state: its ``raw`` signal is the exact form in one regressor) and the ideal record (E_Y less that
term at its true coefficient: nothing left to find), each campaign's share of its CV MSE gained.
``fresh``: the shipped bar on seeds never used (clean 7561-7572, planted 7573-7584;
bench_diagnose_refnoise57.row, as bench_planted72's ``fresh``).  ``removal``: bench_stranger74's
``write ROOT SEED 24 60`` record (tcm74, 22 sensors, one record cut 70/30), ``thermocomp diagnose``
at the defaults, each removal the health step weighed with its evidence.

Item 1: planted 4001 (traced before any rule; no rule proposed)
---------------------------------------------------------------
Measured (2026-12-02, main 960d5025, ``trace 4001``; round 1 of E_Y; g CV RMSE gain %, the 8
held-out campaigns' shares of their CV MSE gained, p the raw gains' sign flips, "alone" the bar's
own statistic -- the 67 blocks' signed ranks -- with a family of one, pf family-wise over the
round, the oracles included)::

  67 test blocks of ~8 samples in 8 campaigns, min p 5e-5
  train campaign         K01   K02   K04   K05   K07   K08   K10   K11
  CV MSE (µm²)          20.2   4.9   3.2   4.8   2.8  13.5   5.2   2.4
  planted term RMS (µm) 3.85  3.56  1.26  2.14  0.49  3.07  1.94  1.21

  candidate                        q  g     campaigns' shares of MSE gained   p     alone pf    blocks+
  S_truth raw (the exact term)     1  37.1  .82 .63 -.31 .82 -.38 .66 .80 .73  .0007 .021  .050  37/67
  S_pos_Y x inputs' rises (bank)  10  31.2  .77 .72 -.45 .74 -.80 .60 .81 .39  .0043 .075  .141  34/67
  S_pos_Y x T_motor1               1  26.9  .66 .67 -.64 .76 -.85 .49 .78 .84  .0037 .029  .064  37/67
  the ideal record (E_Y less the term at its true coefficient), its base MLR against the
  planted record's: CV RMSE 2.669 -> 1.607, shares .87 .54 -.45 .81 -.47 .68 .76 .76,
  test RMSE 5.313 -> 2.376

(Without the oracles in the family, the shipped round: the product pf .036, the bank .075 --
bench_planted72's trace, reproduced.)  **Power, not resolution nor the candidate set.** The
design reaches 5e-5, and the exact planted term, offered in its exact one-regressor form, fails
the bar's own statistic alone (.021 > .01, a family of one, so no step-down or smaller family
helps): like the search's best readings it makes K04 and K07 worse, the two campaigns where the
term is smallest (1.26 / 0.49 µm RMS), and gains in 37 of 67 blocks only.  The ideal record
says why: with the term gone exactly, the base MLR's CV on K04 / K07 is 45 / 47 % WORSE -- the
10 input coefficients had absorbed part of the tilt, and that absorption happened to cancel part
of those two campaigns' own misfit.  Two of 8 campaigns contradict the truth itself; only a
weaker statistic (the raw gains, which the two hot campaigns K01 / K08 carry: family-wise .0099
for the product, bench_planted69) would take it, and ranks stand where they are for clean data's
sake (``Search._family_bar``).  No general rule is proposed.

``fresh`` at the shipped code (960d5025; 22.8 s CPU): clean 7561-7572 accepting 0 of 12 (the
control clears the bar in a round of planted 7573, not accepted), planted 7573-7584 found first
11 of 12 (test RMSE -30 ... -76 %), none worse; the miss, 7581 (89 blocks, min p 5e-5), traces
as 4001: the exact term raw p 0.075 alone (48 of 89 blocks), the bank 0.011 alone / 0.050
family-wise, and the ideal record's base worse on 2 of the 8 campaigns (K01 -74 %, K10 -29 %).

Item 2: the removal's p (the rule and its bar, written and committed before scoring)
-----------------------------------------------------------------------------------
What the code does (``search.Search._evaluate``, ``search.sensor_health``): a ``sensor_fault``'s
evidence is the self-prediction jump ratio (>= ``fault_ratio``, 3); the CV of the model without the
sensor is a non-inferiority check (no target >= ``min_gain_pct`` worse, over all rows and where no
fold extrapolates).  The removal's sign-flip ``p_value`` is computed and written in
``diagnosis.json`` but is no part of its bar: a p of 0.08 does not exclude the sensor, the jump
ratio does.  Effects are held to ``p_family <= alpha``; removals to no p at all.

The rule ``onealpha`` (one test, one alpha): a removal clears only if, besides the jump ratio
and the non-inferiority, its CV gain on at least one target has the effects' test at the effects'
alpha: the sign-flip ``p_value`` of the blocks' MSE gains <= ``alpha`` (a family of one per
nominee: the nominee is chosen by the jump, not by the gain, so no step-down over sensors).

The bar (adopt only if all hold; else src reverted, bench + patch kept, REFUSED):

1. bench_diagnose_faults58's 36 cases: every planted fault the shipped code excludes still
   excluded (shipped 10 of 16, one-unit 5 of 16); no healthy sensor removed that shipped keeps.
2. The health-check tests of tests/apps/test_diagnose*.py pass.
3. tcm74 seed 7442 (``removal``): the healthy ``T_Hydraulik`` kept.
4. bench_moretest68's rows: planted found >= 22 of 23, clean + null accepting 0 of 44; fl_thermal
   60/20/20 and 90/10 (hammerstein, mlr, lagbank on all five channels) no channel > 2 % worse than
   shipped; fresh seeds (``fresh``) no clean record accepting, planted found not fewer.
Expected from fault70's table (``bench_fault70.py``: the faults the shipped code finds gain
-1.35 ... +59 % at p 0.0016-0.5): item 1 fails; scored on it first.

Scored (2026-12-02; shipped = a ``git archive`` of 960d5025, the rule = it + ``diag75_rule.patch``;
bench_diagnose_faults58's 20 cases and 16 one-unit cases, one ``write`` root; CPU user + sys
127.8 s shipped, 129.1 s the rule):

1. **Fails.** Planted faults excluded 10 -> 2 of 16, in one unit 5 -> 2 of 16: the climate
   room's four (CV gain -1.35 ... +0.56 %: the model had already learnt to discount them), the
   twin lathe's four (nominated and refused by the p although ``T_Sub_bearing`` gains
   +58 % on E_Z2: a fault in a few of one record's blocks; fault70 measured p 0.02-0.20) and
   year-round drift1 / offset1 / stuck1 lost; the Swiss lathe's drift and stuck still found.
   Healthy sensors removed 18 -> 0 (the twin lathe's pair in its 9 cases).
3. Held: tcm74 7442 keeps ``T_Hydraulik`` (``removal``; its removal's p 0.43 / 0.11 / 0.038 on
   E_dX / E_dY / E_dZ, CV gain +3.0 ... +3.8 %, jump ratio 3.58).  But kept, E_dY takes the
   inputs' 900 s lag: test 0.389 -> 0.684 µm deployed (+76 %; as run 0.242 -> 0.463), E_dZ
   ``S_Drehzahl`` raw 1.720 -> 1.400 (shipped: 2.194, the removal alone, as run 0.998).

**REFUSED** (item 1); src unchanged, the rule kept as ``benchmarks/diag75_rule.patch``; items 2
and 4 not scored.  Why the two bars differ: a removal's evidence is the sensor's own (its
self-prediction jump), an effect's the error it explains.  A broken sensor the model already
discounts gains little when removed, so a gain test at 0.01 keeps it; the CV on a removal is a
non-inferiority check (no target 5 % worse), and its p is reported, not tested.

The shipped removal on tcm74 7442 (24 h at 60 s, cut 70/30), as ``removal`` prints it: E_dX /
E_dY / E_dZ as run 0.865 / 0.242 / 1.010 -> 0.685 / 0.241 / 0.998 µm, deployed 1.428 / 0.389 /
1.720 -> 1.485 / 0.435 / 2.194 (the stream clamps 109 -> 260 test rows to the envelope of the
model without the sensor): +3.9 / +11.8 / +27.6 % as the machine gets it, the envelope's doing
(clamp74), not the model's: the envelope's pattern (rank 9 both), refitted on the 21 inputs, has
361 of 432 test rows off it against 247 (tol 0.080 -> 0.077; the model frame, run's model.pkl
of each and the train part, measured once by hand).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import made_folder, run_commands  # noqa: E402

FRESH_CLEAN = list(range(7561, 7573))
FRESH_PLANTED = list(range(7573, 7585))


def _planted_with_truth(seed: int):
    """The few-campaign VMC of ``seed`` with its planted term added to every campaign as
    ``S_truth`` (the simulator's own ``extra``, recorded as it plants it)."""
    from test_diagnose_few import few
    from thermocomp.apps.sim import effects

    terms, shipped = [], effects.AxisPosition.modify_errors

    def spy(self, ctx, errors):
        position = ctx.states[self.column]
        terms.append(float(self.params["gain_um_per_K_per_m"]) * self.tilt(ctx)
                     * (position - position[0]) / 1000.0)
        return shipped(self, ctx, errors)

    effects.AxisPosition.modify_errors = spy
    try:
        ds, truth = few("axis_position", seed)
    finally:
        effects.AxisPosition.modify_errors = shipped
    for term, frame in zip(terms, ds.campaigns.values()):
        frame["S_truth"] = term
    return ds, truth


def _round_one(ds):
    """(diagnosis, round 1's candidate effects of E_Y, the CV result they were weighed against)."""
    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.apps.diagnose.search import Search
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    shipped, seen = Search._family_bar, []

    def bar(self, evals, current):
        shipped(self, evals, current)
        seen.append(([ev for ev in evals if not ev.control and ev.effect.transform != "remove"], current))

    Search._family_bar = bar
    try:
        d = diagnose(ds, Compensator(MLR()), targets=["E_Y"], options=SearchOptions(max_effects=1))
    finally:
        Search._family_bar = shipped
    return (d, *seen[0])


def _shares(before, after) -> list:
    return np.round(np.clip((before - after) / before, -1.0, 1.0), 2).tolist()


def trace(seed: str) -> None:
    """Round 1 of E_Y with the oracles; the ideal record's CV against the planted one's."""
    from scipy.stats import rankdata

    from thermocomp.apps.diagnose.cv import sign_flip_pvalues

    ds, truth = _planted_with_truth(int(seed))
    train = ds.ids("train")
    print(f"== planted:{seed} ({truth['undeclared_effects'][0]['description']})")
    for cid in train:
        f = ds.campaigns[cid]
        print(f"  {cid}: planted term RMS {np.sqrt(np.mean(f['S_truth'] ** 2)):.2f} µm", flush=True)
    d, family, current = _round_one(ds)
    cv = d.to_json("E_Y")["cv"]
    print(f"  {cv['test_blocks']} test blocks, {cv['units']} units, min p {cv['min_p']:.2g}; "
          f"campaigns' CV MSE {np.round(current.unit_mse, 2).tolist()}")
    for ev in sorted(family, key=lambda e: -e.gain):
        if ev.gain_pct < 10.0 and "S_truth" not in str(ev.effect.column):
            continue
        D = current.block_mse - ev.result.block_mse          # the bar's statistic, a family of one
        alone = sign_flip_pvalues(np.sign(D) * rankdata(np.abs(D)))[0]
        print(f"  {ev.effect.kind} {ev.effect.column} {ev.effect.label[:36]}: q {ev.n_features} g "
              f"{ev.gain_pct:.1f} units {_shares(current.unit_mse, ev.result.unit_mse)} p "
              f"{ev.p_value:.4f} ranked alone {alone:.4f} family-wise {ev.p_family:.4f} margin "
              f"{ev.p_margin:.3f} blocks gaining {int((D > 0).sum())}/{D.size} clears {ev.clears_bar}",
              flush=True)
    for frame in ds.campaigns.values():      # the ideal: the term taken out at its true coefficient
        frame["E_Y"] = frame["E_Y"] - frame.pop("S_truth")
    ideal, _, ideal_cv = _round_one(ds)
    print(f"  ideal (E_Y less the term): CV RMSE {np.sqrt(ideal_cv.unit_mse.mean()):.3f} against "
          f"{np.sqrt(current.unit_mse.mean()):.3f}; campaigns' shares "
          f"{_shares(current.unit_mse, ideal_cv.unit_mse)}; test RMSE "
          f"{ideal.to_json('E_Y')['before']['test_rmse']:.3f} against "
          f"{d.to_json('E_Y')['before']['test_rmse']:.3f}", flush=True)


def fresh(root: str) -> None:
    """The fresh seeds' rows to ROOT/fresh.jsonl with their CPU s."""
    import bench_diagnose_refnoise57 as refnoise
    import bench_remeasure62 as rm

    folder = made_folder(root)
    cases = [f"clean:{s}" for s in FRESH_CLEAN] + [f"planted:{s}" for s in FRESH_PLANTED]
    rm.measure(folder / "fresh.jsonl", (("diag75", refnoise.row(c, "before", folder / "lag")) for c in cases))


def removal(root: str, seed: str) -> None:
    """tcm74's record (24 h at 60 s, cut 70/30) diagnosed at the defaults: each removal weighed."""
    folder = made_folder(root)
    tree = [sys.executable, str(HERE / "bench_stranger74.py")]
    subprocess.run([*tree, "write", str(folder), seed, "24", "60"], check=True, capture_output=True)
    out = folder / "diag"
    subprocess.run([sys.executable, "-m", "thermocomp", "diagnose",
                    f"hydra.searchpath=[file://{folder / 'conf'}]", f"data=fs{seed}", "track=false",
                    f"out={out}"], check=True, capture_output=True)
    for path in sorted((out / "diagnosis").glob("diagnosis_*.json")):
        d = json.loads(path.read_text())
        print(f"  {d['target']}: test RMSE before -> after {d['before']['test_rmse']:.3f} -> "
              f"{d['after']['test_rmse']:.3f} (deployed), {d['before']['test_rmse_as_run']:.3f} -> "
              f"{d['after']['test_rmse_as_run']:.3f} (as run); excluded {d['excluded_inputs']}; "
              f"accepted {[_named(e) for e in d['effects'] if e['accepted']]}")
        for ev in (d["rounds"][0]["evaluated"] if d["rounds"] else []):
            e = ev["evidence"]
            if ev["effect"]["transform"] == "remove":
                print(f"    {ev['column']}: jump {e['self_prediction_jump_ratio']:.2f}, CV gain "
                      f"{e['cv_rmse_gain_pct']:+.2f} % (in range {e['cv_rmse_gain_pct_in_range']:+.2f} %), "
                      f"p {e['p_value']:.4f}, excluded {ev['accepted']}")


def _named(effect: dict) -> str:
    return f"{effect['column'] or '-'} {effect['transform'][:24]}"


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "fresh": fresh, "removal": removal}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
