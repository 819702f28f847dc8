"""Which default for the training envelope (``promote.envelope.policy``): clamp or off?  (Answer,
now shipped: clamp, gated by the training pattern, ``promote.envelope.pattern=true``.)

Run (simulates and fits what is missing under ``--root``, default ``/tmp/cd49``; the spindle
workbook is a lab's file at ``/tmp/lab48``, its line fails without it)::

    PYTHONPATH=src .venv/bin/python benchmarks/bench_envelope_policy.py [--only mill7717] \
        [--adaptive false]
    PYTHONPATH=src .venv/bin/python benchmarks/bench_envelope_policy.py --table [--adaptive false]

Per record and family (``mlr``, ``arx``, ``lagbank``): ``run`` (the scored model, no envelope:
``replay.json``'s ``rmse_batch``) and ``replay`` with ``promote.envelope.policy=clamp
promote.envelope.pattern=false`` (``clamp``: every excursion clamped, the default until
2026-11-29), ``off`` and ``pattern`` (the shipped default: a sample is clamped only where its inputs
leave the training *pattern*, passed where they leave the range along it; a prototype
monkeypatched here first, ``Envelope`` in ``thermocomp.apps.deploy.streaming`` since), as Σ² = sum
over the targets of the squared RMSE (µm²), and the test samples with an input clamped (by
``clamp``; by ``pattern``).  The record set and the seed halves were written
down before measuring (``records``, ``DECIDE``; the rule's 0.999 and its tolerance fixed a priori,
never tuned; CPU: 26 s for mill7717 with mlr from nothing, simulation included):

(a) unseen source: ``column_moving_source`` seeds 3141, 5003 | 4253, 6007 (Q3 in the test);
(b) hotter test: ``large_mill_week``'s train week alone as one file cut 90/10 (``mill``),
    ``long_record`` (its own split, absolute values), ``yearround_spindle`` with its summer
    campaigns K10-K16 (27-33 °C) held out, ``swiss_lathe_door`` (its own split) and (added after
    both never left the envelope, before measuring it) its calibration file cut 90/10
    (``swissone``); seeds 7717 (5003 for year) | 4253;
(c) measured: ``fl_thermal`` 90/10 | its authors' 60/20/20, the spindle workbook (``spindel``).

Measured 2026-11-29 (today's monitor defaults, ``monitor.adaptive=true``); lines where some input
left the envelope (every other line: clamp = off = pattern; year, swiss, swissone, long4253,
fl_60_20_20 never leave it: records referenced to each campaign's first sample see no hotter
season)::

  record   model    half     clamped        run     clamp       off   pattern (clamped)
  cms3141  mlr      decide   520/1441      1614       788      1401       788   419
           arx                            11920      1335      9826      1335   419
           lagbank                          972       938      1000       943   419
  cms5003  mlr      decide   561/1441      8311      1887      5902      1887   461
           arx                              274       843       286       843   461
           lagbank                         1508      1324      1341      1320   461
  cms4253  mlr      confirm  541/1441       530      1179       546      1179   439
           arx                             5955      1527      5805      1529   439
           lagbank                          549       591       567       592   439
  cms6007  mlr      confirm  577/1441      1390       851      1377       851   477
           arx                              943       749      1025       749   477
           lagbank                         1027      1145      1117      1152   477
  mill7717 mlr      decide  2719/2808      8.28      61.1      8.28      8.30     1
           arx                             27.2      39.8      27.2      27.2     1
           lagbank                          297       521       292       292     1
  mill4253 mlr      confirm 2740/2808      8.42      50.8      8.42      8.42     0
           arx                             29.6      39.8      29.6      29.6     0
           lagbank                         64.5       113      64.5      64.5     0
  long7717 mlr      decide   150/3024     0.930     0.742     0.749     0.749     0
           arx                             1.66      1.34      1.35      1.35     0
           lagbank                        0.153     0.167     0.152     0.152     0
  fl_90_10 mlr      decide    88/1112      83.9      84.0      83.9      83.9     0
           arx                              129       129       129       129     0
           lagbank                          120       120       120       120     0
  spindel  mlr      confirm    42/60     0.0460    0.0460    0.0460    0.0460     0
           arx                           0.0462    0.0462    0.0462    0.0462     0
           lagbank                       0.0476     0.373    0.0476    0.0476     0

Pooled per kind (Σ² summed over every line; geometric mean of Σ²/run over the lines with an
excursion), clamp / off / pattern:

  (a) 12 lines   13156 / 30192 / 13168   (run 34996)   0.686 / 0.957 / 0.686
      decide 7114 / 19757 / 7116, confirm 6042 / 10435 / 6052
  (b) 30 lines    1300 /   905 /   905   (run 911)     1.79  / 0.951 / 0.951   (9 with excursions:
      827 / 432 / 432); decide 861 / 567 / 567, confirm 439 / 338 / 338
  (c)  9 lines    1636 /  1635 /  1635   (run 1769)    1.41  / 1.00  / 1.00    (6 with excursions)
      decide 333 / 333 / 333, confirm 1303 / 1302 / 1302 (spindel lagbank alone: 0.373 / 0.048)

``monitor.adaptive=false`` (the plain stream; the guard out) changes nothing in the picture: off =
run exactly; (a) 13240 / 34996 / 13250; (b) (the 9 lines with excursions) 899 / 438 / 438 (long7717:
clamp 0.881 / 1.42 against off 0.930 / 1.66 for mlr / arx, pattern 0.886 / 1.43, 4 samples
clamped); (c) as above.

CONCLUSION.  Neither policy is better on every kind: the clamp halves the error where an unseen
source makes the models extrapolate wrongly (a: clamp better on 8 of 12 lines, off on 4), and
costs up to 8x where the test carries a linear physical law on to a warmer level or an input is
a little out (b, c: off better on 8 lines, clamp never by more than 1 %).  The rule ``pattern``,
which reads only the training inputs and the stream, matched the better policy pooled on every
kind, on the decide and the confirm half alike: in (a) it clamps 419-477 of the 520-577 samples
(the unseen source moves the sensors off the training pattern), in (b) and (c) 0-4 (a warmer
machine, an ambient a little out, stay on it).

SHIPPED (2026-11-29, branch fix/pattern49): the rule is the clamp policy's default
(``promote.envelope.pattern=true``; ``false``: every excursion, the ``clamp`` column), in the
stream and in the exported Simulator, C and ST alike.  Re-run with the shipped code
(``monitor.adaptive=true``; the ``pattern`` column now replays the default, the ``clamp`` column
``pattern=false``, its cached replays checked fresh on mill7717 mlr and spindel lagbank: equal):
every ``pattern`` figure of the table above is what the default gives, to the digits shown (mill7717
mlr 8.30 with 1 sample clamped, mill4253 8.42 with 0; spindel lagbank 0.0476 with 0 clamped: its
three sensors' pattern spans all three inputs, so nothing leaves it; pooled (a) 13168, (b) 905, (c)
1635).  CPU: 157 s user for the 51 replays of the default (fits and other replays cached).

Then changed by the lead before the merge: where the pattern spans every input (the spindel
workbook's three sensors) the gate passed every excursion, a sensor 30 K out too; there every
excursion is clamped now (``Envelope`` has no basis), so spindel lagbank is 0.373 again (RMSE 0.611
µm, replayed after the change) and (c) pools as ``clamp``; the mill (52 inputs, a pattern of rank 18
and 16) and cms (20 inputs, rank 10) lines keep their gate, checked on the deployed envelopes.

Session 54 (back in range the clamp's limit is the last excess's, so that a one-row spike's memory
is taken out as it decays: ``streaming.py``, bench_deploy_faults.py): the excursion lines re-run
before and after on the same fits (``--root`` copies of /tmp/cd49's fits, ``monitor.adaptive=true``),
``lagbank`` clamp / pattern: cms3141 937.5 / 942.5 -> 937.3 / 942.3, cms5003 1324 / 1320 -> 1335 /
1332, cms4253 590.9 / 591.9 -> 590.1 / 591.1, cms6007 1145 / 1152 -> 1145 / 1151, mill7717 520.8 /
292.1 -> 520.8 / 292.4, long7717 0.1666 / 0.1515 -> 0.1691 / 0.1515, fl_90_10 120.4 / 120.3 ->
120.1 / 120.3, spindel 0.3734 both; ``arx`` (cms, mill7717, long7717) and ``mlr`` (static: nothing to
remember) unchanged to the digits shown.  Pooled (a) lagbank pattern 4006 -> 4016 (+0.25 %): a real
excursion's last excess is small, so is what its bound then takes out.  CPU: 383 s user for the
27 lines after (fits cached).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import shutil
from pathlib import Path

import numpy as np

from thermocomp.shell.cli import main as thermocomp_main

FAMILIES = ("mlr", "arx", "lagbank")
POLICIES = ("clamp", "off", "pattern")
# the replay overrides of each column: the clamp of every excursion, off, the shipped default
OVERRIDES = {"clamp": ["promote.envelope.policy=clamp", "promote.envelope.pattern=false"],
             "off": ["promote.envelope.policy=off"], "pattern": []}
SUMMER = {f"K{k:02d}": "test" for k in range(10, 17)}          # ambient 27-33 °C
OTHERS = {k: "train" for k in ("K03", "K06", "K09", "K18", "K21", "K24")}
YEAR_SPLIT = "data.split_overrides={" + ",".join(f"{k}:{v}" for k, v in {**OTHERS, **SUMMER}.items()) + "}"
SPINDEL = ["hydra.searchpath=[file:///tmp/lab48/o/conf]", "data=spindel"]


def records(root: Path) -> dict[str, tuple[str, list[str], tuple | None]]:
    """name -> (kind, data overrides, (scenario, seed) to simulate or None).  Written down before
    any measurement (kinds: a unseen source, b hotter/colder test, c measured)."""
    d = root / "data"
    recs = {}
    for s in (3141, 5003, 4253, 6007):
        recs[f"cms{s}"] = ("a", [f"data.path={d}/cms{s}"], ("column_moving_source", s))
    for s in (7717, 4253):
        recs[f"mill{s}"] = ("b", [f"data.path={d}/mill{s}/train_week.csv", "data.test_fraction=0.1"],
                            ("large_mill_week", s))
        recs[f"long{s}"] = ("b", [f"data.path={d}/long{s}", "data.reference=none"], ("long_record", s))
        recs[f"swiss{s}"] = ("b", [f"data.path={d}/swiss{s}"], ("swiss_lathe_door", s))
        recs[f"swissone{s}"] = ("b", [f"data.path={d}/swissone{s}/calibration.csv", "data.test_fraction=0.1"],
                                ("swiss_lathe_door", s))
    for s in (5003, 4253):
        recs[f"year{s}"] = ("b", [f"data.path={d}/year{s}", YEAR_SPLIT], ("yearround_spindle", s))
    recs["fl_90_10"] = ("c", ["data=fl_thermal"], None)
    recs["fl_60_20_20"] = ("c", ["data=fl_thermal", "data.split_order=[train,test,val]",
                                 "data.test_fraction=0.2", "data.val_fraction=0.2"], None)
    recs["spindel"] = ("c", SPINDEL, None)
    return recs


DECIDE = ("cms3141", "cms5003", "mill7717", "long7717", "year5003", "swiss7717", "swissone7717", "fl_90_10")
ONE_FILE = {"mill": "train_week.csv", "swissone": "calibration.csv"}   # a lab's one file: the train campaign


def cli(*args: str) -> None:
    with contextlib.redirect_stdout(io.StringIO()):
        code = thermocomp_main(["-q", *args])
    if code not in (0, None):
        raise RuntimeError(f"thermocomp {' '.join(args)} exited {code}")


def simulate(root: Path, name: str, scenario: str, seed: int) -> None:
    """The scenario into ``data/<name>``; a one-file record (``ONE_FILE``): its train campaign's
    file alone into ``data/<name>`` (from the scenario simulated into ``data/<scenario><seed>``)."""
    d = root / "data"
    prefix = name.rstrip("0123456789")
    if (d / name).exists():
        return
    full = d / name
    if prefix in ONE_FILE:                        # the train campaign alone, as a lab's one file
        full = d / f"{scenario}{seed}"
    if not full.exists():
        cli("simulate", f"sim={scenario}", f"seed={seed}", f"data.path={full}", "track=false")
    if prefix in ONE_FILE:
        (d / name).mkdir(parents=True)
        shutil.copy(full / ONE_FILE[prefix], d / name / ONE_FILE[prefix])


def measure(root: Path, name: str, kind: str, data: list[str], fam: str, adaptive: str) -> dict:
    fit = root / "fit" / f"{name}-{fam}"
    if not (fit / "model.pkl").exists():
        cli("run", *data, f"model={fam}", f"out={fit}", "plots=none", "eval.mutual_prediction=false",
            "track=false")
    row = {"record": name, "kind": kind, "family": fam, "adaptive": adaptive}
    for pol in POLICIES:
        # "pattern" was a prototype monkeypatched in here; "default" is the shipped rule
        out = root / "replay" / f"{name}-{fam}-{'default' if pol == 'pattern' else pol}-{adaptive}"
        if not (out / "replay.json").exists():
            cli("replay", *data, f"replay.model={fit / 'model.pkl'}", *OVERRIDES[pol],
                f"monitor.adaptive={adaptive}", "track=false", f"out={out}")
        t = json.loads((out / "replay.json").read_text())["targets"]
        row[pol] = sum(v["rmse"] ** 2 for v in t.values())
        row["run"] = sum(v["rmse_batch"] ** 2 for v in t.values())
        row["targets"] = {k: {"run": v["rmse_batch"], pol: v["rmse"]} | row.get("targets", {}).get(k, {})
                          for k, v in t.items()}
        if pol == "pattern":
            row["clamped_pattern"] = max(v.get("clamped_samples", 0) for v in t.values())
        if pol == "clamp":
            row["clamped"] = max(v.get("clamped_samples", 0) for v in t.values())
            row["n"] = max(v["n_samples"] for v in t.values())
    return row


def table(rows: list[dict]) -> str:
    cols = ("run", "clamp", "off", "pattern")
    lines = [f"{'record':12} {'model':8} {'half':7} {'clamped':>11} " + " ".join(f"{c:>8}" for c in cols)
             + "  pattern clamps"]
    for r in rows:
        half = "decide" if r["record"] in DECIDE else "confirm"
        lines.append(f"{r['record']:12} {r['family']:8} {half:7} {r['clamped']:>5}/{r['n']:<5} "
                     + " ".join(f"{r[c]:8.4g}" for c in cols) + f"  {r['clamped_pattern']:>5}")
    lines.append("pooled Σ² (lines where one policy is lower than the other by > 1 %):")
    for kind in "abc":
        for half in ("decide", "confirm", "all"):
            sel = [r for r in rows if r["kind"] == kind
                   and (half == "all" or (r["record"] in DECIDE) == (half == "decide"))]
            if not sel:
                continue
            s = {k: sum(r[k] for r in sel) for k in cols}
            cw = sum(r["clamp"] < 0.99 * r["off"] for r in sel)
            ow = sum(r["off"] < 0.99 * r["clamp"] for r in sel)
            best = sum(r["pattern"] <= 1.01 * min(r["clamp"], r["off"]) for r in sel)
            out = [r for r in sel if r["clamped"]]       # scale-free: mean log ratio to run
            gm = {c: float(np.exp(np.mean([np.log(r[c] / r["run"]) for r in out]))) if out else 1.0
                  for c in cols[1:]}
            lines.append(f"  ({kind}) {half:7} {len(sel):2} lines "
                         + " ".join(f"{c} {s[c]:8.4g}" for c in cols)
                         + f" | clamp<off {cw}, off<clamp {ow}, pattern within 1 % of the better {best}")
            lines.append(f"      {len(out):2} lines with an excursion, geometric mean of Σ²/run: "
                         + " ".join(f"{c} {gm[c]:.3g}" for c in cols[1:]))
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", type=Path, default=Path("/tmp/cd49"))
    ap.add_argument("--only", default=None, help="comma-separated record names")
    ap.add_argument("--families", default=",".join(FAMILIES))
    ap.add_argument("--adaptive", default="true")
    ap.add_argument("--table", action="store_true")
    a = ap.parse_args()
    results = a.root / f"results-{a.adaptive}.jsonl"
    if a.table:
        last = {}                                 # the last measurement of each line
        for x in results.read_text().splitlines():
            r = json.loads(x)
            if "pattern" in r:
                last[r["record"], r["family"]] = r
        rows = sorted(last.values(), key=lambda r: ("abc".index(r["kind"]), r["record"] not in DECIDE,
                                                     r["record"], FAMILIES.index(r["family"])))
        print(table(rows))
        return
    recs = records(a.root)
    names = a.only.split(",") if a.only else list(recs)
    for name in names:
        kind, data, sim = recs[name]
        if sim:
            simulate(a.root, name, *sim)
        for fam in a.families.split(","):
            try:
                row = measure(a.root, name, kind, data, fam, a.adaptive)
            except Exception as exc:  # noqa: BLE001 - a failing line is reported, the others go on
                print(f"{name} {fam}: FAILED {exc}", flush=True)
                continue
            with results.open("a") as f:
                f.write(json.dumps(row) + "\n")
            print(f"{name:12} {fam:8} clamped {row['clamped']}/{row['n']}  run {row['run']:.4g}  "
                  f"clamp {row['clamp']:.4g}  off {row['off']:.4g}  pattern {row['pattern']:.4g} "
                  f"({row['clamped_pattern']} clamped)", flush=True)


if __name__ == "__main__":
    main()
