"""`thermocomp connect`: a deployed compensator as an OPC UA client of a machine
(:class:`~thermocomp.apps.machine.client.Connection`); ends when the server says the campaigns are
done and writes ``<out>/connect.json`` (its events, CLI.md).

``connect.model`` is loaded as ``replay.model`` is (null: the configured model fitted on the
train split, made deployable with the adaptive compensator of ``monitor``).  What is written is
bounded and rate-limited by the deployed compensator's correction guard; a plain stream gets
one fitted on the train split as ``monitor`` fits it.  With ``adapt.method`` (else the
setting a registered model was promoted with) it learns from the machine's reference
measurements (the ``reference`` nodes) as ``replay`` learns from its simulated ones.
"""

from __future__ import annotations

import asyncio
import os
from pathlib import Path

import numpy as np
from omegaconf import DictConfig

from ...apps.deploy.adapt import from_config as adapt_from_config
from ...base.errors import ConfigError
from ...base.files import write_json
from ...base.log import logger, say
from ...base.paths import resolve
from ..builders import deployable_model, is_registered
from ..config.checks import check_config
from ..source import read_streamed

PASSWORD_ENV = "THERMOCOMP_OPCUA_PASSWORD"     # connect.user's password (opcua67)


def _guard(cfg: DictConfig, deployed, ds, train_ids):
    guard = getattr(deployed, "guard", None)
    if guard is not None:
        return guard
    if ds is None:
        raise ConfigError(f"connect.model={cfg.connect.model}: a plain stream without a correction "
                          "guard; register it with monitor.adaptive=true, or give a model.pkl")
    from ...apps.deploy.adaptive import AdaptiveCompensator

    train = {c: ds.campaigns[c] for c in train_ids}
    return AdaptiveCompensator.from_training(deployed, train, guard=dict(cfg.monitor.guard)).guard


def offset_limiter(deployed, guard, hold_s: float, decay_s: float):
    """What may reach the machine: ``guard``'s bound (widened as the guard widens it for the
    inputs the model read: :func:`~thermocomp.apps.deploy.adaptive.stream_allowance`) and rate
    (over a step or one training period, the longer: the guard's rule), held ``hold_s`` and
    decaying over ``decay_s`` while stale."""
    from functools import partial

    from ...apps.deploy.adaptive import stream_allowance
    from ...apps.machine.offsets import OffsetLimiter

    return OffsetLimiter(guard.lo, guard.hi, guard.max_rate_per_s, hold_s, decay_s,
                         widen=partial(stream_allowance, guard, getattr(deployed, "streaming", deployed)),
                         period_s=guard.period_s)


def _warm_rows(cfg: DictConfig, deployed):
    """``connect.warm``: the rows logged since the running campaign's start, read as a stream
    on stdin is (``data.delimiter``, ``data.columns``, a lab's headers and units), or None; of
    a log of several runs, the last (:func:`~thermocomp.core.io.stdin.read_last_run`)."""
    warm = cfg.connect.get("warm")
    if warm is None:
        return None
    from io import TextIOWrapper

    from ...core import io
    from ...core.io.stdin import SOURCE, read_last_run, stdin_text
    from ..config.checks import data_options

    path = resolve(str(warm))
    if not path.is_file():
        raise ConfigError(f"connect.warm={warm}: no such file (the rows logged since the "
                          "running campaign's start, CSV with a header)")
    opts = io.ReadOptions.from_cfg(data_options(cfg))
    try:
        with open(path, "rb") as raw:
            frame, runs = read_last_run(stdin_text(TextIOWrapper(raw), opts.encoding),
                                        deployed.columns_, opts,
                                        getattr(deployed, "slashed_", None),  # the record's order (code71)
                                        getattr(deployed, "lab_names_", None))
    except io.ContractError as exc:
        if str(exc.file) != SOURCE:
            raise
        # (data88) read as a stream is, but a file the user named: "file <stdin>" pointed nowhere
        raise io.ContractError(exc.reason, file=path, column=exc.column, row=exc.row,
                               line=exc.line) from None
    if runs > 1:       # (data88) was refused: "stream one run"
        say(f"connect.warm={warm}: the log holds {runs} runs (sessions); the stream is warmed on "
            f"the last, {len(frame)} row(s), the campaign running when it was logged")
    return frame


def _user(c) -> tuple[str, str] | None:
    """(opcua67) ``connect.user`` and its password, from THERMOCOMP_OPCUA_PASSWORD (never from
    the config or the endpoint: both are written to the run's log)."""
    from urllib.parse import urlsplit

    if urlsplit(str(c.endpoint)).password is not None:
        raise ConfigError("connect.endpoint holds a password (user:password@): it would be written "
                          "to the run's log; give the user as connect.user and the password in "
                          f"{PASSWORD_ENV}")
    user = c.get("user")
    if user is None:
        return None
    password = os.environ.get(PASSWORD_ENV)
    if password is None:
        raise ConfigError(f"connect.user={user}: its password in the environment variable "
                          f"{PASSWORD_ENV} (not set)")
    return str(user), password


def connect(cfg: DictConfig) -> dict:
    """Run the compensator against ``connect.endpoint`` until the campaigns are done (or, a
    server without a ``done`` node, until SIGINT / SIGTERM)."""
    check_config(cfg, inputs=("connect.model", "connect.warm"))
    from ...apps.machine.client import Connection, LinkLost, NodesRefused, SessionRefused, WriteRefused
    from ...apps.machine.nodes import NodeMap

    c = cfg.connect
    user = _user(c)          # before the model is read: a said refusal costs no fit
    source = c.get("model")
    if source is not None and not str(source).strip():
        raise ConfigError("connect.model is empty: a model.pkl, a pyfunc folder or "
                          "models:/<name>@<alias>")
    ds, train_ids = (None, []) if is_registered(source) else read_streamed(cfg, test=False)[:2]
    deployed, source, name = deployable_model(cfg, ds, train_ids, source, "connect.model")
    guard = _guard(cfg, deployed, ds, train_ids)
    limiter = offset_limiter(deployed, guard, float(c.hold_s), float(c.decay_s))
    adapt = (adapt_from_config(cfg.get("adapt"), len(deployed.targets_), scheduled=False)
             or getattr(deployed, "adapt_", None))
    nodes = NodeMap.from_config(c.nodes)
    clock = str(c.get("clock") or "node")
    period_s = float(c.get("period_s") or guard.period_s)     # null: the model's sample period
    link = Connection(deployed, nodes, str(c.endpoint), limiter,
                      retry_s=float(c.retry_s), give_up_s=float(c.give_up_s), adapt=adapt,
                      warm=_warm_rows(cfg, deployed), clock=clock, period_s=period_s, user=user)
    say(f"connect: {name} ({source}) to {c.endpoint}: inputs {', '.join(deployed.columns_)}")
    for key, mapped, names in (("inputs", nodes.inputs, deployed.columns_),
                               ("offsets", nodes.offsets, deployed.targets_)):
        extra = sorted(set(mapped) - set(names) - {"time"})
        if extra:          # a shared mapping may name more; a typo falls back on the pattern
            logger.warning(f"connect.nodes.{key} names {', '.join(extra)}, which the model does "
                           f"not {'read' if key == 'inputs' else 'correct'} "
                           f"({', '.join(names)}): not used")
    absent = nodes.missing()
    if absent:
        say(f"connect: the server has no {', '.join(absent)} node"
            + (f": a sample every {period_s:g} s of the "
               f"{'server' if clock == 'server' else 'time node'}'s clock" if "sample" in absent else "")
            + ("; runs until stopped (Ctrl-C or SIGTERM: connect.json is written)"
               if "done" in absent else ""))
    try:
        asyncio.run(link.run())
    except LinkLost as exc:
        raise ConfigError(f"connect.endpoint={c.endpoint}: {exc}") from None
    except NodesRefused as exc:
        raise ConfigError(f"connect.nodes at {c.endpoint}: {exc}") from None
    except SessionRefused as exc:
        raise ConfigError(f"connect.endpoint={c.endpoint}: {exc}") from None
    except WriteRefused as exc:
        raise ConfigError(f"connect.nodes.offset: {c.endpoint} refused the offsets' write "
                          f"({exc}); nothing more was written") from None
    written = np.vstack(link.written) if link.written else np.empty((0, len(deployed.targets_)))
    report = {"model": name, "source": source, "endpoint": str(c.endpoint),
              "samples": link.samples, "samples_missed": link.missed,
              "samples_refused": link.refused, "writes": int(len(written)),
              "max_abs_offset": {t: float(np.max(np.abs(written[:, j]))) if len(written) else 0.0
                                 for j, t in enumerate(deployed.targets_)},
              "bound": {t: [float(guard.lo[j]), float(guard.hi[j])]
                        for j, t in enumerate(deployed.targets_)},
              **({"adapt": {t: adapt.figures(j) for j, t in enumerate(deployed.targets_)}}
                 if adapt is not None else {}),
              **({"stopped": link.stopped} if link.stopped else {}),
              "events": link.events}
    path = write_json(Path(resolve(cfg.out)) / "connect.json", report)
    say(f"connect: {link.samples} samples, {len(link.events)} events: {path}")
    return report
