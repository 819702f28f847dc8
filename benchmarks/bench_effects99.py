"""metrics.json and the printed table say which effects ``model=auto``'s ``diagnosed``
candidate took (issue 34; stop 99, effects99; follow-up of ``bench_autodiag99b.py``, KEPT).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the tree measured)::

    python benchmarks/bench_effects99.py on ROOT OUT RECORD               # model.diagnosed=true
    python benchmarks/bench_effects99.py off ROOT OUT BASE RECORD         # key off: this tree vs BASE

RECORD as bench_autodiag99's (``mt<seed>``, ``yr<seed>`` under ``ROOT/data``).  ``on`` runs
``thermocomp run model=auto model.diagnosed=true`` into ``OUT/<record>/on`` and prints each
target's ``targets.<t>.auto.diagnosed`` of metrics.json, the printed table's ``diagnosed:``
lines and the test RMSE; ``off`` is bench_autodiag99b's ``off`` (every file of ``run
model=auto`` with this tree and with ``BASE/src``, byte by byte; clock-set fields masked).

The change (no rule, no fresh seeds): ``shell.builders.diagnosed_candidate`` keeps, per target,
what the search accepted (:func:`~thermocomp.shell.builders.accepted_entry`: each effect's title
with the lab's headers where the record has them, its acceptance p -- family-wise over its
round, ``diagnosis.json``'s ``p_value_family`` -- and own p, the penalty ``alpha``, the design's
smallest p ``min_p`` as ``diagnose`` reports it) on the candidate (``ForTargets.about``), also
where nothing is accepted; ``core.models.auto.add_choices`` writes it under
``targets.<t>.auto.diagnosed``; ``core.scoring.results.auto_table`` prints one line per target.

BAR (committed before the key-on runs below):

* E1 (mt9888, seen): metrics.json's ``targets.<t>.auto.diagnosed`` names, per target, the effects
  the log's ``model.diagnosed:`` line names (E_X, E_Z interaction S_B_deg x T_bhead; E_Y lag of
  S_n_tool_rpm), each p <= diagnose.alpha 0.01 and >= min_p; one table line per target; test
  RMSE as bench_autodiag99b's (E_X 3.224750, E_Y 0.251721, E_Z 3.325265 um) |d| 0.
* E2 (yr9900, clean: no effect planted): every target has its entry; a target with nothing
  accepted says ``nothing accepted`` in metrics.json (``accepted: []``) and the table.
* E3 (key off, mt9888): every file byte-identical to BASE 4b0de502's but clock-set fields.
KEPT if E1-E3 are met with a test that fails on 4b0de502.

Measured (2026-12-06, this branch's src at b8cb5cbb + the change of 9b16bbdf, uncommitted then;
nice, ``OMP_NUM_THREADS=1``, 2 cores shared, load 3.5-5.5; ROOT /tmp/autodiag99/root, OUT
/tmp/effects99/out, BASE ``git archive 4b0de502 src conf``)::

  on mt9888   metrics.json targets.<t>.auto.diagnosed = the log's model.diagnosed lines:
              E_X, E_Z interaction:S_B_deg product(T_bhead rise) (absolute), p 5.0e-05 (= p_value
              = min_p 5.0e-05), alpha 0.0316 / 0.1; E_Y signal:S_n_tool_rpm first_order_lag(tau=
              1800s) (absolute), p 5.0e-05, alpha 0 (min_p 5.0e-05); a table line per target;
              test RMSE E_X 3.224750, E_Y 0.251721, E_Z 3.325265 um = autodiag99b's run |d| 0,
              auto's candidates and weights equal; run + bench 47 s wall (13:41:51-13:42:38)
  on yr9900   (clean) nothing accepted on E_X, E_Y, E_Z: "accepted": [], alpha null, min_p
              0.00024 / 0.0039 / 0.0039; the table says "nothing accepted on the train split"
  off mt9888  headline/*.json, ingest_report.json identical byte for byte; metrics.json,
              model.pkl(.sig), thermocomp.log identical but for what the clock sets (54 s wall, 2 runs)

E1, E2, E3 met: KEPT.  Not measured: a record read with lab headers through the key (the lab
naming is covered by the test's stub only), fleet (data.group_by) runs with the key.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))


def on(root: str, out: str, name: str) -> None:
    """E1 / E2: the key on, what metrics.json and the table say (module doc)."""
    from bench_autodiag99b import QUIET, _overrides

    where = Path(out, name, "on").resolve()
    done = subprocess.run([sys.executable, "-m", "thermocomp", "run", *_overrides(root, name),
                           "model=auto", "model.diagnosed=true", *QUIET, f"out={where}"],
                          capture_output=True, text=True)
    print(f"{name}: run exit {done.returncode}; "
          + " | ".join(line for line in done.stderr.splitlines() if "model.diagnosed" in line))
    print("\n".join(line for line in done.stdout.splitlines() if "diagnosed:" in line))
    metrics = json.loads((where / "metrics.json").read_text())
    for t, e in metrics["targets"].items():
        print(f"  {t}: test RMSE {e['test']['rmse']:.6f} um; diagnosed "
              f"{json.dumps(e.get('auto', {}).get('diagnosed'))}", flush=True)


def off(root: str, out: str, base: str, name: str) -> None:
    """E3: bench_autodiag99b's ``off`` (module doc)."""
    from bench_autodiag99b import off as autodiag_off

    autodiag_off(root, out, base, name)


def main(argv: list[str]) -> int:
    from _cli import run_commands

    return run_commands(__doc__, {"on": on, "off": off}, argv)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
