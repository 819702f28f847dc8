"""CI time (issue 34; stop 102, ci102c): the process-heavy test modules compute no more than
their assertions read.

Group: tests/shell/test_{dvc_metrics, sweep, hostile_procs, tracking, serve, team, opcua67,
newcomer, sweep_failed63, dvc_own_data, optuna_sweep}.py, 193 s of CPU in the fresh-clone CI run
of stop 101 (/work/notes/prof102), mostly child processes: DVC stages, sweep jobs, servers.

Trace (d85f1799, before any change; what each process does, read from the modules and timed by
hand as one process of ``thermocomp`` on conftest's SHORT dataset, 9 campaigns of 2-3 h, load
~1.5, ``track=false``, CPU s user + sys):

- ``run`` (the default evaluation, plots=summary) 5.46; without mutual prediction, ATI baselines
  and ISO 10791 A.3: 5.45; plots=none 3.07; plots=none and without the three 2.62.  The
  interpreter's imports (sklearn, scipy.stats, pandas) are ~2 s of each such process.
- the sweep pipeline's stage command (6 jobs, ``LOKY_MAX_CPU_COUNT=1``: one process) 8.49;
  without the three extras 5.94 (-2.55 s: each of the 6 jobs' mutual prediction and baselines).
- ``diagnose`` 3.73; ``monitor.adaptive=false`` (conftest's PLAIN_DIAGNOSE) 3.58; plots=none 3.04.
- every other module of the group already runs its jobs with conftest's LIGHT (or FAST) and one
  process per subject (a joblib sweep's two workers, a server, a killed run, parallel runs on a
  fresh store): what is left there is the processes' start-up, which is their point.

Rule (tests only, no src change): test_dvc_metrics' scratch copy of the project runs the
default study's ``evaluate`` and the sweep pipeline's jobs without the evaluation extras no
assertion of the module reads (``eval.mutual_prediction=false eval.ati_baselines=false
eval.iso10791_a3=false``, appended to the copy's stage commands as the fixture already appends
``track=false`` / ``plots=none``), and ``diagnose`` with PLAIN_DIAGNOSE (its headline is
compared with its own diagnosis_<t>.json, not with the adaptive stream).  The committed grid
(3 models x 2 selections), the seven stages, every ``dvc`` command and every assertion stay.

BAR (the brief's, written and committed here before any after-measurement):

1. every test id of the changed modules stays and passes (``-n 0 -p no:cacheprovider -m "not
   full"``), ``asserts`` shows no fewer ``assert`` / ``refused(`` / tests than d85f1799 and the
   diff edits no assertion; each shrunk subject still holds what its assertions read (the
   stages' figures and numbers that DVC shows; the sweep's 6 jobs ranked by validation);
2. the changed modules' summed pytest CPU (``cpu``: user + sys incl. children of ``/usr/bin/time
   nice pytest -q -n 0 -p no:cacheprovider -m "not full"`` per module; base tree = ``git
   archive d85f1799`` into /tmp/ci102c/base) down >= 30 %, base and after started together;
   1 rep for the set, a 2nd rep if time allows;
3. every plant caught (``plant``, on a copy of the after tree): (a) the repro fixture's stages:
   headline.py's ``"cv_after": d["after"]["cv_rmse"]`` -> ``d["before"]`` must fail
   test_headline_numbers_are_the_full_reports_numbers; (b) the sweep test: plotdata.py's
   compare_plot ``VAL_RMSE: table.get(VAL_RMSE)`` reversed must fail
   test_the_sweep_pipeline_runs_every_job_and_the_comparison_then_nothing.

No seeds (nothing is scored: the same commands, the assertions read the same kinds of numbers).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci102c.py cpu TREE TAG OUT SPEC...      # bench_ci100b's cpu
    python benchmarks/bench_ci102c.py table OUT [BEFORE AFTER BAR]   # bench_ci100b's table
    python benchmarks/bench_ci102c.py asserts BASE SPEC...           # bench_ci101c's asserts
    python benchmarks/bench_ci102c.py plant TREE FILE OLD NEW SPEC   # bench_ci101c's plant

Rule built (tests only; REFUSED, saved as benchmarks/ci102c_rule.patch, which applies to
d85f1799; test_dvc_metrics.py is back to d85f1799 on the branch).  Found after the bar, before
the measurement: copy_project already sets ``mutual_prediction: false`` in the copy's
conf/eval/default.yaml, so the rule's real cut is the ATI baselines, ISO A.3 and the adaptive
diagnosis: the 6-job sweep stage 6.96 -> 6.52 s by hand (-0.4 s), not the -2.55 s traced above.

Measured (2026-12-06 21:52-22:07, base = git archive of d85f1799, after = 3841eac8; paired:
base and after started together, ``cpu``'s command line, load 8-11; CPU s user + sys incl.
children)::

  module                    rep 1             rep 2             mean
  test_dvc_metrics          65.69 -> 64.66    70.41 -> 69.35    68.0 -> 67.0  -1.5 %   7 / 7 passed

Against the bar: (1) kept: ``asserts`` 34 -> 35 (the rule's own ``n == 1`` check added),
refused( 0 -> 0, tests 7 -> 7; no assertion edited; the same 7 pass.  (2) NOT met: -1.5 %
against >= 30 %.  (3) met, after a first plant that could not fail: headline.py ``"cv_after":
d["after"]`` -> ``d["before"]`` passed 7 of 7 (the short study's diagnosis accepts nothing, so
before == after: a blind plant, not a missed break); then ``"test_after": d["after"][TEST_RMSE]``
-> ``d["after"]["cv_rmse"]`` (diagnose) and results.py's dvc headline ``(TEST_RSD_SD, "test",
RSD_SD)`` -> ``RSD_MEAN`` (evaluate) each failed test_headline_numbers_are_the_full_reports_numbers;
plotdata.py's compare_plot ``val_rmse`` reversed failed
test_the_sweep_pipeline_runs_every_job_and_the_comparison_then_nothing.  (bench_ci101c's
``plant`` now copies .dvc/ and pipelines/ too: copy_project reads them; without them the module's
fixture errored, 1 error in 23 s, and a plant proved nothing.)

Why so little: the module's CPU is its processes' start-up.  One interpreter importing sklearn +
pandas is 1.38-1.43 s of CPU, with MLflow 2.56-2.60 s (two runs each); a stage on the SHORT
study is ~2.6-3.5 s, the figures of evaluate ~2 s of it (asserted: DVC shows the PNGs).  The
module starts 12 thermocomp processes (7 stages, 3 reruns, sweep and compare) and 11 dvc ones;
every other module of the group already runs LIGHT/FAST jobs, one process per subject.
"""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_ci101c import measured  # noqa: E402


def main(argv: list[str]) -> int:
    return measured(__doc__, argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
