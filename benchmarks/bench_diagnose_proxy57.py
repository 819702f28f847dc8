"""diagnose on the grinder without its coolant sensors: why an accepted effect raised the test
error 4.7 %, and the rule scored against it (issue 34, item 4; session 57).

DRAFT -- the rule, written down before it was scored on any case (2026-11-30 13:10 UTC); the
forensics, the scores and the decision follow when measured.

Rule W ("the gain within the campaigns").  With ``data.reference=first_sample`` the error and
every referenced feature are zero at a campaign's first sample, so the mean of a held-out
campaign's CV residual carries that first sample's noise (the probe's and the inputs'), which
nothing predicts in a new campaign.  A candidate effect (not the control, not a sensor removal)
must then also gain where no offset can be matched: the CV RMSE of the residual about each
campaign's own mean (over its scored rows) must fall by ``min_gain_pct`` % at least (the bar's
own size), before against after.  Variant ``W_units``: asked only when the test blocks are the
CV units (the path without ranks, where the campaigns' means weigh in whole); variant ``W_all``:
asked on both paths.  Adopted only if: no planted effect taken first is lost, no clean acceptance
added, no record's test error > 2 % worse, grinder-nocoolant within 2 % or nothing accepted,
vendor5's ambient law and gantry's yaw and lag kept.  If both pass, ``W_all`` only if it is
better somewhere and worse nowhere; else ``W_units``.
"""
