"""Is the per-target clamp (``promote.envelope.per_target``, env93) safe under the deployed
monitor?  Sensor faults streamed through the ADAPTIVE compensator (``monitor.adaptive=true``, the
default deployment) with the key on and off, each scored by its distance to the truth (env93b,
issue 34).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_env93b.py faults ROOT SEEDS
    python benchmarks/bench_env93b.py table ROOT
    python benchmarks/bench_env93b.py widths ROOT SEEDS
    python benchmarks/bench_env93b.py spike54

``faults``: bench_env92's ``draw ROOT SEEDS`` first (``column_moving_source`` seed by seed into
``ROOT/data/cms<seed>``, per family ``mlr``, ``arx``, ``lagbank`` the model fitted into
``ROOT/fit``; cells already drawn are not redone), then per cell and per ``per_target`` (off: the
shipped default; on: env93's rule) the model made deployable as ``replay`` / ``promote`` make it
(``builders.deployable_model``: the adaptive compensator around the plain stream) and its test
campaign streamed as ``replay`` streams it (``report.replay_report``): the TRUE readings (the drawn
record, nothing planted) and each fault of :data:`KINDS` planted on each sensor of :data:`SENSORS`
at three quarters of the campaign (inside Q3's excursion, where the rule unclamps E_X):
``spike`` +50 °C on one row (test_export_spike54's), ``jump`` +2 K from the row on, ``drift``
+1 K/h from it (bench_mon84's ``four_faults``), ``range`` +20 K for 30 rows then back (outside
the training range: the monitor's ``out of range``), ``dropout`` missing for 30 rows.  Lines into
``ROOT/faults.jsonl``: per case the deployed RMSE per target against the measured error.
``table``: per row (record, family, kind, sensor, target) the distance to the truth
d = |log(RMSE_fault / RMSE_true)| (bench_bar91b's, the truth the same configuration on the true
readings), on and off; a FAULT CASE (record, family, kind, sensor) is "on worse" when one of its
rows has d_on > d_off + log(1.02); beside it the deployed Σ² (six targets) on / off.
``spike54``: the spike suite's record (tests/shell/test_export_spike54.py: ``arx`` with AR and
``lagbank``, every excursion clamped) deployed adaptive, key on and off: the healthy test
campaign and the +50 °C spike of ``T_a``; the same distance and the largest |correction(spiked)
- correction(healthy)| after the spike row.

``widths``: per seen cell (``mlr``'s inputs) how far Q3 and each fault leave the envelope, in
training widths (``hi - lo``): what a rule that unclamps only "an excursion a heat source can
make" (env93's Left) would have to separate.

Step (1), seen seeds (env92's and env93's seen: 3141, 5003, 4253, 6007, 9406; nothing fresh).
Step (2) only if no fault case there is "on worse" (the brief: on never worse than off by > 2 %
in any fault case under the adaptive deployment): a bar written before scoring, on fresh
9589-9593.  Step (2) did not arise: the fresh seeds were NOT drawn (9589-9593 unspent).

MEASURED, step (1) (``faults /tmp/env93b/seen 3141,5003,4253,6007,9406`` then ``table``;
2026-12-05, main 5fe17063's src, env92's fits of the seen cells copied from /tmp/env93/lines;
CPU 263 s for 30 deployments and 330 streams of 1441 rows; 5 seeds x 3 families x 5 kinds x 2
sensors = 150 fault cases, 900 target rows)::

  kind     cases  on worse by d (*)  mean d off / on  Σ² on > 1.02 off  added Σ² off / on
  spike      30     26              0.0663 / 0.0764        1              1486 / 1582
  jump       30     26              0.0660 / 0.0763        1              1470 / 1566
  drift      30     30              0.3104 / 0.4481       21             22971 / 37940
  range      30     26              0.0663 / 0.0764        1              1486 / 1582
  dropout    30     26              0.0656 / 0.0757        1              1554 / 1652
  all       150    134              0.1149 / 0.1506       25 (Σ² on/off geometric mean 0.693)
  (*) cases with a target row d_on > d_off + log(1.02)

Per cell, Σ² (µm², six targets) on the true readings off / on, and what each fault adds to the
deployed Σ² off / on (R3 = T_right3, L3 = T_left3; jump, range and dropout as spike to a few µm²)::

  record   model    true Σ² off/on   spike:R3      spike:L3      drift:R3        drift:L3
  cms3141  arx        1336 /   848   -20 /  -9     28 /  48     3187 / 3916      418 / 1021
  cms3141  lagbank     943 /   850    23 /  29    160 / 181      -91 /  -41      512 /  726
  cms3141  mlr         788 /   316    20 /  22    127 / 140      573 / 1259     1588 / 2134
  cms4253  arx        1528 /   866   -46 / -55     74 /  46     1583 / 2436      362 / 1075
  cms4253  lagbank     589 /   447    30 /  28    236 / 254       97 /  260      960 / 1171
  cms4253  mlr        1179 /   505    15 /   1    124 / 100      409 / 1154      842 / 1492
  cms5003  arx         867 /   364     2 /  10     40 /  41      225 /  747     2188 / 2648
  cms5003  lagbank    1386 /  1412    -4 /  -4    -34 / -31      245 /  460      578 /  915
  cms5003  mlr        1952 /  1518   -11 /  -7   -136 / -125     110 /  496      818 / 1717
  cms6007  arx         753 /   331    26 /  22    280 / 250      322 / 1390     2361 / 2808
  cms6007  lagbank    1076 /  1023    94 /  95    -95 / -83      944 / 1057      306 /  512
  cms6007  mlr         857 /   432    21 /  10    195 / 162      412 / 1341     1162 / 1538
  cms9406  arx        1088 /   433   -24 /  17    155 / 151      276 / 1146     1191 / 1676
  cms9406  lagbank     782 /   692     3 /  22     86 / 112      102 /  245      653 /  865
  cms9406  mlr        1035 /   371    11 /  61    104 /  94       77 /  783      562 /  994

Reading. The monitor takes a spike, a jump, an out-of-range stretch and a dropout out: the four
leave the same footprint to a few µm² (read as the sensor replaced by the field's prediction for the
monitor's window, then back: inferred, not traced event by event; no sensor excluded at the
campaign's end in any case), and with the key on that footprint costs +6 % more (1486 -> 1582 µm²
added over 30 cases): while it stands in, the replacement presumably does not carry Q3, which the
unclamped E_X then misses. Against the truth's distance (bar91b's) on is further in 26 of 30 cases
of each of the four, a relative figure against a truth that on makes smaller (true Σ² pooled 16 160
off / 10 407 on): in deployed Σ² on stays lower than off in every such case but cms5003 lagbank's
(1.019-1.021), whose true Σ² is already 1.9 % higher on. The unsafe fault is the slow DRIFT (+1 K/h
from three quarters of the campaign, 10 K at its end): the adaptive compensator does not take it out
(the sensor is not excluded at the end in any case), the clamp bounds what a clamped target takes of
it, and an unclamped white target follows it linearly: added Σ² larger on in 30 of 30 cases (22 971
-> 37 940 pooled), deployed Σ² on > 1.02 off in 21 of 30 (up to 1.60x: cms6007 arx drift:R3 1074 ->
1721; mlr drift:R3 2.2-10x the added Σ²).

``widths`` (seen seeds, mlr; largest excess in training widths): Q3 on the true record 0.75 /
0.76 / 1.04 / 0.80 / 0.91 (3141, 5003, 4253, 6007, 9406); spike 10.5-12.5 (R3) and 7.2-8.6
(L3); range 4.6-5.5 / 2.7-3.4; jump 1.03-1.24 / 0.03-0.40; drift (at its end) 1.53-1.89 /
1.09-1.39.  A width bound would keep a spike and a range stretch clamped but not a drift's first
hours (a drift reaches 1 width where Q3 itself does).

``spike54`` (the spike suite's record, adaptive, every excursion clamped; CPU 5 s): under the
monitor the key changes nothing the +50 °C spike of ``T_a`` leaves: arx (on unclamps E_Z) K05 E_X
0.4495 -> 1.2851, E_Z 0.4038 -> 0.5048 µm both ways, K06 E_Z 0.9324 -> 0.9835 off / 0.9225 -> 0.9737
on (d 0.053 / 0.054); lagbank (on unclamps E_X, E_Z) the same to 4 decimals on K05, K06 d 1.313 /
1.304 (E_X), 0.095 / 0.095 (E_Z); the largest |correction(spiked) - correction(healthy)| after the
spike row 2.53 / 1.57 µm (arx) and 3.16 / 2.42 µm (lagbank), on and off alike: the monitor's window,
not the clamp's memory. So env93's objection (a spike stays in a white ARX target's memory) holds
for the plain stream only; under the adaptive deployment the objection is the drift.

VERDICT: TRACED.  Step (1)'s condition fails (drift: 21 of 30 cases > 2 % worse in deployed Σ²,
30 of 30 by the distance), so no bar was written and no fresh seed drawn; src untouched
(``promote.envelope.per_target`` stays opt-in, default false).  Left: a white target unclamped
only while its inputs' excess is one a source makes, with the drift priced: the monitor's drift
detection for a predicted sensor (monb92b's growth rule is for a blind one), or a rate bound on
the excess (a drift's 1 K/h against Q3's own rise), scored on this bench's drift cases.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_env92 as env92  # noqa: E402
import bench_envelope_policy as envelope_policy  # noqa: E402
from _cli import run_commands, seed_list  # noqa: E402

KINDS = ("spike", "jump", "drift", "range", "dropout")
SENSORS = ("T_right3", "T_left3")      # E_X's two faces: the right face's largest gain (env93's trace)
SLACK = np.log(1.02)                     # "worse by > 2 %", bar91b's clause (b)
KEY = "promote.envelope.per_target"


def planted(frame, kind: str, sensor: str):
    """``frame`` with the fault ``kind`` on ``sensor`` from three quarters of the campaign on."""
    out, n = frame.copy(), len(frame)
    row = 3 * n // 4
    rows = np.arange(n)
    x = out[sensor].to_numpy(float)
    period = float(np.median(np.diff(out["time"].to_numpy(float))))
    after, stretch = rows >= row, (rows >= row) & (rows < row + 30)
    out[sensor] = {"spike": x + 50.0 * (rows == row), "jump": x + 2.0 * after,
                   "drift": x + np.clip(rows - row, 0, None) * period / 3600.0,
                   "range": x + 20.0 * stretch, "dropout": np.where(stretch, np.nan, x)}[kind]
    return out


def _config(*overrides):
    from hydra import compose, initialize_config_dir

    from thermocomp.base.paths import conf_dir
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=list(overrides))


def _streamed(deployed, ds, tid, frame) -> tuple[dict, list]:
    """``(per target the deployed RMSE, the sensors excluded at the end)`` of ``frame`` streamed
    as ``replay`` streams a test campaign."""
    from thermocomp.apps.deploy.report import replay_report

    result = replay_report(deployed, {tid: frame}, {tid: ds.rows_named(tid)})
    return ({t: v["rmse"] for t, v in result["targets"].items()}, result["excluded_inputs"])


def faults(root: str, seeds: str) -> None:
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    env92.draw(root, seeds)
    base = Path(root)
    out = base / "faults.jsonl"
    done = {(r["record"], r["family"], r["per_target"]) for r in env92._rows(out)}
    for seed in seed_list(seeds):
        record = f"cms{seed}"
        for fam in envelope_policy.FAMILIES:
            for on in (False, True):
                if (record, fam, on) in done:
                    continue
                cfg = _config(f"data.path={base / 'data' / record}", "track=false",
                              "monitor.adaptive=true", f"{KEY}={str(on).lower()}")
                ds, train_ids, test_ids, _ = read_streamed(cfg)
                model = base / "fit" / f"{record}-{fam}" / "model.pkl"
                deployed, _, _ = deployable_model(cfg, ds, train_ids, str(model), "replay.model")
                tid = test_ids[0]
                true = ds.campaigns[tid]
                line = {"record": record, "family": fam, "per_target": on,
                        "unclamped": list(getattr(deployed.streaming, "unclamped_", ())),
                        "true": _streamed(deployed, ds, tid, true)[0], "faults": {}, "excluded": {}}
                for sensor in SENSORS:
                    for kind in KINDS:
                        case = f"{kind}:{sensor}"
                        line["faults"][case], line["excluded"][case] = _streamed(
                            deployed, ds, tid, planted(true, kind, sensor))
                with out.open("a") as f:
                    f.write(json.dumps(line) + "\n")
                print(record, fam, "on" if on else "off", "unclamped", line["unclamped"], flush=True)


def cases(lines: list[dict]) -> list[dict]:
    """Per fault case (record, family, kind:sensor) the rows' distances on / off and Σ²."""
    by = {(r["record"], r["family"], r["per_target"]): r for r in lines}
    out = []
    for (record, fam, on), r in sorted(by.items()):
        if on or (record, fam, True) not in by:
            continue
        r_on = by[record, fam, True]
        for case in r["faults"]:
            rows = {}
            for t in r["true"]:
                d_off = abs(np.log(r["faults"][case][t] / r["true"][t]))
                d_on = abs(np.log(r_on["faults"][case][t] / r_on["true"][t]))
                rows[t] = (float(d_off), float(d_on))
            worse = [t for t, (a, b) in rows.items() if b > a + SLACK]
            out.append({"record": record, "family": fam, "case": case, "rows": rows, "worse": worse,
                        "s2_off": sum(v ** 2 for v in r["faults"][case].values()),
                        "s2_on": sum(v ** 2 for v in r_on["faults"][case].values()),
                        "true_off": sum(v ** 2 for v in r["true"].values()),
                        "true_on": sum(v ** 2 for v in r_on["true"].values()),
                        "unclamped": r_on["unclamped"],
                        "out_at_end": r.get("excluded", {}).get(case, "?")})
    return out


def table(root: str) -> None:
    rows = cases(env92._rows(Path(root) / "faults.jsonl"))
    print(f"{'record':8} {'model':8} {'case':17} {'Σ² off':>8} {'Σ² on':>8} {'+off':>6} {'+on':>6}"
          "  max d off / on   on worse rows")
    for c in rows:
        d = np.array(list(c["rows"].values()))
        print(f"{c['record']:8} {c['family']:8} {c['case']:17} {c['s2_off']:8.0f} {c['s2_on']:8.0f}"
              f" {c['s2_off'] - c['true_off']:6.0f} {c['s2_on'] - c['true_on']:6.0f}"
              f"  {d[:, 0].max():.4f} / {d[:, 1].max():.4f}  {','.join(c['worse']) or '-'}"
              f"  (out at the end: {','.join(c['out_at_end']) or '-'})")
    n_worse = sum(bool(c["worse"]) for c in rows)
    n_s2 = sum(c["s2_on"] > 1.02 * c["s2_off"] for c in rows)
    harm = sum(c["s2_on"] - c["true_on"] > c["s2_off"] - c["true_off"] for c in rows)
    geo = np.exp(np.mean([np.log(c["s2_on"] / c["s2_off"]) for c in rows]))
    d_all = np.array([v for c in rows for v in c["rows"].values()])
    print(f"cases {len(rows)}, on worse (a row > 2 % further from the truth) in {n_worse};"
          f" mean d off {d_all[:, 0].mean():.4f} on {d_all[:, 1].mean():.4f};"
          f" Σ² on/off geometric mean {geo:.3f},"
          f" Σ² on > 1.02 off in {n_s2} cases, the fault's added Σ² larger on in {harm}")
    for kind in KINDS:
        sel = [c for c in rows if c["case"].startswith(kind + ":")]
        if sel:
            d = np.array([v for c in sel for v in c["rows"].values()])
            print(f"  {kind:8} {len(sel):3} cases, on worse in {sum(bool(c['worse']) for c in sel):3};"
                  f" mean d off {d[:, 0].mean():.4f} on {d[:, 1].mean():.4f};"
                  f" Σ² on > 1.02 off in {sum(c['s2_on'] > 1.02 * c['s2_off'] for c in sel)};"
                  f" added Σ² off {sum(c['s2_off'] - c['true_off'] for c in sel):.0f}"
                  f" on {sum(c['s2_on'] - c['true_on'] for c in sel):.0f}")


def widths(root: str, seeds: str) -> None:
    """How far each fault leaves the training envelope, against Q3: per cell (``mlr``: the
    model's own inputs), the largest excess over the envelope in training widths (``hi - lo``)
    of any input on the true record (Q3's excursion), and of the faulted sensor under each fault
    (its largest over the campaign, its own part of Q3's included: a dropout shows that alone)."""
    import pandas as pd
    from bench_env93 import _cell

    base = Path(root)
    print(f"{'record':8} {'Q3 (true)':>9} " + " ".join(f"{k}:{s[2:]}" for s in SENSORS for k in KINDS))
    for seed in seed_list(seeds):
        record = f"cms{seed}"
        model, stream, _ = _cell(base, record, "mlr")
        env, cols = stream.envelope, list(stream.envelope.columns)
        true = pd.read_csv(base / "data" / record / "test_cycle.csv")

        def most(frame, only=None):
            x = model.stacked({"test": frame}, []).X[cols].to_numpy()
            ex = np.abs(np.array([env.excess(r) for r in x])) / (env.hi - env.lo)
            return float(np.nanmax(ex if only is None else ex[:, cols.index(only)]))
        cells = [most(planted(true, k, s), s) for s in SENSORS for k in KINDS]
        print(f"{record:8} {most(true):9.2f} " + " ".join(f"{c:{len(k) + 8}.2f}" for c, k in
                                                         zip(cells, [k for _ in SENSORS for k in KINDS])))


def spike54() -> None:
    """The spike suite's record, key on / off (module doc)."""
    import tempfile

    sys.path[:0] = [str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
    from test_export import EVERY_EXCURSION, _make_dataset
    from test_export_spike54 import FAMILIES, SENSOR, SPIKE_C
    from thermocomp.apps.deploy.report import replay_report
    from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
    from thermocomp.shell.source import read_streamed

    data = _make_dataset(Path(tempfile.mkdtemp(prefix="env93b-spike54-")) / "data")
    for fam, words in FAMILIES.items():
        for on in (False, True):
            cfg = _config(f"data.path={data}", "track=false", "monitor.adaptive=true", EVERY_EXCURSION,
                          f"{KEY}={str(on).lower()}", *words)
            ds, train_ids, test_ids, _ = read_streamed(cfg)
            train = {c: ds.campaigns[c] for c in train_ids}
            deployed = deployable(cfg, deploy_stream(cfg, build_compensator(cfg, ds=ds).fit(train), train),
                                  train, ds)
            for tid in test_ids:
                healthy = ds.campaigns[tid].reset_index(drop=True)
                row = len(healthy) // 2
                spiked = healthy.copy()
                spiked.loc[row, SENSOR] += SPIKE_C
                r = {k: replay_report(deployed, {tid: f}, {tid: ds.rows_named(tid)})["targets"]
                     for k, f in (("true", healthy), ("spiked", spiked))}
                deployed.reset()
                y_h = deployed.predict(healthy)[deployed.targets_].to_numpy()
                deployed.reset()
                y_s = deployed.predict(spiked)[deployed.targets_].to_numpy()
                after = np.abs(y_s - y_h)[row + 1:]
                pair = {t: (r["true"][t]["rmse"], r["spiked"][t]["rmse"]) for t in r["true"]}
                print(f"{fam:8} {'on ' if on else 'off'} {tid:10} unclamped"
                      f" {','.join(getattr(deployed.streaming, 'unclamped_', ())) or '-':10}"
                      " rmse true/spiked " + " ".join(
                          f"{t} {a:.4f}/{b:.4f} (d {abs(np.log(b / a)):.4f})" for t, (a, b) in pair.items())
                      + f"  max|after| {after.max():.3f} µm on {int((after > 1e-9).sum())} of {after.size}",
                      flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"faults": faults, "table": table, "widths": widths,
                                  "spike54": spike54},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
