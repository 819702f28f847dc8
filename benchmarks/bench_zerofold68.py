"""An independent check of rule Z2 (``model=auto``'s zero correction judged fold by fold, with a
margin) on records nobody tuned on, where the zero can fire (issue 34; stop 68, zerofold68).

Usage::

    python benchmarks/bench_zerofold68.py write ROOT            # the 12 records (once)
    PYTHONPATH=<fix/autoloss68's src> python benchmarks/bench_zerofold68.py run ROOT [RECORD ...]
    python benchmarks/bench_zerofold68.py score ROOT            # shipped against Z2, the verdict
    python benchmarks/bench_zerofold68.py check ROOT [RECORD ...]   # Z2's src end to end

The rule (src, ``AutoRegressor._none_unless_better``; autoloss68's rule Z with ``FOLD_MARGIN`` 2,
its ``MARGIN``): under ``uncompensated=zero`` (the default) a target whose kept model's pooled
validation RMSE is not below no correction's keeps the zero correction UNLESS the kept model's
per-fold measure (``blend.mean_fold_ratio``: each fold's summed squared error over MLR's there,
averaged over the folds) is below HALF of no correction's.  Z2 only removes zeros; one-fold
records and a val split are unchanged.  autoloss68 scored Z2 after its verdict on the records it
had (iso_a / iso_b: 4 zeros undone, bar geometric mean 0.756; guard 1.000), so those are not
evidence: its factor was chosen with them in sight.

The records (chosen and written here BEFORE anything was fitted or scored; seeds 6861-6872, on
none of which anything was run; kinds where the shipped zero fired before)
-----------------------------------------------------------------------------------------------
* ``iso6861..6863``: iso67's machining centre (``benchmarks/iso67.py``), the lab's files as
  bench_iso67 writes them (tilts in µrad), ``thermocomp init`` of the folder as written (it holds
  the last test out, ``test_fraction: 0.1``: 5 train tests, 1 test), candidates bench_iso67's
  matrix ``[mlr,pcr,arx,lagbank,hammerstein,ati]`` (autoloss68's ``ISO_CANDIDATES``);
* ``grind14_6864``, ``grind14_6865``: stable67's grinder as built (``spindle_um=0``), 14 runs, the
  last fifth held out (bench_zerofew67's ``grind_record``, as its ``grind_a``);
  ``grind14_6866``, ``grind14_6867``: the same with the 1.5 µm spindle growth (as ``grind_b``);
* few-run records as bench_zerofew67 built them: ``grind5_6868`` (5 runs, as built),
  ``grind5_6869`` (5 runs, ``spindle_um=1.5``), ``spindle6870..6872`` (test_export_guard's spindle
  fixture, 4 train campaigns, its rng seeded 6870-6872).  (Its year / lab kinds never zeroed: left
  out, they cannot tell Z2 from the rule.)

Each record is fitted ONCE with the shipped code (fix/autoloss68's src, equal to main's) by
bench_autoloss68's runner (``fitted``: bench_auto_rank through bench_remeasure62's ``auto_row``,
the default ``uncompensated=zero``, every candidate's out-of-fold and test predictions kept) and
scored from those arrays by bench_autoloss68's ``zero_row``: the shipped zero decision recomputed
and asserted against the fit's, Z2's (``zeroed and q_none <= 2 q_kept``) beside it; a zeroed
target tests the RMS of its test labels, a kept one the kept model's test RMSE.  Per record the
mean test RMSE over its targets.  ``check`` then runs ``thermocomp run model=auto`` with Z2's src
on every record where Z2 differs, and on ``make run``'s record and ``fl_thermal`` 90/10: the
figures must equal the arrays' (records that differ) and the rule must not fire (the other two:
the code differs from the shipped only in the branch that says "fold by fold").

The verdict (written and committed before anything was scored)
---------------------------------------------------------------
Z2 is adopted only if ALL hold:
(1) at least 3 records where the shipped zero fires on some target (else "not enough evidence",
    not adopted, whatever the rest says);
(2) over the records where shipped and Z2 differ on any target: the geometric mean of record mean
    test RMSE Z2 / shipped <= 1.0, and no record's ratio > 1.03;
(3) unchanged: ``make run``'s record under ``model=auto`` (E_X / E_Y / E_Z: the rule does not fire)
    and ``fl_thermal`` 90/10 ``model=auto`` mean test RMSE 2.481 µm (``data=fl_thermal``).
If (2) holds vacuously (Z2 differs nowhere) Z2 is not adopted either: nothing would show it helps.
Otherwise src is reverted, the bench kept with its numbers: REFUSED.

Measured 2026-12-01 (stop 68; fits with fix/autoloss68's src dda5a27a, Z2 in cbc7b18f; 2 shared
cores under other sessions' load; run once; CPU user + sys: ``write`` 12.5 s, ``run`` 86.6 s (iso
4.8-5.3 s each, grind14 11.4-16.1, the few-run records 5-6), ``score`` 0.7 s, ``check`` 96.8 s).
(``score`` prints autoloss68's ``summary``: its "Z" is margin 1, its "Z2 (deciding nothing)" label
is autoloss68's; here Z2 is the rule judged.)  The shipped zero fires on all 12 records, 17
targets; Z2 undoes 6, all on the iso records (E_Y1 and E_Tilt_A of each; q none / q kept 5.5-265),
and keeps the 11 others (q none / q kept <= 1.044, spindle6871 E_X 0.9438 / 0.9039, which margin 1
would have undone: 1.664 -> 2.042 µm, +22.7 %).  Test RMSE zero -> Z2 (MLR):

  iso6861  E_Y1 2.185 -> 1.027 (0.9665)   E_Tilt_A 20.40 -> 1.841 (1.914)   record 0.1759
  iso6862  E_Y1 2.184 -> 0.2395 (0.2812)  E_Tilt_A 22.01 -> 0.5043 (0.5299) record 0.0681
  iso6863  E_Y1 2.213 -> 0.1972 (0.299)   E_Tilt_A 19.48 -> 0.5828 (0.6886) record 0.1183

Records better than MLR 7 -> 10 of 12; within 10 % of the best family 6 -> 7.
(1) 12 records >= 3; (2) 3 records differ, geometric mean 0.1123, worst 0.1759; (3) ``check``:
Z2's src end to end on iso6861-6863 equals the arrays' Z2 on every target (<= 2.2e-16 relative,
the reason says "fold by fold"); ``make run``'s record auto 0.6481 / 0.8429 / 0.9943
(docs/measured/models.md's 0.648 / 0.843 / 0.994) and ``fl_thermal`` 90/10 auto mean 2.481, the
rule firing on neither.
**Verdict: PASSES, Z2 adopted.**  Its limit: every zero undone is iso67's one kind of fold (its test
plan puts the X-axis test in fold 0 on every seed), and no target fell between 1.044 and 5.5.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import bench_autoloss68 as autoloss  # noqa: E402
import bench_iso67 as iso  # noqa: E402
import bench_remeasure62 as remeasure  # noqa: E402
import bench_zerofew67 as zerofew  # noqa: E402
from _cli import run_commands  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

ISO = {f"iso{s}": s for s in (6861, 6862, 6863)}
GRINDS = {**{f"grind14_{s}": (14, 0.0 if s < 6866 else 1.5, s) for s in (6864, 6865, 6866, 6867)},
          "grind5_6868": (5, 0.0, 6868), "grind5_6869": (5, 1.5, 6869)}
SPINDLES = {f"spindle{s}": s for s in (6870, 6871, 6872)}
RECORDS = {
    **{n: ["hydra.searchpath=[file://{root}/init-" + n + "/conf]", f"data={n}",
           autoloss.ISO_CANDIDATES] for n in ISO},
    **{n: ["data.path={root}/" + n] for n in (*GRINDS, *SPINDLES)},
}
WORST, SHOWN = 1.03, 3          # the verdict's bars: worst record ratio, records where the zero fires
FL9010_AUTO = 2.481             # fl_thermal 90/10 model=auto mean test RMSE (README)


def write(root: Path) -> None:
    root.mkdir(parents=True, exist_ok=True)
    iso.SEEDS = ISO                                  # bench_iso67's writer, these seeds
    iso.write(root)
    for name in ISO:
        if not (root / f"init-{name}").exists():
            iso.initialised(root, name, [])
    for name, args in GRINDS.items():
        if not (root / name).exists():
            zerofew.grind_record(root / name, *args)
    for name, seed in SPINDLES.items():
        if not (root / name).exists():
            zerofew.spindle_record(root / name, seed)


def verdict(root: Path) -> tuple[list[str], dict]:
    result = autoloss.scored(root, list(RECORDS))
    lines, _ = autoloss.summary(f"fresh ({len(result)} records, seeds 6861-6872)", result)
    fires = [n for n, s in result if any(r["zeroed"] for r in s["targets"].values())]
    differ = {n: s["mean"]["Z2"] / s["mean"]["shipped"] for n, s in result
              if any(r["zeroed"] != r["zeroed_Z2"] for r in s["targets"].values())}
    geo = float(np.exp(np.mean(np.log(list(differ.values()))))) if differ else float("nan")
    worst = max(differ.values()) if differ else float("nan")
    ok = {f"zero fires on >= {SHOWN} records ({len(fires)})": len(fires) >= SHOWN,
          f"Z2 differs somewhere ({len(differ)})": bool(differ),
          f"geometric mean Z2 / shipped {geo:.4f} <= 1.0": geo <= 1.0,
          f"worst {worst:.4f} <= {WORST}": worst <= WORST}
    lines += [f"the shipped zero fires on: {', '.join(fires) or 'none'}",
              "records where Z2 differs (Z2 / shipped): "
              + (", ".join(f"{n} {q:.4f}" for n, q in differ.items()) or "none"),
              "verdict (1)-(2): " + ", ".join(f"{k} {'yes' if v else 'NO'}" for k, v in ok.items())
              + (" -> PASSES (then (3): check)" if all(ok.values()) else
                 " -> not enough evidence" if len(fires) < SHOWN else " -> FAILS")]
    return lines, {n: s for n, s in result if n in differ}


def _env() -> dict:
    """This tree's src, the project root its own (``data=fl_thermal``'s relative path)."""
    env = dict(os.environ, PYTHONPATH=str(HERE.parent / "src"))
    env.pop("THERMOCOMP_ROOT", None)
    return env


def run_auto(root: Path, label: str, overrides: list[str]) -> dict:
    """``thermocomp run model=auto`` with this tree's src: per target (test RMSE, auto's reason)."""
    out = root / "check" / label
    start = cpu_seconds(children=True)
    subprocess.run([sys.executable, "-m", "thermocomp", "run", *overrides, "model=auto",
                    "track=false", "plots=none", f"out={out}"], cwd=HERE.parent, check=True,
                   capture_output=True, env=_env())
    metrics = json.loads((out / "metrics.json").read_text())
    said = json.dumps(metrics)
    return {"cpu_s": round(cpu_seconds(children=True) - start, 1), "fold by fold": "fold by fold" in said,
            "rmse": {t: v["test"]["rmse"] for t, v in metrics["targets"].items()}}


def check(root: Path, names: list[str]) -> list[str]:
    _, differ = verdict(root)
    lines = []
    for name in names or list(differ):
        got = run_auto(root, name, [o.format(root=root) for o in RECORDS[name]])
        want = {t: r["Z2"] for t, r in differ[name]["targets"].items()} if name in differ else {}
        gap = max((abs(got["rmse"][t] - v) / v for t, v in want.items()), default=float("nan"))
        lines.append(f"{name}: Z2's src test RMSE {got['rmse']}; largest relative gap to the arrays' "
                     f"Z2 {gap:.2e}; rule fired: {got['fold by fold']}; CPU {got['cpu_s']} s")
    if not names:
        sim = root / "make_run"
        subprocess.run([sys.executable, "-m", "thermocomp", "simulate", f"data.path={sim}",
                        "track=false"], cwd=HERE.parent, check=True, capture_output=True, env=_env())
        for label, overrides in (("make_run", [f"data.path={sim}"]), ("fl9010", ["data=fl_thermal"])):
            got = run_auto(root, label, overrides)
            mean = float(np.mean(list(got["rmse"].values())))
            lines.append(f"{label}: auto test RMSE {got['rmse']} (mean {mean:.4g}); the rule fired: "
                         f"{got['fold by fold']}; CPU {got['cpu_s']} s"
                         + (f"; fl9010 {mean:.3f} against {FL9010_AUTO}" if label == "fl9010" else ""))
    return lines


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "write": lambda root, *_: write(Path(root).resolve()),
        "run": lambda root, *names: autoloss.fitted(Path(root).resolve(), list(names) or list(RECORDS),
                                                    RECORDS),
        "score": lambda root, *_: print(remeasure._wrapped(verdict(Path(root).resolve())[0], 110)),
        "check": lambda root, *names: print("\n".join(check(Path(root).resolve(), list(names)))),
    }, argv, cpu=sys.stdout)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
