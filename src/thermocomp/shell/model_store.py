"""A fitted compensator on disk: ``model.pkl`` signed beside it (:mod:`thermocomp.base.signing`), and
the model family a loaded one was configured as."""

from __future__ import annotations

from pathlib import Path

from omegaconf import OmegaConf

from ..base import signing
from ..base.paths import conf_dir, resolve
from ..core.compensator import Compensator
from ..core.io import ContractError


def save_model(comp: Compensator, path) -> Path:
    """Pickle ``comp`` to ``path`` with its signature ``<path>.sig`` (:mod:`thermocomp.base.signing`)."""
    return signing.dump(comp, resolve(path))


def load_model(path) -> Compensator:
    """The :class:`Compensator` pickled at ``path``; its signature is checked before unpickling."""
    path = resolve(path)
    if not path.is_file():
        raise ContractError("no trained model; run `thermocomp train` first", file=path)
    return signing.load(path, Compensator)


def model_family(comp) -> str:
    """The model family (``conf/model/<name>.yaml``'s ``name``) of a loaded compensator, as
    ``replay.json`` names a fitted one: through an ATI or a diagnosed wrapper to the model
    inside; the class name for an estimator no config builds."""
    families = {}
    for f in sorted(conf_dir().glob("model/*.yaml")):
        c = OmegaConf.load(f)
        families[str(c.estimator._target_).rsplit(".", 1)[-1]] = str(c.name)
    from ..apps.diagnose.augmented import MODEL_NAME, AugmentedRegressor

    est, suffix = comp.estimator, ""
    while type(est).__name__ not in families:
        if isinstance(est, AugmentedRegressor):
            suffix = f"+{MODEL_NAME}"            # as diagnose names it: <family>+diagnosed
        inner = getattr(est, "base_estimator", None) or getattr(est, "estimator", None)
        if inner is None:
            return type(comp.estimator).__name__
        est = inner
    return families[type(est).__name__] + suffix
