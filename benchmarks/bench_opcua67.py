"""`thermocomp connect` against a vendor's OPC UA server, not the twin (opcua67, issue 34).

    .venv/bin/python benchmarks/bench_opcua67.py DIR [--models mlr lagbank] [--runs clean faults
        warm-stamped warm-seconds]

The record is `make run`'s (`thermocomp simulate`, the default scenario, written to DIR/data);
each model is fitted on its train part (`thermocomp run`), and its test campaigns are served,
one NC program each, by ``tests/shell/vendor_machine.py``'s server: the vendor's namespace
(index 5, named by its URI in connect.nodes), a Float node per input (string ids, one numeric),
offsets E_X as a Float in µm, E_Y as a Double in µm, E_Z as an Int32 in 0.1 µm, no sample / done
/ campaign sample / offset_sample node, the program's name as the campaign, the server's clock
the record's time.  `connect` runs in its own process (`connect.clock=server`, the sample period
the model's); the server sends it SIGTERM after the last row.  Two runs per model:

- ``clean``: every sensor in a 0.02 K deadband (the record's resolution is 0.01 K);
- ``faults``: the same, and `T_nose` dropped for 20 samples of the first program
  (UncertainLastUsableValue, its last value held), the server down for 10 samples of the
  second (a restart: the machine runs on).

What is measured, written before it ran: per target the largest |offset the machine held -
replay's correction| over the samples answered, replay streaming the rows as the server
published them (Float inputs, the deadband's held values, NaN for the dropped sensor, the rows
of the restart left out); the RMS of the error compensated with the offsets the machine held
(the error in the frame the model predicts: from the program's first sample) against replay's
on the same rows; connect's samples, samples missed, its events; its CPU (user + sys of its
process, from wait4).  And (``held or missing``) what reading the dropped sensor's held value as
a reading (before opcua67) or as missing (now) does to replay's RMS over the first program and
over the dropout's 20 samples.  No rule is chosen by it.

(connect68) ``warm-stamped`` / ``warm-seconds``: the same clean serving, `connect` stopped by
SIGTERM once the first program's row 35 is answered, 5 rows served with no client, then a new
`connect` process joins with ``connect.warm=<the first program's rows 0-35 as published>``, their
time the server's timestamps or the record's seconds.  Measured, written before it ran: per
target the largest |offset the machine held - replay's correction| over the samples answered,
replay streaming the rows the clients saw (the 5 left out; with seconds, the rows after them
moved 5 periods earlier: the join follows the log's last row by one period); the RMS of the
error compensated by the machine's offsets and by replay's over the first program's rows after
the join; both processes' CPU.  Before connect68 the log was not read without a campaign_sample
node: run this bench with the old code for the restarted stream's figures.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "tests" / "shell"), str(ROOT / "tests"), str(ROOT / "src")]

from asyncua import ua  # noqa: E402

from vendor_machine import EPOCH, VendorMachine, as_published, connect_nodes, served_in_thread  # noqa: E402

PY = sys.executable
FAST = ["track=false", "plots=none"]
OFFSETS = {"E_X": ("s=CNC5000.Compensation.OffsetX", ua.VariantType.Float, 1.0),
           "E_Y": ("s=CNC5000.Compensation.OffsetY", ua.VariantType.Double, 1.0),
           "E_Z": ("s=CNC5000.Compensation.OffsetZ_01um", ua.VariantType.Int32, 0.1)}


def cli(*args: str) -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    subprocess.run([PY, "-m", "thermocomp", *args], check=True, env=env, capture_output=True)


def free_port() -> int:
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def sensors_of(columns: list[str]) -> dict[str, str]:
    """A node per input: string ids, the first a numeric one (as a vendor's generator makes)."""
    return {c: ("i=6012" if i == 0 else f"s=CNC5000.{c.split('_', 1)[1]}.Value")
            for i, c in enumerate(columns)}


def replay_rows(data: Path, pkl: Path, frames: dict[str, pd.DataFrame]) -> np.ndarray:
    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.cli import _compose
    from thermocomp.shell.source import read_streamed

    cfg = _compose([f"data.path={data}", f"connect.model={pkl}", *FAST], "connect")
    ds, train_ids = read_streamed(cfg, test=False)[:2]
    deployed = deployable_model(cfg, ds, train_ids, str(pkl), "connect.model")[0]
    return np.vstack([stream_rows(deployed, df.reset_index(drop=True)).y for df in frames.values()])


def one(data: Path, pkl: Path, out: Path, programs: dict, columns: list[str], faults: bool) -> dict:
    sensors = sensors_of(columns)
    first, second = list(programs)[:2]
    n1 = len(programs[first])
    bad = {"T_nose": (10, 29, ua.StatusCodes.UncertainLastUsableValue)} if faults else {}
    restarts = [(n1 + 15, 10)] if faults else []
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    port = free_port()
    args = [PY, "-m", "thermocomp", "connect", f"data.path={data}", f"out={out}", *FAST,
            f"connect.model={pkl}", f"connect.endpoint=opc.tcp://127.0.0.1:{port}",
            "connect.retry_s=0.4", "connect.give_up_s=120", "connect.hold_s=600",
            *connect_nodes(sensors, OFFSETS)]
    client = subprocess.Popen(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    machine = VendorMachine(programs, port, deadband=0.02, bad=bad, restarts=restarts,
                            sensors=sensors, offsets=OFFSETS, stop_pid=client.pid, wait_s=120)
    thread = served_in_thread(machine)
    _, status, usage = os.wait4(client.pid, 0)
    client.returncode = os.waitstatus_to_exitcode(status)
    err = client.stderr.read().decode()
    machine.closing.set()
    thread.join(timeout=60)
    assert client.returncode == 0 and not machine.raised, (client.returncode, err, machine.raised)
    link = json.loads((out / "connect.json").read_text())
    seen = as_published(programs, 0.02, bad, sensors)
    answered = np.array(machine.served.answered)
    if faults:
        a, n = restarts[0]
        seen[second] = seen[second].drop(index=range(a - n1, a - n1 + n))
    held = np.vstack(machine.served.offsets)[answered]
    replayed = replay_rows(data, pkl, seen)
    targets = list(OFFSETS)
    errors = np.vstack([(df[targets] - df[targets].iloc[0]).to_numpy(float)
                        for df in programs.values()])[answered]
    rms = lambda r: float(np.sqrt(np.nanmean(r ** 2)))   # noqa: E731
    values = pd.concat([df[[c for c in sensors if c.startswith("T_")]] for df in seen.values()])
    return {"samples": link["samples"], "missed": link["samples_missed"],
            "deadband_held": round(float((values.diff() == 0).to_numpy().mean()), 3),
            "answered": int(answered.sum()), "rows": int(len(answered)),
            "events": [e["event"] for e in link["events"]],
            "cpu_s": round(usage.ru_utime + usage.ru_stime, 2),
            "max_abs_diff": {t: float(np.max(np.abs(held[:, j] - replayed[:, j])))
                             for j, t in enumerate(targets)},
            "rms_machine": {t: rms(errors[:, j] - held[:, j]) for j, t in enumerate(targets)},
            "rms_replay": {t: rms(errors[:, j] - replayed[:, j]) for j, t in enumerate(targets)},
            "rms_uncompensated": {t: rms(errors[:, j]) for j, t in enumerate(targets)}}


STOP, GAP = 35, 5      # warm runs: the first program's row answered before the stop, rows without


def warmed(data: Path, pkl: Path, out: Path, programs: dict, columns: list[str],
           stamped: bool) -> dict:
    """A `connect` stopped mid-program and a new one warmed on the program's log (module doc)."""
    from datetime import timedelta

    sensors = sensors_of(columns)
    first = list(programs)[0]
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    port = free_port()
    machine = VendorMachine(programs, port, deadband=0.02, sensors=sensors, offsets=OFFSETS,
                            wait_s=120, handover=(STOP, GAP))
    log = as_published(programs, 0.02, None, sensors)[first].iloc[:STOP + 1]
    t0 = float(programs[first]["time"].iloc[0])       # the machine's clock: the program at EPOCH
    log = log[["time", *sensors]].assign(time=[
        (EPOCH + timedelta(seconds=float(t) - t0)).isoformat() for t in log["time"]]
        if stamped else log["time"])
    out.mkdir(parents=True, exist_ok=True)
    log.to_csv(out / "log.csv", index=False)
    args = [PY, "-m", "thermocomp", "connect", f"data.path={data}", *FAST, f"connect.model={pkl}",
            f"connect.endpoint=opc.tcp://127.0.0.1:{port}", "connect.retry_s=0.4",
            "connect.give_up_s=120", "connect.hold_s=600", *connect_nodes(sensors, OFFSETS)]
    thread = served_in_thread(machine)
    cpu, links = 0.0, []
    try:
        for part, extra in (("first", []), ("second", [f"connect.warm={out / 'log.csv'}"])):
            client = subprocess.Popen([*args, f"out={out / part}", *extra], env=env,
                                      stdout=subprocess.PIPE, stderr=subprocess.PIPE)
            machine.stop_pid = client.pid
            _, status, usage = os.wait4(client.pid, 0)
            err = client.stderr.read().decode()
            assert os.waitstatus_to_exitcode(status) == 0, err
            cpu += usage.ru_utime + usage.ru_stime
            links.append(json.loads((out / part / "connect.json").read_text()))
            if part == "first":
                machine.stopped.set()
                assert machine.handed_over.wait(120)
    finally:
        machine.closing.set()
        thread.join(timeout=60)
    assert not machine.raised, machine.raised
    answered = np.array(machine.served.answered)
    seen = as_published(programs, 0.02, None, sensors)
    seen[first] = seen[first].drop(index=range(STOP + 1, STOP + GAP + 1))
    if not stamped:
        seen[first].loc[STOP + GAP + 1:, "time"] -= GAP * float(np.median(np.diff(log["time"])))
    held = np.vstack(machine.served.offsets)[answered]
    replayed = replay_rows(data, pkl, seen)
    targets = list(OFFSETS)
    errors = np.vstack([(df[targets] - df[targets].iloc[0]).to_numpy(float)
                        for df in programs.values()])[answered]
    after = np.flatnonzero(answered)
    after = (after > STOP + GAP) & (after < len(programs[first]))      # the first program's, after
    rms = lambda r: float(np.sqrt(np.mean(r ** 2)))   # noqa: E731
    return {"samples": [link["samples"] for link in links],
            "events": [[e["event"] for e in link["events"]] for link in links],
            "warmed": [e["detail"] for e in links[1]["events"] if e["event"] == "warmed"],
            "cpu_s": round(cpu, 2),
            "max_abs_diff": {t: float(np.max(np.abs(held[:, j] - replayed[:, j])))
                             for j, t in enumerate(targets)},
            "rms_after_join_machine": {t: rms(errors[after, j] - held[after, j])
                                       for j, t in enumerate(targets)},
            "rms_after_join_replay": {t: rms(errors[after, j] - replayed[after, j])
                                      for j, t in enumerate(targets)}}


def held_or_missing(data: Path, pkl: Path, programs: dict, columns: list[str]) -> dict:
    """The first program with `T_nose` dropped as in ``faults`` (rows 10-29): the RMS of the error
    compensated by replay's corrections when the held value is streamed as a reading (what
    `connect` did before opcua67 with an Uncertain value) and when it is missing (now)."""
    first = list(programs)[0]
    sensors = sensors_of(columns)
    missing = as_published({first: programs[first]}, 0.02,
                           {"T_nose": (10, 29, ua.StatusCodes.UncertainLastUsableValue)}, sensors)
    held = {first: missing[first].copy()}
    held[first].loc[10:29, "T_nose"] = held[first].loc[9, "T_nose"]
    targets = list(OFFSETS)
    e = (programs[first][targets] - programs[first][targets].iloc[0]).to_numpy(float)
    out = {}
    for name, frames in (("held", held), ("missing", missing)):
        r = e - replay_rows(data, pkl, frames)
        out[name] = {t: {"program": float(np.sqrt(np.mean(r[:, j] ** 2))),
                         "dropout": float(np.sqrt(np.mean(r[10:30, j] ** 2)))}
                     for j, t in enumerate(targets)}
    return out


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("dir", type=Path)
    p.add_argument("--models", nargs="+", default=["mlr", "lagbank"])
    p.add_argument("--runs", nargs="+", default=["clean", "faults", "warm-stamped", "warm-seconds"])
    a = p.parse_args()
    data = a.dir / "data"
    if not (data / "campaigns.csv").is_file():
        cli("simulate", f"data.path={data}", *FAST)
    manifest = pd.read_csv(data / "campaigns.csv")
    tests = manifest.loc[manifest["split"] == "test", "campaign"].tolist()
    programs = {f"{c}.MPF": pd.read_csv(data / f"{c}.csv") for c in tests}
    columns = [c for c in programs[f"{tests[0]}.MPF"].columns if c.startswith(("T_", "S_"))]
    results = {}
    for model in a.models:
        pkl = a.dir / model / "model.pkl"
        if not pkl.is_file():
            cli("run", f"data.path={data}", f"out={pkl.parent}", f"model_path={pkl}", f"model={model}",
                *FAST, "eval.validation=false", "eval.mutual_prediction=false")
        if {"clean", "faults"} & set(a.runs):
            results[f"{model} held or missing"] = held_or_missing(data, pkl, programs, columns)
            print(json.dumps({f"{model} held or missing": results[f"{model} held or missing"]}),
                  flush=True)
        for run in a.runs:
            start = time.monotonic()
            out = a.dir / f"{model}-{run}"
            r = (one(data, pkl, out, programs, columns, run == "faults") if run in ("clean", "faults")
                 else warmed(data, pkl, out, programs, columns, run == "warm-stamped"))
            r["wall_s"] = round(time.monotonic() - start, 1)
            results[f"{model} {run}"] = r
            print(json.dumps({f"{model} {run}": r}), flush=True)
    (a.dir / "bench_opcua67.json").write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
