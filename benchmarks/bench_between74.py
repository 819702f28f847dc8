"""What the rows between the grid cost (deploy74): ``between_steps`` streamed each campaign's grid
rows again for their states after the batch had predicted them, and deep-copied the state for
every row between.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_between74.py cpu ROOT [seed ...]

``cpu``: bench_between73's ``mixed`` record per seed (default 7456 7457: the swiss lathe, its
error known every 60 s, trained on every 5th row (300 s), its production run tested at 60 s);
``run`` and ``replay`` of it per family with a memory (lagbank, hammerstein, lstm as bench
lab_matrix shortens it), the sha256 of their ``metrics.json`` and ``replay.json`` (the outputs
that must stay byte-identical; their own timings left out), and in process the CPU (user +
sys, best of 3) of the model's batch prediction of the 60 s production run, of the
``between_steps`` calls within it, and within those of the grid rows streamed again and of the
states deep-copied; whether one stream pass could give the grid rows' answers too (the grid
rows streamed as ``between_steps`` streams them, byte for byte against the batch's).

Not a rule that changes a choice (no bar): the change is kept only where the digests are the
same before and after, and only if the CPU it saves is measurable.

Measured (2026-12-02, 2 shared cores, CPU user + sys; before: 4812ce97's code, after: this
branch's, deploy74 items 1, 2 and 4; the production run 1441 rows at 60 s)
--------------------------------------------------------------------------------------------
metrics.json and replay.json (timings left out) the same before and after for all 12 seed x
family runs.  After, per 1441-row batch prediction (best of 3):

    seed family       predict  between_steps  grid rows again  deep copies   run    replay
    7456 lagbank       0.248       0.224          0.100           0.026      3.6 s   1.6 s
    7456 hammerstein   0.349       0.328          0.178           0.027      3.0 s   1.9 s
    7456 lstm          0.966       0.937          0.123           0.248     11.0 s   6.4 s
    7457 lagbank       0.239       0.223          0.097           0.028      1.5 s   1.4 s
    7457 hammerstein   0.408       0.385          0.208           0.032      3.1 s   1.8 s
    7457 lstm          0.909       0.883          0.121           0.229      6.9 s   6.5 s

(before, the same code for this: between_steps 0.185-0.212 / 0.415-0.425 / 0.807-0.989 s.)
between_steps is 90-97 % of the prediction; the grid rows streamed again 43-54 % of it for the
lag bank and Hammerstein, 13-14 % for the LSTM (its deep copies 26-27 %).  Measurable, but not
removable with the outputs byte-identical: the grid rows streamed as between_steps streams them
DIFFER from the batch's answers there on every run (max 1.4e-14 to 3.2e-14 µm), so one pass that
yields both changes the grid rows' answers (and the metrics), and the batch's own states (kept
while predicting) are not the states the stream commits, from which the rows between are
answered today.  The deep copies guard the committed state against a stream_step that changes
the state it is given; which family's does not is no generic knowledge.  Left as it is (REFUSED:
no src change).
"""

from __future__ import annotations

import hashlib
import resource
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(REPO / "benchmarks")]

import bench_between73  # noqa: E402
import lab_matrix  # noqa: E402
from _cli import run_commands  # noqa: E402

SEEDS = (7456, 7457)
FAMILIES = {f: bench_between73.FAMILIES[f] for f in ("lagbank", "hammerstein", "lstm")}


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


TIMING = ("fit_time_s", "us_per_sample")     # what a run measures of its own speed


def _digest(path: Path, root: Path) -> str:
    """sha256 of the JSON file, the bench's root written ROOT (replay.json names the model's
    path) and the timings (:data:`TIMING`) left out."""
    import json

    if not path.exists():
        return "missing"

    def kept(value):
        if isinstance(value, dict):
            return {k: kept(v) for k, v in value.items() if k not in TIMING}
        return [kept(v) for v in value] if isinstance(value, list) else value

    text = path.read_text(encoding="utf-8").replace(str(root), "ROOT")
    return hashlib.sha256(json.dumps(kept(json.loads(text))).encode()).hexdigest()[:16]


def _timed_predict(model: Path, test) -> dict:
    """CPU s (best of 3) of the batch prediction of ``test`` (``predict``), of its
    ``between_steps``, of the grid rows streamed again within them (``stream_steps``) and of
    the state deep-copied for each row between (``deepcopy``)."""
    import copy
    from types import SimpleNamespace

    from thermocomp.core import compensator, context
    from thermocomp.shell.model_store import load_model

    comp = load_model(model)
    spent = dict.fromkeys(("between_steps", "stream_steps", "deepcopy"), 0.0)

    def timed(name, inner):
        def call(*args, **kwargs):
            t = _cpu()
            try:
                return inner(*args, **kwargs)
            finally:
                spent[name] += _cpu() - t
        return call

    saved = compensator.between_steps, context.stream_steps, context.copy
    compensator.between_steps = timed("between_steps", saved[0])
    context.stream_steps = timed("stream_steps", saved[1])
    context.copy = SimpleNamespace(deepcopy=timed("deepcopy", copy.deepcopy))
    try:
        best = None
        for _ in range(3):
            spent.update(dict.fromkeys(spent, 0.0))
            t = _cpu()
            comp.predict({"p": test})
            if best is None or _cpu() - t < best["predict"]:
                best = {"predict": _cpu() - t, **spent}
    finally:
        compensator.between_steps, context.stream_steps, context.copy = saved
    return best


def _one_pass(model: Path, test) -> str:
    """Whether one stream pass could yield the grid rows' answers too: the grid rows streamed
    as ``between_steps`` streams them (a campaign's first row alone, then each run of grid rows
    as a block) against the batch's answers there, byte for byte (the production run is one
    campaign)."""
    import numpy as np

    from thermocomp.core.compensator import _simulation
    from thermocomp.core.context import row_context, stream_steps
    from thermocomp.core.timerule import grid_rows
    from thermocomp.shell.model_store import load_model

    comp = load_model(model)
    m = comp.stacked({"p": test})
    stepped = grid_rows(m.time, m.groups, comp._grid_candidate())
    batch = comp.predict_stacked(m.subset(stepped), "simulation")
    cols = {c: v.to_numpy() for c, v in _simulation(m.context).items()}
    worst, equal = 0.0, True
    for k, (target, est) in enumerate(comp.estimators_.items()):
        X = m.X[comp.selected_[target]].to_numpy()
        first = row_context(cols, 0, len(X))
        y, state = est.stream_step(X[0], est.stream_init(first), first)
        ys, i = [y], 1
        while i < len(X):
            j = i + 1
            while stepped[i] and j < len(X) and stepped[j]:
                j += 1
            if stepped[i]:
                y, state = stream_steps(est, X[i:j], state, {c: v[i:j] for c, v in cols.items()})
                ys.extend(y)
            i = j
        ys = np.asarray(ys, float)
        equal &= ys.tobytes() == batch[:, k].tobytes()
        worst = max(worst, float(np.abs(ys - batch[:, k]).max()))
    said = "byte-identical to" if equal else "DIFFER from"
    return f"grid rows streamed {said} the batch's (max {worst:.2g} µm)"


def cpu(root: Path, seeds: list[str]) -> None:
    import pandas as pd

    lab_matrix.project(root)
    for seed in [int(s) for s in seeds] or SEEDS:
        base = bench_between73.records(root, seed)
        test = pd.read_csv(base / "mixed" / "production.csv")
        for family, extra in FAMILIES.items():
            out, data = base / "out" / f"mixed-{family}", [f"data.path={base / 'mixed'}"]
            rc, err, run_cpu = lab_matrix.stage("run", *data, f"model={family}", *extra,
                                                "track=false", "plots=none", f"out={out}")
            if rc:
                print(f"{seed} {family}: run exit {rc}: {err[:200]}", flush=True)
                continue
            rc, err, replay_cpu = lab_matrix.stage("replay", *data, f"replay.model={out / 'model.pkl'}",
                                                   "track=false", "plots=none",
                                                   f"out={base / 'out' / f'replay-{family}'}")
            t = _timed_predict(out / "model.pkl", test)
            print(f"{seed} {family}: rows {len(test)}; metrics.json {_digest(out / 'metrics.json', root)}, "
                  f"replay.json {_digest(base / 'out' / f'replay-{family}' / 'replay.json', root)} "
                  f"(replay exit {rc}); CPU run {run_cpu:.1f} s, replay {replay_cpu:.1f} s, "
                  f"batch predict {t['predict']:.3f} s, between_steps {t['between_steps']:.3f} s, in "
                  f"it the grid rows streamed again {t['stream_steps']:.3f} s and the states "
                  f"deep-copied {t['deepcopy']:.3f} s; {_one_pass(out / 'model.pkl', test)}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cpu": lambda root, *seeds: cpu(Path(root).resolve(), list(seeds))},
                        argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
