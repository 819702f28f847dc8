"""`thermocomp export` refuses a model.pkl that cannot be exported before it derives the model's
deployment (envelope, guard) from the train split: for a causal EMD window that is one EMD per
training sample, minutes on a real record, all for a refusal."""

from __future__ import annotations

import json

from conftest import refused
from test_export import _compose, _make_dataset
from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.shell.builders import build_compensator
from thermocomp.shell.cli import main
from thermocomp.shell.model_store import save_model
from thermocomp.shell.source import read_streamed


def test_a_window_denoised_model_is_refused_before_its_deployment_is_derived(tmp_path, capsys,
                                                                             monkeypatch):
    data = _make_dataset(tmp_path / "data")
    cfg = _compose("model=mlr", "denoise=emd", "denoise.denoiser.causal=window",
                   f"data.path={data}", "track=false")
    ds, train_ids, _, _ = read_streamed(cfg)
    comp = build_compensator(cfg, ds=ds).fit({c: ds.campaigns[c] for c in train_ids})
    pkl = save_model(comp, tmp_path / "model.pkl")

    def derived(*args, **kwargs):
        raise AssertionError("the deployment was derived from the train split before the refusal")

    monkeypatch.setattr(StreamingCompensator, "from_training", derived)
    out = tmp_path / "code"
    refused(["export", f"data.path={data}", f"export.model={pkl}", f"out={out}", "track=false"],
            capsys, f"export.model={pkl}", "(mlr) cannot be exported as c", "causal=fir")
    assert not out.exists()


def test_an_ati_model_of_several_intervals_exports_since_export57(tmp_path):
    # it was refused: "ati=cmeans switches between one model per ambient interval ... not one
    # linear system"; each interval's laws are now picked at a campaign's first sample by its
    # initial ambient (test_export_ati57.py proves the code equal to replay)
    data = _make_dataset(tmp_path / "data")
    cfg = _compose("model=mlr", "ati=cmeans", "ati.estimator.n_intervals=2", f"data.path={data}",
                   "track=false")
    ds, train_ids, _, _ = read_streamed(cfg)
    comp = build_compensator(cfg, ds=ds).fit({c: ds.campaigns[c] for c in train_ids})
    pkl = save_model(comp, tmp_path / "model.pkl")
    out = tmp_path / "code"
    assert main(["export", f"data.path={data}", f"export.model={pkl}", f"out={out}",
                 "track=false", "export.format=json"]) == 0
    exported = json.loads((out / "compensator.json").read_text())
    assert len(exported["law_target"]) == sum(2 if i else 1 for est in comp.estimators_.values()
                                              for i in est.interactions_)
    assert set(exported["law_target"]) == set(range(len(comp.targets_)))


def test_a_model_pkl_that_cannot_be_exported_is_refused_for_that_before_data_path_is_read(
        tmp_path, capsys):
    # matrix61: `export export.model=<an lstm's, arx_rf's or a window-denoised model.pkl>` without
    # data.path said the default data.path was no folder; given the data, it then said the model
    # does not export: the reason that holds whatever the data comes first
    data = _make_dataset(tmp_path / "data")
    cfg = _compose("model=mlr", f"data.path={data}", "track=false")
    ds, train_ids, _, _ = read_streamed(cfg)
    comp = build_compensator(cfg, ds=ds).fit({c: ds.campaigns[c] for c in train_ids})
    pkl = save_model(comp, tmp_path / "model.pkl")
    nowhere = tmp_path / "no-data"
    refused(["export", f"data.path={nowhere}", f"export.model={pkl}", "export.format=onnx",
             f"out={tmp_path / 'code'}", "track=false"],
            capsys, f"export.model={pkl}", "(mlr) cannot be exported as onnx", "export to json, c and st")
    # an exportable one still needs its train split, and says so
    refused(["export", f"data.path={nowhere}", f"export.model={pkl}", "export.format=c",
             f"out={tmp_path / 'code'}", "track=false"], capsys, str(nowhere), "data.path")
