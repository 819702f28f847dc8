"""``promote``'s side of MLflow: the candidate run and its model, the champion and the versions
of the registry, the registration and its tags.  What is decided from them is pure
(:mod:`thermocomp.apps.deploy.promotion`, :mod:`thermocomp.core.scoring.champion`)."""

from __future__ import annotations

import hashlib
import subprocess
from pathlib import Path

from omegaconf import DictConfig

from ..apps.deploy.promotion import (
    Candidate,
    Outcome,
    check_dataset,
    find_registered,
    validation_figures,
    version_tags,
)
from ..base import signing
from ..base.errors import ConfigError, ContractError
from ..base.log import logger, say
from ..base.paths import project_root
from ..core.compensator import Compensator
from ..core.scoring.champion import champion_validation, decide, fmt
from ..core.scoring.evaluation import require_split
from ..core.scoring.leaderboard import (
    DEPLOYED_MODE,
    mean_label,
    rank,
    ranked_by,
    ranking_line,
    validation_mode,
)
from ..core.scoring.results import EvaluationResult, worse_than_none
from .store import REGISTERED, is_registered_model
from .sweeps import failed_jobs, failed_note, parent_run_id, run_metrics, sweep_rows
from .tracking import DATASET_TAG, child_runs, retry_locked


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


def best_run(cfg: DictConfig, client, uri: str, dataset_hash: str, data_path) -> tuple[str, dict]:
    """The best finished child of the sweep among those scored on this dataset, by its
    simulation-mode validation, and what ranked (:func:`~thermocomp.core.scoring.leaderboard.ranked_by`)."""
    parent = parent_run_id(cfg, client)
    children = child_runs(client, parent)
    seen = {r.info.run_id: r.data.tags.get(DATASET_TAG) for r in children}
    # the datasets of the runs that finished: a failed run's is no data.path to promote with
    # (audit87: a sweep whose every run failed was refused naming theirs, "no finished child
    # run" only once given it)
    scored = {seen[r.info.run_id] for r in children if r.info.status == "FINISHED"}
    if scored and dataset_hash not in scored:
        hashes = ", ".join(sorted({(h or "none")[:12] for h in scored}))
        raise ConfigError(f"data.path={data_path} (dataset {dataset_hash[:12]}) was not scored by "
                          f"any run of sweep {parent} (datasets seen: {hashes}); promote with "
                          f"the data.path the sweep ran on")
    rows = [r for r in sweep_rows(client, uri, parent, str(cfg.promote.target))
            if r["status"] == "FINISHED" and seen.get(r["run_id"]) in (dataset_hash, None)]
    if not rows:
        note = failed_note(*failed_jobs(client, parent))
        raise ConfigError(f"sweep {parent} has no finished child run to promote"
                          + (f" ({note})" if note else ""))
    try:
        table = rank(rows, str(cfg.promote.criterion))
    except KeyError as exc:
        raise ConfigError(f"promote.criterion: {exc.args[0]}") from None
    basis = ranked_by(table, str(cfg.promote.criterion))
    say(f"sweep {parent}: {len(table)} finished run(s) ranked by {ranking_line(basis)}")
    if note := failed_note(*failed_jobs(client, parent)):   # the best of a grid not whole
        logger.warning(f"sweep {parent}: {note}; the candidate is the best of the runs that "
                       "finished")
    return str(table["run_id"].iloc[0]), basis


def _refuse_fleet_run(run_id: str, uri: str) -> None:
    """A fleet's run (``data.group_by``) logs no model.pkl: its models are one per group in its
    ``out``'s ``models/``.  Said as such, not as "promote a `run` run" (it is one)."""
    import mlflow

    try:
        params = mlflow.tracking.MlflowClient(uri).get_run(run_id).data.params
    except Exception:       # the run itself unreadable: the caller's message says enough
        return
    column = params.get("data.group_by")
    if column in (None, "None", "null", ""):
        return
    raise ConfigError(
        f"run {run_id} is a fleet's run (data.group_by={column}): it fitted one model per "
        f"{column}, saved as models/<{column}>.pkl in its out and not logged to MLflow, so it has "
        "no model to promote; use one of them as a file (replay.model=, export.model=, "
        f"monitor.model=), or promote a run of that {column}'s campaigns alone (a folder of "
        "their files and manifest rows, run without data.group_by)")


def load_run_model(run_id: str, uri: str) -> tuple[Compensator, str]:
    """The run's compensator and the SHA-256 of its pickle; the signature is checked before
    anything is unpickled (a tracking server may not be trusted).  The two files alone are
    fetched (:class:`~thermocomp.apps.deploy.pyfunc.ModelFiles`, as a registered model's)."""
    from ..apps.deploy.pyfunc import ModelFiles
    from ..base.files import scratch_folder

    with scratch_folder("thermocomp-run-model-") as tmp:
        try:
            files = ModelFiles(f"runs:/{run_id}", tmp, uri)
            path = files.fetch("model.pkl")
        except Exception as exc:
            _refuse_fleet_run(run_id, uri)
            raise ConfigError(f"run {run_id} has no model.pkl artifact (promote a `run` or "
                              f"`train` run): {' '.join(str(exc).split())[:200]}") from None
        try:
            files.fetch("model.pkl.sig")
        except ContractError:  # verified_bytes says "not signed by this project"
            pass
        digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()
        return signing.load(path, Compensator), digest


def candidate(cfg: DictConfig, client, uri: str, data_path, dataset_hash: str
              ) -> tuple[Compensator, Candidate]:
    """The candidate run, checked against the dataset, with its model and validation score
    (in simulation mode where it has it)."""
    import mlflow

    opts, criterion = cfg.promote, str(cfg.promote.criterion)
    run_id, basis = ((str(opts.run_id), None) if opts.get("run_id")
                     else best_run(cfg, client, uri, dataset_hash, data_path))
    say(f"candidate run {run_id}")
    try:
        run = retry_locked(client.get_run, run_id)
    except mlflow.exceptions.MlflowException as exc:
        raise ConfigError(f"promote.run_id={run_id}: no such run in {uri} "
                          f"({' '.join(str(exc).split())[:120]})") from None
    check_dataset(run.data.tags, run.data.params, run_id, dataset_hash, data_path)
    comp, digest = load_run_model(run_id, uri)
    metrics = run_metrics(run_id, uri)
    score, val_figures = validation_figures(metrics, run_id, criterion, str(opts.target))
    mode, val_mode = str(metrics.get("mode", DEPLOYED_MODE)), validation_mode(metrics)
    basis = basis or {"figure": criterion, "mode": DEPLOYED_MODE, "fallback": {}}
    target = mean_label(metrics["targets"], str(opts.target))    # µm/m ones left out of a mean
    if target != str(opts.target):
        basis.setdefault("mean_over", [target])
    say(f"run {run_id}: {criterion} {fmt(score)} of its {val_mode}-mode validation (scored "
        f"in {mode}; the deployed compensator runs in {DEPLOYED_MODE})"
        + (f", of the {target}" if target != str(opts.target) else ""))
    for line in worse_than_none(EvaluationResult(metrics).targets):
        logger.warning("run %s: %s", run_id, line)
    if val_mode != DEPLOYED_MODE:
        basis["fallback"][run_id] = val_mode
        logger.warning("run %s has no %s-mode validation (scored in %s before it was recorded): "
                       "its %s validation decides; rerun it to choose by the deployed mode",
                       run_id, DEPLOYED_MODE, val_mode, val_mode)
    return comp, Candidate(run_id, dict(run.data.params), digest, score, mode, val_mode, basis,
                           val_figures)


def _champion(client, name: str, alias: str):
    try:
        return retry_locked(client.get_model_version_by_alias, name, alias)
    except Exception:  # no registered model yet, or no version holds the alias
        return None


def _versions(client, name: str) -> list:
    try:
        return retry_locked(client.search_model_versions, f"name='{name}'")
    except Exception:  # no registered model yet
        return []


def register(cfg: DictConfig, client, cand: Candidate, ds, dataset_hash: str) -> Outcome:
    """Read the champion, register, decide, tag, move the alias: one transaction, to be run
    under the registry lock (a second promote then compares against what this one decided)."""
    from ..apps.deploy import pyfunc

    opts, name, alias = cfg.promote, str(cfg.promote.model_name), str(cfg.promote.alias)
    champion = _champion(client, name, alias)
    existing = find_registered(champion, lambda: _versions(client, name), cand, dataset_hash)
    champ_score, champ_note = None, None
    # a mean leaving µm/m targets out is tagged so: a champion scored by the mean over every
    # target (µm and µm/m added, before isoleft67) is no score to beat
    target = mean_label(cand.streaming.targets_, str(opts.target))
    if champion is not None:
        champ_score, champ_note = champion_validation(
            champion.tags, str(opts.criterion), target, dataset_hash, cand.val_mode)
    champ_version = None if champion is None else str(champion.version)
    how = dict(criterion=str(opts.criterion), min_improvement=float(opts.min_improvement),
               force=bool(opts.get("force", False)), mode=cand.val_mode)
    if existing is not None:
        version = str(existing.version)
        moved, why = decide(version, cand.score, champ_version, champ_score, champ_note, **how)
        tags = {"decision": why, **({"promoted": True} if moved else {})}
        for k, v in tags.items():
            retry_locked(client.set_model_version_tag, name, version, k, str(v))
    else:
        # A new version is never the champion, so it is decided before it exists and created
        # with its tags in one write: no version without them (find_registered reads them),
        # and one commit instead of one per tag.
        moved, why = decide(None, cand.score, champ_version, champ_score, champ_note, **how)
        outputs = ([pyfunc.correction_column(t) for t in cand.streaming.targets_] + ["n_clamped"]
                   + (list(pyfunc.REPORT_COLUMNS) if cand.kind["adaptive"] else []))
        tags = {"decision": why,
                **version_tags(cand, ds, dataset_hash=dataset_hash, commit=git_commit(),
                               criterion=str(opts.criterion), target=target,
                               policy=str(opts.envelope.policy), outputs=outputs),
                "promoted": moved}
        test = ds.campaigns[require_split(ds, "test")[0]]
        # a campaign's first block, as a caller sends one (MLflow predicts it to check the
        # signature): without ``reset`` the model warned of a session it does not hold, a
        # restart mid-campaign, at every promote
        rows = test[cand.streaming.columns_ + ["time"]]
        example = (rows[rows.notna().all(axis=1)].head(5), {"reset": True})   # a dropout aside
        # into the run without resuming it: a killed promote leaves its status alone
        info = pyfunc.log_compensator(cand.deployed, input_example=example,
                                      registered_model_name=name, run_id=cand.run_id,
                                      tags={k: str(v) for k, v in tags.items()})
        version = str(info.registered_model_version)
    kept = "already registered, no new version" if existing is not None else "registered"
    if moved:
        retry_locked(client.set_registered_model_alias, name, alias, version)
        say(f"{name} version {version} ({kept}) is now @{alias}: {why}")
    else:
        say(f"{name} version {version} {kept}; @{alias} stays on version {champ_version}: {why}")
    return Outcome(version, existing is None, champ_version, champ_score, moved, why)


def registered_version(client, model: str):
    """The model version ``models:/<name>@<alias>`` or ``models:/<name>/<version>`` names
    (MLflow's exception when there is none)."""
    name, sep, alias = model[len(REGISTERED):].partition("@")
    if sep:
        return retry_locked(client.get_model_version_by_alias, name, alias)
    name, _, version = name.partition("/")
    return retry_locked(client.get_model_version, name, version)


def check_served_model(model: str, uri: str) -> str:
    """``serve.model`` as the server takes it: a pyfunc folder or a run's ``model.pkl`` (resolved),
    or a registered
    ``models:/<name>@<alias>`` / ``models:/<name>/<version>`` that exists in ``uri``."""
    from mlflow import MlflowClient

    from ..base.paths import resolve
    from .tracking import ensure_store

    if not is_registered_model(model):
        path = resolve(model)
        if not ((path / "MLmodel").is_file() or path.is_file()):
            raise ConfigError(f"serve.model={model}: neither models:/<name>@<alias>, a pyfunc "
                              f"model folder (no {path / 'MLmodel'}) nor a model.pkl")
        return str(path)
    ensure_store(uri)
    try:
        registered_version(MlflowClient(uri, registry_uri=uri), model)
    except Exception:
        raise ConfigError(f"serve.model={model}: no such model version in {uri}; run "
                          f"`thermocomp promote` first") from None
    return model
