"""A `connect` restarted mid-campaign: its first offset against the ones the machine kept
(restart69).

small69: a new process keeps the offsets the machine holds (the stopped client's last) until its
first computed one.  That first one was taken as a campaign's first is, in one jump, as if the
error had been zeroed there: on restart58's Swiss lathe (lag bank, the client stopped 4 h into
the 8 h run, a new one joining cold at sample 310 of 481) the registers went from the kept
27.33 / 19.08 µm to -2.40 / -1.56 in one sample, a step of 29.7 / 20.6 µm where the limiter
lets 22.2 / 14.4 through (benchmarks/bench_restart69.py).  A campaign joined mid-way is not
zeroed: the first offset is now rate-limited from what the machine holds, as after a decay.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip("asyncua")

from conftest import free_port  # noqa: E402
from thermocomp.shell.cli import main  # noqa: E402
from twin_bench import FAST, Handoff, _served_in_thread, handing_over, limiter_step  # noqa: E402

SIM = ["sim=swiss_lathe_door", "seed=5851", "sim.generator.calibration_hours=20",
       "sim.generator.production_hours=8"]
STOP, JOIN = 240, 310      # restart58's: stopped 4 h in, the new process joined at sample 310


@pytest.fixture(scope="module")
def lathe(tmp_path_factory):
    """restart58's lathe record and a lag bank fitted on its train part."""
    tmp = tmp_path_factory.mktemp("lathe")
    data, pkl = tmp / "data", tmp / "lagbank" / "model.pkl"
    assert main(["simulate", f"data.path={data}", *SIM, *FAST]) == 0
    assert main(["run", f"data.path={data}", f"out={pkl.parent}", f"model_path={pkl}",
                 "model=lagbank", *FAST, "eval.validation=false",
                 "eval.mutual_prediction=false"]) == 0
    return data, pkl


def test_a_new_process_joining_mid_campaign_moves_the_kept_offsets_at_the_rate_limit(lathe, tmp_path):
    data, pkl = lathe
    port = free_port()
    connect = ["connect", f"data.path={data}", *FAST, f"connect.model={pkl}",
               f"connect.endpoint=opc.tcp://127.0.0.1:{port}", "connect.retry_s=0.2",
               "connect.give_up_s=120", "connect.hold_s=600"]
    handoff = Handoff(STOP, JOIN)
    with handing_over(handoff):
        thread, raised = _served_in_thread([f"data.path={data}", f"out={tmp_path / 'twin'}",
                                            f"twin.port={port}", "twin.speed=50",
                                            "twin.lockstep=true", "twin.wait_s=120", *FAST])
        assert main([*connect, f"out={tmp_path / 'first'}"]) == 0      # SIGTERM at STOP
        handoff.gone.set()
        assert handoff.reached.wait(120)
        assert main([*connect, f"out={tmp_path / 'second'}"]) == 0
        thread.join(timeout=120)
    assert not thread.is_alive() and not raised, raised
    report = json.loads((tmp_path / "twin" / "twin.json").read_text())
    held = np.column_stack([report["offsets"][t] for t in ("E_X", "E_Y")])
    np.testing.assert_array_equal(held[STOP + 1:JOIN], np.repeat(held[STOP:STOP + 1], JOIN - STOP - 1, 0))
    step = limiter_step(data, pkl)
    kept, first = held[JOIN - 1], held[JOIN]
    assert np.all(np.abs(kept) > 15.0), kept               # the stopped client's, warm
    # before: -2.40 / -1.56 (the cold stream's own), a step of 29.7 / 20.6 µm over 22.2 / 14.4
    assert np.all(np.abs(np.diff(held[JOIN - 1:], axis=0)) <= step + 1e-9), (kept, first, step)
    # the rate limit delays the cold stream's offsets, it does not keep the earlier ones
    assert np.all(np.abs(held[JOIN + 2]) < np.abs(kept) / 2), held[JOIN - 1:JOIN + 3]
    second = json.loads((tmp_path / "second" / "connect.json").read_text())
    events = [e["event"] for e in second["events"]]
    assert events[:4] == ["connected", "offsets_kept", "campaign", "joined_mid_campaign"]
