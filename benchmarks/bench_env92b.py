"""A per-target training envelope decided on the train part alone: does a train-only extrapolation
check single out the target (``E_X``) that env92 found worse clamped on column records?  (env92b,
issue 34; a trace, no rule shipped.)

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_env92b.py check ROOT SEEDS FRACTION
    python benchmarks/bench_env92b.py trace ROOT FRACTION

``check``: per seed of SEEDS (``3141,5003,4253,6007,9406``), bench_env92's ``draw`` (the full
``column_moving_source`` record into ``ROOT/data/cms<seed>``, its test campaign replayed ``clamp``
/ ``off`` / ``pattern`` per family ``mlr``, ``arx``, ``lagbank``, lines in ``ROOT/results.jsonl``),
then the train-only check: the record's train campaign alone, as a lab's one file, cut
chronologically by ``data.test_fraction=FRACTION`` (the model fitted on the first part, the last
part continuing it: on these records the train cycle's hottest stretch lies at 60-80 % of its 40 h,
so ``0.4`` puts it in the checked part), measured by the same bench_envelope_policy line
(``ROOT/cut<FRACTION>/results.jsonl``).  Nothing of the test campaign enters the check.
``trace``: per cell the rule's Σ² on the test campaign, composed per target; per check the
targets it unclamps and G, the geometric mean over the cells of Σ²(rule) / Σ²(pattern).

The rule traced (chosen on the seen seeds above, the only records it was looked at on): a target
is clamped in deployment iff on the check the shipped clamp (``pattern``, the default gate) leaves
its squared RMSE no larger than ``off`` does, else it streams unclamped.  Its test Σ² per cell is
the sum over targets of the chosen replay's squared RMSE: exact for these families, whose targets
are fitted and streamed one model each (a target's prediction does not depend on another's clamp).
Also shown: the check with every excursion clamped (``clamp``, ``pattern=false``) in place of the
gate, the oracle (per target the better of pattern / off on test) and "E_X alone unclamped".

BAR (for a follow-up that builds the rule; written 2026-12-05 before any fresh seed was drawn, and
no fresh seed was drawn here): FRESH ``column_moving_source`` seeds 9506-9515 x mlr/arx/lagbank,
G = geometric mean over the cells of Σ²(per-target) / Σ²(pattern) <= 0.95 and the cells > 10 %
worse no more than the cells > 10 % better; bench_envelope_policy's non-column lines (mill, long,
fl: its ``--table`` or a re-run of the cheap ones) not worse.  The brief's gate before that bar:
the check must single out ``E_X``.

Traced (2026-12-05, fix/env92b = main 2b918bfd's src; seen seeds 3141, 5003, 4253, 6007, 9406;
``check /tmp/env92b/seen 3141,5003,4253,6007,9406 0.4``, then ``0.3``)::

  targets unclamped by the rule, of 15 cells   E_X E_Y E_Z E_X_mid E_Y_mid E_Z_mid   G    >10%: worse/better
  FRACTION 0.4 (576 checked samples; every-excursion clamp acting on 171-430, the gate on 7-114)
  check clamp                                  14  14  15   13      14      15     1.221        7 / 5
  check pattern                                13   6  10   13       7       7     0.735        3 / 10
  FRACTION 0.3 (432 checked samples; a robustness look, written down after 0.4's numbers)
  check clamp                                   7   3   8    7       6       8     0.974        1 / 4
  check pattern                                 3   2   8    3       1       7     0.908        2 / 3
  oracle (per target the better of pattern / off on test) 0.545; E_X alone unclamped 0.582

CPU: ``check`` 101 s (the five full records' 15 cells and the 15 cuts at 0.4), 34 s more for 0.3.

The answer: **no, the check does not single out E_X.**  With every excursion clamped, clamping
hurts every target on the train part (squared RMSE up to 259x ``off``, E_X the largest in most
cells) and the rule unclamps nearly everything (= ``off``, 1.221).  Through the shipped gate it
unclamps E_X in 13 of 15 cells but E_X_mid just as often (13 of 15), and E_X_mid is better clamped
on the test campaign in 15 of 15 (env92); E_Z 10 of 15.  The check's numbers are small: ``off``
leaves E_X at ~1 µm² on the checked part (what it decides on is the clamp's cost there, not a
held-out extrapolation of a source it never saw: the train record has no Q3).  The gain over the
default on the seen seeds (0.735) is real but about 60 % of the oracle's gain (0.545) and
comes with 3 cells > 10 % worse (cms3141 lagbank 1.14, 6007 mlr 1.22, arx 1.27) against 10 better.
At FRACTION 0.3 the check flips: E_X unclamped in 3 of 15 cells only (E_Z in 8), G 0.908: what
it decides rides on where the cut falls, not on the target.  The fresh seeds 9506-9515 were left undrawn (the
brief's gate failed).
Verdict: TRACED (src untouched; the one shared envelope stays).
"""

from __future__ import annotations

import json
import shutil
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_env92 as env92  # noqa: E402
import bench_envelope_policy as envelope_policy  # noqa: E402
from _cli import run_commands, seed_list  # noqa: E402


def check(root: str, seeds: str, fraction: str) -> None:
    """The full records' lines (bench_env92) and the train-only check's, per seed and family."""
    env92.draw(root, seeds)
    base = Path(root) / f"cut{fraction}"
    done = {(r["record"], r["family"]) for r in env92._rows(base / "results.jsonl")}
    for seed in seed_list(seeds):
        name, one_file = f"cut{seed}", base / "data" / f"cut{seed}" / "train_cycle.csv"
        if not one_file.exists():           # the train campaign alone, as a lab's one file
            one_file.parent.mkdir(parents=True)
            shutil.copy(Path(root) / "data" / f"cms{seed}" / "train_cycle.csv", one_file)
        for fam in envelope_policy.FAMILIES:
            if (name, fam) in done:
                continue
            row = envelope_policy.measure(base, name, "a", [f"data.path={one_file}",
                                                            f"data.test_fraction={fraction}"], fam, "true")
            with (base / "results.jsonl").open("a") as f:
                f.write(json.dumps(row) + "\n")
            print(f"{name:8} {fam:8} clamped {row['clamped']}/{row['n']} (pattern {row['clamped_pattern']})",
                  flush=True)


def trace(root: str, fraction: str) -> None:
    test = {(r["record"][3:], r["family"]): r for r in env92._rows(Path(root) / "results.jsonl")}
    cut_rows = env92._rows(Path(root) / f"cut{fraction}" / "results.jsonl")
    cut = {(r["record"][3:], r["family"]): r for r in cut_rows}
    cells = [k for k in cut if k in test]
    targets = list(test[cells[0]]["targets"])
    for by in ("clamp", "pattern"):
        unclamped, ratios = dict.fromkeys(targets, 0), []
        for k in cells:
            chosen = 0.0
            for t in targets:
                c = cut[k]["targets"][t]
                keep = c[by] <= c["off"]
                unclamped[t] += not keep
                chosen += test[k]["targets"][t]["pattern" if keep else "off"] ** 2
            ratios.append(chosen / test[k]["pattern"])
            print(f"check {by:7} cms{k[0]} {k[1]:8} pattern {test[k]['pattern']:7.0f}"
                  f" off {test[k]['off']:7.0f} per-target {chosen:7.0f}  ratio {ratios[-1]:.3f}")
        r = np.array(ratios)
        print(f"check {by}: unclamped of {len(cells)} {unclamped}  G {np.exp(np.log(r).mean()):.3f}"
              f"  > 10 % worse {(r > env92.WORSE).sum()}  better {(r < 1 / env92.WORSE).sum()}")
    for label, pick in (("oracle", lambda v, t: min(v["pattern"], v["off"])),
                        ("E_X alone unclamped", lambda v, t: v["off"] if t == "E_X" else v["pattern"])):
        r = [sum(pick(test[k]["targets"][t], t) ** 2 for t in targets) / test[k]["pattern"] for k in cells]
        print(f"{label}: G {np.exp(np.log(r).mean()):.3f}")


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"check": check, "trace": trace},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
