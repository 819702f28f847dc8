"""Which served rule the exported C's monitor most often does not hold (cmon84, issue 34): the
``NOT_IN_CODE`` rules that fire, and the conformance pack's rows each cuts.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon84.py count [ROOT] [SPEC]
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon84.py compare [ROOT] [SPEC]

``ROOT`` (default ``/tmp/cmon84-bench``); ``SPEC`` (default ``column:8716-8719,trunnion:8720-8721,
lathe:8722-8723,jig:8724-8725``: fresh seeds of this task, none tuned on) names the machines and
their seeds.  ``column``: ``thermocomp simulate sim=column_moving_source``, its test campaigns as
simulated (healthy) and with each of ``_faults.four_faults`` (frozen, jump +2 K, drift +1 K/h,
dropout of a quarter of the rows after the middle) planted from the middle row on the sensor
bench_cmon82's ``_sensor`` names; ``trunnion`` / ``lathe`` / ``jig``: the stranger machines as
bench_mon83 draws them (``bench_stranger82b`` / ``82`` / ``80``'s ``write`` and ``faults``,
``thermocomp init`` once per machine), the faulted record's test campaigns that differ from the
healthy one's.  MLR fitted on the record's train split and deployed adaptive as by default
(``_ccode.deployed_on``), exported with its monitor (``state_space(monitor=True)``); per campaign
the code's numpy mirror (:class:`~thermocomp.apps.deploy.export.Simulator`, equal to the C) run
row by row: each ``NOT_IN_CODE`` rule's first row, and the conformance pack's cut (its rows less
those kept; the planted copies of the pack not counted) put on the campaign's first rule.

``count`` changes nothing; the rule the code holds next is the one that cuts the most rows.  The
served monitor is not changed, so no bar: the code is measured against it (``compare``).

Counted (2026-12-04, sources of main at bf78019c, ``count`` with the defaults; 463 s CPU of the
bench process with the 10 draws, ``init`` and the fits): 50 campaigns (10 records x healthy + 4
faults; one test campaign each), 100800 rows, the pack cut 11788 of them.  Per rule not in the
code, the campaigns it fires in and the rows the pack cuts from the campaign's first flag on:

| rule | fires in (first in) | pack rows cut | where |
|---|---|---|---|
| MISSING_BLIND | 6 (6) | 4800 | every stranger dropout: MUTTER_X / MUTTER_Z, no other predicts them |
| BLIND | 4 (4) | 4734 | trunnion and jig frozen PINOLE (no other predicts it): its freeze |
| DRIFT | 5 (5) | 940 | column dropout, T_front1 out (709: s8719); s8718 frozen (231) |
| SECOND | 1 (1) | 710 | column s8716 frozen: a second sensor out |
| STEPPED | 2 (2) | 604 | column s8717 / s8719 drift |

Per campaign (rows, cut, first row of each rule): column 8716-8719 healthy, jump and drift (but
the two STEPPED) no flag; the dropout flags DRIFT at row 733/734 on all four (cut 0, 0, 0, 709:
the served monitor vetoes, or as s8719 takes out T_right4 and declares a new thermal state);
trunnion 8720-8721, lathe 8722-8723, jig 8724-8725: healthy, jump and drift no flag, the dropout
refused at its first missing row (``MISSING_BLIND``, 600 rows cut of 1800, 1200 of the jig's 3598),
the frozen PINOLE flagged ``BLIND`` where the served monitor excludes it (trunnion 1099 / 1335,
jig 1816: 702, 466, 1783, 1783 rows cut; the lathe's frozen SPINDELKASTEN, predicted by others,
is in the code).  The two leading rules are one served rule: a sensor no other predicts, every
other in, out for an instant fault (a dropout, a freeze), held at its last reading, its fallback
model served while it is out.

So both are now in the code (watch.py, watch_c.py: ``blind_drop``), the served arithmetic alike:
such a sensor, every other in, out for a dropout or a freeze (the code held only one the others
predict), held at its last reading while the model reads it, its fallback model served while it is
out (after a dropout not once it reads again: the served ``_fallen_back``), re-admitted after a
calm window where no band judges it.  No new operator: the set with it out is one of the
one-out operators the code holds.  The served monitor is unchanged (no bar: C = served is the
check).

Scored (2026-12-04, ``compare``: per campaign the compiled C, gcc -std=c99 -Wall -Wextra -Werror
-O2, of the same deployed model "before", its monitor's arrays without ``blind_drop`` -- an export
before cmon84, which refuses / flags as main's code: its pack rows equal ``count``'s on main,
row for row -- and "now"; CPU of the bench process 229.9 s for trunnion 8720-8721 + lathe 8723,
65.3 s lathe 8722 (run on the dropout half of the rule: its frozen sensor the others predict,
the freeze half not met), 327.8 s jig 8724-8725, the column's process stopped after its 20
campaigns).  E_* RMSE not printed: where C = served on every row it is the served model's.
Before -> now, the rows where C = served (every target within 1e-9 µm, over the rows the C takes:
before, ``stream`` stops at the refused row), the largest |C - served| over them, the first flag,
the pack's rows kept; the changed campaigns:

| campaign | rows C = served | max abs(C - served), µm | first flag | pack rows |
|---|---|---|---|---|
| trunnion s8720 frozen | 1098 -> 1800 | 6.9 -> 1.4e-14 | BLIND@1099 -> none | 1098 -> 1800 |
| trunnion s8720 dropout | 1200 -> 1800 | 1.4e-14 -> 2.1e-14 | MISSING_BLIND@1201 -> none | 1200 -> 1800 |
| trunnion s8721 frozen | 1334 -> 1800 | 2.5 -> 1.4e-14 | BLIND@1335 -> none | 1334 -> 1800 |
| trunnion s8721 dropout | 1200 -> 1800 | 1.4e-14 -> 1.4e-14 | MISSING_BLIND@1201 -> none | 1200 -> 1800 |
| lathe s8722 dropout | 1200 -> 1800 | 1.1e-14 -> 1.1e-14 | MISSING_BLIND@1201 -> none | 1200 -> 1800 |
| lathe s8723 dropout | 1200 -> 1800 | 1.1e-14 -> 1.1e-14 | MISSING_BLIND@1201 -> none | 1200 -> 1800 |
| jig s8724 frozen | 1815 -> 3598 | 5.2 -> 1.8e-14 | BLIND@1816 -> none | 1815 -> 3598 |
| jig s8724 dropout | 2398 -> 3598 | 1.8e-14 -> 1.8e-14 | MISSING_BLIND@2399 -> none | 2398 -> 3598 |
| jig s8725 frozen | 1815 -> 3598 | 11 -> 2.5e-14 | BLIND@1816 -> none | 1815 -> 3598 |
| jig s8725 dropout | 2398 -> 3598 | 1.2e-14 -> 1.8e-14 | MISSING_BLIND@2399 -> none | 2398 -> 3598 |

Every other campaign (the 20 column ones, each machine's healthy, jump and drift, the lathe's
frozen SPINDELKASTEN) as before, digit for digit.  Over the 50: C = served on every row of
45 (before 35), on 100648 of 100800 rows (before 91114); the pack keeps
98546 rows (before 89012, ``count``'s 89012); campaigns flagged 18 -> 8.
The C now equals the served corrections on every row of each of the 10 (a dropout's C before
took no row after the refused one, a freeze's parted by up to 11 µm).

What remains (flagged as before, ``count``'s order): a drift beyond the band with a sensor out
already (``DRIFT``, 940 rows: the column's T_front1 dropout, s8719 where the served monitor
takes out T_right4 as a second sensor and the field follows it; needs the POD operator of any
set with two out, n (n - 1) / 2 more n x n, or a k x k solve in the C at run time, and the
second sensor out), ``SECOND`` (710) and ``STEPPED`` (604); and of this rule's kin a jump of such
a sensor while it is out (``BLIND``: the served return may undo it, ``Readmission._readmit``).
"""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import made_folder, run_commands, seed_list  # noqa: E402

SPEC = "column:8716-8719,trunnion:8720-8721,lathe:8722-8723,jig:8724-8725"
FAULTS = ("frozen", "jump", "drift", "dropout")
STRANGERS = {"trunnion": "bench_stranger82b", "lathe": "bench_stranger82", "jig": "bench_stranger80"}


def _config(data: Path, given: tuple = ()):
    from hydra import compose, initialize_config_dir

    from thermocomp.base.paths import conf_dir

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=[f"data.path={data}", "track=false",
                                                        "model=mlr", *given])


def _deployed(data: Path, given: tuple = ()):
    from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
    from thermocomp.shell.source import read_streamed

    cfg = _config(data, given)
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {k: ds.campaigns[k] for k in train_ids}
    deployed = deployable(cfg, deploy_stream(cfg, build_compensator(cfg, ds=ds).fit(train), train),
                          train, ds)
    return deployed, {t: ds.campaigns[t].reset_index(drop=True) for t in test_ids}


def _tests(data: Path, given: tuple = ()) -> dict:
    from thermocomp.shell.source import read_streamed

    ds, _, test_ids, _ = read_streamed(_config(data, given))
    return {t: ds.campaigns[t].reset_index(drop=True) for t in test_ids}


def _column_faults(frame, sensor: str) -> dict:
    """``{kind: frame}``: ``four_faults`` planted on ``sensor`` from the middle row."""
    from _faults import four_faults

    n, half = len(frame), len(frame) // 2
    period = float(np.median(np.diff(frame["time"].to_numpy(float))))
    cases = four_faults(n, period, frozen=(sensor, half), jump=(sensor, half),
                        drift=(sensor, half), dropout=(sensor, half, half + max(1, (n - half) // 4)))
    out = {}
    for kind, (_, change) in cases.items():
        df = frame.copy()
        df[sensor] = change(df[sensor].to_numpy(float))
        out[kind] = df
    return out


def flagged(ss, frame) -> list[tuple[int, str]]:
    """``(row, rule)`` (1-based) of each rule the code's monitor flags not in the code, its first
    row, in order; a refused sample named by its rule."""
    from thermocomp.apps.deploy.export import Simulator
    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE, RULES

    sim = Simulator(ss)
    sim.reset()
    seen: dict[str, int] = {}
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        sim.step(u, t)
        w = sim.watch
        if w.flags & NOT_IN_CODE or sim.refused:
            seen.setdefault(RULES[w.missed or w.rule], i + 1)
    return sorted(((r, k) for k, r in seen.items()))


def scored(deployed, tests: dict, label: str) -> list[tuple]:
    """Per campaign ``(label, campaign, rows, rows cut, flags)``."""
    from thermocomp.apps.deploy.export import state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack

    ss = state_space(deployed, monitor=True)
    if not ss.monitor:
        return [(label, t, len(df), 0, [("NO MONITOR", 0)]) for t, df in tests.items()]
    _, summary = conformance_pack(deployed, ss, tests, script=False)
    kept = {e["campaign"]: e["rows"] for e in summary["campaigns"] if "planted" not in e}
    return [(label, t, len(df), len(df) - kept[str(t)], flagged(ss, df))
            for t, df in tests.items()]


def _column(root: Path, seed: int):
    """``(deployed, test campaigns, label)`` of a ``column_moving_source`` draw, as simulated
    and with each fault."""
    from bench_cmon82 import _sensor

    from thermocomp.apps.deploy.export import state_space
    from thermocomp.shell.cli import main

    data = root / f"column-{seed}"
    if not (data / "campaigns.csv").is_file():
        assert main(["-q", "simulate", f"seed={seed}", f"data.path={data}", "track=false",
                     "sim=column_moving_source"]) == 0
    deployed, tests = _deployed(data)
    sensor = _sensor(state_space(deployed, monitor=True))
    yield deployed, tests, f"column s{seed} healthy"
    planted = {t: _column_faults(df, sensor) for t, df in tests.items()}
    for kind in FAULTS:
        yield deployed, {t: p[kind] for t, p in planted.items()}, f"column s{seed} {kind} {sensor}"


def _stranger(root: Path, name: str, seed: int):
    """``(deployed, test campaigns, label)`` of a stranger machine's record, healthy, then each
    faulted record's campaigns that differ from the healthy one's (the same model)."""
    from bench_mon77 import thermocomp

    bench = __import__(STRANGERS[name])
    data = root / "data"
    conf = data / f"init_{name}"
    if not (data / f"fault_dropout_{seed}").exists() or not (data / f"{name}{seed}").exists():
        bench.write(str(data), str(seed))
        bench.faults(str(data), str(seed))
    if not (conf / "conf").exists():
        thermocomp("init", str(data / f"{name}{seed}"), f"out={conf}")
    cfg = next((conf / "conf" / "data").glob("*.yaml")).stem
    given = (f"hydra.searchpath=[file://{conf}/conf]", f"data={cfg}")
    deployed, tests = _deployed(data / f"{name}{seed}", given)
    yield deployed, tests, f"{name} s{seed} healthy"
    for kind in FAULTS:
        faulted = _tests(data / f"fault_{kind}_{seed}", given)
        yield deployed, {t: df for t, df in faulted.items()
                         if t not in tests or not df.equals(tests[t])}, f"{name} s{seed} {kind}"


def _records(root: Path, name: str, seed: int):
    return _column(root, seed) if name == "column" else _stranger(root, name, seed)


def _c_rows(binary: Path, frame, inputs: list) -> np.ndarray:
    """The corrections the compiled ``stream`` prints for ``frame``'s rows, up to a row it refuses
    (``stream.c`` stops there, exit 2)."""
    import io
    import subprocess

    import pandas as pd

    text = frame[["time", *inputs]].to_csv(index=False, float_format="%.17g")
    run = subprocess.run([str(binary)], input=text, text=True, capture_output=True)
    return pd.read_csv(io.StringIO(run.stdout)).to_numpy(float) if run.stdout.strip() else (
        np.empty((0, 0)))


def _before(ss):
    """``ss`` as exported before cmon84 (no ``blind_drop``: a blind sensor's missing reading
    refused)."""
    import dataclasses

    return dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items()
                                            if k != "blind_drop"})


def measured(deployed, tests: dict, label: str, folder: Path) -> list[str]:
    """Per campaign, before (an export without ``blind_drop``) and now: the rows where the
    compiled C equals the served corrections (every target within 1e-9 µm), the largest
    |C - served| over the rows C gives, the first flag, the pack's rows kept."""
    from _ccode import built

    from thermocomp.apps.deploy.export import c, state_space
    from thermocomp.apps.deploy.export.driver import DRIVER
    from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
    from thermocomp.apps.deploy.report import stream_rows

    now = state_space(deployed, monitor=True)
    if not now.monitor:
        return [f"{label}: no monitor in the code"]
    said = {}
    for name, ss in (("before", _before(now)), ("now", now)):
        code = built(folder / name, {"compensator.h": c.header(ss), "compensator.c": c.source(ss),
                                     "stream.c": DRIVER})
        _, summary = conformance_pack(deployed, ss, tests, script=False)
        kept = {e["campaign"]: e["rows"] for e in summary["campaigns"] if "planted" not in e}
        for t, df in tests.items():
            want = corrections(ss, stream_rows(deployed, df, t).y)
            got = _c_rows(code, df, ss.inputs)
            gap = np.abs(got - want[:len(got)]).max(axis=1) if len(got) else np.zeros(0)
            first = flagged(ss, df)
            said.setdefault(t, []).append(
                (int((gap < 1e-9).sum()), float(gap.max()) if len(gap) else float("nan"),
                 f"{first[0][1]}@{first[0][0]}" if first else "none", kept[str(t)], len(df)))
    out = []
    for t, ((s0, g0, f0, k0, n), (s1, g1, f1, k1, _)) in said.items():
        out.append(f"{label} {t}: C = served {s0} -> {s1} of {n} rows; max|C - served| "
                   f"{g0:.2g} -> {g1:.2g} um; first flag {f0} -> {f1}; pack rows {k0} -> {k1}")
    return out


def compare(root: str = "/tmp/cmon84-bench", spec: str = SPEC) -> None:
    """Before / now per campaign (:func:`measured`) on the records :func:`count` draws."""
    import tempfile

    folder = made_folder(root)
    for part in spec.split(","):
        name, seeds = part.split(":")
        for seed in seed_list(seeds):
            for deployed, tests, label in _records(folder, name, seed):
                with tempfile.TemporaryDirectory(prefix="cmon84-") as tmp:
                    print("\n".join(measured(deployed, tests, label, Path(tmp))), flush=True)


def count(root: str = "/tmp/cmon84-bench", spec: str = SPEC) -> None:
    folder = made_folder(root)
    rows: list[tuple] = []
    for part in spec.split(","):
        name, seeds = part.split(":")
        for seed in seed_list(seeds):
            got = [r for d, tests, label in _records(folder, name, seed)
                   for r in scored(d, tests, label)]
            for label, t, n, cut, flags in got:
                print(f"{label} {t}: {n} rows, cut {cut}; "
                      f"{', '.join(f'{k}@{r}' for r, k in flags) or 'no flag'}", flush=True)
            rows += got
    fired, first, cuts = Counter(), Counter(), Counter()
    for _, _, _, cut, flags in rows:
        fired.update(k for _, k in flags)
        if flags:
            first[flags[0][1]] += 1
            cuts[flags[0][1]] += cut
        elif cut:
            cuts["(no flag)"] += cut
    total = sum(n for _, _, n, _, _ in rows)
    print(f"{len(rows)} campaigns, {total} rows, pack cuts {sum(c for *_, c, _ in rows)}")
    for rule in sorted(set(fired) | set(cuts), key=lambda k: -cuts[k]):
        print(f"{rule}: fires in {fired[rule]} campaigns (first in {first[rule]}), "
              f"cuts {cuts[rule]} rows")


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"count": count, "compare": compare}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
