"""Config resolvers of the shell (OmegaConf): ``${sim_dataset:}``, the folder of a scenario's
dataset.  Registered by :mod:`thermocomp.shell.cli` (``${root:}`` is registered there too), so the
layers below the shell never import OmegaConf."""

from __future__ import annotations

import functools
import hashlib
import json
from pathlib import Path

from omegaconf import OmegaConf

from ..base.paths import conf_dir


@functools.lru_cache(maxsize=32)
def _written_generator(path: str, mtime_ns: int) -> dict | None:
    """``generator`` of a scenario file as written (``@package _global_`` or not), read once."""
    written = OmegaConf.load(path)
    written = written.get("sim", written).get("generator")
    return None if written is None else OmegaConf.to_container(written, resolve=False)


def scenario_dataset(_root_) -> str:
    """The folder name of the scenario's dataset (``${sim_dataset:}`` in ``data.path``): the
    scenario's name when its generator is as ``conf/sim/<name>.yaml`` says, else the name and
    a digest of the generator, so that a changed generator never replaces the default dataset
    (the one ``make run`` and the champion were made from) and the commands given the same
    overrides read what ``simulate`` wrote."""
    sim = _root_.get("sim")
    if sim is None or sim.get("name") is None:
        return "dataset"
    name = str(sim.name)
    if sim.get("generator") is None:
        return name
    generator = OmegaConf.to_container(sim.generator, resolve=False)
    scenario = _scenario_file(_root_, name)
    if scenario is None:              # composed from nowhere we can read: nothing to compare
        return name
    written = _written_generator(str(scenario), scenario.stat().st_mtime_ns)
    if written is None or written == generator:
        return name
    digest = hashlib.sha256(json.dumps(generator, sort_keys=True, default=str).encode()).hexdigest()
    return f"{name}-{digest[:8]}"


def _scenario_file(root, name: str) -> Path | None:
    """``sim/<name>.yaml`` where Hydra finds it: this repository's ``conf/`` first, then the
    ``file://`` folders of ``hydra.searchpath``.  A user's own scenario (under a search path)
    was never compared, so ``sim.generator.sample_period_s=60`` replaced its dataset, which
    cli.md says a changed generator never does."""
    shipped = conf_dir() / "sim" / f"{name}.yaml"
    if shipped.is_file():
        return shipped
    for entry in _searchpath(root):
        if entry.startswith("file://"):
            candidate = Path(entry[len("file://"):]) / "sim" / f"{name}.yaml"
            if candidate.is_file():
                return candidate
    return None


def _searchpath(root) -> list[str]:
    """``hydra.searchpath`` of the composed config, else of the running Hydra job."""
    hydra = root.get("hydra") if hasattr(root, "get") else None
    if hydra is not None and hydra.get("searchpath") is not None:
        return [str(e) for e in hydra.searchpath]
    from hydra.core.hydra_config import HydraConfig

    if HydraConfig.initialized():
        return [str(e) for e in HydraConfig.get().searchpath]
    return []
