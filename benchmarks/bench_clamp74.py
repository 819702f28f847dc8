"""A machine running colder than in training, and the envelope's pattern gate (clamp74).

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_clamp74.py score ROOT SRC TAG
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_clamp74.py bar ROOT OLD_TAG NEW_TAG
    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_clamp74.py faults ROOT OLD_SRC NEW_SRC

``ROOT/fs<seed>.txt`` and ``ROOT/mx<seed>/<family>-<wrapper>/model.pkl`` as ``bench_stranger74.py
write ROOT SEED 24 60`` and its ``matrix`` make them (tcm74, 24 h at 60 s, cut 70/30: the test
part is the night). ``score``: ``replay`` of every fitted cell with ``PYTHONPATH=SRC`` (a source
tree: the shipped one from ``git archive``, or this one), run's and replay's test RMSE per target
into ``ROOT/score-TAG.json``. ``bar``: the cells side by side and the bar below. ``faults``:
``bench_deploy_faults.py`` with each source tree, every figure of its table compared.

Why the night was clamped (seed 7442, mlr, diagnosed before the rule): the hall air falls below
any training row (hall sensors 18.1 against 19.1 °C) while the beds, whose time constant is a
day, are hotter than any training row (their heat accumulates): 381 of 432 test rows outside
the range. The pattern (rank 9 of 22 inputs) covers the largest part of that move, its
components beyond their training range (the 6th: -1.31 against -0.21 .. 0.17), but the
residual off it is the residual of a longer excursion: median 1.23 x tol² (0.45 .. 5.2), spread
over the small components (each within ~1.3 x its training range; the most: 'Ständer oben', the
sensor the monitor then excludes), 246 rows clamped by the plain stream. A level of the hall no
training row saw is the one direction the pattern cannot learn from one day, and the one physics
gives: the heat equation is linear with the air as its boundary, so a machine in a hall
colder by d runs, in steady state, colder by d at every sensor, the rises of its sources
unchanged (the uniform shift, uncorrelated with any heat source's pattern).

Rule (fixed before scoring; no constant tuned): the training pattern's basis takes the uniform
shift of the temperature inputs (``T_``; in the scaled frame ``1 / scale``, orthogonalised
against the principal basis) as one more direction, ``tol`` the largest training residual off
the widened basis, as before; where the widened basis would span every input the pattern is
kept as it was (a gate needs a direction to leave). A sensor's offset, a spike, an unseen source
move sensors apart, not together: they stay off it.

Bar (clamp74, written before scoring): tcm74 seeds 7442 and fresh 7486-7490 (cut 70/30), every
cell fitted (family x wrapper of ``bench_stranger74``'s matrix; the cells fitted by the time of
scoring, the same cells for both trees), a cell's figure the pooled RMSE over E_dX/E_dY/E_dZ
(sqrt of the mean of the squared RMSEs): (1) more cells deployed within 5 % of run's pooled
RMSE or better than shipped, i.e. count(new <= 1.05 run) > count(shipped <= 1.05 run);
(2) no cell worse than shipped by > 2 % (new <= 1.02 shipped, every cell); (3)
``bench_deploy_faults.py``: no figure worse than shipped by > 2 % (a figure 0.0 read as 0.05);
(4) tests/apps/test_envelope*.py and tests/*/test_deploy*.py pass. If any fails: src reverted,
the rule kept as ``benchmarks/clamp74_rule.patch``, REFUSED.

Measured 2026-12-02 (clamp74): REFUSED, src reverted, the rule kept as
``benchmarks/clamp74_rule.patch``. 49 cells (8 families without wrapper x 6 seeds, and 7442's mlr
with ``denoise=emd``; the matrix's other wrappers were not fitted in time), pooled RMSE µm run /
shipped / rule: bar 1 failed, 11 and 11 cells within 5 % of run; bar 2 met (no cell worse by > 2 %;
the worst +1.9 %, 7442 lagbank 1.160 -> 1.183). It helps where the night is a colder hall: 7442 mlr
0.780 / 1.310 / 1.147 (E_dX 1.428 -> 1.044, E_dY 0.389 -> 0.302, E_dZ 1.720 -> 1.664; clamped 109 ->
47), arx 1.451 -> 1.290, lstm 1.395 -> 1.224, auto 1.314 -> 1.167, pcr 3.803 -> 3.795; 7488 mlr
1.075 -> 1.047, arx 1.219 -> 1.143; 7486, 7487, 7489, 7490 within 0.4 % (mlr 7490: 267 rows clamped
either way). On 7490 (looked at after scoring) the hall is not colder: the beds are hotter than any
training row (bed3/bed4 outside on 372/394 of 432 rows; their heat, a day's time constant,
accumulates), the residual off the pattern mostly the column's, the floor's and the motor's sensors
(median 2.25 x tol²), and the deployed gap is the monitor's as much as the clamp's (mlr 7490, run
1.041 / 1.035 / 0.507: envelope off 1.295 / 0.679 / 3.156, monitor off 1.695 / 0.869 / 0.590).
Bar 3 failed: every fault of the table as shipped to the digit (spikes, offsets of T_amb, stuck,
kelvin: sensors moving apart stay clamped), but the air stepped for real (+5 K, T_amb's column and
the structure following) is clamped less: the plain stream's RMS after the step, mlr 6.46 -> 8.37
µm, lagbank 11.77 -> 12.23; over 30 min mlr 6.76 -> 7.45, lagbank 10.17 -> 10.51 (adaptive 3.93 ->
4.04); better for arx's plain stream (+5 K: 5.61 -> 5.44) and the adaptive mlr (over 30 min: 6.21 ->
5.71). An air step is no steady state: the uniform direction takes up part of it (the air alone
projects on it), and the models' static response to the air overshoots the structure's slow one. Bar
4 met (97 passed with the rule). CPU: 295 s per tree for the 49 replays, 30 s for ``faults``.
"""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402

HERE = Path(__file__).resolve().parent


def _env(src: str) -> dict:
    return {**os.environ, "PYTHONPATH": str(Path(src).resolve())}


def score(root: str, src: str, tag: str) -> None:
    """Replay every ``ROOT/mx<seed>/<cell>/model.pkl`` with the source tree ``src``."""
    root_p = Path(root).resolve()
    scores = {}
    for model in sorted(root_p.glob("mx*/*/model.pkl")):
        seed, cell = model.parent.parent.name[2:], model.parent.name
        keys = {"emd": ["denoise=emd"], "pearson": ["select=pearson"]}.get(cell.rsplit("-", 1)[1], [])
        out = root_p / "replays" / tag / seed / cell
        ran = subprocess.run([sys.executable, "-m", "thermocomp", "replay",
                              f"hydra.searchpath=[file://{root_p / 'conf'}]", f"data=fs{seed}",
                              "track=false", *keys, f"replay.model={model}", f"out={out}"],
                             capture_output=True, text=True, env=_env(src))
        if ran.returncode:
            print(f"{seed} {cell}: replay exit {ran.returncode}: {ran.stderr[-300:]}")
            continue
        scored = json.loads((model.parent / "metrics.json").read_text())["targets"]
        streamed = json.loads((out / "replay.json").read_text())["targets"]
        scores[f"{seed} {cell}"] = {t: [scored[t]["test"]["rmse"], r["rmse"]] for t, r in streamed.items()}
        print(f"{seed} {cell}: " + "; ".join(f"{t} {a:.3f} / {b:.3f}" for t, (a, b) in
                                             scores[f"{seed} {cell}"].items()), flush=True)
    (root_p / f"score-{tag}.json").write_text(json.dumps(scores, indent=1))


def _pooled(cell: dict, which: int) -> float:
    return (sum(v[which] ** 2 for v in cell.values()) / len(cell)) ** 0.5


def bar(root: str, old: str, new: str) -> None:
    """The cells of both scores side by side, and bars (1) and (2)."""
    root_p = Path(root)
    a, b = (json.loads((root_p / f"score-{t}.json").read_text()) for t in (old, new))
    good_old = good_new = 0
    worse = []
    print(f"{'cell':24s} {'run':>7s} {old:>7s} {new:>7s}   (pooled RMSE, µm)")
    for key in sorted(set(a) & set(b)):
        run, shipped, now = _pooled(a[key], 0), _pooled(a[key], 1), _pooled(b[key], 1)
        good_old += shipped <= 1.05 * run
        good_new += now <= 1.05 * run
        if now > 1.02 * shipped:
            worse.append(key)
        print(f"{key:24s} {run:7.3f} {shipped:7.3f} {now:7.3f}")
    print(f"within 5 % of run: {old} {good_old}, {new} {good_new} of {len(set(a) & set(b))} cells; "
          f"worse than {old} by > 2 %: {worse or 'none'}")
    print("bar 1 and 2:", "met" if good_new > good_old and not worse else "FAILED")


def _figures(src: str, root: str) -> list[str]:
    ran = subprocess.run([sys.executable, str(HERE / "bench_deploy_faults.py"), "--root", root],
                         capture_output=True, text=True, env=_env(src))
    if ran.returncode:
        raise SystemExit(f"bench_deploy_faults with {src}: {ran.stderr[-500:]}")
    return ran.stdout.splitlines()


def faults(root: str, old_src: str, new_src: str) -> None:
    """Bar (3): every number of ``bench_deploy_faults``'s lines, shipped against now."""
    number = re.compile(r"-?\d+\.\d+(?:e[-+]?\d+)?")
    old, new = _figures(old_src, f"{root}/old"), _figures(new_src, f"{root}/new")
    worse = []
    for line_old, line_new in zip(old, new):
        if line_old != line_new:
            print(f"shipped: {line_old}\nnow:     {line_new}")
        for x, y in zip(number.findall(line_old), number.findall(line_new)):
            if abs(float(y)) > 1.02 * max(abs(float(x)), 0.05):
                worse.append((line_new[:26], x, y))
    print(f"{len(old)} lines; figures worse than shipped by > 2 %: {worse or 'none'}")
    print("bar 3:", "met" if not worse and len(old) == len(new) else "FAILED")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": score, "bar": bar, "faults": faults}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
