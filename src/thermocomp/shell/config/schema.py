"""The config's schema: a dataclass per group, each field a key with its type and its :class:`Rule`.

The YAML in ``conf/`` holds the defaults and says what each key does (its comments); this schema
says what each key may be.  The rule tables every stage checks (:mod:`.rules`) are derived from it
(:func:`rules`), and so are ``--help`` (the types and domains) and the MLflow params and run names
(:data:`NAMING`, :data:`LOGGED`), so a key is declared once.  Keys without a field are read by
their owner's own checks (the ``_target_`` objects' ``param_rules``, ``data.*`` by
``io.ReadOptions``) or not checked.
"""

import dataclasses
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Optional

from ...apps.volumetric.artefact import MAX_BALLS, POSITION_SETS, UNCERTAINTY
from ...base.params import (
    BOOLEAN,
    NON_NEGATIVE,
    POSITIVE,
    Rule,
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
from ...core.choices import MODES, REFERENCES
from ...core.model_selection.schemes import CV_SCHEMES

MAX_WINDOW = 100_000      # monitor.window: samples kept per sensor (1e9 was OOM-killed at 24 GB)
MAX_MACHINES = 10_000     # design.n_machines: 50x the paper's 200 (1e9 ran 211 s, then killed)
MAX_GRID = 1_000_000      # VCE grid points: ~24 MB per machine at most, not a MemoryError
MAX_JOBS = 1024           # worker processes

AUTO_REFERENCE = "auto"   # data.reference: none where test/val campaigns continue others
PLOTS = ("summary", "test", "all", "none")  # `plots=`: which figures a stage draws


# data.sheet: a workbook's sheet by its name (not its number: 2 would be ambiguous)
SHEET = Rule(lambda v: v is None or isinstance(v, str) and v != "",
             "null or a sheet's name (one that reads as a number quoted: data.sheet=\"'2024'\")")


def key(rule: Rule | None = None, *, names: bool = False, logged: bool = False,
        reports: bool = False):
    """A config key checked by ``rule`` (None: by its reader, as ``out`` where it is written).
    How a run records it (:mod:`.naming`): ``names``, it names every run; ``logged``, an MLflow
    param of every run; ``reports``, it says where things go or how much is reported, not what
    is fitted, so it never names a run (any other key does when overridden)."""
    return field(default=None, metadata={"rule": rule, "names": names, "logged": logged,
                                         "reports": reports})


def group(schema: type, *, names: bool = False, unnamed: str | None = None,
          reports: bool = False):
    """A nested group of keys (``monitor.bands``).  ``names``: a config group whose option
    names every run but ``unnamed`` (``select=all``); ``reports`` as :func:`key`'s."""
    return field(default_factory=schema, metadata={"names": names, "unnamed": unnamed,
                                                   "reports": reports})


# twin.drops / twin.restarts: outages of the virtual machine, [[sample, samples], ...]
OUTAGES = Rule(lambda v: all(len(p) == 2 and all(isinstance(x, int) and not isinstance(x, bool)
                                                  and x >= 0 for x in p) for p in v),
               "a list of [sample, samples] pairs of integers >= 0")


def _position_sets(v) -> bool:
    if not texts()(v):
        return False
    parts = [[p.strip() for p in str(ps).split("+")] for ps in v]
    # each set once: 'S1+S1' measured every S1 pose twice without a word
    return all(p in POSITION_SETS for ps in parts for p in ps) and all(
        len(set(ps)) == len(ps) for ps in parts)


@dataclass
class Data:
    path: str = key(logged=True, reports=True)
    sheet: Optional[str] = key(SHEET, logged=True, reports=True)
    interim: str = key(reports=True)
    processed: str = key(reports=True)
    inputs: list = key(texts("column names or patterns", unique=True), logged=True)
    targets: Optional[list] = key(optional(texts("E_ column names", unique=True)), logged=True)
    reference: str = key(choice(*REFERENCES, AUTO_REFERENCE), logged=True)
    group_jobs: int = key(integer(1, at_most=1024))           # processes


@dataclass
class EP95:
    statistic: str = key(choice("range", "std"))
    max_points: Optional[int] = key(optional(integer(2)))  # 0 or 1 window lengths: an empty curve


@dataclass
class Eval:
    mode: str = key(choice(*MODES), names=True, logged=True)
    # the rest scores what was fitted: never a run's name
    e_p95: EP95 = group(EP95, reports=True)
    anova_alpha: float = key(number(0.0, 1.0, open_lo=True, open_hi=True), reports=True)
    mutual_prediction: bool = key(BOOLEAN, reports=True)
    mutual_prediction_max_models: Optional[int] = key(optional(integer(1)), reports=True)
    ati_baselines: bool = key(BOOLEAN, reports=True)
    iso10791_a3: bool = key(BOOLEAN, reports=True)
    validation: bool = key(BOOLEAN, logged=True, reports=True)
    validation_folds: int = key(integer(2, at_most=1000), reports=True)
    validation_scheme: str = key(choice("auto", "forward", "interleaved"), reports=True)


@dataclass
class Bands:
    warning_c: float = key(POSITIVE)
    alarm_c: float = key(POSITIVE)
    learned: bool = key(BOOLEAN)
    spread_factor: float = key(NON_NEGATIVE)


@dataclass
class Pod:
    energy: float = key(number(0.0, 1.0, open_lo=True))
    modes: Optional[int] = key(optional(integer(1)))
    fit_share: Optional[float] = key(optional(POSITIVE))
    max_leverage: float = key(number(0.0, 1.0, open_lo=True))
    placement: str = key(choice("qr", "covariance"))


@dataclass
class Detectors:
    jump_factor: float = key(POSITIVE)
    freeze_factor: float = key(POSITIVE)
    range_margin_c: float = key(NON_NEGATIVE)


@dataclass
class NewState:
    enabled: bool = key(BOOLEAN)
    others: int = key(integer(1, at_most=MAX_WINDOW))


@dataclass
class Guard:
    margin: float = key(NON_NEGATIVE)
    rate_margin: float = key(NON_NEGATIVE)
    new_state_margin: Optional[float] = key(optional(NON_NEGATIVE))
    follow_inputs: bool = key(BOOLEAN)


@dataclass
class Monitor:
    input: Optional[str] = key(choice(None, "-"))
    continues: Optional[Any] = key(optional(either(text(), integer(0))))
    ambient_c: Optional[float] = key(optional(number()))
    adaptive: bool = key(BOOLEAN)
    window: int = key(integer(1, at_most=MAX_WINDOW))
    confirm: int = key(integer(1, at_most=MAX_WINDOW))
    exclude_at: str = key(choice("warning", "alarm"))
    bands: Bands = group(Bands)
    pod: Pod = group(Pod)
    detectors: Detectors = group(Detectors)
    new_state: NewState = group(NewState)
    guard: Guard = group(Guard)
    map_time_h: Optional[float] = key(optional(NON_NEGATIVE))


@dataclass
class Envelope:
    margin: float = key(NON_NEGATIVE)
    pattern: bool = key(BOOLEAN)
    per_target: bool = key(BOOLEAN)


@dataclass
class Promote:
    model_name: str = key(text())
    # MLflow's alias rule: letters, digits, _ and -; not a version (v1) nor 'latest'
    alias: str = key(Rule(lambda v: isinstance(v, str) and re.fullmatch(r"[\w-]+", v) is not None
                          and re.fullmatch(r"[vV]\d+|latest", v) is None,
                          "letters, digits, _ and - (not v<number> nor latest)"))
    min_improvement: float = key(NON_NEGATIVE)   # negative would let a worse candidate replace it
    force: bool = key(BOOLEAN)
    envelope: Envelope = group(Envelope)
    max_stream_deviation_um: float = key(NON_NEGATIVE)


@dataclass
class Export:
    model: Optional[str] = key(optional(text()))
    format: str = key(choice("json", "c", "st", "onnx"))
    check: Optional[bool] = key(optional(BOOLEAN), reports=True)
    campaigns: Optional[list] = key(optional(texts("campaign ids", unique=True)), reports=True)


@dataclass
class Rows:         # `thermocomp rows` (extension, lab78)
    campaigns: Optional[list] = key(optional(texts("campaign ids", unique=True)))
    errors: bool = key(BOOLEAN)


@dataclass
class Adapt:
    method: str = key(choice("none", "rls", "bias"))
    every_s: float = key(POSITIVE)
    forgetting: float = key(number(0.0, 1.0, open_lo=True))
    max_gain_change: float = key(number(0.0, 1.0, open_hi=True))
    max_bias_um: float = key(NON_NEGATIVE)
    prior_var_gain: float = key(NON_NEGATIVE)
    prior_var_bias: float = key(NON_NEGATIVE)


@dataclass
class Serve:
    model: str = key(text())
    host: str = key(text())
    port: int = key(integer(1, 65535))
    timeout_s: float = key(POSITIVE)
    max_rows: int = key(integer(1, 10_000_000))
    max_body_mb: float = key(number(0.0, 4096.0, open_lo=True))


@dataclass
class Twin:
    host: str = key(text())
    port: int = key(integer(1, 65535))
    speed: float = key(number(0.0, 100_000.0, open_lo=True))
    wait_s: float = key(NON_NEGATIVE)
    lockstep: bool = key(BOOLEAN)
    drops: list = key(OUTAGES)
    restarts: list = key(OUTAGES)
    campaigns: Optional[list] = key(optional(texts("test campaign ids", unique=True)))


# connect.nodes.inputs / offsets: {name: node id}
NODE_MAP = Rule(lambda v: isinstance(v, Mapping) and all(
    isinstance(n, str) and n.strip() for n in v.values()), "a map of names to node ids")

UNIT_MAP = Rule(lambda v: isinstance(v, Mapping) and len(v) > 0 and all(POSITIVE(u) for u in v.values()),
                "a map of targets to numbers > 0")


@dataclass
class Nodes:
    namespace: str = key(text())
    input: str = key(text())
    offset: str = key(text())
    # (opcua67) a vendor's server has none of the twin's status nodes: null, absent
    offset_sample: Optional[str] = key(optional(text()))
    sample: Optional[str] = key(optional(text()))
    campaign: Optional[str] = key(optional(text()))
    campaign_sample: Optional[str] = key(optional(text()))
    done: Optional[str] = key(optional(text()))
    reference: str = key(text())
    inputs: Optional[dict] = key(optional(NODE_MAP))      # column -> node id, over `input`
    offsets: Optional[dict] = key(optional(NODE_MAP))     # target -> node id, over `offset`
    # µm per unit of the offset nodes: one for all, or {target: µm} (1 for one not named)
    offset_unit_um: Any = key(either(POSITIVE, UNIT_MAP))


@dataclass
class Connect:
    endpoint: str = key(Rule(lambda v: isinstance(v, str) and v.startswith("opc.tcp://"),
                             "an opc.tcp://host:port URL"))
    model: Optional[str] = key(optional(text()))
    hold_s: float = key(NON_NEGATIVE)
    decay_s: float = key(NON_NEGATIVE)
    retry_s: float = key(POSITIVE)
    give_up_s: float = key(POSITIVE)
    warm: Optional[str] = key(optional(text()))
    clock: str = key(choice("node", "server"))            # (opcua67) a sample's time
    period_s: Optional[float] = key(optional(POSITIVE))   # (opcua67) null: the model's period
    user: Optional[str] = key(optional(text()))           # (opcua67) its password: in the env
    nodes: Nodes = group(Nodes)


@dataclass
class Diagnose:      # its families are the stage's (diagnose.features.KINDS): checked there
    max_effects: int = key(integer(0))
    min_gain_pct: float = key(NON_NEGATIVE)
    alpha: float = key(number(0.0, 1.0, open_lo=True, open_hi=True))
    shortlist: int = key(integer(1))
    cv: str = key(choice(*CV_SCHEMES))
    n_folds: int = key(integer(2))
    n_blocks: int = key(integer(2))
    min_train_fraction: float = key(number(0.0, 1.0, open_lo=True, open_hi=True))
    shrink: bool = key(BOOLEAN)
    taus_s: list = key(numbers(0.0, open_lo=True, empty=True))     # empty: no lagged effects tried
    initial_directions: list = key(integers(1, empty=True))
    n_squares: int = key(integer(0))
    fault_ratio: float = key(POSITIVE)
    targets: Optional[Any] = key(optional(either(text(), texts("targets"))))
    seed: int = key(integer(0, 2 ** 32 - 1))


@dataclass
class Machine:
    order: Optional[int] = key(optional(integer(1, at_most=12)))
    cross_terms: bool = key(BOOLEAN)


@dataclass
class Design:        # its ranges and studies are maps of names: checked by rules.RELATIONS
    n_machines: int = key(integer(1, at_most=MAX_MACHINES))
    n_jobs: int = key(Rule(lambda v: integer(-MAX_JOBS, MAX_JOBS)(v) and v != 0,
                           f"an integer other than 0, |n_jobs| <= {MAX_JOBS} (-1: every core)"))
    grid: list = key(Rule(lambda v: integers(2)(v) and len(list(v)) == 3 and math.prod(v) <= MAX_GRID,
                          f"3 integers >= 2 (points in X, Y, Z), {MAX_GRID:,} points at most"))
    x_centres: list = key(numbers(0.0, 1.0))
    length_mm: Optional[float] = key(optional(POSITIVE))
    probing_um: Optional[float] = key(optional(UNCERTAINTY))
    ball_um: Optional[float] = key(optional(UNCERTAINTY))
    compensation_order: Optional[int] = key(optional(integer(1, 10)))
    machine: Machine = group(Machine)


@dataclass
class Study:         # one of design.studies
    n_balls: list = key(integers(2, MAX_BALLS))
    misalignment_deg: list = key(Rule(lambda v: numbers(0.0)(v) and all(x < 90 for x in v),
                                      "a non-empty list of angles in [0, 90)"))
    position_sets: list = key(Rule(_position_sets, f"a non-empty list of '+'-joined "
                                                   f"{', '.join(POSITION_SETS)}, each at most once"))


CALIBRATE_KINDS = ("positioning", "straightness", "angular", "cross")


@dataclass
class Calibrate:     # calibrate.* (the stage, and `run` on a volumetric dataset)
    outlier_z: float = key(either(POSITIVE, Rule(lambda v: v == math.inf, "inf")))  # inf: none left out
    column_share: float = key(number(0.0, 1.0, open_lo=True))
    format: str = key(choice("parquet", "csv"))
    require_seen: list = key(subset(CALIBRATE_KINDS, empty=True))
    prior: Optional[dict] = key(optional(Rule(
        lambda v: isinstance(v, Mapping) and len(v) > 0,
        "a range a per kind (as design.ranges: positioning, straightness, squareness, angular, "
        "cross, decay)")))


@dataclass
class Compare:       # compare.descending and compare.target: checked by the stage
    pass


@dataclass
class Replay:        # replay.model: checked where it is loaded
    cold_start: bool = key(BOOLEAN, reports=True)


@dataclass
class Group:
    """A config group chosen by name (``model=arx``): its ``name`` names the run unless it is
    ``default`` (the model always does), and is always logged."""

    name: str = key(logged=True)


@dataclass
class Root:
    name: str = key(file_name(), logged=True, reports=True)
    seed: int = key(names=True, logged=True)      # checked first of all (cli._check_seed)
    out: str = key(logged=True, reports=True)
    model_path: str = key(reports=True)
    tracking_uri: str = key(reports=True)         # checked by store.store_uri
    experiment_name: str = key(reports=True)
    track: Optional[bool] = key(optional(BOOLEAN), reports=True)
    plots: str = key(choice(*PLOTS), reports=True)
    data: Data = group(Data)
    eval: Eval = group(Eval)
    model: Group = group(Group, names=True)               # every option names a run
    select: Group = group(Group, names=True, unnamed="all")   # but the default ones
    ati: Group = group(Group, names=True, unnamed="none")
    denoise: Group = group(Group, names=True, unnamed="none")
    compare: Compare = group(Compare, reports=True)
    promote: Promote = group(Promote, reports=True)
    replay: Replay = group(Replay, reports=True)
    serve: Serve = group(Serve, reports=True)
    monitor: Monitor = group(Monitor)
    export: Export = group(Export)
    rows: Rows = group(Rows)
    adapt: Adapt = group(Adapt)
    twin: Twin = group(Twin)
    connect: Connect = group(Connect)
    diagnose: Diagnose = group(Diagnose)
    design: Design = group(Design)
    calibrate: Calibrate = group(Calibrate)


def fields(schema: type = Root, prefix: str = ""):
    """``(dotted key, dataclass field)`` of every key of ``schema``, nested groups flattened."""
    for f in dataclasses.fields(schema):
        name = f"{prefix}{f.name}"
        if f.default_factory is not dataclasses.MISSING:
            yield from fields(f.default_factory, f"{name}.")
        else:
            yield name, f


def rules(schema: type, prefix: str = "") -> dict[str, Rule]:
    """``{dotted key: rule}`` of ``schema`` (its keys under ``prefix``)."""
    return {name: f.metadata["rule"] for name, f in fields(schema, prefix)
            if f.metadata["rule"] is not None}


def part(name: str) -> type:
    """The schema of the root's group ``name``."""
    return next(f.default_factory for f in dataclasses.fields(Root) if f.name == name)
