"""`thermocomp simulate`: a dataset from the digital twin (conf/sim/<scenario>)."""

from __future__ import annotations

import time
from pathlib import Path

from omegaconf import DictConfig

from ...apps.sim.scenario import write_scenario
from ...base.errors import ConfigError
from ...base.files import write_json
from ...base.log import logger, say
from ...base.paths import resolve
from ..build import build
from ..config.checks import _check_writable
from ..resolvers import scenario_dataset
from ..tracking import stage_run


def simulate(cfg: DictConfig) -> dict:
    """Write a dataset from the digital twin to ``data.path`` and its truth next to it."""
    t0 = time.perf_counter()
    generator = build(cfg.sim.generator, "sim.generator")
    say(f"simulating {cfg.sim.name} ...")
    path = resolve(cfg.data.path)
    _check_writable("data.path", cfg.data.path, folder=True)
    if path.is_dir() and any(path.iterdir()) and not (path / "campaigns.csv").is_file():
        # the dataset replaces data.path whole: never a folder of something else
        raise ConfigError(f"data.path={cfg.data.path}: not empty and holds no dataset "
                          "(campaigns.csv); simulate replaces it whole: give a new or empty folder")
    if (path / "campaigns.csv").is_file() and not Path(f"{path}.truth.json").is_file():
        # nor a dataset it did not write: an outside probe's measured one was replaced silently
        raise ConfigError(f"data.path={cfg.data.path}: holds a dataset simulate did not write (no "
                          f"{path.name}.truth.json next to it: measured data?); simulate replaces "
                          "it whole: give a new or empty folder")
    before = _seed_of(Path(f"{path}.truth.json"))
    truth, n_campaigns, rows = write_scenario(generator, path)
    truth_path = write_json(f"{path}.truth.json", truth)
    say(f"wrote {n_campaigns} campaigns, {rows} rows to {path} "
        f"({time.perf_counter() - t0:.1f} s); truth: {truth_path}")
    if before is not None and truth.get("seed") is not None and before != truth["seed"]:
        # the seed is not in the folder's name (it seeds the models too: `run seed=1` reads the
        # scenario's data), so a stage run later without this seed= reads these data all the same
        logger.warning(f"{path} was simulated with seed {before}, now with seed {truth['seed']}: "
                       "every stage reading it gets these data whatever its own seed=; give "
                       "data.path=<new folder> to keep both")
    folder = scenario_dataset(cfg)
    if folder != cfg.sim.name and path.name == folder:     # data.path as conf/data says
        say(f"sim.generator differs from conf/sim/{cfg.sim.name}.yaml: its dataset is kept apart "
            f"from the scenario's ({path.with_name(str(cfg.sim.name))}); the stages given the same "
            f"overrides read it, or data.path={path}")
    with stage_run(cfg, "simulate", default=False) as tr:   # logged only with track=true
        tr.log_metrics({"campaigns": n_campaigns, "rows": rows})
        tr.log_artifact(truth_path)
    return {"path": str(path), "truth": str(truth_path)}


def _seed_of(truth: Path):
    """The ``seed`` recorded in a simulated dataset's truth file (None: none, or unreadable)."""
    import json

    try:
        return json.loads(truth.read_text()).get("seed")
    except (OSError, ValueError, AttributeError):
        return None
