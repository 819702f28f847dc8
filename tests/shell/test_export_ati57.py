"""An ATI model of several ambient intervals, with its ambient interaction, exported (export57).

``ati=cmeans`` predicts a campaign by the model of the interval of its initial ambient ``A0``
(the mean of the ambient sensors at its first sample), that model reading ``x`` and ``x (A0 -
20 °C)`` where it takes the interaction.  The export refused it ("switches between one model per
ambient interval ... not one linear system"); on a cut-short ``climate_room`` record the
champion of ``model=auto`` kept it for E_Z, so that record's model could not reach the machine.
Now each interval's model is two laws (its own coefficients, and those of the interaction times
``A0 - 20``, both with its feedback), counted only in a campaign whose ``A0`` falls in the
interval: the code picks them at the campaign's first sample as ``ati.py`` does.  Campaigns
started cold and warm, so both intervals stream; the compiled C, the Structured Text and the
numpy reference equal ``replay`` (one input pushed out of the envelope: the clamp acts).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from test_export import needs_cc
from test_export_auto57 import TOLERANCE_UM, _proved, deployed
from thermocomp.apps.deploy.export import state_space
from thermocomp.core.models.ati import ATIRegressor

# (campaign, split, initial ambient °C): two clusters of four train levels, a test in each
CAMPAIGNS = (("K01", "train", 14.0), ("K02", "train", 16.0), ("K03", "train", 18.0),
             ("K04", "train", 20.0), ("K05", "train", 27.0), ("K06", "train", 29.0),
             ("K07", "train", 31.0), ("K08", "train", 33.0), ("K09", "test", 15.0),
             ("K10", "test", 32.0))


def write_manifest(root) -> None:
    """``root/campaigns.csv`` of :data:`CAMPAIGNS`, each with its ambient level as ``ambient_c``."""
    pd.DataFrame([(c, f"{c}.csv", s, a0) for c, s, a0 in CAMPAIGNS],
                 columns=["campaign", "file", "split", "ambient_c"]).to_csv(root / "campaigns.csv",
                                                                            index=False)


def _levels(root, rows: int = 50, ambient_column: bool = True):
    """A two-sensor machine whose gain steps down between the cold and the warm levels and falls
    with the level within each (the climate room's law)."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(5761)
    t = np.arange(rows) * 120.0
    for i, (cid, _, a0) in enumerate(CAMPAIGNS):
        a = a0 + (3 + i % 3) * (1 - np.exp(-t / 2000)) + rng.normal(0, 0.03, rows)
        amb = a0 + 0.4 * np.sin(t / 3000 + i) + rng.normal(0, 0.03, rows)
        amb[0] = a0
        gain = (3.0 if a0 < 24 else 1.5) - 0.04 * (a0 - 20)      # a law that steps, and drifts
        ex = gain * (a - a[0]) - 1.5 * (amb - amb[0]) + rng.normal(0, 0.05, rows)
        frame = {"time": t, "T_a": a, "T_amb": amb, "E_X": ex}
        if not ambient_column:
            frame.pop("T_amb")
        pd.DataFrame(frame).to_csv(root / f"{cid}.csv", index=False)
    write_manifest(root)
    return root


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return _levels(tmp_path_factory.mktemp("ati") / "data")


def _deployed(data, *overrides, ati=("ati=cmeans", "ati.estimator.n_intervals=2")):
    return deployed(data, *ati, *overrides, pushed="T_a")


def _ati(est):
    inner = getattr(est, "estimator_", est)
    return [e for e in getattr(inner, "estimators_", {}).values() if isinstance(e, ATIRegressor)] \
        if not isinstance(inner, ATIRegressor) else [inner]


@needs_cc
@pytest.mark.parametrize("model", [
    ("model=mlr",), ("model=mlr", "data.inputs=[T_a]"),
    ("model=lagbank", "model.estimator.n_taus=3", "model.estimator.ar=true"),
    ("model=arx", "model.estimator.ar=true", "model.estimator.delays=[2]"),
], ids=["mlr", "mlr-ambient-not-an-input", "lagbank-ar", "arx-ar"])
def test_an_ati_model_of_two_intervals_with_its_interaction_streams_as_replay(data, tmp_path, model):
    stream, tests, _ = _deployed(data, *model)
    [(_, est, _)] = stream._plan
    assert est.n_intervals_ == 2 and all(est.interactions_)
    ss = state_space(stream)                                  # refused before
    assert len(ss.law_target) == 4 and sum(ss.law_ambient) == 2
    assert ss.law_hi[0] == ss.law_lo[2] == float(est.boundaries_[0])
    assert [ss.inputs[j] for j in ss.ambient_inputs] == ["T_amb"]
    # the code says what it switches on (its provenance named the inner family only)
    edge = f"{float(est.boundaries_[0]):.4g}"
    assert ss.provenance["laws"] == {
        "E_X": f"ati (A0 <= {edge} +interaction | A0 > {edge} +interaction)"}
    a0 = [df["T_amb"].iloc[0] for df in tests]          # one test campaign in each interval
    assert sorted(int(np.searchsorted(est.boundaries_, a, side="left")) for a in a0) == [0, 1]
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM


@needs_cc
def test_auto_blending_an_ati_candidate_exports(data, tmp_path):
    stream, tests, _ = _deployed(
        data, "model=auto", "model.candidates=[mlr,ati]",
        "+model.estimator.chosen={E_X:{mlr:0.4,ati:0.6}}", ati=())
    [(_, est, _)] = stream._plan
    [ati] = _ati(est)
    assert ati.n_intervals_ >= 2 and all(ati.interactions_)     # the elbow's choice here
    ss = state_space(stream)
    assert len(ss.law_target) == 1 + 2 * ati.n_intervals_       # mlr's, each interval's two
    law = ss.provenance["laws"]["E_X"]
    assert law.startswith("blend mlr 0.4 + ati (A0 <= ") and law.endswith(" +interaction) 0.6")
    assert law.count("+interaction") == ati.n_intervals_
    assert _proved(stream, tests, tmp_path) <= TOLERANCE_UM
