"""The ST block's campaign counters do not wrap on a long campaign (stop 97 review): a PLC's INT
wraps after 32767 samples (9 h at 1 s), and a wrapped ``mon_count`` turns ``mon_count + 1 >=
MON_CONFIRM`` false (the block stops judging) and passes through 1 again (its first-sample
branch).  The counters that grow with the campaign are DINT (st98: each sensor's run of equal
readings too, ``mon_frun``), and the sample count is held at its top rather than incremented past
it."""

from __future__ import annotations

import re

from thermocomp.apps.deploy.export import st_watch

GROWING = ("mon_count", "mon_stop_row", "mon_calm", "mon_run", "mon_run_was", "mon_frun", "mon_quiet",
           "mon_jcalm")


def _declared(text: str) -> dict[str, str]:
    return dict(re.findall(r"^\s*(\w+) : (?:ARRAY\[[^\]]*\] OF )?(\w+);$", text, re.M))


def test_the_counters_that_grow_with_a_campaign_are_dint():
    declared = {**_declared(st_watch.OUTPUTS), **_declared(st_watch.VARS)}
    assert {name: declared[name] for name in GROWING} == dict.fromkeys(GROWING, "DINT")


def test_the_sample_count_is_held_below_dints_top_not_wrapped():
    block = st_watch.BLOCK
    increments = [m.start() for m in re.finditer(r"mon_count := mon_count \+ 1;", block)]
    assert len(increments) == 1
    guard = block.rfind("IF mon_count < ", 0, increments[0])
    assert guard >= 0 and block[guard:increments[0]].count("\n") == 1
    bound = int(re.match(r"IF mon_count < (\d+) THEN", block[guard:]).group(1))
    assert bound + 1 <= 2**31 - 1
