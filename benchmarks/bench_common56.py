"""A common-mode sensor fault against the guard that follows the inputs (stop 56, common56).

``monitor.guard.follow_inputs`` (``bench_guard56.py``'s G3) widens the correction guard's bound
at a sample on the envelope's training pattern.  A fault that moves EVERY temperature channel
together (a logger's cold-junction / reference failure, a shared supply offset) stays on that
pattern: does the guard now pass what the fixed bound cut?

Records (the train / test split each record's config gives): ``ys5353`` (``yearround_spindle``,
seed 5353, 9 campaigns of 3-5 h; ``bench_ambient_step55.py``'s record, its real air steps),
``sld`` (``swiss_lathe_door``, its default seed), ``long4253`` (``bench_state_envelope.py``'s
overspeed record, ``data.reference=none``), ``fl9010`` (the measured ``fl_thermal``, 90/10; no
channel is named as the air: the "without the ambient" variant is not made).  Models mlr /
arx / lagbank, fitted on the train campaigns and deployed as replay deploys them: ``plain``
(``monitor.adaptive=false``), ``follow`` (adaptive, the guard following the inputs: src's
default) and ``fixed`` (the same deployment, ``follow_inputs=false``).

Faults, from the middle row of each test campaign, on every ``T_`` column (``all``) or every one
but ``T_amb`` (``noamb``): +2 K, +5 K, -5 K steps and a +1 K/h drift.  Score: Σ² = sum over the
targets of the mean squared (fault-free measured error - correction), rows from the middle on,
test campaigns pooled (µm²).  Real air steps (``ys5353`` only; the simulation rerun with the air
of one test campaign stepped at its middle row, ``bench_ambient_step55.py``'s files): the same
score against that campaign's own measured error.

Run (the records are written under ``--work`` once: ys5353 and its air steps as
``bench_ambient_step55.py`` writes them, long4253 as ``bench_state_envelope.py`` does, ``sld`` by
``thermocomp simulate``)::

    PYTHONPATH=src .venv/bin/python benchmarks/bench_common56.py [--only ys5353] [--out f.json]

Measured 2026-11-30 (stop 56; 225.1 s user + sys for the whole run, the records cached).
Σ² plain / fixed / follow (µm²); ``*`` follow > 1.05 x fixed, ``-`` follow < 0.95 x fixed::

  record   case            mlr                     arx                     lagbank
  ys5353   healthy         15.6/15.6/15.6          27.3/27.3/27.3          30.8/30.8/30.8
           +2K all         66.3/148/148            58.9/52.0/52.0          84.5/78.8/78.8
           +2K noamb       148/164/164             38.5/37.0/37.0          68.8/90.0/90.0
           +5K all         373/241/241             270/92.0/92.0           447/129/129
           +5K noamb       443/589/601             120/51.8/51.8           313/235/235
           -5K all         453/351/376 *           352/118/120             572/160/161
           -5K noamb       553/578/658 *           169/58.3/58.3           180/216/217
           1K/h all        30.9/30.9/30.9          32.0/32.0/32.0          42.3/42.3/42.3
           1K/h noamb      58.8/58.8/58.8          27.6/27.6/27.6          38.0/38.0/38.0
           +2K real air    61.2/42.7/42.7          36.5/60.4/60.4          33.8/64.9/64.9
           +5K real air    158/153/153             86.4/160/160            84.4/145/145
           -5K real air    136/106/106             40.6/102/102            116/83.3/83.3
  sld      healthy         5.2/5.2/5.2             5.7/5.7/5.7             2.5/2.5/2.5
           +2K all         169/97.0/97.0           183/95.4/95.4           308/189/192
           +2K noamb       146/418/429             150/248/254             357/627/691 *
           +5K all         1044/40.0/40.0          1024/38.6/38.6          1981/52.1/52.1
           +5K noamb       997/1554/1554           763/1017/1017           1442/1644/1644
           -5K all         1036/1674/1814 *        1020/1381/1491 *        1774/1672/1821 *
           -5K noamb       1159/1767/1839          1020/1412/1452          2090/1853/2116 *
           1K/h all        1359/979/1479 *         1418/1001/1543 *        3191/1133/2465 *
           1K/h noamb      835/976/1637 *          798/1003/1753 *         1251/1147/2123 *
  long4253 healthy         6.4/10.0/4.3 -          11.4/14.4/15.7 *        1.0/8.5/4.6 -
           +2K all         6.8/2246/2246           13.0/2600/2600          42.5/1640/1640
           +2K noamb       6.4/2455/2492           11.5/2539/2606          105/1427/1427
           +5K all         10.3/2758/2949 *        20.5/2758/3066 *        251/2280/2358
           +5K noamb       9.9/2758/3230 *         14.5/2758/3124 *        637/1910/1910
           -5K all         12.5/738/738            19.1/261/261            238/529/529
           -5K noamb       8.3/1649/1658           12.9/921/921            619/697/697
           1K/h all        52.6/893/890            84.2/867/867            2326/1426/1448
           1K/h noamb      863/2457/2453           589/2710/2710           4865/3693/3785
  fl9010   healthy         84.5/84.5/84.5          179/179/179             205/205/205
           +2K all         370/1291/1424 *         479/1398/1521 *         281/4481/4706 *
           +5K all         949/11185/11185         2452/11325/11325        1842/11028/11028
           -5K all         6127/3011/3011          6636/6708/6708          1880/6837/6837
           1K/h all        290/331/331             268/248/248             64.5/176/176

Events (the run prints them per form): at a step the sensor monitor excludes most channels
(``excluded`` 9-30 per record and case, e.g. 30 of 30 on ys5353 at +-5 K all) and re-admits
some (``ok``); on long4253 at +2 / +5 K all it re-admits none (11 of 14 out for the rest of the
24 h campaign).  A 1 K/h drift raises nothing on ys5353, 4 exclusions on sld (all; 2 and 10
``warning`` without the air), 15-17 on long4253, 1 exclusion, 4 ``alarm`` and 7 ``warning`` on
fl9010.  The guard's ``bounded`` episodes move both ways (sld arx -5K all: 49 fixed -> 3
follow; sld lag bank 1K/h all: 13 -> 71, the widened bound flickering with the inputs).

Findings.  (1) follow is never better than fixed on a fault by more than 0.4 % and worse by
> 5 % on 20 of 84 fault lines: on sld's common drift 1.51-2.18 x (the fixed bound protected:
below plain on the "all" drift, 979 vs 1359 µm² for mlr), 1.07-1.14 x on -5 K steps (ys5353
mlr, sld), 1.10 x on sld lag bank's +2 K without the air, 1.07-1.17 x on long4253's +5 K (mlr,
arx), 1.05-1.10 x on fl9010's +2 K.  (2) The real air steps (ys5353) give follow = fixed on
every line: the guard does not act there either way; what follow buys is bench_guard56's
overspeed (here long4253 healthy, vs the measured error: 10.0 -> 4.3 mlr, 8.5 -> 4.6 lag bank;
arx 14.4 -> 15.7).  (3) Larger than either: the ADAPTIVE deployment (either bound) is far worse
than plain under a common step on long4253 (plain 6.4-637, adaptive 261-3230 µm²; the plain
models nearly blind to it: mlr 6.4 -> 6.8 at +2 K) and on fl9010 at +2 / +5 K (mlr 949 ->
11185 at +5 K): the monitor, built for one sensor leaving the others, excludes most channels at
the jump and feeds the model its field estimate from the few left.

The two rules the brief proposed, checked against the figures they would read (after the fault
lines were scored; no rule was run; MLR, the train campaigns): (a) "no widening where the
inputs' common mode moves faster than in training" cannot see a 1 K/h drift (the mean of every
channel moved up to 7.7 / 8.7 / 43.2 K/h per sample in training on ys5353 / sld / fl9010), and
long4253's overspeed moves the structure sensors' mean 7.2 K/h over an hour against 3.3 K/h at
most in training: the real state would be cut; (b) "widening capped by the correction's
training rate, integrated": the guard's rate is 21-22 x the allowance's growth under a 1 K/h
common drift on sld (1260 / 888 vs 61 / 41 µm/h per target), 31 x on fl9010 (1.6-4 x on ys5353,
where follow = fixed on the drift anyway): the cap does not bind where the drift costs.
Neither was implemented (src unchanged): no rule on the inputs alone tells a common drift that
spares the air from a machine that heats up, which is what follow passes by design.

The rule (commonjump56, written down before it was scored).  Measured first (long4253 mlr +2 K
all, campaign R1b): at the middle row the ``jump`` detector fires on the 11 channels whose jump
limit (3 x the largest training step, 0.5-1.4 K) is below 2 K and excludes them, each
re-referenced by its step less the others' predicted change (for a sensor the others predict,
that change had taken the step too: offset ~0, checked on the 10-sensor line of
``tests/apps/test_monitor_common_step56.py``: -0.05..+0.06 K of +2 K); 3 stay (``T_amb``,
``T_col_back``, ``T_zdrive``: limits 6-10 K), fewer than the r + 1 = 11 the field is rebuilt
from, and none was re-admitted for the rest of the campaign.  Rule:
a one-sample step that the jump detector sees on at least 3 sensors, with more than half of the
active sensors stepping by 1/2-2 x the jumping ones' median step (same sign), is one event, the
logger's: every active sensor that took it is re-referenced by its own step and stays in; a jump
off it is judged as before.  Bars (the brief's): the step lines adaptive <= plain or much closer;
the drift and real-air-step lines not worse; ``bench_deploy_faults.py`` and
``bench_monitor_healthy.py`` unchanged.

Scored (2026-11-30, the rule in src: ``SensorMonitor._common_step``; 176.4 s CPU, the code before
it 232.8 s).  Σ² plain / follow before / follow after (µm², ``follow`` = src's default; ``fixed``
after = follow on every step line but long4253's, where it is 8.8-22.0)::

  record   case            mlr                     arx                     lagbank
  ys5353   +2K all         66.3/148/27.0           58.9/52.0/39.0          84.5/78.8/51.0
           +2K noamb       148/164/26.9            38.5/37.0/38.9          68.8/90.0/51.1
           +5K all         373/241/27.0            270/92.0/39.0           447/129/51.0
           +5K noamb       443/601/26.9            120/51.8/38.9           313/235/51.1
           -5K all         453/376/27.0            352/120/39.0            572/161/51.0
           -5K noamb       553/658/26.9            169/58.3/38.9           180/217/51.1
  sld      +2K all         169/97.0/6.60           183/95.4/7.52           308/192/2.56
           +2K noamb       146/429/6.52            150/254/7.41            357/691/2.61
           +5K all         1044/40.0/6.60          1024/38.6/7.52          1981/52.1/2.56
           +5K noamb       997/1554/6.52           763/1017/7.41           1442/1644/2.61
           -5K all         1036/1814/6.60          1020/1491/7.52          1774/1821/2.56
           -5K noamb       1159/1839/6.52          1020/1452/7.41          2090/2116/2.61
  long4253 +2K all         6.76/2246/7.34          13.0/2600/19.0          42.5/1640/5.35
           +2K noamb       6.38/2492/7.35          11.5/2606/19.0          105/1427/5.24
           +5K all         10.3/2949/8.99          20.5/3066/25.0          251/2358/7.52
           +5K noamb       9.88/3230/9.00          14.5/3124/25.1          637/1910/7.40
           -5K all         12.5/738/7.55           19.1/261/15.7           238/529/2.61
           -5K noamb       8.26/1658/7.57          12.9/921/15.7           619/697/2.49
  fl9010   +2K all         370/1424/56.0           479/1521/109            281/4706/159
           +5K all         949/11185/56.0          2452/11325/109          1842/11028/159
           -5K all         6127/3011/56.0          6636/6708/109           1880/6837/159

(The "before" column is the code of this stop's main, after hold56: long4253 differs from the
table above, measured before it.)  Every healthy, 1K/h drift and real-air-step line is the same to
the last digit before and after, follow and fixed (the rule did not fire there).  After: the
adaptive stream at or below plain on 55 of the 63 step lines; above it on ys5353 arx +2K noamb
(38.9 vs 38.5; 37.0 before: the one line worse than before, +5 %), long4253 mlr +2K (7.34 / 7.35
vs 6.76 / 6.38) and arx +-2 / +5 K and -5 K noamb (15.7-25.1 vs 11.5-20.5; 921-3124 before),
where plain, nearly blind to the offset, is close to its healthy figure (adaptive healthy: mlr
6.40, arx 11.4).  Events at the step: 30 / 27 ``re-referenced`` on ys5353 (all / noamb), 12 / 11
on sld, 14 / 13 on long4253, 16 on fl9010, no exclusion (long4253: 2-4 later ones, each
re-admitted; its healthy run has 2).  ``bench_deploy_faults.py``: its tables identical before and
after (one fault, one sensor: the rule needs 3 jumping).  ``bench_monitor_healthy.py`` on long_record
s5306, fl_thermal, swiss_lathe s5304, column no Q3 s5305 x mlr / lagbank (180.6 s CPU): every row
identical to ``bench_hold56``'s run of the code before, healthy and faulted (but swiss lag bank's
drift, which that run lost to an error: here 1 exclusion, E_X RMSE fixed 15.6 -> adaptive 1.53 µm).
"""

from __future__ import annotations

import argparse
import copy
import json
import os
import sys
from collections import Counter
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import pandas as pd
from hydra import compose, initialize_config_dir

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cpu import print_cpu  # noqa: E402

from thermocomp.apps.deploy.streaming import replay
from thermocomp.base.paths import conf_dir
from thermocomp.core.continuation import lead_ins
from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
from thermocomp.shell.source import read_streamed

FAMILIES = ("mlr", "arx", "lagbank")
FAULTS = {"+2K": ("step", 2.0), "+5K": ("step", 5.0), "-5K": ("step", -5.0),
          "1K/h": ("drift", 1.0)}
REAL = {"+2K": "2", "+5K": "5", "-5K": "-5"}


def records(work: Path) -> dict[str, list[str]]:
    """Per record, its config overrides (the data written under ``work`` if missing)."""
    import bench_ambient_step55 as air
    from bench_state_envelope import simulate

    from thermocomp.apps.sim.scenario import write_scenario
    from thermocomp.shell.cli import main as cli

    if not (work / "ys" / "campaigns.csv").is_file():
        write_scenario(air._scenario(5353), work / "ys")
    for cid in pd.read_csv(work / "ys" / "campaigns.csv").query("split == 'test'")["campaign"]:
        for step in REAL.values():
            if not (work / f"air_{cid}_{step}_0").exists():
                write_scenario(air._scenario(5353, cid=cid, step_c=float(step)),
                               work / f"air_{cid}_{step}_0")
    simulate(work, "long4253")                     # cached as long4253_noisy (and _truth)
    sld = work / "sld"
    if not (sld / "campaigns.csv").is_file():
        cli(["-q", "simulate", "sim=swiss_lathe_door", f"data.path={sld}", "track=false",
             f"out={work / 'sim'}"])
    return {"ys5353": [f"data.path={work / 'ys'}"],
            "sld": [f"data.path={sld}"],
            "long4253": [f"data.path={work / 'long4253_noisy'}", "data.reference=none"],
            "fl9010": ["data=fl_thermal"]}


def _cfg(*overrides):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=["track=false", *overrides])


def fault(df: pd.DataFrame, kind: str, size: float, ambient: bool) -> pd.DataFrame:
    """Every temperature channel (``T_amb`` too if ``ambient``) offset from the middle row."""
    h, f = len(df) // 2, df.copy()
    cols = [c for c in df.columns if c.startswith("T_") and (ambient or c != "T_amb")]
    t = f["time"].to_numpy(float)
    shift = np.full(len(f) - h, size) if kind == "step" else size * (t[h:] - t[h]) / 3600.0
    f.loc[h:, cols] = f.loc[h:, cols].astype(float).to_numpy() + shift[:, None]
    return f


def _run(dep, df, lead, true, targets) -> tuple[float, Counter]:
    """Σ² from the middle row on and the events' counts (by kind)."""
    pred = replay(dep, df, lead_in=lead)
    h = len(df) // 2
    r = true[h:] - pred[targets].to_numpy(float)[h:]
    kinds = Counter()
    for row in pred.get("events", []):
        for e in json.loads(row):
            kinds[("bounded" if "correction bounded" in e.get("reason", "")
                   else str(e.get("to")))] += 1
    return r, kinds


def score(forms: dict, cases: list, targets) -> dict:
    """Per form: Σ² pooled over ``cases`` ``(df, lead, true)`` and the events."""
    out = {}
    for name, dep in forms.items():
        rs, kinds = [], Counter()
        for df, lead, true in cases:
            r, k = _run(dep, df, lead, true, targets)
            rs.append(r)
            kinds += k
        r = np.vstack(rs)
        out[name] = {"s2": float((r ** 2).mean(0).sum()), "events": dict(kinds)}
    return out


def one(work: Path, rec: str, overrides: list[str], family: str) -> list[dict]:
    cfg = _cfg(*overrides, f"model={family}", "monitor.adaptive=true")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds).fit(train)
    stream = deploy_stream(cfg, comp, train)
    follow = deployable(cfg, copy.deepcopy(stream), train, ds)
    fixed = copy.deepcopy(follow)
    fixed.guard.in_gain = None                     # = monitor.guard.follow_inputs=false
    forms = {"plain": stream, "follow": follow, "fixed": fixed}
    targets = comp.targets_
    leads = lead_ins(comp, ds, test_ids)
    measured = comp.measured({c: ds.campaigns[c] for c in test_ids})
    base = [(ds.campaigns[c].reset_index(drop=True), leads.get(c),
             measured[c][targets].to_numpy(float)) for c in test_ids]
    has_amb = "T_amb" in base[0][0].columns
    lines = [{"record": rec, "family": family, "case": "healthy",
              "forms": score(forms, base, targets)}]
    for name, (kind, size) in FAULTS.items():
        for ambient in (True, False) if has_amb else (True,):
            cases = [(fault(df, kind, size, ambient), lead, true) for df, lead, true in base]
            lines.append({"record": rec, "family": family,
                          "case": f"{name} {'all' if ambient else 'noamb'}",
                          "forms": score(forms, cases, targets)})
    if rec == "ys5353":                            # the air really stepped, one campaign at a time
        for name, step in REAL.items():
            cases = []
            for cid, (_, lead, _) in zip(test_ids, base):
                df = pd.read_csv(work / f"air_{cid}_{step}_0" / f"{cid}.csv")
                true = comp.measured({cid: df})[cid][targets].to_numpy(float)
                cases.append((df, lead, true))
            lines.append({"record": rec, "family": family, "case": f"{name} real air",
                          "forms": score(forms, cases, targets)})
    return lines


def _events(ev: dict) -> str:
    return " ".join(f"{k}:{v}" for k, v in sorted(ev.items())) or "-"


def main(argv=None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", default="/tmp/common56-w")
    ap.add_argument("--only", default="")
    ap.add_argument("--out", default=None)
    args = ap.parse_args(argv)
    work = Path(args.work)
    results = []
    for rec, overrides in records(work).items():
        for family in FAMILIES:
            if args.only and args.only not in f"{rec} {family}":
                continue
            for line in one(work, rec, overrides, family):
                results.append(line)
                f = line["forms"]
                print(f"{rec:8s} {family:7s} {line['case']:16s} plain {f['plain']['s2']:9.3f}  "
                      f"follow {f['follow']['s2']:9.3f}  fixed {f['fixed']['s2']:9.3f}  "
                      f"| follow {_events(f['follow']['events'])} | fixed "
                      f"{_events(f['fixed']['events'])}", flush=True)
    print_cpu()
    if args.out:
        Path(args.out).write_text(json.dumps(results))


if __name__ == "__main__":
    main()
