"""A row written again (same time, same values) is skipped by the deployed stream (dup99).

A logger re-sending its last sample: the served stream took each copy as a new sample one period
on, its sensor monitor saw every sensor frozen (audit98: all ten excluded at the 12th copy) and
the lags stood still for the burst.  ``run`` refuses a time that repeats (the row written twice
is to be deleted), so the record scored is the one without the copies: the adaptive
compensator (served, replay), the Simulator, the compiled C and the Structured Text now skip
such a row, the last corrections given again.  Before dup99 each form of the lag bank below
parted from the record without the copies by the lags' drift (> 1e-3 µm; the test fails there).
benchmarks/bench_dup99.py measures it on simulated machines.

(dep107c) What the forms say of their rows' time and cells, as the file reader says it of the same
rows: a logger set to another rate mid-stream and a stretch without rows (a gateway's outage)
were said by ``replay`` (the file reader) and not by the compiled C nor the served model, whose
corrections were the same (audit107); ``monitor.input=-`` said no stretch without rows; the C asked
whether a decimal comma (``22,61`` in a ','-separated stream) was a missing-value mark, stdin named
no decimal comma.  Now each says it, naming the row; no correction changes
(benchmarks/bench_dep107c.py holds the C's output to its base's byte for byte on audit107's record).
"""

from __future__ import annotations

import io
import json
import logging
import subprocess

import numpy as np
import pandas as pd
import pytest

from test_export import StructuredText, _compiled, _make_dataset, needs_cc
from test_export_first_time import AGREE_UM, _corrections, _deployed
from test_export_guard import _rows, _simulated, _st
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.apps.deploy.pyfunc import CompensatorModel
from thermocomp.base.log import logger
from thermocomp.core.io import read_dataset
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.stdin import stream_campaigns

ROW, COPIES = 20, 8        # the row written again, how many times more
SLOW_FROM, GAP = 20, range(25, 29)     # (dep107c) the row from which the period is 10x; rows left out
EARLY = 22      # (con111) the gap this many rows sooner: into the watch's first steps


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("repeat99") / "data")


def _burst(df: pd.DataFrame, time=True) -> pd.DataFrame:
    """``df`` with row :data:`ROW` written :data:`COPIES` times more (time and values)."""
    out = pd.concat([df.iloc[:ROW + 1], df.iloc[[ROW] * COPIES], df.iloc[ROW + 1:]],
                    ignore_index=True)
    return out if time else out.assign(time=np.nan)


def _served(deployed, df) -> pd.DataFrame:
    """The served model's answer (``predict``, row by row as a session's block) from a reset."""
    deployed.reset()
    return deployed.predict(df)


def _forms(deployed, df, tmp_path) -> dict:
    """Every form's corrections of ``df``'s rows; the compiled stream's stderr."""
    cols, ss = deployed.columns_, state_space(deployed)
    run = subprocess.run([str(_compiled(deployed, tmp_path))], input=_rows([df], cols), text=True,
                         capture_output=True, check=True)
    return {"replay": _corrections(deployed, df),
            "served": -_served(deployed, df)[deployed.targets_].to_numpy(float),
            "simulator": _simulated(ss, [df], cols),
            "c": pd.read_csv(io.StringIO(run.stdout)).to_numpy(float),
            "st": _st(StructuredText(exported_files(deployed, "st")["compensator.st"]), [df], cols),
            "said": run.stderr}


@pytest.fixture(scope="module")
def c_folder(tmp_path_factory):
    """Where the adaptive lag bank's C is built (once: by :func:`burst`'s forms)."""
    return tmp_path_factory.mktemp("c")


@pytest.fixture(scope="module")
def burst(dataset, c_folder):
    """``(every form's corrections of the burst, the healthy ones each row should give, the
    deployed lag bank, the burst)``."""
    deployed, test = _deployed(dataset, adaptive=True)
    healthy = _corrections(deployed, test)
    want = np.vstack([healthy[:ROW + 1], healthy[[ROW] * COPIES], healthy[ROW + 1:]])
    df = _burst(test)
    return _forms(deployed, df, c_folder), want, deployed, df


@needs_cc
@pytest.mark.parametrize("form", ("served", "replay", "simulator", "c", "st"))
def test_a_row_written_again_is_skipped_in_every_form(burst, form):
    forms, want, _, _ = burst
    assert np.max(np.abs(forms[form] - want)) <= AGREE_UM


@needs_cc
def test_a_burst_of_rows_written_again_is_said_once_and_counted(burst):
    forms, _, deployed, df = burst
    assert forms["said"].count("a row written again") == 1, forms["said"]
    events = [e for row in _served(deployed, df)["events"] for e in json.loads(row)]
    assert [e["to"] for e in events] == ["repeated"] and deployed.n_repeated_ == COPIES
    assert state_space(deployed).skip_repeats


@needs_cc
@pytest.mark.parametrize("case", ("plain", "no time"))
def test_a_row_that_cannot_be_told_from_a_sample_is_one_in_every_form(dataset, tmp_path, case):
    # a plain stream (no monitor to misjudge it) steps it as before; a stream without a time
    # cannot tell a row written again from a machine standing still (run scores such a file's
    # every row): stepped one period on, every form alike
    deployed, test = _deployed(dataset, adaptive=case != "plain")
    df = _burst(test, time=case == "plain")
    forms = _forms(deployed, df, tmp_path)
    forms.pop("said")
    if case == "plain":
        forms.pop("served")           # (a plain stream's predict is replay's)
    ref = forms.pop("replay")
    assert np.max(np.abs(ref[ROW + 1:ROW + 1 + COPIES] - ref[ROW])) > 1e-3   # the lags moved
    for form, got in forms.items():
        assert np.max(np.abs(got[1:] - ref[1:])) <= AGREE_UM, form


class _Lines(logging.Handler):
    def __init__(self):
        super().__init__()
        self.lines: list[str] = []

    def emit(self, record):
        self.lines.append(record.getMessage())


def _said(make) -> tuple[str, object]:
    """What ``make()`` logs (the thermocomp logger does not propagate to caplog) and returns, or
    its refusal."""
    handler = _Lines()
    logger.addHandler(handler)
    try:
        got = make()
    except ValueError as exc:
        got = exc
    finally:
        logger.removeHandler(handler)
    return "\n".join(handler.lines), got


def _said_forms(deployed, df, stream_c, tmp_path) -> dict:
    """What the file reader, stdin, the C and the served model say of ``df``'s rows, with the C's
    and the served corrections."""
    cols = deployed.columns_
    text = _rows([df], cols)
    df.to_csv(tmp_path / "rows.csv", index=False)             # (with its errors: a record's file)
    fed = subprocess.run([str(stream_c)], input=text, text=True, capture_output=True)
    model = CompensatorModel(deployed)
    served_said, served = _said(lambda: model.predict(None, df[["time", *cols]],
                                                      {"session": "m7", "reset": True}))
    return {"file": _said(lambda: read_dataset(tmp_path / "rows.csv"))[0],
            "stdin": _said(lambda: stream_campaigns(text, cols, ReadOptions.from_cfg({})))[0],
            "c": fed.stderr, "served": served_said, "events": [
                e for row in served["events"] for e in json.loads(row) if e["sensor"] == "time"],
            "corrections": (pd.read_csv(io.StringIO(fed.stdout)).to_numpy(float),
                            served.filter(like="C_").to_numpy(float))}


@needs_cc
@pytest.mark.parametrize("fault", ("period", "gap", "early_gap", "healthy"))
def test_the_c_and_the_served_model_say_the_rows_time_as_the_file_reader(dataset, c_folder, burst,
                                                                          tmp_path, fault):
    deployed, test = _deployed(dataset, adaptive=True)
    stream_c = c_folder / "stream"
    df = test.copy()
    if fault == "period":          # 120 s, then 1200 s from data row 21 (line 22)
        t = df["time"].to_numpy(float)
        df["time"] = np.r_[t[:SLOW_FROM], t[SLOW_FROM - 1] + 1200.0 * np.arange(1, len(t) - SLOW_FROM + 1)]
    elif fault == "gap":           # data rows 26-29 left out: 5 periods before data row 26
        df = df.drop(index=list(GAP)).reset_index(drop=True)
    elif fault == "early_gap":     # (con111) rows 4-7, while the period is learned: before data row 4
        df = df.drop(index=[g - EARLY for g in GAP]).reset_index(drop=True)
    said = _said_forms(deployed, df, stream_c, tmp_path)
    c, served = said["corrections"]
    # the corrections as they were: the C = the served = replay of the same rows
    assert np.max(np.abs(c - served)) <= AGREE_UM
    assert np.max(np.abs(c - _corrections(deployed, df))) <= AGREE_UM
    if fault == "healthy":
        assert not [ln for form, ln in said.items() if form in ("file", "stdin", "c", "served")
                    and ("sample period" in ln or "without rows" in ln)]
        assert said["events"] == []
        return
    words, row = (("the sample period changes from 120 s to 1200 s here", 21) if fault == "period"
                  else ("5 sample periods of 120 s without rows", 26 - EARLY * (fault == "early_gap")))
    file_words = words if fault == "period" else "steps of 5 sample periods of 120 s"
    assert f"line {row + 1} (data row {row})" in said["file"] and file_words in said["file"]
    assert said["stdin"].startswith("<stdin>, column 'time'") and f"data row {row}" in said["stdin"]
    assert file_words in said["stdin"]
    assert f"stream: line {row + 1}: {words}" in said["c"], said["c"]
    assert f"session 'm7', column 'time', data row {row} of the block: {words}" in said["served"]
    assert [(e["to"], e["time"]) for e in said["events"]] == [
        ("period changed" if fault == "period" else "rows missing", float(df["time"].iloc[row - 1]))]


@needs_cc
def test_a_decimal_comma_in_a_comma_separated_stream_is_named_as_one(dataset, c_folder, burst):
    # audit107: the C asked whether `22,61` was a missing-value mark; stdin named no decimal comma
    deployed, test = _deployed(dataset, adaptive=True)
    stream_c = c_folder / "stream"
    rows = test[["time", *deployed.columns_]].astype(object)
    rows.loc[9, "T_a"] = "22,61"
    text = rows.to_csv(index=False)                   # (the cell quoted: "22,61")
    fed = subprocess.run([str(stream_c)], input=text, text=True, capture_output=True)
    assert fed.returncode == 2
    assert fed.stderr.startswith("stream: line 11: input T_a: '22,61' is no number: a decimal comma? "
                                 "this stream separates its cells with ','"), fed.stderr
    refused = _said(lambda: stream_campaigns(text, deployed.columns_, ReadOptions.from_cfg({})))[1]
    assert str(refused) == ("file <stdin>, column 'T_a', data row 10: non-numeric value: '22,61' is not "
                            "a number: a decimal comma? set data.decimal=','")
