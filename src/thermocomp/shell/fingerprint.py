"""One fingerprint for what a stage hands to the next: the digest of the dataset it read
(``ds.meta["digest"]``, :func:`~thermocomp.base.files.folder_digest`) and a hash of the config
sections its output depends on.  ``ingest`` records one in ``ingested_with`` (of ``data.path``),
``denoise`` and ``select`` in ``denoise.json``/``selection.json`` (of ``data.interim``); the stages
reading them compare (:func:`matches`).  A model records the digest it was fitted on
(``interim_digest_``), a run its ``dataset_hash`` tag: the same digest, no config.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Iterable, Mapping

from omegaconf import DictConfig, OmegaConf

DIGEST, CONFIG = "digest", "config"

# the config sections each hand-off depends on (select works on the denoised inputs)
DENOISE_KEYS = ("denoise", "data.inputs")
SELECT_KEYS = (*DENOISE_KEYS, "select", "data.targets", "data.reference")


def plain(node) -> object:
    """A config node (or value) as JSON-comparable plain data, interpolations resolved."""
    data = OmegaConf.to_container(node, resolve=True) if OmegaConf.is_config(node) else node
    return json.loads(json.dumps(data, default=str))


def json_hash(settings: Mapping) -> str:
    """SHA-256 (hex) of ``settings`` as canonical JSON (keys sorted)."""
    text = json.dumps(plain(dict(settings)), sort_keys=True, ensure_ascii=True)
    return hashlib.sha256(text.encode()).hexdigest()


def sections(cfg: DictConfig, keys: Iterable[str]) -> dict:
    """The config sections ``keys`` (dotted; an absent one is null), plain."""
    return {k: plain(OmegaConf.select(cfg, k, default=None)) for k in keys}


def config_hash(cfg: DictConfig, keys: Iterable[str]) -> str:
    """:func:`json_hash` of the config sections ``keys``."""
    return json_hash(sections(cfg, keys))


def fingerprint(digest: str, cfg: DictConfig, keys: Iterable[str]) -> dict:
    """``{"digest": digest, "config": config_hash(cfg, keys)}``."""
    return {DIGEST: digest, CONFIG: config_hash(cfg, keys)}


def matches(made: Mapping | None, want: Mapping) -> bool:
    """``made`` (as recorded) was made from the data and settings of ``want``."""
    return made is not None and all(made.get(k) == want[k] for k in (DIGEST, CONFIG))
