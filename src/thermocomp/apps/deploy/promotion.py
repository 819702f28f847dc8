"""What ``thermocomp promote`` knows and decides of a candidate, registry aside (pure where it
decides: plain values in, checks, tags and the report out).

The shell reads runs and the registry (``shell/registry.py``) and writes tags;
the champion decision itself is :mod:`thermocomp.core.scoring.champion`.  The steps:

1. The candidate is ``promote.run_id``, or the best child of the sweep
   ``compare.sweep`` (default: the latest) by ``promote.criterion``, a
   validation figure (``val_*``; a test figure is refused), among the children
   scored on ``data.path`` (their ``dataset_hash`` tag): a dataset no child
   was scored on is refused, naming the hashes the sweep saw.
2. Its ``model.pkl`` (signature checked before unpickling: a tracking server
   may have no authentication) becomes a deployable :class:`~thermocomp.apps.deploy.StreamingCompensator`
   (training envelope from the train split of ``data.path``), checked to stream
   exactly as it predicts in batch (causality; the plain stream, envelope off).
   With ``monitor.adaptive`` (default) what is registered is the
   :class:`~thermocomp.apps.deploy.AdaptiveCompensator` of the ``monitor`` group
   around it (POD, detectors and guard fitted on the train split: missing or
   faulty sensors, bad times, bounded correction); ``monitor.adaptive=false``
   registers the plain streaming compensator.  It is registered as an
   ``mlflow.pyfunc`` model with a signature: a new version of ``promote.model_name``,
   tagged with the dataset hash, git commit, what was deployed (``adaptive``,
   ``deploy_config``), its validation figures (from its run's ``metrics.json``)
   and its test figures (streamed per test campaign as deployed, from a reset
   or, for a campaign that continues others, warmed on them: reported, never
   used to decide; ``promote.json`` adds, per target, the test rows whose correction the
   guard changed, and the test figures of each test campaign streamed from a reset at its
   first row, as a controller powered on there: ``test_reported_cold_start``; and, as
   ``replay.json``, ``lead_in_events``: what the sensor monitor did while a test campaign's
   stream was warmed on the campaigns it continues).
3. The gate compares validation scores on the same dataset: the candidate's
   against the one the champion was promoted with, when the champion's
   ``dataset_hash``, ``criterion_target`` and ``validation_mode`` tags match
   (``eval_mode`` for a champion tagged before ``validation_mode`` existed).  The
   alias moves only if the candidate beats it by more than
   ``promote.min_improvement``; a champion with no comparable validation score
   stays unless ``promote.force``.  No registry stages (deprecated): aliases
   and tags only.
4. Idempotent: a candidate already registered on this dataset and deployed the
   same way (``deploy_config``: adaptive or not, the ``monitor`` group, the
   envelope, ``adapt`` when it learns) -- the same run, the same model bytes ``model_digest``, or the
   champion's figures -- gets no new version; promoting the champion again says
   ``already champion: version N``.

Writes ``<out>/promote.json``.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from ...base.errors import ConfigError
from ...base.paths import resolve
from ...core.scoring.champion import check_stream_deviation, same_deployment, same_figures, tag_value
from ...core.scoring.evaluation import require_split, sample_period
from ...core.scoring.leaderboard import is_validation, summary
from .report import summary as deployed_summary
from .streaming import end_states, stream_scores, streaming_deviation

# the monitor stage's own keys: not part of what the adaptive compensator is built from
MONITOR_STAGE_KEYS = ("model", "input", "map_time_h")


@dataclass
class Candidate:
    """What promote knows of the candidate once it is scored and wrapped for deployment."""

    run_id: str
    run_params: dict
    digest: str
    score: float
    mode: str
    val_mode: str
    basis: dict
    val_figures: dict
    figures: dict = field(default_factory=dict)
    test_figures: dict = field(default_factory=dict)
    # the same test figures with each test campaign streamed from a reset at its first row (a
    # controller powered on there), and the test campaigns that continue others (none: one stream)
    test_figures_cold: dict = field(default_factory=dict)
    cold_start_campaigns: list = field(default_factory=list)
    # per target, the test rows whose correction the guard changed (None: the plain stream)
    test_guarded: dict | None = None
    test_samples: int = 0
    # the test rows with an input clamped to the envelope / excluded by the sensor monitor
    test_clamped: int = 0
    test_excluded: int = 0
    # what the sensor monitor did while a test campaign's stream was warmed (replay's, deploy88b)
    lead_in_events: list = field(default_factory=list)
    deviation: float = 0.0
    deployed: object = None
    streaming: object = None
    kind: dict = field(default_factory=dict)
    deploy_key: str = ""


def deploy_key(adaptive: bool, monitor: Mapping | None, envelope: Mapping,
               adapt: Mapping | None = None) -> str:
    """SHA-256 (12 hex) of what makes the deployed object from a fitted model: adaptive or
    not, the ``monitor`` settings it is built with, the envelope and, when it learns from
    reference measurements (``adapt.method`` not ``none``), the ``adapt`` settings the served
    model keeps (its ``every_s`` schedule is replay's, not the served model's).  A frozen
    deployment hashes as before ``adapt`` was part of it, so its versions are still found."""
    kept = ({k: v for k, v in monitor.items() if k not in MONITOR_STAGE_KEYS}
            if adaptive else None)
    spec = {"adaptive": bool(adaptive), "monitor": kept, "envelope": dict(envelope)}
    if adapt and adapt.get("method", "none") != "none":
        # without it a run promoted frozen and then with adapt.method=bias was "already
        # registered": the champion served and exported without the learning asked for
        spec["adapt"] = {k: v for k, v in adapt.items() if k != "every_s"}
    return hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()[:12]


def figures_of(targets: Mapping, target: str) -> dict:
    """The leaderboard figures of ``targets`` for ``promote.target``."""
    try:
        return summary(targets, target)
    except KeyError as exc:
        raise ConfigError(f"promote.target: {exc.args[0]}") from None


def validation_figures(metrics: Mapping | None, run_id: str, criterion: str, target: str
                       ) -> tuple[float, dict]:
    """(score by ``criterion``, validation figures) of a run's ``metrics.json``."""
    if not metrics or "targets" not in metrics:
        raise ConfigError(f"run {run_id} has no metrics.json: promote a `run` or `evaluate` run")
    figures = {k: v for k, v in figures_of(metrics["targets"], target).items() if is_validation(k)}
    score = figures[criterion]
    if score is None:
        raise ConfigError(f"run {run_id} has no {criterion} (made with "
                          f"eval.validation=false?): rerun it with eval.validation=true")
    return score, figures


def check_dataset(tags: Mapping, params: Mapping, run_id: str, dataset_hash: str, data_path) -> None:
    """Refuse a dataset the candidate was not scored on (its ``dataset_hash`` tag, else its
    ``data.path`` param for runs made before the tag existed)."""
    seen = tags.get("dataset_hash")
    if seen is not None:
        if seen != dataset_hash:
            raise ConfigError(f"data.path={data_path} (dataset {dataset_hash[:12]}) is not the "
                              f"dataset run {run_id} was scored on (dataset {seen[:12]}): promote "
                              f"it with that data.path")
        return
    trained_on = params.get("data.path")
    if trained_on and resolve(trained_on) != data_path:
        raise ConfigError(f"run {run_id} was trained and validated on data.path={trained_on}, "
                          f"not {data_path}: promote it with that data.path")


def find_registered(champion, versions: Callable[[], list], cand: Candidate, dataset_hash: str):
    """The version that already holds this candidate, or None: a champion deployed the same
    way on the same dataset whose tagged figures (validation and test) equal the candidate's;
    else, of ``versions()`` (asked only then), one deployed the same way on the same dataset
    from the same run or the same model bytes."""
    if champion is not None and same_deployment(champion.tags, dataset_hash, cand.deploy_key) \
            and same_figures(champion.tags, cand.figures):
        return champion
    for v in sorted(versions(), key=lambda v: int(v.version)):
        tags = v.tags or {}
        if same_deployment(tags, dataset_hash, cand.deploy_key) and (
                tags.get("source_run_id") == cand.run_id or tags.get("model_digest") == cand.digest):
            return v
    return None


def deploy(cand: Candidate, comp, ds, *, stream_of: Callable, deployed_of: Callable,
           leads: Mapping, max_deviation_um: float, e_p95: tuple, target: str,
           deploy_config: str, adapt_of: Callable = lambda n_targets: None) -> None:
    """Wrap the model as deployed (causality gate first: the plain stream, envelope off, no
    monitor) and stream the test split through it (``cand`` filled in).

    ``stream_of(train)`` makes the plain stream, ``deployed_of(streaming, train)`` what is
    registered; ``leads`` warms the campaigns that continue others; ``e_p95`` is
    ``(statistic, max_points)``; ``adapt_of(n_targets)`` the scheduled adaptation the deployed
    model learns with (``adapt.method``; None: frozen), in the test figures as ``replay``'s."""
    train_ids, test_ids = require_split(ds, "train"), require_split(ds, "test")
    train = {c: ds.campaigns[c] for c in train_ids}
    cand.streaming = stream_of(train)
    cand.deviation = max(streaming_deviation(cand.streaming, ds.campaigns[c], lead_in=leads.get(c))
                         for c in train_ids[:2])
    check_stream_deviation(cand.deviation, max_deviation_um, cand.run_id)
    cand.deployed = deployed_of(cand.streaming, train)
    # where each campaign leaves the stream: a served campaign may continue it (``continues``)
    cand.deployed.end_states_ = end_states(
        cand.deployed, {c: ds.campaigns[c] for c in train_ids + test_ids}, leads)
    cand.kind, cand.deploy_key = deployed_summary(cand.deployed), deploy_config
    test = {c: ds.campaigns[c] for c in test_ids}
    # the test figures, as deployed: reported beside the validation ones, never used to decide
    scores = stream_scores(cand.deployed, test, sample_period(ds, test_ids), *e_p95, leads,
                           adapt=adapt_of(len(cand.deployed.targets_)))
    cand.test_figures = {k: v for k, v in figures_of(scores, target).items() if not is_validation(k)}
    # a machine powered off between its campaigns starts the next one cold: the same figures
    # from a reset at each test campaign's first row, beside the continued ones (deploy88)
    cand.cold_start_campaigns = [c for c in test_ids if c in leads]
    cand.test_figures_cold = cand.test_figures if not cand.cold_start_campaigns else {
        k: v for k, v in figures_of(stream_scores(
            cand.deployed, test, sample_period(ds, test_ids), *e_p95,
            adapt=adapt_of(len(cand.deployed.targets_))), target).items() if not is_validation(k)}
    # why "as deployed" leaves run's test figure with no input clamped (guard70, as replay says it)
    guarded = {t: s["guarded_samples"] for t, s in scores.items()}
    cand.test_guarded = None if None in guarded.values() else guarded
    cand.test_samples = sum(len(df) for df in test.values())
    first = next(iter(scores.values()), {})
    cand.test_clamped, cand.test_excluded = first.get("clamped_samples", 0), first.get(
        "excluded_samples", 0)
    cand.lead_in_events = first.get("lead_in_events", [])
    cand.figures = {**cand.val_figures, **cand.test_figures}


def version_tags(cand: Candidate, ds, *, dataset_hash: str, commit: tuple[str, bool],
                 criterion: str, target: str, policy: str, outputs: list[str]) -> dict:
    """What a new version is and where it comes from (``commit``: (hash, dirty))."""
    params, kind = cand.run_params, cand.kind
    tags = {"dataset_hash": dataset_hash, "dataset": ds.name, "git_commit": commit[0],
            "git_dirty": commit[1], "source_run_id": cand.run_id, "model_digest": cand.digest,
            "model": params.get("model.name"), "select": params.get("select.name"),
            "criterion": criterion, "criterion_target": target,
            "eval_mode": cand.mode, "validation_mode": cand.val_mode,
            "test_campaigns": ",".join(require_split(ds, "test")),
            "train_campaigns": ",".join(require_split(ds, "train")),
            "envelope_policy": policy,
            "stream_deviation_um": f"{cand.deviation:.3g}", "outputs": ",".join(outputs),
            "adaptive": kind["adaptive"], "deploy_config": cand.deploy_key,
            "pod_modes": "none" if kind["pod"] is None else kind["pod"]["n_modes"]}
    return {**tags, **{f"metric.{k}": tag_value(v) for k, v in cand.figures.items()}}


@dataclass
class Outcome:
    """What the registry transaction decided."""

    version: str
    registered: bool
    champion_version: str | None
    champion_score: float | None
    moved: bool
    why: str


def promote_report(cand: Candidate, outcome: Outcome, *, name: str, alias: str,
                   criterion: str) -> dict:
    """``promote.json``."""
    o = outcome
    return {"model_name": name, "alias": alias, "version": o.version, "run_id": cand.run_id,
            "moved": o.moved, "registered": o.registered, "reason": o.why,
            "criterion": criterion, "ranked_by": cand.basis,
            "candidate": {"score": cand.score, "figures": cand.figures,
                          "validation": cand.val_figures, "test_reported": cand.test_figures,
                          "test_reported_cold_start": cand.test_figures_cold,
                          "cold_start_campaigns": cand.cold_start_campaigns,
                          "test_rows_guarded": cand.test_guarded,
                          "test_rows_clamped": cand.test_clamped,
                          "test_rows_excluded": cand.test_excluded,
                          **({"lead_in_events": cand.lead_in_events} if cand.lead_in_events else {})},
            "champion": None if o.champion_version is None else {"version": o.champion_version,
                                                                 "score": o.champion_score},
            "stream_deviation_um": cand.deviation, "model_uri": f"models:/{name}/{o.version}",
            "adaptive": cand.kind["adaptive"], "pod": cand.kind["pod"],
            "continuable": sorted(cand.deployed.end_states_)}
