"""Objects built from the config's ``_target_``: only the classes the project allows.

Hydra calls whatever a ``_target_`` names: ``model.estimator._target_=builtins.open`` with
``+model.estimator.file=/tmp/x +model.estimator.mode=w`` created the file before the run
failed, and ``shutil.copyfile``, ``numpy.savetxt`` or ``os.makedirs`` did their work the same
way (Hydra's block-list stops only ``subprocess`` and ``shutil.rmtree``).  Every node is
built through :func:`build`, and the CLI checks the whole composed config with
:func:`check_targets` before a stage starts: a ``_target_`` must be a *class* of the project
(``thermocomp.*``) or an estimator it documents (:data:`DOCUMENTED`).  Under ``hydra`` (what
Hydra itself builds: callbacks, launcher, sweeper, logging) the installed plugins are allowed
too.  ``THERMOCOMP_TARGETS`` (comma-separated dotted prefixes) adds classes of your own, a
model family under development or a test's stub: an environment setting, never a config value.
"""

from __future__ import annotations

import inspect
import os

from hydra.utils import instantiate

from ..base.errors import ConfigError, closest
from ..base.extras import missing

PROJECT = ("thermocomp.",)
# External estimators the documentation names (conf/model/arx_rf.yaml's forest).
DOCUMENTED = ("sklearn.ensemble.RandomForestRegressor",)
# What Hydra builds from its own node: its core plugins, installed launchers and sweepers,
# Optuna's samplers; a logging config's handlers and formatters (``class``, ``()``).
HYDRA = ("hydra._internal.core_plugins.", "hydra_plugins.", "optuna.samplers.")
LOGGING_NODES = ("hydra.job_logging", "hydra.hydra_logging")
LOGGING = ("thermocomp.base.log.",)      # no FileHandler: `mode: w` would truncate any file named
LOGGING_CLASSES = ("logging.StreamHandler", "logging.Formatter", "logging.NullHandler")
EXTRA_ENV = "THERMOCOMP_TARGETS"


def _extra() -> tuple[str, ...]:
    return tuple(p.strip() for p in os.environ.get(EXTRA_ENV, "").split(",") if p.strip())


def _allowed(target: str, where: str) -> tuple[str, ...] | None:
    """The module prefixes ``target`` may resolve into ("": any, for a class named exactly),
    None when its name is refused."""
    if where.startswith(LOGGING_NODES):
        named, prefixes = LOGGING_CLASSES, LOGGING
    else:
        named = DOCUMENTED
        prefixes = (*PROJECT, *_extra(), *(HYDRA if where.split(".")[0] == "hydra" else ()))
    if target in named:
        return ("",)
    return prefixes if target.startswith(prefixes) else None


def _refuse(key: str, target: str, why: str = "") -> None:
    raise ConfigError(f"{key}={target}: {why or 'not a class thermocomp builds'} (only its own "
                      f"thermocomp.* classes and the documented estimators {', '.join(DOCUMENTED)} "
                      f"are built from a config; {EXTRA_ENV} adds your own)")


def _targets(node, where: str):
    """``(key, target)`` of every ``_target_`` in ``node`` (and ``class``/``()`` of a logging
    config), nested nodes and lists included."""
    from omegaconf import DictConfig, ListConfig, OmegaConf

    if isinstance(node, (DictConfig, ListConfig)):
        node = OmegaConf.to_container(node, resolve=False)
    if isinstance(node, dict):
        for name, value in node.items():
            key = f"{where}.{name}" if where else str(name)
            if name == "_target_" or (name in ("class", "()") and where.startswith(LOGGING_NODES)):
                yield key, str(value)
            else:
                yield from _targets(value, key)
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from _targets(value, f"{where}[{i}]")


def check_targets(node, where: str = "") -> None:
    """Every ``_target_`` in config ``node`` (at key ``where``) names an allowed class, judged
    by its name alone (nothing is imported): one line naming the key and the target."""
    for key, target in _targets(node, where):
        if _allowed(target, key) is None:
            _refuse(key, target)


def check_built(node, where: str = "") -> None:
    """:func:`check_targets`, and each target resolved: a class defined in an allowed module
    (``thermocomp.base.log.logging.FileHandler`` is named under ``thermocomp.`` but is not one)."""
    from hydra._internal.utils import _locate

    for key, target in _targets(node, where):
        prefixes = _allowed(target, key)
        if prefixes is None:
            _refuse(key, target)
        try:
            obj = _locate(target)
        except ImportError as exc:   # an optional dependency not installed names its extra
            raise missing(exc) or ConfigError(
                f"{key}={target}: cannot be found ({' '.join(str(exc).split())})") from None
        if not inspect.isclass(obj):
            _refuse(key, target, "not a class")
        if not f"{obj.__module__}.".startswith(prefixes):
            _refuse(key, target, f"a class of {obj.__module__}")


def build(node, key: str):
    """``hydra.utils.instantiate(node)`` once :func:`check_built` allows every target in it
    (``key``: where ``node`` sits in the config, for the message)."""
    check_built(node, key)
    _check_arguments(node, key)
    return instantiate(node)


def _check_arguments(node, key: str) -> None:
    """Every key of ``node`` an argument of its ``_target_``'s constructor: a typo in a user's
    own ``conf/sim/<name>.yaml`` (or ``+sim.generator.sample_perod_s=60``) was Hydra's
    ``Error in call to target ... TypeError(...)``, naming neither the key nor the right one."""
    from hydra.utils import get_object
    from omegaconf import DictConfig

    if not isinstance(node, (DictConfig, dict)) or "_target_" not in node:
        return
    params = inspect.signature(get_object(str(node["_target_"]))).parameters
    if any(p.kind is inspect.Parameter.VAR_KEYWORD for p in params.values()):
        return                                   # takes any keyword: its own check
    names = [n for n, p in params.items() if n != "self" and p.kind in (
        inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)]
    for name in node:
        if str(name).startswith("_") and str(name).endswith("_"):   # _target_, _partial_, ...
            continue
        if name not in names:
            close = closest(str(name), names)
            hint = f"; did you mean {key}.{close[0]}?" if close else ""
            raise ConfigError(f"{key}.{name}: not an argument of {node['_target_']}{hint} "
                              f"(its arguments: {', '.join(names)})")


def load_node(path, seed, where: str):
    """The config file at ``path``, its interpolations (``${seed}``) resolved against ``seed``;
    one that cannot be composed is a ConfigError naming ``where``."""
    from omegaconf import OmegaConf

    root = OmegaConf.create({"seed": seed})
    root.node = OmegaConf.load(path)
    try:
        return OmegaConf.create(OmegaConf.to_container(root.node, resolve=True))
    except Exception as exc:   # an interpolation this root does not hold: say where
        raise ConfigError(f"{where}: {path} cannot be composed ({exc})") from None
