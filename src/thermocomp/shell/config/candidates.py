"""``model=auto``'s candidates, built from their own configs (checked with the config).

A candidate is named by its family's config (``conf/model/<name>.yaml``), so a new
family becomes a candidate by a config edit (``model.candidates=[...]``);
``ati`` / ``ati+<family>`` is the ATI wrapper (``conf/ati/cmeans.yaml``) of MLR /
that family.
"""

from __future__ import annotations

from collections.abc import Mapping

from omegaconf import DictConfig, ListConfig, OmegaConf

from ...base.errors import ConfigError
from ...base.paths import conf_dir
from ...core.models.auto import ATI, BASELINE
from ..build import build

AUTO = "auto"


def is_auto(cfg: DictConfig) -> bool:
    return cfg.model.get("candidates") is not None


def build_candidates(cfg: DictConfig) -> dict:
    """``{name: unfitted estimator}`` of ``model.candidates``, each family with its
    ``model.candidate_defaults`` (the candidate role's settings, for the families present) and
    the candidate's ``model.candidate_params`` over them."""
    if cfg.get("ati") is not None and cfg.ati.get("estimator") is not None:
        raise ConfigError(f"model=auto with ati={cfg.ati.name}: the ATI wrapper is a candidate of its "
                          "own, name it in model.candidates (ati, or ati+<family>) with ati=none")
    candidates, params = cfg.model.get("candidates"), cfg.model.get("candidate_params") or {}
    if not isinstance(candidates, (list, tuple, ListConfig)):
        raise ConfigError(f"model.candidates={candidates}: must be a list of model families, "
                          "e.g. [mlr,lagbank]")
    if not isinstance(params, (Mapping, DictConfig)):
        raise ConfigError(f"model.candidate_params={params}: must be a mapping candidate -> "
                          "its keys, e.g. {lstm:{max_epochs:30}}")
    defaults = cfg.model.get("candidate_defaults") or {}
    if not isinstance(defaults, (Mapping, DictConfig)):
        raise ConfigError(f"model.candidate_defaults={defaults}: must be a mapping family -> "
                          "its keys, e.g. {lstm:{max_epochs:30}}")
    names = list(candidates)
    if not names:
        raise ConfigError("model.candidates is empty: name at least one model family")
    for name in params:
        if name not in names:
            raise ConfigError(f"model.candidate_params.{name}: {name} is not among model.candidates "
                              f"{names}")
    out = {}
    for name in names:
        wrapped = str(name).split("+", 1)
        family = BASELINE if wrapped == [ATI] else wrapped[-1]
        if len(wrapped) == 2 and wrapped[0] != ATI or family in (AUTO, ATI) or not str(name).strip():
            raise ConfigError(f"model.candidates: {name!r} is not a model family nor ati[+family]")
        estimator = _family(cfg, family, defaults.get(family), params.get(name), name)
        if family != name:   # an ATI candidate
            ati = _load(cfg, conf_dir() / "ati" / "cmeans.yaml", f"model.candidates: {name}")
            estimator = build(ati.estimator, f"model.candidates.{name}")(base_estimator=estimator)
        out[str(name)] = estimator
    return out


def _family(cfg: DictConfig, family: str, defaults, overrides, name: str):
    path = conf_dir() / "model" / f"{family}.yaml"
    if not path.is_file():
        known = sorted(p.stem for p in (conf_dir() / "model").glob("*.yaml") if p.stem != AUTO)
        raise ConfigError(f"model.candidates: {name!r} is not a model family (conf/model/ has "
                          f"{', '.join(known)}; ati or ati+<family> for the ATI wrapper)")
    node = _load(cfg, path, f"model.candidates: {name}")
    node.estimator = OmegaConf.merge(node.estimator, defaults or {}, overrides or {})
    where = (f"model.candidate_params.{name}" if overrides else
             f"model.candidate_defaults.{family}" if defaults else f"model.candidates.{name}")
    return build(node.estimator, where)


def _load(cfg: DictConfig, path, where: str) -> DictConfig:
    """The config file at ``path``, its interpolations (``${seed}``) against ``cfg``'s root."""
    root = OmegaConf.create({"seed": cfg.get("seed", 0)})
    root.node = OmegaConf.load(path)
    try:
        return OmegaConf.create(OmegaConf.to_container(root.node, resolve=True))
    except Exception as exc:   # an interpolation this root does not hold: say where
        raise ConfigError(f"{where}: {path} cannot be composed ({exc})") from None
