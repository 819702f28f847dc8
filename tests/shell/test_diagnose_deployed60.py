"""diagnose's "after" is the deployed model's test error (diagafter60).

The deployed stream (promote, replay, the exported code) holds an input that leaves the
training envelope off its training pattern to the envelope; ``run`` scores in batch, without
it.  A lag bank on a planted ambient law was diagnosed at 0.66 µm and deployed at 0.688
(one test row clamped).  Here one test campaign's last rows take one sensor far out.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from conftest import LIGHT, SHORT, thermocomp

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def excursion(tmp_path_factory):
    """A short dataset whose first test campaign ends with one sensor 30 K above its start."""
    data = tmp_path_factory.mktemp("diagafter") / "excursion"
    thermocomp("simulate", f"data.path={data}", "track=false", *SHORT)
    manifest = pd.read_csv(data / "campaigns.csv")
    first_test = manifest.loc[manifest.split == "test", "file"].iloc[0]
    df = pd.read_csv(data / first_test)
    sensor = next(c for c in df if c.startswith("T_") and "amb" not in c)
    df.loc[df.index[-3:], sensor] += 30.0        # off the pattern: the other sensors stay put
    df.to_csv(data / first_test, index=False)
    return data


def deployed_rmse(model_pkl, data, target: str) -> float:
    """The test RMSE of the run's model streamed as promote deploys it (conf/promote defaults)."""
    from thermocomp.apps.deploy.streaming import StreamingCompensator, replay
    from thermocomp.core.io.read import read_dataset
    from thermocomp.core.scoring.evaluation import require_split
    from thermocomp.shell.model_store import load_model

    ds, _ = read_dataset(data)
    comp = load_model(model_pkl)
    train = {c: ds.campaigns[c] for c in require_split(ds, "train")}
    stream = StreamingCompensator.from_training(comp, train, 0.1, "clamp", True)
    test = {c: ds.campaigns[c] for c in require_split(ds, "test")}
    measured = comp.measured(test)
    r = np.concatenate([measured[c][target].to_numpy() - replay(stream, df)[target].to_numpy()
                        for c, df in test.items()])
    return float(np.sqrt(np.nanmean(r ** 2)))


def _model_config(out) -> list[str]:
    """The diagnosed model's config files, but their comment naming the folder to rerun from."""
    return [line for f in sorted((out / "diagnosis" / "conf").rglob("*.yaml"))
            for line in f.read_text().splitlines() if not line.startswith("# Rerun:")]


@pytest.fixture(scope="module")
def diagnosed(excursion, tmp_path_factory):
    """The default diagnosis of E_Y and the run of the model it wrote (its rerun): ``(after,
    diagnosis out, rerun out)``.  Read by both tests of "after": the plain stream's diagnosis
    writes the same model (asserted there), so one rerun serves them (0.41-0.56 s of CPU each,
    process_time of 3 reruns warm)."""
    root = tmp_path_factory.mktemp("diagnosed")
    out, rerun = root / "diag", root / "rerun"
    thermocomp("diagnose", f"data.path={excursion}", f"out={out}", "track=false", "plots=none",
               "diagnose.targets=[E_Y]")
    after = json.loads((out / "diagnosis.json").read_text())["after"]["test_rmse"]
    thermocomp("run", f"hydra.searchpath=[file://{out / 'diagnosis' / 'conf'}]",
               "experiment=diagnosed", f"data.path={excursion}", f"out={rerun}", "track=false",
               *LIGHT)
    return after, out, rerun


def test_after_is_the_deployed_error_and_the_rerun_is_after_as_run(excursion, diagnosed, tmp_path):
    # the plain stream deployed (monitor.adaptive=false): the clamp alone parts it from batch
    out = tmp_path / "diag"
    proc = thermocomp("diagnose", f"data.path={excursion}", f"out={out}", "track=false",
                      "plots=none", "diagnose.targets=[E_Y]", "monitor.adaptive=false")
    j = json.loads((out / "diagnosis.json").read_text())
    # the stream scores "after", it does not choose the model: the default diagnosis's model,
    # whose rerun is the rerun of this one
    _, default_out, rerun = diagnosed
    assert _model_config(out) == _model_config(default_out) != []
    metrics = json.loads((rerun / "metrics.json").read_text())
    deployed = deployed_rmse(rerun / "model.pkl", excursion, "E_Y")
    batch = metrics["targets"]["E_Y"]["test"]["rmse"]
    assert abs(deployed - batch) > 1e-6 * batch       # the excursion is clamped when deployed
    assert j["after"]["test_rmse"] == pytest.approx(deployed, rel=1e-9)
    assert j["after"]["test_rmse_as_run"] == pytest.approx(batch, rel=1e-9)
    assert j["test_scored"] == "deployed" and j["after"]["test_rows_clamped"] >= 1
    assert "clamped to the training" in proc.stdout
    assert "clamped to the training" in (out / "diagnosis" / "report.md").read_text()


def test_after_is_what_promote_deploys_the_adaptive_compensator_by_default(excursion, diagnosed,
                                                                             tmp_path):
    # matrix61: diagnose streamed the plain stream whatever monitor.adaptive said, and promote
    # registers (and replay streams) the adaptive compensator by default: where its monitor or
    # guard acts on the test (here the +30 K reading, excluded), "after" was not the promoted
    # version's "as deployed" figure (a column meeting a source training never saw: 5.46 µm
    # after, 6.20 promoted)
    after, _, rerun = diagnosed
    thermocomp("replay", f"data.path={excursion}", f"replay.model={rerun / 'model.pkl'}",
               f"out={tmp_path / 'replay'}", "track=false")
    replayed = json.loads((tmp_path / "replay" / "replay.json").read_text())
    assert replayed["adaptive"] and replayed["events"]        # the monitor acted on the test
    assert after == pytest.approx(replayed["targets"]["E_Y"]["rmse"], rel=1e-9)
    assert abs(after - deployed_rmse(rerun / "model.pkl", excursion, "E_Y")) > 1e-6 * after


def test_before_is_promotes_figure_of_a_model_that_learns_from_references(excursion, tmp_path):
    # diag76: diagnose streamed the model as promote registers it but scored it frozen, where
    # promote and replay adapt it to the reference measurements (adapt.method): one
    # computation now, promote's own (stream_scores)
    learns = ["adapt.method=bias", "adapt.every_s=600"]
    out = tmp_path / "diag"
    thermocomp("diagnose", f"data.path={excursion}", f"out={out}", "track=false", "plots=none",
               "diagnose.targets=[E_Y]", "diagnose.max_effects=1", *learns)
    before = json.loads((out / "diagnosis.json").read_text())["before"]["test_rmse"]
    run = tmp_path / "run"
    thermocomp("run", f"data.path={excursion}", f"out={run}", "track=false", *LIGHT)
    replayed = {}
    for name, args in (("learns", learns), ("frozen", [])):
        thermocomp("replay", f"data.path={excursion}", f"replay.model={run / 'model.pkl'}",
                   f"out={tmp_path / name}", "track=false", *args)
        replayed[name] = json.loads((tmp_path / name / "replay.json").read_text())["targets"]["E_Y"]["rmse"]
    assert abs(replayed["learns"] - replayed["frozen"]) > 1e-6 * replayed["frozen"]
    assert before == pytest.approx(replayed["learns"], rel=1e-9)
