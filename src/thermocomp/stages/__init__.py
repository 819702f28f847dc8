"""Pipeline stages: one function per DVC stage (the thin shell).

Each reads its inputs from files, calls the pure core, writes its outputs
atomically and logs to MLflow through :mod:`thermocomp.tracking`.  A stage
never reaches into another stage's internals: they meet at files.
"""

from .compare import compare
from .denoise import denoise
from .diagnose import diagnose
from .ingest import ingest
from .modelling import evaluate, run, train
from .promote import promote
from .replay import replay
from .select import select
from .simulate import simulate

STAGES = {"simulate": simulate, "ingest": ingest, "denoise": denoise, "select": select,
          "train": train, "evaluate": evaluate, "diagnose": diagnose, "run": run,
          "compare": compare, "promote": promote, "replay": replay}
