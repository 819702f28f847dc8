"""The project root, from which every relative path in the config is resolved.

Hydra runs with ``version_base="1.3"`` and no working-directory change, but a
user may still call ``thermocomp`` from anywhere: paths are built from the
project root (``THERMOCOMP_ROOT``, else the checkout this package lives in,
else the current directory), never from the current directory by accident.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
from pathlib import Path

from omegaconf import OmegaConf


def project_root() -> Path:
    env = os.environ.get("THERMOCOMP_ROOT")
    if env:
        return Path(env).resolve()
    checkout = Path(__file__).resolve().parents[2]
    if (checkout / "conf" / "config.yaml").is_file():
        return checkout
    return Path.cwd()


def resolve(path: str | os.PathLike) -> Path:
    """``path`` if absolute, else relative to the project root."""
    p = Path(os.path.expanduser(str(path)))
    return p if p.is_absolute() else project_root() / p


def conf_dir() -> Path:
    return project_root() / "conf"


def rooted_override(arg: str) -> str:
    """``hydra.sweep.dir=`` / ``hydra.run.dir=`` with a relative value, rooted at the project root:
    Hydra makes those folders relative to the current directory (a sweep started elsewhere wrote
    its jobs there, and its sweep.json here)."""
    for key in ("hydra.sweep.dir=", "hydra.run.dir="):
        if arg.startswith(key) and not os.path.isabs(os.path.expanduser(arg[len(key):])):
            return f"{key}{resolve(arg[len(key):])}"
    return arg


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
    scenario = conf_dir() / "sim" / f"{name}.yaml"
    if not scenario.is_file():        # a scenario of another search path: nothing to compare
        return name
    written = _written_generator(str(scenario), scenario.stat().st_mtime_ns)
    if written is None or written == generator:
        return name
    digest = hashlib.sha256(json.dumps(generator, sort_keys=True, default=str).encode()).hexdigest()
    return f"{name}-{digest[:8]}"


# `${root:reports/x}` in the config: the path under the project root (Hydra's own folders)
OmegaConf.register_new_resolver("root", lambda path=".": str(resolve(path)), replace=True)
OmegaConf.register_new_resolver("sim_dataset", scenario_dataset, replace=True)
