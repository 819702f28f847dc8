"""The served fallback model in the exported C (cmon83, issue 34): while a sensor no other
predicts is out, the served correction is the model fitted without it (``monitor.fallbacks``,
the default); the code now holds that model beside its own and serves it where the served
monitor does, and the model again once the sensor is back.

test_export_cmon82c's machine and ramp (``T_u``, a sensor no other predicts, excluded as
explaining ``T_b``'s band and re-admitted once back), deployed with its fallback model.  Before,
the code flagged ``FALLBACK`` from the exclusion on and the pack was cut there; now the numpy
mirror and the compiled code (gcc -Wall -Wextra -Werror) give the served corrections on every row
and the pack, not cut, passes.  An export without the fallback's laws (before cmon83) still
flags."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from test_export import needs_cc
from test_export_cmon80 import assert_packed_as_served
from test_export_cmon82c import _deployed, _machine, _served_moves
from thermocomp.apps.deploy.export import Simulator, state_space
from thermocomp.apps.deploy.export.fallbacks import _merge
from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
from thermocomp.apps.deploy.export.watch import FALLBACK, NOT_IN_CODE
from thermocomp.apps.deploy.report import stream_rows


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR with T_u's fallback model, its system with the monitor, the ramped
    record)``."""
    deployed, frame = _deployed(_machine(tmp_path_factory.mktemp("cmon83") / "data"),
                                "unobservable")
    return deployed, state_space(deployed, monitor=True), frame


def _mirror(ss, frame) -> tuple[np.ndarray, list[int], list[int]]:
    """The numpy mirror's corrections, the law set it serves and the rule it flags, per row."""
    sim = Simulator(ss)
    sim.reset()
    got, sets, missed = [], [], []
    for u, t in zip(frame[ss.inputs].to_numpy(float), frame["time"]):
        got.append(sim.step(u, t))
        sets.append(sim.serving)
        missed.append(sim.watch.missed if sim.watch.flags & NOT_IN_CODE else 0)
    return np.array(got), sets, missed


def _before_cmon83(ss):
    """``ss`` as exported before cmon83: the model's laws only, no ``fallback_set``."""
    keep = np.flatnonzero(np.asarray(ss.law_set) == 0)
    laws = {k: [getattr(ss, k)[r] for r in keep] for k in (
        "intercept", "b0", "bd", "g", "ar", "law_target", "law_lo", "law_hi", "law_ambient")}
    gain = [ss.clamp_gain[r] for r in keep] if ss.clamp_gain is not None else None
    return dataclasses.replace(ss, **laws, clamp_gain=gain, law_set=[], monitor={
        k: v for k, v in ss.monitor.items() if k != "fallback_set"})


@needs_cc
def test_the_code_serves_the_fallback_model_while_its_sensor_is_out(served, tmp_path):
    deployed, ss, frame = served
    assert "T_u" in deployed.fallbacks_
    k = [ss.inputs[i] for i in ss.monitor["inputs"]].index("T_u")
    assert ss.monitor["fallback_set"][k] == 1 and set(ss.law_set) == {0, 1}
    moves = [(r, to) for r, to, _ in _served_moves(deployed, frame) if to in ("excluded", "ok")]
    assert [to for _, to in moves] == ["excluded", "ok"], moves
    (out, _), (back, _) = moves
    want = corrections(ss, stream_rows(deployed, frame, "K06").y)
    got, sets, missed = _mirror(ss, frame)
    # the fallback served from the exclusion to the re-admission, the model before and after
    assert sets == [0] * (out - 1) + [1] * (back - out) + [0] * (len(frame) - back + 1)
    assert not any(missed) and np.max(np.abs(got - want)) < 1e-9
    # the model alone (an export before cmon83) parts from the served corrections there
    alone, _, _ = _mirror(_before_cmon83(ss), frame)
    assert np.max(np.abs(alone - want)[out - 1:back - 1]) > 1e-3
    assert_packed_as_served(tmp_path, deployed, ss, "K06", frame, want)


def test_an_export_before_cmon83_flags_the_fallback_from_the_exclusion_on(served):
    """Without the fallback's laws the code flags from the exclusion to the end, and the pack
    is cut at the first row the corrections part, not before the exclusion."""
    deployed, ss, frame = served
    row = [r for r, to, _ in _served_moves(deployed, frame) if to == "excluded"][0]
    old = _before_cmon83(ss)
    _, sets, missed = _mirror(old, frame)
    assert missed == [0] * (row - 1) + [FALLBACK] * (len(frame) - row + 1) and not any(sets)
    _, summary = conformance_pack(deployed, old, {"K06": frame})
    cut = summary["campaigns"][0]["cut"]
    assert cut["row"] >= row and "model fitted without" in cut["why"], cut


def _swapped_powers(ss):
    """``ss`` with its two static powers in the other order (its columns and lags alike): the
    same system."""
    n = len(ss.inputs)
    order = [*range(n), n + 1, n, *range(n + 2, len(ss.b0[0]))]
    lag_input = [{n: n + 1, n + 1: n}.get(j, j) for j in ss.lag_input]
    return dataclasses.replace(ss, powers=[ss.powers[1], ss.powers[0]], lag_input=lag_input,
                               b0=[[row[j] for j in order] for row in ss.b0])


@pytest.fixture(scope="module")
def merged_models(tmp_path_factory):
    """``deployed(model)``: ``(model with T_u's fallback, the ramped record)`` on the door-state
    record, fitted once per model for both ``into`` cases (scopec: each case fitted it again; the
    tests read it only, their systems made afresh from it)."""
    made: dict = {}

    def deployed(model: str):
        if model not in made:
            root = _machine(tmp_path_factory.mktemp(f"cmon83{model}") / "data")
            for csv in root.glob("K*.csv"):     # a state of many values (a door's 0 / 1: its powers alike)
                df = pd.read_csv(csv)
                df["S_door"] = (np.arange(len(df)) % 10) / 9.0
                df.to_csv(csv, index=False)
            made[model] = _deployed(root, "unobservable", model)
        return made[model]
    return deployed


@pytest.mark.parametrize("model", ["hammerstein", "lstm"])
@pytest.mark.parametrize("into", ["model", "fallback"])
def test_a_merged_fallback_steps_as_its_own_system(merged_models, model, into):
    """A model's fallback merged into the model's system, served, gives its own system's
    corrections, and the model's merged into its fallback's its own: a Hammerstein model's (its
    lags fewer: the model's appended; its powers in another order), an lstm's (its network of
    fewer inputs, padded)."""
    deployed, frame = merged_models(model)
    own = dataclasses.replace(state_space(deployed), monitor={})
    fallback = state_space(deployed.fallbacks_["T_u"])
    if model == "hammerstein":
        fallback = _swapped_powers(fallback)
        assert len(fallback.powers) == 2 and fallback.powers != own.powers
    else:
        assert len(own.lstm_in[0]) > len(fallback.lstm_in[0])
    base, added = (own, fallback) if into == "model" else (fallback, own)
    merged = dataclasses.replace(base, **{k: list(getattr(base, k)) for k in (
        "powers", "taus", "lag_input", "lag_decay", "lag_of")})
    _merge(merged, added, 1)
    # (the lag bank of a Hammerstein model's fallback: fewer lags, the model's appended to it)
    assert (len(merged.taus) > len(base.taus)) == (into == "fallback" and model == "hammerstein")
    assert len(merged.lstm_target) == len(base.lstm_target) + len(added.lstm_target)
    served = dataclasses.replace(merged, law_set=[1 - s for s in merged.law_set])
    rows, times = frame[own.inputs].to_numpy(float), frame["time"]
    assert np.max(np.abs(_plain(served, rows, times) - _plain(added, rows, times))) < 1e-9
    # the base's laws served: its own corrections, the added laws stepping beside
    assert np.max(np.abs(_plain(merged, rows, times) - _plain(base, rows, times))) < 1e-9


def _plain(ss, rows, times) -> np.ndarray:
    sim = Simulator(ss)
    sim.reset()
    return np.array([sim.step(u, t) for u, t in zip(rows, times)])
