"""A lag of the base's own fit in place of the low-pass copy of every input, with few runs (stop 112,
diag112e; REFUSED: the rule is ``benchmarks/diag112e_rule.patch``, not in src).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's; apply
the patch to a tree of 820dcb1b to measure the rule)::

    python benchmarks/bench_diag112e.py planted ROOT LABEL SEED...   # bench_diag112c's draws, cv=forward

The rule (the bar, ``benchmarks/diag112e_bar.md``, fixed before scoring): a ``dynamics`` candidate
``lowpass_model`` = ``L_tau[x . w]`` (``w`` the inputs' least squares on each fold's train rows, as
``ambient_scaled`` learns its direction; one coefficient), at every tau, and the 12-feature
``lowpass_inputs`` copy only from ``MIN_CAMPAIGNS_LOWPASS_COPY`` = 4 train campaigns.  The patch
streams it (``AugmentedRegressor``) and exports it (a low-pass block, its k coefficients the
column's times ``w``: C = replay to 1e-9 um, tests/shell/test_export_effects59.py).

Scored (2026-12-08, once per tree; BASE = 820dcb1b's src, RULE = the patch's; diagnose CPU s):
* 10247 E_Z: BASE 4.277 -> 8.624 (12-copy, 4 h), RULE 4.277 -> 4.277 (nothing; the fit's lag 900 s
  evaluated: CV gain 2.4 %, p .17).
* 10271 E_Z (lag_node): BASE 3.415 -> 2.895 (12-copy, 4 h), RULE 3.415 (nothing: the fit's lag is
  not even shortlisted, its screen R2 below the 20th candidate's 0.31; the 12-copy's was 0.76).
* 10272 E_X (clean): BASE 0.306 -> 0.780 (12-copy, 1 h), RULE 0.306 -> 0.329 (x1.075: without the
  copy a signal lag of S_spindle_rpm, 4 h absolute, takes the round: CV 36.7 %, p_shift .01).
* 10246, 10248, 10270: identical.  diagnose CPU BASE 2.8 2.3 2.6 3.4 2.6 2.8 / RULE 2.7 2.8 3.3 3.5
  2.7 2.7 s (10247 10271 10272 10246 10248 10270).
* BOTH (the patch with ``MIN_CAMPAIGNS_LOWPASS_COPY = 0``: both offered): 10247, 10271, 10272
  accept exactly BASE's (the 12-copy): the one-feature form does not carry these lags.
* ``bench_diag112b.py forward 0 200``: 1 of 200 both (18); CPU 29.0 / 30.7 s.
* The patch fails 3 diagnose tests (``-m "not full"``, 175 pass): test_diagnose_scenarios' one long
  record (forward: a T_motor lag taken in place of the copy, test 0.717 -> 0.866), test_diagnose's
  lag of many inputs (a single lag taken), test_diagnose_shift112b's clean record (p_shift .01001).
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_diag112c as d112c  # noqa: E402
from _cli import run_commands  # noqa: E402


def planted(root: str, label: str, *seeds: str) -> None:
    """bench_diag112c's ``planted`` on this tree (data simulated once into ROOT/data)."""
    d112c.planted(root, label, *seeds)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"planted": planted}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
