"""The acceptance rule of ``diagnose`` with few campaigns, case by case (issue 34, item 4).

Usage::

    python benchmarks/bench_diagnose_few.py [CASE ...]   # CASE: planted:SEED or clean:SEED

The scenario of ``tests/apps/test_diagnose_few.py`` (year-round machine, 12 campaigns: 8 train,
4 test; ``planted``: an axis-position effect on Y), diagnosed on ``E_Y`` with an MLR base and
``max_effects=2``.  One line per case: test blocks (samples / count), round 1's top candidate
(largest CV gain), its CV gain, family-wise p and ``1 - alpha`` lower bound of the gain (% of the
CV RMSE, the bar's margin where the blocks are finer than the campaigns), the effects accepted,
E_Y's test RMSE before -> after (µm) and whether the random-walk control ever clears the bar.

Measured 2026-11-28.  Shipped rule: ``p <= alpha`` and a CV gain of ``min_gain_pct`` (5 %) in the
point estimate (with ranked blocks also a 95 % lower bound above 0).  New rule: with ranked blocks
the ``1 - alpha`` lower bound of the gain must itself reach ``min_gain_pct`` (superiority by the
margin at alpha).  Tuned on the first 13 cases; 737/848/959 were run once, after the rule was
fixed, and are reported as they came::

  case         blocks  top (round 1)              gain  p_fam   bound  shipped               new
  planted 515  67/8    S_pos_Y x T_bearing_r      44.8  .039    (8 u)  none                  none
  planted 626  13/45   S_pos_Y x T_bearing_r      35.3  .0043    7.6   2: 11.10->4.10        same
  planted 6     9/56   S_pos_Y x T_bearing_r      27.2  .052     0.2   none                  none
  planted 101   7/87   S_pos_Y x T_motor1         31.1  .00085   6.6   2: 4.41->2.69         2: 4.41->2.57 (a)
  clean 0      93/8    lag 7200 s of the inputs   44.6  .023    (8 u)  none                  none
  clean 1      83/8    T_bearing_f2 lag 900 s      6.0  .94     (8 u)  none                  none
  clean 2      93/8    inputs x [A0 > 17.1 °C]    17.2  .082    (8 u)  none                  none
  clean 11      1/609  lag 1800 s of the inputs    5.4  .00045   2.0   1: 0.64->0.69 (+8 %)  none
  clean 101    64/8    inputs x [A0 > 18.8 °C]     6.9  .71     (8 u)  none                  none
  clean 202    39/10   inputs x (A0 - 20 °C)       9.7  .12     -2.4   none                  none
  clean 303    88/8    inputs x [A0 > 9.3 °C]     15.3  .12     (8 u)  none, control clears  same
  clean 515    93/8    T_box2 square               3.3  .35     (8 u)  none                  none
  clean 626    95/8    S_spindle lag 14400 s      17.2  .094    (8 u)  none                  none
  fresh, run once after the rule was fixed:
  planted 737  58/8    S_pos_Y x T_box1           45.2  .41     (8 u)  1 wrong: 6.89->7.16   same (b)
  planted 848   9/63   S_pos_Y x T_box2           47.2  .00005  24.7   2: 4.04->2.57         same
  planted 959   9/60   S_pos_Y x T_bearing_f2     45.3  .00005  16.6   2: 4.23->1.68         2: 4.23->1.61 (a)
  clean 737    96/8    T_amb lag 7200 s           18.6  .086    (8 u)  none                  none
  clean 848    94/8    inputs x [A0 > 22.4 °C]     5.1  .58     (8 u)  none                  none
  clean 959    85/8    T_nose lag 900 s           17.3  .035    (8 u)  none                  none

  (8 u): one block per campaign -- no margin, the shares' p alone (min p 1/256).  The control
  clears on clean 303 under both rules (one block per campaign: its raw p 1/256 <= alpha).
  (a) round 2 takes another effect: 101 a T_motor1 lag from the initial state instead of
  S_spindle x T_motor1 rise (bound 2.5 % < 5 %), 959 a lag of the inputs instead of S_pos_Y raw.
  (b) inputs x (A0 - 20 °C) at family-wise .0039 (8 of 8 campaigns gain, one block each); the
  planted product makes 3 of 8 campaigns worse (-17/-24/-69 %) and is refused: test +4 %.

Counts (shipped -> new).  Tuning (4 planted, 9 clean): planted accepted with the right effect
2/4 -> 2/4; clean accepting nothing 8/9 -> 9/9; control never clearing 12/13 -> 12/13; test
error never > 2 % worse 12/13 -> 13/13.  Fresh (3 + 3): 2/3, 3/3, 6/6, 5/6 under both rules.

Rivals (measured 2026-11-28, the rule of 0d2c048 -> the one-standard-error rule measured from
the best of every refitted candidate of the round, cleared or not: :func:`~thermocomp.apps.
diagnose.search.choose`).  Planted 737 (b): the ambient law (10 regressors) stands in for the
position effect: in CV the product's per-campaign MSE is 6.46 +- 2.07 (mean +- SE over the 8
campaigns), the ambient law's 9.22 (start 20.5), beyond one SE; its test campaigns split 2 better
(K09, K12) and 2 worse (K03 4.79 -> 4.90, K06 5.74 -> 6.73 µm) although all four lie inside the
train ambients (8.1-30.0 °C against 4.5-31.1 °C): a stand-in, not extrapolation.  Now nothing is
accepted there: 6.89 -> 6.89.  Every other case of the table above is unchanged (same effects,
same test RMSE, 303's control as before); tuning + first fresh set: planted right 4/7 -> 4/7,
clean nothing 12/12 -> 12/12, control never clearing 18/19 -> 18/19, test never > 2 % worse
18/19 -> 19/19.  Fresh seeds run once after the rule was fixed, as they came (both rules alike)::

  case          blocks  top (round 1)              gain  p_fam   bound  accepted, E_Y test RMSE
  planted 1070   7/82   S_pos_Y x T_box1           59.0  .00005  26.0   1: 3.32->2.08
  planted 1181   9/55   S_pos_Y x T_box1           50.7  .00005   5.7   2 (+ ambient law): 3.66->1.63
  planted 1292  11/49   S_pos_Y x T_bearing_r      40.8  .0046    9.1   1: 4.74->2.18
  clean 1070    72/8    S_spindle x T_motor1 rise   1.9  .29     (8 u)  none
  clean 1181    54/8    inputs x [A0 > 21.1 °C]     7.3  .91     (8 u)  none
  clean 1292    83/8    T_nose lag 900 s           18.3  .082    (8 u)  none

  Fresh (3 + 3): planted right 3/3, clean nothing 3/3, control never clearing 6/6, test never
  > 2 % worse 6/6, under both rules.

Fresh seeds, run once (2026-11-29, nothing tuned on them), the shipped rule::

  case          blocks  top (round 1)              gain  p_fam   bound  accepted, E_Y test RMSE
  planted 1403  10/58   S_pos_Y x T_box1           39.6  .0068    8.6   2 (+ S_pos_Y raw): 4.29->2.35
  planted 1514  55/8    S_pos_Y x T_nose           53.0  .16     (8 u)  none: 3.78->3.78 (c)
  planted 1625   9/66   S_pos_Y x T_box1           32.7  .0024   11.0   2 (S_pos_Y x T_box2 + ambient
                                                                       interval): 3.60->2.14
  clean 1403    80/8    inputs x (A0 - 20 °C)       4.7  .62     (8 u)  none
  clean 1514    94/8    inputs x [A0 > 27.0 °C]     2.2  .97     (8 u)  none
  clean 1625    95/8    lag 14400 s of the inputs   6.0  .73     (8 u)  none

  (c) the right effect, refused as seed 515: one block per campaign, raw p 5/256 (.020), .16
  family-wise.  Planted right 2/3, clean nothing 3/3, control never clearing 6/6, test never
  > 2 % worse 6/6.

Why not the other rules (measured on the same cases, round 1):

- campaign-level evidence (t or sign flips of the 8 campaigns' gains, raw or as shares): the
  planted effects are not consistent over campaigns either -- 626's accepted effect makes 3 of 8
  campaigns worse (shares -100/-78/-2 %, t 0.8; in MSE t 2.1), 101's 2 of 8 (t 1.7), against
  clean 11's lag at t 1.5 (shares 6 of 8 positive, t 1.8): no level separates them, and a
  campaign t would accept clean 0's lag (8 of 8 campaigns, t 5.6, CV gain 38 %) and clean 303's
  control (8 of 8, t 4.0);
- longer blocks (the integrated autocorrelation time, Geyer's initial positive sequence, instead
  of the first lag at 0.2): clean 11 -> 23-sample blocks (p .049, refused) but planted 0 -> 12
  (p .018, lost; it needs <= 10) -- planted effects pass only with blocks of 7-13 samples and clean
  11 is refused only from ~16, so no block length tied to the residual separates them;
- gain-memory blocks (``bench_diagnose_blocks.py``): worse on both sides;
- the ``1 - alpha`` margin with one block per campaign too (a t bound over 8 campaigns' MSE
  gains): refuses 737's ambient law and 303's control, but also the default scenario's position
  effect (``test_diagnose_scenarios``: nothing accepted for E_Y) -- too strict at campaign level.

The rivals rule's margin on 737 is modest: the ambient law's CV MSE 9.22 against a limit of 8.53
(one SE above the product's 6.46), i.e. 0.33 SE beyond it.

Seed 515 (planted) stays refused under every rule tried (the rivals rule only refuses, it
cannot help it): one of its 8 campaigns loses 37 % with
the right effect, the exact campaign-level p is 2/256 alone and .039 family-wise, a t on the
shares .011 alone; only blocks shorter than the residual's memory (67 samples) reach below .01.
Blocks from the residual or the gain left once a candidate is fitted, campaign-level t and
bootstrap-t, and fresh seeds (planted 4001-4012, clean 4001-4006; shipped rule: 9 of 12
planted right, clean 4004 accepted with the test error +39 %): ``bench_diagnose_memory.py``.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "apps"))

from test_diagnose_few import few  # noqa: E402
from thermocomp.apps.diagnose import SearchOptions, diagnose  # noqa: E402
from thermocomp.core.compensator import Compensator  # noqa: E402
from thermocomp.core.models import MLR  # noqa: E402

TUNING = ["planted:515", "planted:626", "planted:6", "planted:101",
          "clean:0", "clean:1", "clean:2", "clean:11", "clean:101", "clean:202", "clean:303",
          "clean:515", "clean:626"]
FRESH = [f"{kind}:{seed}" for seed in (737, 848, 959, 1070, 1181, 1292) for kind in ("planted", "clean")]


def row(case: str) -> dict:
    kind, seed = case.split(":")
    ds, truth = few("axis_position" if kind == "planted" else None, int(seed))
    d = diagnose(ds, Compensator(MLR()), targets=["E_Y"], options=SearchOptions(max_effects=2))
    j = d.to_json("E_Y")
    first = next(r for r in j["rounds"] if r["step"] == 1)
    fam = [e for e in first["evaluated"] if not e.get("control")]
    top = max(fam, key=lambda e: e["evidence"]["cv_rmse_gain"])
    ev = top["evidence"]
    planted = [e["column"] for e in truth["undeclared_effects"]]
    accepted = [e for e in j["effects"] if e["accepted"]]
    return {"case": case, "blocks": f'{j["cv"]["block_samples"]}/{j["cv"]["test_blocks"]}',
            "top": f'{top["column"]} {top["transform"]}', "gain_pct": ev["cv_rmse_gain_pct"],
            "p_family": ev["p_value_family"],
            "bound_pct": 100 * ev["cv_rmse_gain_lcb_alpha"] / first["cv_rmse"],
            "accepted": [f'{e["kind"]} {e["column"]} {e["transform"]}' for e in accepted],
            "right_effect": bool(accepted) and accepted[0]["column"] in planted,
            "control_clears": j["control_ever_clears_bar"],
            "test_rmse": [j["before"]["test_rmse"], j["after"]["test_rmse"]]}


def main(cases: list[str]) -> None:
    for case in cases:
        print(json.dumps(row(case)), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or TUNING + FRESH)
