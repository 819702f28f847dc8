"""Why ``model=auto`` lost 61 % to MLR on the ``hmc`` (E_Y), and a rule for the defect found.

    .venv/bin/python benchmarks/bench_new_machines59.py write ROOT --data hmc
    .venv/bin/python benchmarks/bench_new_machines59.py init ROOT --data hmc
    .venv/bin/python benchmarks/bench_auto_hmc59.py forensics ROOT      # ~5 s CPU
    .venv/bin/python benchmarks/bench_auto_hmc59.py score OUT           # the rule on the records below

The record: ``bench_new_machines59``'s ``hmc`` (8 runs of a pallet-shuttle HMC, the last two test,
6 train: 3 blocked forward folds fitting runs 1-3 / 1-4 / 1-5).  auto kept hammerstein alone on
E_Y (validation 0.812 against MLR's 1.387, ahead in every fold), test 1.26 against MLR's 0.78.

Forensics (:func:`forensics`; the test split only scored, nothing chosen on it)
-----------------------------------------------------------------------------
FORENSICS_TABLE

The rule (written down before it was scored on any record)
-----------------------------------------------------------
Defect: the lag bank starts every first-order lag in steady state at a campaign's first sample
(``z_0 = u_0``).  For the temperatures in the first-sample frame ``u_0 = 0``: nothing before the
start.  The Hammerstein's machine states enter raw (scaled, not referenced), so a run that starts
with the spindle at 10 000 rpm is modelled as if it had run at 10 000 rpm forever: the lags (up to
2 days, longer than a run) hold that first value through the run, the heat of the first state never
develops in the prediction, and the first state's level is a constant for the whole run.  Any
record whose campaigns start in different states (a logger started with the machine running) has
it; it is no property of the hmc.

Rule ``state_start='rest'`` (Hammerstein): a machine state that is never negative and is 0 on some
training row (a speed, a power, an on/off flag: 0 is its rest) has its lags start at rest, ``z_0 =
0`` at each campaign's first sample (the machine's heat from it begins with the record, as the
first-sample frame takes the temperatures); any other state (a temperature, a position, a pallet
number) keeps the steady start.  The same in ``predict``, ``stream_step`` and every fit (folds,
CV), nothing else changed.

Records scored (chosen before running, the stop-57 batch of ``docs/models.md``'s "Where it stands"
without the two ``large_mill_week`` records, ~170 s CPU per fit of auto there):
``column_moving_source``, ``swiss_lathe_door``, ``yearround_spindle``, seeds 5791 and 5792
(``bench_auto_rank.py``, defaults).  Acceptance (fixed with the rule): auto better than MLR on at
least as many records as with the steady start, no record more than 2 % worse (mean test RMSE over
the targets), and the geometric mean of auto over the best single family not worse.  hmc, the
record the defect was found on, is reported beside them, not counted.

RESULT
"""
