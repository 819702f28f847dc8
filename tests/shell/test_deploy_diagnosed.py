"""A diagnosed model (accepted effects read raw columns through context) streams like any model."""

import pickle

import pytest

from conftest import FAST, PLAIN_DIAGNOSE, thermocomp
from thermocomp.apps.deploy.streaming import StreamingCompensator, streaming_deviation
from thermocomp.core import io

pytestmark = pytest.mark.slow


def test_diagnosed_model_streams_exactly_as_it_predicts(door_dataset, tmp_path):
    data, out = door_dataset, tmp_path / "out"
    # one target (E_Y: S_door accepted, test_diagnose_cli), no figures, no validation folds: the
    # streaming of the rerun model is what is asserted, not the diagnosis' report
    thermocomp("diagnose", f"data.path={data}", f"out={out}", "diagnose.targets=[E_Y]", *FAST,
               *PLAIN_DIAGNOSE)
    thermocomp("run", f"hydra.searchpath=[file://{out / 'diagnosis' / 'conf'}]", "experiment=diagnosed",
               f"data.path={data}", f"out={out / 'rerun'}", *FAST)
    comp = pickle.loads((out / "rerun" / "model.pkl").read_bytes())
    assert any(getattr(e, "required_context_", None) for e in comp.estimators_.values())
    ds, _ = io.read_dataset(data)
    streaming = StreamingCompensator.from_training(comp, {c: ds.campaigns[c] for c in ds.ids("train")})
    assert "S_door" in streaming.columns_ and streaming.time_required_
    for cid in ds.ids("test")[:2]:
        assert streaming_deviation(streaming, ds.campaigns[cid]) < 1e-9
