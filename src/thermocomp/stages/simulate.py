"""`thermocomp simulate`: a dataset from the digital twin (conf/sim/<scenario>)."""

from __future__ import annotations

import time

from hydra.utils import instantiate
from omegaconf import DictConfig

from .. import io
from ..files import write_json
from ..paths import resolve
from ..tracking import stage_run
from .common import say


def simulate(cfg: DictConfig) -> dict:
    """Write a dataset from the digital twin to ``data.path`` and its truth next to it."""
    t0 = time.perf_counter()
    generator = instantiate(cfg.sim.generator)
    say(f"simulating {cfg.sim.name} ...")
    path = resolve(cfg.data.path)
    if hasattr(generator, "write"):       # a big scenario (fleet) streams to disk, never whole in memory
        truth = generator.write(path)
        n_campaigns, rows = truth["campaigns"], truth["rows"]
    else:
        ds, truth = generator.generate()
        # a scenario may ask for Parquet files and more files in the folder (volumetric.json)
        io.write_dataset(ds, path, getattr(generator, "file_format", "csv"),
                         generator.dataset_files() if hasattr(generator, "dataset_files") else None)
        n_campaigns, rows = len(ds.campaigns), int(sum(len(df) for df in ds.campaigns.values()))
    truth_path = write_json(f"{path}.truth.json", truth)
    say(f"wrote {n_campaigns} campaigns, {rows} rows to {path} "
        f"({time.perf_counter() - t0:.1f} s); truth: {truth_path}")
    with stage_run(cfg, "simulate", default=False) as tr:   # logged only with track=true
        tr.log_metrics({"campaigns": n_campaigns, "rows": rows})
        tr.log_artifact(truth_path)
    return {"path": str(path), "truth": str(truth_path)}
