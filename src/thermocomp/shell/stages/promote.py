"""`thermocomp promote`: register a run's compensator, move ``champion`` only if it is better.

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
   used to decide).
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
   envelope) -- the same run, the same model bytes ``model_digest``, or the
   champion's figures -- gets no new version; promoting the champion again says
   ``already champion: version N``.

Writes ``<out>/promote.json``.
"""

from __future__ import annotations

import hashlib
import json
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from omegaconf import DictConfig, OmegaConf

from ...apps.deploy import POLICIES, stream_scores, streaming_deviation
from ...apps.deploy.report import summary as deployed_summary
from ...apps.deploy.streaming import end_states
from ...base import signing
from ...base.errors import ConfigError
from ...base.files import folder_digest, write_json
from ...base.log import logger, say
from ...base.params import choice
from ...base.paths import project_root, resolve
from ...core import io
from ...core.compensator import Compensator
from ...core.continuation import lead_ins
from ...core.scoring.champion import (
    champion_validation,
    check_criterion,
    check_stream_deviation,
    decide,
    fmt,
    outcome_line,
    same_deployment,
    same_figures,
    tag_value,
)
from ...core.scoring.evaluation import require_split, sample_period
from ...core.scoring.leaderboard import (
    DEPLOYED_MODE,
    is_validation,
    rank,
    ranked_by,
    ranking_line,
    summary,
    validation_mode,
)
from ..store import registry_lock
from ..sweeps import parent_run_id, run_metrics, sweep_rows
from ..tracking import DATASET_TAG, child_runs, connect, retry_locked
from ..tracking import client as mlflow_client
from .builders import deploy_stream, deployable
from .common import check_config, check_keys, data_options

# The plain promote.* keys are checked by every stage (rules.PROMOTE_RULES); the envelope's
# policies are the deployment's own.
POLICY_RULE = {"promote.envelope.policy": choice(*POLICIES)}


def git_commit() -> tuple[str, bool]:
    """(commit of the project checkout or 'unknown', whether the tree has local changes)."""
    def git(*args):
        return subprocess.run(["git", "-C", str(project_root()), *args], capture_output=True,
                              text=True, timeout=30)
    try:
        head = git("rev-parse", "HEAD")
        if head.returncode != 0:
            return "unknown", False
        dirty = bool(git("status", "--porcelain", "--untracked-files=no").stdout.strip())
        return head.stdout.strip(), dirty
    except (OSError, subprocess.SubprocessError):
        return "unknown", False


def _best_run(cfg: DictConfig, client, uri: str, dataset_hash: str, data_path) -> tuple[str, dict]:
    """The best finished child of the sweep among those scored on this dataset, by its
    simulation-mode validation, and what ranked (:func:`~thermocomp.core.scoring.leaderboard.ranked_by`)."""
    parent = parent_run_id(cfg, client)
    seen = {r.info.run_id: r.data.tags.get(DATASET_TAG) for r in child_runs(client, parent)}
    if seen and dataset_hash not in seen.values():
        hashes = ", ".join(sorted({(h or "none")[:12] for h in seen.values()}))
        raise ConfigError(f"data.path={data_path} (dataset {dataset_hash[:12]}) was not scored by "
                          f"any run of sweep {parent} (datasets seen: {hashes}); promote with "
                          f"the data.path the sweep ran on")
    rows = [r for r in sweep_rows(client, uri, parent, str(cfg.promote.target))
            if r["status"] == "FINISHED" and seen.get(r["run_id"]) in (dataset_hash, None)]
    if not rows:
        raise ConfigError(f"sweep {parent} has no finished child run to promote")
    try:
        table = rank(rows, str(cfg.promote.criterion))
    except KeyError as exc:
        raise ConfigError(f"promote.criterion: {exc.args[0]}") from None
    basis = ranked_by(table, str(cfg.promote.criterion))
    say(f"sweep {parent}: {len(table)} finished run(s) ranked by {ranking_line(basis)}")
    return str(table["run_id"].iloc[0]), basis


def _load_run_model(run_id: str, uri: str) -> tuple[Compensator, str]:
    """The run's compensator and the SHA-256 of its pickle; the signature is checked before
    anything is unpickled (a tracking server may not be trusted)."""
    import mlflow

    with tempfile.TemporaryDirectory() as tmp:
        try:
            path = mlflow.artifacts.download_artifacts(run_id=run_id, artifact_path="model.pkl",
                                                       dst_path=tmp, tracking_uri=uri)
        except Exception as exc:
            raise ConfigError(f"run {run_id} has no model.pkl artifact (promote a `run` or "
                              f"`train` run): {' '.join(str(exc).split())[:200]}") from None
        try:
            mlflow.artifacts.download_artifacts(run_id=run_id, artifact_path="model.pkl.sig",
                                                dst_path=tmp, tracking_uri=uri)
        except Exception:  # verified_bytes says "not signed by this project"
            pass
        digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()
        return signing.load(path, Compensator), digest


def _figures(targets: dict, cfg: DictConfig) -> dict:
    try:
        return summary(targets, str(cfg.promote.target))
    except KeyError as exc:
        raise ConfigError(f"promote.target: {exc.args[0]}") from None


def _validation_score(run_id: str, uri: str, cfg: DictConfig) -> tuple[float, dict, str, str]:
    """The candidate's validation figures from its run's ``metrics.json``, in simulation mode
    where it has them: (score, figures, the run's eval.mode, the figures' mode)."""
    metrics = run_metrics(run_id, uri)
    if not metrics or "targets" not in metrics:
        raise ConfigError(f"run {run_id} has no metrics.json: promote a `run` or `evaluate` run")
    figures = {k: v for k, v in _figures(metrics["targets"], cfg).items() if is_validation(k)}
    score = figures[str(cfg.promote.criterion)]
    if score is None:
        raise ConfigError(f"run {run_id} has no {cfg.promote.criterion} (made with "
                          f"eval.validation=false?): rerun it with eval.validation=true")
    return score, figures, str(metrics.get("mode", DEPLOYED_MODE)), validation_mode(metrics)


def _current_champion(client, name: str, alias: str):
    try:
        return retry_locked(client.get_model_version_by_alias, name, alias)
    except Exception:  # no registered model yet, or no version holds the alias
        return None


def _check_dataset(run, run_id: str, dataset_hash: str, data_path) -> None:
    """Refuse a dataset the candidate was not scored on (its ``dataset_hash`` tag, else its
    ``data.path`` param for runs made before the tag existed)."""
    seen = run.data.tags.get(DATASET_TAG)
    if seen is not None:
        if seen != dataset_hash:
            raise ConfigError(f"data.path={data_path} (dataset {dataset_hash[:12]}) is not the "
                              f"dataset run {run_id} was scored on (dataset {seen[:12]}): promote "
                              f"it with that data.path")
        return
    trained_on = run.data.params.get("data.path")
    if trained_on and resolve(trained_on) != data_path:
        raise ConfigError(f"run {run_id} was trained and validated on data.path={trained_on}, "
                          f"not {data_path}: promote it with that data.path")


def deploy_config(cfg: DictConfig) -> str:
    """SHA-256 (12 hex) of what makes the deployed object from a fitted model: adaptive or
    not, the ``monitor`` settings it is built with, the envelope."""
    adaptive = bool(cfg.monitor.adaptive)
    monitor = None
    if adaptive:  # the keys the adaptive compensator is built from (not the monitor stage's own)
        monitor = {k: v for k, v in OmegaConf.to_container(cfg.monitor, resolve=True).items()
                   if k not in ("model", "input", "map_time_h")}
    spec = {"adaptive": adaptive, "monitor": monitor,
            "envelope": OmegaConf.to_container(cfg.promote.envelope, resolve=True)}
    return hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()[:12]



def _registered(client, name: str, run_id: str, digest: str, dataset_hash: str, champion,
                figures: dict, deployed: str):
    """The version that already holds this candidate, or None.

    Deployed the same way (``deployed``: :func:`deploy_config`) on the same
    dataset: the same run, or the same model bytes; or a champion whose figures
    (validation and test, as tagged) equal the candidate's.
    """
    if champion is not None and same_deployment(champion.tags, dataset_hash, deployed) \
            and same_figures(champion.tags, figures):
        return champion
    try:
        versions = retry_locked(client.search_model_versions, f"name='{name}'")
    except Exception:  # no registered model yet
        return None
    for v in sorted(versions, key=lambda v: int(v.version)):
        tags = v.tags or {}
        if same_deployment(tags, dataset_hash, deployed) and (
                tags.get("source_run_id") == run_id or tags.get("model_digest") == digest):
            return v
    return None


@dataclass
class _Candidate:
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
    deviation: float = 0.0
    deployed: object = None
    streaming: object = None
    kind: dict = field(default_factory=dict)
    deploy_key: str = ""


def _candidate(cfg: DictConfig, client, uri: str, data_path, dataset_hash: str) -> tuple:
    """The candidate run, checked against the dataset, with its model and validation score."""
    import mlflow

    opts, criterion = cfg.promote, str(cfg.promote.criterion)
    run_id, basis = ((str(opts.run_id), None) if opts.get("run_id")
                     else _best_run(cfg, client, uri, dataset_hash, data_path))
    say(f"candidate run {run_id}")
    try:
        run = retry_locked(client.get_run, run_id)
    except mlflow.exceptions.MlflowException as exc:
        raise ConfigError(f"promote.run_id={run_id}: no such run in {uri} "
                          f"({' '.join(str(exc).split())[:120]})") from None
    _check_dataset(run, run_id, dataset_hash, data_path)
    comp, digest = _load_run_model(run_id, uri)
    score, val_figures, mode, val_mode = _validation_score(run_id, uri, cfg)
    basis = basis or {"figure": criterion, "mode": DEPLOYED_MODE, "fallback": {}}
    say(f"run {run_id}: {criterion} {fmt(score)} of its {val_mode}-mode validation (scored "
        f"in {mode}; the deployed compensator runs in {DEPLOYED_MODE})")
    if val_mode != DEPLOYED_MODE:
        basis["fallback"][run_id] = val_mode
        logger.warning("run %s has no %s-mode validation (scored in %s before it was recorded): "
                       "its %s validation decides; rerun it to choose by the deployed mode",
                       run_id, DEPLOYED_MODE, val_mode, val_mode)
    return comp, _Candidate(run_id, dict(run.data.params), digest, score, mode, val_mode, basis,
                            val_figures)


def _deploy(cfg: DictConfig, comp: Compensator, ds, cand: _Candidate) -> None:
    """Wrap the model as deployed (causality gate first) and stream the test split through it."""
    train_ids, test_ids = require_split(ds, "train"), require_split(ds, "test")
    train = {c: ds.campaigns[c] for c in train_ids}
    cand.streaming = deploy_stream(cfg, comp, train, f"run {cand.run_id}")
    # causality is a property of the plain stream (envelope off, no monitor), checked before wrapping
    leads = lead_ins(comp, ds, train_ids + test_ids)   # continuing campaigns start warmed
    cand.deviation = max(streaming_deviation(cand.streaming, ds.campaigns[c], lead_in=leads.get(c))
                         for c in train_ids[:2])
    check_stream_deviation(cand.deviation, float(cfg.promote.max_stream_deviation_um), cand.run_id)
    cand.deployed = deployable(cfg, cand.streaming, train, ds)   # what the pyfunc holds
    # where each campaign leaves the stream: a served campaign may continue it (``continues``)
    cand.deployed.end_states_ = end_states(
        cand.deployed, {c: ds.campaigns[c] for c in train_ids + test_ids}, leads)
    cand.kind, cand.deploy_key = deployed_summary(cand.deployed), deploy_config(cfg)
    test = {c: ds.campaigns[c] for c in test_ids}
    dt = sample_period(ds, test_ids)
    # the test figures, as deployed: reported beside the validation ones, never used to decide
    scores = stream_scores(cand.deployed, test, dt, cfg.eval.e_p95.statistic,
                           cfg.eval.e_p95.max_points, leads)
    cand.test_figures = {k: v for k, v in _figures(scores, cfg).items() if not is_validation(k)}
    cand.figures = {**cand.val_figures, **cand.test_figures}


def _new_version_tags(cfg: DictConfig, cand: _Candidate, ds, dataset_hash: str) -> dict:
    """What a new version is and where it comes from."""
    from ...apps.deploy.pyfunc import REPORT_COLUMNS, correction_column

    opts, params, kind = cfg.promote, cand.run_params, cand.kind
    commit, dirty = git_commit()
    outputs = ([correction_column(t) for t in cand.streaming.targets_] + ["n_clamped"]
               + (list(REPORT_COLUMNS) if kind["adaptive"] else []))
    tags = {"dataset_hash": dataset_hash, "dataset": ds.name, "git_commit": commit,
            "git_dirty": dirty, "source_run_id": cand.run_id, "model_digest": cand.digest,
            "model": params.get("model.name"), "select": params.get("select.name"),
            "criterion": str(opts.criterion), "criterion_target": str(opts.target),
            "eval_mode": cand.mode, "validation_mode": cand.val_mode,
            "test_campaigns": ",".join(require_split(ds, "test")),
            "train_campaigns": ",".join(require_split(ds, "train")),
            "envelope_policy": str(opts.envelope.policy),
            "stream_deviation_um": f"{cand.deviation:.3g}", "outputs": ",".join(outputs),
            "adaptive": kind["adaptive"], "deploy_config": cand.deploy_key,
            "pod_modes": "none" if kind["pod"] is None else kind["pod"]["n_modes"]}
    return {**tags, **{f"metric.{k}": tag_value(v) for k, v in cand.figures.items()}}


def _register(cfg: DictConfig, client, uri: str, cand: _Candidate, ds, dataset_hash: str):
    """One transaction: read the champion, register, decide, tag, move the alias; a second
    promote waits here and then compares against what this one decided."""
    from ...apps.deploy.pyfunc import log_compensator

    opts, name, alias = cfg.promote, str(cfg.promote.model_name), str(cfg.promote.alias)
    with registry_lock(uri):
        champion = _current_champion(client, name, alias)
        existing = _registered(client, name, cand.run_id, cand.digest, dataset_hash, champion,
                               cand.figures, cand.deploy_key)
        champ_score, champ_note = None, None
        if champion is not None:
            champ_score, champ_note = champion_validation(
                champion.tags, str(opts.criterion), str(opts.target), dataset_hash, cand.val_mode)
        if existing is not None:
            version = str(existing.version)
        else:
            test = ds.campaigns[require_split(ds, "test")[0]]
            example = test[cand.streaming.columns_ + ["time"]].head(5)
            # into the run without resuming it: a killed promote leaves its status alone
            info = log_compensator(cand.deployed, input_example=example,
                                   registered_model_name=name, run_id=cand.run_id)
            version = str(info.registered_model_version)
        champ_version = None if champion is None else str(champion.version)
        moved, why = decide(version, cand.score, champ_version, champ_score, champ_note,
                            criterion=str(opts.criterion),
                            min_improvement=float(opts.min_improvement),
                            force=bool(opts.get("force", False)), mode=cand.val_mode)
        tags = {"decision": why}
        if existing is None:
            tags.update({**_new_version_tags(cfg, cand, ds, dataset_hash), "promoted": moved})
        elif moved:
            tags["promoted"] = True
        for k, v in tags.items():
            retry_locked(client.set_model_version_tag, name, version, k, str(v))
        kept = "already registered, no new version" if existing is not None else "registered"
        if moved:
            retry_locked(client.set_registered_model_alias, name, alias, version)
            say(f"{name} version {version} ({kept}) is now @{alias}: {why}")
        else:
            say(f"{name} version {version} {kept}; @{alias} stays on version {champ_version}: {why}")
    return version, existing is None, champ_version, champ_score, moved, why


def promote(cfg: DictConfig) -> dict:
    """Register the candidate's compensator; move the alias if it beats the champion.

    Idempotent: a candidate already registered (same run, same model bytes, or
    the champion's figures on the same dataset) gets no new version.
    """
    check_config(cfg)
    check_keys(cfg, POLICY_RULE)
    check_criterion(str(cfg.promote.criterion))
    client, uri = mlflow_client(cfg), connect(cfg)
    data_path = resolve(cfg.data.path)
    ds, _ = io.read_dataset(data_path, data_options(cfg))
    dataset_hash = folder_digest(data_path)
    comp, cand = _candidate(cfg, client, uri, data_path, dataset_hash)
    _deploy(cfg, comp, ds, cand)
    version, registered, champ_version, champ_score, moved, why = _register(
        cfg, client, uri, cand, ds, dataset_hash)
    name, alias = str(cfg.promote.model_name), str(cfg.promote.alias)
    report = {"model_name": name, "alias": alias, "version": version, "run_id": cand.run_id,
              "moved": moved, "registered": registered, "reason": why,
              "criterion": str(cfg.promote.criterion), "ranked_by": cand.basis,
              "candidate": {"score": cand.score, "figures": cand.figures,
                            "validation": cand.val_figures, "test_reported": cand.test_figures},
              "champion": None if champ_version is None else {"version": champ_version,
                                                              "score": champ_score},
              "stream_deviation_um": cand.deviation, "model_uri": f"models:/{name}/{version}",
              "adaptive": cand.kind["adaptive"], "pod": cand.kind["pod"],
              "continuable": sorted(cand.deployed.end_states_)}
    write_json(resolve(cfg.out) / "promote.json", report)
    print(outcome_line(name, version, alias, moved, why, champ_version))
    return report
