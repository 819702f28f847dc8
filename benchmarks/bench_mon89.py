"""A one-sample spike read as a jump: the served monitor re-referenced the sensor at the spike and
again at its return, kept the pair's noise as an offset and held the sensor out a window, so the
deployed lag models read 16-23 % worse than run scored them (stop 89, mon89; deploy88's lr9211).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_mon89.py traced ROOT          # lr9211 / lr9171: run, replay, events
    python benchmarks/bench_mon89.py fresh ROOT SEEDS     # fresh records -> ROOT/fresh.json
    python benchmarks/bench_mon89.py compare BEFORE AFTER # two fresh.json side by side

``traced``: in ``ROOT`` (made anew; the measured tree's ``conf/`` linked in, ``THERMOCOMP_ROOT``)
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
not changed).

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
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands, seed_list  # noqa: E402
from bench_mon88 import LONG, ROOM, _drawn, _moves, _root, planted, replayed  # noqa: E402
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
    run = {t: metrics["targets"][t]["rmse"] for t in got["rmse"]}
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
            for e in got["events"]:
                if e.get("sensor"):
                    print(f"  {e['campaign']} {e['time']:>7.0f} s {e['sensor']:<14} {e['to']:<9} "
                          f"{e['reason'][:150]}", flush=True)


def fresh(root: str, seeds: str) -> None:
    """Fresh records (module doc) -> ``ROOT/fresh.json``."""
    folder = _root(root)
    results = {}
    for seed in seed_list(seeds):
        kind, sim, extra = FRESH[seed]
        name = f"{kind}{seed}"
        data = _drawn(name, seed, sim, folder)
        faults = planted(data, seed) if kind == "cr" else ["the generator's spikes as drawn"]
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
        out_a = {m[:3] for m in _moves(a[row]["events"]) if m[3] == "excluded"}
        out_b = {m[:3] for m in _moves(b[row]["events"]) if m[3] == "excluded"}
        back_a = [m[:3] for m in _moves(a[row]["events"]) if m[3] == "ok"]
        back_b = [m[:3] for m in _moves(b[row]["events"]) if m[3] == "ok"]
        print(f"{row:<16}{a[row]['run']:>8.4f}{ra:>15.4f}{rb:>9.4f}{rb / ra:>8.4f}{ga:>14.4f}"
              f"{gb:>8.4f}  {len(out_a & out_b)} / {len(out_a - out_b)} ({len(out_b - out_a)})"
              f"  {len(back_a)} -> {len(back_b)}; out at the end {a[row]['excluded']} -> "
              f"{b[row]['excluded']}")
        for m in sorted(out_a ^ out_b) + sorted(set(back_a) ^ set(back_b)):
            print(f"    differs: {m}")
    ga, gb = np.mean(gaps, axis=0)
    print(f"mean |replay - run| over {len(gaps)} rows: {ga:.4f} -> {gb:.4f} µm")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"traced": traced, "fresh": fresh, "compare": compare},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
