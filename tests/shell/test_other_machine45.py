"""A machine that is not ours, run as a stranger would (issue 34; benchmarks/bench_other_machine.py):
a lab's folder of run files without a manifest through `init` and `run`, a model config naming a
column this machine has not, BLAS threads on a shared machine."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import yaml

from conftest import FAST, refused, thermocomp
from test_hostile import make_dataset


def runs_folder(root: Path) -> Path:
    """make_dataset's four campaigns as a lab leaves them: ``run_1.csv`` .. ``run_4.csv``, no
    manifest."""
    ds = make_dataset(root)
    (ds / "campaigns.csv").unlink()
    for k, cid in enumerate(("K01", "K02", "K03", "K04")):
        (ds / f"{cid}.csv").rename(ds / f"run_{k + 1}.csv")
    return ds


def test_init_on_a_folder_of_runs_writes_a_config_that_run_takes(tmp_path):
    ds = runs_folder(tmp_path / "lab")
    proc = thermocomp("init", str(ds), f"out={tmp_path / 'init'}")
    config = tmp_path / "init" / "conf" / "data" / "lab.yaml"
    assert yaml.safe_load(config.read_text())["test_fraction"] == 0.1
    assert "campaign run_4: test" in proc.stdout        # the last run held out, said
    thermocomp("run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=lab", *FAST,
               f"out={tmp_path / 'out'}")
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert list(metrics["targets"]["E_X"]["test"]["per_campaign"]) == ["run_4"]


def test_no_test_split_without_a_manifest_names_the_fraction_not_a_missing_file(tmp_path, capsys):
    ds = runs_folder(tmp_path / "lab")
    line = refused(["run", f"data.path={ds}", *FAST, f"out={tmp_path / 'out'}"], capsys,
                   "data.test_fraction")
    assert "campaigns.csv" not in line, line            # there is none to set a split in
    assert not (tmp_path / "out").exists()


def test_a_state_column_the_machine_has_not_is_refused_naming_the_key(tmp_path, capsys):
    ds = make_dataset(tmp_path / "ds")      # no S_ column: ARX+RF's default S_door is not there
    refused(["run", f"data.path={ds}", "model=arx_rf", *FAST, f"out={tmp_path / 'out'}"], capsys,
            "model.estimator.state_column='S_door'", "null")
    assert not (tmp_path / "out").exists()


def _blas_threads(env: dict) -> set[int]:
    code = ("import thermocomp.shell.cli, numpy, scipy.linalg; from threadpoolctl import "
            "threadpool_info; print(sorted({i['num_threads'] for i in threadpool_info() "
            "if i['internal_api'] == 'openblas'}))")
    keep = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")}
    out = subprocess.run([sys.executable, "-c", code], env={**keep, **env}, capture_output=True,
                         text=True, check=True).stdout
    return set(json.loads(out))


def test_a_command_runs_blas_on_one_thread_unless_the_user_says_otherwise():
    # a second OpenBLAS thread on matrices tens of columns wide made an MLR run on 43 lathe
    # runs cost 7.6 s of CPU instead of 2.8 s on a shared 2-core machine
    assert _blas_threads({}) == {1}
    assert _blas_threads({"OPENBLAS_NUM_THREADS": "2"}) == {2}


def test_runs_named_otherwise_than_in_time_are_held_out_by_their_timestamps(tmp_path):
    # a lab names its runs by operator; their files' ISO times say which came last
    ds = runs_folder(tmp_path / "lab")
    names = {"run_1": "mueller", "run_2": "abel", "run_3": "zander", "run_4": "klein"}
    for day, (run, name) in enumerate(names.items()):
        frame = pd.read_csv(ds / f"{run}.csv")
        stamps = pd.Timestamp("2026-03-02 07:00") + pd.to_timedelta(day, unit="D") \
            + pd.to_timedelta(frame["time"], unit="s")
        frame.assign(time=stamps.dt.strftime("%Y-%m-%dT%H:%M:%S")).to_csv(ds / f"{name}.csv",
                                                                          index=False)
        (ds / f"{run}.csv").unlink()
    thermocomp("run", f"data.path={ds}", "data.test_fraction=0.25", *FAST, f"out={tmp_path / 'out'}")
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert list(metrics["targets"]["E_X"]["test"]["per_campaign"]) == ["klein"]   # not zander
    report = json.loads((tmp_path / "out" / "ingest_report.json").read_text())
    assert report["campaigns"]["klein"]["split"] == "test"
    assert report["campaigns"]["zander"]["split"] == "train"


def test_a_stream_refused_for_want_of_the_ambient_says_so_at_every_row(tmp_path):
    # a climate-room model whose ambient is the manifest's ambient_c (no air sensor): served
    # without `ambient_c`, the first row was refused clearly but left the stream half started,
    # and every later row was a KeyError naming the target (MLflow's input-example check: 'E_X')
    from test_ambient_manifest import make_dataset as climate_room
    from thermocomp.apps.deploy.streaming import OutOfEnvelopeError, StreamingCompensator
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.io import read_dataset
    from thermocomp.core.models.ati import ATIRegressor
    from thermocomp.core.models.linear import MLR

    ds, _ = read_dataset(climate_room(tmp_path / "ds"))
    comp = Compensator(ATIRegressor(MLR(), n_intervals=2), inputs=["T_spindle"]).fit(
        {c: ds.campaigns[c] for c in ds.ids("train")})
    stream = StreamingCompensator(comp)
    assert stream.ambient_given_
    row = ds.campaigns[ds.ids("test")[0]][["time", *stream.columns_]]
    stream.reset()                                     # no ambient_c given
    for k in range(2):
        try:
            stream.step(row[stream.columns_].iloc[k].to_numpy(), row["time"].iloc[k])
        except OutOfEnvelopeError as exc:
            assert "ambient_c" in str(exc), exc
        else:
            raise AssertionError(f"row {k} streamed without the campaign's ambient")
    stream.reset(float(ds.manifest.loc[ds.ids("test")[0], "ambient_c"]))   # given: it runs
    assert np.isfinite(stream.step(row[stream.columns_].iloc[0].to_numpy(), 0.0)).all()


def test_the_ati_elbow_cross_validates_one_model_once(tmp_path, monkeypatch):
    # on 39 climate-room runs the elbow's leave-one-campaign-out fits were most of an ATI fit
    # (35 s; in `auto` 173 s): the one-model figures are the count 1's, not a second round
    from test_ambient_manifest import make_dataset as climate_room
    from thermocomp.core.compensator import Compensator
    from thermocomp.core.io import read_dataset
    from thermocomp.core.models import ati
    from thermocomp.core.models.linear import MLR

    ds, _ = read_dataset(climate_room(tmp_path / "ds"))
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    fits = []
    fit = MLR.fit
    monkeypatch.setattr(MLR, "fit", lambda self, *a, **k: fits.append(1) or fit(self, *a, **k))
    # every fold through the base's fit (an MLR base's folds otherwise come from per-campaign QR
    # factors, no fit call: tests/core/test_campaign_ls59.py)
    monkeypatch.setattr(ati.ATIRegressor, "_fast_elbow", False)
    model = Compensator(ati.ATIRegressor(MLR(), candidates=[1, 2]), inputs=["T_spindle"]).fit(train)
    elbow = model.estimators_["E_X"].elbow_
    assert elbow["single_model"] == {"sm": elbow["sm"][0], "sd": elbow["sd"][0]}
    # one leave-one-out round per count, then the chosen intervals' fits
    assert len(fits) == 2 * len(train) + model.estimators_["E_X"].n_intervals_


def test_an_accepted_effect_of_all_inputs_is_named_not_none():
    # the vendor's runs: E_X accepted a lag of the model inputs, listed in diagnosis.json's
    # other_targets as 'dynamics:None'; the stage's table, steps and other_targets share one name
    from thermocomp.apps.diagnose.features import Effect

    lag = Effect(kind="dynamics", transform="lowpass_inputs", tau_s=900.0)
    assert lag.title == "dynamics:- first_order_lag(tau=900s) of the model inputs"
    door = Effect(kind="signal", transform="first_order_lag", column="S_door", tau_s=3600.0)
    assert door.title == "signal:S_door first_order_lag(tau=3600s)"


def test_a_labs_headers_without_roles_point_to_init(tmp_path, capsys):
    # `run` straight on a lab's folder: 28 headers with units and no role; init proposes them all
    ds = runs_folder(tmp_path / "lab")
    for k in range(1, 5):
        frame = pd.read_csv(ds / f"run_{k}.csv")
        frame.rename(columns={"time": "Zeit [s]", "T_0": "Pt01 [°C]", "T_amb": "Raum [°C]",
                              "E_X": "dX [µm]"}).to_csv(ds / f"run_{k}.csv", index=False)
    refused(["run", f"data.path={ds}", "data.test_fraction=0.25", *FAST, f"out={tmp_path / 'o'}"],
            capsys, "not read", "thermocomp init")
    thermocomp("init", str(ds), f"out={tmp_path / 'init'}")          # and it does


def test_the_exported_code_says_the_labs_name_of_each_input(tmp_path):
    # the code reads contract names (T_Pt01); the lab's logger calls the signal 'Pt01 [°C]'
    ds = runs_folder(tmp_path / "lab")
    for k in range(1, 5):
        frame = pd.read_csv(ds / f"run_{k}.csv")
        frame.rename(columns={"time": "Zeit [s]", "T_0": "Pt01 [°C]", "T_amb": "Raum [°C]",
                              "E_X": "dX [µm]"}).to_csv(ds / f"run_{k}.csv", index=False)
    thermocomp("init", str(ds), f"out={tmp_path / 'init'}")
    data = (f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=lab")
    thermocomp("run", *data, *FAST, f"out={tmp_path / 'run'}")
    thermocomp("export", *data, f"export.model={tmp_path / 'run' / 'model.pkl'}", "export.format=c",
               "track=false", f"out={tmp_path / 'code'}")
    exported = json.loads((tmp_path / "code" / "compensator.json").read_text())
    # (and of the time and the error: the code reads either name, session 52)
    assert exported["provenance"]["lab_names"] == {"T_Pt01": "Pt01 [°C]", "T_amb": "Raum [°C]",
                                                   "time": "Zeit [s]", "E_dX": "dX [µm]"}
    header = (tmp_path / "code" / "compensator.h").read_text()
    assert "T_Pt01* degC" in header and "(the lab's 'Pt01 [\\xb0C]')" in header
    assert header.isascii()
