"""The champion decision of ``thermocomp promote`` (pure: tags and scores in, decision out).

The stage reads the registry and writes tags; what it decides -- which
criterion may choose, whether the stream is causal enough to deploy, whether
the champion's score is comparable, whether the alias moves and why, and what
a new version is tagged with -- lives here, testable on hand-made values.
"""

from __future__ import annotations

from collections.abc import Mapping

from ...base.errors import ConfigError
from .leaderboard import FIGURES, beats, is_validation


def tag_value(value: float | None) -> str:
    """A figure as a registry tag: 6 significant digits, ``null`` when missing."""
    return "null" if value is None else f"{value:.6g}"


def fmt(value: float | None) -> str:
    return "n/a" if value is None else f"{value:.4g}"


def check_criterion(criterion: str) -> None:
    """Only a validation figure may choose (the test split is reported, never used)."""
    if not is_validation(criterion):
        what = ("is a test figure: the test split is reported, never used to choose"
                if criterion in FIGURES else "is not a figure")
        raise ConfigError(f"promote.criterion={criterion} {what} (use val_rmse, val_rsd_mean or "
                          f"val_rsd_sd)")


def check_stream_deviation(deviation: float, limit: float, run_id: str) -> None:
    """Refuse a model whose streamed predictions drift from its batch ones (it is not causal)."""
    if deviation > limit:
        raise ConfigError(
            f"run {run_id}: streamed predictions differ from batch ones by {deviation:.3g} µm "
            f"(> promote.max_stream_deviation_um); a model with memory must implement "
            f"stream_init/stream_step to be deployed")


def champion_validation(tags: Mapping | None, criterion: str, target: str, dataset_hash: str,
                        mode: str) -> tuple[float | None, str | None]:
    """The validation score the champion was promoted with, if it is comparable here: same
    dataset, target and mode of the validation figures (``mode``; an old champion's is its
    ``eval_mode``); else ``(None, why not)``."""
    tags = dict(tags or {})
    tags.setdefault("validation_mode", tags.get("eval_mode"))
    for key, want, what in (("dataset_hash", dataset_hash, "another dataset"),
                            ("criterion_target", target, f"another target than {target}"),
                            ("validation_mode", mode, f"another mode than {mode}")):
        if tags.get(key) != want:
            return None, f"its validation score is on {what} ({key}={tags.get(key)})"
    value = tags.get(f"metric.{criterion}")
    if value in (None, "null"):
        return None, f"it has no validation score {criterion}"
    return float(value), None


def same_figures(tags: Mapping | None, figures: Mapping) -> bool:
    """Whether a version's tagged figures equal these (the same model deployed the same way)."""
    tags = tags or {}
    return all(tags.get(f"metric.{k}") == tag_value(v) for k, v in figures.items())


def same_deployment(tags: Mapping | None, dataset_hash: str, deployed: str) -> bool:
    tags = tags or {}
    return tags.get("dataset_hash") == dataset_hash and tags.get("deploy_config") == deployed


def decide(version: str | None, score: float | None, champion_version: str | None,
           champion_score: float | None, champion_note: str | None, *, criterion: str,
           min_improvement: float, force: bool = False, mode: str = "simulation"
           ) -> tuple[bool, str]:
    """(whether the alias moves to ``version``, why).

    ``version`` None: one not registered yet (never the champion).  No champion: it moves.
    The champion itself: it stays.  A champion with no comparable score (``champion_note``
    says why) is replaced only when ``force``.  Otherwise the candidate must beat it by more than
    ``min_improvement``, compared at the precision of a tag so that the same
    model (e.g. deployed another way) ties instead of "beating" itself.
    """
    if champion_version is None:
        return True, "no champion yet"
    if version == str(champion_version):
        return False, f"already champion: version {version}"
    if champion_score is None:
        return force, (f"the champion (version {champion_version}) has no comparable validation "
                       f"score ({champion_note})"
                       + ("; forced" if force else "; set promote.force=true to replace it"))
    moved = beats(float(tag_value(score)), champion_score, criterion, min_improvement)
    verb = "beats" if moved else "does not beat"
    return moved, (f"{mode}-mode validation {criterion} {fmt(score)} {verb} the champion's "
                   f"{fmt(champion_score)} (version {champion_version}) on the same dataset")


def outcome_line(name: str, version: str, alias: str, moved: bool, why: str,
                 champion_version: str | None) -> str:
    """The one line promote prints last."""
    state = ("promoted to @" + alias if moved else
             why if version == str(champion_version or "") else "not promoted")
    return f"{name} v{version}: {state}" + ("" if state == why else f" ({why})")
