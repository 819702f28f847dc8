"""A one-sample spike read as a jump: the served monitor re-referenced the sensor at the spike and
again at its return, kept the pair's noise as an offset and held the sensor out a window, so the
deployed lag models read 16-23 % worse than run scored them (stop 89, mon89; deploy88's lr9211).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_mon89.py traced ROOT          # lr9211 / lr9171: run, replay, events
    python benchmarks/bench_mon89.py fresh ROOT SEEDS     # fresh records -> ROOT/fresh.json
    python benchmarks/bench_mon89.py compare BEFORE AFTER # two fresh.json side by side
    python benchmarks/bench_mon89.py pack ROOT            # compiled C / mirror against served
    python benchmarks/bench_mon89.py why ROOT SEED FAMILY # one fresh record row by row

``traced``: in ``ROOT`` (kept; the measured tree's ``conf/`` linked in, ``THERMOCOMP_ROOT``)
deploy88's lr9211 and mon88's lr9171 (``sim=long_record``, 3 days, ``test_fraction=0.2``: R1b
continues R1a; the generator's own spikes) with ``data.reference=none``, per family of
:data:`FAMILIES`: ``run`` -> ``replay`` of its ``model.pkl``; run's and replay's test RMSE (µm,
mean over targets) and the test campaign's events.  ``fresh``: per seed of SEEDS the record
bench_mon88's :data:`~bench_mon88.FRESH` generators draw (9291-9295: long lathe records as
lr9171, the generator's spikes left as drawn; 9296-9300: climate rooms as cr9031 with
:func:`~bench_mon88.planted`'s frozen ``T_amb`` and spike), per family of :data:`FAMILIES`:
``run`` -> ``replay``; run's and replay's RMSE and the exclusions / re-admissions written to
``ROOT/fresh.json``.  ``compare``: the two files row by row (record x family): replay RMSE before
-> after and its ratio, |replay - run| before -> after and their means, exclusions kept / lost /
new, re-admissions (run with main's src for BEFORE and this tree's for AFTER; the simulator is
not changed).  ``pack``: lr9211 (mlr and lagbank, R1b after R1a): the served stream, the numpy
mirror and the compiled C (gcc -Werror) of the export with and without the ``spike`` key; rows
where C = served (every target within 1e-9 µm), the first flag, the conformance pack's rows
(bench_mon88's ``_pack_rows``).  ``why``: the fresh record of SEED (as ``fresh`` draws it)
with FAMILY deployed as promote deploys it, per test campaign: the deployed stream's and the
unmonitored one's RMSE, the rows where they part, the sum of squares and mean residual before
the first event, from it, and per quarter after, and each monitored sensor's reference at the
end against the one it started with (run on main's src and the tree's: main's kept offsets).

Traced (main a0d62dea; lr9211, mlr; ``T_head_left``: warning band 0.40 °C, re-admission band
0.20, jump limit 0.54 °C)
------
R1b 34800 s: ``T_head_left`` reads 16.54 °C, 3.85 °C below the sample before: a jump; excluded,
re-referenced by its step less the change the others predict (``_instant``); the model reads the
field's prediction (2.238 °C referenced).  34860 s: it reads 20.32 °C, on its reference before
the jump (18.100) 2.220 °C, the field predicting 2.243 (-0.023 °C off): the spike is over.  But
out, the sensor is judged by no one, so the return is a second jump re-referenced by its whole
step: reference 18.100 -> 17.977 °C, the others' one-sample prediction noise kept as an offset;
it reads +0.09..+0.18 °C off the field from there, waits out its calm window and the re-admission
band (within 0.20 °C for 16 samples: back at 35820 s) and feeds the model +0.123 °C for the
record's last 4.7 h.  The deployed stream: 17 samples of field prediction and the offset (mlr
replay 0.6437 against run's 0.7718, the offset lucky; lagbank 0.9912 against 0.8560).

The rule (served ``faults._spike_back``)
---------------------------------------
A sensor the others predict, out for jumps only (not by the field's judgement, a dropout, out
of range or frozen), whose next jump comes within a window (``window`` samples) of its last one
and brings its reading, on its reference before the first jump (``_ref0``), within its
re-admission band (``READMIT`` of its warning band in the set it returns to) of the field the
active sensors predict: a spike.  Its reference is put back and it is in again at once (the
spike's samples were the field's prediction, nothing else changes); a jump that stays, or a
return the field does not vouch for, is re-referenced and waits as before.  Work: one operator
per candidate at a sensor's return jump (none on a healthy record).

Bar (written before scoring the fresh seeds; lr9211 and lr9171 were traced and run on this tree
first; the brief's bar, made concrete)
---
On fresh 9291-9300 (``fresh``, :data:`FAMILIES` mlr and lagbank on every record: 20 rows):

1. No row's replay RMSE (mean over targets) more than 2 % worse than main's.
2. The mean over the 20 rows of |replay - run| smaller on the tree than on main.
3. No detection lost: every exclusion main makes (sensor, campaign, time) made by the tree;
   no new exclusion.
4. Healthy records no new events: tests/shell/test_monitor_healthy53.py and the monitor tests
   pass; monitor / export / replay tests and tests/test_readme.py pass.
5. The exported C and its numpy mirror follow the served monitor (C = served on every row of
   lr9211's R1b, as on main), older exports (without the new key) unchanged.
KEPT if 1-5 hold; else REFUSED (src reverted; benchmarks/mon89_rule.patch).

Scored (2026-12-05; main = a0d62dea's src, rule = a0d62dea's src with benchmarks/mon89_rule.patch's
src (a copy under /tmp), the same draws; ``fresh`` then ``compare``; CPU s of the bench process,
2 cores shared by seven helpers)
------
``traced`` (seen, not in the bar; run -> replay µm, main | rule)::

  lr9211/mlr      0.7718 -> 0.6437 (|gap| 0.1281) | 0.6663 (0.1055)  T_head_left back 34860 s (was 35820)
  lr9211/lagbank  0.8560 -> 0.9912 (0.1351)       | 0.8628 (0.0068)
  lr9171/mlr      0.7955 -> 0.5097 (0.2858)       | 0.6019 (0.1936)  T_col_back back at each spike's
  lr9171/lagbank  1.0527 -> 0.7845 (0.2682)       | 1.0442 (0.0086)  end (was: out to R1b's end)

1. ``fresh`` 9291-9300, replay RMSE (mean over targets, µm) main -> rule, run's in brackets::

     lr9291 mlr 0.8417 = / lagbank 1.2527 =        lr9292, lr9293, lr9295: no row changed
     lr9294/mlr      1.4640 -> 1.5093  x1.0309  (run 1.6007)   2 spikes
     lr9294/lagbank  1.8189 -> 1.8477  x1.0158  (run 1.8257)
     cr9296/mlr      3.5673 -> 3.5736  x1.0018  (run 3.5666)
     cr9296/lagbank  3.4261 -> 3.4383  x1.0035  (run 4.4981)
     cr9297/mlr      2.6166 -> 2.6767  x1.0230  (run 4.4419)
     cr9297/lagbank  3.2796 -> 3.4589  x1.0547  (run 9.6533)
     cr9298/mlr      3.2081 -> 3.2778  x1.0217  (run 3.5125)
     cr9298/lagbank  2.2094 -> 2.2296  x1.0092  (run 2.3538)
     cr9299/mlr      1.4323 -> 1.4454  x1.0091  (run 2.0641)
     cr9299/lagbank  1.1015 -> 1.1047  x1.0029  (run 1.2022)
     cr9300/mlr      1.6111 -> 1.5671  x0.9727  (run 3.0673)
     cr9300/lagbank  2.6503 -> 2.6581  x1.0030  (run 10.2131)

   Four rows more than 2 % worse (lr9294/mlr +3.1 %, cr9297/mlr +2.3 %, cr9297/lagbank +5.5 %,
   cr9298/mlr +2.2 %): FAILS.
2. Mean |replay - run| over the 20 rows 0.9817 -> 0.9644 µm: MET (row by row it shrinks on 9,
   grows on 3: lr9294/lagbank 0.0068 -> 0.0220, cr9296/mlr 0.0007 -> 0.0070, cr9300/mlr
   1.4562 -> 1.5002; the climate rooms' gap is their frozen ``T_amb``'s, which the rule leaves).
3. Every exclusion main makes made at the same campaign and time (46 of 46 over the 20 rows),
   none new: MET.  Each of the 13 spikes of a sensor the others predict (per family: 2 on lr9294,
   11 on the rooms) now back at the spike's end (1-3 samples after its jump, its reading within
   0.0007-0.198 °C of the field; main: after 10-36 calm samples); the 4 of sensors no other predicts
   (``T_motor``, ``T_nc_spindle_motor``, ``T_nc_tool_motor``) as on main.
4. On the rule's src (-n 2, OMP_NUM_THREADS=1): tests/apps/test_monitor*.py + sensor_fallback71
   / deployed_as_scored44 / warm_batch59 / fallback_arx87 118 passed, 1 xfailed (mon77's);
   tests/shell/test_monitor*.py (healthy53, readmit88 with lr9171 no longer xfailed, the
   patch's spike89) 122 passed, 2 xfailed (the drift gaps); tests/shell/test_replay*.py +
   adaptive_deploy / deploy88 / deploy88b / deployed_as_scored / deployed_guarded 76 passed;
   tests/shell/test_export*.py (the patch's export_spike89) 271 passed; tests/test_readme.py +
   tests/test_docs.py 53 passed.  The patch's tests fail on a0d62dea (spike89: the sensor back
   at the next sample, deployed = unmonitored but on the spike's row; export_spike89: C =
   served with one row out), their controls (a step that stays; an export without ``spike``)
   pass on both.  MET.
5. ``pack`` (lr9211 R1b after R1a): C = served on 864 of 864 rows with ``spike`` (mlr 9.2e-14,
   lagbank 5.6e-13 µm), pack 864 rows; without the key the C parts from the served at row 581
   (the spike's return: the export before it re-references it as before).  MET.
CPU: ``fresh`` 31.2 s (main) / 32.0 s (rule) for the 20 rows.

Why item 1 fails (``why 9294 mlr`` / ``why 9297 lagbank`` on both trees, the spent draws, after
the verdict): with the rule the deployed stream parts from the unmonitored one on the spike rows
alone (lr9294/mlr: 3 rows; RMSE 1.5093 against 1.5114) and every reference ends where it
started.  Main's two re-references per spike left ``T_col_back`` +0.0067 °C and ``T_bed_left``
+0.0457 °C (809 rows parted); R1b's residual has a mean of +1.3 to +1.95 µm (the model's own
drift), and the offsets, through MLR's several-µm/°C weights on the collinear head / bed
sensors, happen to pull against it: last quarter's sum of squares 797.7 (unmonitored) / 799.0
(rule) / 695.5 (main).  cr9297/lagbank, ``T_amb`` frozen out: C12's ``T_frame2`` kept -0.098 °C
(E_X / E_Z 2.578 / 5.954 main, 2.888 / 6.613 rule), while C10's ``T_toolholder1`` kept -0.026 °C
the other way (1.497 / 3.955 main, 1.440 / 3.837 rule).  The offsets are the others' one-sample
prediction noise and the sensor's true change over the outage; their sign relative to a
record's residual is the draw's: main's luck, as mon88 found for lr9199 (run 1.0479, main
0.9303).  A bar on replay RMSE against main's cannot tell that luck from a loss.
Verdict: REFUSED by item 1 (benchmarks/mon89_rule.patch: served, mirror, C, docs and tests).
Kept later by bar91b (benchmarks/bench_bar91b.py: scored by the distance to the truth).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands, seed_list  # noqa: E402
from bench_mon88 import (  # noqa: E402
    LONG,
    ROOM,
    _drawn,
    _pack_rows,
    _root,
    drawn_fresh,
    exclusions_and_returns,
    print_events,
    replayed,
)
from cpu import cpu_seconds  # noqa: E402

FAMILIES = ("mlr", "lagbank")
TRACED = {"lr9211": 9211, "lr9171": 9171}
FRESH = {**{seed: ("lr", LONG, ("data.reference=none",)) for seed in range(9291, 9296)},
         **{seed: ("cr", ROOM, ()) for seed in range(9296, 9301)}}


def _mean(rmse: dict) -> float:
    return float(np.mean(list(rmse.values())))


def scored(root: Path, name: str, data: Path, family: str, extra: tuple) -> dict:
    """``run`` -> ``replay`` of ``family`` on ``data``: both RMSE (mean over targets) and the
    replay's events."""
    start = cpu_seconds()
    got = replayed(root, f"{name}-{family}", data, (f"model={family}",), extra)
    metrics = json.loads((root / "reports" / f"{name}-{family}" / "metrics.json").read_text())
    run = {t: metrics["targets"][t]["test"]["rmse"] for t in got["rmse"]}
    return {"run": _mean(run), "replay": _mean(got["rmse"]), "events": got["events"],
            "excluded": got["excluded"], "cpu": cpu_seconds() - start}


def _said(name: str, family: str, got: dict) -> str:
    return (f"{name}/{family}: run {got['run']:.4f} replay {got['replay']:.4f} µm "
            f"(|gap| {abs(got['replay'] - got['run']):.4f}); {len(got['events'])} events; "
            f"CPU {got['cpu']:.1f} s")


def traced(root: str) -> None:
    """The two seen records (module doc): run, replay and the test events per family."""
    folder = _root(root)
    for name, seed in TRACED.items():
        data = _drawn(name, seed, LONG, folder)
        for family in FAMILIES:
            got = scored(folder, name, data, family, ("data.reference=none",))
            print(_said(name, family, got), flush=True)
            print_events(got["events"], 150)


def fresh(root: str, seeds: str) -> None:
    """Fresh records (module doc) -> ``ROOT/fresh.json``."""
    folder = _root(root)
    results = {}
    for seed in seed_list(seeds):
        name, data, faults, extra = drawn_fresh(folder, seed, FRESH)
        for family in FAMILIES:
            got = scored(folder, name, data, family, extra)
            got["faults"] = faults
            results[f"{name}/{family}"] = got
            print(_said(name, family, got), flush=True)
    (folder / "fresh.json").write_text(json.dumps(results, indent=1))


def compare(before: str, after: str) -> None:
    """The two ``fresh.json`` row by row (module doc)."""
    a = json.loads((Path(before) / "fresh.json").read_text())
    b = json.loads((Path(after) / "fresh.json").read_text())
    print(f"{'row':<16}{'run':>8}{'replay before':>15}{'after':>9}{'ratio':>8}{'|gap| before':>14}"
          f"{'after':>8}  exclusions kept / lost (new)  re-admissions")
    gaps = []
    for row in a:
        ra, rb = a[row]["replay"], b[row]["replay"]
        ga, gb = abs(ra - a[row]["run"]), abs(rb - b[row]["run"])
        gaps.append((ga, gb))
        out_a, out_b, back_a, back_b = exclusions_and_returns(a[row]["events"], b[row]["events"])
        print(f"{row:<16}{a[row]['run']:>8.4f}{ra:>15.4f}{rb:>9.4f}{rb / ra:>8.4f}{ga:>14.4f}"
              f"{gb:>8.4f}  {len(out_a & out_b)} / {len(out_a - out_b)} ({len(out_b - out_a)})"
              f"  {len(back_a)} -> {len(back_b)}; out at the end {a[row]['excluded']} -> "
              f"{b[row]['excluded']}")
        for m in sorted(out_a ^ out_b) + sorted(set(back_a) ^ set(back_b)):
            print(f"    differs: {m}")
    ga, gb = np.mean(gaps, axis=0)
    print(f"mean |replay - run| over {len(gaps)} rows: {ga:.4f} -> {gb:.4f} µm")


def pack(root: str) -> None:
    """lr9211 through the code, with and without the ``spike`` key (module doc)."""
    folder = _root(root)
    data = _drawn("lr9211", TRACED["lr9211"], LONG, folder)
    for family in FAMILIES:
        start = cpu_seconds()
        lines = _pack_rows(folder, f"lr9211/{family}", data, ("data.reference=none",),
                           model=family, keys=("spike",))
        print("\n".join(lines) + f"\n  CPU {cpu_seconds() - start:.1f} s", flush=True)


def why(root: str, seed: str, family: str) -> None:
    """One fresh record row by row (module doc)."""
    import copy

    from _ccode import deployed_on

    from thermocomp.apps.deploy.report import plain, stream_rows
    from thermocomp.apps.deploy.surveillance.monitor import SensorMonitor
    from thermocomp.core.continuation import lead_ins

    name, data, _, extra = drawn_fresh(_root(root), int(seed), FRESH)
    deployed, ds, test_ids = deployed_on(data, family, extra)
    leads = lead_ins(plain(deployed).compensator, ds, test_ids)
    refs = []
    update = SensorMonitor.update

    def kept(self, *args, **kwargs):     # each sample's reference, to read the last one's
        out = update(self, *args, **kwargs)
        refs.append(None if self._ref is None else self._ref.copy())
        return out

    SensorMonitor.update = kept
    try:
        for t in test_ids:
            frame = ds.campaigns[t].reset_index(drop=True)
            errors = frame[deployed.targets_].to_numpy(float)
            refs.clear()
            served = stream_rows(copy.deepcopy(deployed), frame, str(t), lead_in=leads.get(t))
            start, end = refs[-len(frame)], refs[-1]
            bare = stream_rows(plain(copy.deepcopy(deployed)), frame, str(t), lead_in=leads.get(t))
            r = {"deployed": errors - served.y, "plain": errors - bare.y}
            moved = {n: round(float(b - a), 4) for n, a, b in
                     zip(deployed.monitor.names, start, end) if abs(b - a) > 1e-9}
            events = [(e["time"], e["sensor"], e["to"]) for e in served.events if e.get("sensor")]
            parted = np.flatnonzero(np.abs(r["deployed"] - r["plain"]).max(axis=1) > 1e-9)
            print(f"{name}/{family} {t}: RMSE deployed "
                  f"{np.sqrt(np.mean(r['deployed'] ** 2, axis=0)).round(4)} plain "
                  f"{np.sqrt(np.mean(r['plain'] ** 2, axis=0)).round(4)}; events {events}; "
                  f"rows parted {len(parted)}; reference end - start {moved}", flush=True)
            first = int(parted[0]) if len(parted) else len(frame)
            edges = [0, first, *np.linspace(first + 1, len(frame), 5).astype(int)[:-1], len(frame)]
            for lo, hi in zip(edges[:-1], edges[1:]):
                if hi > lo:
                    print(f"  rows {lo}-{hi}: SS " + ", ".join(
                        f"{k} {float((v[lo:hi] ** 2).sum()):.2f} (mean {v[lo:hi].mean():+.3f})"
                        for k, v in r.items()), flush=True)
    finally:
        SensorMonitor.update = update


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"traced": traced, "fresh": fresh, "compare": compare,
                                  "pack": pack, "why": why}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
