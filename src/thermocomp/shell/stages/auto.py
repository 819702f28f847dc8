"""``model=auto`` in the stages: its candidates built from their families' configs
(``conf/model/<name>.yaml``; ``ati`` / ``ati+<family>``: the ATI wrapper of ``conf/ati/cmeans.yaml``
around MLR / that family), so a new family becomes a candidate by a config edit."""

from __future__ import annotations

from collections.abc import Mapping

from omegaconf import DictConfig, ListConfig, OmegaConf

from ...base.errors import ConfigError
from ...base.paths import conf_dir
from ...core.models.auto import AUTO, add_choices, as_chosen, candidate_family, check_candidates
from ...core.scoring.auto_validation import val_split_scores
from ..build import build, load_node

# common and modelling read these here
__all__ = ["add_choices", "as_chosen", "auto_scheme", "build_candidates", "is_auto", "val_split_scores"]


def is_auto(cfg: DictConfig) -> bool:
    return cfg.model.get("candidates") is not None


def auto_scheme(cfg: DictConfig, ds) -> dict:
    """``{"scheme": ...}``: validate as the test split of ``ds`` is held out, unless
    ``model.estimator.scheme`` names one (``{}`` without a dataset)."""
    if ds is None or cfg.model.estimator.get("scheme", "auto") != "auto":
        return {}
    from ...core.scoring.evaluation import holdout_scheme

    return {"scheme": holdout_scheme(ds)}


def build_candidates(cfg: DictConfig) -> dict:
    """``{name: unfitted estimator}`` of ``model.candidates``, each family with its
    ``model.candidate_defaults`` (the candidate role's settings, for the families present) and
    the candidate's ``model.candidate_params`` over them."""
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
