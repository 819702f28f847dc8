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
from ..build import build, load_node

AUTO = "auto"


def is_auto(cfg: DictConfig) -> bool:
    return cfg.model.get("candidates") is not None


def build_candidates(cfg: DictConfig) -> dict:
    """``{name: unfitted estimator}`` of ``model.candidates``, each family with its
    ``model.candidate_defaults`` (the candidate role's settings, for the families present) and
    the candidate's ``model.candidate_params`` over them."""
    # here, not at the top: every stage checks its config, and only model=auto needs the models
    from ...core.models.auto import candidate_family, check_candidates

    if cfg.get("ati") is not None and cfg.ati.get("estimator") is not None:
        raise ConfigError(f"model=auto with ati={cfg.ati.name}: the ATI wrapper is a candidate of its "
                          "own, name it in model.candidates (ati, or ati+<family>) with ati=none")
    params = cfg.model.get("candidate_params") or {}
    defaults = cfg.model.get("candidate_defaults") or {}
    names = check_candidates(cfg.model.get("candidates"), params, defaults,
                             (list, tuple, ListConfig), (Mapping, DictConfig))
    out = {}
    for name in names:
        family, where = candidate_family(name), f"model.candidates: {name}"
        estimator = _family(cfg, family, defaults.get(family), params.get(name), name)
        if family != name:   # an ATI candidate
            ati = load_node(conf_dir() / "ati" / "cmeans.yaml", cfg.get("seed", 0), where)
            estimator = build(ati.estimator, f"model.candidates.{name}")(base_estimator=estimator)
        out[str(name)] = estimator
    return out


def family_estimator(cfg: DictConfig, family: str):
    """The unfitted estimator of ``conf/model/<family>.yaml`` as it is (no candidate keys)."""
    return _family(cfg, family, None, None, family)


def _family(cfg: DictConfig, family: str, defaults, overrides, name: str):
    path = conf_dir() / "model" / f"{family}.yaml"
    if not path.is_file():
        known = sorted(p.stem for p in (conf_dir() / "model").glob("*.yaml") if p.stem != AUTO)
        raise ConfigError(f"model.candidates: {name!r} is not a model family (conf/model/ has "
                          f"{', '.join(known)}; ati or ati+<family> for the ATI wrapper)")
    node = load_node(path, cfg.get("seed", 0), f"model.candidates: {name}")
    node.estimator = OmegaConf.merge(node.estimator, defaults or {}, overrides or {})
    where = (f"model.candidate_params.{name}" if overrides else
             f"model.candidate_defaults.{family}" if defaults else f"model.candidates.{name}")
    return build(node.estimator, where)
