"""What the keys of every config group may be, checked by every stage before any work.

A stage used to check its own group only, while several read another's: replay and monitor
stream with ``promote.envelope``, replay and promote build the ``monitor`` group's adaptive
compensator.  So ``replay promote.envelope.margin=nan`` streamed with the clamp off (an outside
probe: max correction 1,216 µm against 251 with 0.1).  :func:`check_groups` (in
``check_config``) checks every table here whatever the stage; a stage adds only the rules that
need its own code (the envelope's policies, diagnose's families).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

from omegaconf import DictConfig, OmegaConf

from ...apps.volumetric.artefact import MAX_BALLS, POSITION_SETS, UNCERTAINTY
from ...apps.volumetric.design import KINDS
from ...base.errors import ConfigError
from ...base.params import (
    BOOLEAN,
    NON_NEGATIVE,
    POSITIVE,
    Rule,
    check_values,
    choice,
    either,
    file_name,
    integer,
    integers,
    number,
    numbers,
    optional,
    subset,
    text,
    texts,
)
from ...core.compensator import MODES
from ...core.frame import REFERENCES
from ...core.model_selection import CV_SCHEMES

MAX_WINDOW = 100_000      # monitor.window: samples kept per sensor (1e9 was OOM-killed at 24 GB)
MAX_MACHINES = 10_000     # design.n_machines: 50x the paper's 200 (1e9 ran 211 s, then killed)
MAX_GRID = 1_000_000      # VCE grid points: ~24 MB per machine at most, not a MemoryError
MAX_JOBS = 1024           # worker processes

AUTO_REFERENCE = "auto"   # data.reference: none where test/val campaigns continue others
PLOTS = ("summary", "test", "all", "none")  # `plots=`: which figures a stage draws (config.yaml)

# What the plain keys of the shared config groups may be (the components below check their own).
CONFIG_RULES = {
    "name": file_name(),
    "track": optional(BOOLEAN), "plots": choice(*PLOTS),
    "data.reference": choice(*REFERENCES, AUTO_REFERENCE),
    "eval.mode": choice(*MODES), "eval.e_p95.statistic": choice("range", "std"),
    "eval.e_p95.max_points": optional(integer(2)),  # 0 or 1 window lengths: an empty E_P95 curve
    "eval.anova_alpha": number(0.0, 1.0, open_lo=True, open_hi=True),
    "eval.mutual_prediction": BOOLEAN, "eval.ati_baselines": BOOLEAN, "eval.iso10791_a3": BOOLEAN,
    "eval.validation": BOOLEAN, "eval.validation_folds": integer(2, at_most=1000),
    "eval.validation_scheme": choice("auto", "forward", "interleaved"),
    "data.group_jobs": integer(1, at_most=1024),           # processes
    "data.inputs": texts("column names or patterns", unique=True),
    "data.targets": optional(texts("E_ column names", unique=True)),
}

MONITOR_RULES = {f"monitor.{k}": rule for k, rule in {
    "input": choice(None, "-"), "continues": optional(either(text(), integer(0))),
    "adaptive": BOOLEAN, "window": integer(1, at_most=MAX_WINDOW),
    "confirm": integer(1, at_most=MAX_WINDOW), "exclude_at": choice("warning", "alarm"),
    "bands.warning_c": POSITIVE, "bands.alarm_c": POSITIVE, "bands.learned": BOOLEAN,
    "bands.spread_factor": NON_NEGATIVE,
    "pod.energy": number(0.0, 1.0, open_lo=True), "pod.modes": optional(integer(1)),
    "pod.fit_share": optional(POSITIVE), "pod.max_leverage": number(0.0, 1.0, open_lo=True),
    "pod.placement": choice("qr", "covariance"), "detectors.jump_factor": POSITIVE,
    "detectors.freeze_factor": POSITIVE, "detectors.range_margin_c": NON_NEGATIVE,
    "guard.margin": NON_NEGATIVE, "guard.rate_margin": NON_NEGATIVE,
    "map_time_h": optional(NON_NEGATIVE)}.items()}

PROMOTE_RULES = {
    "promote.model_name": text(),
    # MLflow's alias rule: letters, digits, _ and -; not a version (v1) nor 'latest'
    "promote.alias": Rule(lambda v: isinstance(v, str) and re.fullmatch(r"[\w-]+", v) is not None
                          and re.fullmatch(r"[vV]\d+|latest", v) is None,
                          "letters, digits, _ and - (not v<number> nor latest)"),
    "promote.min_improvement": NON_NEGATIVE,   # negative would let a worse candidate replace it
    "promote.force": BOOLEAN, "promote.envelope.margin": NON_NEGATIVE,
    "promote.max_stream_deviation_um": NON_NEGATIVE,
}

EXPORT_RULES = {"export.model": optional(text()),
                "export.format": choice("json", "c", "st", "onnx")}
ADAPT_RULES = {"adapt.method": choice("none", "rls", "bias"), "adapt.every_s": POSITIVE,
               "adapt.forgetting": number(0.0, 1.0, open_lo=True),
               "adapt.max_gain_change": number(0.0, 1.0, open_hi=True),
               "adapt.max_bias_um": NON_NEGATIVE, "adapt.prior_var_gain": NON_NEGATIVE,
               "adapt.prior_var_bias": NON_NEGATIVE}
SERVE_RULES = {"serve.model": text(), "serve.host": text(), "serve.port": integer(1, 65535),
               "serve.timeout_s": POSITIVE, "serve.max_rows": integer(1, 10_000_000),
               "serve.max_body_mb": number(0.0, 4096.0, open_lo=True)}

# twin.drops / twin.restarts: outages of the virtual machine, [[sample, samples], ...]
OUTAGES = Rule(lambda v: all(len(p) == 2 and all(isinstance(x, int) and not isinstance(x, bool)
                                                  and x >= 0 for x in p) for p in v),
               "a list of [sample, samples] pairs of integers >= 0")
TWIN_RULES = {"twin.host": text(), "twin.port": integer(1, 65535),
              "twin.speed": number(0.0, 100_000.0, open_lo=True), "twin.wait_s": NON_NEGATIVE,
              "twin.drops": OUTAGES,
              "twin.restarts": OUTAGES}
CONNECT_RULES = {"connect.endpoint": Rule(lambda v: isinstance(v, str) and v.startswith("opc.tcp://"),
                                          "an opc.tcp://host:port URL"),
                 "connect.model": optional(text()), "connect.hold_s": NON_NEGATIVE,
                 "connect.decay_s": NON_NEGATIVE, "connect.retry_s": POSITIVE,
                 "connect.give_up_s": POSITIVE,
                 **{f"connect.nodes.{k}": text() for k in ("namespace", "input", "offset",
                                                            "offset_sample", "sample", "campaign",
                                                            "campaign_sample", "done")}}

# diagnose.* (its families are the stage's: diagnose.features.KINDS)
DIAGNOSE_RULES = {
    "max_effects": integer(0), "min_gain_pct": NON_NEGATIVE,
    "alpha": number(0.0, 1.0, open_lo=True, open_hi=True), "shortlist": integer(1),
    "cv": choice(*CV_SCHEMES), "n_folds": integer(2), "n_blocks": integer(2),
    "min_train_fraction": number(0.0, 1.0, open_lo=True, open_hi=True), "shrink": BOOLEAN,
    "taus_s": numbers(0.0, open_lo=True, empty=True),        # empty: no lagged effects tried
    "initial_directions": integers(1, empty=True), "n_squares": integer(0),
    "fault_ratio": POSITIVE, "targets": optional(either(text(), texts("targets"))),
    "seed": integer(0, 2 ** 32 - 1),
}


def _position_sets(v) -> bool:
    if not texts()(v):
        return False
    parts = [[p.strip() for p in str(ps).split("+")] for ps in v]
    # each set once: 'S1+S1' measured every S1 pose twice without a word
    return all(p in POSITION_SETS for ps in parts for p in ps) and all(
        len(set(ps)) == len(ps) for ps in parts)


# What each design.* key may be (the machine's order is checked against the set-up later).
DESIGN_RULES = {
    "n_machines": integer(1, at_most=MAX_MACHINES),
    "n_jobs": Rule(lambda v: integer(-MAX_JOBS, MAX_JOBS)(v) and v != 0,
                   f"an integer other than 0, |n_jobs| <= {MAX_JOBS} (-1: every core)"),
    "grid": Rule(lambda v: integers(2)(v) and len(list(v)) == 3 and math.prod(v) <= MAX_GRID,
                 f"3 integers >= 2 (points in X, Y, Z), {MAX_GRID:,} points at most"),
    "x_centres": numbers(0.0, 1.0), "length_mm": optional(POSITIVE),
    "probing_um": optional(UNCERTAINTY), "ball_um": optional(UNCERTAINTY),
    "compensation_order": optional(integer(1, 10)),
}
STUDY_RULES = {
    "n_balls": integers(2, MAX_BALLS),
    "misalignment_deg": Rule(lambda v: numbers(0.0)(v) and all(x < 90 for x in v),
                             "a non-empty list of angles in [0, 90)"),
    "position_sets": Rule(_position_sets, f"a non-empty list of '+'-joined {', '.join(POSITION_SETS)}, "
                                          "each at most once"),
}


def check_keys(cfg: DictConfig, rules: dict) -> None:
    """Every dotted key of ``rules`` in ``cfg`` within its rule (``eval.validation_folds=1:
    must be an integer >= 2``)."""
    for key, rule in rules.items():
        group, _, name = key.rpartition(".")
        check_values({name: OmegaConf.select(cfg, key)}, {name: rule}, group)


def check_monitor(cfg: DictConfig) -> None:
    """Refuse a ``monitor.*`` value the monitor cannot use, before any data is read."""
    check_keys(cfg, MONITOR_RULES)
    m = cfg.monitor
    if m.get("continues") is not None and m.input != "-":
        raise ConfigError(f"monitor.continues={m.continues}: applies to a stream on stdin "
                          "(monitor.input=-); a test campaign's predecessor is its manifest's")
    if m.confirm > m.window:
        raise ConfigError(f"monitor.confirm={m.confirm}: must be <= monitor.window={m.window}")
    if m.bands.alarm_c < m.bands.warning_c:
        raise ConfigError(f"monitor.bands.alarm_c={m.bands.alarm_c}: must be >= "
                          f"monitor.bands.warning_c={m.bands.warning_c}")


def check_design(d: dict) -> None:
    """Refuse a ``design.*`` value the study cannot use, before any work."""
    check_values(d, DESIGN_RULES, "design")
    check_values(d.get("machine") or {}, {"order": optional(integer(1, at_most=12)), "cross_terms": BOOLEAN},
                 "design.machine")
    ranges = d.get("ranges") or {}
    unknown = [k for k in ranges if k not in (*KINDS, "decay")]
    if unknown:
        raise ConfigError(f"design.ranges.{unknown[0]}: not a parameter kind "
                          f"({', '.join(KINDS)}, decay)")
    check_values(ranges, {k: NON_NEGATIVE if k == "decay" else either(NON_NEGATIVE, numbers(0.0))
                          for k in ("decay", *ranges)}, "design.ranges")
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


def check_groups(cfg: DictConfig) -> None:
    """Every group's table, whatever the stage (a group absent from ``cfg`` is skipped)."""
    for group, check in (("monitor", check_monitor),
                         ("promote", lambda c: check_keys(c, PROMOTE_RULES)),
                         ("serve", lambda c: check_keys(c, SERVE_RULES)),
                         ("export", lambda c: check_keys(c, EXPORT_RULES)),
                         ("adapt", lambda c: check_keys(c, ADAPT_RULES)),
                         ("twin", lambda c: check_keys(c, TWIN_RULES)),
                         ("connect", lambda c: check_keys(c, CONNECT_RULES)),
                         ("diagnose", lambda c: check_values(c.diagnose, DIAGNOSE_RULES, "diagnose")),
                         ("design", lambda c: check_design(
                             OmegaConf.to_container(c.design, resolve=True)))):
        if cfg.get(group) is not None:
            check(cfg)


# calibrate.* (the stage, and `run` on a volumetric dataset)
CALIBRATE_KINDS = ("positioning", "straightness", "angular", "cross")
FORMATS = ("parquet", "csv")
CALIBRATE_RULES = {
    "outlier_z": either(POSITIVE, Rule(lambda v: v == math.inf, "inf")),  # inf: fit them as they are
    "column_share": number(0.0, 1.0, open_lo=True), "format": choice(*FORMATS),
    "require_seen": subset(CALIBRATE_KINDS, empty=True),
    "prior": optional(Rule(lambda v: isinstance(v, Mapping) and len(v) > 0,
                           "a range a per kind (as design.ranges: positioning, straightness, "
                           "squareness, angular, cross, decay)")),
}


def check_calibrate(c: DictConfig) -> None:
    """Refuse a ``calibrate.*`` value the stage cannot use, before any data is read."""
    check_values(c, CALIBRATE_RULES, "calibrate")
    prior = c.get("prior")
    if prior is not None:    # a range per kind (decay: one number), or one per Legendre order
        from ...apps.volumetric.calibration import check_prior_kinds

        check_values(prior, {k: NON_NEGATIVE if k == "decay" else either(NON_NEGATIVE, numbers(0.0))
                             for k in prior}, "calibrate.prior")
        # the kinds every machine has (cross only with its cross terms: checked with the model)
        check_prior_kinds(prior, {"positioning", "straightness", "squareness", "angular"})
