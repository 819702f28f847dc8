"""Every rule the exported C does not follow named on stream.c's stderr (cmon92b, issue 34):
where a rule of the served monitor that is not in the code sets in at the sample of an
exclusion, ``stream`` said only the exclusion (the sample's first event, ``mon_rule``) and never
named the rule it does not follow, though ``mon_flags`` carried it (bench_cmon92: lr9212 arx_rf,
``T_amb`` and ``T_motor`` frozen together).  The state now keeps the sample's first rule not in
the code (``mon_missed``, ``mon_missed_sensor``) and ``stream`` says both.

lr9132 (``thermocomp simulate sim=long_record``, seed 9132, 3 days, R1b the last fifth), MLR
deployed adaptive with ``data.reference=none``; ``T_table`` and ``T_xdrive`` frozen together from
R1b's middle row: the code takes one out for its freeze and, in the same sample, the other as a
second sensor out it does not hold (found with the numpy mirror, benchmarks/bench_cmon92b.py).
Since freezeu100 the code takes that second out too, as served (a freeze of one no other predicts
as its dropout, ``second_instant``): the case is made with arrays exported before cmon89 (no
``second_instant``), and the current export sets no rule not in the code at an exclusion.
R1b streamed after R1a's last 864 rows (:data:`LEAD_ROWS`, ci102a; R1a whole before): the rule not
in the code sets in beside ``T_table``'s exclusion at R1b's row 443 on both."""

from __future__ import annotations

import re
import subprocess

import pytest

from test_export import built_stream, needs_cc
from test_export_cmon85 import _mirror, without
from test_export_cmon87 import LEAD_ROWS, long_record
from thermocomp.apps.deploy.export import Simulator, c, exported_files
from thermocomp.apps.deploy.export.pack import fed
from thermocomp.apps.deploy.export.watch import EXCLUDED, NOT_IN_CODE, REASONS

SEED = 9132
FROZEN = ("T_table", "T_xdrive")


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """``(deployed, ss, the fed frame with the two sensors frozen from R1b's middle row)``."""
    deployed, ss, _, _, tests, leads = long_record(tmp_path_factory, SEED, LEAD_ROWS)
    (test, campaign), = tests.items()
    campaign = campaign.copy()
    half = campaign.index[len(campaign) // 2:]
    for sensor in FROZEN:
        campaign.loc[half, sensor] = campaign.loc[half[0] - 1, sensor]
    return deployed, ss, fed(campaign, leads.get(test))


def _first_missed_at_an_exclusion(ss, frame) -> tuple[int, str, int, int]:
    """The mirror's first sample where a rule not in the code sets in beside an exclusion that
    is the sample's first event: ``(row 1-based, the excluded sensor, its rule, the rule not in
    the code)``."""
    sim = Simulator(ss)
    sim.reset()
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    flagged = False
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        sim.step(u, t)
        w = sim.watch
        now = bool(w.flags & NOT_IN_CODE)
        if now and not flagged and w.flags & EXCLUDED and w.missed != w.rule:
            return i + 1, names[w.sensor], w.rule, w.missed
        flagged = now
    raise AssertionError("no rule not in the code set in at an exclusion")


@needs_cc
def test_stream_names_the_rule_not_in_the_code_beside_an_exclusion(record, tmp_path):
    deployed, ss, frame = record
    with pytest.raises(AssertionError, match="no rule not in the code"):
        _first_missed_at_an_exclusion(ss, frame)      # (freezeu100) the code holds both, as served
    old = without(ss, "second_instant")
    row, excluded, rule, missed = _first_missed_at_an_exclusion(old, frame)
    assert excluded in FROZEN and REASONS[missed].startswith("not in the code")
    assert (row, missed) in _mirror(old, frame, rows=row)[2]     # (its row: none after it read)
    stream = built_stream(tmp_path, {**exported_files(deployed, "c"), "compensator.h": c.header(old),
                                     "compensator.c": c.source(old)})
    run = subprocess.run([str(stream)], capture_output=True, text=True, check=True,
                         input=frame[["time", *ss.inputs]].to_csv(index=False, float_format="%.17g"))
    said = re.findall(rf"line {row + 1}: monitor: (\S+): (.*)", run.stderr)
    # the exclusion, as before, and (on the base: never said) the rule the code does not follow
    assert (excluded, REASONS[rule]) in said
    assert REASONS[missed] in [why for _, why in said], said
