"""`thermocomp serve`: the registered compensator over HTTP, without an activated venv.

Runs MLflow's scoring server (what ``mlflow models serve -m <folder> --env-manager local -w 1``
runs: uvicorn, one worker) behind the request limits of :mod:`thermocomp.apps.deploy.server`
(``serve.max_body_mb``, ``serve.max_rows``: 413, too deep a JSON: 400, before the model
parses anything), on a pyfunc folder this installed package writes around ``serve.model``'s
signed pickle (its own code never runs), with

* the project's tracking store (``tracking_uri`` resolved against the project
  root, as every stage does) in ``MLFLOW_TRACKING_URI``, so ``models:/...``
  resolves there and no stray ``./mlflow.db`` appears in the current folder;
* the directory of this Python's executables first on ``PATH``, so the server
  (``uvicorn``) is found even when the venv is not activated.

One worker: the served compensator keeps one stream state per ``session``
parameter inside the serving process; several workers would each hold their
own, and a session's samples would be split between them.  The server runs as
a child of ``thermocomp serve`` (it ends with it): stop it with Ctrl-C or SIGTERM;
either way the model folder written for it in the temp dir is removed.

Request: ``POST http://<host>:<port>/invocations`` with
``{"dataframe_split": {"columns": [...], "data": [[...]]}, "params": {"session": "machine-7",
"reset": true}}`` (``reset`` on the first block of each campaign).
"""

from __future__ import annotations

import math
import os
import shutil
import sys
from pathlib import Path

from omegaconf import DictConfig

from ...base.errors import ConfigError
from ...base.log import logger, say
from ...base.paths import resolve
from ..config.rules import SERVE_RULES, check_keys
from ..tracking import DEFAULT_URI, resolve_uri, retry_locked

QUIET_DOWNLOADS = "MLFLOW_ENABLE_ARTIFACTS_PROGRESS_BAR"


def _loopback(host: str) -> bool:
    """Whether ``host`` listens on this machine only (``localhost`` or a loopback address)."""
    import ipaddress

    try:
        return host == "localhost" or ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False      # a name that may resolve to any interface


def _check_model(model: str, uri: str) -> str:
    """``model`` as ``mlflow models serve`` takes it; refuse one that does not exist (exit 2)."""
    if not model.startswith("models:/"):
        path = resolve(model)
        if not (path / "MLmodel").is_file():
            raise ConfigError(f"serve.model={model}: neither models:/<name>@<alias> nor a pyfunc "
                              f"model folder (no {path / 'MLmodel'})")
        return str(path)
    from mlflow import MlflowClient

    from ..tracking import ensure_store

    ensure_store(uri)
    name, sep, alias = model[len("models:/"):].partition("@")
    client = MlflowClient(uri, registry_uri=uri)
    try:
        if sep:
            retry_locked(client.get_model_version_by_alias, name, alias)
        else:
            name, _, version = name.partition("/")
            retry_locked(client.get_model_version, name, version)
    except Exception:
        raise ConfigError(f"serve.model={model}: no such model version in {uri}; run "
                          f"`thermocomp promote` first") from None
    return model


def _trusted_copy(model: str, uri: str) -> str:
    """A pyfunc folder made by this installed package around the model's signed pickle, which
    is what the server loads: the registered model's own code (``model_code.py``, ``code/``,
    ``MLmodel``) is never run (the signature covers the pickle alone).  A pickle whose
    signature does not match is refused here (exit 2), before any server starts."""
    import tempfile

    import mlflow

    from ...apps.deploy.pyfunc import load_deployed, save_compensator

    mlflow.set_tracking_uri(uri)    # the registry follows it (no process-wide registry URI:
                                    # it would outlive this call in a process that goes on)
    # one folder in the temp dir holds the model and whatever MLflow stages to write it (the
    # temp dir pointed there meanwhile): serve() removes it when the server ends, this function
    # when it cannot be written; a signal at any point leaves nothing else behind
    folder = Path(tempfile.mkdtemp(prefix="thermocomp-serve-"))
    previous, tempfile.tempdir = tempfile.tempdir, str(folder)
    try:
        local = None if model.startswith("models:/") else Path(model)
        return str(save_compensator(load_deployed(model, local), folder / "model"))
    except BaseException:
        shutil.rmtree(folder, ignore_errors=True)
        raise
    finally:
        tempfile.tempdir = previous


def serve_command(cfg: DictConfig) -> tuple[list[str], dict]:
    """``(argv, environment)`` of the server ``thermocomp serve`` runs."""
    from mlflow.pyfunc.scoring_server import _SERVER_MODEL_PATH
    from mlflow.utils.file_utils import path_to_local_file_uri

    from ...apps.deploy import server

    opts = cfg.serve
    check_keys(cfg, SERVE_RULES)     # serve runs no check_config: no data, no output
    if not _loopback(str(opts.host)):
        logger.warning("serve.host=%s is not a loopback address: the model is reachable from the "
                       "network, without authentication", opts.host)
    uri = resolve_uri(str(cfg.get("tracking_uri") or DEFAULT_URI))
    # a registered model comes down file by file: a progress line each, hundreds of them
    os.environ.setdefault(QUIET_DOWNLOADS, "false")
    model = _trusted_copy(_check_model(str(opts.model), uri), uri)
    bin_dir = str(Path(sys.executable).parent)
    env = {**os.environ, "MLFLOW_TRACKING_URI": uri, "MLFLOW_REGISTRY_URI": uri,
           "PATH": os.pathsep.join([bin_dir, os.environ.get("PATH", "")]),
           _SERVER_MODEL_PATH: path_to_local_file_uri(model),
           "MLFLOW_SCORING_SERVER_REQUEST_TIMEOUT": str(math.ceil(opts.timeout_s)),
           server.ROWS_ENV: str(int(opts.max_rows)),
           server.BODY_ENV: str(int(opts.max_body_mb * 2**20))}
    argv = [str(Path(bin_dir) / "uvicorn"), "--host", str(opts.host), "--port", str(opts.port),
            "--workers", "1", "--factory", f"{server.__name__}:{server.scoring_app.__name__}"]
    return argv, env


def serve(cfg: DictConfig) -> None:
    """Run the scoring server until it ends or this process is stopped (see the module doc)."""
    import signal
    import subprocess

    from mlflow.pyfunc.scoring_server import _SERVER_MODEL_PATH
    from mlflow.utils.file_utils import local_file_uri_to_path

    from ...apps.deploy.server import PARENT_ENV
    from ...base.files import Terminated

    argv, env = serve_command(cfg)
    folder = Path(local_file_uri_to_path(env[_SERVER_MODEL_PATH])).parent
    try:
        say(f"serving {cfg.serve.model} on http://{cfg.serve.host}:{int(cfg.serve.port)}/invocations "
            f"(one worker; store {env['MLFLOW_TRACKING_URI']})")
        sys.stdout.flush()
        sys.stderr.flush()
        server = subprocess.Popen(argv, env={**env, PARENT_ENV: str(os.getpid())})
        try:
            code = server.wait()
        except (KeyboardInterrupt, Terminated):    # Ctrl-C, SIGTERM: the server stops, cleanly
            server.terminate()
            code = server.wait()
    finally:    # the model folder written for it, whatever ended the server
        shutil.rmtree(folder, ignore_errors=True)
    if code not in (0, -signal.SIGTERM, -signal.SIGINT):
        raise SystemExit(code if code > 0 else 1)
