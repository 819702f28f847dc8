"""An ATI model whose ambient comes from the manifest exports (exportrest62, issue 34 item 1).

A climate-room record without an air sensor gives each campaign's ambient in campaigns.csv
(``ambient_c``); ``ati=cmeans`` picks a campaign's interval model (and its interaction's factor
``A0 - 20``) by it, and the served stream takes it at reset.  ``thermocomp export`` refused the
model ("the code has no input for it").  Now the code takes A0 at a campaign's start: C
``tc_set_ambient`` after ``tc_reset`` (``stream.c`` reads an ``ambient_c`` column or
``--ambient``), ST the block's input ``ambient_c``, the JSON ``ambient_given``; the check pack
carries it per campaign (check.json and an ``ambient_c`` column of rows.csv).  The compiled C,
the Structured Text and the numpy reading of the arrays equal ``replay`` to 1e-9 µm, one input
pushed out of the envelope (the clamp's gain: the interval's), in campaigns of both intervals.
"""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pandas as pd
import pytest

from test_export import StructuredText, _exported_code, checked_pack, needs_cc
from test_export_ati57 import _levels
from test_export_auto57 import TOLERANCE_UM, deployed
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.streaming import replay
from thermocomp.core.io.contract import manifest_ambient

ATI = ("ati=cmeans", "ati.estimator.n_intervals=2")


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _levels(tmp_path_factory.mktemp("ambient62") / "data", ambient_column=False)


@pytest.mark.parametrize("model", [
    ("model=mlr",), ("model=lagbank", "model.estimator.n_taus=3", "model.estimator.ar=true"),
], ids=["mlr", "lagbank-ar"])
def test_the_structured_text_and_the_arrays_take_the_given_ambient_as_replay(data, model):
    stream, tests, _ = deployed(data, *ATI, *model, pushed="T_a")
    [(_, est, _)] = stream._plan
    assert stream.ambient_given_ and not stream.ambient_columns
    ss = state_space(stream)                                  # refused before
    assert ss.ambient_given and ss.ambient_inputs == [] and len(ss.law_target) == 4
    a0 = [manifest_ambient(df) for df in tests]        # a test campaign in each interval
    assert sorted(int(np.searchsorted(est.boundaries_, a)) for a in a0) == [0, 1]
    streamed = [replay(stream, df) for df in tests]
    assert all(s["n_clamped"].iloc[len(s) // 2:].gt(0).all() for s in streamed)
    sim = Simulator(ss)
    fb = StructuredText(exported_files(stream, "st")["compensator.st"])
    for df, s, a in zip(tests, streamed, a0):
        want = -s[stream.targets_].to_numpy(float)
        sim.reset(a)
        fb.vars["ambient_c"] = a
        U, t = df[stream.columns_].to_numpy(float), df["time"].to_numpy(float)
        got = np.array([sim.step(u, ti) for u, ti in zip(U, t)])
        assert np.max(np.abs(got - want)) <= TOLERANCE_UM
        got = np.array([fb(u, ti, k == 0) for k, (u, ti) in enumerate(zip(U, t))])
        assert np.max(np.abs(got - want)) <= TOLERANCE_UM
    # without its ambient a campaign does not start: the sample refused, as the stream refuses it
    sim.reset()
    sim.step(tests[0][stream.columns_].to_numpy(float)[0], 0.0)
    assert sim.refused and sim.first


def _exported(data, tmp_path, fmt: str = "c"):
    return _exported_code(data, tmp_path, fmt, "lagbank", "model.estimator.n_taus=3", *ATI)


@needs_cc
def test_the_export_commands_check_pack_carries_each_campaigns_ambient_and_passes(data, tmp_path):
    out = _exported(data, tmp_path)
    assert json.loads((out / "compensator.json").read_text())["ambient_given"] is True
    assert "TC_AMBIENT_GIVEN 1" in (out / "compensator.h").read_text()
    assert checked_pack(out).count("stream: check passed: 50 rows") == 2
    manifest = pd.read_csv(data / "campaigns.csv").set_index("campaign")["ambient_c"]
    pack = json.loads((out / "check" / "check.json").read_text())
    listed = {e["campaign"]: e for e in pack["campaigns"]}
    assert {c: e["ambient_c"] for c, e in listed.items()} == {"K09": 15.0, "K10": 32.0}
    assert pack["inputs"][-1] == "ambient_c" and "tc_set_ambient" in pack["ambient"]
    for cid, e in listed.items():
        rows = pd.read_csv(out / e["folder"] / "rows.csv")
        assert (rows["ambient_c"] == manifest[cid]).all()
    # the ambient is what picks the laws: K10's rows with K09's ambient (--ambient, no column)
    # part from K10's expected corrections; without any, stream.c says what it needs
    rows = pd.read_csv(out / "check" / "K10" / "rows.csv").drop(columns="ambient_c")
    text = rows.to_csv(index=False, float_format="%.17g")
    run = subprocess.run(["./stream", "--check", "check/K10/expected.csv", "--ambient", "15"],
                         cwd=out, input=text, capture_output=True, text=True)
    assert run.returncode == 1 and "check failed" in run.stderr
    run = subprocess.run(["./stream", "--check", "check/K10/expected.csv", "--ambient", "32"],
                         cwd=out, input=text, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    run = subprocess.run(["./stream"], cwd=out, input=text, capture_output=True, text=True)
    assert run.returncode == 2 and "ambient_c column" in run.stderr


def test_the_structured_text_reads_the_ambient_as_an_input(data, tmp_path):
    out = _exported(data, tmp_path, "st")
    st = (out / "compensator.st").read_text()
    assert "    ambient_c : LREAL;" in st.split("END_VAR")[0]
    assert "AMBIENT_GIVEN : BOOL := TRUE;" in st
