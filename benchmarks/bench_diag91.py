"""Diagnose's acceptance test on blocks as long as the candidates' GAINS take to decorrelate, not
the residual (stop 91, diag91; issue 34: "diagnose accepts a planted position effect with 8 train
campaigns, accepts nothing on clean data, and never leaves a record's test error more than 2 %
worse"; bench_diag89b's cause A).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag91.py draws ROOT LABEL SET   # SET's draws -> ROOT/SET-LABEL.jsonl
    python benchmarks/bench_diag91.py compare ROOT SET A B   # two labels' rows of SET: the bar's counts
    python benchmarks/bench_diag91.py record ROOT            # the measured record cut 90/10, every channel

``draws``: every draw of ``SET`` (:data:`SETS`: ``trace`` the six rows the brief names, ``seen``
bench_diag89b's 23 planted draws, bench_diag88's seen draws and the seen clean / lag draws,
``fresh`` the unspent seeds 9336-9345 with bench_diag88d's generators; bench_diag86's ``draw``,
12 campaigns, every 3rd test, 8 train) diagnosed with MLR on every target, ``max_effects=2``, test
figures as run (bench_diag89b's ``halved``), per target each round's test blocks, the position
candidate's own and family-wise p on E_Y, the smallest p the round's blocks can reach, what was
accepted and whether the control ever clears.  ``compare``: per label the planted draws found,
the clean draws accepting anything, the controls clearing; then every (draw, target) whose after
differs, with the change against A.  ``record``: tests/apps/test_diagnose_record.py's record (the
vendored fl_thermal spindle record cut 90/10, MLR, ``reference=none``, forward chaining, shipped
options) diagnosed on every channel: per channel its rounds' test blocks (and samples), before ->
after and what was accepted.  The rule is not in src (refused, below): ``git apply
benchmarks/diag91_rule.patch`` in a scratch copy to measure it.

The rule (``Search._recut_on_gains``; the diff against main in ``diag91_rule.patch`` if refused)
-----------------------------------------------------------------------------------------------
Each round, once the shortlist is refitted, the test blocks are re-cut as long as the candidates'
per-sample GAIN ``e^2 - e_+^2`` (the current CV residual squared less the candidate's) takes to
decorrelate (:func:`~thermocomp.core.model_selection.blocks.decorrelation_length`, the same
estimator as the residual's), the longest over the round's family (one max-T null over the same
blocks), where that is shorter than the residual's blocks (never fewer blocks than main); the
current and every candidate's CV result are re-scored on them (no refit) and each candidate's own
p, margin p and bounds read again.  Why: a sign-flip test needs its units' GAINS near-independent
under the null; the residual that still holds the effect being tested forgets slowly (cause A:
one block per campaign, the family-wise floor), while under the null the gain ``2 e d - d^2`` (d
the candidate's fitted change) forgets as the product of the two memories, faster than either.
History (read before designing): stop 41's ``fix/blocks`` (bench_diagnose_blocks.py) sized blocks
by the gain's memory and clean seeds accepted harmful effects (626 +81 %, 303 +6 %); that was
before the within / within-rest / margin / saturation checks, which this rule keeps unchanged.

The bar (the brief's; written here after the ``trace`` rows below were first run -- said plainly:
they are the brief's seen rows, for looking -- and before any run of either tree on the fresh
seeds; all must hold, else REFUSED: src reverted, this bench and ``diag91_rule.patch`` kept):

1. FRESH 9336-9345 (bench_diag88d's generators: clean 9336-9339, planted 9340-9342, lag
   9343-9345; 12 campaigns, 8 train): no (draw, target) row more than 2 % worse than main.
2. FRESH clean 9336-9339 accept nothing on any target; no control clears.
3. FRESH planted: the position found wherever main finds it.
4. SEEN rows (``seen``: bench_diag89b's 23 planted draws with ``trace``'s, bench_diag88's seen
   draws and cases, the seen clean and lag draws; bench_diag88's ``seen`` rows -- the grinders,
   planted:6 / 959 -- and bench_diagnose_faults58's climate_room rows where time allows): the
   position found on more draws than main, no row more than 2 % worse than main, no seen clean
   draw accepting what main does not.
5. tests/*/test_diag*.py pass (in parts, ``-n 2``).

Scored (2026-12-05, 2 cores shared by seven helpers; main = 277a181d's src (``git archive`` under
/tmp/diag91/main), rule = 88bbc85c's src; each command once per tree, main after the rule)
------------------------------------------------------------------------------------------
Test RMSE (µm, as run), before -> after; every (draw, target) row where main and the rule differ.

``trace`` (the brief's six rows; seen)::

  row             before  main                   rule
  planted:8966 E_Y 3.7935 nothing (9 blocks)     1.6397 position (45 blocks; p_fam 1e-4)  -56.8 %
  planted:8968 E_Y 4.9939 nothing (9 blocks)     2.3810 position (17 blocks; p_fam 1e-4)  -52.3 %
  lag:9288 E_X     1.1694 nothing (12 blocks)    0.8135 T_box2 14400 s +init (19)         -30.4 %
  lag:9289 E_X     2.1815 nothing (10 blocks)    1.0737 T_box1 14400 s +init (30)         -50.8 %
  planted:8969 / 8885: identical (8969's round 1 stays at 8 blocks: a family member's gain
  forgets no faster than the residual; its position p 2/256, p_fam 3/256, still missed; 8885 keeps
  both its effects, round 2 on 13 blocks, not 8).

Smallest p each row's round-1 design reaches (``min_p``: 1/2^n exact up to 16 blocks, 1/20001
beyond), main -> rule: 8966 E_Y 1/512 -> 1/20001 (45 blocks); 8968 E_Y 1/512 -> 1/20001 (17);
9288 E_X 1/4096 -> 1/20001 (19); 9289 E_X 1/1024 -> 1/20001 (30); 8969 E_Y 1/256 in both (8);
8885 E_Y 1/8192 in both (13).  The position's own p on the rule: 5e-5 (8966, 8968), family-wise
1e-4.

``seen`` (44 draws, 132 rows): position found on 19 draws in both trees (+ ``trace``'s 8966 /
8968: 20 -> 22 over the seen draws); clean draws accept what main accepts (8075 / 8170 / 8178's
spurious start lags, bench_diag88's); no control clears in either; three rows differ::

  planted:9266 E_X 0.6664 nothing (8 blocks)  -> 0.6764 T_nose 14400 s +init (14, 205)  +1.5 %
  clean:8075 E_Y   0.7010 T_box1 3600 s +init -> 0.6998 T_box2 3600 s +init             -0.2 %
  lag:9193 E_X     0.9167 T_box2 14400 s      -> 0.7684 T_box1 14400 s                  -16.2 %

bench_diag88's ``seen`` (cases 8457 / 8178 / 8075 / 8170 / 8885, real planted:6 / 959, grinders
5687 / 5682, draws 9046 / 9103 / 8980 / 9150): identical but 8075 E_Y (-0.2 %, above).
bench_diagnose_faults58's climate_room drift / stuck / contact: identical JSON lines.
CPU (``seen``, diagnose only): 32.0 s main, 32.9 s rule.

``fresh`` (9336-9345, once, after the bar above): position found on 9340-9342 in both; clean
9336-9339 accept nothing in both (their blocks finer on the rule: 9339 E_Y 8 -> 53, E_Z 8 -> 35,
nothing taken); the control clears on lag:9343 E_Z in BOTH trees (main's own, not the rule's);
one row differs: planted:9341 E_Y 1.2988 -> 1.2980 (-0.1 %, a 7200 s spindle lag added in round
2 on 26 blocks, not 8).  The start lags of 9343-9345 are taken in both trees (0.610 / 0.805 /
0.866).  CPU 7.4 s main, 7.3 s rule.

Bar: 1 holds (0 rows > 2 %); 2 holds on the clean draws (nothing accepted; no control clears
there -- lag:9343 E_Z's control clears in both trees); 3 holds (3 of 3 in both); 4 holds (found
20 -> 22, worst row +1.5 %).  **5 fails**: 2 of 136 tests in the 24 diagnose files (three parts,
``-n 2``; the other 134 pass, the rule's two new tests among them):

- ``test_diagnose_record.py::test_diagnose_never_makes_the_measured_record_worse``: the measured
  record (``record``)::

    channel  main: round-1 blocks, after      rule: round blocks (samples), after, taken
    E_ch1    12 (403)  4.6016 nothing         14 (356)  4.6016 nothing
    E_ch2    12 (389)  3.9533 nothing         13 (367), 34 (146)  1.8772 the inputs' rises x a state
    E_ch3     6 (715)  4.3425 nothing         14 (342), 14 (344)  4.5449 (+4.7 %) 3600 s lag of the
                                              inputs, CV gain 59.0 %, p_fam 0.0061, margin p 0.0007
    E_ch4     7 (686)  4.3244 nothing         13 (365), 13 (374)  5.4407 (+25.8 %) the same lag,
                                              60.3 %, p_fam 0.0078, margin p 0.0015
    E_ch5    19 (251)  3.0405 nothing         19 (251)  3.0405 nothing

  the very harm blocks.py records (16 forward validation blocks tested as units passed a lag that
  made ch3 / ch4 33 % / 38 % worse): in forward chaining the gains forget in half the residual's
  time, the units are halved, and the same lag passes.  (The warning that E_ch3's 6 blocks
  cannot reach alpha also goes stale under the rule: it is printed from the starting design.)
- ``test_diagnose_few.py::test_a_candidate_that_can_match_every_training_campaign_is_not_accepted_
  on_campaign_blocks`` (clean seed 4004, E_Y): nothing is accepted on either tree, but round 1 is
  no longer on the campaign blocks (8 of 70 samples -> 13 of 37): the 12-regressor start lag that
  fits the campaigns' offsets reaches p_fam 0.0015 (main 0.0039) and is kept out by saturation
  only; the spindle's one-regressor lag's p_fam goes 0.0039 -> 0.0101, so the test's one-regressor
  clause is left empty.  A residual of campaign offsets: the gains of a candidate matching them are
  one number per campaign, yet their autocorrelation falls under 0.2 within half a campaign.

**REFUSED** (item 5; the record's E_ch3 +4.7 % / E_ch4 +25.8 % is the issue's "never more than
2 % worse" on the one measured record diagnose is tested on).  src and docs reverted to
277a181d's; the rule (``Search._recut_on_gains``, ``Search._block_evidence`` split out of
``_evaluate``, docstrings) in ``diag91_rule.patch``; its two tests (8966 E_Y alone: 3.793 ->
1.640, round 1 on 45 blocks; lag:9289 every target: E_X 2.182 -> 1.074 on 30 blocks; both fail on
277a181d) dropped with it.  Also seen, not a bar item: lag:9289 E_X diagnosed ALONE takes the
all-inputs start lag in round 1 on the rule, and round 2's control (random walk, CV gain 33 %)
clears at p 1/1024 on the residual's 10 blocks as on the gains' 12 (1/4096): main never reaches
that round (nothing taken in round 1).

What the numbers say: on the year-round VMC with 8 campaigns the gains' blocks do what the brief
hoped (cause A's 8966 / 8968 found, the two short start lags taken, nothing worse than 1.5 %); on
the measured spindle record in forward chaining, and on a clean draw whose residual is campaign
offsets, the gain's autocorrelation at 0.2 understates what its units share (a slow lag's gain,
an offset's gain), which the residual's length had held.  Next (not scored here; it needs
unspent seeds): the same rule in the ``campaigns`` scheme only (forward validation blocks already
share test blocks by the residual's length: the record would stay as main), with the gain's
length read where its autocorrelation reaches 0.2 AND its campaign-level share (the variance of
the campaigns' mean gains against the gain's variance) is small -- the 4004 case.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import made_folder, run_commands  # noqa: E402

# (kind, seed): 12 campaigns, every 3rd test, so 8 train
SETS = {
    "trace": [("planted", 8966), ("planted", 8968), ("planted", 8969), ("planted", 8885),
              ("lag", 9288), ("lag", 9289)],
    # bench_diag89b's SEEN planted draws (its cause-A three are in ``trace``), bench_diag88's
    # SEEN_DRAWS and cases (8457 / 8178 / 8075 / 8170), the clean and lag draws of bench_diag88 /
    # 88d / 89 (9186-9189, 9261-9264, 9281-9284; 9193-9195, 9268-9270, 9290) and lag:8980
    "seen": ([("planted", s) for s in (8967, *range(9046, 9050), *range(9101, 9105), 9150,
                                       *range(9190, 9193), 9231, 9232, 9256, 9257,
                                       *range(9265, 9268), 8457)]
             + [("clean", s) for s in (8075, 8170, 8178, *range(9186, 9190), *range(9261, 9265),
                                       *range(9281, 9285))]
             + [("lag", s) for s in (8980, *range(9193, 9196), *range(9268, 9271), 9290)]),
    "fresh": ([("clean", s) for s in range(9336, 9340)] + [("planted", s) for s in range(9340, 9343)]
              + [("lag", s) for s in range(9343, 9346)]),
}


def _position(rnd) -> dict | None:
    """E_Y's best position candidate of a round (an interaction on S_pos_Y): its evidence."""
    pos = [ev for ev in rnd.evaluated if ev.effect.kind == "interaction"
           and "S_pos_Y" in f"{ev.effect.column} {ev.effect.other}"]
    if not pos:
        return None
    ev = max(pos, key=lambda e: e.gain)
    return {"gain_pct": round(ev.gain_pct, 1), "p": ev.p_value, "p_fam": ev.p_family,
            "p_margin": ev.p_margin, "clears": bool(ev.clears_bar)}


def _draw(kind: str, seed: int):
    """bench_diag86's draw with 12 campaigns, every target diagnosed."""
    from bench_diag86 import draw
    return draw(kind, seed, 12), None


def draws(root: str, label: str, name: str) -> None:
    """:data:`SETS` ``name`` diagnosed (module doc) -> ``ROOT/NAME-LABEL.jsonl``."""
    diagnose_cases(root, label, name, SETS[name], _draw)


def diagnose_cases(root: str, label: str, name: str, cases, dataset,
                   reference: str = "first_sample", keep=None) -> None:
    """``cases`` ((kind, seed) pairs) diagnosed -> ``ROOT/NAME-LABEL.jsonl``; ``dataset(kind,
    seed)`` gives the draw and the targets diagnosed (None: every one); MLR fitted with
    ``data.reference=reference``; ``keep(case, ds, diagnosis)``, if given, is called on each."""
    from cpu import cpu_seconds

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.apps.diagnose.cv import smallest_p
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    with open(made_folder(root) / f"{name}-{label}.jsonl", "w") as out:
        for kind, seed in cases:
            ds, targets = dataset(kind, seed)
            t0 = cpu_seconds()
            d = diagnose(ds, Compensator(MLR(), reference=reference), targets=targets,
                         options=SearchOptions(max_effects=2))
            row = {"case": f"{kind}:{seed}", "cpu_s": round(cpu_seconds() - t0, 1), "targets": {}}
            for t, x in d.targets.items():
                j = d.to_json(t)
                rounds = x.search.rounds
                row["targets"][t] = {
                    "before": j["before"]["test_rmse"], "after": j["after"]["test_rmse"],
                    "accepted": [e.effect.title for e in x.accepted],
                    "blocks": [r.test_blocks for r in rounds],
                    "min_p": [smallest_p(r.test_blocks) for r in rounds],
                    "control": bool(j["control_ever_clears_bar"]),
                    "position": [_position(r) for r in rounds] if t == "E_Y" else None}
            row["found"] = any(a.startswith("interaction:S_pos_Y")
                               for a in row["targets"]["E_Y"]["accepted"])
            print(json.dumps(row, ensure_ascii=False, default=float), file=out, flush=True)
            if keep is not None:
                keep(row["case"], ds, d)
            print(f"  {row['case']} {label} ({row['cpu_s']} s): found {row['found']}; " + " | ".join(
                f"{t} {v['blocks']} {v['before']:.3f} -> {v['after']:.3f} "
                f"{[a[:40] for a in v['accepted']]}{' CONTROL' if v['control'] else ''}"
                for t, v in row["targets"].items()), flush=True)
            if row["targets"]["E_Y"]["position"]:
                print(f"    E_Y position by round: {row['targets']['E_Y']['position']}", flush=True)


def _rows(path: Path) -> dict:
    with open(path) as f:
        return {r["case"]: r for r in map(json.loads, f)}


def compare(root: str, name: str, a: str, b: str) -> None:
    """The bar's counts of labels ``a`` and ``b`` on set ``name``, then the rows that differ."""
    rows = {n: _rows(Path(root) / f"{name}-{n}.jsonl") for n in (a, b)}
    for n, rs in rows.items():
        found = sorted(c for c, r in rs.items() if r["found"])
        clean = [c for c, r in rs.items()
                 if c.startswith("clean:") and any(v["accepted"] for v in r["targets"].values())]
        control = [f"{c} {t}" for c, r in rs.items() for t, v in r["targets"].items() if v["control"]]
        print(f"{n}: position found on {len(found)} {found}; clean accepting {clean}; control clears "
              f"{control}; diagnose CPU {sum(r['cpu_s'] for r in rs.values()):.1f} s")
    worse = 0
    for c, r in rows[a].items():
        for t, v in r["targets"].items():
            w = rows[b][c]["targets"][t]
            if (v["accepted"], v["after"]) != (w["accepted"], w["after"]):
                change = 100 * (w["after"] / v["after"] - 1)
                worse += change > 2.0
                print(f"  {c} {t}: before {v['before']:.4f}; {a} {v['after']:.4f} {v['blocks']} "
                      f"{[x[:44] for x in v['accepted']]} | {b} {w['after']:.4f} {w['blocks']} "
                      f"{[x[:44] for x in w['accepted']]} ({change:+.1f} %)")
    print(f"rows more than 2 % worse in {b} than in {a}: {worse}")


def record(root: str) -> None:
    """The measured record cut 90/10 (tests/apps/test_diagnose_record.py), every channel."""
    from test_diagnose_record import record_cut
    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    ds = record_cut(made_folder(root) / "fl_9010")
    d = diagnose(ds, Compensator(MLR(), reference="none"), options=SearchOptions())
    for t in d.targets:
        j = d.to_json(t)
        taken = [(e["transform"][:50], round(e["evidence"]["cv_rmse_gain_pct"], 1),
                  e["evidence"].get("p_value_family")) for e in j["effects"] if e["accepted"]]
        print(f"  {t}: {j['cv']['units']} units, rounds' blocks "
              f"{[(r['test_blocks'], r['block_samples']) for r in j['rounds'] if r['step'] > 0]}, "
              f"{j['before']['test_rmse']:.4f} -> {j['after']['test_rmse']:.4f} {taken}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"draws": draws, "compare": compare, "record": record}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
