"""The guard's rate limit judged on the model's own step, not the envelope clamp's (guard96).

audit95's cr9762 (a climate room ramped +5 K past training) and audit96's lmv9775 (the volumetric
mill) reported correction-guard events (sensor None) on healthy records.  guard95 traced cr9762:
every rate-limited row is a row where the envelope clamp switches on or off (its pattern gate on
its threshold), a step of the deployment's own, not of the model.  The rule: the guard limits the
output's rate as before, but reports ``rate_limited`` only where the model's own correction (the
output plus what the clamp took out of it, ``StreamingCompensator.last_take_``) moved beyond the
limit; a step the clamp made is paced without an event (``guard.CorrectionGuard.step``, its
``take``).  No constant, nothing fitted: the same limit, judged on the model rather than on the
clamp.  The corrections sent are unchanged (the exported C / ST / numpy mirror carry no events).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_guard96.py score DATA MODELS OUT.json CELL...
    python benchmarks/bench_guard96.py compare BASE.json RULE.json
    python benchmarks/bench_guard96.py fresh ROOT SEEDS
    python benchmarks/bench_guard96.py faults ROOT OUT.json

``score``: per cell (``MODELS/<cell>/model.pkl``), the model made deployable as ``replay`` makes it
and each test campaign streamed from a reset (bench_guard95's stream): the guard's events by kind
(rate / bound / other), the rows it changed, RMSE per target against the measured error; the
corrections kept (``OUT.npz``) so that ``compare`` can give max|rule - base|.  ``fresh``: SEEDS
simulated in ROOT (:data:`FRESH`), every cell of :data:`CELLS` fitted by ``run``; then ``score``
with ROOT's data and reports.  A cell named ``CELL+c`` is also exported as C, compiled (gcc) and
fed its test campaigns from a reset: max|C - deployed| (``dC``, µm).  ``faults``: the record,
models and injected faults of bench_deploy_faults.py through the adaptive form (the served
model): the guard's events per fault (row, target, state) and the corrections, for B3.

BAR (written and committed BEFORE fresh seeds 9782-9786 were simulated; the rule unchanged after)
-------------------------------------------------------------------------------------------
B1. seen cr9762 (guard95's 9 cells) and lmv9775 (audit96's 4 cells with events): the guard's
    RATE events on the healthy test campaigns -> 0; bound events as main (the rule does not touch
    the bound: lmv9775's are bound events, traced below, said as remaining with why).
B2. RMSE per target not worse than main by > 1 % on any cell (the rule changes no correction:
    expected max|rule - main| = 0 µm on every row).
B3. the guard's fault cases all still caught at their row: tests/ guard and monitor cases
    (test_guard*, test_monitor*'s guard cases, bench_guard56's tests) pass unchanged.
B4. fresh 9782-9786 (climate_room as cr9762 for 9782-9784; large_mill_volumetric as shipped for
    9785-9786; generators named before drawing): healthy events <= main's in every cell, no RMSE
    worse than main's by > 1 %, deployed rule = main to 1e-9 µm (so = replay = C as on main).

Traced (seen, at 55f940b8, before the rule): lmv9775 is NOT cr9762's mechanism.  Its events are
all ``bounded`` (E_XY1, E_ZY1), no input beyond the envelope on any of 508 test rows (0 clamped),
the gate's residual/tol 1.0-1.5 (off the training pattern within the range: no allowance); the
model's correction beyond the training error bound on 13 (mlr) / 45 (pcr) / 25 (arx) / 30 + 13
(lagbank) rows while the measured error stays inside it on every row; the bound cuts RMSE E_XY1
2.6125 -> 2.6082 (mlr), 4.8025 -> 4.7537 (pcr), 3.0910 -> 3.0677 (arx), 4.1385 -> 4.0849
(lagbank; E_ZY1 3.5181 -> 3.5146): the guard doing its job on a model that extrapolates.

Status: the bar and the rule were committed in 0ece5f46 before any of 9782-9786 was simulated.
After it, before the fresh score: a stream object without ``last_take_`` / ``takes_`` read as
taking nothing (``getattr``; no change for the shipped streams), and this bench's reporting only
(``CELL+c``, ``faults``).  Scored once, 2026-12-06 04:48-04:53 UTC (2 shared cores, ``nice``).

Seen (``score`` at 55f940b8's src -> the rule's; events = every guard event, episodes = from free)::

  cr9762 C11       mlr-none mlr-ati pcr-none pcr-ati arx-none arx-ati lagbank-none lagbank-ati lstm-ati
  events main       7        3       5        5       9        0       5            0           2
  events rule       0        0       0        0       0        0       0            0           2
  C10, C12: 0 -> 0 everywhere; every cell's corrections max|rule - main| = 0 µm (RMSE the same
  to every digit); mlr-none's exported C = the rule's stream to 1.2e-14 µm over C10-C12.
  lmv9775 (bound events): mlr 2 -> 2, pcr 6 -> 6, arx 2 -> 2, lagbank 4 -> 4; max|dy| 0 µm.

B1: cr9762's 36 events (21 rate-limited episodes) -> 2, in 8 of 9 cells 0; lstm-ati's one pair
(E_X, 11880 s) remains: ATI over an LSTM has no step gain, so the clamp is not taken out of its
correction but streamed inside the model (the stream on the clamped inputs alone): no ``take``
to tell the clamp's step from the model's.  lmv9775's 14 bound events remain (traced above: the
bound right, the measured error inside it on every row).  B2: max|rule - main| = 0 µm in every
cell: RMSE unchanged.  B3: the guard and monitor tests below pass unchanged; bench_deploy_faults'
record (seed 5353, K06, 17 faults + healthy, mlr / arx / lagbank, adaptive form): the guard's
events per fault identical main / rule (none there: the monitor takes those faults) and the
corrections identical (max|dy| 0 µm over 51 streams).

Fresh, scored once (B4)::

  record   cells  events main -> rule         max|dy|  worst RMSE  dC (rule, compiled C)
  cr9782   6      0 -> 0 (C10-C12, every cell) 0 µm     +0 %        <= 8.2e-14 µm
  cr9783   6      0 -> 0                       0 µm     +0 %        <= 5.7e-14 µm
  cr9784   6      0 -> 0                       0 µm     +0 %        <= 3.8e-14 µm
  lmv9785  4      4 / 4 / 2 / 4 -> the same (bound)   0 µm     +0 %        <= 6.1e-14 µm
  lmv9786  4      2 / 6 / 2 / 4 -> the same (bound)   0 µm     +0 %        <= 4.8e-14 µm

B4 holds: events <= main's in every cell (equal), no RMSE worse, deployed = main's to 0 µm and =
the compiled C to 8.2e-14 µm.  The fresh climate rooms had no clamp chatter (0 events on main):
they show the rule harmless, not at work; the seen cr9762 is where it works.
Verdict KEPT (B1 with lstm-ati's one pair and lmv9775's bound events said, B2-B4 met).
CPU (this process): seen score 27.7 (main) / 30.8 s (rule) for cr9762, 5.0 / 5.4 s lmv9775;
fresh simulate + 26 runs 68.1 s; fresh score 33.1 (main) / 41.6 s (rule with the C);
faults 8.3 (main, with its fits) / 4.5 s (rule).
"""

from __future__ import annotations

import io
import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import project_root, run_commands, seed_list  # noqa: E402

FRESH = {"cr": ["sim=climate_room", "sim.generator.n_runs=12", "sim.generator.duration_h=[3.0,4.0]",
                "sim.generator.test_fraction=0.25"],          # bench_audit95's cr9762
         "lmv": ["sim=large_mill_volumetric"]}                # bench_audit96's lmv9775
CR_SEEDS = (9782, 9783, 9784)
CELLS = {"cr": ("mlr-none", "mlr-ati", "pcr-none", "pcr-ati", "arx-none", "lagbank-none"),
         "lmv": ("mlr-none", "pcr-none", "arx-none", "lagbank-none")}
WRAPPERS = {"none": [], "ati": ["ati=cmeans"]}


def _kind(event: dict) -> str:
    if event.get("sensor") is not None:
        return "sensor"
    return {"rate_limited": "rate", "bounded": "bound"}.get(event.get("to"), "other")


def _stream(data: str, model: str) -> dict:
    """Per test campaign ``(y, measured, events)`` of the deployed model streamed from a reset."""
    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.source import read_streamed

    cfg = compose([f"data.path={data}", "track=false"], "replay")
    ds, train, test, _ = read_streamed(cfg)
    dep, _, _ = deployable_model(cfg, ds, train, model, "replay.model")
    out = {}
    for c in test:
        s = stream_rows(dep, ds.campaigns[c], c)
        m = dep.compensator.measured({c: ds.campaigns[c]})[c][dep.targets_].to_numpy(float)
        out[c] = (np.asarray(s.y, float), m, list(s.events), dep.targets_)
    return out, dep, {c: ds.campaigns[c] for c in test}


def _c_apart(dep, frames: dict, folder: Path) -> float:
    """max|C's correction + deployed y| (µm) over ``frames``, each streamed from a reset by the
    compiled exported C (``-y`` is the correction it prints); NaN where the model exports no C."""
    import subprocess

    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.report import stream_rows

    try:
        ss = state_space(dep, monitor=True)
    except Exception:  # noqa: BLE001  (NotExportable and its kin: said as NaN)
        return float("nan")
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in exported_files(dep, "c").items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    subprocess.run(["gcc", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"], cwd=folder,
                   check=True, capture_output=True)
    worst = 0.0
    for c, frame in frames.items():
        y = np.asarray(stream_rows(dep, frame, c).y, float)
        run = subprocess.run([str(folder / "stream")], capture_output=True, text=True, check=True,
                             input=frame[["time", *ss.inputs]].to_csv(index=False, float_format="%.17g"))
        code = -pd.read_csv(io.StringIO(run.stdout)).to_numpy(float)
        worst = max(worst, float(np.nanmax(np.abs(code - y))))
    return worst


def score(data: str, models: str, out: str, *cells: str) -> None:
    """Per cell: events by kind, rows changed by the guard, RMSE per target (module doc); a cell
    named ``CELL+c`` also the exported C against the deployed stream (``dC``, µm)."""
    rows, ys = {}, {}
    for named in cells:
        cell, _, code = named.partition("+")
        streams, dep, frames = _stream(data, str(Path(models) / cell / "model.pkl"))
        if code:
            print(f"{cell:<28} dC {_c_apart(dep, frames, Path(out).parent / f'c-{cell}'):.3g} µm",
                  flush=True)
        for c, (y, m, events, targets) in streams.items():
            kinds = [_kind(e) for e in events if e.get("from") == "free" or e.get("sensor")]
            rmse = np.sqrt(np.nanmean((m - y) ** 2, axis=0))
            key = f"{cell}/{c}"
            rows[key] = {"events": len(events), **{k: kinds.count(k) for k in
                                                   ("rate", "bound", "other", "sensor")},
                         "rmse": dict(zip(targets, rmse.round(6).tolist()))}
            ys[key] = y
            print(f"{key:<28} events {len(events):>3}  rate {rows[key]['rate']:>2}  bound "
                  f"{rows[key]['bound']:>2}  other {rows[key]['other']}  sensor {rows[key]['sensor']}"
                  f"  RMSE mean {np.nanmean(rmse):.4f}", flush=True)
    Path(out).write_text(json.dumps(rows, indent=1))
    np.savez(Path(out).with_suffix(".npz"), **{k.replace("/", "__"): v for k, v in ys.items()})


def compare(base: str, rule: str) -> None:
    """Per cell: events base -> rule (rate, bound), the worst RMSE change per target, max|dy|."""
    b, r = json.loads(Path(base).read_text()), json.loads(Path(rule).read_text())
    yb, yr = np.load(Path(base).with_suffix(".npz")), np.load(Path(rule).with_suffix(".npz"))
    for key in b:
        worst = max((r[key]["rmse"][t] - v) / v if v else 0.0 for t, v in b[key]["rmse"].items())
        name = key.replace("/", "__")
        print(f"{key:<28} events {b[key]['events']:>3} -> {r[key]['events']:>3}  rate "
              f"{b[key]['rate']:>2} -> {r[key]['rate']:>2}  bound {b[key]['bound']:>2} -> "
              f"{r[key]['bound']:>2}  worst RMSE {100 * worst:+.4f} %  max|dy| "
              f"{np.nanmax(np.abs(yr[name] - yb[name])):.3g} µm")


def fresh(root: str, seeds: str) -> None:
    """SEEDS simulated in ROOT (9782-9784 climate rooms, the rest volumetric), every cell fitted."""
    from bench_audit86b import stage

    base = project_root(root)
    for seed in seed_list(seeds):
        kind = "cr" if seed in CR_SEEDS else "lmv"
        data = base / "data" / f"{kind}{seed}"
        if not (data / "campaigns.csv").exists():
            rc, said = stage("simulate", *FRESH[kind], f"seed={seed}", f"data.path={data}")
            assert rc == 0, said
        for cell in CELLS[kind]:
            family, wrapper = cell.split("-")
            out = base / "reports" / f"{kind}{seed}" / cell
            if not (out / "model.pkl").exists():
                rc, said = stage("run", f"data.path={data}", f"out={out}", "plots=none", "track=false",
                                 f"model={family}", *WRAPPERS[wrapper])
                print(f"{kind}{seed} {cell}: run exit {rc} {said[-120:] if rc else ''}", flush=True)


def faults(root: str, out: str) -> None:
    """bench_deploy_faults' record, models and faults through the adaptive form: per family and
    fault the guard's events (row, target, to) and the corrections (``OUT.json``, ``OUT.npz``)."""
    import bench_deploy_faults as bdf

    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    base = project_root(root)
    data = base / "ys"
    if not data.exists():
        bdf.main(["simulate", "sim=yearround_spindle", "seed=5353", "sim.generator.n_campaigns=9",
                  "sim.generator.duration_h=[3.0,5.0]", f"data.path={data}", f"out={base / 'sim'}"])
    raw = pd.read_csv(data / f"{bdf.CAMPAIGN}.csv")
    rows, ys = {}, {}
    for family in bdf.FAMILIES:
        model = base / family / "model.pkl"
        if not model.exists():
            bdf.main(["run", f"data.path={data}", f"model={family}", "track=false", "plots=none",
                      f"out={base / family}"])
        cfg = bdf._cfg(data, "monitor.adaptive=true")
        ds, train_ids, _, _ = read_streamed(cfg)
        dep = deployable_model(cfg, ds, train_ids, str(model), "replay.model")[0]
        for name, df in {"healthy": raw, **bdf.faults(raw)}.items():
            try:
                s = stream_rows(dep, df, bdf.CAMPAIGN)
            except Exception as exc:  # noqa: BLE001  (a refusal: said)
                rows[f"{family}/{name}"] = str(exc)[:80]
                continue
            t = df["time"].to_numpy(float)
            got = [[int(np.searchsorted(t, e["time"])) if np.isfinite(e["time"]) else -1,
                    e["target"], e["to"]] for e in s.events if e.get("target")]
            rows[f"{family}/{name}"] = got
            ys[f"{family}__{name}"] = np.asarray(s.y, float)
            print(f"{family:<8} {name:<17} guard events {got}", flush=True)
    Path(out).write_text(json.dumps(rows, indent=1))
    np.savez(Path(out).with_suffix(".npz"), **ys)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": score, "compare": compare, "fresh": fresh,
                                  "faults": faults}, argv,
                        cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
