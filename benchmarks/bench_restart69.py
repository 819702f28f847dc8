"""`thermocomp connect` restarted mid-campaign against the twin (restart69; the connect rows of
docs/measured/to-the-machine.md "Restarted mid-campaign: measured", measured by hand in restart58).

    .venv/bin/python benchmarks/bench_restart69.py DIR [--src SRC] [--runs uninterrupted cold warm]

The record is restart58's Swiss lathe (`thermocomp simulate sim=swiss_lathe_door seed=5851
sim.generator.calibration_hours=20 sim.generator.production_hours=8`, 60 s samples; its test
campaign ``production``, 481 samples), the model a lag bank fitted on its train part (written to
DIR once).  The twin (the ``twin`` stage in a thread of this process, lockstep at 20 samples/s,
handing over as ``tests/shell/twin_bench.py``'s ``Handoff`` says) serves it to `connect`
processes run with ``--src`` (the code measured: this checkout's, or another's unpacked by
``git archive``; the twin is this checkout's for both):

- ``uninterrupted``: one `connect` from the first sample to the last;
- ``cold``: the first `connect` gets SIGTERM once it answered sample 240 (4 h into the 8 h run),
  samples 241-309 are served with no client (the machine runs on with the offsets it holds),
  then the twin waits at sample 310 for a new `connect` process (restart58's join: 310 of 481);
- ``warm``: the same, the new process joins at sample 327 (restart58's) with
  ``connect.warm=<the campaign's rows 0-240>``, the rows the stopped client had seen (samples
  241-326 no client saw: spanned by one time step, as after a link drop);
- ``warm-full`` (not run by default): joins at 327 with the rows 0-326 (a machine's log up to
  the join).

Where restart58 started the processes by hand at the twin's pace (the join sample a matter of a
process's start-up), the twin here waits for them: the join samples are the table's, every run.

Measured, written before it ran (E_X / E_Y, µm, the error in the frame the model predicts: from
the campaign's first sample): the RMS of the error compensated by the offsets the machine held
(the twin's record) from the join to the end ("after it"; and from the stop on, the held
samples with them), from 18 samples after the join on, and over the campaign (twin.json's
``rms_compensated``), each against the uninterrupted run's over the same samples; the offsets
the machine held at the sample before the join (the stopped client's, kept) and at the join
(the new process's first), their step against the limiter's one-sample rate (``max_step``);
what the registers held when the new process connected, before its first answer
(``at_connection``); the new process's events; each `connect` process's CPU (user + sys, from
wait4).  No rule is chosen by it.
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

from conftest import free_port  # noqa: E402
from twin_bench import Handoff, _served_in_thread, handing_over, limiter_step  # noqa: E402

PY = sys.executable
FAST = ["track=false", "plots=none"]
SIM = ["sim=swiss_lathe_door", "seed=5851", "sim.generator.calibration_hours=20",
       "sim.generator.production_hours=8"]
STOP = 240                                   # the first client's last sample (4 h in)
JOINS = {"cold": 310, "warm": 327, "warm-full": 327}     # restart58's join samples
SETTLED = 18                                 # restart58's "from 18 samples on"
SPEED = 20.0


def cli(src: Path, *args: str) -> None:
    env = {**os.environ, "PYTHONPATH": str(src)}
    subprocess.run([PY, "-m", "thermocomp", *args], check=True, env=env, capture_output=True)


def connect_args(data: Path, pkl: Path, port: int, out: Path, warm: Path | None) -> list[str]:
    return ["connect", f"data.path={data}", f"out={out}", *FAST, f"connect.model={pkl}",
            f"connect.endpoint=opc.tcp://127.0.0.1:{port}", "connect.retry_s=0.4",
            "connect.give_up_s=120", "connect.hold_s=600",
            *([f"connect.warm={warm}"] if warm is not None else [])]


def served(data: Path, pkl: Path, src: Path, out: Path, run: str) -> dict:
    """One run (module doc): twin.json, each client's connect.json and CPU, what the registers
    held when the new client connected."""
    out.mkdir(parents=True, exist_ok=True)
    port = free_port()
    warm = None
    if run.startswith("warm"):
        rows = pd.read_csv(data / "production.csv")
        upto = STOP if run == "warm" else JOINS[run] - 1
        warm = out / "log.csv"
        rows.drop(columns=[c for c in rows if c.startswith("E_")]).iloc[:upto + 1].to_csv(
            warm, index=False)
    # uninterrupted: a handover after the last sample, never reached
    handoff = Handoff(STOP, JOINS[run]) if run != "uninterrupted" else Handoff(10 ** 9, 10 ** 9 + 1)
    env = {**os.environ, "PYTHONPATH": str(src)}
    clients = [("first", None)] + ([] if run == "uninterrupted" else [("second", warm)])
    cpu, links = [], []
    with handing_over(handoff):
        thread, raised = _served_in_thread([
            f"data.path={data}", f"out={out}", *FAST, f"connect.endpoint=opc.tcp://127.0.0.1:{port}",
            f"twin.port={port}", f"twin.speed={SPEED}", "twin.lockstep=true", "twin.wait_s=120"])
        for part, log in clients:
            if part == "second":
                assert handoff.reached.wait(300), "the twin never reached the join"
            p = subprocess.Popen([PY, "-m", "thermocomp",
                                  *connect_args(data, pkl, port, out / part, log)],
                                 env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
            handoff.pid = p.pid
            _, status, usage = os.wait4(p.pid, 0)
            err = p.stderr.read().decode()
            assert os.waitstatus_to_exitcode(status) == 0, err
            cpu.append(round(usage.ru_utime + usage.ru_stime, 2))
            links.append(json.loads((out / part / "connect.json").read_text()))
            handoff.gone.set()
        thread.join(timeout=120)
    assert not thread.is_alive() and not raised, raised
    report = json.loads((out / "twin.json").read_text())
    return {"twin": report, "links": links, "cpu_s": cpu, "at_connection": handoff.at_connection}


def figures(r: dict, base: dict, data: Path, run: str) -> dict:
    rows = pd.read_csv(data / "production.csv")
    targets = [c for c in rows if c.startswith("E_")]
    e = (rows[targets] - rows[targets].iloc[0]).to_numpy(float)
    held = np.column_stack([r["twin"]["offsets"][t] for t in targets])
    unint = np.column_stack([base["twin"]["offsets"][t] for t in targets])
    rms = lambda x: [round(float(v), 3) for v in np.sqrt(np.mean(x ** 2, axis=0))]  # noqa: E731
    out = {"twin_rms": [round(r["twin"]["targets"][t]["rms_compensated"], 3) for t in targets],
           "twin_rms_uninterrupted": [round(base["twin"]["targets"][t]["rms_compensated"], 3)
                                      for t in targets],
           "cpu_s": r["cpu_s"], "samples": [link["samples"] for link in r["links"]]}
    if run != "uninterrupted":
        j = JOINS[run]
        step = limiter_step(data, Path(r["pkl"]))
        out.update({
            "join": j, "after_restart": rms(e[STOP + 1:] - held[STOP + 1:]),
            "after_restart_uninterrupted": rms(e[STOP + 1:] - unint[STOP + 1:]),
            "after": rms(e[j:] - held[j:]), "after_uninterrupted": rms(e[j:] - unint[j:]),
            "settled": rms(e[j + SETTLED:] - held[j + SETTLED:]),
            "settled_uninterrupted": rms(e[j + SETTLED:] - unint[j + SETTLED:]),
            "kept": [round(float(v), 3) for v in held[j - 1]],
            "at_connection": r["at_connection"],
            "first": [round(float(v), 3) for v in held[j]],
            "uninterrupted_at_join": [round(float(v), 3) for v in unint[j]],
            "max_step": [round(float(v), 3) for v in step],
            "steps_after_join": [[round(float(v), 3) for v in s]
                                 for s in np.diff(held[j - 1:j + 6], axis=0)],
            "events": [e["event"] for e in r["links"][1]["events"]][:12]})
    return out


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("dir", type=Path)
    p.add_argument("--src", type=Path, default=ROOT / "src", help="the code `connect` runs")
    p.add_argument("--runs", nargs="+", default=["uninterrupted", "cold", "warm"])
    a = p.parse_args()
    data, pkl = a.dir / "data", a.dir / "lagbank" / "model.pkl"
    if not (data / "campaigns.csv").is_file():
        cli(ROOT / "src", "simulate", f"data.path={data}", *SIM, *FAST)
    if not pkl.is_file():
        cli(ROOT / "src", "run", f"data.path={data}", f"out={pkl.parent}", f"model_path={pkl}",
            "model=lagbank", *FAST, "eval.validation=false", "eval.mutual_prediction=false")
    tag = a.src.resolve().parent.name
    runs = {}
    for run in dict.fromkeys(["uninterrupted", *a.runs]):
        start = time.monotonic()
        runs[run] = served(data, pkl, a.src, a.dir / f"{tag}-{run}", run)
        runs[run]["pkl"] = str(pkl)
        runs[run]["wall_s"] = round(time.monotonic() - start, 1)
    results = {run: figures(r, runs["uninterrupted"], data, run) for run, r in runs.items()}
    for run, r in results.items():
        print(json.dumps({run: r}), flush=True)
    (a.dir / f"bench_restart69-{tag}.json").write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
