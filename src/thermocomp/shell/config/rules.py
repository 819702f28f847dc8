"""What the keys of every config group may be, checked by every stage before any work.

A stage used to check its own group only, while several read another's: replay and monitor
stream with ``promote.envelope``, replay and promote build the ``monitor`` group's adaptive
compensator.  So ``replay promote.envelope.margin=nan`` streamed with the clamp off (an outside
probe: max correction 1,216 µm against 251 with 0.1).  :func:`check_schema` (in
``checks.check_config``) checks every group of the schema (:mod:`.schema`) the config holds,
whatever the stage, and the relations between keys below; a stage adds only the rules that need
its own code (the envelope's policies, diagnose's families).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from omegaconf import DictConfig, OmegaConf

from ...apps.volumetric.kinematics import KINDS
from ...base.errors import ConfigError
from ...base.params import NON_NEGATIVE, check_values, either, numbers
from .schema import AUTO_REFERENCE, PLOTS, Root, Study, part, rules  # noqa: F401  (re-exported)

# The rule tables of the groups, as the stages name them (keys under the group's prefix, or
# relative where a stage checks the group's own node).
CONFIG_RULES = {**{k: r for k, r in rules(Root).items() if "." not in k},
                **rules(part("data"), "data."), **rules(part("eval"), "eval.")}
MONITOR_RULES, PROMOTE_RULES, EXPORT_RULES, ADAPT_RULES, SERVE_RULES, TWIN_RULES, CONNECT_RULES = (
    rules(part(g), f"{g}.") for g in ("monitor", "promote", "export", "adapt", "serve", "twin",
                                      "connect"))
DIAGNOSE_RULES = rules(part("diagnose"))
STUDY_RULES = rules(Study)


def check_keys(cfg: DictConfig, rules: dict) -> None:
    """Every dotted key of ``rules`` in ``cfg`` within its rule (``eval.validation_folds=1:
    must be an integer >= 2``)."""
    for key, rule in rules.items():
        group, _, name = key.rpartition(".")
        check_values({name: OmegaConf.select(cfg, key)}, {name: rule}, group)


def check_part(node, schema: type, prefix: str) -> None:
    """Every key of ``schema`` in ``node`` (a mapping: ``cfg.monitor``) within its rule; a
    missing key is None."""
    for key, rule in rules(schema).items():
        value = node
        for name in key.split("."):
            value = value.get(name) if isinstance(value, Mapping) else None
        check_values({key: value}, {key: rule}, prefix)


def check_monitor(m: DictConfig) -> None:
    """``monitor.*`` relations the monitor needs, beyond each key's rule."""
    if m.get("continues") is not None and m.input != "-":
        raise ConfigError(f"monitor.continues={m.continues}: applies to a stream on stdin "
                          "(monitor.input=-); a test campaign's predecessor is its manifest's")
    if m.get("ambient_c") is not None and (m.input != "-" or m.get("continues") is not None):
        raise ConfigError(f"monitor.ambient_c={m.ambient_c}: applies to a stream on stdin "
                          "(monitor.input=-) that continues no campaign; a campaign of data.path "
                          "has its manifest's ambient_c")
    if m.confirm > m.window:
        raise ConfigError(f"monitor.confirm={m.confirm}: must be <= monitor.window={m.window}")
    if m.bands.alarm_c < m.bands.warning_c:
        raise ConfigError(f"monitor.bands.alarm_c={m.bands.alarm_c}: must be >= "
                          f"monitor.bands.warning_c={m.bands.warning_c}")


def kind_ranges(kinds) -> dict:
    """The rule of a range per parameter kind (``design.ranges``, ``calibrate.prior``): a number
    >= 0, or one per Legendre order; ``decay`` one number."""
    return {k: NON_NEGATIVE if k == "decay" else either(NON_NEGATIVE, numbers(0.0)) for k in kinds}


def _check_design_maps(d) -> None:
    """``design.ranges`` and ``design.studies``: maps of names, beyond the schema's keys."""
    d = OmegaConf.to_container(d, resolve=True) if isinstance(d, DictConfig) else d
    ranges = d.get("ranges") or {}
    unknown = [k for k in ranges if k not in (*KINDS, "decay")]
    if unknown:
        raise ConfigError(f"design.ranges.{unknown[0]}: not a parameter kind "
                          f"({', '.join(KINDS)}, decay)")
    check_values(ranges, kind_ranges(("decay", *ranges)), "design.ranges")
    studies = d.get("studies")
    if not isinstance(studies, dict) or not studies:
        raise ConfigError("design.studies must map study names to n_balls, misalignment_deg, position_sets")
    if all(s is None for s in studies.values()):
        raise ConfigError("design.studies: every study is null, none left to run")
    for name, study in studies.items():
        if study is not None:            # null: a default study dropped
            keys = set(study) if isinstance(study, dict) else set()
            odd = sorted(keys - set(STUDY_RULES)) + sorted(set(STUDY_RULES) - keys)
            if odd:
                what = "not a study key" if odd[0] in keys else "missing"
                raise ConfigError(f"design.studies.{name}.{odd[0]}: {what} (a study gives "
                                  f"{', '.join(STUDY_RULES)})")
            check_values(study, STUDY_RULES, f"design.studies.{name}")


def _check_prior(c) -> None:
    prior = c.get("prior")
    if prior is not None:    # a range per kind (decay: one number), or one per Legendre order
        from ...apps.volumetric.calibration import check_prior_kinds

        check_values(prior, kind_ranges(prior), "calibrate.prior")
        # the kinds every machine has (cross only with its cross terms: checked with the model)
        check_prior_kinds(prior, {"positioning", "straightness", "squareness", "angular"})


# What a group needs beyond its keys' rules.
RELATIONS = {"monitor": check_monitor, "design": _check_design_maps, "calibrate": _check_prior}


def check_schema(cfg: DictConfig) -> None:
    """Every key of the schema in ``cfg`` within its rule, group by group (a group ``cfg`` does
    not hold is skipped: a command composes only what it reads), then each group's relations."""
    for f in dataclasses.fields(Root):
        if f.default_factory is dataclasses.MISSING:
            if f.metadata["rule"] is not None:
                check_values({f.name: cfg.get(f.name)}, {f.name: f.metadata["rule"]}, "")
        elif cfg.get(f.name) is not None:
            check_part(cfg[f.name], f.default_factory, f.name)
            if f.name in RELATIONS:
                RELATIONS[f.name](cfg[f.name])
