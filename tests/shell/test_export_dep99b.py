"""A jump with two sensors already out in the exported C (dep99b, issue 34: deployed as scored;
benchmarks/bench_dep99b.py, dl9878's ambient row 824).  Served re-references a sensor the others
predict that jumps and takes it out whatever the set out (here the third), and re-admits it as a
spike when its next reading is back on the field.  The C held a jump beside those out only where
a place was free (the second): it flagged ``SECOND`` and fed the jump to the model.  Now a jump is
held beside any number out where the set solves, as dep99 holds a range reading: the numpy mirror
and the compiled C give served's corrections on every row.

An eight-sensor machine (seven ``T_`` sensors warmed by two heats, ``T_u`` no other predicts; 3
POD modes, ``min_active`` 4; MLR deployed adaptive, no fallback model), its last test campaign:
``T_e`` and ``T_f`` in kelvin for ``K_ROWS`` samples (both out, back a window after), and a
one-sample +3 °C spike of ``T_c`` while they are still out.  Fails on 90cf3c74 (the mirror
flags ``SECOND`` at the spike and parts from served by 0.27 µm, rows 35-44)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import test_export
from conftest import deployed_as_replay
from test_export import CAMPAIGNS, built_stream, needs_cc
from test_export_cmon80 import _streamed
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.export.watch import JUMP, NOT_IN_CODE
from thermocomp.apps.deploy.report import stream_rows

ROWS, ONSET, K_ROWS, SPIKE = 80, 20, 10, 35
#: each sensor's share of the two heats (``T_u`` apart: its own cycle)
SHARES = {"T_a": (1, .2), "T_b": (.6, 1), "T_c": (.3, 1), "T_d": (1, .5), "T_e": (.8, .8),
          "T_f": (.2, .6), "T_g": (.5, .1)}


def _machine(root):
    """test_export's six campaigns, the eight sensors (module doc), one sample every 2 min."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(3)
    t = np.arange(ROWS) * 120.0
    for i, (cid, _) in enumerate(CAMPAIGNS):
        amb = 16 + 2.5 * i
        w1, w2 = (4 + i % 3) * (1 - np.exp(-t / 1500)), (2 + i % 2) * (1 - np.exp(-t / 4000))
        cols = {"time": t, **{name: amb + p * w1 + q * w2 + rng.normal(0, 0.05, ROWS)
                              for name, (p, q) in SHARES.items()}}
        cols["T_u"] = amb + 1.5 * np.sin(t / 900 + 1.7 * i) + rng.normal(0, 0.05, ROWS)
        a, b, d = (cols[k] - cols[k][0] for k in ("T_a", "T_b", "T_d"))
        cols["E_X"] = 3 * a - 1.2 * b + rng.normal(0, 0.2, ROWS)
        cols["E_Z"] = 2 * b + 1.5 * d + rng.normal(0, 0.2, ROWS)
        pd.DataFrame(cols).to_csv(root / f"{cid}.csv", index=False)
    pd.DataFrame([(c, f"{c}.csv", s, "") for c, s in CAMPAIGNS],
                 columns=["campaign", "file", "split", "notes"]).to_csv(root / "campaigns.csv",
                                                                        index=False)
    return root


def faulted(folder, fault):
    """``(adaptive MLR as replay deploys it, its system with the monitor, the faulted campaign)``:
    the machine under ``folder``, its last test campaign with ``T_e`` / ``T_f`` in kelvin and
    ``fault(frame)`` applied (step99's stepped error shares it)."""
    deployed, ds, test_ids = deployed_as_replay(test_export._compose(
        f"data.path={_machine(folder)}", "track=false", "monitor.adaptive=true",
        "monitor.fallbacks=none"))
    frame = ds.campaigns[test_ids[-1]].reset_index(drop=True)
    frame.loc[ONSET:ONSET + K_ROWS - 1, ["T_e", "T_f"]] += 273.15
    fault(frame)
    return deployed, state_space(deployed, monitor=True), frame


def held_as_served(deployed, ss, frame, want, rule, tmp_path, at=SPIKE, out=3, built=None):
    """The mirror and the compiled C (``built``: its ``stream``, else built in ``tmp_path``) give
    ``want`` on every row, nothing flagged as not in the code, ``rule`` at row ``at`` with ``out``
    out."""
    sim = Simulator(ss)
    sim.reset()
    U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    mirror = []
    for i in range(len(frame)):
        mirror.append(sim.step(U[i], t[i]))
        w = sim.watch
        assert not w.flags & NOT_IN_CODE, (i, w.missed)          # the base: SECOND at SPIKE
        if i == at:
            assert (w.rule, len(w.gone)) == (rule, out)
    assert np.max(np.abs(np.array(mirror) - want)) < 1e-9                    # every row
    got, said = _streamed(built or built_stream(tmp_path, exported_files(deployed, "c")), frame,
                          ss.inputs)
    assert got.shape == want.shape and np.max(np.abs(got - want)) < 1e-9     # every row
    assert "not in the code" not in said


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """:func:`faulted` with a one-sample +3 °C spike of ``T_c`` at ``SPIKE``."""
    def spike(frame):
        frame.loc[SPIKE, "T_c"] += 3.0
    return faulted(tmp_path_factory.mktemp("dep99b") / "data", spike)


@needs_cc
def test_a_jump_with_two_out_is_held_as_served(served, tmp_path):
    deployed, ss, frame = served
    run = stream_rows(deployed, frame, "K06")
    want = corrections(ss, run.y)
    times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
    moves = [(int(np.searchsorted(times, e["time"])), e["sensor"], e["to"], e["reason"][:5])
             for e in run.events if e.get("sensor")]
    # served: the two out by range, then T_c out for its jump as the third, back as a spike
    assert (SPIKE, "T_c", "excluded", "jump:") in moves and (SPIKE + 1, "T_c", "ok", "re-ad") in moves
    assert {s for r, s, to, _ in moves if to == "excluded" and r < SPIKE} == {"T_e", "T_f"}
    assert not any(s in ("T_e", "T_f") and to == "ok" for r, s, to, _ in moves if r <= SPIKE)
    held_as_served(deployed, ss, frame, want, JUMP, tmp_path)     # 90cf3c74: SECOND at the spike
