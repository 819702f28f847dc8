"""The served monitor's two open false exclusions (stop 88, mon88; issue 34's "what remains" ->
monitor): lr9171's healthy ``T_col_back`` kept out 1.73 h after its second spike, and cr9031's
healthy ``T_nc_cabinet`` left out behind a frozen ``T_amb``.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_mon88.py traced ROOT          # the two cases, events and RMSE
    python benchmarks/bench_mon88.py fresh ROOT SEEDS     # fresh records -> ROOT/fresh.json
    python benchmarks/bench_mon88.py compare BEFORE AFTER # two fresh.json side by side
    python benchmarks/bench_mon88.py pack ROOT            # compiled C / mirror against served

``traced``: in ``ROOT`` (made where missing, what an earlier command wrote there kept: review95;
the measured tree's ``conf/`` linked in, ``THERMOCOMP_ROOT``) deploy87's lr9171
(``sim=long_record``, 3 days, ``test_fraction=0.2``: R1b continues R1a; the generator's own spikes
on ``T_col_back``) with ``model=lagbank data.reference=none`` as bench_deploy87 runs it, and
audit86b's cr9031 (``sim=climate_room``, 12 runs of 3-4 h, ``test_fraction=0.25``) with
``model=mlr``, its test campaigns given audit86b's frozen ``T_amb`` (the reading held from a third
of each campaign): ``run`` -> ``replay`` of its ``model.pkl``; the replay's RMSE per target (µm)
and its events.  ``fresh``: per seed of SEEDS a record drawn as :data:`FRESH` says (seeds
9196-9200 long records as lr9171, the generator's spikes left as drawn; 9201-9205 climate rooms as
cr9031 with :func:`planted` faults), ``model=mlr``, ``run`` -> ``replay``; per record the replay
RMSE and the exclusions / re-admissions (sensor, campaign, row) written to ``ROOT/fresh.json``.
``compare``: the two files' records side by side (run with main's src for BEFORE and this tree's
for AFTER; the simulator is not changed).  ``pack``: on lr9171 (MLR, R1b after R1a) and cr9031
with its frozen ``T_amb`` (MLR): the served stream, the numpy mirror and the compiled C (gcc
-Werror) of the export with and without this stop's two keys (``undo``, ``cleared``): rows where C
= served (every target within 1e-9 µm), the first flag, the conformance pack's rows.

Traced (main d76bdde2)
----------------------
lr9171 (lagbank, R1b): ``T_col_back`` (the others predict it: ``predictable``; its warning band
0.763 °C, the re-admission band half of it, 0.381) reads within +0.02 °C of its field before
its first spike.  At 18540 s it reads 3.45 °C low for 3 samples: a jump, re-referenced by its
step less its change as the others predict it (``_instant``), excluded; its return at 18720 s a
second jump, re-referenced by the whole step (out, it is judged by no one: no expected change).
The two re-references do not cancel: the reference moved 18.070 -> 18.346 °C (the others'
one-sample prediction noise and the true change over the outage kept with it), its error
against the field from +0.02 to about -0.33 °C for good.  It came back at 19980 s (21 calm
samples: the half band let it in only when the noise allowed).  At 45540 s a 1-sample +3.79 °C
spike: the same two jumps move the reference another +0.112 °C (18.458), its error -0.35 to
-0.47 °C against the 0.381 half band, never within it for a window: out to the record's end
(1.73 h).  The undo of a spike's jumps at return (``_readmit``) was only for a sensor no other
predicts (the reading nearer its last good value); for one the field predicts nothing undid it.

cr9031 (mlr; test C11, a room ramped -5 K): ``T_amb`` frozen from row 68; its error grows with
the field, ``T_nc_cabinet``'s mirrors it (each is the other's only predictor: a coupled pair).
At 5040 s ``T_amb`` +0.43 °C (band 0.40), ``T_nc_cabinet`` -0.35 °C within its band; the freeze
rule needs the field 0.40 °C on, it had moved 0.39.  The pick (``_lone_fault``): paper 002's
culprit ``T_nc_cabinet`` (within its band: ``_hid``), ``T_amb`` out with it as its blind partner.
Its return (``_pass_once_back``): with ``T_amb`` out no sensor predicts ``T_nc_cabinet``, and a
sensor the others predict with every sensor in never passes blind; ``T_amb``, frozen (its run
16 -> 137 samples, past ``blind_run`` 10), never comes back: ``T_nc_cabinet`` out to C11's end.
The same shape as test_monitor_frozen_pair77's record (``T_b`` out with the frozen ``T_a``).

The rules (served ``readmission.py``, the numpy mirror ``watch.py``, the C ``watch_c.py``)
-----------------------------------------------------------------------------------------
(A, refused: mon88_rule.patch) ``_field_undoes``: a due sensor the others predict, out for
jumps, takes back the reference it had before the first of them (``_ref0``) where the mean of
its window's errors against the active sensors' field is nearer zero with the jumps undone than
kept; the field tells a spike (the reading returned) from a step that stays, as the last good
reading does for a sensor no other predicts. (B) ``_blind_for_frozen``: a sensor out by the
field's judgement, blind in the re-admission trial only for want of a partner that is out and
frozen by the rule for a sensor no other predicts (constant longer than ``blind_run``), passes:
what it was blamed for is the partner's. Mirror and C: the same, behind the export keys ``undo``
/ ``cleared`` (absent: as before); the C keeps ``mon_ref0`` (A's, in the patch only). Work:
O(window) per due sensor, a solve per frozen partner at a re-admission check.

Bar (written before scoring the fresh seeds; the two cases were traced and run on this tree
first)
------
1. lr9171 (lagbank): ``T_col_back`` back after each spike within its calm window (``window``
   = 10 samples) plus ``confirm`` (2) of the spike's end (the lead's "within confirm samples of
   the fault's end" cannot hold for any rule that keeps the calm window a jump-excluded sensor
   waits: said); out at R1b's end: none.  cr9031 (mlr, frozen ``T_amb``): ``T_nc_cabinet`` back
   within window + confirm samples of its exclusion while ``T_amb`` stays out (the fault does
   not end in C11; "never out" would need a change of the pick, mon84b / mon86b's refused
   ground).
2. Fresh 9196-9205: every exclusion main makes of a faulty sensor (the climate rooms' planted
   ``T_amb`` and spiked sensor; on the long records each sensor main excludes for a "jump", the
   generator's spikes) made by the tree at the same campaign and time (no detection lost); no
   record's replay RMSE (mean over targets) worse than main's by more than 2 %.
3. Healthy records quiet: tests/shell/test_monitor_healthy53.py and the healthy tests of
   tests/apps/test_monitor*.py pass; every monitor / export test passes (run in parts, -n 2).
4. ``pack``: C = served on every row of lr9171's R1b and cr9031's frozen test campaigns where
   main's C was, and the pack not cut earlier than on main.
KEPT if 1-4 hold; else REFUSED (src reverted, mon88_rule.patch).

Scored: rules A + B (2026-12-04, fix/mon88 at 369929b4's src; main = d76bdde2's src, the same
draws; CPU s of the bench process, 2 cores shared by several helpers)
------
1. ``traced``: lr9171 (lagbank) replay E_Z 0.7845 -> 1.0464 µm (run scores 1.053: deployed =
   scored now); ``T_col_back`` out 18540 s, back 19980 -> 19320 s (10 samples after the spike's
   end at 18720), out 45540 s, back never -> 46200 s (10 samples after 45600), "its 2 jump(s)
   undone"; nothing out at R1b's end (main: ``T_col_back``).  cr9031 (mlr, frozen ``T_amb``):
   E_X / E_Z 2.2553 / 4.0631 -> 2.2061 / 4.0247 µm; ``T_nc_cabinet`` out 5040 s, back never ->
   5700 s (11 samples), ``T_amb`` out to the end.  MET.
2. ``fresh`` 9196-9205 (``compare``; RMSE mean over targets, µm, main -> tree): lr9196 1.0451 =,
   lr9197 1.7626 =, lr9198 1.8510 =, lr9199 0.9303 -> 0.9897 (+6.38 %), lr9200 1.2934 =, cr9201
   1.2311 -> 1.2514 (+1.65 %), cr9202 2.2088 -> 2.2069, cr9203 2.8231 -> 2.8806 (+2.04 %), cr9204
   2.4425 -> 2.4414, cr9205 1.3856 -> 1.3881 (+0.18 %); no exclusion lost (24 of 24 at the same
   campaign and time), re-admissions at main's times but cr9202's ``T_toolholder1`` (C12 9840 ->
   8100 s).  Two records worse by > 2 %: FAILS.  Every change is rule A's (the reference put
   back at a re-admission main makes at the same time; B fired on none of them).  lr9199's run
   (raw readings) scores 1.0479: main's kept offsets served better than the true readings.
4. ``pack``: C = served on every row on main and with A + B (lr9171 R1b 864 of 864, 8.5e-14 µm;
   cr9031 C10 / C11 / C12 whole, <= 8.3e-14 µm); without the two keys the tree's C parts from
   its served at R1b's row 333 and C11's row 96 (the keys are needed).  MET.
Verdict on A + B: REFUSED by item 2 (benchmarks/mon88_rule.patch: served, mirror, C).

Second rule: B alone (the bar written after A + B was scored, before B alone was; the same
fresh seeds, on which B fired on no record under A + B: said)
------
(B1) cr9031 as item 1 says; lr9171 not mended (A's gap, a strict xfail in
tests/shell/test_monitor_readmit88.py); (B2) fresh 9196-9205 as item 2; (B3) = 3; (B4) = 4 on
cr9031.  KEPT if B1-B4 hold.

Scored: B alone (2026-12-04, fix/mon88 at 3dba4e5a's src; ``fresh /tmp/mon88/fr-B 9196-9205``,
``traced``, ``pack``; main's figures the runs above)
------
B1. cr9031 (mlr, frozen ``T_amb``): replay E_X / E_Z 2.2553 / 4.0631 -> 2.2061 / 4.0247 µm;
    ``T_nc_cabinet`` out at C11's 5040 s, back never -> 5700 s (11 samples <= window + confirm
    = 12: "no detector fired for 11 samples; the others in do not predict it without a partner
    that is out frozen"), ``T_amb`` out to the end; C10's freeze and C12 as on main.  lr9171 as
    on main (0.7845 µm, ``T_col_back`` out from 45540 s to the end: A's gap, the strict xfail).
    MET (cr9031; lr9171 left, as the second bar says).  test_monitor_frozen_pair77's record:
    ``T_b`` back 10 samples after it went out with the frozen ``T_a`` (the strict xfail asks it
    never out: still a gap).
B2. fresh 9196-9205: every record's replay RMSE equal to main's (ratio 1.0000 on all ten), 24 of
    24 exclusions and every re-admission at main's campaign and time: B fired on none.  On
    cr9201's C12 ``T_amb`` goes out for its freeze (4740 s) and the planted 1-sample spike on
    ``T_nc_cabinet`` (7680 s) takes that sensor out for a jump, blind behind the frozen
    ``T_amb``: out to the end on both trees (B asks an exclusion by the field's judgement; a
    jump's return blind is A's ground).  MET.
B3. tests (-n 2, OMP_NUM_THREADS=1, in parts): tests/shell/test_export*.py 133 + 132 passed (with
    test_export_mon88.py); tests/shell/test_monitor*.py (healthy53 among them) + faults71 /
    keysight70 / lab75 / lab_export53 / bits85 / data86b / replay / adaptive_deploy /
    test_benchmarks_cli 595 passed, 3 xfailed (two known, readmit88's lr9171 strict xfail);
    tests/apps/test_monitor*.py + sensor_fallback71 / deployed_as_scored44 / warm_batch59 + this
    stop's two files 120 passed, 2 xfailed.  The new tests fail on d76bdde2 (readmit88's partner
    test, export_mon88's C test; their controls pass on both).  MET.
B4. ``pack`` (``pack /tmp/mon88/pack-B``): cr9031 C10 / C11 / C12 C = served on every row (186 /
    206 / 239, <= 8.2e-14 µm), pack whole; the export without ``cleared`` parts from this
    served at C11's row 96 (pack 95 rows): the key is needed.  lr9171 R1b 864 of 864 either
    way.  gcc -Werror builds.  MET.
CPU: replay of cr9031 1.3 s (main 1.4 s); the check runs only for a blind sensor due back.
Verdict: rule A REFUSED (mon88_rule.patch, A + B as scored); rule B KEPT by its second bar.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import project_root, run_commands, seed_list  # noqa: E402
from bench_deploy87 import stage  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

LONG = ("sim=long_record", "sim.generator.duration_days=3.0", "sim.generator.test_fraction=0.2")
ROOM = ("sim=climate_room", "sim.generator.n_runs=12", "sim.generator.duration_h=[3.0,4.0]",
        "sim.generator.test_fraction=0.25")
TRACED = {"lr9171": (9171, LONG, ("model=lagbank", "data.reference=none"), False),
          "cr9031": (9031, ROOM, ("model=mlr",), True)}
FRESH = {**{seed: ("lr", LONG, ("data.reference=none",)) for seed in range(9196, 9201)},
         **{seed: ("cr", ROOM, ()) for seed in range(9201, 9206)}}


def _root(word: str) -> Path:
    """The scratch project root (:func:`_cli.project_root`: made where missing, what an earlier
    command wrote there kept; until review95 it was made anew)."""
    return project_root(word)


def _tests(data: Path) -> list[str]:
    manifest = pd.read_csv(data / "campaigns.csv")
    return list(manifest.loc[manifest["split"] == "test", "file"])


def planted(data: Path, seed: int, frozen: bool = True) -> list[str]:
    """Faults written into the test campaigns of ``data`` (in place): ``T_amb`` held at its
    reading from a third of each (audit86b's frozen sensor; ``frozen``), and one spike of 1-3
    samples, +-2-5 °C, on a monitored sensor drawn at random (not ``T_amb``) two thirds in."""
    rng = np.random.default_rng([seed, 88])
    said = []
    for file in _tests(data):
        df = pd.read_csv(data / file)
        n = len(df)
        if frozen:
            df.loc[n // 3:, "T_amb"] = df.loc[n // 3, "T_amb"]
            said.append(f"{file} T_amb frozen from row {n // 3 + 1}")
        names = [c for c in df.columns if c.startswith("T_") and c != "T_amb"]
        name = names[int(rng.integers(len(names)))]
        row, width = 2 * n // 3, int(rng.integers(1, 4))
        size = float(rng.choice([-1, 1]) * rng.uniform(2.0, 5.0))
        df.loc[row:row + width - 1, name] += size
        said.append(f"{file} {name} {size:+.2f} °C rows {row + 1}-{row + width}")
        df.to_csv(data / file, index=False)
    return said


def replayed(root: Path, name: str, data: Path, model: tuple, extra: tuple) -> dict:
    """``run`` -> ``replay`` of ``data``'s model.pkl: the replay's RMSE per target and events."""
    out = root / "reports" / name
    rc, said = stage("run", f"data.path={data}", f"out={out}", "plots=none", "track=false",
                     *model, *extra)
    assert rc == 0, said
    rc, said = stage("replay", f"data.path={data}", f"out={out}-replay", "track=false",
                     f"replay.model={out / 'model.pkl'}", *extra)
    assert rc == 0, said
    rep = json.loads((out.parent / f"{name}-replay" / "replay.json").read_text())
    return {"rmse": {k: v["rmse"] for k, v in rep["targets"].items()}, "events": rep["events"],
            "excluded": rep["excluded_inputs"]}


def _drawn(name: str, seed: int, sim: tuple, root: Path) -> Path:
    data = root / "data" / name
    rc, said = stage("simulate", f"seed={seed}", *sim, f"data.path={data}", "track=false")
    assert rc == 0, said
    return data


def _traced_data(folder: Path, name: str) -> Path:
    """:data:`TRACED`'s record ``name`` drawn into ``folder`` (cr9031: ``T_amb`` frozen from a
    third of each test campaign, audit86b's fault)."""
    seed, sim, _, frozen = TRACED[name]
    data = _drawn(name, seed, sim, folder)
    for file in _tests(data) if frozen else ():
        df = pd.read_csv(data / file)
        df.loc[len(df) // 3:, "T_amb"] = df.loc[len(df) // 3, "T_amb"]
        df.to_csv(data / file, index=False)
    return data


def traced(root: str) -> None:
    """The two cases (module doc): replay RMSE and every exclusion / re-admission."""
    folder = _root(root)
    for name, (seed, sim, model, frozen) in TRACED.items():
        data = _traced_data(folder, name)
        start = cpu_seconds()
        got = replayed(folder, name, data, model, ("data.reference=none",) if not frozen else ())
        rmse = ", ".join(f"{k} {v:.4f}" for k, v in got["rmse"].items())
        print(f"{name}: replay RMSE {rmse} µm; excluded at the end {got['excluded']}; "
              f"CPU {cpu_seconds() - start:.1f} s", flush=True)
        print_events(got["events"], 120)


def print_events(events: list, width: int) -> None:
    """A replay's sensor events, one a line (the reason cut at ``width``)."""
    for e in events:
        if e.get("sensor"):
            print(f"  {e['campaign']} {e['time']:>7.0f} s {e['sensor']:<14} {e['to']:<9} "
                  f"{e['reason'][:width]}", flush=True)


def drawn_fresh(folder: Path, seed: int, table: dict) -> tuple[str, Path, list, tuple]:
    """``(name, data, faults, overrides)`` of the fresh record ``table[seed]`` names (``(kind,
    sim, overrides)``: ``lr`` as drawn, ``cr`` with :func:`planted`'s faults) drawn into
    ``folder``."""
    kind, sim, extra = table[seed]
    name = f"{kind}{seed}"
    data = _drawn(name, seed, sim, folder)
    faults = planted(data, seed) if kind == "cr" else ["the generator's spikes as drawn"]
    return name, data, faults, extra


def fresh(root: str, seeds: str) -> None:
    """Fresh records (module doc) -> ``ROOT/fresh.json``."""
    folder = _root(root)
    results = {}
    for seed in seed_list(seeds):
        name, data, faults, extra = drawn_fresh(folder, seed, FRESH)
        start = cpu_seconds()
        got = replayed(folder, name, data, ("model=mlr",), extra)
        got.update(faults=faults, cpu=cpu_seconds() - start)
        results[name] = got
        print(f"{name}: {faults}; RMSE {got['rmse']}; {len(got['events'])} events; "
              f"CPU {got['cpu']:.1f} s", flush=True)
    (folder / "fresh.json").write_text(json.dumps(results, indent=1))


def _moves(events: list) -> list[tuple]:
    return [(e["campaign"], e["time"], e["sensor"], e["to"]) for e in events
            if e.get("sensor") and e["to"] in ("excluded", "ok")]


def exclusions_and_returns(before: list, after: list) -> tuple[set, set, list, list]:
    """``(out before, out after, back before, back after)``: (campaign, time, sensor) of the
    exclusions and re-admissions of two runs' events."""
    outs = [{m[:3] for m in _moves(ev) if m[3] == "excluded"} for ev in (before, after)]
    backs = [[m[:3] for m in _moves(ev) if m[3] == "ok"] for ev in (before, after)]
    return outs[0], outs[1], backs[0], backs[1]


def compare(before: str, after: str) -> None:
    """The two ``fresh.json`` side by side: RMSE (mean over targets), exclusions kept / lost,
    samples out (the sensors' excluded time, s)."""
    a = json.loads((Path(before) / "fresh.json").read_text())
    b = json.loads((Path(after) / "fresh.json").read_text())
    print(f"{'record':<8}{'rmse before':>12}{'after':>9}{'ratio':>8}  exclusions (kept / lost)  "
          "re-admissions before -> after")
    for name in a:
        ra, rb = (float(np.mean(list(r[name]["rmse"].values()))) for r in (a, b))
        out_a, out_b, back_a, back_b = exclusions_and_returns(a[name]["events"], b[name]["events"])
        print(f"{name:<8}{ra:>12.4f}{rb:>9.4f}{rb / ra:>8.4f}  {len(out_a & out_b)} / "
              f"{len(out_a - out_b)} (new {len(out_b - out_a)})  {len(back_a)} -> {len(back_b)}; "
              f"out at the end {a[name]['excluded']} -> {b[name]['excluded']}")
        for m in sorted(out_a ^ out_b) + sorted(set(back_a) ^ set(back_b)):
            print(f"    differs: {m}")


def _pack_rows(root: Path, name: str, data: Path, extra: tuple, model: str = "mlr",
               keys: tuple = ("undo", "cleared")) -> list[str]:
    """C / mirror / served on ``data``'s test campaigns, the export with and without the monitor
    ``keys`` (this stop's by default: module doc)."""
    import dataclasses
    import tempfile

    from _ccode import built, deployed_on
    from bench_cmon84 import _c_rows, flagged

    from thermocomp.apps.deploy.export import c, state_space
    from thermocomp.apps.deploy.export.driver import DRIVER
    from thermocomp.apps.deploy.export.pack import conformance_pack, corrections, fed
    from thermocomp.apps.deploy.report import plain, stream_rows
    from thermocomp.core.continuation import lead_ins

    deployed, ds, test_ids = deployed_on(data, model, extra)
    now = state_space(deployed, monitor=True)
    before = dataclasses.replace(now, monitor={k: v for k, v in now.monitor.items()
                                               if k not in keys})
    tests = {t: ds.campaigns[t].reset_index(drop=True) for t in test_ids}
    leads = lead_ins(plain(deployed).compensator, ds, test_ids)
    frames = {t: fed(df, leads.get(t)) for t, df in tests.items()}
    lines = []
    with tempfile.TemporaryDirectory(prefix="mon88-") as tmp:
        for label, ss in ((f"without {' / '.join(keys)}", before), ("with", now)):
            code = built(Path(tmp) / label.split()[0], {
                "compensator.h": c.header(ss), "compensator.c": c.source(ss), "stream.c": DRIVER})
            _, summary = conformance_pack(deployed, ss, tests, leads, script=False)
            kept = {e["campaign"]: e["rows"] - e["lead_in_rows"] for e in summary["campaigns"]}
            for t, df in tests.items():
                frame = frames[t]
                lead = len(frame) - len(df)
                want = corrections(ss, stream_rows(deployed, frame, str(t)).y)[lead:]
                got = _c_rows(code, frame, ss.inputs)[lead:]
                gap = np.abs(got - want[:len(got)]).max(axis=1)
                first = [(r - lead, k) for r, k in flagged(ss, frame) if r > lead]
                lines.append(f"{name} {t} export {label}: C = served {int((gap < 1e-9).sum())} of "
                             f"{len(df)} rows, max |C - served| {gap.max():.2g} µm, first flag "
                             f"{first[0] if first else 'none'}, pack rows {kept[str(t)]}")
    return lines


def pack(root: str) -> None:
    """lr9171 and cr9031 with its frozen ``T_amb`` through the code (module doc)."""
    folder = _root(root)
    for name, (_, _, _, frozen) in TRACED.items():
        data = _traced_data(folder, name)
        start = cpu_seconds()
        lines = _pack_rows(folder, name, data, () if frozen else ("data.reference=none",))
        print("\n".join(lines) + f"\n  CPU {cpu_seconds() - start:.1f} s", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "traced": traced, "fresh": fresh, "compare": compare, "pack": pack,
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
