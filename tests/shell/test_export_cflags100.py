"""The compiled stream prints its sensor monitor's flags with ``--flags`` (cflags100, issue 34;
benchmarks/bench_cflags100.py): per row, after the corrections, one 0/1 column per kind of
``tc_state.mon_flags`` and ``excluded_inputs`` (the sensors out, ``;`` between them), equal to the
numpy mirror's on every row; the corrections' bytes as without it; (cin103) then ``time_read``,
what the row's time was taken as, where served says it in its ``time`` events.

test_export_dep99b's machine (``T_e`` and ``T_f`` in kelvin for 10 samples, a one-sample spike of
``T_c`` while they are out).  Fails on cd356319: ``--flags`` is no option there (usage, exit 2)."""

from __future__ import annotations

import json
import subprocess

import pandas as pd
import pytest

from test_export import built_stream, needs_cc
from test_export_dep99b import SPIKE, faulted
from thermocomp.apps.deploy.export import Simulator, exported_files
from thermocomp.apps.deploy.export.watch import FLAG_KINDS, flag_row


@pytest.fixture(scope="module")
def spiked(tmp_path_factory):
    def spike(frame):
        frame.loc[SPIKE, "T_c"] += 3.0
    return faulted(tmp_path_factory.mktemp("cflags100") / "data", spike)


def _mirror(ss, frame) -> list[tuple]:
    """Per row the mirror's :func:`~thermocomp.apps.deploy.export.watch.flag_row`."""
    sim = Simulator(ss)
    sim.reset()
    U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    names = [ss.inputs[i] for i in sim.watch.idx]
    rows = []
    for i in range(len(frame)):
        sim.step(U[i], t[i])
        rows.append(flag_row(sim.watch, names))
    return rows


@needs_cc
def test_stream_prints_the_mirrors_flags(spiked, tmp_path):
    deployed, ss, frame = spiked
    stream = built_stream(tmp_path, exported_files(deployed, "c"))
    rows = frame[["time", *ss.inputs]].to_csv(index=False, float_format="%.17g")
    flagged = subprocess.run([str(stream), "--flags"], input=rows, capture_output=True, text=True)
    assert flagged.returncode == 0, flagged.stderr
    plain = subprocess.run([str(stream)], input=rows, capture_output=True, text=True, check=True)
    kinds = [f"mon_{kind}" for kind, _ in FLAG_KINDS]
    printed = pd.read_csv(pd.io.common.StringIO(flagged.stdout), keep_default_na=False, dtype=str)
    outputs = [f"C_{t.removeprefix('E_')}" for t in ss.targets]
    assert list(printed.columns) == [*outputs, *kinds, "excluded_inputs", "time_read"]  # appended
    cut = [",".join(line.split(",")[:len(outputs)]) for line in flagged.stdout.splitlines()]
    assert cut == plain.stdout.splitlines()                  # the corrections' bytes unchanged
    said = [(*(int(v) for v in r[kinds]), r["excluded_inputs"]) for _, r in printed.iterrows()]
    assert (printed["time_read"] == "0").all()               # every time read as given
    assert said == _mirror(ss, frame)                        # every row
    assert said[SPIKE][-1] == "T_e;T_f;T_c" and said[SPIKE][kinds.index("mon_excluded")] == 1
    assert not any(any(r[:-1]) or r[-1] for r in said[:15])  # nothing before the fault


@needs_cc
def test_flags_name_the_rows_whose_time_the_served_model_names(spiked, tmp_path):
    # cin103 (audit103's finding 3): an empty time cell was taken silently and a time not after
    # the last one read said on stderr only; served names both in its `time` events.  --flags'
    # time_read: 1 / 2 from the row served's `ok -> substituted` names to the row before its
    # `substituted -> ok`, 0 elsewhere; the corrections as without the odd times' flags
    deployed, ss, frame = spiked
    rows = frame[["time", *ss.inputs]].iloc[:12].copy()
    rows.loc[3, "time"] = float("nan")                            # an empty cell
    rows.loc[8, "time"] = rows.loc[7, "time"] - 30.0              # before its predecessor's
    stream = built_stream(tmp_path, exported_files(deployed, "c"))
    fed = subprocess.run([str(stream), "--flags"], input=rows.to_csv(index=False, float_format="%.17g"),
                         capture_output=True, text=True)
    assert fed.returncode == 0, fed.stderr
    codes = pd.read_csv(pd.io.common.StringIO(fed.stdout), keep_default_na=False)["time_read"]
    assert codes.tolist() == [0, 0, 0, 1, 0, 0, 0, 0, 2, 0, 0, 0]
    deployed.reset()
    events = deployed.predict(rows)["events"]
    timed = [(i, e["to"]) for i, row in enumerate(events) for e in json.loads(row) if e["sensor"] == "time"]
    assert timed == [(3, "substituted"), (4, "ok"), (8, "substituted"), (9, "ok")]
