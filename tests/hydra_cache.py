"""Hydra's composition cached in a test process: each in-process command composes its config, and
the suite composes thousands (~0.17 s of CPU each, most of it the defaults list and the merge of
the same yaml files).

What is cached is what depends on the config files alone: the defaults list of a root config
under its group overrides (``model=arx``, ``hydra/launcher=joblib``, a sweep's ``model=mlr,pcr``)
and the config merged from it, before any value override (``data.path=...``). Hydra applies the
value overrides and fills its ``hydra`` node afresh on every call, as without the cache.

The key holds everything those two results are computed from: the root's name, the overrides
that are not value overrides (by Hydra's own rule, :func:`_value_overrides`), ``skip_missing``
(a sweep's), and the search path's contents: every file of each folder source (bytes, not
times: a test edits a copy of ``conf/`` within a clock tick) and each node of the ConfigStore
(where ``thermocomp.shell.config.commands.register`` puts a command's root). A miss is Hydra's
own call; it is kept only when Hydra split the overrides as :func:`_value_overrides` does.

Private Hydra functions are wrapped (``create_defaults_list`` as ``config_loader_impl`` calls it,
``ConfigLoaderImpl._compose_config_from_defaults_list``): :func:`install` does it only for the
Hydra release whose code was read (the sources of the caller and the two functions hashed), and
otherwise leaves Hydra as it is.  tests/test_hydra_cache.py checks the cache against plain
Hydra (same configs, same errors) and that an edited file is read again.

Hit or miss, each composition also started with a deep copy of Hydra's config repository
(``CachingConfigRepository.__init__``), the whole ConfigStore with it (its structured source
holds the store): 0.017 of a hit's 0.035 s of CPU.  :func:`_caching_repository` copies the
repository's object only: the composition rebinds its list of sources (``initialize_sources``),
never changes a source, and the store hands out copies of its nodes.
"""

from __future__ import annotations

import copy
import dataclasses
import hashlib
import inspect
import os
import pickle
from collections import OrderedDict

HYDRA_VERSION = "1.3.8"
# sha256 of the sources the wrappers rely on, as read in that release
SOURCES = {
    "ConfigLoaderImpl._load_configuration_impl":
        "f611c97e466f94db72ac0a127250fa439eb79a30fe164968e5d71f543bb960c2",
    "ConfigLoaderImpl._compose_config_from_defaults_list":
        "136c76d6cb280db8f0644f528dffed4d6cf4850bb1193827e9a1dbda5d360fba",
    "create_defaults_list": "f0dd0ad31a342543a481e620268f953fe6851f2fc8d3db986b49d66046846a0a",
    "Overrides.__init__": "d8bba688061e455c5464ddab60643980d9d63b1849467079e0b229ee3c8521c8",
    "CachingConfigRepository.__init__":
        "d2b1c125731574fe7de0b14a17d17fde84fa942ce5f1f5a645cc860edbae1332",
    "ConfigRepository.initialize_sources":
        "24ecb24ffa8860f91e67a07d639d8283eadd28fb4bb90b168caf4b5d048375b0",
}
MAX_ENTRIES = 64          # the suite's distinct (conf folder, root, group overrides): dozens

_entries: OrderedDict = OrderedDict()      # key -> _Entry, least recently used first
_by_defaults: dict[int, "_Entry"] = {}     # id(entry.result.defaults) -> entry
_node_digests: dict[int, tuple] = {}       # id(ConfigNode) -> (the node, its digest)
_original: dict = {}


@dataclasses.dataclass
class _Entry:
    result: object                 # Hydra's DefaultsList for the key
    config: object = None          # the merged config before value overrides (a pristine copy)
    pickled: bytes | None = None   # that config pickled at its first hit (b"": it does not pickle)


def _copy(entry: _Entry):
    """A fresh copy of ``entry``'s pristine config for a cache hit: unpickled (~0.010 s of CPU
    for the default root's) rather than deep-copied (~0.036 s), on every hit of every in-process
    command; pickled at the first hit (a miss never hit again pays nothing), deep-copied if it
    does not pickle (a ConfigStore node whose class pickle cannot import)."""
    if entry.pickled is None:
        try:
            entry.pickled = pickle.dumps(entry.config)
        except (pickle.PicklingError, AttributeError, TypeError):
            entry.pickled = b""
    return pickle.loads(entry.pickled) if entry.pickled else copy.deepcopy(entry.config)


def _functions():
    """Hydra's functions the wrappers rely on (the wrapped ones as Hydra has them)."""
    from hydra._internal import config_loader_impl, config_repository, defaults_list

    return {
        "ConfigLoaderImpl._load_configuration_impl":
            config_loader_impl.ConfigLoaderImpl._load_configuration_impl,
        "ConfigLoaderImpl._compose_config_from_defaults_list": _original.get(
            "compose", config_loader_impl.ConfigLoaderImpl._compose_config_from_defaults_list),
        "create_defaults_list": defaults_list.create_defaults_list,
        "Overrides.__init__": defaults_list.Overrides.__init__,
        "CachingConfigRepository.__init__": _original.get(
            "caching_repository", config_repository.CachingConfigRepository.__init__),
        "ConfigRepository.initialize_sources": config_repository.ConfigRepository.initialize_sources,
    }


def _sha(function) -> str:
    return hashlib.sha256(inspect.getsource(function).encode()).hexdigest()


def supported() -> bool:
    """Whether this Hydra is the release whose code the wrappers were written against."""
    import hydra

    if hydra.__version__ != HYDRA_VERSION:
        return False
    found = _functions()
    return all(_sha(found[name]) == sha for name, sha in SOURCES.items())


def install() -> bool:
    """Wrap Hydra's composition with the cache when :func:`supported`; True if it is on."""
    if _original:
        return True
    if not supported():
        return False
    from hydra._internal import config_loader_impl, config_repository

    _original["create_defaults_list"] = config_loader_impl.create_defaults_list
    _original["compose"] = config_loader_impl.ConfigLoaderImpl._compose_config_from_defaults_list
    _original["caching_repository"] = config_repository.CachingConfigRepository.__init__
    config_loader_impl.create_defaults_list = _create_defaults_list
    config_loader_impl.ConfigLoaderImpl._compose_config_from_defaults_list = _compose
    config_repository.CachingConfigRepository.__init__ = _caching_repository
    return True


def uninstall() -> None:
    """Hydra as it was, the cache emptied."""
    if not _original:
        return
    from hydra._internal import config_loader_impl, config_repository

    config_loader_impl.create_defaults_list = _original.pop("create_defaults_list")
    config_loader_impl.ConfigLoaderImpl._compose_config_from_defaults_list = _original.pop("compose")
    config_repository.CachingConfigRepository.__init__ = _original.pop("caching_repository")
    clear()


def clear() -> None:
    _entries.clear()
    _by_defaults.clear()
    _node_digests.clear()


def _value_overrides(repo, overrides_list) -> list:
    """The overrides Hydra applies to the merged config (``Overrides.__init__``'s rule): not a
    sweep, and a dict or a key that names no config group."""
    return [o for o in overrides_list if not o.is_sweep_override()
            and (isinstance(o.value(), dict) or not repo.group_exists(o.key_or_group))]


def _folder_digest(path: str) -> str:
    digest = hashlib.blake2b()
    for folder, dirs, files in os.walk(path):
        dirs.sort()
        for name in sorted(files):
            file = os.path.join(folder, name)
            digest.update(os.path.relpath(file, path).encode() + b"\0")
            with open(file, "rb") as f:
                digest.update(f.read())
            digest.update(b"\0")
    return digest.hexdigest()


def _store_digest() -> tuple:
    """Each ConfigStore node (its place, name, package, provider and yaml). Hydra never changes a
    stored node (its ``load`` hands out copies); a node stored again is a new object."""
    from hydra.core.config_store import ConfigNode, ConfigStore
    from omegaconf import OmegaConf

    found = []

    def walk(tree: dict, path: str) -> None:
        for name in sorted(tree):
            item = tree[name]
            if isinstance(item, ConfigNode):
                seen = _node_digests.get(id(item))
                if seen is None or seen[0] is not item:
                    text = OmegaConf.to_yaml(item.node) if item.node is not None else ""
                    seen = (item, hashlib.blake2b(text.encode()).hexdigest())
                    _node_digests[id(item)] = seen
                found.append((path, name, item.group, item.package, item.provider, seen[1]))
            else:
                walk(item, f"{path}/{name}")

    walk(ConfigStore.instance().repo, "")
    return tuple(found)


def _sources_key(repo) -> tuple:
    key = []
    for source in repo.get_sources():
        scheme = source.scheme()
        if scheme == "file":
            content = _folder_digest(source.path) if os.path.isdir(source.path) else None
        elif scheme == "structured":
            content = _store_digest()
        else:          # pkg://: a package installed in the venv, as it is for the whole run
            content = None
        key.append((scheme, source.path, source.provider, content))
    return tuple(key)


def _create_defaults_list(repo, config_name, overrides_list, prepend_hydra, skip_missing):
    values = _value_overrides(repo, overrides_list)
    chosen = tuple(o.input_line for o in overrides_list if not any(o is v for v in values))
    key = (_sources_key(repo), config_name, chosen, prepend_hydra, skip_missing)
    entry = _entries.get(key)
    if entry is None:
        result = _original["create_defaults_list"](
            repo=repo, config_name=config_name, overrides_list=overrides_list,
            prepend_hydra=prepend_hydra, skip_missing=skip_missing)
        if [id(o) for o in result.config_overrides] == [id(o) for o in values]:
            entry = _remember(key, _Entry(result))
        return result
    _entries.move_to_end(key)
    return dataclasses.replace(entry.result, config_overrides=values)


def _remember(key, entry: _Entry) -> _Entry:
    _entries[key] = entry
    _by_defaults[id(entry.result.defaults)] = entry
    while len(_entries) > MAX_ENTRIES:
        _, old = _entries.popitem(last=False)
        _by_defaults.pop(id(old.result.defaults), None)
    return entry


def _compose(self, defaults, repo):
    entry = _by_defaults.get(id(defaults))
    if entry is None or entry.result.defaults is not defaults:
        return _original["compose"](self, defaults=defaults, repo=repo)
    if entry.config is None:
        config = _original["compose"](self, defaults=defaults, repo=repo)
        entry.config = copy.deepcopy(config)           # Hydra changes what it returns
        return config
    return _copy(entry)


def _caching_repository(self, delegate) -> None:
    """``CachingConfigRepository.__init__`` with a copy of the repository object, not of all it
    holds (see the module's docstring)."""
    self.delegate = copy.copy(delegate)
    self.cache = {}
