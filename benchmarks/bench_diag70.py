"""diagnose judged where it had not been (issue 34 item 4; stop 70, diag70): the default scenario
(``make run``'s record) and the measured ``fl_thermal`` record, ``thermocomp diagnose`` with its
defaults.  No rule is tried here: this measures the shipped code (moretest68's instrument did not
draw these rows: ``scenario`` was left, ``record`` cannot be drawn again).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag70.py scenario WORK      # -> WORK/scenario.jsonl
    python benchmarks/bench_diag70.py record WORK [SPLIT ...]  # -> WORK/record.jsonl
    python benchmarks/bench_diag70.py table WORK         # both, the verdicts

Every diagnosis is the ``diagnose`` stage itself (``thermocomp diagnose``'s code, its config
composed with the defaults, ``track=false``, ``out`` under WORK), so before / after are its
deployed test figures; the bench only appends test campaigns to what the stage reads and keeps
the diagnosis it returns.

``scenario``: ``thermocomp simulate`` (defaults: ``sim=yearround_spindle``, 24 campaigns, 8 test)
with ``seed=0`` (``make run``'s record: conf/common.yaml) and fresh seeds 7111, 7112, written to
WORK/records; each diagnosed with the defaults (every target, MLR, ``diagnose.cv=auto``).  Each is
scored on its own 8 test campaigns AND on 128 NEW campaigns of the same machine: the test
campaigns of ``sim=yearround_spindle`` drawn with seeds 7115-7130 (bench_automore69's
``_simulated``: the twin's machine does not depend on the seed, its programmes, calendar,
weather and noise do), appended after the record's own as test campaigns (bench_moretest68's
``with_new``; the train split is the record's, so the search and the fitted models are the
record's own: checked, the own-test figures equal the diagnosis without them).  Every record's
models meet the same 128 new campaigns.  Per target: test RMSE uncompensated (measured) / MLR
(before) / diagnosed (after) on the own test, before -> after on the new campaigns with the 90 %
interval of the change when the new campaigns are resampled (bench_moretest68's ``resampled``,
2000 draws), and per draw (seed) the change.

``record``: ``data=fl_thermal`` (90/10: the last 10 % one test campaign continuing the rest) and
its authors' split (``data.split_order=[train,test,val] data.test_fraction=0.2
data.val_fraction=0.2``: the middle 20 % is the test; diagnose ignores the ``val`` part), with the
defaults; per channel test RMSE and MAE before -> after, the accepted effects, the test part's
rows and campaigns.  ``model=auto`` is tried as the stage takes it (docs/diagnose.md: refused,
exit 2, before any search).  No new campaigns of that spindle exist: judged on its test part
alone.

What counts as a failure (written before anything here was run or scored)
-------------------------------------------------------------------------
The issue's criterion: ``diagnose`` "accepts nothing on clean data, and never leaves a record's
test error more than 2 % worse".

Scenario (3 records x 3 targets = 9 rows):

* F1 own: a row whose diagnosed test RMSE on the record's own 8 test campaigns is > 2 % above
  MLR's (before) -- the criterion as the issue words it.
* F2 new: a row > 2 % worse on the 128 new campaigns with the 90 % resampled interval of the
  change above +2 % -- a real harm (moretest68's count).  A row > 2 % worse on one but not the
  other is reported with both figures; the new campaigns decide whether the harm is the effect's
  or the own test draw's.
* F3 clean: the scenario plants no undeclared effect (``sim.generator.effects=[]``), but its
  errors are the twin's thermal physics, which MLR's static law of the sensors does not hold
  exactly, so an effect of that physics may be real.  An accepted effect is a FALSE acceptance
  (failure) unless its row is better by > 2 % on the new campaigns with the interval below -2 %.
* F4 control: the random-walk control clearing the bar in any round of any row.

Record (``fl_thermal``, 5 channels x 2 splits = 10 rows):

* F5: a channel's test RMSE after > 1.02 x before on either split (one test campaign: no interval
  can be given; MAE is reported beside it, not part of the verdict).

Any failure is traced (which candidate, its CV gain in the held-out units' means vs within them,
as bench_jig68 / bench_clean69 did) and reported; a rule only with its bar committed first.

Measured (2026-12-02, stop 70, main 547d6bb9's src; 2 shared cores, load 7-14; CPU user + sys)
--------------------------------------------------------------------------------------------
Scenario (``scenario``; 57.6 s with the three records simulated and the 16 draws, 8.8 s of them):
16 train campaigns, the campaigns scheme, 16 test blocks (min p 1.5e-5).  Test RMSE µm, MLR ->
diagnosed, own 8 test campaigns | 128 new, the change's 90 % interval (%)::

  seed  target  accepted                          own: MLR -> diagnosed | new: MLR -> diagnosed [90 %]
  0     E_X     nothing                           0.7504                | 0.6794
  0     E_Y     T_motor1 2 h lag +init (2 dir.)   1.4235 -> 1.0628      | 1.3462 -> 1.0163 [-29.5, -19.4]
  0     E_Z     inputs x (A0 - 20)                5.8019 -> 0.9403      | 5.3558 -> 1.0251 [-82.5, -79.0]
  7111  E_X     nothing                           0.6151                | 0.6960
  7111  E_Y     inputs' 4 h lag +init;            1.6893 -> 1.5119      | 1.3627 -> 1.0975 [-25.8, -12.9]
                T_bearing_r 1 h lag +init
  7111  E_Z     inputs x (A0 - 20)                6.4131 -> 0.8710      | 5.3353 -> 0.9648 [-83.4, -80.4]
  7112  E_X     nothing                           0.7531                | 0.6981
  7112  E_Y     inputs x [A0 > 18.02]             1.8908 -> 1.5437      | 1.4816 -> 1.0896 [-30.1, -22.4]
  7112  E_Z     inputs x (A0 - 20)                6.1400 -> 1.0521      | 5.0007 -> 0.9525 [-82.4, -79.3]

failures: none (F1-F4).  Every accepted effect's interval lies below -2 %; the control never clears.

Record (``record``; the defaults 17.5 s with the refused ``model=auto``): 90/10, 1,112 test rows,
forward chaining, 6 test blocks (min p 0.016 > alpha): nothing can be accepted, nothing is.
60/20/20, 2,223 test rows, 10 blocks: ch1, ch2 take S_spindle's 1 h lag, RMSE 9.53 -> 3.79 and
7.77 -> 2.94 (MAE 9.21 -> 3.61, 7.59 -> 2.80), ch3-ch5 nothing.  F5: none.  ``model=auto``:
refused, exit 2.  Informative (not under F5): 90/10 with ``diagnose.cv=campaigns`` takes the
inputs' lags on all five, each better (mean RMSE 4.06 -> 3.25; 15.3 s); the families auto kept on
60/20/20: lagbank ch1 1.49 -> 0.85, ch2 / ch3 nothing, arx ch5 nothing, hammerstein ch4 excludes
T_t5 as a sensor fault, 1.84 -> 5.41 (+194 %; 120 s for the three).  Traced (``record WORK/trace
...``, 262 s): hammerstein on all five excludes T_t5 too, ch1-ch4 +7.7 / +8.4 / +21.5 / +194 %;
MLR at the defaults keeps it only because ch5's CV is 9.2 % worse without it (MLR on ch4 alone
excludes it, +1.0 %); hammerstein on ch4 without the sensor_fault family accepts nothing.
"""

from __future__ import annotations

import contextlib
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import made_folder, run_commands  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

RECORD_SEEDS = (0, 7111, 7112)          # make run's (seed 0) and two fresh
NEW_SEEDS = tuple(range(7115, 7131))    # 16 draws x 8 test campaigns
SPLITS = {"90/10": ["data=fl_thermal"],
          "60/20/20": ["data=fl_thermal", "data.split_order=[train,test,val]",
                       "data.test_fraction=0.2", "data.val_fraction=0.2"],
          # added after the two above were scored: what the 90/10 cut's warning suggests (its 6
          # forward test blocks cannot reach alpha); informative, not under F5
          "90/10 cv=campaigns": ["data=fl_thermal", "diagnose.cv=campaigns"],
          # model=auto refused: the family auto kept per channel on 60/20/20 (docs/own-data.md:
          # lagbank, lagbank, lagbank, hammerstein, arx), each diagnosed on its channels
          **{f"60/20/20 {family}": ["data=fl_thermal", "data.split_order=[train,test,val]",
                                    "data.test_fraction=0.2", "data.val_fraction=0.2",
                                    f"model={family}", f"diagnose.targets=[{targets}]"]
             for family, targets in (("lagbank", "E_ch1,E_ch2,E_ch3"), ("hammerstein", "E_ch4"),
                                     ("arx", "E_ch5"))}}
# the trace of the one row > 2 % worse (hammerstein's E_ch4 above, T_t5 removed as a fault),
# added after it was scored: MLR on E_ch4 alone, hammerstein without the fault family, with all
# five channels
NO_FAULT = "diagnose.families=[signal,dynamics,ambient_interval,interaction,nonlinear]"
SPLITS |= {f"60/20/20 {name}": [*SPLITS["60/20/20"], *extra] for name, extra in (
    ("mlr E_ch4", ["diagnose.targets=[E_ch4]"]),
    ("hammerstein E_ch4 no fault family", ["model=hammerstein", "diagnose.targets=[E_ch4]", NO_FAULT]),
    ("hammerstein all", ["model=hammerstein"]))}
VERDICT = ("90/10", "60/20/20")          # the defaults: F5's rows; the others informative


@contextlib.contextmanager
def stage_with(news: list):
    """While inside, the ``diagnose`` stage reads its source with the campaigns of ``news`` added
    as test campaigns; what it read and the diagnosis it computed are kept (``kept["ds"]``,
    ``kept["d"]``)."""
    from bench_moretest68 import with_new

    import thermocomp.shell.stages.diagnose as stage

    shipped, kept = (stage.open_source, stage.run_diagnosis), {}

    def opened(cfg, **kw):
        kept["own"] = shipped[0](cfg, **kw)
        kept["ds"] = with_new(kept["own"], news) if news else kept["own"]
        return kept["ds"]

    def diagnosed(*a, **kw):
        kept["d"] = shipped[1](*a, **kw)
        return kept["d"]

    stage.open_source, stage.run_diagnosis = opened, diagnosed
    try:
        yield kept
    finally:
        stage.open_source, stage.run_diagnosis = shipped


def run_stage(overrides: list[str], news: list | None = None) -> dict:
    """``thermocomp diagnose OVERRIDES`` (with ``news`` appended as test campaigns): ``{"d": the
    Diagnosis, "ds": the dataset it read, "own": the record's own}``."""
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.stages.diagnose import diagnose

    cfg = compose(["track=false", *overrides], "diagnose")
    with stage_with(news or []) as kept:
        diagnose(cfg)
    return kept


def _measured(d, target: str) -> dict:
    """Per target of diagnosis ``d`` as the stage reports it: accepted effects, the control, the
    own test's uncompensated / before / after RMSE (deployed)."""
    j = d.to_json(target)
    keys = ("cv_rmse_gain_pct", "p_value", "p_value_family", "p_value_margin", "n_features",
            "shrink_alpha", "cv_rmse_gain_pct_within", "cv_rmse_gain_pct_within_rest")
    return {"accepted": [f'{e["kind"]} {e["column"]} {e["transform"]}' for e in j["effects"]
                         if e["accepted"]],
            "evidence": [{k: e["evidence"].get(k) for k in keys} for e in j["effects"] if e["accepted"]],
            "control_clears": j["control_ever_clears_bar"],
            "cv": [j["before"]["cv_rmse"], j["after"]["cv_rmse"]],
            "measured": j["before"]["test_rms_measured"],
            "test_rmse": [j["before"]["test_rmse"], j["after"]["test_rmse"]],
            "excluded": j["excluded_inputs"], "cv_scheme": j["cv"].get("scheme"), "min_p": j["cv"]["min_p"]}


def scenario(work: Path) -> None:
    import bench_remeasure62 as rm
    from bench_automore69 import _simulated
    from bench_jig68 import scores

    from thermocomp.core.continuation import predecessors

    start = cpu_seconds(children=True)
    news = [_simulated(["sim=yearround_spindle"], s) for s in NEW_SEEDS]
    rm._append(work / "scenario.jsonl", {"draws": True, "cpu_s": round(cpu_seconds(True) - start, 1)})
    for seed in RECORD_SEEDS:
        start = cpu_seconds(children=True)
        folder = work / "records" / f"yearround-{seed}"
        if not folder.exists():
            subprocess.run([sys.executable, "-m", "thermocomp", "simulate", f"data.path={folder}",
                            f"seed={seed}", "track=false", "-q"], check=True)
        args = [f"data.path={folder}", f"seed={seed}"]
        alone = run_stage([*args, f"out={work / 'out' / f'alone-{seed}'}"])["d"]
        kept = run_stage([*args, f"out={work / 'out' / f'new-{seed}'}"], news)
        d, ds, own = kept["d"], kept["ds"], kept["own"].ids("test")
        # as bench_automore69: the own campaigns' links kept, a new one continues only its draw's
        links = predecessors(ds)
        assert {c: p for c, p in links.items() if c in own} == {
            c: p for c, p in predecessors(kept["own"]).items() if c in own}, seed
        assert all(p.split("_")[0] == c.split("_")[0] for c, p in links.items()
                   if c not in kept["own"].ids()), seed
        row = {"seed": seed, "targets": {}, "draws": [len(n.ids()) for n in news]}
        for t in alone.targets:
            a, b = _measured(alone, t), _measured(d, t)
            own_rmse = scores(d, t, own)["own"]["rmse"]
            same = a["accepted"] == b["accepted"] and np.allclose(a["test_rmse"], own_rmse, rtol=5e-4)
            assert same, (seed, t, a, own_rmse)
            # the stage's deployed figure over all 136 test campaigns beside the batch pooled one
            # the rows above use (bench_jig68.scores: run's predictions, as moretest68's)
            per = np.array([*scores(d, t, own)["own"]["per_campaign"],
                            *scores(d, t, own)["new"]["per_campaign"]], float)
            row["targets"][t] = {**a, **scores(d, t, own), "all_deployed": b["test_rmse"],
                                 "all_batch": list(np.sqrt(per[:, 1:].sum(0) / per[:, 0].sum()))}
        row["cpu_s"] = round(cpu_seconds(children=True) - start, 1)
        rm._append(work / "scenario.jsonl", row)


def record(work: Path, splits: list[str]) -> None:
    import bench_remeasure62 as rm

    from thermocomp.base.errors import ConfigError

    for split in splits:
        overrides, start = SPLITS[split], cpu_seconds()
        folder = work / "out" / "".join(c if c.isalnum() else "-" for c in split)
        d = run_stage([*overrides, f"out={folder}"])["d"]
        tests = list(d.predictions["before"])
        row = {"split": split, "test_campaigns": len(tests), "targets": {}}
        for t in d.targets:
            errors = {}
            for w in ("before", "after"):
                e = np.concatenate([np.asarray(d.predictions[w][c][0][t], float)
                                    - np.asarray(d.predictions[w][c][1][t], float) for c in tests])
                errors[w] = e[np.isfinite(e)]
            row["test_rows"] = int(errors["before"].size)
            faults = [{"sensor": e.effect.column, "jump": e.jump_ratio, "cv_pct": e.gain_pct,
                       "in_range_pct": e.gain_pct_in_range, "clears": e.clears_bar, "accepted": e.accepted}
                      for r in d.targets[t].search.rounds for e in r.evaluated
                      if e.effect.transform == "remove"]
            row["targets"][t] = {**_measured(d, t), "faults": faults,
                                 "rmse": [float(np.sqrt(np.mean(errors[w] ** 2))) for w in errors],
                                 "mae": [float(np.mean(np.abs(errors[w]))) for w in errors]}
        try:
            if split in VERDICT:
                run_stage([*overrides, "model=auto", f"out={work / 'out' / 'auto'}"])
                row["auto"] = "diagnosed"
        except ConfigError as exc:
            row["auto"] = f"refused: {exc}"
        row["cpu_s"] = round(cpu_seconds() - start, 1)
        rm._append(work / "record.jsonl", row)


def _pct(after: float, before: float) -> float:
    return 100.0 * (after / before - 1.0)


def table(work: Path) -> None:
    import bench_remeasure62 as rm
    from bench_moretest68 import _change, resampled

    lines, fails = [], []
    rows = rm._read(work / "scenario.jsonl") if (work / "scenario.jsonl").exists() else []
    for r in rows:
        if "seed" not in r:
            lines.append(f"new campaigns drawn: CPU s {r['cpu_s']}")
            continue
        for t, o in r["targets"].items():
            (ob, oa), (nb, na) = o["own"]["rmse"], o["new"]["rmse"]
            per = np.array(o["new"]["per_campaign"], float)
            cut = np.cumsum([0] + r["draws"])
            lo, hi = resampled(per)
            own, new = _pct(oa, ob), _pct(na, nb)
            draws = ", ".join(f"{_change(per[a:b]):+.1f}" for a, b in zip(cut[:-1], cut[1:]))
            lines.append(f"seed {r['seed']} {t}: own {o['own']['campaigns']}: measured {o['measured']:.3f}, "
                         f"MLR {ob:.4f} -> diagnosed {oa:.4f} ({own:+.1f} %) | new {o['new']['campaigns']}: "
                         f"{nb:.4f} -> {na:.4f} ({new:+.1f} %) [{lo:+.1f}, {hi:+.1f}]; worse / better "
                         f"{o['new']['worse']} / {o['new']['better']}; {o['cv_scheme']}, min p "
                         f"{o['min_p']:.2g}; accepted: " + ("; ".join(o["accepted"]) or "none")
                         + (f"; excluded {o['excluded']}" if o["excluded"] else ""))
            if o["accepted"]:
                n = o["own"]["campaigns"] + o["new"]["campaigns"]
                lines.append(f"    per draw: {draws}; all {n} test campaigns, "
                             f"deployed {o['all_deployed'][0]:.4f} -> {o['all_deployed'][1]:.4f}, batch "
                             f"{o['all_batch'][0]:.4f} -> {o['all_batch'][1]:.4f}")
                lines += [f"    evidence {k + 1}: " + ", ".join(f"{n} {v:.3g}" for n, v in e.items()
                                                            if v is not None)
                          for k, e in enumerate(o["evidence"])]
            name = f"seed {r['seed']} {t}"
            fails += [f"F1 {name} {own:+.1f} %"] * bool(own > 2) + [f"F2 {name} {new:+.1f} %"] * bool(lo > 2)
            fails += [f"F3 {name}"] * bool(o["accepted"] and not hi < -2)
            fails += [f"F4 {name}"] * o["control_clears"]
        lines.append(f"  CPU s {r['cpu_s']} (simulate, the diagnosis alone and with the new campaigns)")
    recs = rm._read(work / "record.jsonl") if (work / "record.jsonl").exists() else []
    for r in recs:
        lines.append(f"fl_thermal {r['split']}: test {r['test_campaigns']} campaign(s), "
                     f"{r['test_rows']} rows; model=auto: {r.get('auto', 'not tried')[:8]}; "
                     f"CPU s {r['cpu_s']}")
        for t, o in r["targets"].items():
            # RMSE: diagnose's (deployed) and run's (batch: the predictions), MAE from the latter
            (db, da), (rb, ra), (mb, ma) = o["test_rmse"], o["rmse"], o["mae"]
            lines.append(f"  {t}: measured {o['measured']:.2f}; RMSE {db:.3f} -> {da:.3f} "
                         f"({_pct(da, db):+.1f} %), batch {rb:.3f} -> {ra:.3f}; MAE {mb:.3f} -> {ma:.3f} "
                         f"({_pct(ma, mb):+.1f} %); CV "
                         f"{o['cv'][0]:.3f} -> {o['cv'][1]:.3f}; {o['cv_scheme']}, min p {o['min_p']:.2g}; "
                         "accepted: " + ("; ".join(o["accepted"]) or "none")
                         + (f"; excluded {o['excluded']}" if o["excluded"] else ""))
            lines += [f"    evidence {k + 1}: " + ", ".join(f"{n} {v:.3g}" for n, v in e.items()
                                                            if v is not None)
                      for k, e in enumerate(o.get("evidence", []))]
            lines += [f"    fault check {f['sensor']}: jump ratio {f['jump']:.2f}, CV RMSE gain without it "
                      f"{f['cv_pct']:+.2f} % (rows in range {f['in_range_pct']:+.2f} %), "
                      f"clears {f['clears']}, accepted {f['accepted']}"
                      for f in o.get("faults", [])]
            worse = [f"F5 fl_thermal {r['split']} {t} {_pct(x, y):+.1f} %"
                     for x, y in ((da, db), (ra, rb)) if x > 1.02 * y]
            fails += worse[:1] if r["split"] in VERDICT else []
    lines += ["", "failures: " + ("; ".join(fails) or "none")]
    print(rm._wrapped(lines, 150))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "scenario": lambda work: scenario(made_folder(work)),
        "record": lambda work, *splits: record(made_folder(work), list(splits) or list(SPLITS)),
        "table": lambda work: table(Path(work).resolve()),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
