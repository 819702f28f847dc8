"""The project's ``conf/`` read by Hydra with each file's YAML parsed once per text.

Each Hydra compose reads and parses again every config file of its defaults list (~24 for a
command: about a fifth of its CPU).  :class:`ProjectConf` puts :class:`ParsedOnceSource` before
the project's ``conf/`` in Hydra's search path; that source reads each file as Hydra's own file
source does, every time, and parses a text it has not seen: the parse is keyed by the file's
whole text, so an edited file is parsed anew, and a folder added with ``hydra.searchpath`` stays
Hydra's own.  Both are Hydra plugins, found by its scan of the ``hydra_plugins`` namespace.
"""

import functools
import io
import os
from typing import List, Optional

from hydra.core.config_search_path import ConfigSearchPath, SearchPathQuery
from hydra.core.object_type import ObjectType
from hydra.plugins.config_source import ConfigLoadError, ConfigResult, ConfigSource
from hydra.plugins.search_path_plugin import SearchPathPlugin
from omegaconf import OmegaConf

SCHEME = "thermocomp-conf"


@functools.lru_cache(maxsize=1024)
def parsed(text: str):
    """A config file's text as ``OmegaConf.load`` reads it, as plain containers (``${...}`` and
    ``???`` kept as written); the cache of one process, never part of a source (Hydra deep-copies
    its sources at each compose)."""
    return OmegaConf.to_container(OmegaConf.load(io.StringIO(text)), resolve=False)


class ParsedOnceSource(ConfigSource):
    """Hydra's file config source, but for the parse (:func:`parsed`)."""

    @staticmethod
    def scheme() -> str:
        return SCHEME

    def _full(self, config_path: str) -> str:
        return os.path.realpath(os.path.join(self.path, config_path))

    def load_config(self, config_path: str) -> ConfigResult:
        full_path = self._full(self._normalize_file_name(config_path))
        if not os.path.exists(full_path):
            raise ConfigLoadError(f"Config not found : {full_path}")
        with open(full_path, encoding="utf-8") as f:
            text = f.read()
        return ConfigResult(config=OmegaConf.create(parsed(text)), path=f"{SCHEME}://{self.path}",
                            provider=self.provider, header=ConfigSource._get_header_dict(text[:512]))

    def available(self) -> bool:
        return self.is_group("")

    def is_group(self, config_path: str) -> bool:
        return os.path.isdir(self._full(config_path))

    def is_config(self, config_path: str) -> bool:
        return os.path.isfile(self._full(self._normalize_file_name(config_path)))

    def list(self, config_path: str, results_filter: Optional[ObjectType]) -> List[str]:
        files: List[str] = []
        for name in os.listdir(self._full(config_path)):
            self._list_add_result(files=files, file_path=os.path.join(config_path, name),
                                  file_name=name, results_filter=results_filter)
        return sorted(set(files))


class ProjectConf(SearchPathPlugin):
    """:class:`ParsedOnceSource` on the project's ``conf/`` just before it, when it is the
    primary config folder (``thermocomp``'s commands; another Hydra app is left as it is)."""

    def manipulate_search_path(self, search_path: ConfigSearchPath) -> None:
        from thermocomp.base.paths import conf_dir

        conf = str(conf_dir())
        main = SearchPathQuery(provider="main")
        if any(e.provider == "main" and e.path.split("://")[-1] == conf for e in search_path.get_path()):
            search_path.prepend("thermocomp", f"{SCHEME}://{conf}", anchor=main)
