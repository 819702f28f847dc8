"""`thermocomp serve`: the registered compensator over HTTP, without an activated venv.

Runs MLflow's scoring server (uvicorn, one worker: the served compensator keeps one stream
state per ``session`` parameter inside the serving process) behind the request limits of
:mod:`thermocomp.apps.deploy.server` (``serve.max_body_mb``, ``serve.max_rows``), on a pyfunc
folder this installed package writes around ``serve.model``'s signed pickle (its own code
never runs; a run's ``model.pkl`` is made deployable on the train split of ``data.path``
first, as ``replay`` and ``connect`` make it), with the project's tracking store in
``MLFLOW_TRACKING_URI`` and this Python's
executables first on ``PATH``.  The server is a child of ``thermocomp serve``: stop it with
Ctrl-C or SIGTERM; either way the model folder written for it is removed.  Requests:
:mod:`thermocomp.apps.deploy.server`.
"""

from __future__ import annotations

import os

from omegaconf import DictConfig

from ...apps.deploy import server
from ...base.log import logger, say
from ..config.rules import SERVE_RULES, check_keys
from ..registry import check_served_model
from ..store import check_existing, is_registered_model
from ..tracking import DEFAULT_URI, resolve_uri

QUIET_DOWNLOADS = "MLFLOW_ENABLE_ARTIFACTS_PROGRESS_BAR"


def _deployed(cfg: DictConfig, model: str):
    """The compensator ``model`` holds: a registered or saved one as it is (its signature checked),
    a ``model.pkl`` made deployable on the train split of ``data.path``, holding where each
    campaign of ``data.path`` leaves its stream, as ``promote`` registers it: a served campaign
    may continue one (``continues``; without them a record cut in two was refused there)."""
    from ...apps.deploy.report import plain
    from ...apps.deploy.streaming import end_states
    from ...core.continuation import lead_ins
    from ..builders import deployable_model, is_registered
    from ..source import read_streamed

    if is_registered(model):
        return deployable_model(cfg, None, [], model, "serve.model")[0]
    ds, train_ids = read_streamed(cfg, test=False)[:2]
    deployed = deployable_model(cfg, ds, train_ids, model, "serve.model")[0]
    ids = train_ids + ds.ids("test")
    deployed.end_states_ = end_states(deployed, {c: ds.campaigns[c] for c in ids},
                                      lead_ins(plain(deployed).compensator, ds, ids))
    return deployed


def serve_command(cfg: DictConfig) -> tuple[list[str], dict]:
    """``(argv, environment)`` of the server ``thermocomp serve`` runs."""
    opts = cfg.serve
    check_keys(cfg, SERVE_RULES)     # serve runs no check_config: no data, no output
    if not server.is_loopback(str(opts.host)):
        logger.warning("serve.host=%s is not a loopback address: the model is reachable from the "
                       "network, without authentication", opts.host)
    raw = str(cfg.get("tracking_uri") or DEFAULT_URI)
    if is_registered_model(opts.model):
        check_existing(raw)         # a registered model is read: no store created to find none
    uri = resolve_uri(raw)
    # a registered model comes down file by file (its three: download66): a progress line each
    os.environ.setdefault(QUIET_DOWNLOADS, "false")
    model = check_served_model(str(opts.model), uri)
    model = server.trusted_copy(lambda: _deployed(cfg, model), uri)
    return server.server_command(model, uri, host=str(opts.host), port=opts.port,
                                 timeout_s=opts.timeout_s, max_rows=opts.max_rows,
                                 max_body_mb=opts.max_body_mb)


def serve(cfg: DictConfig) -> None:
    """Run the scoring server until it ends or this process is stopped (see the module doc)."""
    argv, env = serve_command(cfg)
    say(f"serving {cfg.serve.model} on http://{cfg.serve.host}:{int(cfg.serve.port)}/invocations "
        f"(one worker; store {env['MLFLOW_TRACKING_URI']})")
    code = server.run_server(argv, env)
    if code:
        raise SystemExit(code)
