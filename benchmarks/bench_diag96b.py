"""diag96's ``data.reference=start_level`` judged with every score in ONE frame (stop 96, diag96b;
REFUSED on clause (3), seen and fresh: src as on main, the rule is ``benchmarks/diag96_rule.patch``,
applied here unchanged -- this branch's ``git diff af5dfe9a -- src tests`` with it was byte-identical
to that file, so no second copy is kept; ``git apply`` it to run ``draws ... start_level``,
``bar`` or ``trace start_level``; issue 34: "diagnose ... never leaves a record's test error more
than 2 % worse").  bench_diag96 REFUSED the rule on its clause (3), 7 of 44 helpful rows losing
> 5 gain points, where each run's gain was read in its own frame (main's against the first
sample, the rule's against the start level: two different targets).  Here both runs' test
predictions, before diagnose and after, are scored against ONE truth.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag96b.py draws ROOT LABEL SET REFERENCE   # -> ROOT/SET-LABEL.jsonl + .npz
    python benchmarks/bench_diag96b.py bar ROOT SET MAIN RULE           # the bar, in the one frame
    python benchmarks/bench_diag96b.py trace REFERENCE CASE:TARGET ...   # a row's rounds, candidates

``draws``: bench_diag96's (bench_diag93b's SET ``seen``: bench_diag92's 70 draws, ``fresh``
9546-9555; MLR on every target, ``max_effects=2``, MLR fitted with ``data.reference=REFERENCE``),
the same jsonl rows, and beside them ``ROOT/SET-LABEL.npz``: per draw, target and test campaign
its time, the error as read (raw), and the before / after predictions in the run's own frame.
``bar`` (run with the rule's src, the patch applied: it reads ``core.frame.start_rows``) scores
MAIN's and RULE's predictions in each frame both ways and applies the bar below to the ONE frame.

The one frame: the first-sample frame, ``nat``
----------------------------------------------
Truth: the error as read less its first valid sample in the test campaign, y(t) - y(t0) -- the
contract's default frame, the machinist's zero, what ``run`` scores with the default, and the frame
in which bench_diag92 counted the 8 harm rows (main's numbers here are its rows unchanged).
Main's predictions are scored as its run scores them.  The rule's predictions p (of y - its start
level) are taken into the frame by the same functional, p(t) - p(t0): the change from t0 the rule
predicts.  Nothing of the test campaign's measured start level enters the rule's score (shifting p
by the measured level difference would make its score its own frame's again, by construction).
Printed beside it, read only: the start-level frame (truth y less its mean over the first
``start_rows``; main's p less the mean of p over the same rows) and ``map`` (both runs'
predictions taken into the frame alike, so an intercept drops out of both).

The rule (diag96's ``benchmarks/diag96_rule.patch``, applied unchanged in this tree)
-----------------------------------------------------------------------------------
``data.reference=start_level``: every ``T_`` / ``E_`` column of a campaign less its mean over the
rows within 900 s of its first row (``core.frame.frame_shift`` / ``start_rows``); opt-in, the
default unchanged; streaming consumers exit 2 (``refuse_stream``).

The bar (the brief's; committed before the fresh seeds 9546-9555 are drawn; all in the one frame)
------------------------------------------------------------------------------------------------
MAIN = af5dfe9a's src with ``first_sample``, RULE = this tree with ``start_level``.  SEEN (70):
(1) rows (draw, target) > 2 % worse after diagnose than before: 8 (main) -> <= 2;
(2) planted position found on >= 27 draws;
(3) no row main helps (main's after < its before) has the rule's after-RMSE > 5 % above main's
    after-RMSE;
(4) clean draws: the rule accepts on no target an effect main does not accept there.
FRESH 9546-9555, scored ONCE after this bar, same clauses: (1) rule's rows > 2 % worse <= 2,
(2) found on no fewer planted draws than main, (3), (4).  Seen gate and fresh both hold: KEPT as
opt-in (src, the patch's 6 tests, docs); else REFUSED (this bench's table kept).
Also reported (no clause): which of bench_diag96's 7 "lost" rows are a frame artefact (the rule's
after within 5 % of main's, or below it, in the one frame) and which a real loss; 9340 E_Y's
position candidate per round under each reference (CV gain, p, family-wise p).

Measured (2026-12-06; MAIN = ``git archive af5dfe9a src``, RULE = af5dfe9a + the patch; nice, 2 cores shared)
------------------------------------------------------------------------------------------------------
``draws``: process CPU seen main 101.3 s, rule 118.2 s; fresh main 16.1 s, rule 17.6 s (about 12 min
wall for the four, run side by side).  The jsonl rows are bench_diag96's to the last digit (all 70
seen draws, both trees).  Main in the one frame equals its rows as run (max |diff| 0.0 µm).

SEEN, ``bar ROOT seen main rule``, the one frame (first-sample, nat):
  (1) rows > 2 % worse than before diagnose 8 -> 1: met (the rule's one: planted 9342 E_X +65.9 %,
      0.7874 -> 1.3059; in its own frame it was 9104 E_X, here 0.6154 -> 0.6085).
  (2) position found 27 -> 30: met (+8969 9048 9265 9440, -9340).
  (3) FAILS: 23 of 44 helpful rows have the rule's after > 5 % above main's after (11 are > 5 %
      below), e.g. 9190 E_Y 1.6027 -> 3.3516, 9340 E_Y 1.8830 -> 3.7003, 9341 E_Y 1.2980 -> 2.6601,
      8457 E_Y 1.8137 -> 3.2030, lag 9268 E_X 0.6631 -> 0.9176, 9046 E_Y 2.3197 -> 3.1367.
  (4) clean draws accepting what main does not: none: met.
  Read only: 14 helpful rows lose > 5 gain points with both gains in this frame (bench_diag96: 7
  in two frames).  Every row, rule / main test RMSE: before diagnose geometric mean x1.004 (70 rows
  > 5 % above, 79 > 5 % below), after x0.987 (71 above, 88 below); in the start-level frame
  x0.948 / x0.932.  The fit's frame alone moves 149 of 210 rows by > 5 % either way before
  diagnose runs: clause (3), row by row against main's after, reads mostly that.  The other
  frames fail (3) too: start-level nat 15 rows, first-sample map 22, start-level map 17.

bench_diag96's 7 "lost" rows, rule / main after in the one frame (start-level nat, first-sample
map, start-level map): 2 are frame artefacts -- 9441 E_Y x0.960 (0.876, 1.004, 0.889), lag 9343
E_X x1.039 (0.886, 0.936, 0.843); 5 are real losses, > 5 % in every frame: 9340 E_Y x1.965 (2.252,
1.907, 2.259), 9103 E_Y x1.399 (1.408, 1.553, 1.647), lag 9268 E_X x1.384 (1.256, 1.405, 1.404),
8457 E_Y x1.766 (1.126, 1.768, 1.054), 9190 E_Y x2.091 (1.085, 1.629, 1.125).  ``trace`` (every
target diagnosed, as ``draws``; E_Y diagnosed alone takes other effects, 9340 E_Y 3.989 -> 1.287):
  9340 E_Y: round 1, 61 test blocks in both; main accepts ``S_pos_Y product(T_box1 over T_amb)``,
    CV gain 43.3 %, p 1.5e-4, family-wise p 0.0054; under start_level the same candidate gains
    36.3 %, p 5.5e-4, family-wise 0.029 > alpha 0.01: not cleared, nothing accepted (the inputs'
    product: 47.9 % p_fam 0.0020 / 43.2 % p_fam 0.0076, cleared in neither).
  9103 E_Y: round 1 the same effect (gain 50.0 / 60.8 %); round 2 main takes a T_motor2 3600 s
    start lag on 8 test blocks (p_fam 0.0039, the 8-unit floor); the rule's round 2 is on 22 blocks
    and nothing clears there.
  lag 9268 E_X: both take a 14400 s start lag in round 1, main T_box1's (gain 62.2 %), the rule
    T_box2's (70.3 %, T_box1's 69.0 %): a pick among near-equal candidates.
  9190 / 8457 E_Y: the SAME effect (T_box1 over T_amb) and nothing more in both trees: the loss is
    the product S_pos_Y x dT fitted against another reference (S x (T - T(t0)) and S x (T - level)
    differ by S(t) x (T(t0) - level), not a constant), 1.09x / 1.13x in the start-level frame.

FRESH 9546-9555 (scored once, after the bar at a301a7f2), ``bar ROOT fresh main rule``, the one frame:
  (1) rows > 2 % worse 1 -> 0: met (main's: clean 9548 E_X +12.7 %, an S_spindle_rpm 14400 s lag).
  (2) found 2 -> 2 (9551, 9552; 9550 in neither): met.  (4) no clean draw accepts anything: met.
  (3) FAILS: 2 of 4 helpful rows, both with the SAME effect accepted in both trees: planted 9551 E_Y
      1.6596 -> 1.7627 (+6.2 %), lag 9553 E_X 0.6608 -> 0.7460 (+12.9 %); their rule's before is
      already above main's (2.8612 / 2.5618, 2.2393 / 1.7516): no helpful row loses > 5 gain points
      in the one frame.  The rule also takes a T_box2 lag on lag 9555 E_X (2.5190 -> 1.3605), where
      main takes nothing (2.5903).  Every row: before x1.054, after x1.001 (12 rows > 5 % above,
      10 below); start-level frame x0.900 / x0.875.

Verdict: **REFUSED** (clause (3), seen 23 rows and fresh 2; (1), (2), (4) met in both).  In the one
frame the rule mends the harm rows (8 -> 1 seen, 1 -> 0 fresh) and finds the position on 30 draws,
but the reference a model is fitted in moves most rows' test error by more than 5 % either way,
before diagnose as after; 5 of the 7 rows bench_diag96 counted are real losses in every frame.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402
from bench_diag91 import _rows, diagnose_cases  # noqa: E402 (the same rows)

FRAMES = ("first_sample", "start_level")
LOST_96 = ("planted:9103 E_Y", "planted:9190 E_Y", "planted:8457 E_Y", "planted:9340 E_Y",
           "planted:9441 E_Y", "lag:9268 E_X", "lag:9343 E_X")   # bench_diag96's clause (3)


def draws(root: str, label: str, name: str, reference: str) -> None:
    """bench_diag96's ``draws``, the test series kept beside the rows (module doc)."""
    from bench_diag92c import _dataset
    from bench_diag93b import SETS

    kept = {}

    def keep(case, ds, d):
        for t in d.targets:
            for c, (_, before) in d.predictions["before"].items():
                df, key = ds.campaigns[c], f"{case}|{t}|{c}"
                kept[f"{key}|time"] = df["time"].to_numpy(float)
                kept[f"{key}|y"] = df[t].to_numpy(float)
                kept[f"{key}|before"] = before[t].to_numpy(float)
                kept[f"{key}|after"] = d.predictions["after"][c][1][t].to_numpy(float)
        np.savez_compressed(Path(root) / f"{name}-{label}.npz", **kept)

    diagnose_cases(root, label, name, SETS[name], _dataset, reference, keep)


def _shift(x: np.ndarray, valid: np.ndarray, time: np.ndarray, frame: str) -> float:
    """What ``frame`` subtracts from series ``x`` of one campaign (``valid``: the error's rows)."""
    from thermocomp.core.frame import start_rows

    if frame == "first_sample":
        return float(x[np.argmax(valid)])
    head = np.arange(len(x)) < start_rows(time)
    return float(np.mean(x[head & valid]))


def _scored(series: dict, ref: str, frame: str, how: str) -> dict:
    """``{(case, target): {"before": rmse, "after": rmse}}``: a run fitted in ``ref`` scored in
    ``frame`` (``nat``: as its run scores it where ``ref`` is ``frame``, else p taken in by the
    frame's functional; ``map``: p always taken in)."""
    res = {}
    for (case, t, c), s in series.items():
        valid = ~np.isnan(s["y"])
        truth = s["y"] - _shift(s["y"], valid, s["time"], frame)
        for when in ("before", "after"):
            p = s[when]
            if how == "map" or ref != frame:
                p = p - _shift(p, valid, s["time"], frame)
            res.setdefault((case, t), {}).setdefault(when, []).append((truth - p)[valid])
    return {k: {w: float(np.sqrt(np.mean(np.concatenate(v) ** 2))) for w, v in d.items()}
            for k, d in res.items()}


def _series(path: Path) -> dict:
    with np.load(path) as z:
        out = {}
        for key in z.files:
            case, t, c, what = key.split("|")
            out.setdefault((case, t, c), {})[what] = z[key]
    return out


def _bar(name: str, rows: dict, main: dict, rule: dict) -> bool:
    """The four clauses on one frame's scores (module doc); prints them, returns whether all hold."""
    worse = {n: [k for k, v in s.items() if v["after"] > 1.02 * v["before"]]
             for n, s in (("main", main), ("rule", rule))}
    found = {n: sorted(c for c, r in rs.items() if r["found"]) for n, rs in rows.items()}
    helpful = [k for k, v in main.items() if v["after"] < v["before"]]
    above = [k for k in helpful if rule[k]["after"] > 1.05 * main[k]["after"]]
    below = [k for k in helpful if rule[k]["after"] < main[k]["after"] / 1.05]
    clean = [(c, t) for c, r in rows["rule"].items() if c.startswith("clean:")
             for t, v in r["targets"].items()
             if set(v["accepted"]) - set(rows["main"][c]["targets"][t]["accepted"])]
    for n, s in (("main", main), ("rule", rule)):
        print(f"  {n} rows > 2 % worse: {len(worse[n])}: " + ", ".join(
            f"{c} {t} {100 * (s[c, t]['after'] / s[c, t]['before'] - 1):+.1f} %" for c, t in worse[n]))
    print(f"  helpful rows (main after < before): {len(helpful)}; rule's after > 1.05 main's: "
          + ", ".join(f"{c} {t} {main[c, t]['after']:.4f} -> {rule[c, t]['after']:.4f}"
                      for c, t in above))
    print(f"  (helpful rows where the rule's after is > 5 % BELOW main's: {len(below)})")
    gain = {n: {k: 100 * (v["after"] / v["before"] - 1) for k, v in s.items()}
            for n, s in (("main", main), ("rule", rule))}
    points = [k for k in helpful if gain["rule"][k] - gain["main"][k] > 5.0]
    print(f"  (read only: helpful rows losing > 5 gain points, both gains in this frame: {len(points)}: "
          + ", ".join(f"{c} {t} {gain['main'][c, t]:+.1f} -> {gain['rule'][c, t]:+.1f} %" for c, t in points)
          + ")")
    need = 27 if name == "seen" else len(found["main"])
    ok = [len(worse["rule"]) <= 2, len(found["rule"]) >= need, not above, not clean]
    print(f"  (1) rows > 2 % worse {len(worse['main'])} -> {len(worse['rule'])} (<= 2): {_met(ok[0])}")
    print(f"  (2) found {len(found['main'])} -> {len(found['rule'])} (>= {need}): {_met(ok[1])}; "
          f"gained {sorted(set(found['rule']) - set(found['main']))}, "
          f"lost {sorted(set(found['main']) - set(found['rule']))}")
    print(f"  (3) helpful rows > 5 % above main's after: {len(above)}: {_met(ok[2])}")
    print(f"  (4) clean rows accepting what main does not: {clean}: {_met(ok[3])}")
    return all(ok)


def _met(ok: bool) -> str:
    return "met" if ok else "FAILS"


def bar(root: str, name: str, main: str, rule: str) -> None:
    """The bar in the one frame, and every row in both frames both ways (module doc)."""
    rows = {"main": _rows(Path(root) / f"{name}-{main}.jsonl"),
            "rule": _rows(Path(root) / f"{name}-{rule}.jsonl")}
    series = {"main": _series(Path(root) / f"{name}-{main}.npz"),
              "rule": _series(Path(root) / f"{name}-{rule}.npz")}
    refs = {"main": "first_sample", "rule": "start_level"}
    scores = {(n, f, h): _scored(series[n], refs[n], f, h)
              for n in refs for f in FRAMES for h in ("nat", "map")}
    as_run = max(abs(v["after"] - rows["main"][c]["targets"][t]["after"])
                 for (c, t), v in scores["main", "first_sample", "nat"].items())
    print(f"main in the one frame vs its rows as run: max |after diff| {as_run:.2e} µm")
    print("row: before -> after (µm) main | rule; first-sample nat (THE frame) ; start-level nat ; "
          "first-sample map")
    for k in sorted(scores["main", "first_sample", "nat"]):
        cells = []
        for f, h in (("first_sample", "nat"), ("start_level", "nat"), ("first_sample", "map")):
            a, b = scores["main", f, h][k], scores["rule", f, h][k]
            cells.append(f"{a['before']:.4f}->{a['after']:.4f} | {b['before']:.4f}->{b['after']:.4f}")
        print(f"  {k[0]:>13} {k[1]}: " + " ; ".join(cells) + (" LOST96" if " ".join(k) in LOST_96 else ""))
    one = {n: scores[n, "first_sample", "nat"] for n in refs}
    print("bench_diag96's 7 lost rows in the one frame: after main -> rule (ratio), verdict; the "
          "ratio in the other frames / ways (start-level nat, first-sample map, start-level map)")
    for key in LOST_96:
        k = tuple(key.split(" "))
        if k in one["main"]:
            a, b = one["main"][k]["after"], one["rule"][k]["after"]
            other = [scores["rule", f, h][k]["after"] / scores["main", f, h][k]["after"]
                     for f, h in (("start_level", "nat"), ("first_sample", "map"), ("start_level", "map"))]
            print(f"  {key}: {a:.4f} -> {b:.4f} (x{b / a:.3f}) "
                  f"{'frame artefact' if b <= 1.05 * a else 'REAL loss'}; "
                  + " / ".join(f"x{r:.3f}" for r in other))
    for f, h in (("first_sample", "nat"), ("start_level", "nat"), ("first_sample", "map"),
                 ("start_level", "map")):
        r = {w: np.array([scores["rule", f, h][k][w] / v[w] for k, v in scores["main", f, h].items()])
             for w in ("before", "after")}
        print(f"  rule / main over every row, {f} {h}: " + "; ".join(
            f"{w} geometric mean x{np.exp(np.mean(np.log(x))):.3f}, > 5 % above {np.sum(x > 1.05)}, "
            f"> 5 % below {np.sum(x < 1 / 1.05)}" for w, x in r.items()))
    for case in ("planted:9340",):
        for n in refs:
            if case in rows[n]:
                print(f"  {case} E_Y position by round, {n}: {rows[n][case]['targets']['E_Y']['position']}"
                      f"; accepted {rows[n][case]['targets']['E_Y']['accepted']}")
    for f, h in (("first_sample", "nat"), ("start_level", "nat"), ("first_sample", "map"),
                 ("start_level", "map")):
        the = " (THE ONE FRAME: the bar)" if (f, h) == ("first_sample", "nat") else ""
        print(f"== {name}, {f} frame, {h}{the}")
        holds = _bar(name, rows, scores["main", f, h], scores["rule", f, h])
        print(f"  bar in this frame: {'HOLDS' if holds else 'FAILS'}")


def trace(reference: str, *rows: str) -> None:
    """Each row's rounds in ``reference`` (module doc)."""
    from bench_diag86 import draw

    from thermocomp.apps.diagnose import SearchOptions, diagnose
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.models import MLR

    for row in rows:
        kind, seed, target = row.split(":")
        d = diagnose(draw(kind, int(seed), 12), Compensator(MLR(), reference=reference),
                     options=SearchOptions(max_effects=2))   # every target, as ``draws``
        j = d.to_json(target)
        print(f"== {row} ({reference}): test {j['before']['test_rmse']:.4f} -> "
              f"{j['after']['test_rmse']:.4f}")
        for r in d.targets[target].search.rounds:
            print(f"  round {r.step}: {r.test_blocks} test blocks, CV {r.cv_rmse:.4f}, accepted "
                  f"{r.accepted.effect.title if r.accepted else None}")
            pos = [ev for ev in r.evaluated if "S_pos_Y" in f"{ev.effect.column} {ev.effect.other}"]
            top = sorted(r.evaluated, key=lambda e: -e.gain)[:5]
            for ev in pos + [ev for ev in top if ev not in pos]:
                within = [f"{v:.1f}" if v is not None else "-" for v in (ev.gain_pct_within,
                                                                           ev.gain_pct_within_rest)]
                print(f"    {ev.effect.title[:60]:60} gain {ev.gain_pct:5.1f} % p {ev.p_value:.2g} "
                      f"p_fam {ev.p_family if ev.p_family is None else f'{ev.p_family:.2g}'} "
                      f"p_margin {ev.p_margin:.2g} in range {ev.gain_pct_in_range:.1f} within / "
                      f"less best {within[0]} / {within[1]} k {ev.n_features} "
                      f"clears {ev.clears_bar} accepted {ev.accepted}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"draws": draws, "bar": bar, "trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
