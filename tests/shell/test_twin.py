"""`thermocomp twin` + `thermocomp connect` on loopback (issue 36, items 3-4).

The twin serves the test campaigns of a small dataset over OPC UA at high speed; the client
runs the deployed (adaptive) compensator against it.  What the machine would have had with the
offsets it received is compared with what ``replay`` streams from the same model; a sensor link
drop and a server restart are survived, a NaN and a stuck sensor handled as the adaptive
compensator handles them in ``replay``/``monitor``.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

pytest.importorskip("asyncua")

from conftest import free_port, refused  # noqa: E402
from thermocomp.apps.machine import OffsetLimiter  # noqa: E402
from thermocomp.shell.cli import main  # noqa: E402
from twin_bench import FAST  # noqa: E402
from twin_bench import twin_and_connect as served

CAMPAIGNS = (("K01", "train"), ("K02", "train"), ("K03", "train"), ("K04", "test"),
             ("K05", "test"))
ROWS = 60
SPEED = 20          # samples per second: 50 ms for the client to answer one (lockstep: the
                    # next one as soon as it did)


def twin_and_connect(data: Path, tmp: Path, *twin_args: str, connect_args=(),
                     process: bool = False) -> tuple[dict, dict]:
    """``(twin.json, connect.json)`` of the twin at SPEED (in a thread, ``process``: its own)."""
    return served(data, tmp, twin_args, connect_args, speed=SPEED, process=process)


def make_machine(root: Path, fault=None, continued: bool = False) -> Path:
    """Five campaigns (three train, two test) of a four-sensor machine whose error is linear
    in two sensors' rises, one sample a minute; ``fault(df)`` edits the first test campaign;
    ``continued``: the last test campaign continues the first (one record, absolute values; said
    in the manifest's ``continues``, as the four others end where it starts)."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(0)
    t = np.arange(ROWS) * 60.0
    for i, (cid, _) in enumerate(CAMPAIGNS):
        if continued and cid == "K05":
            before = pd.read_csv(root / "K04.csv")
            temps = {c: before[c].iloc[-1] + 1.5 * (1 - np.exp(-t / 700)) * (j + 1)
                     + rng.normal(0, 0.03, ROWS) for j, c in enumerate(["T_0", "T_1", "T_2"])}
            temps["T_amb"] = before["T_amb"].iloc[-1] + rng.normal(0, 0.03, ROWS)
            e = (before["E_X"].iloc[-1] + 3 * (temps["T_0"] - before["T_0"].iloc[-1])
                 - (temps["T_2"] - before["T_2"].iloc[-1]) + rng.normal(0, 0.2, ROWS))
            pd.DataFrame({"time": t + before["time"].iloc[-1] + 60.0, **temps, "E_X": e}).to_csv(
                root / f"{cid}.csv", index=False)
            continue
        amb = 18.0 + i
        heat = 1 - np.exp(-t / (900 + 100 * i))
        temps = {f"T_{j}": amb + (4 - j) * heat + rng.normal(0, 0.03, ROWS) for j in range(3)}
        temps["T_amb"] = amb + 0.5 * heat + rng.normal(0, 0.03, ROWS)
        e = (3 * (temps["T_0"] - temps["T_0"][0]) - (temps["T_2"] - temps["T_2"][0])
             + rng.normal(0, 0.2, ROWS))
        df = pd.DataFrame({"time": t, **temps, "E_X": e})
        if fault is not None and cid == "K04":
            fault(df)
        df.to_csv(root / f"{cid}.csv", index=False)
    manifest = pd.DataFrame([(c, f"{c}.csv", s, "") for c, s in CAMPAIGNS],
                            columns=["campaign", "file", "split", "notes"])
    if continued:   # every campaign's clock ends where K05's starts: the times cannot tell which
        manifest["continues"] = ["K04" if c == "K05" else "" for c, _ in CAMPAIGNS]
    manifest.to_csv(root / "campaigns.csv", index=False)
    return root


def replayed(data: Path, out: Path) -> dict:
    assert main(["replay", f"data.path={data}", f"out={out}", *FAST]) == 0
    return json.loads((out / "replay.json").read_text())


def test_twin_connect_compensates_as_replay_streams(tmp_path):
    """A saved model.pkl (connect.model), made deployable as replay makes it."""
    data = make_machine(tmp_path / "data")
    pkl = tmp_path / "run" / "model.pkl"
    assert main(["run", f"data.path={data}", f"out={pkl.parent}", f"model_path={pkl}", *FAST,
                 "eval.validation=false", "eval.mutual_prediction=false"]) == 0
    assert main(["replay", f"data.path={data}", f"out={tmp_path / 'replay'}", *FAST,
                 f"replay.model={pkl}"]) == 0
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())["targets"]["E_X"]
    # the twin as a user serves it, its own process (the other tests serve it in a thread)
    twin, link = twin_and_connect(data, tmp_path, connect_args=(f"connect.model={pkl}",),
                                  process=True)
    assert link["source"] == str(pkl) and link["model"] == "mlr"
    r = twin["targets"]["E_X"]
    assert twin["n_samples"] == 2 * ROWS and link["samples"] == 2 * ROWS
    assert r["stale_samples"] <= 2          # the client answered (almost) every sample in time
    assert r["rms_compensated"] < 0.5 * r["rms_uncompensated"]
    assert abs(r["rms_compensated"] - replay["rmse"]) <= 0.05 * replay["rmse"]
    lo, hi = link["bound"]["E_X"]
    assert lo <= min(twin["offsets"]["E_X"]) and max(twin["offsets"]["E_X"]) <= hi
    assert [e["event"] for e in link["events"]].count("campaign") == 2
    assert link["events"][-1]["event"] == "done"


def test_link_drop_and_server_restart_hold_then_decay(tmp_path):
    """The sensor link down for 15 samples (a 30 s drop at 2 s per sample, scaled to 0.75 s)
    and the server down for 10: the offsets are held, then decay, then come back bounded."""
    data = make_machine(tmp_path / "data")
    hold, decay = 0.2, 0.1           # s of wall time: 4 and 2 samples at SPEED
    twin, link = twin_and_connect(
        data, tmp_path, "twin.drops=[[20,15]]", "twin.restarts=[[80,10]]",
        connect_args=(f"connect.hold_s={hold}", f"connect.decay_s={decay}"))
    r = twin["targets"]["E_X"]
    assert r["offsets_finite"]
    assert r["stale_samples"] >= 15 + 10
    lo, hi = link["bound"]["E_X"]
    assert lo <= min(twin["offsets"]["E_X"]) and max(twin["offsets"]["E_X"]) <= hi
    events = [e["event"] for e in link["events"]]
    assert events.count("connected") >= 2 and "link_lost" in events    # came back after restart
    assert "stale" in events and events.index("stale") < events.index("fresh")
    assert link["samples_missed"] >= 15
    assert events[-1] == "done"
    offsets = np.array(twin["offsets"]["E_X"])
    drop = offsets[20:35]
    assert drop[0] == pytest.approx(offsets[19])                # held first ...
    assert abs(drop[-1]) < 0.1 * abs(offsets[19])              # ... then decayed
    assert np.all(np.diff(np.abs(drop)) <= 1e-9)               # never grows while stale
    # the compensation is back once the server serves again: the last campaign's end is
    # compensated as well as the stream is anywhere
    e = pd.read_csv(data / "K05.csv")["E_X"].to_numpy()
    end = (e - e[0])[-15:] - offsets[-15:]
    assert np.sqrt(np.mean(end ** 2)) < 0.2 * np.sqrt(np.mean((e - e[0])[-15:] ** 2))


def test_nan_and_stuck_sensor_handled_as_replay_handles_them(tmp_path):
    def fault(df):
        df.loc[10:14, "T_1"] = np.nan            # a dropout
        df.loc[30:, "T_0"] = df.loc[30, "T_0"]   # a sensor stuck from sample 30

    data = make_machine(tmp_path / "data", fault)
    replay = replayed(data, tmp_path / "replay")
    twin, link = twin_and_connect(data, tmp_path)
    r, ref = twin["targets"]["E_X"], replay["targets"]["E_X"]
    assert r["offsets_finite"] and ref["all_finite"]
    assert abs(r["rms_compensated"] - ref["rmse"]) <= 0.05 * ref["rmse"]
    sensors = {e["sensor"] for e in link["events"] if e["event"] == "compensator"}
    assert sensors == {e["sensor"] for e in replay["events"]}
    assert "T_1" in sensors


def test_offset_limiter_holds_decays_and_bounds():
    lim = OffsetLimiter([-5.0], [5.0], [1.0], hold_s=2.0, decay_s=1.0)
    assert lim.fresh([3.0], now=0.0)[0] == 3.0                 # the first one as it is
    assert lim.fresh([9.0], now=1.0)[0] == 4.0                 # rate-limited
    assert lim.fresh([np.nan], now=2.0)[0] == 4.0              # a missing one is held
    assert lim.stale(now=3.5)[0] == 4.0                        # held for hold_s
    assert lim.stale(now=5.0)[0] == pytest.approx(4.0 * np.exp(-1.0))   # then decays
    assert lim.fresh([100.0], now=6.0)[0] <= 5.0               # bounded, whatever comes
    lim.new_campaign()
    assert lim.fresh([-50.0], now=7.0)[0] == -5.0


def test_connect_without_a_server_gives_up_in_one_line(tmp_path, capsys):
    data = make_machine(tmp_path / "data")
    port = free_port()
    refused(["connect", f"data.path={data}", f"out={tmp_path / 'c'}", *FAST,
             f"connect.endpoint=opc.tcp://127.0.0.1:{port}", "connect.retry_s=0.1",
             "connect.give_up_s=0.5"], capsys, "connect.endpoint", "no OPC UA server")
    assert not (tmp_path / "c" / "connect.json").exists()


def test_twin_on_a_port_in_use_is_refused_in_one_line(tmp_path, capsys):
    import socket

    data = make_machine(tmp_path / "data")
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        refused(["twin", f"data.path={data}", f"out={tmp_path / 't'}", *FAST, f"twin.port={port}"],
                capsys, f"twin.port={port}")
    assert not (tmp_path / "t").exists()


@pytest.mark.parametrize("stage, key, says", [
    ("twin", "twin.drops=[[3]]", "twin.drops"),
    ("twin", "twin.speed=0", "twin.speed"),
    ("twin", "twin.lockstep=2", "twin.lockstep"),
    ("connect", "connect.endpoint=http://127.0.0.1:4840", "connect.endpoint"),
    ("connect", "connect.hold_s=-1", "connect.hold_s"),
    ("connect", "connect.model=' '", "connect.model is empty"),
])
def test_bad_keys_refused(tmp_path, capsys, stage, key, says):
    data = make_machine(tmp_path / "data")
    refused([stage, f"data.path={data}", f"out={tmp_path / 'o'}", *FAST, key], capsys, says)


def test_a_continuing_campaign_is_served_after_the_one_it_continues(tmp_path):
    """K05 continues K04 (one clock, data.reference=none): the client is warmed on K04 as
    replay warms its stream, so K05 is compensated from the state K04 left."""
    data = make_machine(tmp_path / "data", continued=True)
    args = ("data.reference=none",)
    assert main(["replay", f"data.path={data}", f"out={tmp_path / 'replay'}", *FAST, *args]) == 0
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())["targets"]["E_X"]
    twin, link = twin_and_connect(data, tmp_path, *args, connect_args=args)
    r = twin["targets"]["E_X"]
    assert twin["n_samples"] == 2 * ROWS            # K04 scored once, not again as K05's lead-in
    assert link["samples"] == 3 * ROWS              # ... but streamed before K05
    assert abs(r["rms_compensated"] - replay["rmse"]) <= 0.05 * replay["rmse"]


@pytest.mark.parametrize("reference", ["none", "first_sample"])
def test_the_served_record_carries_the_chains_it_serves_lead_ins_for(tmp_path, reference):
    """One definition of what a campaign continues: the record's chains, whose lead-ins the twin
    serves first (state carried over only with data.reference=none)."""
    from thermocomp.apps.machine.record import served_record
    from thermocomp.core.io import read_dataset

    ds = read_dataset(make_machine(tmp_path / "data", continued=True))[0]
    rec = served_record(ds, ["K04", "K05"], reference, 600.0, "data.path")
    if reference != "none":
        assert rec.chains == rec.lead_ins == {}
        return
    assert list(rec.chains) == list(rec.lead_ins) == ["K05"]
    (before, k05), = rec.chains.values()     # K05's clock picks up where a 60-row campaign ends
    assert k05 == "K05" and before in ds.ids()
    lead = rec.lead_ins["K05"]
    np.testing.assert_array_equal(lead["E_X"], ds.campaigns[before]["E_X"])
    assert lead["time"].iloc[-1] + 60.0 == ds.campaigns["K05"]["time"].iloc[0]
