"""A machine builder's own scenario (``conf/sim/<name>.yaml`` under ``hydra.searchpath``), as
docs/simulation.md says one is written: its typos and impossible truths refused with the key,
and its changed generator kept apart from its dataset as a shipped scenario's is.

Each test failed on the code before it (simstr57): a typo was Hydra's ``Error in call to
target ... TypeError``; a target the machine has not was written into the truth; the lag mass's
unknown target did not name its key; an effect the yaml leaves out said only "not in struct";
``sim.generator.sample_period_s=60`` on an own scenario replaced its dataset.
"""

from __future__ import annotations

import pytest

from conftest import refused

SCENARIO = """\
name: mine
generator:
  _target_: thermocomp.apps.sim.column.ColumnMovingSource
  train_hours: 2.0
  test_hours: 1.0
  sample_period_s: 100.0
  q3: false
  effects: [hidden_source]
  effect_params:
    hidden_source: {anchor: left_4, power_W: 500.0, targets: [E_X]}
EXTRA  seed: ${seed}
"""


def own(tmp_path, extra: str = "") -> str:
    """A search path holding ``sim/mine.yaml`` (``extra``: more generator lines)."""
    (tmp_path / "conf" / "sim").mkdir(parents=True)
    (tmp_path / "conf" / "sim" / "mine.yaml").write_text(SCENARIO.replace("EXTRA", extra))
    return f"hydra.searchpath=[file://{tmp_path / 'conf'}]"


def test_a_typo_in_an_own_scenario_names_the_argument_it_meant(tmp_path, capsys):
    path = tmp_path / "data"
    refused(["simulate", own(tmp_path, "  sample_perod_s: 60.0\n"), "sim=mine",
             f"data.path={path}", "track=false"], capsys,
            "sim.generator.sample_perod_s", "did you mean sim.generator.sample_period_s?")
    assert not path.exists()


def test_an_effect_on_a_target_the_machine_has_not_is_refused(tmp_path, capsys):
    # the truth names the targets a diagnosis must find the effect on: E_Q is none of the data's
    path = tmp_path / "data"
    refused(["simulate", own(tmp_path), "sim=mine", "sim.generator.effect_params.hidden_source."
             "targets=[E_Q]", f"data.path={path}", "track=false"], capsys,
            "sim.generator.effect_params.hidden_source.targets", "E_Q", "E_X_mid")
    assert not path.exists() and not (tmp_path / "data.truth.json").exists()


def test_a_lag_mass_moving_an_unknown_target_names_its_key(tmp_path, capsys):
    refused(["simulate", "sim=column_moving_source", "sim.generator.train_hours=2",
             "sim.generator.test_hours=1", "sim.generator.effects=[lag_node]",
             "+sim.generator.effect_params.lag_node.sensitivity_um_per_K.E_Q=3",
             f"data.path={tmp_path / 'data'}", "track=false"], capsys,
            "sim.generator.effect_params.lag_node.sensitivity_um_per_K", "E_Q")


def test_an_effect_the_own_yaml_leaves_out_says_how_to_add_it(tmp_path, capsys):
    key = "sim.generator.effect_params.sensor_drift.column"
    refused(["simulate", own(tmp_path), "sim=mine", "sim.generator.effects=[sensor_drift]",
             f"{key}=T_front1", f"data.path={tmp_path / 'data'}", "track=false"], capsys,
            f"'+{key}=...'")


@pytest.mark.parametrize("override", ["sim.generator.sample_period_s=60", "seed=3"])
def test_an_own_scenario_changed_keeps_its_dataset_apart(tmp_path, override):
    # the folder `simulate` writes by default and the other stages read (data/raw/<folder>)
    from thermocomp.shell.config.overrides import compose
    from thermocomp.shell.resolvers import scenario_dataset

    searchpath = own(tmp_path)
    plain = scenario_dataset(compose([searchpath, "sim=mine", "track=false"], "simulate"))
    changed = scenario_dataset(compose([searchpath, "sim=mine", override, "track=false"],
                                       "simulate"))
    assert plain == "mine"
    if override.startswith("seed"):      # the seed is not among the generator's settings
        assert changed == "mine"
    else:
        assert changed.startswith("mine-") and len(changed) == len("mine-") + 8
