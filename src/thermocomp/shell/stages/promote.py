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

from omegaconf import DictConfig, OmegaConf

from ...apps.deploy import POLICIES
from ...apps.deploy.promotion import deploy, deploy_key, promote_report
from ...base.files import folder_digest, write_json
from ...base.params import choice
from ...base.paths import resolve
from ...core import io
from ...core.scoring.champion import check_criterion, outcome_line
from .. import registry
from ..store import registry_lock
from ..tracking import client as mlflow_client
from ..tracking import connect
from .common import check_config, check_keys, data_options, deploy_stream, deployable, lead_ins

# The plain promote.* keys are checked by every stage (rules.PROMOTE_RULES); the envelope's
# policies are the deployment's own.
POLICY_RULE = {"promote.envelope.policy": choice(*POLICIES)}


def deploy_config(cfg: DictConfig) -> str:
    """:func:`~thermocomp.apps.deploy.promotion.deploy_key` of the config."""
    return deploy_key(bool(cfg.monitor.adaptive), OmegaConf.to_container(cfg.monitor, resolve=True),
                      OmegaConf.to_container(cfg.promote.envelope, resolve=True))


def promote(cfg: DictConfig) -> dict:
    """Register the candidate's compensator; move the alias if it beats the champion."""
    check_config(cfg)
    check_keys(cfg, POLICY_RULE)
    check_criterion(str(cfg.promote.criterion))
    client, uri = mlflow_client(cfg), connect(cfg)
    data_path = resolve(cfg.data.path)
    ds, _ = io.read_dataset(data_path, data_options(cfg))
    dataset_hash = folder_digest(data_path)
    comp, cand = registry.candidate(cfg, client, uri, data_path, dataset_hash)
    deploy(cand, comp, ds, leads=lead_ins(comp, ds, ds.ids("train") + ds.ids("test")),
           stream_of=lambda train: deploy_stream(cfg, comp, train, f"run {cand.run_id}"),
           deployed_of=lambda streaming, train: deployable(cfg, streaming, train, ds),
           max_deviation_um=float(cfg.promote.max_stream_deviation_um),
           e_p95=(cfg.eval.e_p95.statistic, cfg.eval.e_p95.max_points),
           target=str(cfg.promote.target), deploy_config=deploy_config(cfg))
    with registry_lock(uri):
        outcome = registry.register(cfg, client, cand, ds, dataset_hash)
    name, alias = str(cfg.promote.model_name), str(cfg.promote.alias)
    report = promote_report(cand, outcome, name=name, alias=alias,
                            criterion=str(cfg.promote.criterion))
    write_json(resolve(cfg.out) / "promote.json", report)
    print(outcome_line(name, outcome.version, alias, outcome.moved, outcome.why,
                       outcome.champion_version))
    return report
