"""A white target's unclamped excess only while several inputs share it: the per-target clamp
(``promote.envelope.per_target``, env93) priced against a drifting sensor (env93b) and bounded
(env94, issue 34).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's;
``cache`` needs main 4f0fc94a's src, where ``per_target`` on leaves a white target unclamped
at every sample: the rule is composed from it)::

    python benchmarks/bench_env94.py cache ROOT SEEDS
    python benchmarks/bench_env94.py rules ROOT
    python benchmarks/bench_env94.py check ROOT CELL CASE

``cache``: bench_env92's ``draw ROOT SEEDS`` (``column_moving_source`` seed by seed, per family
``mlr``, ``arx``, ``lagbank`` fitted; cells drawn already are not redone), then per cell the model
deployed as ``replay`` / ``promote`` deploy it (``monitor.adaptive=true``) with ``per_target``
off (the shipped default: one clamp for every target) and on, and per row the deployed
correction of the true test campaign and of bench_env93b's 10 fault cases (spike, jump, drift,
range, dropout on T_right3 and T_left3 from three quarters of the campaign), the excess the
envelope's gate passed on each row (the stream's ``Envelope.excess``), the measured error:
``ROOT/rows/<record>-<family>.npz``.
``rules``: per cell the true record's Σ² (µm², the six targets' squared RMSE summed) under
``off``, ``on`` and the rule, G and the cells either way against ``off``; per fault kind the fault
cases whose Σ² under a rule exceeds 1.02 x ``off``'s.  The rule is composed row by row from the
``off`` and ``on`` rows (exact: a white target's unclamped stream and its clamped twin step the
same states whichever is output, the other targets are the same in both; checked against the
built src below).  ``check`` (benchmarks/env94_rule.patch applied): one cell (``cms3141-arx``) deployed with
``per_target`` on, one case (``drift:T_right3``) streamed by the built rule, against the composed.
Beside the bar (not part of it), ``rules`` prints what the faults add to Σ² pooled, off / rule,
and how many of the cases > 1.02 have a true record already worse under the rule.

THE RULE (chosen on the seen cases: env93b's seeds 3141, 5003, 4253, 6007, 9406)
----------------------------------------------------------------------------------
A white target (``white_targets``) streams unclamped at a sample only when the excess the gate
passes to the clamp is shared by at least two inputs (``spread_excess``); at any other sample
(one input out alone, or back in range) it is clamped as every target is (its clamped twin
forked at the campaign's first excess, the bound of the last excess held).  Why: a heat source
warms the sensors around it together (Q3 took T_right2-5 and T_amb out in every seen cell,
env93's trace), a faulty sensor moves alone; a drift (+1 K/h, never excluded by the monitor)
reaches one width where Q3 does (env93b's widths), so no bound on the excess's size or rate
separates them in a drift's first hours, while the number of inputs out does: on the seen cells,
after Q3's excursion the drifting sensor is the one input out.  No threshold: "two or more" is the
smallest count that is not one sensor.  Not tuned (the only rule tried besides off / on).

BAR (written and committed before the fresh seeds were drawn; the brief's)
--------------------------------------------------------------------------
FRESH ``column_moving_source`` 9589-9593 (stop 93's, unspent) x mlr / arx / lagbank = 15 cells,
deployed adaptive, scored ONCE:
(a) the clean gain, env92b's bar as env93 applied it: over the 15 true test records
    G = geometric mean of Σ²(rule) / Σ²(off) <= 0.95, and the cells > 10 % worse no more than
    the cells > 10 % better;
(b) the faults: NO fault case (15 cells x 5 kinds x 2 sensors = 150) with Σ²(rule) > 1.02 x
    Σ²(off) under the adaptive deployment.
Both met -> KEPT: the rule in the stream and in the exported code (C, ST, the numpy reference:
``clamp_spread``), under ``promote.envelope.per_target`` (the default is left to the lead: it moves
every README / docs figure of a clamped record, not re-measured here).  Else REFUSED (the src
diff saved as benchmarks/env94_rule.patch).

MEASURED
--------
SEEN (``cache /tmp/env94/seen 3141,5003,4253,6007,9406`` on main 4f0fc94a's src, env93b's fits;
2026-12-05; stopped after 8 of the 15 cells, cms4253 lagbank, cms6007 and cms9406 not cached, to
leave the two shared cores to the fresh draw: 80 fault cases, not 150; CPU ~60-100 s a cell)::

  rule   clean G (Σ²/off)  >10 % worse / better   fault cases Σ² > 1.02 off (worst)   drift added off / rule
  on         0.607             0 / 7                 15 of 80 (1.185; drift 11/16)          13 546 / 22 155
  rule       0.607             0 / 7                  5 of 80 (1.024; drift  1/16)          13 546 / 13 606

The rule equals ``on`` on every true record (the Q3 rows that ``on`` frees all have two inputs or
more out; Σ² to the µm²: 848, 850, 316, 866, 505, 364, 1412, 1518 against off's 1336, 943, 788,
1528, 1179, 867, 1386, 1952), and takes the drift's extra cost out (pooled added Σ² 13 606 against
off's 13 546; on 22 155).  The 5 cases above 1.02 are all cms5003 lagbank's (spike, jump, range,
dropout 1.021, drift:L3 1.024), whose TRUE record is 1.019x off already under ``on`` and the rule
(env93b's "1.9 % worse without a fault"): not the fault's price, but bar (b) counts them.
``check``: the built src against the composed rule, Σ² 4043.8 vs 4043.7 (cms3141-arx drift:R3;
E_X's largest row gap 11.9 µm, not traced: the adaptive compensator's state after a switch),
2000.2 vs 2000.2 (cms5003-lagbank drift:L3, every row to 0).
Found on the way (tests/apps/test_envelope_spread94.py's record, seed 9301): the count is of the
inputs beyond their bounds at a sample off the pattern, so a machine still hot from Q3 along with
one drifting sensor counts 2+ inputs and the drift passes unclamped there; a sensor off alone
before Q3 is clamped.

FRESH 9589-9593, scored ONCE (``cache /tmp/env94/fresh 9589-9593`` on main 4f0fc94a's src after the
rule and the bar were committed in 4734c9be / bf660705, then ``rules``; nothing changed after;
CPU 366 s for the draw's 15 cells (simulation, fits, env92's replays) and the 330 streams)::

  record   model    Σ² off    on  rule        record   model    Σ² off    on  rule
  cms9589  arx         880   417   417        cms9591  mlr        1058   424   424
  cms9589  lagbank    1427  1312  1312        cms9592  arx         910   513   513
  cms9589  mlr         753   287   287        cms9592  lagbank    1389  1470  1470
  cms9590  arx         752   317   317        cms9592  mlr         949   379   379
  cms9590  lagbank     729   572   572        cms9593  arx         852   411   411
  cms9590  mlr         789   336   336        cms9593  lagbank    1657  1496  1495
  cms9591  arx        1294   488   488        cms9593  mlr         841   409   409
  cms9591  lagbank    4283  4181  4180

  (a) clean: G 0.561 (rule = on), 0 cells > 10 % worse, 12 better: MET.
  (b) fault cases with Σ²(rule) > 1.02 x off: 10 of 150 (worst 1.071): NOT MET.  All ten are
      cms9592 lagbank's (spike / jump / range / dropout 1.050 on R3, 1.065 on L3; drift 1.071 /
      1.052), whose TRUE record is 1.058x off already (1470 / 1389), the key's clean cost on that
      cell, the same with ``on``; ``on`` was > 1.02 in 33 of 150 (drift 25 of 30, up to 1.759:
      cms9591 arx drift:R3, the rule 0.472 there).
  What the faults add to Σ², pooled over 30 cases each, off / on / rule: spike 593 / 866 / 867,
  jump 609 / 883 / 884, drift 18 400 / 35 708 / 18 688, range 593 / 866 / 866, dropout
  523 / 801 / 801.

VERDICT: REFUSED by the bar as written (clause (b), the brief's "no fault case worse than off by
> 2 %"), though the rule does what it was built for: the drift's extra cost under the per-target
clamp goes (added Σ² 35 708 -> 18 688 against off's 18 400; drift cases > 2 % worse 25 -> 2 of 30,
the two cms9592 lagbank's, at its clean cost), and the clean gain is kept whole (G 0.561 = on's).
What fails (b) is a clean loss of the key on one lag bank cell (cms9592 lagbank 1.058; seen
cms5003 lagbank 1.019), which no fault rule can remove: (b) as written charges it to every fault
case of that cell.  The src (stream ``spread_excess``; the exported code's ``clamp_spread`` in
the numpy reference, C and ST), tests/apps/test_envelope_spread94.py (4 tests, each failing on
4f0fc94a, passing with the rule) and the per_target93 test's amended line are saved as
benchmarks/env94_rule.patch (``git apply`` on 4f0fc94a); src is main's, ``per_target`` stays
opt-in with main's behaviour.  ``check`` needs the patch applied.
Left: the key's clean loss on some lag bank cells (cms5003, cms9592; a lag bank's E_Z / E_Z_mid are
unclamped too, which target loses there not traced), then the rule under a bar that prices a fault
by what it adds;
the count's blind spot (a sensor drifting while other inputs are still out).
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path
from typing import Callable, Iterator

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_env92 as env92  # noqa: E402
import bench_env93b as env93b  # noqa: E402
import bench_envelope_policy as envelope_policy  # noqa: E402
from _cli import run_commands, seed_list  # noqa: E402

CASES = ("true",) + tuple(f"{k}:{s}" for s in env93b.SENSORS for k in env93b.KINDS)


def _excess_recorder(stream) -> list:
    """A list that gets, per stepped row of ``stream``, the excess its envelope gate passed to the
    clamp (zeros: none), in the model frame (``Envelope.excess`` of the inputs as the models read
    them)."""
    rows, models = [], stream._models
    env = stream.envelope

    def recorded(seen, time, first):
        out = models(seen, time, first)
        rows.append(env.excess(stream.last_x_))
        return out
    stream._models = recorded
    return rows


def deployed_cells(root: str, seeds: str) -> Iterator[tuple[str, str, Path, Callable]]:
    """bench_env92's ``draw ROOT SEEDS`` (cells drawn already not redone), then per cell (record x
    family) whose ``ROOT/rows/<record>-<family>.npz`` is not there yet: ``(record, family, that
    path, deployed)``, ``deployed(on)`` the cell's fitted model deployed as ``replay`` deploys it
    (``monitor.adaptive=true``) with ``promote.envelope.per_target`` off / on, and ``(its dataset,
    the train ids, the test campaign's id)`` -- the cells bench_dep95's ``cache`` records too."""
    env92.draw(root, seeds)
    base = Path(root)
    (base / "rows").mkdir(exist_ok=True)
    for seed in seed_list(seeds):
        record = f"cms{seed}"
        for fam in envelope_policy.FAMILIES:
            path = base / "rows" / f"{record}-{fam}.npz"
            if not path.exists():
                yield record, fam, path, functools.partial(_deployed, base, record, fam)


def _deployed(base: Path, record: str, fam: str, on: bool) -> tuple:
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    cfg = env93b._config(f"data.path={base / 'data' / record}", "track=false",
                         "monitor.adaptive=true", f"{env93b.KEY}={str(on).lower()}")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    deployed, _, _ = deployable_model(cfg, ds, train_ids,
                                      str(base / "fit" / f"{record}-{fam}" / "model.pkl"), "replay.model")
    return deployed, ds, train_ids, test_ids[0]


def cache(root: str, seeds: str) -> None:
    """Per cell the deployed rows off / on of the true test campaign and each fault case, the
    measured error, and the model's simulation of its train campaigns: ``ROOT/rows/<cell>.npz``."""
    from thermocomp.apps.deploy.report import stream_rows

    for record, fam, path, deployed_with in deployed_cells(root, seeds):
        out = {}
        for on in (False, True):
            deployed, ds, train_ids, tid = deployed_with(on)
            comp = deployed.streaming.compensator
            true = ds.campaigns[tid]
            seen = _excess_recorder(deployed.streaming)
            for case in CASES:
                frame = true if case == "true" else env93b.planted(true, *case.split(":"))
                seen.clear()
                out[f"{'on' if on else 'off'}|{case}"] = stream_rows(deployed, frame, tid).y
                if on:
                    out[f"excess|{case}"] = np.array(seen)
            if on:
                targets = list(deployed.targets_)
                out["unclamped"] = np.array(deployed.streaming.unclamped_, dtype=str)
                out["targets"] = np.array(targets, dtype=str)
                out["measured"] = comp.measured({tid: true})[tid][targets].to_numpy(float)
                out["time"] = true["time"].to_numpy(float)
                train = {c: ds.campaigns[c] for c in train_ids}
                pred = comp.predict(train)
                meas = comp.measured(train, pred)
                for c in train:
                    out[f"train_pred|{c}"] = pred[c][targets].to_numpy(float)
                    out[f"train_meas|{c}"] = meas[c][targets].to_numpy(float)
                    out[f"train_time|{c}"] = train[c]["time"].to_numpy(float)
        np.savez(path, **out)
        print(record, fam, "unclamped", list(out["unclamped"]), flush=True)


def _load(path: Path) -> dict:
    d = np.load(path)
    return {k: d[k] for k in d.files}


def composed(cell: dict, case: str, rule: str) -> np.ndarray:
    """The deployed rows of ``case`` under ``rule``: per white target (``unclamped``) row by row
    the unclamped stream's correction where the rule frees it, else the clamped one's (exact:
    each target's unclamped and clamped streams step the same states whichever is output, and
    the other targets are the same in both)."""
    off, on = cell[f"off|{case}"], cell[f"on|{case}"]
    if rule == "off":
        return off
    if rule == "on":
        return on
    free = np.zeros(len(off), dtype=bool)
    if rule == "multi":      # a heat source moves several sensors out together, a fault one
        free = (cell[f"excess|{case}"] != 0).sum(axis=1) >= 2
    y = off.copy()
    for t in cell["unclamped"]:
        k = list(cell["targets"]).index(t)
        y[:, k] = np.where(free, on[:, k], off[:, k])
    return y


def sigma2(cell: dict, y: np.ndarray) -> float:
    """Σ² (µm²): the squared RMSE of the deployed residual summed over the targets."""
    r = cell["measured"] - y
    return float(np.nansum(np.nanmean(r ** 2, axis=0)))


RULES = ("off", "on", "multi")


def rules(root: str) -> None:
    """Per cell the true record's Σ² per rule, and per fault case Σ² per rule against off."""
    cells = {p.stem: _load(p) for p in sorted((Path(root) / "rows").glob("*.npz"))}
    print("clean (true test record), Σ² per rule:")
    ratio = {r: [] for r in RULES}
    for name, cell in cells.items():
        s = {r: sigma2(cell, composed(cell, "true", r)) for r in RULES}
        for r in RULES:
            ratio[r].append(s[r] / s["off"])
        print(f"  {name:16} " + " ".join(f"{r} {s[r]:7.0f}" for r in RULES))
    for r in RULES:
        a = np.array(ratio[r])
        print(f"  {r:6} G {np.exp(np.log(a).mean()):.3f}  >10% worse {int((a > 1.1).sum())}"
              f"  >10% better {int((a < 1 / 1.1).sum())}")
    print("fault cases: Σ² rule / off > 1.02 (count, worst), per kind; beside (not the bar): of those,"
          " how many whose true record is already worse under the rule than off; what the faults"
          " add to Σ², pooled, off / rule")
    for r in RULES:
        worst, line, clean = 0.0, [], 0
        for kind in env93b.KINDS:
            q, add_off, add_rule = [], 0.0, 0.0
            for c in cells.values():
                t_rule, t_off = (sigma2(c, composed(c, "true", x)) for x in (r, "off"))
                for case in CASES:
                    if case.startswith(kind + ":"):
                        a, b = sigma2(c, composed(c, case, r)), sigma2(c, composed(c, case, "off"))
                        q.append(a / b)
                        clean += a / b > 1.02 and t_rule > t_off
                        add_rule, add_off = add_rule + a - t_rule, add_off + b - t_off
            q = np.array(q)
            worst = max(worst, q.max())
            line.append(f"{kind} {int((q > 1.02).sum())}/{len(q)} (max {q.max():.3f};"
                        f" added {add_off:.0f} / {add_rule:.0f})")
        print(f"  {r:6} " + "  ".join(line) + f"  worst {worst:.3f}; of the > 1.02, true record"
              f" already worse: {clean}")


def check(root: str, cell: str, case: str) -> None:
    """The built src (``PYTHONPATH``: this branch) against the rule composed from main's rows:
    ``cell`` (``cms3141-mlr``) deployed with ``per_target`` on, ``case`` streamed; the largest
    |streamed - composed| per target (µm)."""
    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    base = Path(root)
    record, fam = cell.split("-")
    cfg = env93b._config(f"data.path={base / 'data' / record}", "track=false", "monitor.adaptive=true",
                         f"{env93b.KEY}=true")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    deployed, _, _ = deployable_model(cfg, ds, train_ids, str(base / "fit" / cell / "model.pkl"),
                                      "replay.model")
    true = ds.campaigns[test_ids[0]]
    frame = true if case == "true" else env93b.planted(true, *case.split(":"))
    rows = _load(base / "rows" / f"{cell}.npz")
    y = stream_rows(deployed, frame, test_ids[0]).y
    gap = np.abs(y - composed(rows, case, "multi")).max(axis=0)
    print(cell, case, "max |src - composed| per target:",
          dict(zip(rows["targets"], np.round(gap, 12))), "Σ² src", round(sigma2(rows, y), 1),
          "composed", round(sigma2(rows, composed(rows, case, "multi")), 1),
          "off", round(sigma2(rows, composed(rows, case, "off")), 1), flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"cache": cache, "rules": rules, "check": check},
                        sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
