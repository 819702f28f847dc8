"""A diagnosed state times the rises of all the inputs exports (export62).

diagpos61's ``inputs_product`` -- a machine state ``c`` (a saddle's position) times the rise
``x_i - x_i(0)`` of every model input -- took a gantry's E_Y from 8.69 to 2.40 µm and streamed,
but ``thermocomp export`` refused it by name, so it could not reach a CNC.  Now it is one derived
input per model input, ``r_c (x_i - x_i(0))``, whose second factor is the model's input itself:
in the code's excess channel the clamped input's, ``r_c (e_i - e_i(0))``, as the stream's clamped
copy reads it; the clamp's bound is the stream's gain, which grows by the state's value held from
the sample before the campaign's first excess (a campaign out at its first sample: the target
clamped outright, as the stream has no value then).  The C, the Structured Text and the JSON read
back equal ``replay`` to 1e-9 µm over MLR, ARX and lag-bank bases, plain and adaptive
(``adapt.method=bias`` learning from reference measurements), and ``thermocomp export``'s check
pack passes on the compiled ``stream --check``; around an ATI model, refused by name here, it
exports since exportprod65 (test_export_atiprod65).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from sklearn.base import clone

from cbuild import LEVEL
from test_export import (
    EVERY_EXCURSION,
    PUSH_C,
    StructuredText,
    _compiled,
    _compose,
    _streamed,
    checked_pack,
    needs_cc,
    parses_as_the_parsed_block,
)
from test_export_ati57 import CAMPAIGNS, write_manifest
from test_export_auto57 import TOLERANCE_UM, _proved, deployed
from test_export_effects59 import _json_proved
from test_export_guard import EVERY, OFFSET_UM, _rows, _served, _simulated, _st
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.apps.diagnose import AugmentedRegressor
from thermocomp.core.models import ARX, MLR, LagBank
from thermocomp.shell.builders import deploy_stream, deployable
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import save_model
from thermocomp.shell.source import read_streamed

PRODUCT = {"kind": "interaction", "transform": "inputs_product", "column": "S_y_pos",
           "frame": "absolute"}
BASES = {"mlr": MLR, "arx": lambda: ARX(ar=True), "lagbank": lambda: LagBank(n_taus=2)}


def _gantry(root, rows: int = 50):
    """A rail (``T_a``) and its top plate (``T_b``) whose rises reach the tool through where a
    saddle stands (``S_y_pos``, a new place every 5 samples), the air beside."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(6201)
    t = np.arange(rows) * 120.0
    for i, (cid, _, a0) in enumerate(CAMPAIGNS):
        a = a0 + (2 + i % 3) * (1 - np.exp(-t / 2500)) + rng.normal(0, 0.03, rows)
        b = a0 + 1.5 * np.sin(t / 2500 + i) + rng.normal(0, 0.03, rows)
        amb = a0 + 0.4 * np.sin(t / 3000 + i) + rng.normal(0, 0.03, rows)
        y = np.repeat(rng.uniform(200, 3800, rows // 5 + 1), 5)[:rows]
        ex = (11.5e-3 * y * (a - a[0]) + 4e-3 * (4000 - 2 * y) * (b - b[0]) - 1.5 * (amb - amb[0])
              + rng.normal(0, 0.05, rows))
        pd.DataFrame({"time": t, "T_a": a, "T_b": b, "T_amb": amb, "S_y_pos": y,
                      "E_X": ex}).to_csv(root / f"{cid}.csv", index=False)
    write_manifest(root)
    return root


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _gantry(tmp_path_factory.mktemp("inputs_product") / "data")


_PLAIN: dict = {}


def _plain(data, overrides: tuple) -> tuple:
    """``(copies of the test campaigns with T_a pushed out half-way, the plain MLR compensator)``,
    :func:`deployed` once per dataset and overrides (the diagnosed model is fitted on a clone of
    the compensator, which it leaves as it was; the tests get copies, which they shift)."""
    key = (str(data), overrides)
    if key not in _PLAIN:
        _, tests, mlr = deployed(data, "model=mlr", *overrides, pushed="T_a")
        _PLAIN[key] = tests, mlr
    tests, mlr = _PLAIN[key]
    return [df.copy() for df in tests], mlr


def _diagnosed(data, effects, base=None, *overrides, adaptive: bool = False, pushed_from="half"):
    """``(deployed, test campaigns with T_a pushed out from row ``pushed_from`` (half-way;
    ``None``: healthy), the fitted compensator)`` of ``base`` (MLR) with ``effects`` for E_X, as
    diagnose's config builds it; ``adaptive``: the adaptive compensator around the stream."""
    common = (f"data.path={data}", "track=false", EVERY_EXCURSION, *overrides)
    tests, mlr = _plain(data, overrides)
    cfg = _compose(*common, f"monitor.adaptive={str(adaptive).lower()}")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = clone(mlr).set_params(estimator=AugmentedRegressor(
        base if base is not None else MLR(), effects={"E_X": effects}))
    comp.fit(train)
    stream = deploy_stream(cfg, comp, train)
    if pushed_from != "half":
        tests = [ds.campaigns[c].reset_index(drop=True).copy() for c in test_ids]
        for df in tests if pushed_from is not None else ():
            df.loc[pushed_from:, "T_a"] += PUSH_C
    return (deployable(cfg, stream, train, ds) if adaptive else stream), tests, comp


@needs_cc
@pytest.mark.parametrize("base, frame", [("mlr", "absolute"), ("mlr", "referenced"),
                                         ("arx", "absolute"), ("lagbank", "absolute")])
def test_a_state_times_the_inputs_rises_exports_and_equals_replay(data, tmp_path, base, frame):
    effect = {**PRODUCT, "frame": frame}
    stream, tests, _ = _diagnosed(data, [effect], BASES[base]())
    ss = state_space(stream)                                       # refused before
    k, state = len(stream.compensator.inputs_), ss.inputs.index("S_y_pos")
    referenced = int(frame == "referenced")
    assert ss.derived == [[state, j, referenced, 1] for j in range(k)]
    assert ss.derived_clamped == [1] * k                           # the model's input, clamped
    # the clamp's bound: the stream's gain, the state's value held at the first excess
    assert ss.clamp_states == [[state, referenced]] and not ss.clamp_outright
    assert np.abs(ss.clamp_state_gain).max() > 0.0 and ss.clamp_state_first == [1]
    assert "interaction:S_y_pos product(model inputs' rises)" in ss.provenance["laws"]["E_X"]
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM        # C, ST, numpy: as replay
    assert _json_proved(stream, tests) <= TOLERANCE_UM


@needs_cc
def test_a_campaign_out_at_its_first_sample_is_clamped_outright_as_the_stream_does(data, tmp_path):
    """Inputs in the absolute frame (``data.reference=none``) pushed out from the first sample:
    the stream has no state value for the gain yet and clamps the target outright for the
    campaign; the code too (its bound otherwise from the state's value held before the excess,
    the other campaign pushed half-way)."""
    stream, tests, _ = _diagnosed(data, [{**PRODUCT, "frame": "referenced"}], LagBank(n_taus=2),
                                  "data.reference=none", pushed_from=0)
    assert state_space(stream).referenced[:3] == [0, 0, 0]
    # further out as the campaign goes (its excess's rise times the position: what the held
    # gain would bound); the other campaign out half-way only
    tests[0]["T_a"] += np.linspace(0.0, PUSH_C, len(tests[0]))
    tests[1].loc[:len(tests[1]) // 2 - 1, "T_a"] -= PUSH_C
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    assert _json_proved(stream, tests) <= TOLERANCE_UM


@needs_cc
def test_the_adaptive_code_learns_a_bias_around_it_as_the_served_model(data, tmp_path):
    """Healthy test campaigns (a sensor pushed out is the sensor monitor's, not in the code)."""
    deployed_, tests, _ = _diagnosed(data, [PRODUCT], LagBank(n_taus=2), "adapt.method=bias",
                                     adaptive=True, pushed_from=None)
    targets, cols = deployed_.targets_, deployed_.columns_
    references = []
    for df in tests:    # every EVERY-th row measured, on a machine whose error moved by OFFSET_UM
        e = df[targets].to_numpy(float) + OFFSET_UM
        e[np.arange(len(df)) % EVERY != EVERY - 1] = np.nan
        references.append(e)
    expected = _served(deployed_, tests, references)
    frozen = _served(deployed_, tests, [np.full_like(e, np.nan) for e in references])
    assert np.max(np.abs(expected - frozen)) > OFFSET_UM / 2        # it learned
    ss = state_space(deployed_)
    assert ss.adapt == "bias" and ss.guard and ss.derived_clamped
    text = _rows([df.assign(**{t: e[:, i] for i, t in enumerate(targets)})
                  for df, e in zip(tests, references)], [*cols, *targets])
    got = _streamed(_compiled(deployed_, tmp_path, LEVEL), text)
    assert np.max(np.abs(got.to_numpy(float) - expected)) <= TOLERANCE_UM
    assert np.max(np.abs(_simulated(ss, tests, cols, references) - expected)) <= TOLERANCE_UM
    fb = StructuredText(exported_files(deployed_, "st")["compensator.st"])
    assert np.max(np.abs(_st(fb, tests, cols, references) - expected)) <= TOLERANCE_UM


def test_its_structured_text_parses_as_iec_61131_3(data, parsed_block):
    stream, _, _ = _diagnosed(data, [PRODUCT])
    text = exported_files(stream, "st")["compensator.st"]
    assert "DERIVED_CLAMPED" in text and "STATE_GAIN" in text
    parses_as_the_parsed_block(text, parsed_block)


# (around an ATI model, refused here before, it exports since exportprod65:
# test_export_atiprod65.py)


@needs_cc
def test_the_export_commands_check_pack_passes_for_it(data, tmp_path):
    """``thermocomp export`` of the model.pkl (refused by name before), the default deployment
    (adaptive): the compiled ``stream --check`` gives the pack's expected corrections."""
    _, _, comp = _diagnosed(data, [PRODUCT], LagBank(n_taus=2))
    out = tmp_path / "code"
    assert main(["export", f"data.path={data}", f"export.model={save_model(comp, tmp_path / 'm.pkl')}",
                 "export.format=c", f"out={out}", "track=false"]) == 0
    banner = (out / "compensator.c").read_text().split("*/")[0]
    assert "interaction:S_y_pos product(model inputs' rises) (absolute)" in banner
    # (the test campaigns, and the jump and the freeze the pack plants: cmon76; a dropout: cdrop77;
    # a reading beyond its range and a common step: cmon80)
    assert checked_pack(out).count("stream: check passed: 50 rows") == 7
