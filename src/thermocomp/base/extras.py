"""Optional dependencies: which extra of ``pip install`` brings a module, and the one-line error
when a command needs one that is not installed (``model=lstm`` without torch: exit 2, naming
``thermocomp[lstm]``), instead of a traceback.

The core (``pip install -e .``) simulates, runs, compares, promotes, deploys and monitors; the
extras are in ``pyproject.toml`` and docs/install.md.
"""

from __future__ import annotations

from .errors import ConfigError

# top-level module (or dotted prefix) -> (extra, what needs it)
MODULES = {
    "torch": ("lstm", "model=lstm"),
    "dvc": ("pipeline", "the DVC pipeline"),
    "optuna": ("scale", "hydra/sweeper=optuna"),
    "hydra_plugins.hydra_ray_launcher": ("scale", "hydra/launcher=ray"),
    "ray": ("scale", "hydra/launcher=ray"),
    "hydra_plugins.hydra_submitit_launcher": ("scale", "hydra/launcher=slurm"),
    "submitit": ("scale", "hydra/launcher=slurm"),
    "psycopg2": ("team", "a PostgreSQL tracking store"),
    "asyncua": ("machine", "OPC UA (thermocomp twin / connect)"),
    "openpyxl": ("excel", "an Excel workbook (data.path=<file>.xlsx)"),
    "nptdms": ("tdms", "a National Instruments TDMS file (data.path=<file>.tdms)"),
    "h5py": ("matlab", "a MATLAB -v7.3 file or an HDF5 file (data.path=<file>.mat | .h5)"),
}
# Hydra configs that a plugin of an extra registers (conf/ extends them)
CONFIGS = {"hydra/launcher/submitit_slurm": "hydra_plugins.hydra_submitit_launcher",
           "hydra/launcher/submitit_local": "hydra_plugins.hydra_submitit_launcher"}


class MissingExtra(ConfigError):
    """A feature whose optional dependency is not installed (exit 2, naming the extra)."""


def _entry(name: str):
    for prefix, entry in MODULES.items():
        if name == prefix or name.startswith(prefix + "."):
            return entry
    return None


def message(module: str) -> str | None:
    """The one line for a missing ``module`` that an extra brings, else None."""
    entry = _entry(module)
    if entry is None:
        return None
    extra, what = entry
    return (f"{what} needs {module.split('.')[-1] if module.startswith('hydra_plugins.') else module}, "
            f"an optional dependency: pip install -e '.[{extra}]' (or make install, which has all)")


def missing(exc: BaseException | None) -> MissingExtra | None:
    """The :class:`MissingExtra` behind ``exc`` (a ``ModuleNotFoundError`` of an extra's module
    anywhere in its chain of causes, or a missing plugin config), else None."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        seen.add(id(exc))
        if isinstance(exc, MissingExtra):
            return exc
        name = getattr(exc, "name", None) if isinstance(exc, ModuleNotFoundError) else None
        name = name or getattr(exc, "missing_cfg_file", None) and CONFIGS.get(exc.missing_cfg_file)
        if name and message(name):
            return MissingExtra(message(name))
        exc = exc.__cause__ or exc.__context__
    return None


def require(module: str) -> None:
    """Import ``module`` or raise :class:`MissingExtra` naming its extra."""
    import importlib

    try:
        importlib.import_module(module)
    except ModuleNotFoundError as exc:
        raise missing(exc) or exc from None
