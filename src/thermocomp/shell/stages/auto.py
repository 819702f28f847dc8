"""``model=auto`` in the stages: its candidates built from their families' configs
(``conf/model/<name>.yaml``; ``ati`` / ``ati+<family>``: the ATI wrapper of ``conf/ati/cmeans.yaml``
around MLR / that family), so a new family becomes a candidate by a config edit."""

from __future__ import annotations

from omegaconf import DictConfig

from ...core.models.auto import add_choices, as_chosen
from ...core.scoring.auto_validation import val_split_scores
from ..config.candidates import build_candidates, is_auto

# common and modelling read these here
__all__ = ["add_choices", "as_chosen", "auto_scheme", "build_candidates", "is_auto", "val_split_scores"]


def auto_scheme(cfg: DictConfig, ds) -> dict:
    """``{"scheme": ...}``: validate as the test split of ``ds`` is held out, unless
    ``model.estimator.scheme`` names one (``{}`` without a dataset)."""
    if ds is None or cfg.model.estimator.get("scheme", "auto") != "auto":
        return {}
    from ...core.scoring.evaluation import holdout_scheme

    return {"scheme": holdout_scheme(ds)}
