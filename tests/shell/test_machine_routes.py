"""The routes to the machine (issue 36, items 3, 4, 6): what `connect`, `twin`, `serve` and
`replay` do with reference measurements, the served campaigns and a run's model.pkl.

- `connect` learns from the twin's reference measurements (`adapt`) as `replay` learns from
  its simulated ones, on a machine that ages after training (the `ageing` effect);
- `twin.json` is there when `connect` ends (the README reads it right after);
- `twin.campaigns` serves some test campaigns (the README's one-campaign demonstration);
- `serve` takes a run's `model.pkl` (the README serves `make run`'s).
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import refused
from test_twin import make_machine
from thermocomp.shell.cli import _compose, main
from twin_bench import FAST
from twin_bench import twin_and_connect as served

SPEED = 25               # samples per second: 40 ms for the client to answer one (lockstep)
AGED = ("K21", "K24")    # the last test campaigns: the machine aged most


@pytest.fixture(scope="module")
def aged(tmp_path_factory) -> Path:
    """The default scenario with the `ageing` effect (the sensitivities grow in the test
    campaigns), the test split cut to its last two campaigns (a short stream)."""
    pytest.importorskip("asyncua")
    data = tmp_path_factory.mktemp("aged") / "data"
    assert main(["simulate", f"data.path={data}", *FAST, "sim.generator.effects=[ageing]"]) == 0
    manifest = pd.read_csv(data / "campaigns.csv")
    keep = (manifest["split"] == "train") | manifest["campaign"].isin(AGED)
    manifest[keep].to_csv(data / "campaigns.csv", index=False)
    return data


def replayed(data: Path, out: Path, *args: str) -> dict:
    assert main(["replay", f"data.path={data}", f"out={out}", *FAST, *args]) == 0
    return json.loads((out / "replay.json").read_text())["targets"]


def twin_and_connect(data: Path, tmp: Path, *connect_args: str) -> tuple[dict, dict]:
    """``(twin.json, connect.json)``, the twin in a thread (test_twin serves it as a process)."""
    return served(data, tmp, (), connect_args, speed=SPEED)


def test_connect_learns_from_the_twins_references_as_replay_does(aged, tmp_path):
    adapt = ("adapt.method=bias",)
    frozen = replayed(aged, tmp_path / "frozen")
    learned = replayed(aged, tmp_path / "learned", *adapt)
    twin, link = twin_and_connect(aged, tmp_path, *adapt)
    for t, r in twin["targets"].items():
        assert r["stale_samples"] <= 0.05 * twin["n_samples"]     # the client kept up
        assert abs(r["rms_compensated"] - learned[t]["rmse"]) <= 0.05 * learned[t]["rmse"], t
        assert r["rms_compensated"] < frozen[t]["rmse"], t
        assert link["adapt"][t]["n_references"] == learned[t]["adapt"]["n_references"] > 0
        assert link["adapt"][t]["bias_um"] == pytest.approx(learned[t]["adapt"]["bias_um"], rel=0.05)
    pooled = {k: np.sqrt(np.mean(np.square(v))) for k, v in (
        ("twin", [r["rms_compensated"] for r in twin["targets"].values()]),
        ("frozen", [r["rmse"] for r in frozen.values()]))}
    assert pooled["twin"] <= 0.7 * pooled["frozen"]       # issue 36: >= 30 % after a change of law
    assert twin["references"] == link["adapt"]["E_X"]["n_references"]


def test_twin_campaigns_chooses_among_the_test_campaigns(tmp_path, capsys):
    from thermocomp.apps.machine.record import served_campaigns

    tests = ["K03", "K06", "K09"]
    assert served_campaigns(None, tests) == tests
    assert served_campaigns(["K09", "K03"], tests) == ["K03", "K09"]      # the split's order
    data = make_machine(tmp_path / "data")
    out = tmp_path / "t"
    refused(["twin", f"data.path={data}", f"out={out}", *FAST, "twin.campaigns=[K01]"], capsys,
            "twin.campaigns=['K01']", "K01 not a test campaign", "K04, K05")
    refused(["twin", f"data.path={data}", f"out={out}", *FAST, "twin.campaigns=[K04,K04]"],
            capsys, "twin.campaigns")
    assert not out.exists()


def test_serve_takes_a_run_model_pkl_deployed_as_replay_streams_it(tmp_path):
    """The served folder is the compensator `replay` streams from the same model.pkl."""
    import mlflow

    from thermocomp.shell.stages.serve import serve_command

    data = make_machine(tmp_path / "data")
    pkl = tmp_path / "run" / "model.pkl"
    assert main(["run", f"data.path={data}", f"out={pkl.parent}", f"model_path={pkl}", *FAST,
                 "eval.validation=false", "eval.mutual_prediction=false"]) == 0
    replay = replayed(data, tmp_path / "replay", f"replay.model={pkl}")["E_X"]
    uri = f"sqlite:///{tmp_path / 'store' / 'mlflow.db'}"
    _, env = serve_command(_compose([f"data.path={data}", f"serve.model={pkl}", f"tracking_uri={uri}"]))
    served = Path(env["__pyfunc_model_path__"].removeprefix("file://"))
    try:
        model = mlflow.pyfunc.load_model(str(served))
        residuals = []
        for cid in ("K04", "K05"):
            df = pd.read_csv(data / f"{cid}.csv")
            out = model.predict(df.drop(columns="E_X"), params={"session": "m", "reset": True})
            residuals.append((df["E_X"] - df["E_X"].iloc[0]) + out["C_X"])
        rmse = float(np.sqrt(np.mean(np.square(np.concatenate(residuals)))))
    finally:
        shutil.rmtree(served.parent, ignore_errors=True)
    assert rmse == pytest.approx(replay["rmse"], rel=1e-9)

