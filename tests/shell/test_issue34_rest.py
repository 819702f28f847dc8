"""Issue 34's smaller leftovers: a stdin stream that continues a campaign, the standalone
ingest's resolved reference, a lead-in with a missing value, fleet's per-group ``model=auto``
and ATI's manifest ambient in a stream."""

from __future__ import annotations

import io
import json

import pytest

import test_deployed_as_scored as deployed
from conftest import refused
from test_hostile import FAST
from thermocomp.shell.cli import main

PLAIN = deployed.PLAIN
record = deployed.record    # the fixture: the spindle record cut in two, B continues A


def _monitor(args: list[str], out, stdin: str | None, monkeypatch) -> dict:
    if stdin is not None:
        monkeypatch.setattr("sys.stdin", io.StringIO(stdin))
    assert main(["monitor", f"out={out}", *PLAIN, *FAST, "model=lagbank", *args]) == 0
    return json.loads((out / "monitor.json").read_text())["targets"]


@pytest.fixture(scope="module")
def from_file(record, tmp_path_factory) -> dict:
    """monitor's targets for the test file B streamed from data.path (warmed on A, which it
    continues), made once: the two stdin tests below compare their streams with it."""
    return _monitor([f"data.path={record}"], tmp_path_factory.mktemp("from_file"), None, None)


def test_a_stdin_stream_that_continues_a_campaign_is_warmed_on_it(record, from_file, tmp_path,
                                                                  monkeypatch, capsys):
    # the test file B continues A: streamed from data.path it is warmed on A (as run scores it);
    # the same rows on stdin, said to continue A, must stream alike
    args = [f"data.path={record}"]
    rows = (record / "B.csv").read_text()
    piped = _monitor([*args, "monitor.input=-", "monitor.continues=A"], tmp_path / "piped", rows,
                     monkeypatch)
    assert "stdin continues A" in capsys.readouterr().err
    cold = _monitor([*args, "monitor.input=-"], tmp_path / "cold", rows, monkeypatch)
    for t, r in from_file.items():
        assert piped[t]["rmse_fixed"] == pytest.approx(r["rmse_fixed"], rel=1e-6)
        assert piped[t]["rmse_adaptive"] == pytest.approx(r["rmse_adaptive"], rel=1e-6)
    # a restarted stream is another figure: the warm-up is what made them equal
    assert any(abs(cold[t]["rmse_fixed"] - r["rmse_fixed"]) > 0.01 * r["rmse_fixed"]
               for t, r in from_file.items())


def test_monitor_continues_refuses_an_unknown_campaign_naming_the_known_ones(
        record, tmp_path, monkeypatch, capsys):
    monkeypatch.setattr("sys.stdin", io.StringIO((record / "B.csv").read_text()))
    out = tmp_path / "out"
    refused(["monitor", f"data.path={record}", f"out={out}", *PLAIN, *FAST, "monitor.input=-",
             "monitor.continues=Z"], capsys, "monitor.continues=Z", "campaigns: A, B")
    assert not out.exists()


def test_monitor_continues_without_stdin_or_carried_state_is_refused(record, tmp_path,
                                                                     monkeypatch, capsys):
    out = tmp_path / "out"
    refused(["monitor", f"data.path={record}", f"out={out}", *PLAIN, *FAST,
             "monitor.continues=A"], capsys, "monitor.continues=A", "monitor.input=-")
    monkeypatch.setattr("sys.stdin", io.StringIO((record / "B.csv").read_text()))
    first_sample = [p if not p.startswith("data.reference=") else "data.reference=first_sample"
                    for p in PLAIN]
    refused(["monitor", f"data.path={record}", f"out={out}", *first_sample, *FAST,
             "monitor.input=-", "monitor.continues=A"], capsys,
            "monitor.continues=A", "data.reference=first_sample")
    assert not out.exists()


@pytest.mark.parametrize("given, resolved", [("auto", "none"), ("none", "none"),
                                             ("first_sample", "first_sample")])
def test_ingest_reports_the_resolved_reference_as_run_does(record, tmp_path, given, resolved):
    # B continues A: auto resolves to none; run's ingest_report.json has said so, ingest's not
    args = [f"data.path={record}", PLAIN[1], PLAIN[3], f"data.reference={given}", *FAST]
    assert main(["ingest", *args, f"data.interim={tmp_path / 'interim'}"]) == 0
    assert main(["run", *args, f"out={tmp_path / 'run'}"]) == 0
    ingested = json.loads((tmp_path / "interim" / "ingest_report.json").read_text())
    ran = json.loads((tmp_path / "run" / "ingest_report.json").read_text())
    assert ingested["reference"] == ran["reference"] == resolved


def test_ingest_of_campaigns_that_continue_none_reports_first_sample(paths):
    assert main(["ingest", *paths["args"]]) == 0
    report = json.loads((paths["interim"] / "ingest_report.json").read_text())
    assert report["reference"] == "first_sample"


@pytest.mark.parametrize("adaptive", [False, True], ids=["plain", "adaptive"])
def test_a_lead_in_with_a_missing_value_warms_as_the_stream_holds_it(adaptive):
    # a test campaign continuing another test campaign read as recorded: its lead-in may hold
    # a dropout; warming must pass it over as the stream does there, not refuse the campaign
    import numpy as np
    import pandas as pd

    from test_deploy import _library, campaigns
    from thermocomp.apps.deploy import StreamingCompensator
    from thermocomp.apps.monitor import AdaptiveCompensator
    from thermocomp.apps.monitor.report import stream_campaign as _stream

    camps = campaigns(0)
    train = {c: camps[c] for c in list(camps)[:3]}
    plain = StreamingCompensator.from_training(_library("arx").fit(train), train, policy="off")
    deployed = AdaptiveCompensator.from_training(plain, train) if adaptive else plain
    lead, test = camps["K04"].copy(), camps["K05"]
    sensor = next(c for c in plain.columns_ if c.startswith("T_"))
    lead.loc[[5, 6, len(lead) // 2], sensor] = np.nan
    lead["time"] -= lead["time"].iloc[-1] + (lead["time"].iloc[1] - lead["time"].iloc[0])
    whole = pd.concat([lead, test], ignore_index=True)
    warmed, _, _ = _stream(deployed, test, lead)
    through, _, _ = _stream(deployed, whole)
    np.testing.assert_allclose(warmed, through[len(lead):], rtol=0, atol=1e-12)
    assert np.isfinite(warmed).all()
    cold, _, _ = _stream(deployed, test)     # the warm-up carries state: not a restart
    assert np.max(np.abs(cold - warmed)) > 1e-3


def test_fleet_reports_each_groups_model_auto_choice_as_its_own_run_does(tmp_path):
    import shutil

    import pandas as pd

    from thermocomp.apps.sim.fleet import Fleet

    path = tmp_path / "fleet"
    Fleet(n_machines=2, days=4, test_days=1, n_sensors=6, sample_period_s=300.0, n_jobs=1,
          seed=3).write(path)
    auto = ["model=auto", "model.candidates=[mlr,pcr,lagbank]", "data.reference=first_sample",
            "track=false", "plots=none", "eval.mutual_prediction=false",
            "eval.ati_baselines=false"]
    assert main(["run", f"data.path={path}", "data.group_by=machine", f"out={tmp_path / 'o'}",
                 *auto]) == 0
    metrics = json.loads((tmp_path / "o" / "metrics.json").read_text())
    table = pd.read_csv(tmp_path / "o" / "fleet.csv")
    # one machine alone, as a single run: the same choice and candidates' validation
    alone = tmp_path / "M002"
    shutil.copytree(path / "machine=M002", alone / "machine=M002")
    manifest = pd.read_csv(path / "campaigns.csv")
    manifest[manifest["machine"] == "M002"].to_csv(alone / "campaigns.csv", index=False)
    assert main(["run", f"data.path={alone}", f"out={tmp_path / 'single'}", *auto]) == 0
    single = json.loads((tmp_path / "single" / "metrics.json").read_text())["targets"]
    group = metrics["groups"]["M002"]["targets"]
    for t, m in single.items():
        assert group[t]["auto"]["chosen"] == m["auto"]["chosen"]
        assert group[t]["auto"]["candidates"] == pytest.approx(m["auto"]["candidates"], rel=1e-9)
    for t, s in metrics["fleet"].items():
        rows = table[table["target"] == t]
        assert list(rows["chosen"]) == [metrics["groups"][g]["targets"][t]["auto"]["chosen"]
                                        for g in rows["group"]]
        assert sum(s["chosen"].values()) == s["groups"] == 2


@pytest.fixture(scope="module")
def manifest_ambient_run(tmp_path_factory):
    """An ATI model (``ati=cmeans``) run on a record whose ambient is the manifest's
    ``ambient_c`` (no ``T_amb`` sensor): (dataset, run folder)."""
    from test_ambient_manifest import make_dataset

    root = tmp_path_factory.mktemp("ambient")
    ds = make_dataset(root / "ds")
    assert main(["run", f"data.path={ds}", f"out={root / 'run'}", "ati=cmeans", *FAST]) == 0
    return ds, root / "run"


def test_replay_streams_an_ati_model_on_the_manifest_ambient_as_run_scores_it(
        manifest_ambient_run, tmp_path):
    ds, run = manifest_ambient_run
    out = tmp_path / "replay"
    assert main(["replay", f"data.path={ds}", f"out={out}", "ati=cmeans", *FAST]) == 0
    replay = json.loads((out / "replay.json").read_text())["targets"]
    metrics = json.loads((run / "metrics.json").read_text())["targets"]
    for t, m in metrics.items():
        assert replay[t]["rmse_batch"] == pytest.approx(m["test"]["rmse"], rel=1e-9)
        assert replay[t]["rmse"] == pytest.approx(m["test"]["rmse"], rel=0.01)
        assert replay[t]["max_abs_stream_minus_batch"] < 1e-9


def test_the_served_ati_model_takes_the_campaigns_ambient_as_a_param(manifest_ambient_run):
    import numpy as np
    from mlflow.exceptions import MlflowException

    from thermocomp.apps.deploy import StreamingCompensator
    from thermocomp.apps.deploy.pyfunc import CompensatorModel, correction_column
    from thermocomp.core.io import read_dataset
    from thermocomp.shell.model_store import load_model

    ds_path, run = manifest_ambient_run
    ds, _ = read_dataset(ds_path)
    comp = load_model(run / "model.pkl")
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    served = CompensatorModel(StreamingCompensator.from_training(comp, train, policy="off"))
    for cid in ds.ids("test"):
        df = ds.campaigns[cid]
        batch = comp.predict({cid: df})[cid].to_numpy()
        ambient = float(ds.manifest.loc[cid, "ambient_c"])
        got = served.predict(None, df, params={"session": cid, "ambient_c": ambient})
        np.testing.assert_allclose(-got[[correction_column(t) for t in comp.targets_]].to_numpy(),
                                   batch, atol=1e-9)
        # the ambient is what ATI reads: another one corrects otherwise
        other = served.predict(None, df, params={"session": cid, "reset": True,
                                                 "ambient_c": ambient + 9})
        assert not np.allclose(other.to_numpy(float), got.to_numpy(float))
    with pytest.raises(MlflowException, match="ambient_c"):
        served.predict(None, ds.campaigns[ds.ids("test")[0]], params={"session": "none"})


def test_monitor_refuses_a_stdin_stream_for_a_model_on_the_manifest_ambient(
        tmp_path, monkeypatch, capsys):
    # stdin has no manifest: its ambient is unknown (the plain stream gave NaN throughout)
    import numpy as np
    import pandas as pd

    from test_ambient_manifest import make_dataset

    ds = make_dataset(tmp_path / "ds")
    for f in ds.glob("R*.csv"):        # a third sensor: the monitor watches 3 at least
        df = pd.read_csv(f)
        df.assign(T_column=0.5 * (df["T_spindle"] + df["T_air"]) + np.sin(df["time"] / 700)
                  ).to_csv(f, index=False)
    monkeypatch.setattr("sys.stdin", io.StringIO((ds / "R03.csv").read_text()))
    out = tmp_path / "out"
    refused(["monitor", f"data.path={ds}", f"out={out}", "ati=cmeans", *FAST, "monitor.input=-"],
            capsys, "monitor.input=-", "ambient_c")
    assert not out.exists()


def test_a_stdin_stream_that_continues_a_campaign_without_its_first_time_streams_alike(
        record, from_file, tmp_path, monkeypatch):
    # the lead-in was moved to end one period before the stream's first time, NaN: every
    # lead-in time was lost, the guard ran it from 0 s and the stream's second row came
    # (lead-in rows x period) before its first (stranger48, session 49)
    args = [f"data.path={record}"]
    lines = (record / "B.csv").read_text().splitlines(keepends=True)
    lines[1] = "," + lines[1].split(",", 1)[1]          # row 1 without its time
    piped = _monitor([*args, "monitor.input=-", "monitor.continues=A"], tmp_path / "piped",
                     "".join(lines), monkeypatch)
    for t, r in from_file.items():
        assert piped[t]["rmse_fixed"] == pytest.approx(r["rmse_fixed"], rel=1e-6)
        assert piped[t]["rmse_adaptive"] == pytest.approx(r["rmse_adaptive"], rel=1e-6)
