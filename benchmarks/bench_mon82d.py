"""The rounding floor on the band that excludes only, the warning as shipped (mon82d): rule, bar.

    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82d.py trunnion ROOT LABEL [SEEDS \
        [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82d.py lathe ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82d.py jig ROOT LABEL [SEEDS [KINDS]]
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_mon82d.py table ROOT SHIPPED RULE

bench_mon82c's commands (its harness: ``thermocomp monitor``, MLR, a line per record in
``ROOT/<LABEL>.jsonl``; the code measured is the tree on ``PYTHONPATH``: ``/work/main/src``
shipped, the branch the rule) on fresh seeds: ``trunnion`` (stranger82b's trunnion centre,
8342 the found case and 8441-8442), ``lathe`` (stranger82's lathe, 8443-8444), ``jig``
(stranger80's jig borer, 8445-8446); kinds ``healthy,frozen,jump,drift,dropout``; ``table``:
bench_mon81's side by side.

The rule (written before scoring): mon82c's rounding bound,
``(q / 2) · sum_k |(I - M)_jk / (1 - h_j)|`` (``q_k`` sensor ``k``'s smallest non-zero step in
training, every sensor in; 0 for a sensor not judged), is added to both bands only where they
exclude for drift (the drift judgement's trigger, ``Judgement._exclude_by_judgement``: a judged
sensor's error beyond ``band + bound`` at the field level); the warning / alarm states and their
events, the culprit pick, the re-admission and the instant detectors keep the bands as shipped.
mon82c floored both and lost test_monitor_regime73's warning (an offset within the rounding's
bound is still to be said; it is no fault to act on).  ``SensorMonitor.from_training`` fits
the bound (``exclude_margin_c``).  The exported watch (``export/watch.py``, its C) does not
carry it: a KEPT rule needs it there too before it ships (deployed = scored).

The bar (written before scoring; fresh seeds 8441-8446, none tuned on; REFUSED if any part fails):
1. Every fresh healthy draw (trunnion 8441-8442, lathe 8443-8444, jig 8445-8446): no exclusion
   where shipped has none, adaptive RMSE not > 1 % worse than shipped on each target.
2. 8342 (the found case, apart): quiet.
3. Every injected fault (frozen, jump, drift, dropout of each bench's ``faults``, on trunnion
   8441, lathe 8443, jig 8445): the faulted sensor excluded no later than shipped where shipped
   excludes it, adaptive RMSE not > 1 % worse.
4. The monitor test files pass (``tests/apps/test_monitor*.py``, ``tests/shell/test_monitor*.py``);
   ``test_monitor_healthy53``'s strict xfail turning to pass is allowed (its healthy column quiet
   is the wanted behaviour) and then becomes a plain test.

Scored: not yet (below when done).
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_mon81 as m81  # noqa: E402
import bench_mon82c as m82c  # noqa: E402
from _cli import run_commands  # noqa: E402

KINDS = m82c.KINDS


def trunnion(root: str, label: str, seeds: str = "8342,8441-8442", kinds: str = KINDS) -> None:
    """stranger82b's trunnion centre, healthy and faulted (docstring)."""
    m82c.trunnion(root, label, seeds, kinds)


def lathe(root: str, label: str, seeds: str = "8443-8444", kinds: str = KINDS) -> None:
    """stranger82's lathe, healthy and faulted (docstring)."""
    m82c.lathe(root, label, seeds, kinds)


def jig(root: str, label: str, seeds: str = "8445-8446", kinds: str = KINDS) -> None:
    """stranger80's jig borer, healthy and faulted (docstring)."""
    m82c.jig(root, label, seeds, kinds)


def main(argv: list[str] | None = None) -> int:
    np.seterr(all="ignore")
    return run_commands(__doc__, {"trunnion": trunnion, "lathe": lathe, "jig": jig,
                                  "table": m81.table},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
