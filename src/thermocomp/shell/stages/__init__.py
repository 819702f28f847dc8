"""Pipeline stages: one function per DVC stage (the thin shell).

Each reads its inputs from files, calls the pure core, writes its outputs
atomically and logs to MLflow through :mod:`thermocomp.shell.tracking`.  A stage
never reaches into another stage's internals: they meet at files.

Stages are looked up by name and imported on first use (:func:`stage`), so a
command imports only what it runs: ``thermocomp run`` never imports MLflow's
registry code of ``promote`` or the diagnosis of ``diagnose``, and ``--help``
imports nothing.
"""

from __future__ import annotations

from importlib import import_module

STAGES = {"simulate": "simulate:simulate", "init": "init:init",
          "ingest": "ingest:ingest", "denoise": "denoise:denoise",
          "select": "select:select", "train": "modelling:train", "evaluate": "modelling:evaluate",
          "diagnose": "diagnose:diagnose", "run": "modelling:run", "compare": "compare:compare",
          "promote": "promote:promote", "replay": "replay:replay", "export": "export:export",
          "serve": "serve:serve", "twin": "twin:twin", "connect": "connect:connect",
          "monitor": "monitor:monitor",
          "calibrate": "calibrate:calibrate", "design": "design:design"}


def stage(name: str):
    """The function of stage ``name`` (a key of :data:`STAGES`), its module imported now."""
    module, function = STAGES[name].split(":")
    return getattr(import_module(f"{__name__}.{module}"), function)
