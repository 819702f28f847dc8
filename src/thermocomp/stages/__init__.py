"""Pipeline stages: one function per DVC stage (the thin shell).

Each reads its inputs from files, calls the pure core, writes its outputs
atomically and logs to MLflow through :mod:`thermocomp.tracking`.  A stage
never reaches into another stage's internals: they meet at files.
"""

from .ingest import ingest
from .modelling import evaluate, run, train
from .simulate import simulate

STAGES = {"simulate": simulate, "ingest": ingest, "train": train, "evaluate": evaluate, "run": run}
