"""``data.reference=start_level`` (diag96): every ``T_`` and ``E_`` column less its start level, the
mean over the campaign's first ``START_SPAN_S`` seconds, so that one probe reading's noise is not
a whole campaign's offset (bench_diag95, bench_diag96).  Every test here fails on bd118abf, where
``start_level`` is no reference (``data.reference must be one of ('first_sample', 'none')``).
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from test_hostile import make_dataset
from thermocomp.apps.diagnose.features import in_frame
from thermocomp.core.choices import START_SPAN_S
from thermocomp.core.compensator import Compensator
from thermocomp.core.frame import stack, start_rows
from thermocomp.core.io.contract import ContractError
from thermocomp.core.models import MLR
from thermocomp.shell.cli import main

PERIOD = 300.0   # s: the twin's; 900 s hold the rows at 0, 300, 600 and 900 s


def campaign(rows: int = 20, kick: float = 0.0) -> pd.DataFrame:
    """A warming machine, error 2 µm/K of its rise, ``kick`` µm of probe noise on the first
    error reading only."""
    time = np.arange(rows) * PERIOD
    t = 20 + 3 * (1 - np.exp(-time / 7200))
    e = 2.0 * (t - t[0])
    e[0] += kick
    return pd.DataFrame({"time": time, "T_a": t, "E_X": e})


def test_start_rows_hold_the_first_900_s():
    assert START_SPAN_S == 900.0
    assert start_rows(np.arange(20) * PERIOD) == 4
    assert start_rows(np.arange(20) * 3600.0) == 1       # a sparse record: its first row alone
    assert start_rows(np.arange(5) * 60.0) == 5          # shorter than the span: every row


def test_one_noisy_first_reading_is_a_quarter_of_the_offset():
    """first_sample spreads a reading's noise over the whole campaign; start_level, read off the
    4 rows of its first 900 s, a quarter of it -- and the same rows shift the temperatures, so
    the law E = 2 ΔT holds in both frames."""
    df = campaign(kick=1.0)
    first = stack({"c": df}, ["T_a"], ["E_X"], "first_sample")
    level = stack({"c": df}, ["T_a"], ["E_X"], "start_level")
    law = 2.0 * level.X["T_a"].to_numpy()
    np.testing.assert_allclose(level.Y["E_X"].to_numpy()[1:] - law[1:], -0.25, atol=1e-12)
    np.testing.assert_allclose(first.Y["E_X"].to_numpy()[1:] - 2.0 * first.X["T_a"].to_numpy()[1:],
                               -1.0, atol=1e-12)
    np.testing.assert_allclose(level.X["T_a"].to_numpy()[:4].mean(), 0.0, atol=1e-12)


def test_an_error_not_read_in_the_span_is_refused_naming_campaign_and_column():
    df = campaign()
    df.loc[df["time"] <= START_SPAN_S, "E_X"] = np.nan
    says = r"start_level: campaign K07's E_X has no value in its first 900 s"
    with pytest.raises(ContractError, match=says):
        stack({"K07": df}, ["T_a"], ["E_X"], "start_level")


def test_diagnose_reads_its_candidates_from_the_same_level():
    time = np.r_[np.arange(6), np.arange(3)] * PERIOD
    v = np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 10.0, 20.0, 30.0])
    g = np.array(["a"] * 6 + ["b"] * 3)
    np.testing.assert_allclose(in_frame(v, g, "start_level", time),
                               [-1.5, -.5, .5, 1.5, 2.5, 3.5, -10, 0, 10])


def test_a_start_level_model_refuses_to_stream():
    """Its level needs the campaign's first 900 s, which a stream has not seen at its start."""
    from thermocomp.apps.deploy import StreamingCompensator

    comp = Compensator(MLR(), reference="start_level").fit({"a": campaign(), "b": campaign(kick=0.5)})
    with pytest.raises(ContractError, match="data.reference=start_level cannot stream"):
        StreamingCompensator(comp)


def test_run_records_it_and_replay_refuses_it_in_one_line(tmp_path, capsys):
    data = make_dataset(tmp_path / "ds", rows=60)
    out = tmp_path / "run"
    assert main(["run", *FAST, f"data.path={data}", f"out={out}", "data.reference=start_level"]) == 0
    metrics = json.loads((out / "metrics.json").read_text())
    assert metrics["reference"] == "start_level"
    capsys.readouterr()
    refused(["replay", *FAST, f"data.path={data}", f"out={tmp_path / 'replay'}",
             "data.reference=start_level"], capsys, "data.reference=start_level cannot stream")
    assert not (tmp_path / "replay" / "replay.json").exists()
