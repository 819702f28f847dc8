"""`thermocomp promote`: register a run's compensator, move ``champion`` only if it is better.

The candidate (``promote.run_id``, or the best child of ``compare.sweep`` by ``promote.criterion``,
a validation figure, among the runs scored on ``data.path``) is made deployable as ``replay``
streams it (causality checked; adaptive unless ``monitor.adaptive=false``), registered as an
``mlflow.pyfunc`` model version with its tags, and ``promote.alias`` moves only if it beats the
champion's validation score on the same dataset by more than ``promote.min_improvement``.
Idempotent.  The steps: :mod:`thermocomp.apps.deploy.promotion`.  Writes ``<out>/promote.json``.
"""

from __future__ import annotations

from omegaconf import DictConfig, OmegaConf

from ...apps.deploy import POLICIES
from ...apps.deploy.adapt import from_config as adapt_from_config
from ...apps.deploy.promotion import deploy, deploy_key, promote_report
from ...apps.deploy.report import clamped_line, cold_line, guarded_line, lead_in_line
from ...base.files import write_json
from ...base.log import logger
from ...base.params import choice
from ...base.paths import resolve
from ...core.continuation import lead_ins
from ...core.metrics import RMSE
from ...core.scoring.champion import check_criterion, outcome_line
from .. import registry
from ..builders import deploy_stream, deployable
from ..config.checks import check_config
from ..config.rules import check_keys
from ..source import open_source
from ..store import registry_lock
from ..tracking import client as mlflow_client
from ..tracking import connect

# The plain promote.* keys are checked by every stage (rules.PROMOTE_RULES); the envelope's
# policies are the deployment's own.
POLICY_RULE = {"promote.envelope.policy": choice(*POLICIES)}


def _filled(cfg: DictConfig, missing: dict):
    """``data.path`` as a batch reads it, for a plain stream's test figures where a test campaign
    misses cells: that stream refuses such a row (replay's exit 2; the served model's HTTP 400),
    so the figures are of the campaigns filled as ``run`` fills them, said."""
    where = ", ".join(f"{c} ({sum(n.values()) if isinstance(n, dict) else n} cells)"
                      for c, n in missing.items())
    logger.warning(f"the test campaigns {where} miss values, which the plain streaming "
                   "compensator refuses (monitor.adaptive=true holds or reconstructs them): its "
                   "test figures are of those campaigns filled as run fills them")
    return open_source(cfg)


def promote(cfg: DictConfig) -> dict:
    """Register the candidate's compensator; move the alias if it beats the champion."""
    check_config(cfg, existing_store=True)     # it reads a run there: creates no store
    check_keys(cfg, POLICY_RULE)
    check_criterion(str(cfg.promote.criterion))
    client, uri = mlflow_client(cfg, existing=True), connect(cfg, existing=True)
    data_path = resolve(cfg.data.path)
    # as a deployed compensator sees it: the test campaigns as recorded (a dropout streams as
    # NaN), the train ones repaired as run fitted on them; a batch read filled the test's gaps
    # from their neighbours, later samples included, and "as deployed" was run's figure
    ds = open_source(cfg, stream=True)
    if ds.meta.get("missing") and not bool(cfg.monitor.adaptive):
        ds = _filled(cfg, ds.meta["missing"])
    dataset_hash = ds.meta["digest"]      # the digest every run of data.path is tagged with
    comp, cand = registry.candidate(cfg, client, uri, data_path, dataset_hash)
    deploy(cand, comp, ds, leads=lead_ins(comp, ds, ds.ids("train") + ds.ids("test")),
           stream_of=lambda train: deploy_stream(cfg, comp, train, f"run {cand.run_id}"),
           deployed_of=lambda streaming, train: deployable(cfg, streaming, train, ds),
           max_deviation_um=float(cfg.promote.max_stream_deviation_um),
           e_p95=(cfg.eval.e_p95.statistic, cfg.eval.e_p95.max_points),
           target=str(cfg.promote.target), deploy_config=deploy_key(
               bool(cfg.monitor.adaptive), OmegaConf.to_container(cfg.monitor, resolve=True),
               OmegaConf.to_container(cfg.promote.envelope, resolve=True),
               OmegaConf.to_container(cfg.adapt, resolve=True) if cfg.get("adapt") else None),
           adapt_of=lambda n_targets: adapt_from_config(cfg.get("adapt"), n_targets))
    with registry_lock(uri):
        outcome = registry.register(cfg, client, cand, ds, dataset_hash)
    name, alias = str(cfg.promote.model_name), str(cfg.promote.alias)
    report = promote_report(cand, outcome, name=name, alias=alias,
                            criterion=str(cfg.promote.criterion))
    write_json(resolve(cfg.out) / "promote.json", report)
    print(outcome_line(name, outcome.version, alias, outcome.moved, outcome.why,
                       outcome.champion_version))
    for line in deployed_lines(cand, str(cfg.promote.envelope.policy), str(cfg.promote.target)):
        print(line)
    return report


def deployed_lines(cand, policy: str, target: str = "mean") -> list[str]:
    """Why the test figures "as deployed" leave run's: the rows clamped to the envelope, with an
    input the sensor monitor excluded, whose correction the guard changed (replay's lines); and,
    where a test campaign continues others, what a cold start there costs (deploy88) and what
    the sensor monitor did while it was warmed (replay's ``warm-up:`` line, deploy88b)."""
    n, why = cand.test_samples, "the test figures are the {} stream's, run's the model's own"
    lines = cold_line(cand.cold_start_campaigns, [(target, cand.test_figures_cold.get(RMSE),
                                                   cand.test_figures.get(RMSE))]
                      ) if cand.cold_start_campaigns else []
    lines += clamped_line(cand.test_clamped, n, policy, why.format("clamped"))
    if cand.test_excluded:
        lines.append(f"excluded: {cand.test_excluded} of {n} samples had an input excluded by "
                     "the sensor monitor (monitor.adaptive; replay names them); "
                     + why.format("adaptive"))
    return (lines + guarded_line(cand.test_guarded or {}, n, why.format("guarded"))
            + lead_in_line(cand.lead_in_events))
