"""An ``arx_rf`` or ``lstm`` within an ATI model, and a diagnosed arx_rf, export (exportati63).

``ati=cmeans`` around ``arx_rf`` or ``lstm`` predicts a campaign by the model of the interval of
its initial ambient ``A0``, that model reading ``x`` and ``x (A0 - 20 °C)`` where it takes the
ambient interaction; ``export`` refused both ("ARXRF is not one of the linear families ...
arx_rf not within an ATI or a diagnosed model"), and ``model=auto``'s blend holding an
``ati+lstm`` or ``ati+arx_rf`` member, and a diagnosed model on arx_rf: a lab that promoted one
could not run it on the machine.  Now each interval's linear part is its laws (as an ATI
interval's ARX or MLR), and its forest or network, emitted as a plain one's, takes the factor
of that interval's law (``forest_law``, ``lstm_law``: 1 in the interval, 0 outside, where it is
neither walked nor stepped); a network with the interaction reads ``[x, x (A0 - 20)]``
standardised (exportlstm64: ``lstm_in``, ``lstm_in_law``, the second half the interaction
law's).  On a record whose train campaigns span two clusters of four ambient levels
(test_export_ati57's, with a door), a test campaign in each interval, the compiled C, the
Structured Text and the numpy reading equal ``replay`` (the clamp acting, the door missing
at a start and mid-run), and ``thermocomp export``'s check pack passes.  (A diagnosed model on
lstm, its network reading the effects' features, refused here, exports since exportlstm64:
test_export_diaglstm64.)
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from sklearn.ensemble import RandomForestRegressor

from conftest import refused
from test_export import _exported_code, _fitted, checked_pack, needs_cc
from test_export_ati57 import CAMPAIGNS, write_manifest
from test_export_auto57 import TOLERANCE_UM, _proved, deployed
from test_export_effects59 import AMBIENT_LAW, LAG, SQUARE, _diagnosed
from thermocomp.apps.deploy.export import state_space
from thermocomp.apps.deploy.export.members import intervals
from thermocomp.core.models import ARXRF
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.core.models.lstm import LSTM

ATI = ("ati=cmeans", "ati.estimator.n_intervals=2")
FOREST = ("model.estimator.forest.n_estimators=4",)
# test_export_lstm62's tiny network, kept whatever its held-out score
NET = ("model.estimator.max_epochs=2", "model.estimator.hidden_size=4", "model.estimator.chunk=16",
       "model.estimator.validation_fraction=0.0")


def _levels_with_a_door(root, rows: int = 40):
    """test_export_ati57's record (a gain that steps between the cold and the warm levels and
    drifts within each) and a door (``S_door``, what arx_rf reads) whose openings cool the axis
    after a lag, each campaign opening it at its own times."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(6301)
    t = np.arange(rows) * 120.0
    for i, (cid, _, a0) in enumerate(CAMPAIGNS):
        a = a0 + (3 + i % 3) * (1 - np.exp(-t / 2000)) + rng.normal(0, 0.03, rows)
        amb = a0 + 0.4 * np.sin(t / 3000 + i) + rng.normal(0, 0.03, rows)
        amb[0] = a0
        door = ((np.arange(rows) + 3 * i) % 12 < 4).astype(float)
        lagged = pd.Series(door).ewm(alpha=0.3).mean().to_numpy()
        gain = (3.0 if a0 < 24 else 1.5) - 0.04 * (a0 - 20)
        ex = gain * (a - a[0]) - 1.5 * (amb - amb[0]) - 2.0 * lagged + rng.normal(0, 0.05, rows)
        pd.DataFrame({"time": t, "T_a": a, "T_amb": amb, "S_door": door, "E_X": ex}).to_csv(
            root / f"{cid}.csv", index=False)
    write_manifest(root)
    return root


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _levels_with_a_door(tmp_path_factory.mktemp("ati63") / "data")


def _with_gaps(tests):
    """The door missing at a campaign's start and mid-run (held, as the served model holds it)."""
    tests = [df.copy() for df in tests]
    tests[0].loc[[0, 1], "S_door"] = float("nan")
    tests[1].loc[[20, 21, 22], "S_door"] = float("nan")
    return tests


def _each_counts_in_its_interval(ss, laws: list, est: ATIRegressor) -> None:
    """Each interval's forest or net takes the factor of its own interval's law (no ambient
    power): one per interval, coldest first."""
    edges = [float(b) for b in est.boundaries_]
    assert [(ss.law_lo[r], ss.law_hi[r], ss.law_ambient[r]) for r in laws] == [
        (ss.law_lo[laws[0]], edges[0], 0), (edges[0], ss.law_hi[laws[1]], 0)]


def _reads_x_and_its_interaction(sources: list, laws: list, ss) -> bool:
    """Whether a net reads ``[x, x (A0 - 20)]``: its inputs twice, the second half times its
    interval's interaction law's ``A0 - 20`` (else ``x`` alone, its own law's factor)."""
    read = [j for j, source in enumerate(sources) if source >= 0]     # (-1: a narrower net's pad)
    sources, n = [sources[j] for j in read], len(read) // 2
    powers = [ss.law_ambient[laws[j]] for j in read]
    twice = len(sources) == 2 * n and sources[:n] == sources[n:]
    return twice and powers == [0] * n + [1] * n and all(0 <= s < len(ss.inputs) for s in sources)


@needs_cc
@pytest.mark.parametrize("family", ["arx_rf", "lstm"])
def test_an_arx_rf_or_lstm_within_an_ati_model_streams_as_replay(data, tmp_path, family):
    stream, tests, _ = deployed(data, f"model={family}", *(FOREST if family == "arx_rf" else NET),
                                *ATI, pushed="T_a")
    [(_, est, _)] = stream._plan
    kind = ARXRF if family == "arx_rf" else LSTM
    assert isinstance(est, ATIRegressor) and all(type(e) is kind for e in est.estimators_)
    assert est.n_intervals_ == 2 and all(est.interactions_)
    ss = state_space(stream)                                  # refused before
    edge = f"{float(est.boundaries_[0]):.4g}"
    assert ss.provenance["laws"] == {
        "E_X": f"ati (A0 <= {edge} +interaction | A0 > {edge} +interaction)"}
    if family == "arx_rf":
        assert ss.forest_target == [0, 0] and len(ss.tree_root) == 8
        _each_counts_in_its_interval(ss, ss.forest_law, est)
    else:
        assert ss.lstm_target == [0, 0] and all(map(_reads_x_and_its_interaction, ss.lstm_in,
                                                     ss.lstm_in_law, [ss] * 2))
        _each_counts_in_its_interval(ss, ss.lstm_law, est)
    assert ss.clamp_outright == [1]          # no step gain: clamped outright, as streamed
    assert _proved(stream, _with_gaps(tests), tmp_path) <= TOLERANCE_UM


@needs_cc
def test_auto_blending_ati_arx_rf_and_ati_lstm_members_exports(data, tmp_path):
    stream, tests, _ = deployed(
        data, "model=auto", "model.candidates=[mlr,ati+arx_rf,ati+lstm]",
        "++model.candidate_params={ati+arx_rf:{forest:{n_estimators:3}},"
        "ati+lstm:{max_epochs:2,hidden_size:4,chunk:16,validation_fraction:0.0}}",
        "+model.estimator.chosen={E_X:{mlr:0.4,ati+arx_rf:0.3,ati+lstm:0.3}}", pushed="T_a")
    [(_, est, _)] = stream._plan
    forests, nets = (est.estimators_[n] for n in ("ati+arx_rf", "ati+lstm"))     # a Blend
    ss = state_space(stream)                                  # refused before
    assert ss.provenance["laws"]["E_X"] == (f"blend mlr 0.4 + ati+arx_rf {intervals(forests)} 0.3"
                                            f" + ati+lstm {intervals(nets)} 0.3")
    # the elbow's intervals, one forest or net each, weighted
    assert ss.forest_weight == [0.3] * forests.n_intervals_ == [0.3] * len(ss.forest_law)
    assert ss.lstm_weight == [0.3] * nets.n_intervals_
    assert [_reads_x_and_its_interaction(*net, ss) for net in zip(ss.lstm_in, ss.lstm_in_law)] \
        == [bool(i) for i in nets.interactions_]
    assert _proved(stream, _with_gaps(tests), tmp_path) <= TOLERANCE_UM


@needs_cc
@pytest.mark.parametrize("family", ["arx_rf", "lstm"])
def test_the_export_commands_check_pack_passes(data, tmp_path, family):
    out = _exported_code(data, tmp_path, "c", family, *(FOREST if family == "arx_rf" else NET), *ATI)
    exported = json.loads((out / "compensator.json").read_text())
    assert len(exported["forest_law" if family == "arx_rf" else "lstm_law"]) == 2
    assert checked_pack(out).count("stream: check passed") == 2


@needs_cc
@pytest.mark.parametrize("effects", [[AMBIENT_LAW], [LAG, AMBIENT_LAW, SQUARE]],
                         ids=["ambient-law", "lag-ambient-law-square"])
def test_a_diagnosed_arx_rf_exports_its_forest_beside_the_effects_laws(data, tmp_path, effects):
    """Its forest reads the door alone; its ARX, fitted on the inputs and the effects' features,
    is a law of the code as a diagnosed ARX's is."""
    base = ARXRF(forest=RandomForestRegressor(n_estimators=4, min_samples_leaf=5, random_state=0))
    stream, tests = _diagnosed(data, effects, base=base)
    ss = state_space(stream)                                  # refused before
    assert ss.forest_target == [0] and ss.law_ambient[ss.forest_law[0]] == 0
    assert max(ss.law_ambient) == 1 and ss.switch_input == [ss.inputs.index("S_door")]
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


# (a diagnosed lstm, refused here, exports since exportlstm64: test_export_diaglstm64.py)


def test_an_lstm_within_an_ati_model_without_its_data_is_not_refused_early(data, tmp_path, capsys):
    """``export`` checks a model before its data (refused_early61): an ATI lstm passes that
    check and is refused for its data path only."""
    pkl = _fitted(data, tmp_path, "lstm", *NET, *ATI)
    nowhere = tmp_path / "no-data"
    refused(["export", f"data.path={nowhere}", f"export.model={pkl}", f"out={tmp_path / 'code'}",
             "track=false"], capsys, str(nowhere), "data.path")
