"""Pipeline stages: one function per DVC stage (the thin shell).

Each reads its inputs from files, calls the pure core, writes its outputs
atomically and logs to MLflow through :mod:`thermocomp.shell.tracking`.  A stage
never reaches into another stage's internals: they meet at files.

Stages are looked up by name and imported on first use (:func:`stage`), so a
command imports only what it runs: ``thermocomp run`` never imports MLflow's
registry code of ``promote`` or the diagnosis of ``diagnose``, and ``--help``
imports nothing.  Each command's function is a field of its entry in the one command table
(:data:`..config.commands.COMMANDS`).
"""

from __future__ import annotations

from importlib import import_module

from ..config.commands import COMMANDS

STAGES = {name: command.stage for name, command in COMMANDS.items()}   # name -> module:function


def stage(name: str):
    """The function of stage ``name`` (a key of :data:`STAGES`), its module imported now."""
    module, function = STAGES[name].split(":")
    return getattr(import_module(f"{__name__}.{module}"), function)
