"""A real ambient step confirmed by the heat the others take in (mon105b): served monitor.

Usage::

    python benchmarks/bench_mon105b.py seen ROOT
    python benchmarks/bench_mon105b.py fresh ROOT SEEDS

The rule (``surveillance/air.py``).  Fitted in ``from_training`` for each ambient sensor
(``is_ambient``): the others' field as a linear dynamic system driven by the air,
``z[t+1] - z[t] = F z[t] + b A[t] + c + e[t]`` (``z``: the others' absolute readings on their
first ``r`` principal directions, ``r`` the POD's modes; least squares on the train campaigns);
``e``'s covariance ``S`` there is mostly the spindle's unobserved heat.  When the air's sensor,
out for a jump ``J`` and re-referenced, is due back (its window calm), the ring's rows are read
under the offset hypothesis (air = reading - J) and the air step the others' innovations call
for is the GLS estimate ``s = sum_t b' S^-1 e_t / ((W - 1) b' S^-1 b)``.  Taken as real (the
jump undone, re-admitted as measured) when ``s`` has ``J``'s sign, ``s / J > 1/4`` and ``|s|``
beyond the largest ``|s|`` of every window of the train campaigns (no jump there).  Different
from the refused rules: monitor68 (each sensor's change of course, the smallest; 11-38 %
take-rate), amb94 (the others' static prediction of the air over hours), session 55 (per-sensor
first-order responses, no joint state, no weighting against the spindle's directions): here the
joint state's innovations, weighted by their training covariance, so the spindle's directions
count little.

BAR (written and committed before any fresh number; fresh seeds 10022-10024, MLR,
``yearround_spindle`` 9 campaigns of 3-5 h as ``tests/shell/test_ambient_step54.py``):
  1. seen: tests/shell/test_ambient_step54.py's xfail passes (mark removed) and its offset test
     passes; tests/shell/test_monitor.py and tests/apps/test_monitor_*.py pass unchanged.
  2. fresh, every test campaign, the air itself stepped +2 K and -2 K from its middle row
     (``SteppedAmbient``): adaptive with the rule <= 1.1 x the plain stream (RMS over E_X, E_Y,
     E_Z of measured minus predicted from the middle row).
  3. fresh, every test campaign, the ``T_amb`` column offset +2 K and -2 K from its middle row:
     not taken as measured (RMS identical to the shipped monitor's).
  4. take-rate (the lead's stop-68 condition): over every row of the fresh healthy test
     campaigns, a +-2 K offset of ``T_amb`` starting there taken as real at <= 5 % of the rows
     (the decision function applied to the window the monitor holds at re-admission).
  KEPT only if 1-4 all hold; else REFUSED (src reverted, ``benchmarks/mon105b_rule.patch``).
"""
