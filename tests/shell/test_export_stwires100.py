"""The Structured Text block reads two exchanged wires as the C does (stwires100, issue 34;
benchmarks/bench_stwires100.py): wires100's machine (test_export_wires100), ``T_a`` and ``T_f``
exchanged from row ``SWAP`` on.  Fails on 063630e6: the block flags the swap row (the two steps
as jumps) and compensates with the swapped readings after it, parting from the C."""

from __future__ import annotations

import numpy as np

from test_export import StructuredText
from test_export_wires100 import SWAP, _swapped, served  # noqa: F401  (the fixture)
from thermocomp.apps.deploy.export import Simulator, exported_files
from thermocomp.apps.deploy.export.watch import WIRES_EXCHANGED


def _stepped(ss, block: str, frame):
    """Per row: the mirror C's corrections, the block's, and the block's (flag, rule, sensor)."""
    sim, fb = Simulator(ss), StructuredText(block)
    sim.reset()
    U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    rows = []
    for i in range(len(frame)):
        c, st = sim.step(U[i], t[i]), fb(U[i], t[i], i == 0)
        v = fb.vars
        rows.append((c, st, (bool(v["mon_flag"]), int(v["mon_rule"]), int(v["mon_sensor"]))))
    return rows


def test_the_block_reads_two_exchanged_wires_as_the_c(served):  # noqa: F811
    deployed, ss, frame = served
    block = exported_files(deployed, "st")["compensator.st"]
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    rows = _stepped(ss, block, _swapped(frame))
    for i, (c, st, said) in enumerate(rows):
        # named at the swap row on the first of the two, not flagged (the C's REREFERENCED);
        # 063630e6: flagged there (the two steps), the swapped readings compensated after it
        want = (False, WIRES_EXCHANGED, names.index("T_a")) if i == SWAP else (False, 0, -1)
        assert said == want, i
        assert np.max(np.abs(st - c)) < 1e-9, i
    healthy = _stepped(ss, block, frame)
    assert all(said == (False, 0, -1) for _, _, said in healthy)
    assert np.max(np.abs(np.array([r[1] for r in rows]) - [r[1] for r in healthy])) < 1e-9


def test_a_repeated_sample_after_the_exchange_is_read_as_read(served):  # noqa: F811
    """The repeat rule compares the inputs as read (``u_read``), not as the block reordered them:
    a sample sent twice after the swap is a repeat, as in the C."""
    deployed, ss, frame = served
    block = exported_files(deployed, "st")["compensator.st"]
    swapped = _swapped(frame)
    fb = StructuredText(block)
    U, t = swapped[ss.inputs].to_numpy(float), swapped["time"].to_numpy(float)
    for i in range(SWAP + 2):
        fb(U[i], t[i], i == 0)
    again = fb(U[SWAP + 1], t[SWAP + 1], False)
    assert fb.vars["repeated"]
    assert np.array_equal(again, fb.vars["c"])
