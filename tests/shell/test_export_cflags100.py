"""The compiled stream prints its sensor monitor's flags with ``--flags`` (cflags100, issue 34;
benchmarks/bench_cflags100.py): per row, after the corrections, one 0/1 column per kind of
``tc_state.mon_flags`` and ``excluded_inputs`` (the sensors out, ``;`` between them), equal to the
numpy mirror's on every row; the corrections' bytes as without it.

test_export_dep99b's machine (``T_e`` and ``T_f`` in kelvin for 10 samples, a one-sample spike of
``T_c`` while they are out).  Fails on cd356319: ``--flags`` is no option there (usage, exit 2)."""

from __future__ import annotations

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
    assert list(printed.columns) == [*outputs, *kinds, "excluded_inputs"]    # appended only
    cut = [",".join(line.split(",")[:len(outputs)]) for line in flagged.stdout.splitlines()]
    assert cut == plain.stdout.splitlines()                  # the corrections' bytes unchanged
    said = [(*(int(v) for v in r[kinds]), r["excluded_inputs"]) for _, r in printed.iterrows()]
    assert said == _mirror(ss, frame)                        # every row
    assert said[SPIKE][-1] == "T_e;T_f;T_c" and said[SPIKE][kinds.index("mon_excluded")] == 1
    assert not any(any(r[:-1]) or r[-1] for r in said[:15])  # nothing before the fault
