"""A diagnosed model's lags, products and squares export as derived inputs (exportdiag59).

``thermocomp diagnose`` accepts most often a lag of an undeclared signal (the door,
``signal:S_door first_order_lag``), a product of two columns (``interaction:S_door
product(T_a)``) or a square; ``export`` refused each of them by name (deploy59), so such a
model reached the machine only through ``serve``/``connect``.  Each is a feature the code
computes from its inputs as the stream's model computes it from its context (the declared
input denoised, a state raw; its change since the campaign's first sample in the effect's
frame), a lag a lag-bank channel on it (a low-pass of the inputs one per input).  The C, the ST
and the JSON (read back into the numpy reference) equal ``replay`` to 1e-9 µm, the clamp acting
(outright, as the stream clamps a model without a step gain) and the door missing at a
campaign's start and mid-run (held, as the served model holds it); what still does not export
(a base of a family the code does not hold: arx_rf's exporting since exportati63, an lstm's
since exportlstm64, test_export_diaglstm64; an initial-state transient, ``ambient_step``, a lag
bank's lag of a lag and effects around an ATI model export since exportrest60, the ambient law
around an ATI model's ambient interaction since exportati60) is refused naming it.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from test_export import needs_cc
from test_export_ati57 import CAMPAIGNS, write_manifest
from test_export_auto57 import TOLERANCE_UM, _proved
from test_export_diagnosed59 import _diagnosed as diagnosed
from test_export_refusal59 import OwnMLR
from thermocomp.apps.deploy.export import NotExportable, Simulator, exported_files, state_space
from thermocomp.apps.deploy.export.statespace import StateSpace
from thermocomp.apps.deploy.streaming import replay
from thermocomp.core.models import LagBank
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import save_model

LAG = {"kind": "signal", "transform": "first_order_lag", "column": "S_door", "tau_s": 600.0}
INPUT_LAG = {"kind": "dynamics", "transform": "first_order_lag", "column": "T_a", "tau_s": 900.0}
PRODUCT = {"kind": "interaction", "transform": "product", "column": "S_door", "other": "T_b"}
AMBIENT_LAW = {"kind": "ambient_interval", "transform": "ambient_linear"}
LOWPASS = {"kind": "dynamics", "transform": "lowpass_inputs", "tau_s": 900.0}
SQUARE = {"kind": "nonlinear", "transform": "square", "column": "T_a"}


def _door(root, rows: int = 50):
    """A machine with a door (``S_door``, not a declared input) whose opening cools the axis
    through a lag, and a second sensor ``T_b``; every campaign starts at its own door state."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(5959)
    t = np.arange(rows) * 120.0
    for i, (cid, _, a0) in enumerate(CAMPAIGNS):
        a = a0 + (3 + i % 3) * (1 - np.exp(-t / 2000)) + rng.normal(0, 0.03, rows)
        b = a0 + 2 * np.sin(t / 2500 + i) + rng.normal(0, 0.03, rows)
        amb = a0 + 0.4 * np.sin(t / 3000 + i) + rng.normal(0, 0.03, rows)
        door = ((t // (600 * (1 + i % 3)) + i) % 2).astype(float)
        lagged = pd.Series(door).ewm(alpha=0.2).mean().to_numpy()
        ex = (2.0 * (a - a[0]) - 1.5 * (amb - amb[0]) - 4.0 * lagged + 0.5 * door * (b - b[0])
              + 0.3 * (a - a[0]) ** 2 + rng.normal(0, 0.05, rows))
        pd.DataFrame({"time": t, "T_a": a, "T_b": b, "T_amb": amb, "S_door": door,
                      "E_X": ex}).to_csv(root / f"{cid}.csv", index=False)
    write_manifest(root)
    return root


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _door(tmp_path_factory.mktemp("effects") / "data")


def _diagnosed(data, effects: list, alpha=None, with_model: bool = False, base=None):
    """``(stream as replay deploys it, test campaigns with T_a pushed out half-way)`` of MLR
    with ``effects`` for E_X, the way diagnose's written config builds it."""
    stream, tests, comp = diagnosed(data, effects, alpha, base)
    tests = [df.copy() for df in tests]        # the door missing at a start and mid-run (held)
    tests[0].loc[[0, 1], "S_door"] = np.nan
    tests[1].loc[[20, 21, 22], "S_door"] = np.nan
    return (stream, tests) + ((comp,) if with_model else ())


def _json_proved(stream, tests) -> float:
    """The largest |difference| of the exported JSON, read back and stepped, from ``replay``."""
    ss = StateSpace.from_dict(json.loads(exported_files(stream, "json")["compensator.json"]))
    sim, rows = Simulator(ss), []
    for df in tests:
        sim.reset()
        rows += [sim.step(u, t) for u, t in zip(df[stream.columns_].to_numpy(float), df["time"])]
    expected = np.vstack([-replay(stream, df)[stream.targets_].to_numpy(float) for df in tests])
    return float(np.max(np.abs(np.array(rows) - expected)))


def _exports_as_replay(data, tmp_path, effects, alpha=None):
    stream, tests = _diagnosed(data, effects, alpha)
    ss = state_space(stream)                                  # refused before
    for e in effects:
        if e["transform"] in ("ambient_linear", "lowpass_inputs"):
            continue
        title = f"{e['kind']}:{e['column']}"
        assert title in ss.provenance["laws"]["E_X"]          # the banner names the effect
        assert title in exported_files(stream, "c")["compensator.c"]
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    assert _json_proved(stream, tests) <= TOLERANCE_UM
    return ss


@needs_cc
@pytest.mark.parametrize("effect, alpha", [(LAG, None), (LAG, 0.01), (INPUT_LAG, None)],
                         ids=["signal", "signal-shrunk", "input"])
def test_a_diagnosed_lag_exports_as_a_lag_bank_channel_and_equals_replay(data, tmp_path, effect,
                                                                         alpha):
    ss = _exports_as_replay(data, tmp_path, [effect], alpha)
    # the door, missing at a campaign's start and mid-run, is held as served; T_a refuses
    assert ss.held == ([int(c == "S_door") for c in ss.inputs] if effect is not INPUT_LAG else [])
    column = ss.inputs.index(effect["column"])
    assert ss.derived == [[column, -1, 1, 0]]                 # the change since the first sample
    assert ss.taus == [effect["tau_s"]] and ss.uses_time


@needs_cc
@pytest.mark.parametrize("effect, frame", [(PRODUCT, [1, 1]), ({**PRODUCT, "frame": "absolute"}, [0, 1]),
                                           ({**PRODUCT, "column": "T_a"}, [1, 1])],
                         ids=["state-input", "absolute-door", "two-inputs"])
def test_a_diagnosed_product_exports_as_a_derived_input_and_equals_replay(data, tmp_path, effect,
                                                                          frame):
    """The door (a state: raw) times the rise of T_b (a declared input: denoised), each in the
    effect's frame (``absolute``: the door as read, the other's change since the first sample)."""
    ss = _exports_as_replay(data, tmp_path, [effect, LAG])
    a, b = (ss.inputs.index(effect[k]) for k in ("column", "other"))
    assert ss.derived[0] == [a, b, *frame]
    assert ss.taus == [LAG["tau_s"]]


@needs_cc
@pytest.mark.parametrize("effect, frame", [(SQUARE, 1), ({**SQUARE, "frame": "absolute"}, 0),
                                           ({**SQUARE, "column": "S_door", "kind": "signal"}, 1)],
                         ids=["input", "input-absolute", "state"])
def test_a_diagnosed_square_exports_as_a_derived_input_and_equals_replay(data, tmp_path, effect,
                                                                         frame):
    """T_a's change squared (its absolute value squared with ``frame=absolute``), and a state's,
    beside a product and a lag: each the stream's feature, in the effect's frame."""
    ss = _exports_as_replay(data, tmp_path, [LAG, effect, PRODUCT])
    a = ss.inputs.index(effect["column"])
    assert ss.derived[1] == [a, a, frame, frame]
    assert len(ss.derived) == 3 and ss.taus == [LAG["tau_s"]]


@needs_cc
@pytest.mark.parametrize("effects", [[AMBIENT_LAW, LAG], [LAG, AMBIENT_LAW, SQUARE]],
                         ids=["ambient-first", "ambient-between"])
def test_derived_inputs_beside_the_ambient_law_export_in_its_campaign_factor(data, tmp_path, effects):
    """The inputs' ambient law ``x (A0 - 20)`` with derived inputs, in the effects' order
    (the model's columns): the base's law on ``[x, derived]`` and its ambient law on ``x``."""
    ss = _exports_as_replay(data, tmp_path, effects)
    assert ss.law_ambient == [0, 1] and len(ss.derived) == len(effects) - 1


@needs_cc
@pytest.mark.parametrize("effects", [[PRODUCT, SQUARE], [AMBIENT_LAW]], ids=["derived", "ambient-law"])
def test_a_diagnosed_lag_bank_is_clamped_by_its_gain_as_the_stream_clamps_it(data, tmp_path, effects):
    """The stream forks a held copy for the clamp's bound of a model with a step gain; a
    diagnosed model's is its base's through its features (clampdiag60: the context's derived
    inputs do not move with the inputs' excess, the ambient law scales it by A0 - 20), so the
    code bounds it by that gain too (outright before, as the stream then clamped it)."""
    stream, tests = _diagnosed(data, effects, base=LagBank(n_taus=2))
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
    assert _json_proved(stream, tests) <= TOLERANCE_UM
    ss = state_space(stream)
    assert not ss.clamp_outright and ss.taus and np.abs(ss.clamp_gain).max() > 0.0


def test_the_export_command_writes_a_diagnosed_models_code_naming_its_effects(data, tmp_path,
                                                                              capsys):
    """``thermocomp export`` of the model.pkl (refused before): the files, the banner naming the
    derived inputs, the door held missing as the served model holds it."""
    _, _, comp = _diagnosed(data, [LAG, PRODUCT], with_model=True)
    out = tmp_path / "code"
    assert main(["export", f"data.path={data}", f"export.model={save_model(comp, tmp_path / 'm.pkl')}",
                 "export.format=st", f"out={out}", "track=false"]) == 0
    exported = json.loads((out / "compensator.json").read_text())
    assert "S_door" in exported["inputs"] and len(exported["derived"]) == 2
    banner = (out / "compensator.st").read_text().split("*)")[0]
    assert "signal:S_door first_order_lag(tau=600s)" in banner
    assert "interaction:S_door product(T_b)" in banner
    assert "S_door    envelope not clamped  held when missing" in banner
    assert exported["held"] == [int(c == "S_door") for c in exported["inputs"]]
    assert "S_door" not in " ".join(exported["provenance"].get("not_in_code", []))


@needs_cc
def test_a_diagnosed_signal_as_read_exports_as_a_derived_input_and_equals_replay(data, tmp_path):
    """``signal:S_door raw``: the door's change since the first sample, no lag."""
    ss = _exports_as_replay(data, tmp_path, [{"kind": "signal", "transform": "raw", "column": "S_door"}])
    assert ss.derived == [[ss.inputs.index("S_door"), -1, 1, 0]] and not ss.taus


@needs_cc
@pytest.mark.parametrize("effects", [[LOWPASS], [LOWPASS, AMBIENT_LAW, PRODUCT,
                                                 {**LOWPASS, "tau_s": 3000.0}]],
                         ids=["alone", "among-others"])
def test_a_diagnosed_low_pass_of_the_inputs_exports_as_their_lag_bank_channels(data, tmp_path,
                                                                               effects):
    """``dynamics:- first_order_lag(tau) of the model inputs``: one lag channel per input (the
    clamped inputs' as the stream's model reads them: both channels of the code)."""
    ss = _exports_as_replay(data, tmp_path, effects)
    taus = [e["tau_s"] for e in effects if e is LOWPASS or e.get("transform") == "lowpass_inputs"]
    assert sorted(set(ss.taus)) == sorted(taus) and len(ss.taus) == 3 * len(taus)


def test_what_still_does_not_export_is_refused_naming_it_and_what_does(data):
    """A diagnosed model whose base is no family the code holds (exportati60 exports the ambient
    law around an ATI model's interaction, ``x (A0 - 20)^2``, the last effect this refused;
    exportati63 arx_rf, its forest beside the laws; exportlstm64 an lstm with any of these
    effects, test_export_diaglstm64): a family the export does not know (a lab's own MLR),
    refused naming the linear families that export."""
    for effects in ([LAG, AMBIENT_LAW, SQUARE], [SQUARE]):
        stream, _ = _diagnosed(data, effects, base=OwnMLR())
        with pytest.raises(NotExportable, match="OwnMLR is not one of the linear families") as info:
            state_space(stream)
        assert "mlr, pcr, arx, lagbank, hammerstein" in str(info.value)
        assert "thermocomp serve" in str(info.value)
