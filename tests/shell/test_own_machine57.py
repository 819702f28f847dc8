"""A machine builder's own scenario class (docs/simulation.md, "Your own machine"): a machine
whose sensor sits on no node of its network is refused, exit 2 naming the class and the sensor,
not a ``ValueError`` traceback with exit 1 (simstr57; fails on the code before it)."""

from __future__ import annotations

from conftest import refused
from thermocomp.apps.sim.ambient import SinusoidalAmbient
from thermocomp.apps.sim.campaign import Machine
from thermocomp.apps.sim.network import Link, Node, ThermalNetwork
from thermocomp.apps.sim.scenario import CampaignPlan, Scenario
from thermocomp.apps.sim.sensors import AMBIENT, TemperatureSensor
from thermocomp.apps.sim.thermoelastic import ThermoelasticMap


class MisplacedSensor(Scenario):
    """Two nodes; ``T_bed`` on ``bedd``, a node the network has not."""

    name = "misplaced"

    def __init__(self, effects=(), effect_params=None, clean=False, seed=0):
        super().__init__(0.02, 0.01, 0.2, 0.1, effects, effect_params, clean, seed)

    def machine(self):
        network = ThermalNetwork([Node("bed", 8e5, 12.0), Node("head", 1e5, 3.0)],
                                 [Link("bed", "head", 5.0)])
        sensors = [TemperatureSensor("T_bed", {"bedd": 1.0}, 0.0),
                   TemperatureSensor("T_amb", {AMBIENT: 1.0}, 0.0)]
        return Machine(network, [], sensors, ThermoelasticMap({"E_Z": {"head": 5.0}}))

    def plans(self, rng):
        return [CampaignPlan(cid=f"G{k}", split=split, start_s=86400.0 * (k + 1),
                             duration_s=3600.0, rng=rng.spawn(1)[0],
                             ambient=SinusoidalAmbient(20.0, 1.0), sample_period_s=60.0)
                for k, split in enumerate(("train", "test"))]


def test_an_own_machine_with_a_sensor_on_no_node_is_refused(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("THERMOCOMP_TARGETS", f"{__name__}.")
    (tmp_path / "conf" / "sim").mkdir(parents=True)
    (tmp_path / "conf" / "sim" / "misplaced.yaml").write_text(
        f"name: misplaced\ngenerator:\n  _target_: {__name__}.MisplacedSensor\n  seed: ${{seed}}\n")
    path = tmp_path / "data"
    refused(["simulate", f"hydra.searchpath=[file://{tmp_path / 'conf'}]", "sim=misplaced",
             f"data.path={path}", "track=false"], capsys,
            f"sim.generator._target_={__name__}.MisplacedSensor", "'T_bed'", "'bedd'")
    assert not path.exists()
