"""The checks every stage runs on its config before anything is read or written."""

from __future__ import annotations

import functools
import tempfile
from numbers import Integral

from omegaconf import DictConfig, OmegaConf

from ...base.errors import ConfigError
from ...base.extras import require
from ...base.params import MAX_COUNT, check_params
from ...base.paths import resolve
from ...core import io
from ..build import build
from ..store import enabled, store_uri
from .apart import check_apart
from .candidates import build_candidates, is_auto
from .rules import check_schema

MAX_COMPONENT = 200   # bytes of one name in a written path: 255 less the staging decoration
# The configured estimators, denoiser and selector: each checks its ``param_rules``.
COMPONENTS = ("model.estimator", "ati.estimator", "denoise.denoiser", "select.selector")


def check_config(cfg: DictConfig, outputs: tuple[str, ...] = ("out",),
                 inputs: tuple[str, ...] = (), existing_store: bool = False) -> None:
    """Refuse bad choices before anything is read or written.

    ``outputs`` are the config keys of what the stage writes: folders (``out``,
    ``data.interim``) or files (``model_path``); each must be writable where it
    is (not an existing file in a folder's place, not a read-only place).
    ``inputs`` are the keys of what it reads besides ``data.path``: no output (nor
    ``out``, where its log goes) is, lies inside or holds one (:mod:`.apart`).
    ``existing_store``: the stage reads runs from the store, which must be there.
    """
    check_schema(cfg)        # every group, whatever the stage: replay streams with promote.* too
    io.ReadOptions.from_cfg(data_options(cfg))      # data.*: before any file is read
    store = ("tracking_uri",) if enabled(cfg) else ()    # a SQLite store and its artifacts
    check_apart(cfg, (*outputs, "out", *store), inputs)
    for key in COMPONENTS:
        node = OmegaConf.select(cfg, key)
        if node is not None:
            check_component(build(node, key), key)
    if is_auto(cfg):
        for name, candidate in build_candidates(cfg).items():
            check_component(candidate, f"model.candidates.{name}")
    for key in outputs:
        _check_writable(key, OmegaConf.select(cfg, key), folder=key != "model_path")
    if enabled(cfg):     # before any data is read: an unreachable server once hung a run for minutes
        store_uri(cfg, existing_store)


def check_component(component, key: str) -> None:
    """``component`` (instantiated from config ``key``; a ``_partial_`` one too) and the
    estimators it holds, each against its ``param_rules``: ``model.estimator.arx.max_inputs=0:
    must be an integer >= 1`` before any data is read."""
    if isinstance(component, functools.partial):       # ati.estimator: the base comes later
        component = component.func(*component.args, **component.keywords)
    check_params(component, key)
    for module in getattr(component, "requires", ()):    # an extra's library, once its values pass
        require(module)
    # scikit-learn's own estimators (the forest of arx_rf) check their parameters in fit, after
    # the data are read: ask them now (private API, but the one scikit-learn itself uses).
    if not hasattr(component, "param_rules") and hasattr(component, "_parameter_constraints"):
        try:
            component._validate_params()
        except ValueError as exc:
            raise ConfigError(f"{key}: {exc}") from None
        # their counts have no upper bound there (n_estimators=1e15 would loop for ever)
        for name, value in component.get_params(deep=False).items():
            if (name != "random_state" and isinstance(value, Integral) and not isinstance(value, bool)
                    and abs(value) > MAX_COUNT):
                raise ConfigError(f"{key}.{name}={value}: must be at most {MAX_COUNT:,}")
    if hasattr(component, "get_params"):
        for name, value in component.get_params(deep=False).items():
            if hasattr(value, "get_params"):
                check_component(value, f"{key}.{name}")


def _check_writable(key: str, value, folder: bool) -> None:
    """``key=value`` names a place this process can write a folder (or a file) to."""
    if value is None or not str(value).strip():      # resolved, '' is the project root
        raise ConfigError(f"{key} is empty: give a {'folder' if folder else 'file'}")
    path = resolve(value)
    long = next((p for p in path.parts if len(p.encode()) > MAX_COMPONENT), None)
    if long is not None:      # the staging folder, .<name>.stage-<pid>-<random>, must fit too
        raise ConfigError(f"{key}={value}: a folder or file name of {len(long.encode())} bytes "
                          f"(at most {MAX_COMPONENT})")
    if path.exists() and path.is_dir() != folder:
        raise ConfigError(f"{key}={value}: exists and is {'not ' * folder}a folder")
    probe = [path] if folder and path.is_dir() else []
    nearest = next(p for p in path.parents if p.exists())  # where its folders get created
    if not nearest.is_dir():
        raise ConfigError(f"{key}={value}: {nearest} is not a folder")
    for where in (*probe, nearest):
        try:
            tempfile.TemporaryFile(dir=where).close()
        except OSError as exc:
            raise ConfigError(f"{key}={value}: cannot write in {where} ({exc.strerror})") from None


def data_options(cfg: DictConfig) -> dict:
    return OmegaConf.to_container(cfg.data, resolve=True)
