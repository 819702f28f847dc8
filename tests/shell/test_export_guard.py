"""`thermocomp export` of what follows the linear system: the correction guard of the adaptive
compensator and the bias learned from reference measurements (``adapt.method=bias``).

The model is deployed as `replay` deploys it with ``monitor.adaptive=true`` on healthy test
campaigns (no sensor fault: the sensor monitor does not act, which the test checks); the
compiled C, the transpiled Structured Text and the numpy reference must equal the adaptive
stream to 1e-6 µm, with the monitor's guard and with one tight enough that the bound and the
rate limit act.  With ``adapt.method=bias`` they must equal the served model fed the same
reference measurements.
"""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cbuild import LEVEL
from conftest import copied_once, deployed_as_replay
from covering import covering
from test_export import (
    CAMPAIGNS,
    EVERY_EXCURSION,
    PARSED_BLOCK,
    TOLERANCE_UM,
    StructuredText,
    _compiled,
    _compose,
    _deployed,
    _make_dataset,
    _streamed,
    _trained,
    needs_cc,
    parses_as_the_parsed_block,
)
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.guard import CorrectionGuard
from thermocomp.apps.deploy.pyfunc import CompensatorModel
from thermocomp.apps.deploy.streaming import replay
from thermocomp.core.models._dynamics import first_order_lag
from thermocomp.shell.builders import build_compensator, deploy_stream
from thermocomp.shell.cli import main
from thermocomp.shell.source import read_streamed

FAMILIES = {"mlr": ["model=mlr"],
            "arx": ["model=arx", "model.estimator.ar=true", "model.estimator.delays=[2]"]}
OFFSET_UM = 5.0        # the machine's error moved by this after training: what the bias learns
EVERY = 6              # a reference measurement every this many rows
PERIOD_S = 60.0


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return _make_dataset(tmp_path_factory.mktemp("guard") / "data")


def _adaptive(dataset, family, *extra):
    """``(adaptive compensator as replay deploys it, healthy test campaigns)``; the second
    test campaign sampled irregularly (the rate limit scales with the time elapsed), with a
    missing, a repeated and a backward time (taken as the previous one plus one period)."""
    cfg = _compose(f"data.path={dataset}", "track=false", "monitor.adaptive=true",
                   *FAMILIES[family], *extra)
    deployed, ds, test_ids = deployed_as_replay(cfg)
    tests = [ds.campaigns[c].reset_index(drop=True).copy() for c in test_ids]
    tests[1]["time"] += np.r_[0.0, np.random.default_rng(1).uniform(-30, 30, len(tests[1]) - 1)]
    time = tests[1]["time"].to_numpy(copy=True)
    time[[5, 9, 13]] = np.nan, time[8], time[12] - 50.0
    tests[1]["time"] = time
    return deployed, tests


# a copy of _adaptive, fitted once for this module's tests (the tight guard replaces the copy's);
# _adaptive itself stays a fresh fit for the modules that import it
_adaptive_copy = copied_once(_adaptive)


def _tight(deployed, tests) -> list:
    """Replace the guard by one whose bound is the middle half of the free corrections and whose
    rate limit is half their median rate (first campaign): both act.  Returns the free corrections."""
    free = [replay(deployed.streaming, df)[deployed.targets_].to_numpy(float) for df in tests]
    y = np.vstack(free)
    rate = np.median(np.abs(np.diff(free[0], axis=0))
                     / np.diff(tests[0]["time"].to_numpy())[:, None], axis=0)   # regular sampling
    deployed.guard = CorrectionGuard(deployed.targets_, np.percentile(y, 25, axis=0),
                                     np.percentile(y, 75, axis=0), rate / 2, deployed.period_s)
    return free


def _guarded(deployed, tests) -> tuple[np.ndarray, list]:
    """The corrections the adaptive stream gives (campaigns stacked) and its events; the sensor
    monitor must not have acted (healthy data)."""
    out, events = [], []
    for df in tests:
        got = replay(deployed, df)
        assert (got["excluded_inputs"] == "").all()
        events += [e for row in got["events"] for e in json.loads(row)]
        out.append(-got[deployed.targets_].to_numpy(float))
    assert not [e for e in events if e.get("sensor") not in (None, "time")], events
    return np.vstack(out), events


def _rows(tests, columns) -> str:
    frames = [df[["time", *columns]] for df in tests]
    parts = [f.to_csv(index=False, float_format="%.17g") for f in frames]
    return parts[0] + "".join("\n" + p.split("\n", 1)[1] for p in parts[1:])


def _st(fb, tests, columns, references=None) -> np.ndarray:
    out = []
    for n, df in enumerate(tests):
        for k, (u, t) in enumerate(zip(df[columns].to_numpy(float), df["time"])):
            e = references[n][k] if references is not None else np.full(len(fb.vars["c"]), np.nan)
            fb.vars["ref_valid"][:] = np.isfinite(e)
            fb.vars["ref_error"][:] = np.nan_to_num(e)
            out.append(fb(u, t, k == 0))
    return np.array(out)


def _simulated(ss, tests, columns, references=None) -> np.ndarray:
    sim, out = Simulator(ss), []
    for n, df in enumerate(tests):
        sim.reset()
        for k, (u, t) in enumerate(zip(df[columns].to_numpy(float), df["time"])):
            out.append(sim.step(u, t))
            if references is not None:
                sim.reference(references[n][k])
    return np.array(out)


@needs_cc
@pytest.mark.parametrize("family, limits", covering(
    "the guard's bound and rate limit act on the corrections, whatever family made them",
    family=list(FAMILIES), limits=["monitor", "tight"]))
def test_the_code_of_an_adaptive_model_streams_as_its_guarded_replay(dataset, tmp_path, family,
                                                                     limits):
    deployed, tests = _adaptive_copy(dataset, family)
    if limits == "tight":
        free = np.vstack([-f for f in _tight(deployed, tests)])
    expected, events = _guarded(deployed, tests)
    assert {"substituted", "ok"} <= {e["to"] for e in events if e.get("sensor") == "time"}
    if limits == "tight":     # the guard acts, and its output is not the model's
        assert {"bounded", "rate_limited"} <= {e["to"] for e in events}
        assert np.max(np.abs(expected - free)) > 1.0
    ss = state_space(deployed)
    assert ss.guard and ss.guard_lo == deployed.guard.lo.tolist()
    cols = deployed.columns_
    got = _streamed(_compiled(deployed, tmp_path, LEVEL), _rows(tests, cols))
    assert np.max(np.abs(got.to_numpy(float) - expected)) <= TOLERANCE_UM
    assert np.max(np.abs(_simulated(ss, tests, cols) - expected)) <= TOLERANCE_UM
    fb = StructuredText(exported_files(deployed, "st")["compensator.st"])
    assert np.max(np.abs(_st(fb, tests, cols) - expected)) <= TOLERANCE_UM


def _served(deployed, tests, references) -> np.ndarray:
    """What the served model gives one machine (one session, a reset per campaign) whose rows
    carry the reference measurements (NaN: none); a copy, so that what it learns stays there."""
    model, out = CompensatorModel(copy.deepcopy(deployed)), []
    for df, e in zip(tests, references):
        frame = df[["time", *deployed.columns_]].assign(
            **{t: e[:, i] for i, t in enumerate(deployed.targets_)})
        got = model.predict(None, frame, params={"reset": True})
        out.append(got[["C_" + t[2:] for t in deployed.targets_]].to_numpy(float))
    return np.vstack(out)


@needs_cc
@pytest.mark.parametrize("family, method", covering(
    "the reference update acts on the corrections, whatever family made them",
    family=list(FAMILIES), method=["bias", "rls"]))
def test_the_code_learns_from_reference_measurements_as_the_served_model(dataset, tmp_path, family,
                                                                         method):
    deployed, tests = _adaptive(dataset, family, f"adapt.method={method}")
    targets = deployed.targets_
    references = []
    for df in tests:   # every EVERY-th row measured, on a machine whose error moved by OFFSET_UM
        e = df[targets].to_numpy(float) + OFFSET_UM
        e[np.arange(len(df)) % EVERY != EVERY - 1] = np.nan
        references.append(e)
    references[1][EVERY - 1::EVERY, 1] = np.nan      # some references measure one axis only
    expected = _served(deployed, tests, references)
    frozen = _served(deployed, tests, [np.full_like(e, np.nan) for e in references])
    assert np.max(np.abs(expected - frozen)) > OFFSET_UM / 2        # it learned
    second = len(tests[0])                                        # and kept it across the reset
    assert np.all(np.abs(expected[second] - frozen[second]) > OFFSET_UM / 2)
    ss = state_space(deployed)
    assert ss.adapt == method and ss.guard
    cols = deployed.columns_
    text = _rows([df.assign(**{t: e[:, i] for i, t in enumerate(targets)})
                  for df, e in zip(tests, references)], [*cols, *targets])
    got = _streamed(_compiled(deployed, tmp_path, LEVEL), text)
    assert np.max(np.abs(got.to_numpy(float) - expected)) <= TOLERANCE_UM
    assert np.max(np.abs(_simulated(ss, tests, cols, references) - expected)) <= TOLERANCE_UM
    fb = StructuredText(exported_files(deployed, "st")["compensator.st"])
    assert np.max(np.abs(_st(fb, tests, cols, references) - expected)) <= TOLERANCE_UM


def _spindle_dataset(root: Path, rows: int = 120, seed: int = 3) -> Path:
    """Six campaigns (four train, two test) of a spindle stepping between speeds, one sample a
    minute: the error is the hall's expansion plus a 30-min lag of friction heat growing as the
    square of the speed, which only a power of the state ``S_spindle_rpm`` explains (``seed``:
    other draws of it, benchmarks/bench_zerofew67.py's)."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(seed)
    t = np.arange(rows) * PERIOD_S
    for cid, _ in CAMPAIGNS:
        rpm = np.repeat(rng.choice([0.0, 2000.0, 4000.0, 8000.0], rows // 20 + 1), 20)[:rows]
        hall = 20 + np.cumsum(rng.normal(0, 0.02, rows))
        heat = first_order_lag((rpm / 8000.0) ** 2, t, None, 1800.0)
        pd.DataFrame({"time": t, "T_hall": hall, "T_far": hall + rng.normal(0, 0.3, rows),
                      "T_amb": 20 + 0.3 * np.sin(t / 2000) + rng.normal(0, 0.05, rows),
                      "S_spindle_rpm": rpm,
                      "E_X": 2.0 * (hall - hall[0]) + 6.0 * heat + rng.normal(0, 0.05, rows)}
                     ).to_csv(root / f"{cid}.csv", index=False)
    pd.DataFrame([(c, f"{c}.csv", s, "") for c, s in CAMPAIGNS],
                 columns=["campaign", "file", "split", "notes"]).to_csv(root / "campaigns.csv", index=False)
    return root


@needs_cc
@pytest.mark.parametrize("denoise", ("none", "emd"))
def test_the_code_of_a_hammerstein_model_streams_as_replay(tmp_path, denoise):
    """The state's static power (sign(w)|w|^e of the speed, read unfiltered) before the lag bank;
    one test sensor pushed out of the envelope half-way, so the clamp acts too."""
    data = _spindle_dataset(tmp_path / "data")
    cfg = _compose(f"data.path={data}", "track=false", "monitor.adaptive=false", "model=hammerstein",
                   EVERY_EXCURSION, "model.estimator.lagbank.n_taus=3", f"denoise={denoise}",
                   "model.estimator.state_start=steady")     # the data's heat starts steady
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    stream = deploy_stream(cfg, build_compensator(cfg, ds=ds).fit(train), train)
    tests = [ds.campaigns[c].reset_index(drop=True).copy() for c in test_ids]
    for df in tests:
        df.loc[len(df) // 2:, "T_hall"] += 30.0
    streamed = [replay(stream, df) for df in tests]
    assert all(s["n_clamped"].iloc[len(s) // 2:].gt(0).all() for s in streamed)
    expected = np.vstack([-s[stream.targets_].to_numpy(float) for s in streamed])
    ss = state_space(stream)
    assert 2.0 in [e for _, _, e in ss.powers] and ss.inputs[-1] == "S_spindle_rpm"
    cols = stream.columns_
    got = _streamed(_compiled(stream, tmp_path, LEVEL), _rows(tests, cols))
    assert np.max(np.abs(got.to_numpy(float) - expected)) <= TOLERANCE_UM
    assert np.max(np.abs(_simulated(ss, tests, cols) - expected)) <= TOLERANCE_UM
    fb = StructuredText(exported_files(stream, "st")["compensator.st"])
    fb.vars["EXPT"] = math.pow
    assert np.max(np.abs(_st(fb, tests, cols) - expected)) <= TOLERANCE_UM


def test_every_step_of_the_block_parses_as_iec_61131_3(dataset, tmp_path):
    """Time rule, powers (EXPT), guard and reference update in one block: an adaptive Hammerstein
    model learning a bias.  The block must be, up to literal values and list lengths, the one
    test_export's `test_the_structured_text_parses_as_iec_61131_3` parses with blark (seconds a
    block): the same declarations and statements."""
    data = _spindle_dataset(tmp_path / "data")
    cfg = _compose(f"data.path={data}", "track=false", "model=hammerstein", "adapt.method=bias",
                   "model.estimator.lagbank.n_taus=3")
    deployed, ds, _ = deployed_as_replay(cfg)
    ss = state_space(deployed)
    assert ss.powers and ss.guard and ss.substitute_time and ss.adapt == "bias"
    parsed = exported_files(_deployed(dataset, *PARSED_BLOCK)[0], "st")["compensator.st"]
    parses_as_the_parsed_block(exported_files(deployed, "st")["compensator.st"], parsed)


def test_export_of_a_model_pkl_names_what_is_not_in_the_code(dataset, tmp_path, capsys):
    model = _trained(dataset, tmp_path, "mlr")
    out = tmp_path / "code"
    assert main(["export", f"data.path={dataset}", f"export.model={model}", "export.format=json",
                 f"out={out}", "track=false", "adapt.method=rls"]) == 0
    said = capsys.readouterr().err
    exported = json.loads((out / "compensator.json").read_text())
    assert exported["guard"] and exported["substitute_time"] and exported["adapt"] == "rls"
    assert np.array(exported["adapt_cov"]).shape == (2, 2, 2)
    left = exported["provenance"]["not_in_code"]
    assert left and "sensor monitor" in left[0] and left[0] in " ".join(said.split())
