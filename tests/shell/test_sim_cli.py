"""`thermocomp simulate sim=<scenario>` with effects by override, then `thermocomp run` on it."""

from __future__ import annotations

import json

import pytest

from conftest import thermocomp

pytestmark = pytest.mark.slow

SMALL = {
    "large_mill_week": ["sim.generator.train_hours=24", "sim.generator.test_hours=12"],
    "swiss_lathe_door": ["sim.generator.calibration_hours=10", "sim.generator.production_hours=5"],
    "column_moving_source": ["sim.generator.train_hours=12", "sim.generator.test_hours=12"],
}


@pytest.mark.parametrize("scenario", list(SMALL))
def test_simulate_with_effects_then_run(scenario, tmp_path):
    path = tmp_path / scenario
    thermocomp("simulate", f"sim={scenario}", f"data.path={path}", "track=false", *SMALL[scenario],
               "sim.generator.effects=[hidden_source,axis_position]",
               "sim.generator.effect_params.hidden_source.power_W=350")
    truth = json.loads(path.with_name(f"{scenario}.truth.json").read_text())
    planted = {e["name"]: e for e in truth["undeclared_effects"]}
    assert {"hidden_source", "axis_position"} <= set(planted)
    assert planted["hidden_source"]["params"]["power_W"] == 350
    assert planted["axis_position"]["kind"] == "interaction"
    header = (path / "campaigns.csv").read_text()
    assert header.startswith("campaign,file,split")
    out = tmp_path / "out"
    thermocomp("run", f"data.path={path}", f"out={out}", f"model_path={out / 'model.pkl'}", "track=false",
               "plots=none")
    metrics = json.loads((out / "metrics.json").read_text())
    assert set(metrics["targets"]) >= {"E_X", "E_Y"}


def test_unknown_effect_is_exit_2(tmp_path):
    proc = thermocomp("simulate", f"data.path={tmp_path / 'x'}", "track=false",
                      "sim.generator.effects=[doors]", check=False)
    assert proc.returncode == 2 and "unknown effect 'doors'" in proc.stderr
    assert not (tmp_path / "x").exists()
